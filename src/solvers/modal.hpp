// Modal analysis: natural frequencies, damping and mode shapes of a model linearised
// about a state (the committed state of an Analysis: loaded or not, at rest or rolling).
//
// About the state, with the prescribed DOFs held, the free equations are
//   M q'' + C q' + K q = 0,
// K = d f_int / du (geometric stiffness of loaded elements, load stiffness of follower
// loads, contact penalty springs), C = d f_damp / dv, M the mass matrix, each assembled with
// the element contract (element.hpp) and one tangent factor: K with cK = 1, C with cC = 1,
// M with cM = 1. Everything is dense: fine up to a few thousand DOFs.
//
// Undamped modes (modal_analysis): K phi = omega^2 M phi.
//  - K symmetric (to symmetry_tolerance relative): Cholesky M = L L^T and the symmetric
//    eigenproblem of L^-1 K L^-T; real spectrum, mass-normalised shapes.
//  - Otherwise (friction, follower loads): eigenvalues of M^-1 K, real parts reported. A
//    complex pair mu +- i nu (typically a degenerate pair that the unsymmetric part splits)
//    spans a real invariant plane: its two modes are the real and imaginary parts of the
//    eigenvector, M-orthonormalised, both at omega^2 = mu.
//  A negative omega^2 (a state past a stability limit) is reported as the negative
//  frequency -sqrt(-omega^2) / (2 pi).
//
// Damped modes (damped_modal_analysis): the quadratic eigenproblem
//   (lambda^2 M + lambda C + K) phi = 0,
// through its first-order form: with y = L^T phi, K~ = L^-1 K L^-T, C~ = L^-1 C L^-T and
// gamma = sqrt(|K~|_inf) to balance the blocks,
//   [ 0          gamma I ] [ y              ]            [ y              ]
//   [ -K~ / gamma  -C~   ] [ lambda y / gamma ] = lambda [ lambda y / gamma ],
// a real 2n x 2n matrix (Eigen's EigenSolver) whose complex roots come in conjugate
// pairs. One member of each pair (Im lambda > 0) is a mode, and so is every real root
// (overdamped motion). Per mode: damped frequency Im lambda / 2 pi, natural frequency
// |lambda| / 2 pi, damping ratio zeta = -Re lambda / |lambda|, shape phi with
// phi^H M phi = 1 and its largest entry real and positive, ascending in |lambda|. A real
// root has frequency 0 and zeta = 1 (-1 when it grows); the two real roots of an
// overdamped single DOF multiply to omega_n^2 and add up to -2 zeta omega_n, zeta > 1.
// The dense form resolves lambda to about eps |K~| / |lambda| (a companion form's
// conditioning): 4e-6 relative for a beam whose shear stiffness is 1e8 above its axial one.
// Above a first-order size of 400, where it takes seconds (10 s for the 1000 x 1000 of the
// tread-layer tire), the modes of lowest |lambda| come from shift-invert block Krylov at 0
// instead: with z = [phi; lambda phi],
//   S [u; v] = [-K^-1 (M v + C u); u],   S z = z / lambda,
// maps them onto the largest eigenvalues of S. In energy coordinates q = [R u; L^T v],
// R^T R = (K + K^T) / 2 (plus the least multiple of M that makes it definite: a sticking
// patch can make the symmetric part indefinite), S is nearly normal (the raw form gives
// spurious Ritz values); a
// block Krylov space (block size 4: up to 4 copies of a multiple root) and Rayleigh-Ritz
// give the roots, accepted when the wanted ones and two beyond have a backward error
//   |P(lambda) phi| / ((|K| + |lambda| |C| + |lambda|^2 |M|) |phi|) <= 1e-10
// (they reach 1e-15; the dense roots agree to 1e-9). A singular K (rigid-body modes) or no
// convergence within 20 mode_count + 100 vectors leaves the problem to the dense solver.
// The support reaction of a mode is (K + lambda C + lambda^2 M)_pf phi at the prescribed
// DOFs: the complex amplitude of the force it puts on a held axle.
//
// Turning frame (spin_rate Omega about z): with x = R(Omega t) y, a node's translations
// see x'' = R (y'' + 2 Omega J y' - Omega^2 y), J = [0 -1; 1 0], so about a state of the
// tire rolling at Omega (its centrifugal pre-stress already in K) the free equations in
// the frame turning with the tire are
//   M q'' + (C + G) q' + (K - Omega^2 J^T M_t J) q = 0,   G = Omega (M_t J + J M_t),
// M_t the mass on the in-plane translations, J acting on every node's (u_x, u_y): the
// Coriolis (gyroscopic, skew) matrix and the centrifugal softening. For a mass isotropic
// in the plane (every element here: point masses, the tread layer, the beams' consistent
// rhoA) G = 2 Omega (M_node (x) J) and J^T M_t J = M_t. Rotational DOFs get neither term:
// a rotation rate theta' + Omega has no Coriolis term. The dampers act on deformation
// rates (sidewall and tread layer against the rim's and the belt node's own turning, beam
// curvature rate), so in the turning frame they give C and no stiffness: the dependence
// on u of their fixed-frame force at the rolling velocity (the terms a kernel weights with
// wC in its tangent) cancels against C Omega J, and both are left out.
// Approximations: the contact springs of the current patch are frozen in the turning frame
// (the real patch stays put while the tire turns through it) and the state is taken as
// steady there. Frequencies are those of the turning frame: a mode with n waves round the
// tire at omega_r appears in the fixed frame at omega_r + n Omega (forward wave) or
// |omega_r - n Omega| (backward wave); n = 0 modes are the same in both. Forces and
// shapes are in the axes of the instant of linearisation.
//
// Rigid-body modes are motions the stiffness (K - Omega^2 J^T M_t J) barely resists,
//   |phi^H K phi| <= rigid_body_tolerance * |phi|^T |K| |phi|   (|.| entrywise),
// the Rayleigh quotient against the mode's own stiffness scale, whatever the largest entry
// of K (a beam whose shear stiffness GA is 1e8 above its axial EA keeps its axial mode).
// They are reported at frequency 0 (damping ratio 0). The quotient is quadratic in the
// round-off of the shape: true rigid-body modes sit near 1e-18, while the softest elastic
// modes in the tests sit at 1e-3 (a bar's axial mode), 7e-8 (ring bending, EA R^2 / EI =
// 1e5), 7e-9 (a pinned beam, EA L^2 / EI = 1e6) and 7e-11 (bending of a beam with GA = 1e8
// EA, whose energy is a cancellation of shear terms), hence the default 1e-13. With a spin
// the damped analysis also applies the test to K alone: the free translations turn at Omega
// in that frame (K does not resist them) and the free rotation's load stiffness is balanced
// by the hoop tension (K - Omega^2 J^T M_t J does not resist it). A rigid-body DOF without
// damping is a double root with one shape, which round-off splits in two; the real and
// imaginary parts of the rigid-body shapes are reported as an M-orthonormal basis, each
// once (a circular translation gives both translations).
// For the undamped symmetric problem omega^2 is the Rayleigh quotient of the computed shape
// (about 1e-11 relative where the solver's eigenvalue is good to eps omega_max^2 only).
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "core/model.hpp"
#include "core/state.hpp"

namespace tirefe {

class Analysis;

struct ModalSettings {
  double rigid_body_tolerance = 1e-13;  // on phi^H K phi relative to |phi|^T |K| |phi|
  double symmetry_tolerance = 1e-10;    // max |K - K^T| relative to max |K|
};

struct ModalResult {
  std::vector<double> frequencies_hz;  // ascending by omega^2; 0 for rigid-body modes
  std::vector<bool> rigid_body;
  std::vector<double> eigenvalues;  // omega^2 [rad^2/s^2]: Rayleigh quotients (symmetric K), real parts (unsymmetric)
  Eigen::MatrixXd shapes;           // dof_count x n: phi^T M phi = 1, largest entry positive, 0 at prescribed DOFs
  Eigen::MatrixXd reactions;        // dof_count x n: K phi at prescribed DOFs, 0 at free DOFs
  bool symmetric = true;            // which solver ran
};

/// How the quadratic eigenproblem is solved (header): densely, by shift-invert block
/// Krylov (falling back to dense when it does not converge), or densely up to a first-order
/// size of 400 and by Krylov above.
enum class DampedSolver { Automatic, Dense, ShiftInvert };

struct DampedModalSettings {
  bool damping = true;     // include C (false: the gyroscopic modes of the undamped model)
  double spin_rate = 0.0;  // Omega [rad/s] about z: modes in the frame turning with the tire
  double rigid_body_tolerance = 1e-13;
  DampedSolver solver = DampedSolver::Automatic;
};

struct DampedModalResult {
  double spin_rate = 0.0;                      // Omega of the frame [rad/s]
  std::vector<std::complex<double>> roots;     // lambda [1/s], Im lambda >= 0, ascending in |lambda|
  std::vector<double> frequencies_hz;          // Im lambda / 2 pi; 0 for real roots and rigid-body modes
  std::vector<double> natural_frequencies_hz;  // |lambda| / 2 pi; 0 for rigid-body modes
  std::vector<double> damping_ratios;          // -Re lambda / |lambda|; 0 for rigid-body modes
  std::vector<bool> rigid_body;
  Eigen::MatrixXcd shapes;     // dof_count x n: phi^H M phi = 1, largest entry real positive, 0 at prescribed DOFs
  Eigen::MatrixXcd reactions;  // dof_count x n: the support reaction at prescribed DOFs, 0 at free DOFs
  bool shift_invert = false;   // which solver gave the roots
};

/// The lowest 'mode_count' undamped modes of 'model' linearised about 'state' (missing
/// trailing DOFs are taken at rest). Leaves the element history as committed. Throws
/// ModelError when a free DOF has no mass.
ModalResult modal_analysis(Model& model, const State& state, int mode_count, const ModalSettings& settings = {});
/// The same about the analysis' committed state.
ModalResult modal_analysis(Analysis& analysis, int mode_count, const ModalSettings& settings = {});

/// The 'mode_count' damped modes of lowest |lambda| (and, with a spin rate, in the turning
/// frame), as modal_analysis. Throws ModelError also when a spin rate meets a node with
/// one translation held and the other free.
DampedModalResult damped_modal_analysis(Model& model, const State& state, int mode_count,
                                        const DampedModalSettings& settings = {});
DampedModalResult damped_modal_analysis(Analysis& analysis, int mode_count, const DampedModalSettings& settings = {});

}  // namespace tirefe
