// LinearSolver: sparse LU over SuiteSparse KLU for the (unsymmetric) effective tangent.
//
// analyze() runs KLU's symbolic ordering once per sparsity pattern. factorize() calls
// klu_factor the first time and klu_refactor (same pivots, cheaper) afterwards,
// falling back to a fresh pivoting factorization when the reused pivots give a poor
// reciprocal pivot growth. No heap allocation happens in factorize() or solve() after
// the first factorization.
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <stdexcept>

namespace tirefe {

class SingularMatrix : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class KluSolver {
 public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  KluSolver();
  ~KluSolver();
  KluSolver(const KluSolver&) = delete;
  KluSolver& operator=(const KluSolver&) = delete;

  void analyze(const Matrix& matrix);
  void factorize(const Matrix& matrix);
  /// Solves A x = b in place (b enters, x leaves).
  void solve(Eigen::VectorXd& right_hand_side) const;
  /// Solves A X = B for several columns in place.
  void solve(Eigen::MatrixXd& right_hand_sides) const;

  int factorization_count() const { return fresh_factorizations_; }
  int refactorization_count() const { return refactorizations_; }

 private:
  struct Klu;  // KLU's handles, kept out of this header
  std::unique_ptr<Klu> klu_;
  int size_ = 0;
  int fresh_factorizations_ = 0;
  int refactorizations_ = 0;
};

}  // namespace tirefe
