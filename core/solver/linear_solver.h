// Linear solves for Newton's method: M Δ = r with M = I − a J.
//
//   n == 1        a division
//   n ≤ dense     partial-pivot LU in plain loops (small components: most
//                 of them)
//   n > dense     SuiteSparse KLU; the sparsity pattern is fixed per
//                 equation mode, so the symbolic analysis (AMD ordering,
//                 block triangular form) is done once and only the numeric
//                 factorization is repeated
//
// The matrix is given as triplets (row, col, value) in a fixed pattern order
// that includes every diagonal entry.
#pragma once

#include <memory>
#include <vector>

namespace asgard::solver {

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  // Factors the matrix whose entries, in pattern order, are `values`.
  // Returns false when the matrix is singular.
  virtual bool Factor(const double* values) = 0;
  // Solves in place.
  virtual void Solve(double* rhs) const = 0;

  // Picks the implementation for an n×n matrix with the given pattern.
  static std::unique_ptr<LinearSolver> Create(int n, const std::vector<int>& rows,
                                              const std::vector<int>& cols, int dense_limit);
};

}  // namespace asgard::solver
