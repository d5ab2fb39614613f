// Broad phase: sort and sweep on axis-aligned boxes.
//
// Design
// ------
// Boxes are sorted by their lower x bound (ties by id, then by insertion, so
// the result does not depend on the sort's stability).  Sweeping in that
// order, box i is compared with the following boxes j until lo_x(j) > hi_x(i);
// every such j overlaps i in x, and the pair is kept when y and z overlap
// too.  Intervals are closed: touching boxes are reported.  The cost is
// N log N for the sort plus the number of x-overlapping pairs, which for the
// solver's boxes (bounds of bodies over one step) is close to the number of
// reported pairs.  Pairs are normalised to (smaller id, larger id), sorted,
// and made unique (the same id added twice never pairs with itself).
//
// Static boxes (walls, floors) would sit in that sweep every time and, being
// large, overlap every moving box in x: they live instead in a bounding-box
// tree built once (median splits on the longest axis), which each moving box
// descends (log S + its hits).  Statics never pair with one another.
//
// Rejected alternatives:
//   * Persistent incremental sweep and prune (insertion sort between calls):
//     faster for coherent scenes, but the interface rebuilds boxes per query
//     and the sort is not the bottleneck at Asgard's scene sizes.
//   * Uniform grid or octree (mentioned by the seed, 5.3.1): needs a cell
//     size tuned to the scene; the sweep needs no parameters.
#include <algorithm>
#include <numeric>

#include "core/collide/collide.h"

namespace asgard::collide {

namespace {

template <typename A, typename B>
bool Overlap(const A& a, const B& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

}  // namespace

void BroadPhase::Clear() { boxes_.clear(); }

void BroadPhase::Add(int id, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  boxes_.push_back(Box{id, lo, hi});
}

void BroadPhase::AddStatic(int id, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  statics_.push_back(Box{id, lo, hi});
  tree_.clear();
}

// Top-down: the node bounds statics_[begin, end); inner nodes split them at
// the median centre along the longest axis of the centres' extent.
int BroadPhase::Build(int begin, int end) const {
  const int index = static_cast<int>(tree_.size());
  tree_.push_back(Node{});
  Eigen::Vector3d lo = statics_[begin].lo, hi = statics_[begin].hi;
  Eigen::Vector3d clo = lo + hi, chi = lo + hi;  // twice the centres
  for (int i = begin + 1; i < end; ++i) {
    lo = lo.cwiseMin(statics_[i].lo);
    hi = hi.cwiseMax(statics_[i].hi);
    clo = clo.cwiseMin(statics_[i].lo + statics_[i].hi);
    chi = chi.cwiseMax(statics_[i].lo + statics_[i].hi);
  }
  tree_[index].lo = lo;
  tree_[index].hi = hi;
  if (end - begin == 1) {
    tree_[index].first = begin;
    return index;
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(statics_.begin() + begin, statics_.begin() + mid, statics_.begin() + end,
                   [axis](const Box& a, const Box& b) {
                     const double ca = a.lo[axis] + a.hi[axis], cb = b.lo[axis] + b.hi[axis];
                     return ca != cb ? ca < cb : a.id < b.id;
                   });
  Build(begin, mid);
  const int right = Build(mid, end);
  tree_[index].right = right;
  return index;
}

std::vector<std::pair<int, int>> BroadPhase::Pairs() const {
  std::vector<size_t> order(boxes_.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [this](size_t i, size_t j) {
    const Box& a = boxes_[i];
    const Box& b = boxes_[j];
    if (a.lo.x() != b.lo.x()) return a.lo.x() < b.lo.x();
    if (a.id != b.id) return a.id < b.id;
    return i < j;
  });
  std::vector<std::pair<int, int>> pairs;
  for (size_t k = 0; k < order.size(); ++k) {
    const Box& a = boxes_[order[k]];
    for (size_t m = k + 1; m < order.size(); ++m) {
      const Box& b = boxes_[order[m]];
      if (b.lo.x() > a.hi.x()) break;
      if (a.id == b.id) continue;
      if (b.lo.y() > a.hi.y() || a.lo.y() > b.hi.y()) continue;
      if (b.lo.z() > a.hi.z() || a.lo.z() > b.hi.z()) continue;
      pairs.emplace_back(std::min(a.id, b.id), std::max(a.id, b.id));
    }
  }
  if (!statics_.empty()) {
    if (tree_.empty()) Build(0, static_cast<int>(statics_.size()));
    std::vector<int> stack;
    for (const Box& a : boxes_) {
      stack.assign(1, 0);
      while (!stack.empty()) {
        const Node& node = tree_[static_cast<size_t>(stack.back())];
        const int at = stack.back();
        stack.pop_back();
        if (!Overlap(a, node)) continue;
        if (node.first >= 0) {
          const Box& s = statics_[static_cast<size_t>(node.first)];
          if (s.id != a.id) pairs.emplace_back(std::min(a.id, s.id), std::max(a.id, s.id));
          continue;
        }
        stack.push_back(node.right);
        stack.push_back(at + 1);
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace asgard::collide
