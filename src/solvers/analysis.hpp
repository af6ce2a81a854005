// Analysis: the solution driver of one model. It advances time (or the load level,
// quasi-statically) in steps, solves each step with Newton, commits the state and
// the element history on success, and on failure reverts, cuts the step and retries.
// Steps grow back after easy convergence. Observers hear of every accepted step
// (output writers, logs).
#pragma once

#include <functional>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/assembler.hpp"
#include "core/model.hpp"
#include "solvers/integrator.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/newton.hpp"

namespace tirefe {

/// Raised when a step cannot be completed even after the allowed cuts.
class StepFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StepControl {
  double min_step = 0.0;     // 0: no lower bound beyond max_cuts
  double max_step = 0.0;     // 0: the nominal step
  int max_cuts = 10;         // consecutive halvings of one step
  int easy_iterations = 4;   // grow the step after converging in this many iterations or fewer
  double growth = 2.0;       // growth factor back toward the nominal step
};

struct StepRecord {
  int step = 0;           // accepted steps since the start
  double time = 0.0;      // at the end of the step
  double step_size = 0.0;
  int newton_iterations = 0;
  int cuts = 0;           // cuts taken before this step converged
  double residual = 0.0;  // final |R|
};

class Analysis : private StepEquations {
 public:
  explicit Analysis(Model& model);

  Model& model() { return model_; }
  const Model& model() const { return model_; }
  void set_integrator(const Integrator& integrator);
  const Integrator& integrator() const { return integrator_; }
  void set_time_step(double step);
  double time_step() const { return nominal_step_; }
  NewtonSettings& newton_settings() { return newton_.settings(); }
  StepControl& step_control() { return control_; }
  void set_log(std::ostream* log);

  /// Advances by 'duration' (default: one nominal step) in as many accepted steps as
  /// it takes; returns the records of the accepted steps. Throws StepFailure.
  const std::vector<StepRecord>& advance(double duration = 0.0);

  /// Solves M a = F - f_int - C v for the accelerations at the current time.
  void initialize_acceleration();

  const State& state() const { return committed_; }
  State& mutable_state() { return committed_; }
  /// Reactions at prescribed DOFs (zero elsewhere), from the last converged step.
  const Eigen::VectorXd& reactions() const { return reactions_; }
  const Eigen::VectorXd& external_forces() const { return external_new_; }
  int accepted_steps() const { return accepted_steps_; }
  const NewtonReport& last_newton_report() const { return newton_.last_report(); }
  Assembler& assembler() { return assembler_; }
  KluSolver& linear_solver() { return linear_solver_; }

  void add_step_observer(std::function<void(const Analysis&, const StepRecord&)> observer) {
    observers_.push_back(std::move(observer));
  }

 private:
  void prepare();
  bool try_step(double step, StepRecord& record);
  void finish_step(double step);
  // StepEquations
  void evaluate(bool with_tangent, Eigen::VectorXd& free_residual, double& force_level) override;
  const SparseMatrix& tangent() const override { return assembler_.tangent(); }
  double apply_increment(const Eigen::VectorXd& increment) override;

  Model& model_;
  Assembler assembler_;
  KluSolver linear_solver_;
  NewtonSolver newton_;
  Integrator integrator_ = Integrator::quasi_static();
  StepControl control_;
  double nominal_step_ = 1.0;
  double current_step_ = 1.0;
  std::ostream* log_ = nullptr;
  std::string last_failure_;

  State committed_, trial_;
  Eigen::VectorXd residual_all_, external_new_, external_old_, old_internal_forces_, reactions_;
  bool old_forces_valid_ = false;
  bool acceleration_pending_ = false;
  int accepted_steps_ = 0;
  std::vector<StepRecord> records_;
  std::vector<std::function<void(const Analysis&, const StepRecord&)>> observers_;
};

}  // namespace tirefe
