// Symbolic derivatives against central difference quotients.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/expr/expr.h"
#include "tests/expr/test_util.h"

namespace asgard::expr {
namespace {

using testing::EvalTape;
using testing::P;

constexpr int kVars = 6;

// Expressions over x, y, z, b1.x, b1.y, tr1.dy (Var 0..5) and t; variables are
// sampled in [0.2, 0.9] so every function is defined and smooth nearby.
const char* const kExpressions[] = {
    "x*y + z",
    "x**3 - 2*x*y + 7",
    "x/y - z/(x*y)",
    "sin(x)*cos(y)",
    "tan(x)",
    "asin(x) + acos(y)",
    "atan(x*y)",
    "sinh(x) + cosh(y) - tanh(z)",
    "exp(x*y)",
    "log(x + y)",
    "sqrt(x*y + 1)",
    "abs(x - 0.05)*y",
    "floor(3*x) + x",
    "ceil(x)*y",
    "sign(x - 0.1)*x",
    "atan2(y, x)",
    "atan2(x - 1, y*z)",
    "hypot(x, y)",
    "min(x, y) + max(x*y, z)",
    "fmod(x*5, y + 0.3)",
    "(x + 2) % (y + 0.5)",
    "x**y",
    "pow(x + 1, y*z)",
    "2**x",
    "x**-1.5",
    "x > y ? x*x : y*z",
    "(x < 0.5)*y + (x == y) + !(z > x) + (x && y) + (x || y)",
    "1/(1 + exp(-x*y))",
    "sin(x)**2 + cos(x)**2",
    "x*y*z*sin(x*y*z)",
    "b1.x*tr1.dy - b1.y**2*t",
    "x*t + sin(t*y)",
    "sqrt(b1.x**2 + b1.y**2)*cos(atan2(b1.y, b1.x) - t)",
    "exp(-x)*sin(10*y)/(1 + z**2)",
    "(x*y - y*x + z)**3",
};

double Eval(const Pool& pool, NodeId e, const std::vector<double>& x, double t) {
  return EvalTape(pool, e, t, x);
}

// Central difference of `e` in variable i at x.
double CentralDifference(const Pool& pool, NodeId e, std::vector<double> x, int i, double t) {
  const double h = 1e-5 * std::max(1.0, std::fabs(x[i]));
  const double x0 = x[i];
  x[i] = x0 + h;
  const double fp = Eval(pool, e, x, t);
  x[i] = x0 - h;
  const double fm = Eval(pool, e, x, t);
  return (fp - fm) / (2 * h);
}

void ExpectClose(double symbolic, double numeric, const std::string& what) {
  const double tol = 1e-6 * std::max({1.0, std::fabs(symbolic), std::fabs(numeric)});
  EXPECT_NEAR(symbolic, numeric, tol) << what;
}

std::vector<double> RandomPoint(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.2, 0.9);
  std::vector<double> x(kVars);
  for (double& v : x) v = u(rng);
  return x;
}

TEST(Derivative, FirstDerivativesMatchCentralDifferences) {
  Pool pool;
  std::mt19937 rng(1);
  for (const char* text : kExpressions) {
    const NodeId e = P(pool, text);
    for (int point = 0; point < 4; ++point) {
      const std::vector<double> x = RandomPoint(rng);
      const double t = std::uniform_real_distribution<double>(0, 2)(rng);
      for (int i = 0; i < kVars; ++i) {
        const NodeId d = pool.Derivative(e, i);
        ExpectClose(Eval(pool, d, x, t), CentralDifference(pool, e, x, i, t),
                    std::string(text) + " d/dx" + std::to_string(i) + " = " + pool.ToString(d));
      }
    }
  }
}

TEST(Derivative, SecondDerivativesMatchCentralDifferencesOfFirstDerivatives) {
  Pool pool;
  std::mt19937 rng(2);
  for (const char* text : kExpressions) {
    const NodeId e = P(pool, text);
    for (int point = 0; point < 2; ++point) {
      const std::vector<double> x = RandomPoint(rng);
      const double t = 0.7;
      for (int i = 0; i < kVars; ++i) {
        const NodeId di = pool.Derivative(e, i);
        for (int j = 0; j < kVars; ++j) {
          const NodeId dij = pool.Derivative(di, j);
          ExpectClose(Eval(pool, dij, x, t), CentralDifference(pool, di, x, j, t),
                      std::string(text) + " d2/dx" + std::to_string(i) + "dx" + std::to_string(j));
        }
      }
    }
  }
}

TEST(Derivative, MixedSecondDerivativesAreSymmetricForSmoothExpressions) {
  Pool pool;
  std::mt19937 rng(3);
  for (const char* text : {"x*y*z*sin(x*y*z)", "exp(x*y)", "x**y", "hypot(x, y)*atan2(y, x)"}) {
    const NodeId e = P(pool, text);
    const NodeId dxy = pool.Derivative(pool.Derivative(e, 0), 1);
    const NodeId dyx = pool.Derivative(pool.Derivative(e, 1), 0);
    const std::vector<double> x = RandomPoint(rng);
    ExpectClose(Eval(pool, dxy, x, 0), Eval(pool, dyx, x, 0), text);
  }
}

TEST(Derivative, ResultsAreSimplifiedAndMemoised) {
  Pool pool;
  EXPECT_EQ(pool.Derivative(P(pool, "x**3"), 0), P(pool, "3*x**2"));
  EXPECT_EQ(pool.Derivative(P(pool, "x*y + 3*x"), 0), P(pool, "y + 3"));
  EXPECT_EQ(pool.Derivative(P(pool, "sin(x)"), 0), P(pool, "cos(x)"));
  EXPECT_EQ(pool.Derivative(P(pool, "abs(x)"), 0), P(pool, "sign(x)"));
  EXPECT_EQ(pool.Derivative(P(pool, "t > 1 ? x*x : 3*x"), 0), P(pool, "t > 1 ? 2*x : 3"));
  EXPECT_EQ(pool.Derivative(P(pool, "min(x, y)"), 0), P(pool, "y < x ? 0 : 1"));
  EXPECT_EQ(pool.Derivative(P(pool, "y*z"), 0), pool.Const(0));

  const NodeId e = P(pool, "sin(x*y)*exp(x) + x**y");
  const NodeId d = pool.Derivative(e, 0);
  const size_t size = pool.size();
  EXPECT_EQ(pool.Derivative(e, 0), d);
  EXPECT_EQ(pool.size(), size);
}

TEST(Derivative, StepFunctionsAndComparisonsHaveZeroDerivative) {
  Pool pool;
  for (const char* text : {"floor(x)", "ceil(x*y)", "sign(x)", "x < y", "x >= 1", "x == y",
                           "x != y", "x && y", "x || y", "!x", "3"}) {
    EXPECT_EQ(pool.Derivative(P(pool, text), 0), pool.Const(0)) << text;
  }
}

TEST(Derivative, TimeDerivativeAdvancesExternOrderAndHoldsVariablesFixed) {
  Pool pool;
  EXPECT_EQ(pool.TimeDerivative(pool.Extern(2, 0)), pool.Extern(2, 1));
  EXPECT_EQ(pool.TimeDerivative(pool.Extern(2, 1)), pool.Extern(2, 2));
  EXPECT_EQ(pool.TimeDerivative(P(pool, "x*y")), pool.Const(0));
  EXPECT_EQ(pool.TimeDerivative(P(pool, "x*t")), pool.Var(0));
  EXPECT_EQ(pool.TimeDerivative(P(pool, "3*ext0 + x")), P(pool, "3*ext0.d1"));
  EXPECT_EQ(pool.Derivative(P(pool, "ext0*x"), 0), pool.Extern(0, 0));

  const char* const exprs[] = {"ext0*t + sin(ext1.d1)*x", "exp(-t)*ext1*ext0.d1",
                               "hypot(ext0, ext1) + t**2*y", "(t > 0.3 ? ext0 : t) * x"};
  std::mt19937 rng(4);
  for (const char* text : exprs) {
    const NodeId e = P(pool, text);
    const NodeId dt = pool.TimeDerivative(e);
    const NodeId dtt = pool.TimeDerivative(dt);
    for (int k = 0; k < 5; ++k) {
      const std::vector<double> x = RandomPoint(rng);
      const double t = std::uniform_real_distribution<double>(0.5, 2)(rng);
      const double h = 1e-5;
      ExpectClose(Eval(pool, dt, x, t),
                  (Eval(pool, e, x, t + h) - Eval(pool, e, x, t - h)) / (2 * h), text);
      ExpectClose(Eval(pool, dtt, x, t),
                  (Eval(pool, dt, x, t + h) - Eval(pool, dt, x, t - h)) / (2 * h), text);
    }
  }
}

TEST(Derivative, RandomExpressionsDifferentiateWithoutFailing) {
  Pool pool;
  testing::RandomExpr gen(pool, 5);
  for (int i = 0; i < 300; ++i) {
    const NodeId e = gen.Make(5);
    const std::vector<int> vars = pool.Variables(e);
    for (int v = 0; v < 4; ++v) {
      const NodeId d = pool.Derivative(e, v);
      if (!std::binary_search(vars.begin(), vars.end(), v)) {
        EXPECT_EQ(d, pool.Const(0));
      }
    }
    pool.TimeDerivative(e);
  }
}

TEST(Substitute, ReplacesVariablesAndSimplifies) {
  Pool pool;
  const NodeId e = P(pool, "x*y + sin(z) - x");
  const NodeId s = pool.Substitute(e, [&](int i) -> std::optional<NodeId> {
    if (i == 0) return pool.Const(1.0);
    return std::nullopt;
  });
  EXPECT_EQ(s, P(pool, "y + sin(z) - 1"));
  EXPECT_EQ(pool.Substitute(e, [](int) { return std::nullopt; }), e);
  const NodeId swapped = pool.Substitute(e, [&](int i) -> std::optional<NodeId> {
    if (i == 2) return P(pool, "t*2");
    return std::nullopt;
  });
  EXPECT_EQ(swapped, P(pool, "x*y + sin(2*t) - x"));
  EXPECT_EQ(pool.Substitute(P(pool, "x - y"),
                            [&](int i) -> std::optional<NodeId> {
                              return i == 1 ? std::optional<NodeId>(pool.Var(0)) : std::nullopt;
                            }),
            pool.Const(0));
}

}  // namespace
}  // namespace asgard::expr
