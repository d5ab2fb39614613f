// Dense and sparse (KLU) factorizations behind LinearSolver.
#include "core/solver/linear_solver.h"

#include <klu.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace asgard::solver {
namespace {

class ScalarSolver final : public LinearSolver {
 public:
  explicit ScalarSolver(const std::vector<int>& rows) : count_(static_cast<int>(rows.size())) {}
  bool Factor(const double* values) override {
    pivot_ = 0.0;
    for (int k = 0; k < count_; ++k) pivot_ += values[k];
    return pivot_ != 0.0 && std::isfinite(pivot_);
  }
  void Solve(double* rhs) const override { rhs[0] /= pivot_; }

 private:
  int count_;
  double pivot_ = 1.0;
};

// Partial-pivot LU of a small dense matrix, row-major, with the rows
// swapped whole as they are chosen (so that P M = L U and a solve applies
// the swaps in order).  Plain loops: a component's matrix is 2–40 wide,
// where a general library's blocking and dynamic-size dispatch cost more
// than the arithmetic (a 2×2 solve: 360 instructions with Eigen's
// PartialPivLU, 97 with these loops, call included; callgrind).
class DenseSolver final : public LinearSolver {
 public:
  DenseSolver(int n, const std::vector<int>& rows, const std::vector<int>& cols)
      : n_(n), rows_(rows), cols_(cols), lu_(static_cast<size_t>(n) * n), pivot_(n) {}
  bool Factor(const double* values) override {
    const int n = n_;
    double* a = lu_.data();
    std::fill(lu_.begin(), lu_.end(), 0.0);
    bool finite = true;
    for (size_t k = 0; k < rows_.size(); ++k) {
      a[rows_[k] * n + cols_[k]] += values[k];
      finite = finite && std::isfinite(values[k]);
    }
    if (!finite) return false;
    double max_d = 0.0, min_d = INFINITY;
    for (int k = 0; k < n; ++k) {
      int p = k;
      for (int i = k + 1; i < n; ++i)
        if (std::abs(a[i * n + k]) > std::abs(a[p * n + k])) p = i;
      pivot_[k] = p;
      if (p != k) std::swap_ranges(a + k * n, a + (k + 1) * n, a + p * n);
      const double d = a[k * n + k];
      max_d = std::max(max_d, std::abs(d));
      min_d = std::min(min_d, std::abs(d));
      finite = finite && std::isfinite(d);
      if (d == 0.0 || !finite) continue;  // singular or not finite: reported below
      for (int i = k + 1; i < n; ++i) {
        const double l = a[i * n + k] / d;
        a[i * n + k] = l;
        if (l == 0.0) continue;
        for (int j = k + 1; j < n; ++j) a[i * n + j] -= l * a[k * n + j];
      }
    }
    return finite && min_d > 1e-300 && min_d > 1e-15 * max_d;
  }
  void Solve(double* r) const override {
    const int n = n_;
    const double* a = lu_.data();
    for (int k = 0; k < n; ++k)
      if (pivot_[k] != k) std::swap(r[k], r[pivot_[k]]);
    for (int i = 1; i < n; ++i) {
      double s = r[i];
      for (int j = 0; j < i; ++j) s -= a[i * n + j] * r[j];
      r[i] = s;
    }
    for (int i = n - 1; i >= 0; --i) {
      double s = r[i];
      for (int j = i + 1; j < n; ++j) s -= a[i * n + j] * r[j];
      r[i] = s / a[i * n + i];
    }
  }

 private:
  int n_;
  std::vector<int> rows_, cols_;
  std::vector<double> lu_;
  std::vector<int> pivot_;
};

class KluSolver final : public LinearSolver {
 public:
  KluSolver(int n, const std::vector<int>& rows, const std::vector<int>& cols) : n_(n) {
    klu_defaults(&common_);
    // Compressed-column pattern; `slot_` maps each triplet to its entry.
    std::vector<int> order(rows.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return cols[a] != cols[b] ? cols[a] < cols[b] : rows[a] < rows[b];
    });
    ap_.assign(n + 1, 0);
    slot_.assign(rows.size(), 0);
    int last_r = -1, last_c = -1;
    for (int k : order) {
      if (rows[k] != last_r || cols[k] != last_c) {
        ai_.push_back(rows[k]);
        ++ap_[cols[k] + 1];
        last_r = rows[k];
        last_c = cols[k];
      }
      slot_[k] = static_cast<int>(ai_.size()) - 1;
    }
    for (int c = 0; c < n; ++c) ap_[c + 1] += ap_[c];
    ax_.assign(ai_.size(), 0.0);
    symbolic_ = klu_analyze(n, ap_.data(), ai_.data(), &common_);
  }
  ~KluSolver() override {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
  }
  bool Factor(const double* values) override {
    if (!symbolic_) return false;
    std::fill(ax_.begin(), ax_.end(), 0.0);
    for (size_t k = 0; k < slot_.size(); ++k) ax_[slot_[k]] += values[k];
    // A fresh factorization every time (not klu_refactor): the pivot order
    // then depends only on this matrix, never on earlier factorizations, so
    // a truncated component that resumes recomputes bit for bit.  klu_rcond
    // is the O(n) ratio of U's extreme diagonal entries, not a condition
    // estimate.
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    numeric_ = klu_factor(ap_.data(), ai_.data(), ax_.data(), symbolic_, &common_);
    if (!numeric_ || common_.status != KLU_OK) return false;
    klu_rcond(symbolic_, numeric_, &common_);
    return common_.rcond > 1e-15;
  }
  void Solve(double* rhs) const override { klu_solve(symbolic_, numeric_, n_, 1, rhs, &common_); }

 private:
  int n_;
  std::vector<int> ap_, ai_, slot_;
  std::vector<double> ax_;
  mutable klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
};

}  // namespace

std::unique_ptr<LinearSolver> LinearSolver::Create(int n, const std::vector<int>& rows,
                                                   const std::vector<int>& cols, int dense_limit) {
  if (n == 1) return std::make_unique<ScalarSolver>(rows);
  if (n <= dense_limit) return std::make_unique<DenseSolver>(n, rows, cols);
  return std::make_unique<KluSolver>(n, rows, cols);
}

}  // namespace asgard::solver
