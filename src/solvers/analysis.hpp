// Analysis: the solution driver of one model. It advances time (or the load level,
// quasi-statically) in steps, solves each step with Newton, commits the state and
// the element history on success, and on failure reverts, cuts the step and retries.
// Steps grow back after easy convergence. Observers hear of every accepted step
// (output writers, logs). The linear solver is a SolverChoice (solver_choice.hpp).
// The energy balance of the accepted steps is an EnergyBalance (energy_balance.hpp).
#pragma once

#include <functional>
#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/assembler.hpp"
#include "core/model.hpp"
#include "solvers/carried_state.hpp"
#include "solvers/driven_dofs.hpp"
#include "solvers/driven_solver.hpp"
#include "solvers/energy_balance.hpp"
#include "solvers/integrator.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/newton.hpp"
#include "solvers/ring_solver.hpp"
#include "solvers/solver_choice.hpp"
#include "solvers/step_controller.hpp"

namespace tirefe {

class Analysis : private StepEquations, private SteppedSystem {
 public:
  explicit Analysis(Model& model);
  Analysis(const Analysis&) = delete;
  Analysis& operator=(const Analysis&) = delete;

  Model& model() { return model_; }
  const Model& model() const { return model_; }
  void set_integrator(const Integrator& integrator);
  const Integrator& integrator() const { return integrator_; }
  void set_time_step(double step);
  double time_step() const { return carried_.steps.nominal; }
  NewtonSettings& newton_settings() { return newton_.settings(); }
  StepControl& step_control() { return controller_.settings(); }
  void set_log(std::ostream* log);

  /// Advances by 'duration' (default: one nominal step) in as many accepted steps as
  /// it takes; returns the records of the accepted steps. Throws StepFailure.
  const std::vector<StepRecord>& advance(double duration = 0.0);
  /// The same, up to the time 'target' (the last step lands on it exactly).
  const std::vector<StepRecord>& advance_to(double target);

  /// The state between steps, for a checkpoint. Taking one also drops the linear
  /// solver's reused pivots, as a restore does, so that the run goes on as a restarted one would.
  CarriedState snapshot();
  /// Continues from a snapshot (with the same integrator; throws ModelError otherwise).
  void restore(const CarriedState& snapshot);

  /// Solves M a = F - f_int - C v for the accelerations at the current time. Called by
  /// advance() when the analysis enters dynamics or after new initial conditions.
  void initialize_acceleration();

  /// Initial conditions, allowed before the first step only: one DOF
  /// (dof_index(node, component)) or the whole field (one entry per DOF). Prescribed
  /// DOFs follow their load functions from the first step on. A dynamic analysis
  /// recomputes the consistent initial acceleration before its first step.
  void set_initial_displacement(int dof, double value);
  void set_initial_velocity(int dof, double value);
  void set_initial_displacement(const Eigen::VectorXd& displacement);
  void set_initial_velocity(const Eigen::VectorXd& velocity);

  const State& state() const { return carried_.state; }
  State& mutable_state() { return carried_.state; }
  /// Reactions at prescribed DOFs (zero elsewhere), from the last converged step.
  const Eigen::VectorXd& reactions() const { return carried_.reactions; }
  const Eigen::VectorXd& external_forces() const { return external_new_; }
  /// Why the last step that failed did not converge (Newton's or the linear solver's words).
  const std::string& last_failure() const { return last_failure_; }
  /// Energy balance as of the last accepted step (all zero before the first).
  const EnergyRecord& energy() const { return energy_.record(); }
  /// Starts the balance afresh at the current state (after a static preload, say):
  /// initial = kinetic + strain now, no external work yet.
  void restart_energy_balance();
  int accepted_steps() const { return carried_.accepted_steps; }
  const NewtonReport& last_newton_report() const { return newton_.last_report(); }
  Assembler& assembler() { return assembler_; }
  /// The solver of the Newton iterations (KLU by default).
  LinearSolver& linear_solver() { return solvers_.solver(); }
  /// Solves with the RingSolver (ring_solver.hpp): ring_nodes in ring order (a tire's
  /// tread nodes), border_nodes coupled to everything (its spindle; mark it with
  /// Model::condense_node so that its equations come last, as H's rows do). The model's
  /// current tangent pattern is checked at once: a model that does not fit throws
  /// ModelError and keeps the current solver. Later changes of structure are checked
  /// again before the next step.
  void use_ring_solver(std::vector<int> ring_nodes, std::vector<int> border_nodes);
  /// Solves with the RingSolver over these nodes whenever the tangent's pattern fits it
  /// (checked at every change of pattern), with KLU otherwise: a lone tire on its road
  /// gets the structured solver, a tire with more structure attached the general one.
  void prefer_ring_solver(std::vector<int> ring_nodes, std::vector<int> border_nodes);
  /// The RingSolver in use, for its border Schur complement; null while KLU solves.
  RingSolver* ring_solver() { return solvers_.ring_solver(); }

  /// Driven DOFs (docs/spindle.md): free DOFs whose displacement at the end of each
  /// step a host gives (a vehicle moving a tire's spindle). Newton solves the other
  /// equations with the factors of the whole tangent (DrivenDofSolver); the driven DOFs'
  /// residuals are the forces that hold them there. At most one node's DOFs, dynamic
  /// integrators only (the tangent must be regular). An empty list ends the driving.
  void drive_dofs(std::vector<int> dofs);
  /// Displacements of the driven DOFs at the end of the next step, in drive_dofs' order.
  void set_driven_displacements(const Eigen::Ref<const Eigen::VectorXd>& values);

  /// One step of size 'step' from the committed state, kept as a trial: the committed
  /// state and element history stay as they are until accept_trial_step(); another
  /// solve_trial_step() starts again from them (no step cuts; throws StepFailure).
  const StepRecord& solve_trial_step(double step);
  /// solve_trial_step() again after new driven displacements, starting from the trial
  /// state moved by its linear response to them (A_uu du_u = -A_us du_s with the factors
  /// of driven_tangent(), taken at that state) instead of from the predictor: a host's
  /// corrector moves the driven DOFs little between its trials, so Newton has little
  /// left to do: its first evaluation assembles the residual alone, the tangent following
  /// only if Newton iterates or driven_tangent() asks for it. Newton's reference force is
  /// at least that of the trial from the predictor, so that the same absolute tolerance
  /// judges both. From the predictor when there is no such trial (none pending, no
  /// driven_tangent() since, another step size).
  const StepRecord& resolve_trial_step(double step);
  /// Commits the trial step as advance() commits a step (observers hear of it).
  void accept_trial_step();
  /// The computing part of accept_trial_step(), which then only tells the observers: the
  /// state, history and energies move on. Tires of one vehicle do this concurrently and
  /// write their output in turn. Only accept_trial_step() may follow it.
  void record_trial_step();
  /// Forgets the trial step.
  void discard_trial_step();
  /// The trial state of the last solve_trial_step().
  const State& trial_state() const { return trial_; }
  /// Residuals at the driven DOFs of the converged trial step: the forces that hold
  /// them, HHT-weighted like the step's equations (the reactions once accepted).
  void driven_forces(Eigen::Ref<Eigen::VectorXd> forces) const;
  /// H = K_ss - K_su K_uu^-1 K_us of the effective tangent at the converged trial step
  /// over the driven DOFs (docs/model.md eq. 27): the Jacobian of driven_forces() with
  /// respect to the driven displacements. One factorization of the converged tangent (and
  /// its assembly, when resolve_trial_step() converged on the residual alone).
  const DrivenDofSolver::SmallMatrix& driven_tangent();

  void add_step_observer(std::function<void(const Analysis&, const StepRecord&)> observer) {
    controller_.add_observer(
        [this, observer = std::move(observer)](const StepRecord& record) { observer(*this, record); });
  }
  /// Runs after every observer of an accepted step (a checkpoint: the step's output is complete then).
  void set_step_end_hook(std::function<void(Analysis&, const StepRecord&)> hook) {
    controller_.set_closing_observer([this, hook = std::move(hook)](const StepRecord& record) { hook(*this, record); });
  }

 private:
  void prepare();
  void size_state();
  /// M a at 'state' (generalized-alpha's old inertia force).
  void query_inertia_forces(const State& state, Eigen::VectorXd& inertia);
  void start_steps();
  // SteppedSystem
  double time() const override { return carried_.state.time; }
  bool try_step(double step, double end_time, StepRecord& record) override;
  /// Newton and the augmentations from the trial state as it is; false (history reverted) on failure.
  bool iterate(double step, StepRecord& record);
  /// The solved trial kept for accept or discard; throws StepFailure if it was not solved.
  const StepRecord& keep_trial(double step, bool solved);
  void commit_step(double step, StepRecord& record) override;
  std::string failure_message(int cuts, double step) const override;
  /// ModelError when there is nothing to solve (no elements, or every DOF fixed).
  void require_equations() const;
  void finish_step(double step);
  Eigen::VectorXd& initial_field(Eigen::VectorXd State::*field, const char* what);
  void update_committed_reactions();
  // StepEquations
  void evaluate(bool with_tangent, Eigen::VectorXd& free_residual, double& force_level) override;
  const SparseMatrix& tangent() const override { return assembler_.tangent(); }
  void factorize_tangent(LinearSolver& solver) override;
  double apply_increment(const Eigen::VectorXd& increment) override;
  /// The RingSolver that Newton's tangent is assembled into (its own storage, bound to the
  /// assembler for this pattern), or null: the RingSolver solving alone, or the held one of
  /// a DrivenDofSolver on the ring route.
  RingSolver* solver_taking_tangent();
  /// A host's driven_tangent() and resolve_trial_step() read the converged step's tangent.
  bool wants_converged_tangent() const override { return !driven_.empty(); }
  bool start_expected_converged() const override { return start_expected_converged_; }
  /// A Newton solve begins: its first evaluation comes next, and no earlier start is made again.
  void begin_solve() {
    first_evaluation_ = true;
    start_without_tangent_ = false;
  }

  Model& model_;
  Assembler assembler_;
  SolverChoice solvers_;
  NewtonSolver newton_;
  Integrator integrator_ = Integrator::quasi_static();
  std::ostream* log_ = nullptr;
  std::string last_failure_;

  CarriedState carried_;
  StepController controller_{carried_.steps};
  EnergyBalance energy_{model_, carried_};
  State trial_;
  Eigen::VectorXd residual_all_, external_new_;
  DrivenDofs driven_;
  bool trial_pending_ = false;
  bool trial_recorded_ = false;  // record_trial_step() done, observers not yet told
  double trial_step_size_ = 0.0;
  StepRecord trial_record_;
  int response_pattern_ = -1;  // pattern of the trial's factors from driven_tangent(); -1: none
  Eigen::VectorXd driven_move_, response_;
  double trial_reference_ = 0.0;           // Newton's reference force of the step's trial from the predictor
  double resolve_reference_ = 0.0;         // that force, a floor of the force level while resolving
  Eigen::VectorXd inertia_forces_;         // M a of the step being finished
  bool first_evaluation_ = false;          // the next evaluate() is the first of a Newton solve
  bool start_expected_converged_ = false;  // the next Newton solve starts from a trial's linear response
  bool start_without_tangent_ = false;     // the last evaluation was such a start's, of the residual alone
  Eigen::VectorXd start_residual_;         // the free residual of that start made again with its tangent
  RingSolver* layout_solver_ = nullptr;    // the solver whose layout the assembler holds bound,
  int layout_pattern_ = -1;                // for this pattern version
  bool tangent_in_solver_ = false;         // the last evaluation's tangent lies in layout_solver_
};

}  // namespace tirefe
