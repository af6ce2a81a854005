#include "fitting/levenberg_marquardt.hpp"

#include <algorithm>
#include <cmath>

#include "fitting/format.hpp"
#include "fitting/objective.hpp"

namespace tirefe::fitting {

namespace {

/// Parameters not held on a bound: a parameter on a bound stays free only if the descent
/// direction -J^T r points into the box.
std::vector<bool> free_parameters(const Objective& objective, const Eigen::VectorXd& z,
                                  const Eigen::VectorXd& gradient) {
  std::vector<bool> free(z.size());
  for (int j = 0; j < z.size(); ++j)
    free[j] =
        !((objective.on_lower(j, z[j]) && gradient[j] > 0.0) || (objective.on_upper(j, z[j]) && gradient[j] < 0.0));
  return free;
}

/// Solves (A + lambda diag(A)) dz = -g over the free parameters; held ones get 0.
Eigen::VectorXd damped_step(const Eigen::MatrixXd& normal, const Eigen::VectorXd& gradient, double lambda,
                            const std::vector<bool>& free) {
  std::vector<int> index;
  for (int j = 0; j < gradient.size(); ++j)
    if (free[j]) index.push_back(j);
  Eigen::VectorXd step = Eigen::VectorXd::Zero(gradient.size());
  if (index.empty()) return step;
  const int k = static_cast<int>(index.size());
  Eigen::MatrixXd system(k, k);
  Eigen::VectorXd right(k);
  for (int a = 0; a < k; ++a) {
    right[a] = -gradient[index[a]];
    for (int b = 0; b < k; ++b) system(a, b) = normal(index[a], index[b]);
  }
  // A floor on the scaling keeps the system positive definite if a column is nearly zero.
  const double floor = 1e-12 * system.diagonal().maxCoeff();
  for (int a = 0; a < k; ++a) system(a, a) += lambda * std::max(system(a, a), floor);
  const Eigen::VectorXd solved = system.ldlt().solve(right);
  for (int a = 0; a < k; ++a) step[index[a]] = solved[a];
  return step;
}

}  // namespace

FitResult fit_levenberg_marquardt(const FitProblem& problem, const FitOptions& options) {
  FitResult result;
  result.method = "levenberg_marquardt";
  Objective objective(problem, options, result);
  const int n = objective.parameter_count(), m = objective.data_count();
  Eigen::VectorXd z = objective.initial();

  if (m < n) {  // decided before spending any evaluation
    Assessment assessment = unassessed(n);
    assessment.identifiable = false;
    for (int j = 0; j < n; ++j) assessment.not_identifiable.push_back(j);
    assessment.reason = std::to_string(m) + " data point" + (m == 1 ? "" : "s") + " cannot determine " +
                        std::to_string(n) + " parameters";
    Objective::Evaluation none;
    none.objective = std::numeric_limits<double>::quiet_NaN();
    objective.finish(z, none, assessment, FitStatus::NotIdentifiable, "", false);
    return result;
  }

  Objective::Evaluation at = objective.evaluate_initial(z);
  objective.record(z, at.objective, "initial");
  Eigen::MatrixXd jacobian = objective.jacobian(z, at);
  const Assessment initial = objective.assess(z, at, jacobian, std::vector<bool>(n, true));
  if (!initial.identifiable) {
    objective.finish(z, at, initial, FitStatus::NotIdentifiable, "", false);
    return result;
  }

  double lambda = options.initial_damping, growth = 2.0;
  FitStatus status = FitStatus::Converged;
  std::string message;
  for (;;) {
    const Eigen::VectorXd gradient = jacobian.transpose() * at.residuals;
    const std::vector<bool> free = free_parameters(objective, z, gradient);
    const Eigen::VectorXd trial =
        objective.clamp(z + damped_step(jacobian.transpose() * jacobian, gradient, lambda, free));
    const Eigen::VectorXd step = trial - z;
    if (objective.within_tolerance(step, z)) break;
    if (objective.exhausted()) {
      status = FitStatus::MaxEvaluations;
      message = "no convergence within " + std::to_string(options.max_evaluations) + " evaluations";
      break;
    }
    Objective::Evaluation next = objective.evaluate(trial);
    if (next.objective < at.objective) {
      const double predicted = at.objective - (at.residuals + jacobian * step).squaredNorm();
      const double ratio = predicted > 0.0 ? (at.objective - next.objective) / predicted : 0.0;
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * ratio - 1.0, 3));
      growth = 2.0;
      z = trial;
      at = next;
      jacobian = objective.jacobian(z, at);
      objective.record(z, at.objective, "levenberg_marquardt", lambda);
    } else {
      objective.note("step to " + objective.describe(trial) + " rejected (S = " + formatted("%.8e", next.objective) +
                     "), lambda " + formatted("%.1e", lambda) + " -> " + formatted("%.1e", lambda * growth));
      lambda *= growth;
      growth *= 2.0;
    }
  }

  const std::vector<bool> free = free_parameters(objective, z, jacobian.transpose() * at.residuals);
  std::string held;
  for (int j = 0; j < n; ++j)
    if (!free[j])
      held += (held.empty() ? "'" : ", '") + problem.parameters[j].name + "' (" +
              (objective.on_lower(j, z[j]) ? "lower" : "upper") + ")";
  if (!held.empty() && status == FitStatus::Converged) {
    status = FitStatus::AtBound;
    message = "the best fit holds " + held + " on a bound (the objective still falls there)";
  }
  objective.finish(z, at, objective.assess(z, at, jacobian, free), status, message);
  return result;
}

}  // namespace tirefe::fitting
