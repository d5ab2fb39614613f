// Tarjan partitioning on hand-made reference graphs.
#include "core/solver/partition.h"

#include <gtest/gtest.h>

namespace asgard::solver {
namespace {

TEST(PartitionEquations, FindsCyclesAndOrdersComponentsAfterTheirInputs) {
  // 0 ← 1 ← 2 ⇄ 3, 4 alone, 5 reads 0 and 4
  const std::vector<std::vector<int>> reads = {{1}, {2}, {3}, {2}, {}, {0, 4}};
  const Partition p = PartitionEquations(reads);
  ASSERT_EQ(p.components.size(), 5u);
  EXPECT_EQ(p.component_of[2], p.component_of[3]);
  for (size_t c = 0; c < p.components.size(); ++c)
    for (int u : p.upstream[c]) EXPECT_LT(u, static_cast<int>(c)) << "component " << c;
  EXPECT_EQ(p.upstream[p.component_of[5]].size(), 2u);
  EXPECT_EQ(p.downstream[p.component_of[2]], std::vector<int>{p.component_of[1]});
}

TEST(PartitionEquations, SelfReferenceIsOneComponentOfOne) {
  const Partition p = PartitionEquations({{0}, {0}});
  ASSERT_EQ(p.components.size(), 2u);
  EXPECT_TRUE(p.upstream[p.component_of[0]].empty());
}

TEST(PartitionEquations, SingleModePutsEverythingInOneComponent) {
  const Partition p = PartitionEquations({{1}, {}, {}}, /*single=*/true);
  ASSERT_EQ(p.components.size(), 1u);
  EXPECT_EQ(p.components[0], (std::vector<int>{0, 1, 2}));
}

TEST(PartitionEquations, ALongChainDoesNotOverflowTheStack) {
  const int n = 200000;
  std::vector<std::vector<int>> reads(n);
  for (int i = 1; i < n; ++i) reads[i] = {i - 1};
  reads[0] = {n - 1};  // one big cycle
  const Partition p = PartitionEquations(reads);
  ASSERT_EQ(p.components.size(), 1u);
  EXPECT_EQ(p.components[0].size(), static_cast<size_t>(n));
}

}  // namespace
}  // namespace asgard::solver
