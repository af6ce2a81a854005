#include "solvers/energy_balance.hpp"

namespace tirefe {

void EnergyBalance::start(const State& state, Eigen::VectorXd& loads) {
  model_.external_forces(state.time, loads);
  const ElementEnergy stored = stored_energy(state);
  record_ = EnergyRecord{};
  record_.kinetic = stored.kinetic;
  record_.strain = stored.strain;
  record_.initial = stored.kinetic + stored.strain;
  started_ = true;
}

double EnergyBalance::step_work(const State& old_state, const State& new_state, const Eigen::VectorXd& loads_old,
                                const Eigen::VectorXd& loads_new, const Eigen::VectorXd& reactions_old,
                                const Eigen::VectorXd& reactions_new, const std::vector<int>& driven_dofs) const {
  const Eigen::VectorXd& u_old = old_state.displacement;
  const Eigen::VectorXd& u_new = new_state.displacement;
  double work = 0.5 * (loads_old + loads_new).dot(u_new - u_old);
  const auto held_work = [&](int dof) {
    return 0.5 * (reactions_old[dof] + reactions_new[dof]) * (u_new[dof] - u_old[dof]);
  };
  for (const auto& constraint : model_.prescribed_dofs()) work += held_work(constraint.dof);
  for (int dof : driven_dofs) work += held_work(dof);
  return work;
}

void EnergyBalance::add_step(const State& state, double work) {
  const ElementEnergy stored = stored_energy(state);
  record_.kinetic = stored.kinetic;
  record_.strain = stored.strain;
  record_.external_work += work;
  record_.dissipated = record_.initial + record_.external_work - stored.kinetic - stored.strain;
}

ElementEnergy EnergyBalance::stored_energy(const State& state) const {
  ElementEnergy total;
  for (const auto& block : model_.blocks()) total += block->energy(state);
  return total;
}

}  // namespace tirefe
