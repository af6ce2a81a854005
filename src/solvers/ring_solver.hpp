// RingSolver: a direct solver that exploits the tire's structure, and the spindle-force
// condensation (docs/model.md section 6, eqs. 25-30) from the same factorization.
//
// Structure. The free equations belong to nodes; a node's equations (ux, uy, rz, fewer
// if some are prescribed) form its block. The ring nodes r_0 ... r_{n-1}, in ring order,
// are each coupled to their two ring neighbours only (r_{n-1} to r_0 closes the ring);
// the border nodes (the spindle: condensed, numbered last by the DofMap) may be coupled
// to everything. analyze() verifies that the sparsity pattern has exactly this form and
// throws ModelError otherwise, so a model that does not fit fails loudly and never gets
// wrong answers. Every free equation must belong to a ring, a border or a satellite node.
//
// Satellites. A node in neither list whose equations couple only to themselves and to one
// ring node, its host (a tread layer's contact node hangs on its belt node so), is found
// by analyze() from the pattern and eliminated first, by static condensation into its
// host's diagonal block: D_h -= A(h,s) D_s^-1 A(s,h). Forward, z_s = D_s^-1 y_s and
// y_h -= A(h,s) z_s; back, x_s = z_s - (D_s^-1 A(s,h)) x_h. A node in neither list that
// couples to two ring nodes, to the border or to another satellite is refused.
//
// Padding. Every ring and satellite block is padded to 3x3: a prescribed DOF's slot gets
// a 1 on the diagonal and zeros elsewhere (right-hand side 0), an exact decoupled identity,
// so all ring arithmetic runs on fixed-size 3x3 blocks whatever the boundary conditions.
// The border holds its free equations only (a dead axle's spindle: rz alone), so the
// products along the chain skip the columns that padding would keep at zero; a satellite
// whose rotation alone is padding (a contact node) is condensed through its 2x2
// translation block, the same numbers as through the padded 3x3.

// Ordering. The chain c_k = r_{k+1}, k = 0..m-1 (m = n-1), comes first; the first ring
// node r_0 joins the border in the "extended border" E = [r_0, border] (width
// e = 3 + border equations). The ring's closing couplings r_1-r_0 and r_{n-1}-r_0 are
// then border couplings, and what is left of the ring is block tridiagonal:
//
//         [ T  W ]   T: diagonal blocks D_k, U_k = A(c_k, c_{k+1}), L_k = A(c_{k+1}, c_k)
//     A = [ V  S ]   W = A(chain, E), V = A(E, chain), S = A(E, E)
//
// Factorization: block Gaussian elimination in the order c_0 .. c_{m-1}, r_0, border,
// with partial pivoting inside each diagonal block (none across blocks: the blocks of
// the effective tangent dominate their couplings; the tests check against KLU):
//
//     for k = 0 .. m-1:
//         D~_k = D_k - L_{k-1} X_{k-1},   W~_k = W_k - L_{k-1} Y_{k-1},   V~_k = V_k - V~_{k-1} X_{k-1}
//         LU-factor D~_k;   X_k = D~_k^-1 U_k,   Y_k = D~_k^-1 W~_k;   S -= V~_k Y_k
//
// after which S is the Schur complement of the chain onto E. Eliminating r_0 from it
// (LU of S_00, S_0b <- S_00^-1 S_0b) leaves the Schur complement onto the border,
//
//     H = S_bb - S_b0 S_00^-1 S_0b = K_bb - K_bu K_uu^-1 K_ub          (eq. 27)
//
// with u = every ring equation and b = the border equations: the condensed spindle
// tangent. factorize_interior() stops here (the partial factorization of eq. 26);
// factorize() also LU-factors H with partial pivoting, for full solves.
//
// Solve, for y = the right-hand side:
//     forward   z_k = D~_k^-1 (y_k - L_{k-1} z_{k-1}),  y_E -= V~_k z_k          (k = 0..m-1)
//               z_0 = S_00^-1 y_0,  y_b -= S_b0 z_0    -> y_b = f_b = R_b - K_bu K_uu^-1 R_u  (eqs. 28-30)
//     border    x_b = H^-1 y_b
//     back      x_0 = z_0 - (S_00^-1 S_0b) x_b,   x_k = z_k - X_k x_{k+1} - Y_k x_E  (k = m-1..0)
//
// Cost: about 350 multiply-adds per ring node with a spindle free (6 border columns), 250
// on a dead axle (4), and about 80 per satellite (45 for a contact node's translations),
// no sparse bookkeeping: 11-12 us to factor the 100-element tire with its tread layer on a
// dead axle, 3 us to solve (bench_tire_iteration).
//
// A pivot not above kPivotTolerance times the largest entry of its row in the assembled
// matrix throws SingularMatrix, which Newton turns into a step cut. Rows are compared
// with themselves because translation and rotation rows differ by orders of magnitude.
// Round-off leaves the pivots of a singular tangent near 1e-13 of their rows (the
// inflated tire free on its spindle, quasi-statically: H is 2e-13 of K_bb), while the
// smallest regular pivots are those of slender free ends: a cantilever's tip pivot is
// 3 / (N EA L^2 / EI) of its row (1.5e-8 for N = 20 elements, EA L^2 / EI = 1e7);
// hence 1e-11. This is stricter than KLU, which stops only at exact zeros: a quasi-static
// tangent with a rigid-body mode is refused here, where KLU returns a solution with an
// arbitrary rigid-body part.
//
// Held equations. holding() gives a solver that takes some border equations out of the system (a driven spindle
// in a DrivenDofSolver's Newton iterations): their rows and columns are skipped, their
// solution is zero, and the border and its width shrink by them, so the chain carries
// fewer border columns (a free spin's rz alone: 4 instead of 6). H is then the Schur
// complement onto the free border equations only. The held rows and columns of the matrix
// are kept beside the factors (held_row(), held_column()), so that a DrivenDofSolver can
// condense onto them from an assembly into this solver's storage.
//
// factorize() and solve() allocate nothing: every buffer is sized by analyze(). solve()
// uses one internal work vector, so one solver must not solve from two threads at once.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "core/dof_map.hpp"
#include "solvers/linear_solver.hpp"

namespace tirefe {

class RingSolver final : public LinearSolver {
 public:
  /// Pivots below this fraction of their row's largest assembled entry count as zero.
  static constexpr double kPivotTolerance = 1e-11;
  /// A row interchange of a block's LU factorisation and the reciprocal of its pivot.
  struct Pivot {
    int row = 0;
    double inverse = 0.0;
  };

  /// ring_nodes in ring order (each coupled to the next, the last to the first);
  /// border_nodes coupled to anything (the spindle); any other node with equations must be
  /// a satellite of one ring node (found by analyze()). The DofMap is read by analyze(), so
  /// the equations may be renumbered after construction; it must outlive the solver.
  RingSolver(const DofMap& dofs, std::vector<int> ring_nodes, std::vector<int> border_nodes);

  /// A solver of the same ring and border that holds these border equations (above);
  /// analyze() throws ModelError for one that is not a border equation.
  std::unique_ptr<RingSolver> holding(std::vector<int> held_equations) const;

  /// Maps the equations to the ring, border and satellite blocks and verifies that every
  /// nonzero of the pattern lies within a node's block, between ring neighbours, between a
  /// satellite and its host, or in a border row or column; throws ModelError naming the
  /// first equation or coupling that does not fit.
  void analyze(const Matrix& pattern) override;
  /// factorize_interior() and the LU factorization of H: ready for solve().
  void factorize(const Matrix& matrix) override;
  void solve(Eigen::VectorXd& right_hand_side) const override;
  void solve(Eigen::MatrixXd& right_hand_sides) const override;
  const char* name() const override { return "ring"; }

  /// The partial factorization (docs/model.md eq. 26): eliminates every ring equation and
  /// forms the border Schur complement H, without factoring H (which may be singular,
  /// e.g. the stiffness of a free tire on its spindle, quasi-statically). Enough for
  /// border_schur_complement() and condense(), not for solve(). Throws SingularMatrix
  /// when K_uu (the ring with the border held) is singular.
  void factorize_interior(const Matrix& matrix);

  /// The tangent assembled straight into the solver's own storage, skipping the sparse
  /// matrix's values (Assembler::bind_solver_layout, docs/kernel.md): where each stored
  /// entry of the analysed pattern, in the pattern's order, lands in that storage.
  const std::vector<int>& entry_destinations() const { return destination_; }
  /// The storage, cleared for an assembly into it; the factors it held are gone.
  double* begin_assembly();
  /// factorize() of the matrix assembled into begin_assembly()'s storage, the same numbers.
  void factorize_assembled();
  /// A held equation's column and row of the last matrix given or assembled, over every
  /// equation in equation order (the column's entries in held rows and the row's in
  /// other equations' columns; the rest zero): what the factors leave out. Kept by the
  /// factorisation, until the next begin_assembly() or factorize().
  const double* held_column(int equation) const;
  const double* held_row(int equation) const;

  /// H = K_bb - K_bu K_uu^-1 K_ub (eq. 27) over the border equations, in the order of
  /// border_equations(); for the effective tangent cK K + cC C + cM M it is the spindle
  /// force Jacobian of eq. 24. Valid after factorize() or factorize_interior().
  const Eigen::MatrixXd& border_schur_complement() const { return border_schur_; }

  /// The condensed border right-hand side f_b = R_b - K_bu K_uu^-1 R_u (eqs. 28-30) of a
  /// right-hand side R over all equations: one forward sweep with the factors.
  void condense(const Eigen::VectorXd& right_hand_side, Eigen::VectorXd& condensed_border_rhs) const;

  /// Finishes the solve of the right-hand side last given to condense(), with its condensed
  /// border right-hand side as the caller changed it (border_equations() order): the border
  /// solve and the back substitution into 'solution' (all equations), no second forward
  /// sweep. A host that holds border equations (DrivenDofSolver) changes f_b so. Needs
  /// factorize(); a solve() in between is refused.
  void solve_condensed(const Eigen::VectorXd& condensed_border_rhs, Eigen::VectorXd& solution) const;

  /// Equation numbers of H's rows and columns and of f_b's entries: the border nodes in
  /// the given order, their free components ux, uy, rz in order (prescribed and held ones skipped).
  /// With the spindle condensed these are the last equations (DofMap numbers condensed nodes last).
  const std::vector<int>& border_equations() const { return border_equations_; }
  int border_size() const { return static_cast<int>(border_equations_.size()); }

 private:
  void clear_blocks();  // the factors gone, every block zero
  void eliminate_interior();
  void factor_border();
  void eliminate_satellites();
  void forward_satellites(double* padded) const;
  void back_satellites(double* padded) const;
  void find_hosts(const Matrix& pattern);
  template <int Width>
  void eliminate_chain();
  void eliminate_first_ring_node();
  template <int Width>
  void forward(double* padded) const;
  template <int Width>
  void back(double* padded) const;
  void solve_in_place(double* values) const;
  void solve_border_and_back(double* values) const;
  void check_size(Eigen::Index size) const;
  void gather(const double* values) const;
  template <class Work>
  void with_width(Work&& work) const;

  // Offsets into blocks_ of chain node k's blocks and of S.
  int diagonal_offset(int k) const { return 9 * k; }
  int upper_offset(int k) const { return 9 * (chain_ + k); }
  int lower_offset(int k) const { return 9 * (2 * chain_ + k); }
  int border_column_offset(int k) const { return 27 * chain_ + 3 * width_ * k; }
  int border_row_offset(int k) const { return 27 * chain_ + 3 * width_ * (chain_ + k); }
  int border_block_offset() const { return 27 * chain_ + 6 * width_ * chain_; }
  // Satellite i's blocks: D_s, A(s,h) (then D_s^-1 A(s,h)), A(h,s).
  int satellite_offset(int i) const { return border_block_offset() + width_ * width_ + 27 * i; }
  // After the satellites' blocks: the held equations' columns, then their rows, each over every equation.
  int held_column_offset(int h) const { return held_coupling_offset_ + h * equation_count(); }
  int held_row_offset(int h) const {
    return held_coupling_offset_ + (static_cast<int>(held_.size()) + h) * equation_count();
  }
  int equation_count() const { return static_cast<int>(position_of_equation_.size()); }
  int held_index(int equation) const;  // its place in held_
  int satellite_position(int i) const { return satellite_start_ + 3 * i; }
  // The host's diagonal block: D_k in the chain, or S's top-left corner for r_0.
  Eigen::Map<Eigen::Matrix3d, 0, Eigen::OuterStride<>> host_block(int i);

  int entry_offset(int row_position, int column_position) const;
  std::string describe_node(int position) const;
  [[noreturn]] void throw_singular(int position, double pivot, double scale) const;
  void check_same_pattern(const Matrix& matrix) const;

  const DofMap& dofs_;
  std::vector<int> ring_nodes_, border_nodes_;
  std::vector<int> held_;  // equations taken out (hold())

  // From analyze(). Padded positions: chain node k at 3k + c, r_0 at 3m + c, border
  // equation j at 3m + 3 + j, satellite i at 3m + 3 ceil(e / 3) + 3i + c; held equations
  // at padded_size_, out of the factors (their entries land in the held rows and columns
  // after the satellites' blocks).
  int chain_ = 0;            // m = ring nodes - 1
  int width_ = 0;            // e = 3 + border equations
  int satellite_start_ = 0;  // 3m + e rounded up to a multiple of 3
  int padded_size_ = 0;
  int held_coupling_offset_ = 0;  // in blocks_, after the satellites' blocks
  std::vector<int> satellite_nodes_;
  std::vector<int> satellite_hosts_;     // padded position of each satellite's host (3k or 3m)
  std::vector<bool> planar_satellites_;  // its rotation padding, its translations free (a contact node)
  std::vector<int> position_of_equation_;
  std::vector<int> padding_;                        // padded positions without an equation: identity rows
  std::vector<int> padding_offsets_;                // their diagonal entries' offsets in blocks_
  std::vector<int> destination_;                    // offset in blocks_ of each stored entry of the pattern
  std::vector<int> row_position_;                   // and the padded position of its row
  std::vector<int> row_starts_, row_offsets_;       // the destinations of each padded row's entries
  std::vector<int> pattern_starts_, pattern_rows_;  // the analysed pattern, to check factorize()'s
  std::vector<int> border_equations_;

  // From factorize().
  std::vector<double> blocks_;     // D, U (then X), L, W (then Y), V, S (then its factors), held rows and columns
  std::vector<double> row_scale_;  // largest |entry| of each padded row (permuted with the pivots)
  std::vector<Pivot> pivots_;      // 3 per chain node, 3 for r_0, H's, 3 per satellite
  Eigen::MatrixXd border_schur_;
  mutable Eigen::VectorXd work_;    // a padded right-hand side
  mutable bool condensed_ = false;  // work_ holds condense()'s forward sweep
  bool assembly_open_ = false;      // begin_assembly() gave the storage to an assembly not yet factored
  bool interior_factored_ = false;
  bool border_factored_ = false;
};

}  // namespace tirefe
