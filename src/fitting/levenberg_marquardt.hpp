// Levenberg-Marquardt fit of several parameters (Marquardt 1963, with Nielsen's damping
// update, H. B. Nielsen, IMM-REP-1999-05).
//
// In internal coordinates z (objective.hpp) with weighted residuals r(z), S = |r|^2 and a
// finite-difference Jacobian J = dr/dz, each iteration solves the damped normal equations
//
//     (J^T J + lambda diag(J^T J)) dz = -J^T r
//
// over the free parameters (a parameter on a bound whose descent direction points out
// of the box is held there for the iteration), clamps z + dz into the box and evaluates it.
// With the gain ratio rho = (S(z) - S(z + dz)) / (S(z) - |r + J dz|^2) of actual to
// predicted decrease:
//   - S decreased: accept, lambda *= max(1/3, 1 - (2 rho - 1)^3), nu = 2, new J;
//   - otherwise: reject, lambda *= nu, nu *= 2 (towards short gradient steps).
// Small lambda is Gauss-Newton (fast near the solution), large lambda a short scaled
// gradient step (safe far from it); diag(J^T J) makes the damping independent of units.
// The fit has converged when a proposed step changes every parameter by less than the
// tolerance (relative; for log parameters |dz| = |dp|/p). Identifiability is checked at
// the initial parameters, before any iteration, and again at the solution.
#pragma once

#include "fitting/fit_problem.hpp"

namespace tirefe::fitting {

FitResult fit_levenberg_marquardt(const FitProblem& problem, const FitOptions& options);

}  // namespace tirefe::fitting
