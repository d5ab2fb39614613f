// Tarjan partitioning on hand-made reference graphs.
#include "core/solver/partition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

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

// Islands (ReadGraph::islands: ranges of a body's variables that read only
// each other and that nothing else reads) listed without their arcs give
// the partition of the whole graph, order included: random graphs of
// bodies, some islands, the others reading one another and loose variables.
TEST(PartitionEquations, IslandsWithoutTheirArcsGiveThePartitionOfTheWholeGraph) {
  std::mt19937_64 rng(7);
  int island_count = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int bodies = 10, per = 4, n = bodies * per + 6;  // and 6 loose variables
    std::vector<char> island(bodies);
    for (auto& i : island) i = rng() % 2 == 0;
    auto body = [&](int v) { return v < bodies * per ? v / per : -1; };
    auto in_island = [&](int v) { return body(v) >= 0 && island[body(v)]; };
    std::vector<int> open;  // variables of no island
    for (int v = 0; v < n; ++v)
      if (!in_island(v)) open.push_back(v);
    std::vector<std::vector<int>> reads(n), outside(n);
    for (int v = 0; v < n; ++v) {
      for (int k = static_cast<int>(rng() % 4); k > 0; --k)
        reads[v].push_back(in_island(v) ? body(v) * per + static_cast<int>(rng() % per)
                                        : open[rng() % open.size()]);
      std::sort(reads[v].begin(), reads[v].end());
      reads[v].erase(std::unique(reads[v].begin(), reads[v].end()), reads[v].end());
      if (!in_island(v)) outside[v] = reads[v];
    }
    std::vector<int> body_of(n);
    for (int v = 0; v < n; ++v) body_of[v] = body(v);
    const Partition whole = PartitionEquations(reads, false, true, body_of);
    ReadGraph g = ReadGraph::From(outside);
    for (int b = 0; b < bodies; ++b)
      if (island[b]) {
        g.islands.push_back({b * per, per});
        ++island_count;
      }
    const Partition fast = PartitionEquations(g, false, true, body_of);
    ASSERT_EQ(fast.components, whole.components) << "trial " << trial;
    ASSERT_EQ(fast.component_of, whole.component_of) << "trial " << trial;
    ASSERT_EQ(fast.upstream, whole.upstream) << "trial " << trial;
    ASSERT_EQ(fast.downstream, whole.downstream) << "trial " << trial;
  }
  EXPECT_GT(island_count, 500);
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
