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

void BroadPhase::Clear() { boxes_.clear(); }

void BroadPhase::Add(int id, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  boxes_.push_back(Box{id, lo, hi});
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
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace asgard::collide
