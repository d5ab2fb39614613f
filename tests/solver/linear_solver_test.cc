// The Newton matrices' solvers (core/solver/linear_solver.h): the dense LU
// against the residual a backward-stable solve must leave, and against the
// sparse solver (KLU, an independent factorization).
#include "core/solver/linear_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace asgard::solver {
namespace {

// A matrix in the solvers' triplet form, every entry present and the
// diagonal given twice (duplicates are summed, as in the Newton matrix,
// whose pattern lists the identity's diagonal and then J's entries).
struct Triplets {
  int n = 0;
  std::vector<int> rows, cols;
  std::vector<double> values;
  std::vector<double> dense;  // row-major, the sums
};

Triplets Random(int n, std::mt19937& rng, double diagonal) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Triplets m;
  m.n = n;
  m.dense.assign(static_cast<size_t>(n) * n, 0.0);
  auto add = [&](int i, int j, double v) {
    m.rows.push_back(i), m.cols.push_back(j), m.values.push_back(v);
    m.dense[i * n + j] += v;
  };
  for (int i = 0; i < n; ++i) add(i, i, diagonal);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) add(i, j, u(rng));
  return m;
}

// ‖M x − b‖∞ / (‖M‖∞ ‖x‖∞): a backward-stable solve leaves a small multiple
// of n ε (partial pivoting's growth is modest on random matrices).
double RelativeResidual(const Triplets& m, const std::vector<double>& x,
                        const std::vector<double>& b) {
  double res = 0.0, norm_m = 0.0, norm_x = 0.0;
  for (int i = 0; i < m.n; ++i) {
    double r = -b[i], row = 0.0;
    for (int j = 0; j < m.n; ++j) {
      r += m.dense[i * m.n + j] * x[j];
      row += std::abs(m.dense[i * m.n + j]);
    }
    res = std::max(res, std::abs(r));
    norm_m = std::max(norm_m, row);
    norm_x = std::max(norm_x, std::abs(x[i]));
  }
  return res / (norm_m * norm_x);
}

std::vector<double> SolveWith(const Triplets& m, int dense_limit, const std::vector<double>& b) {
  auto solver = LinearSolver::Create(m.n, m.rows, m.cols, dense_limit);
  EXPECT_TRUE(solver->Factor(m.values.data()));
  std::vector<double> x = b;
  solver->Solve(x.data());
  return x;
}

TEST(DenseSolver, SolvesRandomSystemsBackwardStablyAndAgreesWithKlu) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double eps = std::numeric_limits<double>::epsilon();
  for (int n = 2; n <= 40; ++n) {
    // A zero added diagonal needs pivoting; a large one (a stiff Newton
    // matrix is I − γhJ, diagonally dominant at small h) does not.
    for (double diagonal : {0.0, 2.0 * n}) {
      const Triplets m = Random(n, rng, diagonal);
      std::vector<double> b(n);
      for (double& v : b) v = u(rng);
      const std::vector<double> dense = SolveWith(m, 40, b), klu = SolveWith(m, 0, b);
      EXPECT_LT(RelativeResidual(m, dense, b), 10 * n * eps) << n << " " << diagonal;
      // The two answers differ by at most cond(M) times the residuals; the
      // solvers' own estimate of cond is not at hand, so compare through
      // the residual of each (both backward stable) and the difference
      // relative to the solution.
      EXPECT_LT(RelativeResidual(m, klu, b), 10 * n * eps) << n << " " << diagonal;
      double diff = 0.0, size = 0.0;
      for (int i = 0; i < n; ++i) {
        diff = std::max(diff, std::abs(dense[i] - klu[i]));
        size = std::max(size, std::abs(klu[i]));
      }
      EXPECT_LT(diff, 1e-8 * size) << n << " " << diagonal;
    }
  }
}

TEST(DenseSolver, ARowSwapIsNeededAndTaken) {
  // [[0 1] [1 0]] has a zero first pivot: only a row swap solves it.
  const std::vector<int> rows = {0, 1, 0, 1}, cols = {0, 1, 1, 0};
  auto solver = LinearSolver::Create(2, rows, cols, 40);
  const double values[] = {0.0, 0.0, 1.0, 1.0};
  ASSERT_TRUE(solver->Factor(values));
  double r[] = {3.0, 5.0};
  solver->Solve(r);
  EXPECT_EQ(r[0], 5.0);
  EXPECT_EQ(r[1], 3.0);
}

TEST(DenseSolver, SingularOrNonFiniteMatricesAreRefused) {
  const std::vector<int> rows = {0, 1, 0, 1, 2, 2, 2}, cols = {0, 1, 1, 0, 0, 1, 2};
  auto solver = LinearSolver::Create(3, rows, cols, 40);
  // Rows 0 and 1 equal: singular.
  const double singular[] = {1.0, 2.0, 2.0, 1.0, 0.0, 0.0, 1.0};
  EXPECT_FALSE(solver->Factor(singular));
  // Rank 3 but a pivot 1e-17 of the largest: refused as numerically singular.
  const double tiny[] = {1.0, 1.0, 1.0, 1.0 + 1e-17, 0.0, 0.0, 1.0};
  EXPECT_FALSE(solver->Factor(tiny));
  const double nan[] = {1.0, 1.0, 0.0, 0.0, std::nan(""), 0.0, 1.0};
  EXPECT_FALSE(solver->Factor(nan));
  const double inf[] = {1.0, 1.0, 0.0, 0.0, 0.0, INFINITY, 1.0};
  EXPECT_FALSE(solver->Factor(inf));
  // Off the diagonal, where elimination would not carry it to a pivot.
  const double off[] = {1.0, 1.0, std::nan(""), 0.0, 0.0, 0.0, 1.0};
  EXPECT_FALSE(solver->Factor(off));
  // And then a regular one factors again.
  const double regular[] = {2.0, 3.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  ASSERT_TRUE(solver->Factor(regular));
  double r[] = {4.0, 9.0, 7.0};
  solver->Solve(r);
  EXPECT_DOUBLE_EQ(r[0], 2.0);
  EXPECT_DOUBLE_EQ(r[1], 3.0);
  EXPECT_DOUBLE_EQ(r[2], 7.0);
}

}  // namespace
}  // namespace asgard::solver
