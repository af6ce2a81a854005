// Modal analysis: natural frequencies and mode shapes of a model linearised about a
// state (the committed state of an Analysis, loaded or not).
//
//   K phi = omega^2 M phi   over the free equations (prescribed DOFs stay fixed),
// with K = d f_int / du at the state, which includes the geometric stiffness of loaded
// elements and the load stiffness of follower loads, and M the mass matrix. Both are
// assembled with the element contract (element.hpp): K with tangent factors (1, 0, 0),
// M with (0, 0, 1); damping is left out. The problem is solved densely:
//  - K symmetric (to symmetry_tolerance relative): Cholesky M = L L^T and the symmetric
//    eigenproblem of L^-1 K L^-T; real spectrum, mass-normalised shapes;
//  - otherwise (friction, follower loads): eigenvalues of M^-1 K, real parts reported.
// A mode is rigid-body when the stiffness barely resists it,
//   |K phi|_inf <= rigid_body_tolerance * |K|_inf * |phi|_inf,
// and is reported with frequency 0. Round-off leaves rigid-body modes near 1e-14 on this
// scale while the softest elastic modes of slender beams (EA L^2 / EI = 1e6) sit near
// 1e-8, hence the default 1e-10. A threshold on omega^2 relative to the largest omega^2
// would not do: a small rotary inertia puts the top of the spectrum 1e10 or more above
// the bending modes. A negative omega^2 beyond that (a state past a
// stability limit) is reported as the negative frequency -sqrt(-omega^2) / (2 pi).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "core/model.hpp"
#include "core/state.hpp"

namespace tirefe {

class Analysis;

struct ModalSettings {
  double rigid_body_tolerance = 1e-10;  // tau above: |K phi| relative to |K| |phi|
  double symmetry_tolerance = 1e-10;   // max |K - K^T| relative to max |K|
};

struct ModalResult {
  std::vector<double> frequencies_hz;  // ascending by omega^2; 0 for rigid-body modes
  std::vector<bool> rigid_body;
  std::vector<double> eigenvalues;     // omega^2 [rad^2/s^2] as computed (real parts)
  Eigen::MatrixXd shapes;              // dof_count x n: phi^T M phi = 1, largest entry positive, 0 at prescribed DOFs
  Eigen::MatrixXd reactions;           // dof_count x n: K phi at prescribed DOFs, 0 at free DOFs
  bool symmetric = true;               // which solver ran
};

/// The lowest 'mode_count' modes of 'model' linearised about 'state' (missing trailing
/// DOFs are taken at rest). Leaves the element history as committed. Throws ModelError
/// when a free DOF has no mass.
ModalResult modal_analysis(Model& model, const State& state, int mode_count, const ModalSettings& settings = {});
/// The same about the analysis' committed state.
ModalResult modal_analysis(Analysis& analysis, int mode_count, const ModalSettings& settings = {});

}  // namespace tirefe
