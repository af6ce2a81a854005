#include "solvers/linear_solver.hpp"

#include <klu.h>

#include <cmath>
#include <string>

namespace tirefe {

namespace {
// The old pivot order is kept while the smallest pivot of U stays above this fraction of
// the largest (klu_rcond: O(n), where the pivot growth klu_rgrowth costs as much as a
// quarter of the refactorisation); below it the matrix is factored afresh with new pivots.
constexpr double kMinimumPivotRatio = 1e-12;
}  // namespace

struct KluSolver::Klu {
  klu_common common;
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;

  Klu() {
    klu_defaults(&common);
    // No row scaling: it costs about a quarter of each refactorisation, and partial
    // pivoting within each column (as LAPACK's) is stable on the tangents without it.
    common.scale = 0;
  }
  ~Klu() {
    release_numeric();
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }
  void release_numeric() {
    if (numeric) klu_free_numeric(&numeric, &common);
  }
  void check_status(const char* what) const {
    if (common.status == KLU_SINGULAR)
      throw SingularMatrix(std::string(what) +
                           ": the tangent matrix is singular (a mechanism, an unconstrained "
                           "rigid-body motion, or a DOF no element stiffens; check the boundary conditions)");
    if (common.status < 0)
      throw std::runtime_error(std::string(what) + " failed (KLU status " + std::to_string(common.status) + ")");
  }
};

KluSolver::KluSolver() : klu_(std::make_unique<Klu>()) {}
KluSolver::~KluSolver() = default;

void KluSolver::analyze(const Matrix& pattern) {
  klu_->release_numeric();
  if (klu_->symbolic) klu_free_symbolic(&klu_->symbolic, &klu_->common);
  size_ = static_cast<int>(pattern.rows());
  klu_->symbolic = klu_analyze(size_, const_cast<int*>(pattern.outerIndexPtr()),
                               const_cast<int*>(pattern.innerIndexPtr()), &klu_->common);
  if (!klu_->symbolic) klu_->check_status("symbolic analysis");
}

void KluSolver::factorize(const Matrix& matrix) {
  if (!klu_->symbolic) analyze(matrix);
  int* column_starts = const_cast<int*>(matrix.outerIndexPtr());
  int* row_indices = const_cast<int*>(matrix.innerIndexPtr());
  double* values = const_cast<double*>(matrix.valuePtr());
  klu_common* common = &klu_->common;
  if (klu_->numeric) {
    const bool refactored = klu_refactor(column_starts, row_indices, values, klu_->symbolic, klu_->numeric, common) &&
                            klu_rcond(klu_->symbolic, klu_->numeric, common) && std::isfinite(common->rcond) &&
                            common->rcond > kMinimumPivotRatio;
    if (refactored) {
      ++refactorizations_;
      return;
    }
    klu_->release_numeric();
  }
  common->status = KLU_OK;
  klu_->numeric = klu_factor(column_starts, row_indices, values, klu_->symbolic, common);
  if (!klu_->numeric || common->status != KLU_OK) {
    klu_->release_numeric();
    klu_->check_status("LU factorization");
    throw SingularMatrix("LU factorization: the tangent matrix is singular");
  }
  ++fresh_factorizations_;
}

void KluSolver::solve(Eigen::VectorXd& right_hand_side) const {
  klu_solve(klu_->symbolic, klu_->numeric, size_, 1, right_hand_side.data(), &klu_->common);
  klu_->check_status("triangular solve");
}

void KluSolver::solve(Eigen::MatrixXd& right_hand_sides) const {
  klu_solve(klu_->symbolic, klu_->numeric, size_, static_cast<int>(right_hand_sides.cols()), right_hand_sides.data(),
            &klu_->common);
  klu_->check_status("triangular solve");
}

}  // namespace tirefe
