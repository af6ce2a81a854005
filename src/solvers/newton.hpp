// NewtonSolver: full Newton-Raphson iterations on one step's equations.
//
// Convergence is judged on the normalised residual |R| / R_ref, where R_ref is the
// largest of the first residual (with the contacts the step began with held, where a
// contact block asks for it: node_contact.hpp), the external force and the reaction force
// levels of the step, or on an increment at round-off level. A NaN, a residual growing past
// divergence_ratio * R_ref, or running out of iterations throws ConvergenceFailure so
// that the driver can cut the step.
//
// Backtracking: from the line_search_from-th increment on, an increment that makes the
// residual grow, when the residual has not halved over the last two increments either, is
// halved (up to max_backtracks times) before the next solve. Contact nodes that open and
// close in turn otherwise trap full Newton in a two-cycle. A residual that grows while
// Newton converges (large rotations, a node landing) is left alone.
//
// The last evaluation: the tangent is only needed when another increment follows. When
// the last increment cut the residual so far that the same cut again would meet the
// tolerance (with a margin), the next evaluation is of the residual alone. If that one
// does not converge after all but the residual fell, one chord increment follows with the
// factors already made (once per solve: a factorisation saved, a cheap iteration spent);
// otherwise the same state is evaluated again with its tangent. The converged state meets
// the same tolerances as plain Newton's; StepEquations::wants_converged_tangent() keeps
// the tangent of the converged evaluation and plain Newton's iterates.
//
// The first evaluation: with the tangent, unless the equations expect their start to
// converge (StepEquations::start_expected_converged(): a trial moved by its linear
// response); then the residual alone, and the same state again with the tangent if it
// does not converge. NewtonSettings::residual_only_when_converging turns off both.
//
// A step budget (real-time hosts): once budget_iterations increments are taken, or after
// the first one once budget_time seconds of wall time have passed, the solve ends at the
// state just evaluated when its residual is within budget_residual (NewtonReport::converged
// false, its residual reported); above that it goes on as plain Newton does. An
// unconverged state's error feeds the next step's accelerations (over h^2): the bound keeps
// it small enough that it dies out rather than grows.
#pragma once

#include <Eigen/Dense>
#include <iosfwd>
#include <stdexcept>
#include <vector>

#include "core/assembler.hpp"
#include "solvers/linear_solver.hpp"

namespace tirefe {

class ConvergenceFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct NewtonSettings {
  int max_iterations = 25;
  double residual_tolerance = 1e-9;    // on |R| / R_ref
  double increment_tolerance = 1e-13;  // on |du|_inf / (1 + |u|_inf): round-off level
  double divergence_ratio = 1e8;
  int line_search_from = 2;  // increments taken whole before backtracking starts
  int max_backtracks = 4;
  bool residual_only_when_converging = true;  // the last evaluation, or an expected start, without the tangent (above)
  int budget_iterations = 0;                  // a step budget (above); 0: none
  double budget_time = 0.0;                   // [s] of wall time per solve; 0: none
  double budget_residual = 1e-4;              // the largest |R|/R_ref a budget ends a solve with
  std::ostream* log = nullptr;                // per-iteration lines when set
};

struct NewtonReport {
  int iterations = 0;     // linear solves performed
  int backtracks = 0;     // halvings of an increment
  int residual_only = 0;  // evaluations of the residual alone (expected to converge)
  int retaken = 0;        // of those, the ones that did not converge: evaluated again with the tangent
  int chords = 0;         // increments with the last factors (after a residual-only evaluation)
  double reference_force = 0.0;
  bool converged = true;               // false: a step budget ended the solve unconverged
  double relative_residual = 0.0;      // |R| / R_ref of the last evaluation
  std::vector<double> residual_norms;  // |R| at each evaluation, the last one converged
};

/// The equations of one step, as the Newton loop sees them.
class StepEquations {
 public:
  virtual ~StepEquations() = default;
  /// Residual over the free equations at the current trial state (and the tangent,
  /// left in tangent(), when with_tangent); also returns the step's force level.
  virtual void evaluate(bool with_tangent, Eigen::VectorXd& free_residual, double& force_level) = 0;
  virtual const SparseMatrix& tangent() const = 0;
  /// Factors the last evaluation's tangent with 'solver' (throws SingularMatrix); equations
  /// that assembled it into the solver's own storage factor it there.
  virtual void factorize_tangent(LinearSolver& solver) { solver.factorize(tangent()); }
  /// Adds the increment of the free equations to the trial state; returns the
  /// relative increment size |du|_inf / (1 + |u|_inf).
  virtual double apply_increment(const Eigen::VectorXd& increment) = 0;
  /// True when the caller reads tangent() after convergence: it is then that of the converged state.
  virtual bool wants_converged_tangent() const { return false; }
  /// True when this solve starts from a state expected to meet the tolerance: its first
  /// evaluation assembles the residual alone (and is made again with the tangent if it
  /// does not converge after all).
  virtual bool start_expected_converged() const { return false; }
};

class NewtonSolver {
 public:
  explicit NewtonSolver(NewtonSettings settings = {}) : settings_(settings) {}
  NewtonSettings& settings() { return settings_; }
  const NewtonSettings& settings() const { return settings_; }

  /// Iterates to convergence; throws ConvergenceFailure. The report stays valid until the next call.
  const NewtonReport& solve(StepEquations& equations, LinearSolver& linear_solver);
  const NewtonReport& last_report() const { return report_; }

 private:
  NewtonSettings settings_;
  NewtonReport report_;
  Eigen::VectorXd residual_, increment_, step_back_;
};

}  // namespace tirefe
