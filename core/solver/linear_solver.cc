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

class DenseSolver final : public LinearSolver {
 public:
  DenseSolver(int n, const std::vector<int>& rows, const std::vector<int>& cols)
      : n_(n), rows_(rows), cols_(cols), m_(n, n), lu_(n), x_(n) {}
  bool Factor(const double* values) override {
    m_.setZero();
    for (size_t k = 0; k < rows_.size(); ++k) m_(rows_[k], cols_[k]) += values[k];
    lu_.compute(m_);
    const auto& u = lu_.matrixLU();
    double max_d = 0.0, min_d = INFINITY;
    for (int i = 0; i < n_; ++i) {
      const double d = std::abs(u(i, i));
      max_d = std::max(max_d, d);
      min_d = std::min(min_d, d);
    }
    return std::isfinite(max_d) && min_d > 1e-300 && min_d > 1e-15 * max_d;
  }
  void Solve(double* rhs) const override {
    Eigen::Map<Eigen::VectorXd> r(rhs, n_);
    x_.noalias() = lu_.solve(r);  // into preallocated storage
    r = x_;
  }

 private:
  int n_;
  std::vector<int> rows_, cols_;
  Eigen::MatrixXd m_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  mutable Eigen::VectorXd x_;
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
