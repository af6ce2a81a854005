#include "solvers/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <sstream>

namespace tirefe {

Analysis::Analysis(Model& model) : model_(model), assembler_(model) {}

void Analysis::set_integrator(const Integrator& integrator) {
  // Entering dynamics needs accelerations in equilibrium with the current state.
  acceleration_pending_ = integrator.is_dynamic() && !integrator_.is_dynamic();
  integrator_ = integrator;
  old_forces_valid_ = false;
}

void Analysis::set_time_step(double step) {
  if (!(step > 0.0) || !std::isfinite(step))
    throw ModelError("the time step must be positive and finite (got " + std::to_string(step) + ")");
  nominal_step_ = step;
  current_step_ = step;
}

void Analysis::set_log(std::ostream* log) {
  log_ = log;
  newton_.settings().log = log;
}

void Analysis::prepare() {
  if (assembler_.update_pattern()) linear_solver_.analyze(assembler_.tangent());
  const int dofs = model_.mesh().dof_count();
  if (committed_.displacement.size() != dofs) {
    // Nodes added since the last step start at rest.
    const int old_size = static_cast<int>(committed_.displacement.size());
    for (Eigen::VectorXd* field : {&committed_.displacement, &committed_.velocity, &committed_.acceleration}) {
      field->conservativeResize(dofs);
      field->tail(dofs - old_size).setZero();
    }
    reactions_.setZero(dofs);
    old_forces_valid_ = false;
  }
}

void Analysis::evaluate(bool with_tangent, Eigen::VectorXd& free_residual, double& force_level) {
  EvaluationContext context;
  context.time = trial_.time;
  context.time_step = current_step_;
  context.factors = integrator_.factors(current_step_);
  context.want_tangent = with_tangent;
  assembler_.assemble(context, trial_, residual_all_);

  residual_all_ -= integrator_.new_force_weight() * external_new_;
  if (integrator_.old_force_weight() != 0.0)
    residual_all_ += integrator_.old_force_weight() * (old_internal_forces_ - external_old_);

  const DofMap& dofs = model_.dof_map();
  free_residual.resize(dofs.equation_count());
  for (int equation = 0; equation < dofs.equation_count(); ++equation)
    free_residual[equation] = residual_all_[dofs.dof(equation)];
  double reaction_squared = 0.0;
  for (const auto& constraint : model_.prescribed_dofs())
    reaction_squared += residual_all_[constraint.dof] * residual_all_[constraint.dof];
  force_level = std::max(external_new_.norm(), std::sqrt(reaction_squared));
}

double Analysis::apply_increment(const Eigen::VectorXd& increment) {
  const DofMap& dofs = model_.dof_map();
  double largest_increment = 0.0;
  for (int equation = 0; equation < dofs.equation_count(); ++equation) {
    integrator_.correct(current_step_, dofs.dof(equation), increment[equation], trial_);
    largest_increment = std::max(largest_increment, std::abs(increment[equation]));
  }
  return largest_increment / (1.0 + trial_.displacement.lpNorm<Eigen::Infinity>());
}

bool Analysis::try_step(double step, StepRecord& record) {
  current_step_ = step;
  trial_ = committed_;
  integrator_.predict(committed_, step, trial_);
  model_.apply_prescribed_displacements(trial_.time, trial_);
  for (const auto& constraint : model_.prescribed_dofs())
    integrator_.update_rates(committed_, step, constraint.dof, trial_);
  model_.external_forces(trial_.time, external_new_);
  if (integrator_.old_force_weight() != 0.0 && !old_forces_valid_) {
    // g_n = f_int(u_n) + C v_n at the committed state, for HHT's weighting.
    EvaluationContext context;
    context.time = committed_.time;
    context.factors = {1.0, 1.0, 0.0, 0.0, 0.0, 0.0};
    context.want_tangent = false;
    assembler_.assemble(context, committed_, old_internal_forces_);
    model_.external_forces(committed_.time, external_old_);
    old_forces_valid_ = true;
  }
  try {
    const NewtonReport& report = newton_.solve(*this, linear_solver_);
    record.newton_iterations = report.iterations;
    record.residual = report.residual_norms.back();
    return true;
  } catch (const std::exception& failure) {  // ConvergenceFailure, NonFiniteResult, SingularMatrix
    model_.revert_history();
    if (log_)
      *log_ << "  step to t = " << trial_.time << " (dt = " << step << ") rejected: " << failure.what() << "\n";
    last_failure_ = failure.what();
    return false;
  }
}

void Analysis::finish_step(double step) {
  const bool weighted = integrator_.old_force_weight() != 0.0;
  if (weighted) {
    // Physical reactions M a + g - F, and g_{n+1} for the next step's weighting.
    EvaluationContext context;
    context.time = trial_.time;
    context.time_step = step;
    context.want_tangent = false;
    context.factors = {1.0, 1.0, 0.0, 0.0, 0.0, 0.0};
    assembler_.assemble(context, trial_, old_internal_forces_);
    context.factors = {0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
    assembler_.assemble(context, trial_, residual_all_);
    residual_all_ += old_internal_forces_ - external_new_;
  }
  reactions_.setZero(model_.mesh().dof_count());
  for (const auto& constraint : model_.prescribed_dofs()) reactions_[constraint.dof] = residual_all_[constraint.dof];
  model_.commit_history();
  std::swap(committed_, trial_);
  external_old_ = external_new_;
  old_forces_valid_ = weighted;
  ++accepted_steps_;
}

const std::vector<StepRecord>& Analysis::advance(double duration) {
  prepare();
  if (acceleration_pending_) initialize_acceleration();
  records_.clear();
  if (duration <= 0.0) duration = nominal_step_;
  const double start = committed_.time;
  const double target = start + duration;
  const double time_round_off = 1e-12 * std::max(1.0, std::abs(target));
  double step = std::min(current_step_, control_.max_step > 0.0 ? control_.max_step : current_step_);
  while (committed_.time < target - time_round_off) {
    const double remaining = target - committed_.time;
    // Take the rest in one step if a sliver would be left over.
    step = (step >= remaining || remaining - step < 1e-6 * step) ? remaining : step;
    StepRecord record;
    while (!try_step(step, record)) {
      ++record.cuts;
      const double cut = 0.5 * step;
      if (record.cuts > control_.max_cuts || cut < control_.min_step) {
        std::ostringstream message;
        message << "the step from t = " << committed_.time << " could not be solved after " << record.cuts - 1
                << " cuts (smallest dt = " << step << "): " << last_failure_
                << ". Use smaller steps, more cuts, or check the loads and supports.";
        throw StepFailure(message.str());
      }
      step = cut;
    }
    finish_step(step);
    record.step = accepted_steps_;
    record.time = committed_.time;
    record.step_size = step;
    records_.push_back(record);
    for (const auto& observer : observers_) observer(*this, record);
    // Grow back toward the nominal step after an easy convergence.
    if (record.newton_iterations <= control_.easy_iterations)
      step = std::min(nominal_step_, step * control_.growth);
    current_step_ = step;
  }
  return records_;
}

void Analysis::initialize_acceleration() {
  prepare();
  EvaluationContext context;
  context.time = committed_.time;
  context.factors = {1.0, 1.0, 0.0, 0.0, 0.0, 1.0};  // residual g, tangent M
  context.want_tangent = true;
  assembler_.assemble(context, committed_, residual_all_);
  model_.external_forces(committed_.time, external_new_);
  const DofMap& dofs = model_.dof_map();
  Eigen::VectorXd unbalanced(dofs.equation_count());
  for (int equation = 0; equation < dofs.equation_count(); ++equation) {
    const int dof = dofs.dof(equation);
    unbalanced[equation] = external_new_[dof] - residual_all_[dof];
  }
  try {
    linear_solver_.factorize(assembler_.tangent());
  } catch (const SingularMatrix&) {
    throw ModelError("the mass matrix is singular: every free DOF needs mass (or rotary inertia) for dynamics");
  }
  linear_solver_.solve(unbalanced);
  for (int equation = 0; equation < dofs.equation_count(); ++equation)
    committed_.acceleration[dofs.dof(equation)] = unbalanced[equation];
  external_old_ = external_new_;
  old_forces_valid_ = false;
  acceleration_pending_ = false;
}

}  // namespace tirefe
