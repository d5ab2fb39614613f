// A set of the integers 0 … n−1 with insertion, removal and membership in
// constant time and iteration over the members only (in an order that
// depends only on the sequence of insertions and removals: the last member
// takes a removed one's place).  The collision monitor keeps its moving
// bodies and its bodies computed short of the end in such sets.
#pragma once

#include <cstddef>
#include <vector>

namespace asgard::solver {

class IndexedSet {
 public:
  // Empties the set and admits the integers 0 … n−1.
  void Reset(size_t n) {
    items_.clear();
    index_.assign(n, -1);
  }
  bool Contains(int x) const { return index_[static_cast<size_t>(x)] >= 0; }
  void Insert(int x) {
    if (Contains(x)) return;
    index_[static_cast<size_t>(x)] = static_cast<int>(items_.size());
    items_.push_back(x);
  }
  void Erase(int x) {
    const int at = index_[static_cast<size_t>(x)];
    if (at < 0) return;
    const int last = items_.back();
    items_[static_cast<size_t>(at)] = last;
    index_[static_cast<size_t>(last)] = at;
    items_.pop_back();
    index_[static_cast<size_t>(x)] = -1;
  }
  size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }
  std::vector<int>::const_iterator begin() const { return items_.begin(); }
  std::vector<int>::const_iterator end() const { return items_.end(); }

 private:
  std::vector<int> items_;
  std::vector<int> index_;  // position in items_, or −1
};

}  // namespace asgard::solver
