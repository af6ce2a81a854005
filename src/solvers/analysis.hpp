// Analysis: the solution driver of one model, as a deck runs it. It holds the integrator
// and the initial conditions and advances time (or the load level, quasi-statically) in
// steps through a StepController: each step's equations are a StepProblem that Newton
// solves; a failed step is cut and retried, and steps grow back after easy convergence.
// Observers hear of every accepted step (output writers, logs). A host that moves some
// DOFs itself (a vehicle holding a tire's spindle) steps through a DrivenStepper instead.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "solvers/driven_stepper.hpp"
#include "solvers/ring_solver.hpp"
#include "solvers/step_problem.hpp"

namespace tirefe {

class Analysis : private SteppedSystem {
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

  /// Advances by 'duration' (default: one nominal step) in as many accepted steps as it
  /// takes; returns the records of the accepted steps. Throws StepFailure.
  const std::vector<StepRecord>& advance(double duration = 0.0);
  /// The same, up to the time 'target' (the last step lands on it exactly).
  const std::vector<StepRecord>& advance_to(double target);

  /// The state between steps, for a checkpoint (the linear solver's reused pivots are
  /// dropped, as a restore does, so that the run goes on as a restarted one would).
  CarriedState snapshot();
  /// Continues from a snapshot (with the same integrator; throws ModelError otherwise).
  void restore(const CarriedState& snapshot);

  /// Initial conditions, before the first step only: one DOF (dof_index(node, component))
  /// or the whole field. A dynamic analysis then recomputes the consistent acceleration,
  /// M a = F - f_int - C v (initialize_acceleration()), before its first step.
  void set_initial_displacement(int dof, double value);
  void set_initial_velocity(int dof, double value);
  void set_initial_displacement(const Eigen::VectorXd& displacement);
  void set_initial_velocity(const Eigen::VectorXd& velocity);
  void initialize_acceleration();

  const State& state() const { return carried_.state; }
  State& mutable_state() { return carried_.state; }
  /// Reactions at prescribed and driven DOFs (zero elsewhere), and the loads, at the committed state.
  const Eigen::VectorXd& reactions() const { return carried_.reactions; }
  const Eigen::VectorXd& external_forces() const { return carried_.external_old; }
  /// Why the last step that failed did not converge (Newton's or the linear solver's words).
  const std::string& last_failure() const { return problem_.failure(); }
  /// Energy balance as of the last accepted step (all zero before the first).
  const EnergyRecord& energy() const { return energy_.record(); }
  void restart_energy_balance();  // afresh at the current state (after a static preload, say)
  int accepted_steps() const { return carried_.accepted_steps; }
  const NewtonReport& last_newton_report() const { return newton_.last_report(); }
  Assembler& assembler() { return assembler_; }
  /// The solver of the Newton iterations (KLU by default).
  LinearSolver& linear_solver() { return solvers_.solver(); }
  /// Solves with the RingSolver (ring_solver.hpp) over ring_nodes in ring order (a tire's
  /// tread), border_nodes coupled to everything (its spindle, marked with
  /// Model::condense_node). A tangent pattern that does not fit throws ModelError now, or
  /// before the next step after a change of structure.
  void use_ring_solver(std::vector<int> ring_nodes, std::vector<int> border_nodes);
  /// The same whenever the pattern fits (checked at every change), KLU otherwise.
  void prefer_ring_solver(std::vector<int> ring_nodes, std::vector<int> border_nodes);
  RingSolver* ring_solver() { return solvers_.ring_solver(); }

  /// Driven DOFs (docs/spindle.md): free DOFs whose displacements at the end of each step
  /// a host gives through driven_stepper(); at most one node's, dynamic integrators only.
  /// An empty list ends the driving.
  void drive_dofs(std::vector<int> dofs);
  /// The host's steps, the analysis started first if its conditions changed.
  DrivenStepper& driven_stepper();

  void add_step_observer(std::function<void(const Analysis&, const StepRecord&)> observer) {
    controller_.add_observer(
        [this, observer = std::move(observer)](const StepRecord& record) { observer(*this, record); });
  }
  /// Runs after every observer of an accepted step (a checkpoint: the step's output is complete then).
  void set_step_end_hook(std::function<void(Analysis&, const StepRecord&)> hook) {
    controller_.set_closing_observer([this, hook = std::move(hook)](const StepRecord& record) { hook(*this, record); });
  }

 private:
  void start_steps();
  void update_committed_reactions();
  Eigen::VectorXd& initial_field(Eigen::VectorXd State::*field, const char* what);
  // SteppedSystem
  double time() const override { return carried_.state.time; }
  bool try_step(double step, double end_time, StepRecord& record) override;
  void commit_step(double step, StepRecord& record) override { problem_.commit(step, energy_, record); }
  std::string failure_message(int cuts, double step) const override;

  Model& model_;
  Assembler assembler_;
  SolverChoice solvers_;
  NewtonSolver newton_;
  Integrator integrator_ = Integrator::quasi_static();
  std::ostream* log_ = nullptr;
  CarriedState carried_;
  StepController controller_{carried_.steps};
  EnergyBalance energy_{model_, carried_};
  DrivenDofs driven_;
  StepProblem problem_{model_, assembler_, solvers_, integrator_, carried_, driven_};
  DrivenStepper stepper_{problem_, driven_, newton_, controller_, energy_, log_};
};

}  // namespace tirefe
