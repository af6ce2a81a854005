#include "fitting/objective.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <set>

#include "fitting/format.hpp"

namespace tirefe::fitting {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::string number(double value) { return formatted("%.8g", value); }

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument(message);
}

void validate(const FitProblem& problem, const FitOptions& options) {
  require(!problem.parameters.empty(), "no parameters to fit");
  require(static_cast<bool>(problem.model), "no model to evaluate");
  std::set<std::string> names;
  for (const FitParameter& p : problem.parameters) {
    const std::string which = "parameter '" + p.name + "'";
    require(!p.name.empty(), "every parameter needs a name");
    require(names.insert(p.name).second, which + " is given twice");
    require(std::isfinite(p.initial), which + ": the initial value must be finite");
    require(p.lower < p.upper,
            which + ": lower (" + number(p.lower) + ") must be below upper (" + number(p.upper) + ")");
    require(p.initial >= p.lower && p.initial <= p.upper, which + ": the initial value " + number(p.initial) +
                                                              " is outside [" + number(p.lower) + ", " +
                                                              number(p.upper) + "]");
    require(!p.log || (p.initial > 0.0 && p.lower >= 0.0),
            which + ": a log parameter needs a positive initial value and a lower bound >= 0");
  }
  require(problem.data.size() > 0, "no data to fit");
  require(problem.data.allFinite(), "the data contain a value that is not finite");
  require(
      problem.weights.size() == 0 || problem.weights.size() == problem.data.size(),
      std::to_string(problem.weights.size()) + " weights for " + std::to_string(problem.data.size()) + " data points");
  require(problem.weights.size() == 0 || ((problem.weights.array() > 0.0).all() && problem.weights.allFinite()),
          "every weight must be positive and finite");
  require(options.tolerance > 0.0, "the tolerance must be positive");
  require(options.max_evaluations > 0, "max_evaluations must be positive");
  require(options.relative_step > 0.0, "the finite-difference step must be positive");
}

}  // namespace

Objective::Objective(const FitProblem& problem, const FitOptions& options, FitResult& result)
    : problem_(problem), options_(options), result_(result) {
  validate(problem, options);
  const int n = parameter_count();
  sqrt_weights_ = problem.weights.size() ? Eigen::VectorXd(problem.weights.cwiseSqrt())
                                         : Eigen::VectorXd::Ones(problem.data.size());
  data_norm_ = sqrt_weights_.cwiseProduct(problem.data).norm();
  lower_.resize(n);
  upper_.resize(n);
  typical_.resize(n);
  for (int j = 0; j < n; ++j) {
    const FitParameter& p = problem.parameters[j];
    lower_[j] = p.log ? (p.lower > 0.0 ? std::log(p.lower) : -kInfinity) : p.lower;
    upper_[j] = p.log ? std::log(p.upper) : p.upper;
    const double range = p.upper - p.lower;
    typical_[j] = p.initial != 0.0 ? std::abs(p.initial) : std::isfinite(range) ? range : 1.0;
  }
}

Eigen::VectorXd Objective::initial() const {
  Eigen::VectorXd z(parameter_count());
  for (int j = 0; j < z.size(); ++j) {
    const FitParameter& p = problem_.parameters[j];
    z[j] = p.log ? std::log(p.initial) : p.initial;
  }
  return z;
}

Eigen::VectorXd Objective::physical(const Eigen::VectorXd& z) const {
  Eigen::VectorXd values(z.size());
  for (int j = 0; j < z.size(); ++j) values[j] = problem_.parameters[j].log ? std::exp(z[j]) : z[j];
  return values;
}

Eigen::VectorXd Objective::clamp(const Eigen::VectorXd& z) const { return z.cwiseMax(lower_).cwiseMin(upper_); }

double Objective::scale(int j, double z_j) const {
  return problem_.parameters[j].log ? 1.0 : std::max(std::abs(z_j), 1e-3 * typical_[j]);
}

bool Objective::within_tolerance(const Eigen::VectorXd& step, const Eigen::VectorXd& z) const {
  for (int j = 0; j < step.size(); ++j)
    if (std::abs(step[j]) > options_.tolerance * scale(j, z[j])) return false;
  return true;
}

Objective::Outcome Objective::call_model(const Eigen::VectorXd& z) {
  ++evaluations_;
  Outcome outcome;
  Evaluation& evaluation = outcome.evaluation;
  try {
    evaluation.predictions = problem_.model(physical(z));
  } catch (const EvaluationError& failure) {
    outcome.failure = failure.what();
    return outcome;
  }
  if (evaluation.predictions.size() != problem_.data.size())
    throw std::invalid_argument("the model returned " + std::to_string(evaluation.predictions.size()) +
                                " predictions for " + std::to_string(problem_.data.size()) + " data points");
  if (!evaluation.predictions.allFinite()) {
    outcome.failure = "a prediction is not finite";
    return outcome;
  }
  evaluation.residuals = sqrt_weights_.cwiseProduct(evaluation.predictions - problem_.data);
  evaluation.objective = evaluation.residuals.squaredNorm();
  evaluation.ok = true;
  return outcome;
}

Objective::Evaluation Objective::evaluate(const Eigen::VectorXd& z) {
  Outcome outcome = call_model(z);
  if (!outcome.evaluation.ok)
    note("evaluation " + std::to_string(evaluations_) + " failed at " + describe(z) + ": " + outcome.failure);
  return outcome.evaluation;
}

Objective::Evaluation Objective::evaluate_initial(const Eigen::VectorXd& z) {
  Outcome outcome = call_model(z);
  if (!outcome.evaluation.ok)
    throw EvaluationError("the model failed at the initial parameters (" + describe(z) + "): " + outcome.failure);
  return outcome.evaluation;
}

Eigen::MatrixXd Objective::jacobian(const Eigen::VectorXd& z, const Evaluation& at) {
  const int n = parameter_count();
  Eigen::MatrixXd jacobian(data_count(), n);
  for (int j = 0; j < n; ++j) {
    const double h = options_.relative_step * scale(j, z[j]);
    // Residuals at z + s h e_j, with the side flipped if it leaves the box or fails.
    auto shifted = [&](double side) {
      Eigen::VectorXd moved = z;
      moved[j] += side * h;
      if (moved[j] > upper_[j] || moved[j] < lower_[j]) return Evaluation{};
      return evaluate(moved);
    };
    const bool central = options_.differences == FiniteDifference::Central;
    Evaluation plus = shifted(1.0), minus;
    if (central || !plus.ok) minus = shifted(-1.0);
    if (central && plus.ok && minus.ok)
      jacobian.col(j) = (plus.residuals - minus.residuals) / (2.0 * h);
    else if (plus.ok)
      jacobian.col(j) = (plus.residuals - at.residuals) / h;
    else if (minus.ok)
      jacobian.col(j) = (at.residuals - minus.residuals) / h;
    else
      throw EvaluationError("the model failed on both sides of " + describe(z) + " while differentiating by '" +
                            problem_.parameters[j].name + "'");
  }
  return jacobian;
}

Assessment Objective::assess(const Eigen::VectorXd& z, const Evaluation& at, const Eigen::MatrixXd& jacobian_z,
                             const std::vector<bool>& free) const {
  // dr/dp = dr/dz dz/dp, with dz/dp = 1/p for log parameters.
  const Eigen::VectorXd values = physical(z);
  Eigen::MatrixXd jacobian_p = jacobian_z;
  Eigen::VectorXd scales(parameter_count());
  std::vector<std::string> names;
  for (int j = 0; j < parameter_count(); ++j) {
    const bool log = problem_.parameters[j].log;
    if (log) jacobian_p.col(j) /= values[j];
    scales[j] = log ? values[j] : scale(j, z[j]);
    names.push_back(problem_.parameters[j].name);
  }
  return assess_estimate(jacobian_p, at.residuals, scales, data_norm_, free, names,
                         {options_.sensitivity_threshold, options_.max_condition});
}

std::string Objective::describe(const Eigen::VectorXd& z) const {
  const Eigen::VectorXd values = physical(z);
  std::string out;
  for (int j = 0; j < values.size(); ++j)
    out += (j ? ", " : "") + problem_.parameters[j].name + " = " + number(values[j]);
  return out;
}

void Objective::record(const Eigen::VectorXd& z, double objective, const std::string& step, double damping) {
  FitIteration iteration;
  iteration.iteration = static_cast<int>(result_.history.size());
  iteration.evaluations = evaluations_;
  iteration.values = physical(z);
  iteration.objective = objective;
  iteration.damping = damping;
  iteration.step = step;
  result_.history.push_back(iteration);
  result_.iterations = iteration.iteration;
  if (options_.log) {
    char text[96];
    std::snprintf(text, sizeof text, "  fit %3d  evaluations %3d  S = %-14.8e", iteration.iteration,
                  iteration.evaluations, objective);
    *options_.log << text << "  " << describe(z);
    if (std::isfinite(damping)) {
      std::snprintf(text, sizeof text, "  (lambda %.1e)", damping);
      *options_.log << text;
    } else {
      *options_.log << "  (" << step << ")";
    }
    *options_.log << "\n";
  }
  if (options_.on_iteration) options_.on_iteration(iteration);
}

void Objective::note(const std::string& line) const {
  if (options_.log) *options_.log << "  fit      " << line << "\n";
}

void Objective::finish(const Eigen::VectorXd& z, const Evaluation& at, const Assessment& assessment, FitStatus status,
                       const std::string& message, bool fitted) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  result_.values = fitted ? physical(z) : Eigen::VectorXd::Constant(z.size(), kNaN);
  result_.prediction = at.predictions;
  result_.objective = at.objective;
  result_.evaluations = evaluations_;
  result_.standard_errors = assessment.standard_errors;
  result_.correlation = assessment.correlation;
  result_.condition_number = assessment.condition_number;
  result_.status = status;
  result_.message = message;
  result_.not_identifiable.clear();
  if (!assessment.identifiable) {
    result_.status = FitStatus::NotIdentifiable;
    result_.message = assessment.reason + (fitted ? "" : "; nothing was fitted");
    for (int j : assessment.not_identifiable) {
      result_.values[j] = kNaN;
      result_.not_identifiable.push_back(problem_.parameters[j].name);
    }
  }
  if (options_.log) {
    *options_.log << "  fit " << status_name(result_.status) << " after " << evaluations_ << " evaluations: ";
    for (int j = 0; j < result_.values.size(); ++j) {
      *options_.log << (j ? ", " : "") << problem_.parameters[j].name << " = " << number(result_.values[j]);
      if (std::isfinite(result_.standard_errors[j])) *options_.log << " +- " << number(result_.standard_errors[j]);
    }
    *options_.log << " (S = " << number(result_.objective) << ")\n";
    if (!result_.message.empty()) *options_.log << "  fit " << result_.message << "\n";
  }
}

}  // namespace tirefe::fitting
