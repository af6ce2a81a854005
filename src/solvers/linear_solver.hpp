// LinearSolver: the direct solvers of the (unsymmetric) effective tangent over the free
// equations, behind one interface so that Newton and the Analysis need not know which:
//   analyze(pattern)  once per sparsity pattern (after the Assembler rebuilds it),
//   factorize(matrix) once per Newton iteration (same pattern as analysed),
//   solve(b)          in place, as often as needed with the last factorization.
// A singular tangent throws SingularMatrix, which Newton turns into a step cut.
//
// KluSolver is the general, always-correct implementation, over SuiteSparse KLU:
// analyze() runs KLU's symbolic ordering once per sparsity pattern. factorize() calls
// klu_factor the first time and klu_refactor (same pivots, cheaper) afterwards,
// falling back to a fresh pivoting factorization when the reused pivots leave a pivot
// below 1e-12 of the largest. Refactorizations and solves allocate no memory; only a fresh
// factorization allocates KLU's numeric factors. The structured RingSolver (ring_solver.hpp) is the fast one
// for a ring of nodes plus a border (the tire); docs/kernel.md says when to use which.
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <stdexcept>

namespace tirefe {

class SingularMatrix : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class LinearSolver {
 public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  LinearSolver() = default;
  virtual ~LinearSolver() = default;
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  /// Prepares for matrices of this sparsity pattern (compressed CSC; values unused).
  virtual void analyze(const Matrix& pattern) = 0;
  /// Factors a matrix of the analysed pattern; throws SingularMatrix.
  virtual void factorize(const Matrix& matrix) = 0;
  /// Solves A x = b in place (b enters, x leaves) with the last factorization.
  virtual void solve(Eigen::VectorXd& right_hand_side) const = 0;
  /// Solves A X = B for several columns in place.
  virtual void solve(Eigen::MatrixXd& right_hand_sides) const = 0;
  /// Short name for logs and benchmarks ("KLU", "ring").
  virtual const char* name() const = 0;

  /// Factorizations that searched for pivots afresh.
  int factorization_count() const { return fresh_factorizations_; }
  /// Factorizations that reused earlier pivots (KLU's refactor; 0 for a solver that always pivots).
  int refactorization_count() const { return refactorizations_; }

 protected:
  int fresh_factorizations_ = 0;
  int refactorizations_ = 0;
};

class KluSolver final : public LinearSolver {
 public:
  KluSolver();
  ~KluSolver() override;

  void analyze(const Matrix& pattern) override;
  void factorize(const Matrix& matrix) override;
  void solve(Eigen::VectorXd& right_hand_side) const override;
  void solve(Eigen::MatrixXd& right_hand_sides) const override;
  const char* name() const override { return "KLU"; }

 private:
  struct Klu;  // KLU's handles, kept out of this header
  std::unique_ptr<Klu> klu_;
  int size_ = 0;
};

}  // namespace tirefe
