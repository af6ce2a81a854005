// EnergyBalance: the work-energy bookkeeping of one analysis (docs/dynamics.md), once per
// accepted step n -> n+1:
//   W_{n+1} = W_n + (F_n + F_{n+1})/2 . (u_{n+1} - u_n) + (R_n + R_{n+1})/2 . (u_{n+1} - u_n)|held,
//   dissipated = (T_0 + U_0) + W - T - U,
// with F the nodal loads, R the reactions at the held (prescribed and driven) DOFs,
// T = v.M v/2 and U the blocks' stored energy. For a linear model under Newmark average
// acceleration the balance is exact, so 'dissipated' is the dashpots' work alone;
// otherwise it also holds the integrator's numerical dissipation (HHT) and the
// trapezoidal rule's error on nonlinear forces.
//
// The balance is also closed term by term, so that energy a scheme creates or loses shows:
//   surface_work        what moving surfaces did on the structure through the contacts,
//                       and contact_dissipated, what friction and the contacts' dashpots
//                       took: the contacts' own accounts (ElementEnergy::supplied, dissipated);
//   damping             the dashpots' work, (C v_n + C v_{n+1})/2 . (u_{n+1} - u_n), C v the
//                       forces the damping factors give of the blocks with dashpots;
//   unstored_work       the work done on the structure by the forces of blocks that store
//                       no energy (a follower pressure, the sidewall), -(f_n + f_{n+1})/2 . du;
//   balance_error = T + U + damping + contact_dissipated - (T_0 + U_0) - W - surface_work
//                   - unstored_work,
// zero for an exact integration: what remains is the energy the time discretisation
// created (> 0) or took (< 0, HHT's numerical damping among it).
// The record and its started flag live in the analysis' CarriedState (a checkpoint
// carries them, and the forces at step n with them); this class keeps them.
#pragma once

#include <vector>

#include "core/model.hpp"
#include "solvers/carried_state.hpp"

namespace tirefe {

class EnergyBalance {
 public:
  EnergyBalance(Model& model, CarriedState& carried) : model_(model), carried_(carried) {}

  const EnergyRecord& record() const { return carried_.energy; }
  bool started() const { return carried_.energy_started; }
  /// New initial conditions: the next start() begins the balance afresh.
  void forget() { carried_.energy_started = false; }
  /// Starts at 'state': initial = kinetic + strain now, no work yet; 'loads' gets F_0,
  /// the first step's old loads.
  void start(const State& state, Eigen::VectorXd& loads);
  /// Trapezoidal work of the step from 'old_state' to 'new_state': the loads on every
  /// DOF, the reactions at the prescribed DOFs and at 'driven_dofs'.
  double step_work(const State& old_state, const State& new_state, const Eigen::VectorXd& loads_old,
                   const Eigen::VectorXd& loads_new, const Eigen::VectorXd& reactions_old,
                   const Eigen::VectorXd& reactions_new, const std::vector<int>& driven_dofs) const;
  /// Books an accepted step from 'old_state' that did 'work' and ended at 'state', whose
  /// element history is committed.
  void add_step(const State& old_state, const State& state, double work);

 private:
  ElementEnergy stored_energy(const State& state) const;
  /// The dashpot forces and the forces of the blocks storing no energy at 'state' (the
  /// committed history left as it was).
  void block_forces(const State& state, Eigen::VectorXd& dashpots, Eigen::VectorXd& unstored);

  Model& model_;
  CarriedState& carried_;
  Eigen::VectorXd dashpots_, unstored_;  // at the new state
};

}  // namespace tirefe
