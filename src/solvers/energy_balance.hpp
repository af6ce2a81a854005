// EnergyBalance: the work-energy bookkeeping of one analysis (docs/dynamics.md), once per
// accepted step n -> n+1:
//   W_{n+1} = W_n + (F_n + F_{n+1})/2 . (u_{n+1} - u_n) + (R_n + R_{n+1})/2 . (u_{n+1} - u_n)|held,
//   dissipated = (T_0 + U_0) + W - T - U,
// with F the nodal loads, R the reactions at the held (prescribed and driven) DOFs,
// T = v.M v/2 and U the blocks' stored energy. For a linear model under Newmark average
// acceleration the balance is exact, so 'dissipated' is the dashpots' work alone;
// otherwise it also holds the integrator's numerical dissipation (HHT) and the
// trapezoidal rule's error on nonlinear forces. The record and its started flag live in
// the analysis' CarriedState (a checkpoint carries them); this class keeps them.
#pragma once

#include <vector>

#include "core/model.hpp"
#include "solvers/carried_state.hpp"

namespace tirefe {

class EnergyBalance {
 public:
  EnergyBalance(const Model& model, EnergyRecord& record, bool& started)
      : model_(model), record_(record), started_(started) {}

  const EnergyRecord& record() const { return record_; }
  bool started() const { return started_; }
  /// New initial conditions: the next start() begins the balance afresh.
  void forget() { started_ = false; }
  /// Starts at 'state': initial = kinetic + strain now, no work yet; 'loads' gets F_0,
  /// the first step's old loads.
  void start(const State& state, Eigen::VectorXd& loads);
  /// Trapezoidal work of the step from 'old_state' to 'new_state': the loads on every
  /// DOF, the reactions at the prescribed DOFs and at 'driven_dofs'.
  double step_work(const State& old_state, const State& new_state, const Eigen::VectorXd& loads_old,
                   const Eigen::VectorXd& loads_new, const Eigen::VectorXd& reactions_old,
                   const Eigen::VectorXd& reactions_new, const std::vector<int>& driven_dofs) const;
  /// Books an accepted step that did 'work' and ended at 'state'.
  void add_step(const State& state, double work);

 private:
  ElementEnergy stored_energy(const State& state) const;

  const Model& model_;
  EnergyRecord& record_;
  bool& started_;
};

}  // namespace tirefe
