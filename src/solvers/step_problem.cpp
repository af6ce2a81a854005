#include "solvers/step_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>

namespace tirefe {

StepProblem::StepProblem(Model& model, Assembler& assembler, SolverChoice& solvers, const Integrator& integrator,
                         CarriedState& carried, const DrivenDofs& driven)
    : model_(model),
      assembler_(assembler),
      solvers_(solvers),
      integrator_(integrator),
      carried_(carried),
      driven_(driven) {}

void StepProblem::require_equations() const {
  int elements = 0;
  for (const auto& block : model_.blocks()) elements += block->size();
  if (elements == 0)
    throw ModelError(
        "the model has no elements: there are no equations to solve (add beams, a tire or other "
        "elements before solving)");
  if (model_.dof_map().equation_count() == 0)
    throw ModelError("the model has no equations to solve: every DOF is fixed or prescribed (release some)");
}

void StepProblem::prepare() {
  // By version rather than update_pattern()'s answer: others (contact set-up) may have
  // rebuilt the pattern through the assembler since the last step.
  assembler_.update_pattern();
  if (!solvers_.analyzed(assembler_.pattern_version())) {
    require_equations();
    solvers_.analyze(assembler_.tangent(), assembler_.pattern_version());
  }
  size_state();
  if (driven_.empty()) {
    solvers_.stop_driving();
  } else if (!solvers_.driving()) {
    if (!integrator_.is_dynamic())
      throw ModelError(
          "driven DOFs need a dynamic integrator (newmark, hht, wbz or generalized_alpha): the quasi-static tangent of a "
          "structure held only at its driven DOFs is singular");
    std::vector<int> equations;
    for (int dof : driven_.dofs()) {
      if (model_.dof_map().is_prescribed(dof))
        throw ModelError("DOF " + std::to_string(dof) + " is prescribed and cannot also be driven (release it first)");
      equations.push_back(model_.dof_map().equation(dof));
    }
    solvers_.drive(std::move(equations), assembler_.tangent());
  }
}

void StepProblem::size_state() {
  const int dofs = model_.mesh().dof_count();
  if (carried_.state.displacement.size() != dofs) {
    // Nodes added since the last step start at rest.
    const int old_size = static_cast<int>(carried_.state.displacement.size());
    for (Eigen::VectorXd* field :
         {&carried_.state.displacement, &carried_.state.velocity, &carried_.state.acceleration}) {
      field->conservativeResize(dofs);
      field->tail(dofs - old_size).setZero();
    }
    carried_.reactions.setZero(dofs);
    model_.external_forces(carried_.state.time, carried_.external_old);
    carried_.reactions_valid = false;
    carried_.old_forces_valid = false;
  }
}

void StepProblem::predict(double step, double end_time) {
  response_pattern_ = -1;
  carried_.steps.current = step;
  trial_ = carried_.state;
  integrator_.predict(carried_.state, step, trial_);
  trial_.time = end_time;
  model_.apply_prescribed_displacements(trial_.time, trial_);
  for (const auto& constraint : model_.prescribed_dofs())
    integrator_.update_rates(carried_.state, step, constraint.dof, trial_);
  driven_.impose(integrator_, carried_.state, step, trial_);
  model_.external_forces(trial_.time, external_new_);
  if (integrator_.weights_old_forces() && !carried_.old_forces_valid) {
    // g_n = f_int(u_n) + C v_n (and M a_n) at the committed state, for the weighting.
    EvaluationContext context;
    context.time = carried_.state.time;
    context.factors = Integrator::internal_force_factors();
    context.want_tangent = false;
    assembler_.query(context, carried_.state, carried_.old_internal_forces);
    if (integrator_.old_inertia_weight() != 0.0) query_inertia_forces(carried_.state, carried_.old_inertia_forces);
    model_.external_forces(carried_.state.time, carried_.external_old);
    carried_.old_forces_valid = true;
  }
}

bool StepProblem::start_from_driven_move(double step) {
  DrivenDofSolver* driven = solvers_.driven();
  const int factored = response_pattern_;
  response_pattern_ = -1;
  if (!driven || assembler_.update_pattern() || factored != assembler_.pattern_version()) return false;
  // The tangent and its factors are still the converged trial's.
  const DofMap& dofs = model_.dof_map();
  driven_move_.setZero(dofs.equation_count());
  const std::vector<int>& driven_dofs = driven_.dofs();
  for (size_t i = 0; i < driven_dofs.size(); ++i)
    driven_move_[dofs.equation(driven_dofs[i])] =
        driven_.displacements()[static_cast<Eigen::Index>(i)] - trial_.displacement[driven_dofs[i]];
  if (tangent_in_solver_)
    driven->multiply_driven_columns(driven_move_, response_);
  else
    response_.noalias() = assembler_.tangent() * driven_move_;
  response_ = -response_;
  driven->solve(response_);  // du_u, with du_s = 0
  response_ += driven_move_;
  model_.revert_history();  // the trial history follows from the committed one again
  apply_increment(response_);
  driven_.impose(integrator_, carried_.state, step, trial_);  // exactly where the host puts them
  // Judged as the trial from the predictor was: against the force level of its first residual.
  resolve_reference_ = trial_reference_;
  start_expected_converged_ = true;
  return true;
}

bool StepProblem::solve(NewtonSolver& newton, int max_augmentations, StepRecord& record, std::ostream* log) {
  const auto begin_solve = [this] {  // its first evaluation comes next; no earlier start is made again
    first_evaluation_ = true;
    start_without_tangent_ = false;
  };
  bool solved = true;
  try {
    LinearSolver& linear_solver = solvers_.newton_solver();
    begin_solve();
    const NewtonReport* report = &newton.solve(*this, linear_solver);
    if (resolve_reference_ == 0.0) trial_reference_ = report->reference_force;
    record.newton_iterations = report->iterations;
    record.augmentations = 0;
    // Augmented Lagrangian: update the multipliers and solve again until the
    // constraints are met to their tolerance (or the augmentation budget is spent).
    while (record.augmentations < max_augmentations && model_.augment()) {
      ++record.augmentations;
      begin_solve();
      report = &newton.solve(*this, linear_solver);
      record.newton_iterations += report->iterations;
    }
    record.residual = report->residual_norms.back();
  } catch (const std::exception& failure) {  // ConvergenceFailure, NonFiniteResult, SingularMatrix
    model_.revert_history();
    if (log)
      *log << "  step to t = " << trial_.time << " (dt = " << carried_.steps.current << ") rejected: " << failure.what()
           << "\n";
    failure_ = failure.what();
    solved = false;
  }
  resolve_reference_ = 0.0;
  return solved;
}

void StepProblem::evaluate(bool with_tangent, Eigen::VectorXd& free_residual, double& force_level) {
  if (with_tangent && start_without_tangent_) {
    // That start again, now with its tangent, from the history it began with: the
    // evaluation plain Newton would have made there, the same residual bit for bit.
    model_.revert_history();
    first_evaluation_ = true;
  }
  start_without_tangent_ = !with_tangent && first_evaluation_;
  start_expected_converged_ = false;
  EvaluationContext context;
  context.time = trial_.time;
  context.time_step = carried_.steps.current;
  context.factors = integrator_.factors(carried_.steps.current);
  context.want_tangent = with_tangent;
  context.first_evaluation = first_evaluation_;
  first_evaluation_ = false;
  RingSolver* solver = with_tangent ? solver_taking_tangent() : nullptr;
  tangent_in_solver_ = false;
  if (solver) {
    // Straight into the solver's blocks: no sparse values to clear and copy (docs/kernel.md).
    double* storage = solvers_.driving() ? solvers_.driven()->begin_assembly() : solver->begin_assembly();
    assembler_.assemble_into_solver(context, trial_, residual_all_, storage);
    tangent_in_solver_ = true;
  } else {
    assembler_.assemble(context, trial_, residual_all_);
  }

  integrator_.add_load_terms(external_new_, carried_.old_internal_forces, carried_.old_inertia_forces,
                             carried_.external_old, residual_all_);

  const DofMap& dofs = model_.dof_map();
  free_residual.resize(dofs.equation_count());
  for (int equation = 0; equation < dofs.equation_count(); ++equation)
    free_residual[equation] = residual_all_[dofs.dof(equation)];
  double reaction_squared = 0.0;
  for (const auto& constraint : model_.prescribed_dofs())
    reaction_squared += residual_all_[constraint.dof] * residual_all_[constraint.dof];
  for (int dof : driven_.dofs()) {  // held where the host puts them: their residuals are reactions
    reaction_squared += residual_all_[dof] * residual_all_[dof];
    free_residual[dofs.equation(dof)] = 0.0;
  }
  force_level = std::max({external_new_.norm(), std::sqrt(reaction_squared), resolve_reference_});
}

RingSolver* StepProblem::solver_taking_tangent() {
  RingSolver* ring = solvers_.driving() ? solvers_.driven()->assembly_solver() : solvers_.ring_solver();
  if (!ring || !solvers_.analyzed(assembler_.pattern_version())) return nullptr;
  if (ring != layout_solver_ || layout_pattern_ != assembler_.pattern_version() || !assembler_.solver_layout_bound()) {
    assembler_.bind_solver_layout(ring->entry_destinations());
    layout_solver_ = ring;
    layout_pattern_ = assembler_.pattern_version();
  }
  return ring;
}

void StepProblem::factorize_tangent(LinearSolver& solver) {
  if (!tangent_in_solver_) {
    solver.factorize(assembler_.tangent());
    return;
  }
  DrivenDofSolver* driven = solvers_.driving() ? solvers_.driven() : nullptr;
  if (driven ? &solver != driven || driven->assembly_solver() != layout_solver_ : &solver != layout_solver_)
    throw std::logic_error("step problem: the tangent lies in one solver's storage and another was asked to factor it");
  if (driven)
    driven->factorize_assembled();
  else
    layout_solver_->factorize_assembled();
}

double StepProblem::apply_increment(const Eigen::VectorXd& increment) {
  const DofMap& dofs = model_.dof_map();
  const RateCorrection rates = integrator_.rate_correction(carried_.steps.current);
  double largest_increment = 0.0;
  for (int equation = 0; equation < dofs.equation_count(); ++equation) {
    rates.apply(dofs.dof(equation), increment[equation], trial_);
    largest_increment = std::max(largest_increment, std::abs(increment[equation]));
  }
  return largest_increment / (1.0 + trial_.displacement.lpNorm<Eigen::Infinity>());
}

const DrivenDofSolver::SmallMatrix& StepProblem::driven_tangent() {
  DrivenDofSolver* driven = solvers_.driven();
  if (!driven) throw ModelError("the driven tangent needs a solved trial step");
  if (start_without_tangent_) {  // Newton converged at a start of the residual alone
    double force_level = 0.0;
    evaluate(true, start_residual_, force_level);
  }
  if (tangent_in_solver_)
    driven->factorize_with_schur_assembled();
  else
    driven->factorize_with_schur(assembler_.tangent());
  response_pattern_ = assembler_.pattern_version();
  return driven->schur_complement();
}

void StepProblem::query_inertia_forces(const State& state, Eigen::VectorXd& inertia) {
  if (assembler_.inertia_forces(state, inertia)) return;
  EvaluationContext context;
  context.time = state.time;
  context.factors = IntegratorFactors::inertia_force();
  context.want_tangent = false;
  assembler_.query(context, state, inertia);
}

void StepProblem::commit(double step, EnergyBalance& energy, StepRecord& record) {
  // Steps are counted in an int (records, checkpoints): the count stops, never wraps.
  if (carried_.accepted_steps == std::numeric_limits<int>::max())
    throw ModelError("the analysis has taken " + std::to_string(carried_.accepted_steps) +
                     " steps, the most it counts; continue in another run");
  // residual_all_ must hold the physical residual M a + g - F of the new state, whose
  // prescribed entries are the reactions: the last Newton evaluation's, as the integrator
  // turns it.
  integrator_.to_physical_residual(
      carried_.external_old, external_new_, carried_.old_internal_forces, carried_.old_inertia_forces,
      [this, step](Eigen::VectorXd& internal, Eigen::VectorXd& inertia) {
        // The last Newton evaluation's element forces, here residual_all_ + w_new F_{n+1},
        // are wK g_{n+1} + wM M a_{n+1} (wK = wC): either part follows from the other.
        const IntegratorFactors weights = integrator_.factors(step);
        const bool with_inertia = integrator_.old_inertia_weight() != 0.0;
        if (weights.force_damping == weights.force_stiffness && assembler_.inertia_forces(trial_, inertia_forces_)) {
          internal =
              (residual_all_ + integrator_.new_force_weight() * external_new_ - weights.force_mass * inertia_forces_) /
              weights.force_stiffness;
          if (with_inertia) inertia = inertia_forces_;
          return;
        }
        EvaluationContext context;
        context.time = trial_.time;
        context.time_step = step;
        context.want_tangent = false;
        context.factors = Integrator::internal_force_factors();
        assembler_.assemble(context, trial_, internal);
        if (with_inertia)
          inertia =
              (residual_all_ + integrator_.new_force_weight() * external_new_ - weights.force_stiffness * internal) /
              weights.force_mass;
      },
      residual_all_);
  const double work =
      energy.step_work(carried_.state, trial_, carried_.external_old, external_new_, carried_.reactions, residual_all_,
                       driven_.dofs());  // before the reactions and the state move on
  carried_.reactions.setZero(model_.mesh().dof_count());
  for (const auto& constraint : model_.prescribed_dofs())
    carried_.reactions[constraint.dof] = residual_all_[constraint.dof];
  for (int dof : driven_.dofs()) carried_.reactions[dof] = residual_all_[dof];
  carried_.reactions_valid = true;
  model_.commit_history();
  std::swap(carried_.state, trial_);
  carried_.external_old = external_new_;
  carried_.old_forces_valid = integrator_.weights_old_forces();
  ++carried_.accepted_steps;
  energy.add_step(trial_, carried_.state, work);  // trial_ holds the old state now
  record.step = carried_.accepted_steps;
  record.time = carried_.state.time;
  record.step_size = step;
  record.energy = energy.record();
}

}  // namespace tirefe
