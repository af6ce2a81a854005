// Parameter fitting by weighted least squares: the problem, the options and the result
// shared by the one-parameter Brent search and the Levenberg-Marquardt method.
//
// A model maps parameter values p (n of them) to predictions f(p) of m measured values y.
// The fit minimises the weighted sum of squared residuals
//
//     S(p) = sum_i w_i (f_i(p) - y_i)^2 = |r(p)|^2,   r_i = sqrt(w_i) (f_i(p) - y_i),
//
// with lower <= p <= upper. Positive parameters such as stiffnesses can be searched in
// log space (z = ln p): steps and tolerances are then relative, and p stays positive.
// At the solution the covariance of the estimate is the usual linearised one,
//
//     Cov(p) = s^2 (J^T J)^-1,   s^2 = S / (m - n),   J_ij = d r_i / d p_j,
//
// giving standard errors sqrt(Cov_jj) and correlations Cov_ij / (se_i se_j). The weights
// are relative: the residual variance s^2 is estimated from the fit itself.
//
// A fit refuses to return a meaningless number: with fewer data than parameters, with
// predictions that do not change when a parameter does, or with parameters that only act
// through a combination the data cannot split (a numerically singular J^T J), the status
// is NotIdentifiable and the message names the parameters and the reason.
#pragma once

#include <Eigen/Dense>

#include <functional>
#include <iosfwd>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace tirefe::fitting {

/// Thrown by a model that could not be evaluated at some parameter values (a simulation
/// that did not converge, say). The optimisers treat such a point as infinitely bad and
/// step back; at the initial parameters it ends the fit.
class EvaluationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FitParameter {
  std::string name;
  double initial = 0.0;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool log = false;  // search ln(value): relative steps, value kept positive
};

/// Predictions for the given parameter values (same order as FitProblem::parameters).
using PredictionModel = std::function<Eigen::VectorXd(const Eigen::VectorXd& values)>;

struct FitProblem {
  std::vector<FitParameter> parameters;
  PredictionModel model;
  Eigen::VectorXd data;     // measured values y
  Eigen::VectorXd weights;  // w, relative; empty: all 1
};

enum class FitMethod { Automatic /* Brent for one parameter */, Brent, LevenbergMarquardt };
enum class FiniteDifference { Forward, Central };

enum class FitStatus {
  Converged,        // the parameters changed by less than the tolerance
  AtBound,          // converged with a parameter on a bound (the data want a value beyond it)
  NotIdentifiable,  // the data cannot determine a parameter (see FitResult::not_identifiable)
  MaxEvaluations,   // the evaluation budget ran out first
};

/// "converged", "at_bound", "not_identifiable", "max_evaluations".
const char* status_name(FitStatus status);
/// "brent", "levenberg_marquardt" (Automatic resolved by the parameter count).
const char* method_name(FitMethod method, int parameter_count);

/// One iteration: the current parameter values (the best point for Brent) and objective.
struct FitIteration {
  int iteration = 0;
  int evaluations = 0;  // model evaluations so far
  Eigen::VectorXd values;
  double objective = 0.0;
  double damping = std::numeric_limits<double>::quiet_NaN();  // Levenberg-Marquardt lambda
  std::string step;  // initial, bracket, parabolic, golden, levenberg_marquardt
};

struct FitOptions {
  FitMethod method = FitMethod::Automatic;
  double tolerance = 1e-6;  // relative change of every parameter at which the fit stops
  int max_evaluations = 100;
  FiniteDifference differences = FiniteDifference::Forward;
  double relative_step = 1e-6;  // finite-difference step relative to the parameter
  // A parameter whose 100 % change moves the weighted predictions by less than this
  // fraction of |sqrt(w) y| is not identifiable.
  double sensitivity_threshold = 1e-6;
  // Largest condition number of the column-scaled J^T J (the correlation structure).
  double max_condition = 1e10;
  double initial_damping = 1e-3;  // Levenberg-Marquardt lambda, relative to diag(J^T J)
  std::ostream* log = nullptr;    // one line per iteration
  std::function<void(const FitIteration&)> on_iteration;
};

struct FitResult {
  FitStatus status = FitStatus::MaxEvaluations;
  std::string message;
  std::string method;
  Eigen::VectorXd values;                                       // NaN for parameters that are not identifiable
  double objective = std::numeric_limits<double>::quiet_NaN();  // S at values
  int evaluations = 0;
  int iterations = 0;
  Eigen::VectorXd standard_errors;  // NaN where not available (m == n, at a bound, ...)
  Eigen::MatrixXd correlation;
  Eigen::VectorXd prediction;  // f at values (empty if never evaluated)
  std::vector<std::string> not_identifiable;
  double condition_number = std::numeric_limits<double>::quiet_NaN();  // of the scaled J^T J
  std::vector<FitIteration> history;
};

/// Fits the problem. Throws std::invalid_argument for an inconsistent problem (bounds,
/// sizes, a model returning the wrong number of predictions) and EvaluationError when the
/// model fails at the initial parameters; every other outcome is a status of the result.
FitResult fit(const FitProblem& problem, const FitOptions& options = {});

}  // namespace tirefe::fitting
