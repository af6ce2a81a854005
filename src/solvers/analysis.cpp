#include "solvers/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>
#include <type_traits>

namespace tirefe {

Analysis::Analysis(Model& model) : model_(model), assembler_(model) {}

void Analysis::use_ring_solver(std::vector<int> ring_nodes, std::vector<int> border_nodes) {
  for (const std::vector<int>* nodes : {&ring_nodes, &border_nodes})
    for (int node : *nodes) model_.mesh().checked(node);
  auto solver = std::make_unique<RingSolver>(model_.dof_map(), std::move(ring_nodes), std::move(border_nodes));
  assembler_.update_pattern();
  solvers_.use_ring(std::move(solver), assembler_.tangent(), assembler_.pattern_version());
}

void Analysis::prefer_ring_solver(std::vector<int> ring_nodes, std::vector<int> border_nodes) {
  for (const std::vector<int>* nodes : {&ring_nodes, &border_nodes})
    for (int node : *nodes) model_.mesh().checked(node);
  solvers_.prefer_ring(std::make_unique<RingSolver>(model_.dof_map(), std::move(ring_nodes), std::move(border_nodes)));
}

void Analysis::set_integrator(const Integrator& integrator) {
  // Entering dynamics needs accelerations in equilibrium with the current state; a
  // request still pending (new initial conditions) survives a change of scheme.
  carried_.acceleration_pending =
      integrator.is_dynamic() && (carried_.acceleration_pending || !integrator_.is_dynamic());
  integrator_ = integrator;
  carried_.old_forces_valid = false;
}

void Analysis::set_time_step(double step) {
  if (!(step > 0.0) || !std::isfinite(step))
    throw ModelError("the time step must be positive and finite (got " + std::to_string(step) + ")");
  carried_.steps.nominal = step;
  carried_.steps.current = step;
}

void Analysis::set_log(std::ostream* log) {
  log_ = log;
  newton_.settings().log = log;
}

void Analysis::drive_dofs(std::vector<int> dofs) {
  DrivenDofs driven(std::move(dofs), model_.mesh().dof_count());
  stepper_.revert();
  problem_.size_state();
  driven.start_at(carried_.state);
  driven_ = std::move(driven);
  solvers_.stop_driving();
  carried_.reactions_valid = false;
}

bool Analysis::try_step(double step, double end_time, StepRecord& record) {
  problem_.predict(step, end_time);
  return problem_.solve(newton_, controller_.settings().max_augmentations, record, log_);
}

DrivenStepper& Analysis::driven_stepper() {
  if (carried_.acceleration_pending || !carried_.reactions_valid || !energy_.started()) start_steps();
  return stepper_;
}

void Analysis::restart_energy_balance() {
  problem_.size_state();
  energy_.start(carried_.state, carried_.external_old);
}

void Analysis::update_committed_reactions() {
  // Physical residual M a + C v + f_int - F at the committed state (no inertia quasi-statically).
  carried_.reactions.setZero(model_.mesh().dof_count());
  carried_.reactions_valid = true;
  if (model_.prescribed_dofs().empty() && driven_.empty()) return;
  EvaluationContext context;
  context.time = carried_.state.time;
  context.time_step = carried_.steps.current;
  context.want_tangent = false;
  context.factors = integrator_.physical_residual_factors();
  Eigen::VectorXd residual;
  assembler_.query(context, carried_.state, residual);
  model_.external_forces(carried_.state.time, carried_.external_old);
  for (const auto& constraint : model_.prescribed_dofs())
    carried_.reactions[constraint.dof] = residual[constraint.dof] - carried_.external_old[constraint.dof];
  for (int dof : driven_.dofs()) carried_.reactions[dof] = residual[dof] - carried_.external_old[dof];
}

Eigen::VectorXd& Analysis::initial_field(Eigen::VectorXd State::*field, const char* what) {
  if (carried_.accepted_steps > 0)
    throw ModelError(std::string("initial ") + what + " can only be set before the first step (" +
                     std::to_string(carried_.accepted_steps) + " steps are already taken)");
  problem_.size_state();
  carried_.acceleration_pending = carried_.acceleration_pending || integrator_.is_dynamic();
  carried_.reactions_valid = false;
  carried_.old_forces_valid = false;
  energy_.forget();
  return carried_.state.*field;
}

namespace {
void set_entry(Eigen::VectorXd& field, int dof, double value, const char* what) {
  if (dof < 0 || dof >= field.size())
    throw ModelError(std::string("initial ") + what + ": DOF " + std::to_string(dof) +
                     " does not exist (the model has " + std::to_string(field.size()) +
                     " DOFs, dof = 3 * node + component)");
  field[dof] = value;
}
void set_field(Eigen::VectorXd& field, const Eigen::VectorXd& values, const char* what) {
  if (values.size() != field.size())
    throw ModelError(std::string("initial ") + what + ": got " + std::to_string(values.size()) +
                     " values for a model with " + std::to_string(field.size()) + " DOFs");
  field = values;
}
}  // namespace

void Analysis::set_initial_displacement(int dof, double value) {
  set_entry(initial_field(&State::displacement, "displacement"), dof, value, "displacement");
}

void Analysis::set_initial_velocity(int dof, double value) {
  set_entry(initial_field(&State::velocity, "velocity"), dof, value, "velocity");
}

void Analysis::set_initial_displacement(const Eigen::VectorXd& displacement) {
  set_field(initial_field(&State::displacement, "displacement"), displacement, "displacement");
}

void Analysis::set_initial_velocity(const Eigen::VectorXd& velocity) {
  set_field(initial_field(&State::velocity, "velocity"), velocity, "velocity");
}

void Analysis::start_steps() {
  stepper_.revert();
  problem_.prepare();
  if (carried_.acceleration_pending) initialize_acceleration();
  if (!carried_.reactions_valid) update_committed_reactions();
  if (!energy_.started()) energy_.start(carried_.state, carried_.external_old);
}

const std::vector<StepRecord>& Analysis::advance(double duration) {
  return advance_to(carried_.state.time + (duration > 0.0 ? duration : carried_.steps.nominal));
}

const std::vector<StepRecord>& Analysis::advance_to(double target) {
  start_steps();
  return controller_.advance_to(*this, target);
}

std::string Analysis::failure_message(int cuts, double step) const {
  std::ostringstream message;
  message << "the step from t = " << carried_.state.time << " could not be solved after " << cuts
          << " cuts (smallest dt = " << step << "): " << problem_.failure()
          << ". Use smaller steps, more cuts, or check the loads and supports.";
  return message.str();
}

CarriedState Analysis::snapshot() {
  carried_.integrator = integrator_.record();
  solvers_.forget_analysis();  // the next factorization starts afresh, as after a restore
  return carried_;
}

void Analysis::restore(const CarriedState& s) {
  if (s.integrator != integrator_.record())
    throw ModelError("the checkpoint was taken with another integrator than the deck's " + integrator_.name());
  const int dofs = model_.mesh().dof_count();
  CarriedState::for_each_field(s, [&s, dofs](const char*, const auto& field) {
    if constexpr (std::is_same_v<std::decay_t<decltype(field)>, Eigen::VectorXd>)
      if (field.size() != dofs && (&field != &s.old_internal_forces || s.old_forces_valid) &&
          (&field != &s.old_inertia_forces || (s.old_forces_valid && s.integrator.alpha_m != 0.0)))
        throw ModelError("the checkpoint holds " + std::to_string(field.size()) + " DOFs, the model has " +
                         std::to_string(dofs));
  });
  carried_ = s;
  solvers_.forget_analysis();
}

void Analysis::initialize_acceleration() {
  problem_.prepare();
  EvaluationContext context;
  context.time = carried_.state.time;
  context.factors = Integrator::initial_acceleration_factors();
  context.want_tangent = true;
  Eigen::VectorXd residual;
  assembler_.query(context, carried_.state, residual);
  model_.external_forces(carried_.state.time, carried_.external_old);
  const DofMap& dofs = model_.dof_map();
  Eigen::VectorXd unbalanced(dofs.equation_count());
  for (int equation = 0; equation < dofs.equation_count(); ++equation) {
    const int dof = dofs.dof(equation);
    unbalanced[equation] = carried_.external_old[dof] - residual[dof];
  }
  try {
    solvers_.solver().factorize(assembler_.tangent());
  } catch (const SingularMatrix&) {
    throw ModelError("the mass matrix is singular: every free DOF needs mass (or rotary inertia) for dynamics");
  }
  solvers_.solver().solve(unbalanced);
  for (int equation = 0; equation < dofs.equation_count(); ++equation)
    carried_.state.acceleration[dofs.dof(equation)] = unbalanced[equation];
  carried_.old_forces_valid = false;
  carried_.acceleration_pending = false;
  carried_.reactions_valid = false;  // the inertia part of the reactions changed
}

}  // namespace tirefe
