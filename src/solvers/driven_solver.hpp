// DrivenDofSolver: Newton's linear solves with some free equations driven from outside
// (the spindle of a tire whose motion a vehicle prescribes), and the Schur complement
// of the tangent onto those equations (docs/model.md section 6, eqs. 25-27).
//
// Partition the effective tangent A over the free equations into the driven equations
// s and all others u. Newton then solves A_uu x_u = b_u with x_s = 0, and the driven
// equations' residuals are the forces that hold them (the spindle force, eqs. 28-30).
// Both come from the factors of the whole A, which any LinearSolver provides: with
// the |s| columns Z = A^-1 [0; I] (one solve with the factors),
//     Z_s = H^-1,  H = A_ss - A_su A_uu^-1 A_us          (eq. 27, the spindle Jacobian)
//     Z_u = -A_uu^-1 A_us H^-1,
// and a solve of A [y_u; y_s] = [b_u; 0] gives A_uu^-1 b_u = y_u - Z_u H y_s.
//
// With a RingSolver whose border holds the driven equations (the spindle) the factors
// give the border Schur complement H_b directly (over the driven equations s and the
// border's free ones f, a free spin's rz), so no columns are solved: per iteration,
//     H   = H_ss - H_sf H_ff^-1 H_fs,
//     x_u = A^-1 [b_u; b_s + delta]  with  delta = H_sf H_ff^-1 y_f - y_s,
// y_b = the condensed border right-hand side of [b_u; 0] (one forward sweep): the delta
// makes the border solution [0; H_ff^-1 y_f], i.e. x_s = 0, and the rest follows. The
// delta changes y_b alone, so the solve goes on from that sweep with y_s + delta =
// H_sf H_ff^-1 y_f (RingSolver::solve_condensed) rather than sweeping [b_u; delta] again.
// Newton's own factorisations need no H: on the ring route they factor A_uu alone, with
// a RingSolver that holds the driven equations (RingSolver::holding), whose chain carries
// the free border equations only (a free spin: 4 columns instead of 6); H and the
// solves after it come from factorize_with_schur().
// A must be regular (a dynamic tangent is: the driven node has mass).
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <vector>

#include "solvers/linear_solver.hpp"
#include "solvers/ring_solver.hpp"

namespace tirefe {

class DrivenDofSolver final : public LinearSolver {
 public:
  /// At most one node's DOFs are driven, so H lives on the stack.
  static constexpr int kMaxDriven = 3;
  using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxDriven, kMaxDriven>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDriven, 1>;

  /// 'inner' factors the whole tangent and must outlive this solver; 'driven' are the
  /// equation numbers held at their current values.
  DrivenDofSolver(LinearSolver& inner, std::vector<int> driven);

  void analyze(const Matrix& pattern) override;
  /// Newton's factorisation: enough for solve(), not for schur_complement().
  void factorize(const Matrix& matrix) override;
  /// The factorisation for solve() and schur_complement().
  void factorize_with_schur(const Matrix& matrix);
  /// x_u = A_uu^-1 b_u, x_s = 0, with the last factorisation of either kind.
  void solve(Eigen::VectorXd& right_hand_side) const override;
  void solve(Eigen::MatrixXd& right_hand_sides) const override;
  const char* name() const override { return inner_.name(); }

  /// H = A_ss - A_su A_uu^-1 A_us over the driven equations, in their given order, of the
  /// last factorized matrix; std::logic_error when that factorisation did not compute it
  /// (factorize() on the ring route).
  const SmallMatrix& schur_complement() const;

  /// The ring route's tangent assembled straight into the held RingSolver's storage (its
  /// held rows and columns kept beside it): that solver, or null on the general route.
  RingSolver* assembly_solver() { return held_.get(); }
  /// That storage, cleared for an assembly (every factorisation gone).
  double* begin_assembly();
  /// Newton's factorisation of the assembled tangent.
  void factorize_assembled();
  /// factorize_with_schur() of the assembled tangent: H = A_ss - A_su A_uu^-1 A_us from
  /// Newton's factors of A_uu (made here if not yet) and the held rows and columns, one
  /// solve per driven equation. Once per assembly.
  void factorize_with_schur_assembled();
  /// product = A(:, s) x_s for the assembled tangent: its driven columns times the driven
  /// entries of 'x' (over every equation).
  void multiply_driven_columns(const Eigen::VectorXd& x, Eigen::VectorXd& product) const;

 private:
  /// Maps the driven equations into the RingSolver's border; false if they do not all lie there.
  bool analyze_ring_route();
  void factorize_on_ring(const Matrix& matrix);
  void solve_on_ring(Eigen::VectorXd& right_hand_side) const;

  LinearSolver& inner_;
  std::vector<int> driven_;
  // The ring route: inner_ as a RingSolver whose border holds every driven equation; the
  // driven and free equations' places in its border Schur complement H_b.
  RingSolver* ring_ = nullptr;
  std::unique_ptr<RingSolver> held_;  // the same ring holding the driven equations: Newton's
  bool held_factors_ = false;         // the last factorisation is held_'s
  bool schur_current_ = false;        // schur_ is of the last factorisation
  std::vector<int> driven_in_border_, free_in_border_;
  SmallMatrix free_inverse_;      // H_ff^-1
  SmallMatrix driven_from_free_;  // H_sf H_ff^-1
  mutable Eigen::VectorXd border_rhs_;
  mutable SmallVector free_rhs_;
  Eigen::MatrixXd columns_;   // Z = A^-1 [0; I]
  Eigen::MatrixXd coupling_;  // Z_u H = -A_uu^-1 A_us (rows over every equation, 0 at s)
  SmallMatrix schur_;         // H
  mutable SmallVector driven_part_;
};

}  // namespace tirefe
