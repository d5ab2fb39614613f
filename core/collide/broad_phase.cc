// Broad phase: sort and sweep on axis-aligned boxes.
//
// Design
// ------
// Boxes are sorted by their lower bound on the sweep axis — the axis their
// centres spread most on — (ties by id, then by insertion, so the result
// does not depend on the sort's stability).  Sweeping in that order, box i
// is compared with the following boxes j until lo(j) > hi(i) on that axis;
// every such j overlaps i there, and the pair is kept when the other axes
// overlap too.  Intervals are closed: touching boxes are reported.  The cost is
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
// Resting boxes (bodies holding still: asleep, or at rest where no force
// moves them) would otherwise be sampled, boxed and sorted every window
// though they do not change: a thousand hanging pendulums cost the sweep a
// thousand boxes per window.  They go in a second tree that pairs only with
// moving boxes.  It changes incrementally: a removal bumps the id's
// generation, so its leaf no longer counts (the node bounds stay
// conservative); an addition waits in a list each moving box scans; the
// tree is rebuilt from the live boxes, at the next query, once that list
// exceeds 8 + R/8 or the dead leaves 8 + R (R live boxes), so a change
// costs amortised O(log R), a window with no change costs only the moving
// boxes' descents, and a thousand bodies coming to rest at once cost one
// build (rebuilt as they came, by the same rule, they cost about nine).
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

void BroadPhase::AddStatic(int id, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  statics_.boxes.push_back(Box{id, lo, hi});
  statics_built_ = false;
}

void BroadPhase::AddResting(int id, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const size_t i = static_cast<size_t>(id);
  if (i >= resting_gen_.size()) resting_gen_.resize(i + 1, 0);
  if (resting_gen_[i] != 0)
    ++resting_dead_;  // the old box of this id
  else
    ++resting_live_;
  resting_gen_[i] = next_gen_++;
  resting_new_.push_back(Box{id, lo, hi, resting_gen_[i]});
}

void BroadPhase::RemoveResting(int id) {
  if (!Resting(id)) return;
  resting_gen_[static_cast<size_t>(id)] = 0;
  --resting_live_;
  ++resting_dead_;
}

void BroadPhase::RebuildResting() const {
  if (static_cast<long>(resting_new_.size()) <= 8 + resting_live_ / 8 &&
      resting_dead_ <= 8 + resting_live_)
    return;
  std::vector<Box> live;
  live.reserve(static_cast<size_t>(resting_live_));
  for (const auto* list : {&resting_.boxes, &resting_new_})
    for (const Box& b : *list)
      if (resting_gen_[static_cast<size_t>(b.id)] == b.gen) live.push_back(b);
  resting_.boxes = std::move(live);
  resting_.Build();
  resting_new_.clear();
  resting_dead_ = 0;
}

// Top-down: the node bounds boxes[begin, end); inner nodes split them at
// the median centre along the longest axis of the centres' extent.
int BroadPhase::Tree::Build(int begin, int end) {
  const int index = static_cast<int>(nodes.size());
  nodes.push_back(Node{});
  Eigen::Vector3d lo = boxes[begin].lo, hi = boxes[begin].hi;
  Eigen::Vector3d clo = lo + hi, chi = lo + hi;  // twice the centres
  for (int i = begin + 1; i < end; ++i) {
    lo = lo.cwiseMin(boxes[i].lo);
    hi = hi.cwiseMax(boxes[i].hi);
    clo = clo.cwiseMin(boxes[i].lo + boxes[i].hi);
    chi = chi.cwiseMax(boxes[i].lo + boxes[i].hi);
  }
  nodes[index].lo = lo;
  nodes[index].hi = hi;
  if (end - begin == 1) {
    nodes[index].first = begin;
    return index;
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(boxes.begin() + begin, boxes.begin() + mid, boxes.begin() + end,
                   [axis](const Box& a, const Box& b) {
                     const double ca = a.lo[axis] + a.hi[axis], cb = b.lo[axis] + b.hi[axis];
                     return ca != cb ? ca < cb : a.id < b.id;
                   });
  Build(begin, mid);
  const int right = Build(mid, end);
  nodes[index].right = right;
  return index;
}

template <typename F>
void BroadPhase::Tree::Query(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, F&& f) const {
  if (nodes.empty()) return;
  int stack[64];  // depth ≤ log2(boxes) + 1 (median splits)
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int at = stack[--top];
    const Node& node = nodes[static_cast<size_t>(at)];
    if (!BoxesOverlap(lo, hi, node.lo, node.hi)) continue;
    if (node.first >= 0) {
      f(boxes[static_cast<size_t>(node.first)]);
      continue;
    }
    stack[top++] = node.right;
    stack[top++] = at + 1;
  }
}

std::vector<std::pair<int, int>> BroadPhase::Pairs() const {
  // The sweep runs along the axis the box centres spread most on: along a
  // fixed x, a grid of idle pendulums in 32 columns put N/32 boxes on each
  // column's x range, N²/64 box tests per window (superlinear in N).
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum2 = Eigen::Vector3d::Zero();
  for (const Box& b : boxes_) {
    const Eigen::Vector3d c = b.lo + b.hi;
    sum += c;
    sum2 += c.cwiseProduct(c);
  }
  int axis = 0;
  if (!boxes_.empty())
    (sum2 - sum.cwiseProduct(sum) / static_cast<double>(boxes_.size())).maxCoeff(&axis);
  std::vector<size_t> order(boxes_.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [this, axis](size_t i, size_t j) {
    const Box& a = boxes_[i];
    const Box& b = boxes_[j];
    if (a.lo[axis] != b.lo[axis]) return a.lo[axis] < b.lo[axis];
    if (a.id != b.id) return a.id < b.id;
    return i < j;
  });
  std::vector<std::pair<int, int>> pairs;
  auto pair = [&pairs](int a, int b) {
    if (a != b) pairs.emplace_back(std::min(a, b), std::max(a, b));
  };
  for (size_t k = 0; k < order.size(); ++k) {
    const Box& a = boxes_[order[k]];
    for (size_t m = k + 1; m < order.size(); ++m) {
      const Box& b = boxes_[order[m]];
      if (b.lo[axis] > a.hi[axis]) break;
      if (BoxesOverlap(a.lo, a.hi, b.lo, b.hi)) pair(a.id, b.id);
    }
  }
  if (!statics_built_) {
    statics_.Build();
    statics_built_ = true;
  }
  RebuildResting();
  for (const Box& a : boxes_) {
    statics_.Query(a.lo, a.hi, [&](const Box& s) { pair(a.id, s.id); });
    auto resting = [&](const Box& r) {
      if (resting_gen_[static_cast<size_t>(r.id)] == r.gen) pair(a.id, r.id);
    };
    resting_.Query(a.lo, a.hi, resting);
    for (const Box& r : resting_new_)
      if (BoxesOverlap(a.lo, a.hi, r.lo, r.hi)) resting(r);
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace asgard::collide
