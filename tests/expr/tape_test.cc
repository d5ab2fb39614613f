// Tape compilation and evaluation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/expr/expr.h"
#include "core/expr/internal.h"
#include "tests/expr/test_util.h"

namespace asgard::expr {
namespace {

using testing::Interpreter;
using testing::P;
using testing::SameDouble;

TEST(Tape, MatchesARecursiveInterpreterBitForBitOnRandomExpressions) {
  Pool pool;
  testing::RandomExpr gen(pool, 17);
  ExternFn ext = testing::TestExtern;
  int finite = 0;
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<NodeId> outs;
    for (int k = 0; k < 3; ++k) outs.push_back(gen.Make(6));
    const Tape tape = Tape::Compile(pool, outs);
    ASSERT_EQ(tape.output_count(), outs.size());
    for (int point = 0; point < 4; ++point) {
      std::vector<double> x(4);
      for (double& v : x) v = gen.Real(-2, 2);
      const double t = gen.Real(-1, 3);
      std::vector<double> got(outs.size());
      tape.Evaluate(t, x.data(), got.data(), &ext);
      const Interpreter ref(pool, t, x);
      for (size_t k = 0; k < outs.size(); ++k) {
        const double want = ref.Eval(outs[k]);
        EXPECT_TRUE(SameDouble(got[k], want))
            << pool.ToString(outs[k]) << ": tape " << got[k] << " reference " << want;
        finite += std::isfinite(want);
      }
    }
  }
  EXPECT_GT(finite, 1000);  // the comparison is not dominated by NaN
}

TEST(Tape, SharedSubexpressionsAreEvaluatedOnce) {
  Pool pool;
  const NodeId r = P(pool, "sin(x)*cos(y)");
  const NodeId a = pool.Add(r, pool.Var(2));
  const NodeId b = pool.Mul(r, pool.Var(2));
  const NodeId outs[2] = {a, b};
  const Tape tape = Tape::Compile(pool, outs);
  // x, y, z, sin, cos, product, sum, product with z: one instruction each.
  EXPECT_EQ(tape.instruction_count(), 8u);
  const double x[3] = {0.3, 0.4, 2.0};
  double out[2];
  tape.Evaluate(0, x, out);
  const double rv = std::sin(0.3) * std::cos(0.4);
  EXPECT_EQ(out[0], rv + 2.0);
  EXPECT_EQ(out[1], rv * 2.0);
}

TEST(Tape, EvaluatesLeavesConstantsAndRepeatedOutputs) {
  Pool pool;
  const NodeId outs[4] = {pool.Const(2.5), pool.Time(), pool.Var(1), pool.Var(1)};
  const Tape tape = Tape::Compile(pool, outs);
  const double x[2] = {7, 8};
  double out[4];
  tape.Evaluate(1.25, x, out);
  EXPECT_EQ(out[0], 2.5);
  EXPECT_EQ(out[1], 1.25);
  EXPECT_EQ(out[2], 8);
  EXPECT_EQ(out[3], 8);
  tape.Evaluate(-3, x, out);  // re-evaluation uses the new t
  EXPECT_EQ(out[1], -3);
  const Tape empty = Tape::Compile(pool, {});
  empty.Evaluate(0, nullptr, nullptr);
  EXPECT_EQ(empty.output_count(), 0u);
}

TEST(Tape, ExternalFunctionsReceiveFunctionOrderAndTime) {
  Pool pool;
  const NodeId e = P(pool, "ext3.d2 + 10*ext1");
  const NodeId outs[1] = {e};
  const Tape tape = Tape::Compile(pool, outs);
  std::vector<std::tuple<int, int, double>> calls;
  ExternFn ext = [&](int fn, int order, double t) {
    calls.emplace_back(fn, order, t);
    return fn * 100.0 + order;
  };
  double out = 0;
  tape.Evaluate(0.5, nullptr, &out, &ext);
  EXPECT_EQ(out, 302.0 + 10 * 100.0);
  EXPECT_EQ(calls.size(), 2u);
  EXPECT_THROW(tape.Evaluate(0.5, nullptr, &out, nullptr), std::invalid_argument);
}

TEST(Tape, DivisionByZeroFollowsIeee) {
  Pool pool;
  const NodeId outs[3] = {P(pool, "1/x"), P(pool, "x/x"), P(pool, "y/x")};
  const Tape tape = Tape::Compile(pool, outs);
  const double x[2] = {0.0, -1.0};
  double out[3];
  tape.Evaluate(0, x, out);
  EXPECT_EQ(out[0], std::numeric_limits<double>::infinity());
  EXPECT_EQ(out[1], 1.0);  // x/x was simplified to 1
  EXPECT_EQ(out[2], -std::numeric_limits<double>::infinity());
  const NodeId nan_out[1] = {P(pool, "(x - y - 1)/x")};
  const Tape nan_tape = Tape::Compile(pool, nan_out);
  nan_tape.Evaluate(0, x, out);
  EXPECT_TRUE(std::isnan(out[0]));
}

TEST(Tape, LargeSumsAndProductsUseOperandLists) {
  Pool pool;
  std::vector<NodeId> terms;
  for (int i = 0; i < 50; ++i) terms.push_back(pool.Mul(pool.Var(i), pool.Var(i + 1)));
  const NodeId outs[2] = {pool.Sum(terms), pool.Product(terms)};
  const Tape tape = Tape::Compile(pool, outs);
  std::vector<double> x(51);
  for (int i = 0; i < 51; ++i) x[i] = 1.0 + i * 0.01;
  double out[2];
  tape.Evaluate(0, x.data(), out);
  const Interpreter ref(pool, 0, x);
  EXPECT_TRUE(SameDouble(out[0], ref.Eval(outs[0])));
  EXPECT_TRUE(SameDouble(out[1], ref.Eval(outs[1])));
}

// The per-node scratch of Compile and Variables: unset again after a walk
// (a stale mark would make the next compilation reuse a register that
// holds another node), a second walk of the same kind inside one refused,
// and grown for a larger pool.
TEST(NodeScratch, IsClearedAfterEachWalkAndRefusesToNest) {
  struct TagA;
  struct TagB;
  {
    internal::NodeScratch<TagA, int, -1> a(8);
    a.set(3, 7);
    a.set(3, 9);
    a.set(5, 1);
    EXPECT_EQ(a.get(3), 9);
    EXPECT_EQ(a.get(4), -1);
    EXPECT_THROW((internal::NodeScratch<TagA, int, -1>(8)), std::logic_error);
    internal::NodeScratch<TagB, int, -1> b(8);  // another kind nests
    EXPECT_EQ(b.get(3), -1);
  }
  internal::NodeScratch<TagA, int, -1> again(100);
  for (NodeId id : {3u, 5u, 99u}) EXPECT_EQ(again.get(id), -1) << id;
}

// Tapes compiled one after another from one pool, sharing nodes, each equal
// to a fresh compilation of its own outputs in a pool of its own.
TEST(Tape, CompilationsInARowShareNothingButThePool) {
  Pool pool;
  const NodeId a = P(pool, "x*y + sin(x)"), b = P(pool, "x*y - 2"), c = P(pool, "sin(x) * (x*y)");
  const std::vector<double> x = {0.3, -1.7};
  std::vector<double> first(1), second(1), third(1);
  Tape::Compile(pool, std::vector<NodeId>{a}).Evaluate(0.0, x.data(), first.data());
  Tape::Compile(pool, std::vector<NodeId>{b}).Evaluate(0.0, x.data(), second.data());
  Tape::Compile(pool, std::vector<NodeId>{c}).Evaluate(0.0, x.data(), third.data());
  EXPECT_EQ(first[0], 0.3 * -1.7 + std::sin(0.3));
  EXPECT_EQ(second[0], 0.3 * -1.7 - 2);
  EXPECT_DOUBLE_EQ(third[0], std::sin(0.3) * (0.3 * -1.7));
}

}  // namespace
}  // namespace asgard::expr
