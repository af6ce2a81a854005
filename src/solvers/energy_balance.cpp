#include "solvers/energy_balance.hpp"

namespace tirefe {

void EnergyBalance::start(const State& state, Eigen::VectorXd& loads) {
  model_.external_forces(state.time, loads);
  const ElementEnergy stored = stored_energy(state);
  EnergyRecord& record = carried_.energy;
  record = EnergyRecord{};
  record.kinetic = stored.kinetic;
  record.strain = stored.strain;
  record.initial = stored.kinetic + stored.strain;
  record.supplied_at_start = stored.supplied;
  record.contact_dissipated_at_start = stored.dissipated;
  block_forces(state, carried_.dashpot_forces, carried_.unstored_forces);
  carried_.energy_started = true;
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

void EnergyBalance::add_step(const State& old_state, const State& state, double work) {
  const ElementEnergy stored = stored_energy(state);
  EnergyRecord& record = carried_.energy;
  record.kinetic = stored.kinetic;
  record.strain = stored.strain;
  record.external_work += work;
  record.dissipated = record.initial + record.external_work - stored.kinetic - stored.strain;

  block_forces(state, dashpots_, unstored_);
  const auto step = state.displacement - old_state.displacement;  // an expression: no allocation per step
  if (carried_.dashpot_forces.size() == step.size() && carried_.unstored_forces.size() == step.size()) {
    record.damping += 0.5 * (carried_.dashpot_forces + dashpots_).dot(step);
    record.unstored_work -= 0.5 * (carried_.unstored_forces + unstored_).dot(step);
  }
  carried_.dashpot_forces.swap(dashpots_);
  carried_.unstored_forces.swap(unstored_);
  record.surface_work = stored.supplied - record.supplied_at_start;
  record.contact_dissipated = stored.dissipated - record.contact_dissipated_at_start;
  record.balance_error = record.kinetic + record.strain + record.damping + record.contact_dissipated - record.initial -
                         record.external_work - record.surface_work - record.unstored_work;
}

ElementEnergy EnergyBalance::stored_energy(const State& state) const {
  ElementEnergy total;
  for (const auto& block : model_.blocks()) total += block->energy(state);
  return total;
}

void EnergyBalance::block_forces(const State& state, Eigen::VectorXd& dashpots, Eigen::VectorXd& unstored) {
  const Eigen::Index size = state.displacement.size();
  dashpots.setZero(size);
  unstored.setZero(size);
  EvaluationContext context;
  context.time = state.time;
  context.want_tangent = false;
  AssemblyTarget target;
  for (const auto& block : model_.blocks()) {
    const bool damped = block->has_dashpots(), unstored_forces = !block->stores_energy();
    if (damped) {
      context.factors = IntegratorFactors::damping_force();
      target.residual = &dashpots;
      block->assemble(context, state, target);
    }
    if (unstored_forces) {
      context.factors = IntegratorFactors::stiffness_force();
      target.residual = &unstored;
      block->assemble(context, state, target);
    }
    // Back to the committed history, for the blocks evaluated here alone: the others'
    // (a contact's samples, 1 kB a chord) are as committed.
    if ((damped || unstored_forces) && !block->history_free()) block->revert();
  }
}

}  // namespace tirefe
