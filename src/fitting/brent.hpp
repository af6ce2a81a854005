// One-parameter minimisation: bracketing, then Brent's method; and the one-parameter fit
// built on it.
//
// Bracketing (in the search coordinate x, within [lower, upper]): from x0 a first step to
// x0 + step (the other way if the objective rises), then downhill steps of 1.618 times the
// distance travelled from x0 (the first one first_growth times) until the objective rises
// again. The result is a triple a < b < c (or reversed) with f(b) <= f(a), f(c); a triple
// much wider on one side of b is narrowed by one point mirroring the near side. A step
// that would cross a bound stops on it; if the objective still falls at the bound (checked
// by one point just inside), the minimum is on the bound.
//
// Brent's method (R. P. Brent, Algorithms for Minimization without Derivatives, 1973,
// ch. 5) then shrinks the bracket, keeping the best point x, the second best w and the
// previous w, v. Each step fits a parabola through (v, w, x) and accepts its vertex
//     u = x - 1/2 [(x-w)^2 (f(x)-f(v)) - (x-v)^2 (f(x)-f(w))] / [(x-w)(f(x)-f(v)) - (x-v)(f(x)-f(w))]
// if it lies inside the bracket and moves less than half the step before last; otherwise
// it takes a golden-section step into the larger part of the bracket. It stops when the
// bracket around x is within +-tolerance(x), so the minimiser is within tolerance(x) of x.
// Parabolic steps make the convergence superlinear on smooth functions.
#pragma once

#include <functional>
#include <limits>

#include "fitting/fit_problem.hpp"

namespace tirefe::fitting {

struct ScalarSearch {
  std::function<double(double)> function;  // +infinity or NaN: a failed evaluation
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  std::function<double(double)> tolerance;  // absolute, at x
  int max_evaluations = 100;
  /// How far beyond a successful first step the bracket looks, as a multiple of that step:
  /// the golden ratio for a blind first step, less when the step estimates the minimum
  /// (a probe just beyond it then closes the bracket).
  double first_growth = 1.618033988749895;
  /// After each evaluation: the step kind (bracket, parabolic, golden) and the best point so far.
  std::function<void(const char* step, double x, double f)> on_step;
};

struct ScalarMinimum {
  enum class Outcome { Converged, AtBound, MaxEvaluations };
  double x = 0.0, f = 0.0;
  int evaluations = 0;
  Outcome outcome = Outcome::MaxEvaluations;
};

/// Minimises search.function from x0 (f0 = f(x0) if known, else NaN) with a first step of
/// 'step' (its sign is the first direction tried).
ScalarMinimum minimize_scalar(const ScalarSearch& search, double x0, double step,
                              double f0 = std::numeric_limits<double>::quiet_NaN());

/// The one-parameter fit: minimise S over z. The first step is the Gauss-Newton step
/// dp = -J^T r / J^T J from a finite-difference derivative at the initial value (which
/// also checks identifiability), limited to a factor 10 for log parameters.
FitResult fit_brent(const FitProblem& problem, const FitOptions& options);

}  // namespace tirefe::fitting
