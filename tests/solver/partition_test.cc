// Tarjan partitioning on hand-made reference graphs.
#include "core/solver/partition.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/solver/tape_cache.h"

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

// Two bodies' rates, the same up to the shift of their variables: one tape,
// evaluated on the shifted values, bit for bit what a tape of its own gives.
// A different constant, a different variable pattern or a negative shift
// compiles a tape of its own.
TEST(TapeCache, SharesATapeBetweenEquationsEqualUpToAShiftOfTheirVariables) {
  expr::Pool pool;
  // f(base) = {sin(x_b) · x_{b+1} + 2.5, x_{b+1}² − t}.  The nodes are made
  // one statement at a time: the pool orders a sum's terms by node id, so a
  // match needs the same relative creation order, which nested calls would
  // leave to the compiler's (unspecified) order of evaluating arguments.
  auto rates = [&](int b, double k) {
    const expr::NodeId s = pool.Apply(expr::Op::kSin, std::vector<expr::NodeId>{pool.Var(b)});
    const expr::NodeId c = pool.Const(k);
    const expr::NodeId next = pool.Var(b + 1);
    const expr::NodeId product = pool.Mul(s, next);
    const expr::NodeId sum = pool.Add(product, c);
    const expr::NodeId t = pool.Time();
    const expr::NodeId two = pool.Const(2.0);
    const expr::NodeId square = pool.Pow(next, two);
    return std::vector<expr::NodeId>{sum, pool.Sub(square, t)};
  };
  TapeCache cache;
  const auto a = cache.Get(pool, rates(2, 2.5));
  const auto b = cache.Get(pool, rates(7, 2.5));
  EXPECT_EQ(cache.compiled(), 1);
  EXPECT_EQ(b.tape, a.tape);
  EXPECT_EQ(b.shift, 5);
  EXPECT_TRUE(b.reads_time);
  const double x[10] = {0, 0, 0.3, -1.7, 0, 0, 0, 1.1, 0.25, 0};
  double shared[2], own[2];
  b.tape->Evaluate(0.75, x + b.shift, shared);
  const expr::Tape mine = expr::Tape::Compile(pool, rates(7, 2.5));
  mine.Evaluate(0.75, x, own);
  EXPECT_EQ(shared[0], own[0]);
  EXPECT_EQ(shared[1], own[1]);
  EXPECT_DOUBLE_EQ(shared[0], std::sin(1.1) * 0.25 + 2.5);
  // Different constant; variables out of step (x_b and x_{b+2}); below the
  // first tape's variables (a negative shift).
  EXPECT_NE(cache.Get(pool, rates(4, 3.5)).tape, a.tape);
  const std::vector<expr::NodeId> apart = {pool.Add(pool.Var(3), pool.Var(5))};
  const std::vector<expr::NodeId> near = {pool.Add(pool.Var(3), pool.Var(4))};
  EXPECT_NE(cache.Get(pool, apart).tape, cache.Get(pool, near).tape);
  EXPECT_NE(cache.Get(pool, rates(0, 2.5)).tape, a.tape);
  EXPECT_EQ(cache.shared(), 1);
}

}  // namespace
}  // namespace asgard::solver
