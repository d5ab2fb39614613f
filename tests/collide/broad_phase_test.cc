// Sweep and prune against brute force.
#include <gtest/gtest.h>

#include <random>

#include "core/collide/collide.h"

namespace asgard::collide {
namespace {

struct Aabb {
  int id;
  Eigen::Vector3d lo, hi;
};

std::vector<std::pair<int, int>> BruteForce(const std::vector<Aabb>& boxes) {
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < boxes.size(); ++i) {
    for (size_t j = i + 1; j < boxes.size(); ++j) {
      const Aabb& a = boxes[i];
      const Aabb& b = boxes[j];
      if ((a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all()) {
        pairs.emplace_back(std::min(a.id, b.id), std::max(a.id, b.id));
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

void CompareWithBruteForce(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> position(0.0, 10.0);
  std::uniform_real_distribution<double> size(0.0, 1.2);
  std::vector<int> ids(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) ids[static_cast<size_t>(i)] = 3 * (n - i) + 7;  // unordered ids
  std::shuffle(ids.begin(), ids.end(), rng);
  std::vector<Aabb> boxes;
  BroadPhase bp;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d lo(position(rng), position(rng), position(rng));
    const Eigen::Vector3d hi = lo + Eigen::Vector3d(size(rng), size(rng), size(rng));
    boxes.push_back({ids[static_cast<size_t>(i)], lo, hi});
    bp.Add(ids[static_cast<size_t>(i)], lo, hi);
  }
  const auto expected = BruteForce(boxes);
  EXPECT_EQ(bp.Pairs(), expected);
  EXPECT_FALSE(expected.empty());
}

TEST(BroadPhase, PairsEqualBruteForceOn200RandomBoxes) { CompareWithBruteForce(200, 1); }

TEST(BroadPhase, PairsEqualBruteForceOn1000RandomBoxes) { CompareWithBruteForce(1000, 2); }

TEST(BroadPhase, EmptyAndSingleBoxGiveNoPairs) {
  BroadPhase bp;
  EXPECT_TRUE(bp.Pairs().empty());
  bp.Add(4, {0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(bp.Pairs().empty());
}

TEST(BroadPhase, TouchingBoxesPairOnceAsSmallerIdFirstAndClearEmpties) {
  BroadPhase bp;
  bp.Add(9, {0, 0, 0}, {1, 1, 1});
  bp.Add(2, {1, 0.5, 0.5}, {2, 2, 2});    // touches at x = 1
  bp.Add(5, {0, 0, 1.5}, {0.5, 0.5, 2});  // overlaps neither
  const auto pairs = bp.Pairs();
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], std::make_pair(2, 9));
  bp.Clear();
  EXPECT_TRUE(bp.Pairs().empty());
}

// Statics in their own tree: moving–moving and moving–static pairs exactly
// as brute force finds them, static–static pairs never; they stay across Clear.
TEST(BroadPhase, StaticBoxesPairOnlyWithMovingOnesAndStayAcrossClear) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> position(0.0, 10.0), size(0.0, 1.2), big(0.0, 6.0);
  std::vector<Aabb> moving, statics;
  BroadPhase bp;
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector3d lo(position(rng), position(rng), position(rng));
    statics.push_back({1000 + i, lo, lo + Eigen::Vector3d(big(rng), big(rng), big(rng))});
    bp.AddStatic(statics.back().id, statics.back().lo, statics.back().hi);
  }
  for (int round = 0; round < 2; ++round) {
    bp.Clear();
    moving.clear();
    for (int i = 0; i < 300; ++i) {
      const Eigen::Vector3d lo(position(rng), position(rng), position(rng));
      moving.push_back({i, lo, lo + Eigen::Vector3d(size(rng), size(rng), size(rng))});
      bp.Add(i, moving.back().lo, moving.back().hi);
    }
    std::vector<Aabb> all = moving;
    all.insert(all.end(), statics.begin(), statics.end());
    auto expected = BruteForce(all);
    std::erase_if(expected, [](const auto& p) { return p.first >= 1000; });  // static–static
    const auto pairs = bp.Pairs();
    EXPECT_EQ(pairs, expected) << "round " << round;
    EXPECT_TRUE(
        std::any_of(pairs.begin(), pairs.end(), [](const auto& p) { return p.second >= 1000; }))
        << "round " << round;
  }
}

// Resting boxes come and go (sleep, wake) across rounds: moving boxes pair
// with moving, static and resting ones exactly as brute force finds them;
// resting boxes never pair with statics or one another.
TEST(BroadPhase, RestingBoxesAddedAndRemovedPairOnlyWithMovingOnes) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> position(0.0, 10.0), size(0.0, 1.2), big(0.0, 6.0);
  std::uniform_int_distribution<int> pick(0, 299);
  BroadPhase bp;
  std::vector<Aabb> statics;
  for (int i = 0; i < 10; ++i) {
    const Eigen::Vector3d lo(position(rng), position(rng), position(rng));
    statics.push_back({1000 + i, lo, lo + Eigen::Vector3d(big(rng), big(rng), big(rng))});
    bp.AddStatic(statics.back().id, statics.back().lo, statics.back().hi);
  }
  std::vector<Aabb> boxes;  // ids 0..299, each moving or resting
  std::vector<char> resting(300, 0);
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d lo(position(rng), position(rng), position(rng));
    boxes.push_back({i, lo, lo + Eigen::Vector3d(size(rng), size(rng), size(rng))});
  }
  for (int round = 0; round < 30; ++round) {
    // Some bodies fall asleep (possibly at a new place), some wake.
    for (int k = 0; k < 25; ++k) {
      const int i = pick(rng);
      if (resting[i] && k % 2) {
        bp.RemoveResting(i);
        resting[i] = 0;
      } else {
        const Eigen::Vector3d lo(position(rng), position(rng), position(rng));
        boxes[i] = {i, lo, lo + Eigen::Vector3d(size(rng), size(rng), size(rng))};
        bp.AddResting(i, boxes[i].lo, boxes[i].hi);
        resting[i] = 1;
      }
    }
    bp.Clear();
    for (const Aabb& b : boxes)
      if (!resting[b.id]) bp.Add(b.id, b.lo, b.hi);
    std::vector<Aabb> all = boxes;
    all.insert(all.end(), statics.begin(), statics.end());
    auto still = [&](int id) { return id >= 1000 || resting[id]; };
    auto expected = BruteForce(all);
    std::erase_if(expected, [&](const auto& p) { return still(p.first) && still(p.second); });
    const auto pairs = bp.Pairs();
    ASSERT_EQ(pairs, expected) << "round " << round;
    for (int i = 0; i < 300; ++i) ASSERT_EQ(bp.Resting(i), resting[i] != 0) << i;
  }
}

// The resting tree is rebuilt lazily, at the first Pairs after enough
// additions or removals: batches of every size between two queries (one
// box, hundreds at once, the same body re-added several times, all removed)
// give exactly the pairs of a broad phase built afresh from the final
// resting set, and of brute force.
TEST(BroadPhase, RestingBatchesOfAnySizeGiveThePairsOfAFreshBuild) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> position(0.0, 10.0), size(0.0, 1.2);
  std::uniform_int_distribution<int> pick(0, 399);
  auto random_box = [&](int id) {
    const Eigen::Vector3d lo(position(rng), position(rng), position(rng));
    return Aabb{id, lo, lo + Eigen::Vector3d(size(rng), size(rng), size(rng))};
  };
  std::vector<Aabb> boxes;
  for (int i = 0; i < 400; ++i) boxes.push_back(random_box(i));
  std::vector<char> resting(400, 0);
  BroadPhase bp;
  bp.AddStatic(1000, {0, 0, -1}, {10, 10, 0.3});  // a floor
  const int batches[] = {1, 300, 2, 150, 40, 1, 400, 9, 0, 250};
  for (int round = 0; round < 10; ++round) {
    for (int k = 0; k < batches[round]; ++k) {
      const int i = pick(rng);
      if (resting[i] && (round == 3 || k % 3 == 0)) {
        bp.RemoveResting(i);
        resting[i] = 0;
      } else {  // first rest, or a re-add at a new place
        boxes[i] = random_box(i);
        bp.AddResting(i, boxes[i].lo, boxes[i].hi);
        resting[i] = 1;
      }
    }
    if (round == 8)  // everything wakes
      for (int i = 0; i < 400; ++i)
        if (resting[i]) {
          bp.RemoveResting(i);
          resting[i] = 0;
        }
    BroadPhase fresh;
    fresh.AddStatic(1000, {0, 0, -1}, {10, 10, 0.3});
    std::vector<Aabb> all = {Aabb{1000, {0, 0, -1}, {10, 10, 0.3}}};
    bp.Clear();
    for (const Aabb& b : boxes) {
      all.push_back(b);
      if (resting[b.id]) {
        fresh.AddResting(b.id, b.lo, b.hi);
      } else {
        bp.Add(b.id, b.lo, b.hi);
        fresh.Add(b.id, b.lo, b.hi);
      }
    }
    auto expected = BruteForce(all);
    auto still = [&](int id) { return id >= 1000 || resting[id]; };
    std::erase_if(expected, [&](const auto& p) { return still(p.first) && still(p.second); });
    const auto pairs = bp.Pairs();
    ASSERT_EQ(pairs, fresh.Pairs()) << "round " << round;
    ASSERT_EQ(pairs, expected) << "round " << round;
  }
}

}  // namespace
}  // namespace asgard::collide
