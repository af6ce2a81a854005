#include "solvers/newton.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

namespace tirefe {

namespace {
std::string format_norms(int iteration, double norm, double relative, double increment) {
  char line[128];
  std::snprintf(line, sizeof line, "    newton %2d  |R| %.3e  |R|/Rref %.3e  |du| %.2e\n", iteration, norm, relative,
                increment);
  return line;
}

// The next residual, relative, if the last increment's reduction repeats; the next
// evaluation skips the tangent when it is below this multiple of the tolerance. Full
// Newton's reduction grows from increment to increment, so the guess errs on the safe
// side; on the drum-cleat deck 3 skips the tangent in nine steps out of ten and
// re-evaluates in one step out of forty.
constexpr double kConvergingMargin = 3.0;
}  // namespace

const NewtonReport& NewtonSolver::solve(StepEquations& equations, LinearSolver& linear_solver) {
  report_.iterations = 0;
  report_.backtracks = 0;
  report_.residual_only = 0;
  report_.retaken = 0;
  report_.chords = 0;
  report_.converged = true;
  report_.residual_norms.clear();
  report_.residual_norms.reserve(settings_.max_iterations * (settings_.max_backtracks + 1) + 1);
  double relative_increment = 0.0;
  double previous_norm = 0.0;  // at the start of the current increment
  double norm_two_back = 0.0;  // at the start of the one before
  double step_fraction = 1.0;  // of the current increment applied so far
  int halvings = 0;
  bool with_tangent = !(settings_.residual_only_when_converging && equations.start_expected_converged());
  bool chord_taken = false;  // in this solve
  const bool may_skip_tangent = settings_.residual_only_when_converging && !equations.wants_converged_tangent();
  using Clock = std::chrono::steady_clock;
  const bool timed = settings_.budget_time > 0.0;
  const Clock::time_point start = timed ? Clock::now() : Clock::time_point{};
  auto budget_spent = [&] {
    return (settings_.budget_iterations > 0 && report_.iterations >= settings_.budget_iterations) ||
           (timed && report_.iterations >= 1 &&
            std::chrono::duration<double>(Clock::now() - start).count() > settings_.budget_time);
  };
  for (;;) {
    double force_level = 0.0;
    equations.evaluate(with_tangent, residual_, force_level);
    if (!with_tangent) ++report_.residual_only;
    const double norm = residual_.norm();
    report_.residual_norms.push_back(norm);
    if (report_.iterations == 0) report_.reference_force = std::max({norm, force_level, 1e-300});
    const double relative = norm / report_.reference_force;
    report_.relative_residual = relative;
    if (settings_.log) *settings_.log << format_norms(report_.iterations, norm, relative, relative_increment);

    const bool converged = relative <= settings_.residual_tolerance ||
                           (report_.iterations > 0 && relative_increment <= settings_.increment_tolerance);
    // A cycle: the residual grows and has not halved over the last two increments.
    const bool cycling =
        report_.iterations >= settings_.line_search_from && !(norm < previous_norm) && !(norm < 0.5 * norm_two_back);
    if (!converged && cycling && halvings < settings_.max_backtracks) {
      // Back along the increment to half the fraction applied.
      step_back_ = -0.5 * step_fraction * increment_;  // no allocation once sized
      relative_increment = equations.apply_increment(step_back_);
      step_fraction *= 0.5;
      ++halvings;
      ++report_.backtracks;
      with_tangent = true;
      continue;
    }
    if (!std::isfinite(norm))
      throw ConvergenceFailure("the residual is not finite (NaN or infinity) at Newton iteration " +
                               std::to_string(report_.iterations));
    if (converged) return report_;
    if (relative > settings_.divergence_ratio)
      throw ConvergenceFailure("Newton iterations diverge (|R|/Rref = " + std::to_string(relative) + " at iteration " +
                               std::to_string(report_.iterations) + ")");
    if (relative <= settings_.budget_residual && budget_spent()) {
      report_.converged = false;  // the budget is spent: this state, its residual reported
      return report_;
    }
    if (report_.iterations == settings_.max_iterations)
      throw ConvergenceFailure("no convergence in " + std::to_string(settings_.max_iterations) +
                               " Newton iterations (|R|/Rref = " + std::to_string(relative) + ")");

    // Not converged after all, but closer: once per solve, a chord increment with the
    // last factors; otherwise the tangent of this same state.
    const bool chord = !with_tangent && !chord_taken && norm < previous_norm;
    if (!chord) {
      if (!with_tangent) {
        equations.evaluate(true, residual_, force_level);
        ++report_.retaken;
      }
      try {
        equations.factorize_tangent(linear_solver);
      } catch (const SingularMatrix& singular) {
        throw ConvergenceFailure(singular.what());
      }
    }
    increment_ = -residual_;
    linear_solver.solve(increment_);
    if (!increment_.allFinite())
      throw ConvergenceFailure("the Newton increment is not finite at iteration " + std::to_string(report_.iterations));
    norm_two_back = previous_norm;
    previous_norm = norm;
    step_fraction = 1.0;
    halvings = 0;
    relative_increment = equations.apply_increment(increment_);
    ++report_.iterations;
    if (chord) {
      ++report_.chords;
      chord_taken = true;
      with_tangent = false;
      continue;
    }
    // The reduction of this increment's start over the last one's, repeated.
    with_tangent =
        !(may_skip_tangent && report_.iterations >= 2 && norm < norm_two_back &&
          norm * (norm / norm_two_back) < kConvergingMargin * settings_.residual_tolerance * report_.reference_force);
  }
}

}  // namespace tirefe
