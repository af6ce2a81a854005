#include "io/fit_file.hpp"

#include "io/hdf5_file.hpp"
#include "tirefe/version.hpp"

namespace tirefe::io {

namespace {

std::vector<double> to_std(const Eigen::VectorXd& values) { return {values.data(), values.data() + values.size()}; }

}  // namespace

void write_fit_file(const std::string& path, const fitting::FitProblem& problem, const fitting::FitResult& result,
                    const FitAxes& axes, const std::string& deck_path) {
  Hdf5File file = Hdf5File::create(path);
  file.write_attribute("/", "tirefe_version", std::string(kVersion));
  file.write_attribute("/", "git_commit", std::string(kGitCommit));
  file.write_attribute("/", "deck_path", deck_path);
  file.write_attribute("/", "method", result.method);
  file.write_attribute("/", "status", std::string(fitting::status_name(result.status)));
  file.write_attribute("/", "message", result.message);
  file.write_attribute("/", "objective", result.objective);
  file.write_attribute("/", "evaluations", result.evaluations);
  file.write_attribute("/", "iterations", result.iterations);

  const size_t n = problem.parameters.size();
  std::vector<std::string> names;
  std::vector<double> initial, lower, upper;
  std::vector<long long> log;
  for (const fitting::FitParameter& p : problem.parameters) {
    names.push_back(p.name);
    initial.push_back(p.initial);
    lower.push_back(p.lower);
    upper.push_back(p.upper);
    log.push_back(p.log ? 1 : 0);
  }
  file.write_strings("/fit/parameters/name", names);
  file.write_vector("/fit/parameters/initial", initial);
  file.write_vector("/fit/parameters/lower", lower);
  file.write_vector("/fit/parameters/upper", upper);
  file.write_int_vector("/fit/parameters/log", log);
  file.write_vector("/fit/parameters/value", to_std(result.values));
  file.write_vector("/fit/parameters/standard_error", to_std(result.standard_errors));
  file.write_matrix("/fit/correlation", result.correlation);

  file.write_vector("/fit/data", to_std(problem.data));
  file.write_attribute("/fit/data", "label", axes.data_label);
  if (!axes.data_unit.empty()) file.write_attribute("/fit/data", "file_unit", axes.data_unit);
  file.write_attribute("/fit/data", "to_si", axes.data_to_si);
  file.write_vector("/fit/weights", to_std(problem.weights.size() ? problem.weights
                                                                  : Eigen::VectorXd::Ones(problem.data.size()).eval()));
  file.write_vector("/fit/prediction", to_std(result.prediction));
  if (axes.x.size()) {
    file.write_vector("/fit/x", to_std(axes.x));
    file.write_attribute("/fit/x", "label", axes.x_label);
    if (!axes.x_unit.empty()) file.write_attribute("/fit/x", "file_unit", axes.x_unit);
    file.write_attribute("/fit/x", "to_si", axes.x_to_si);
  }
  if (axes.curve_x.size()) {
    file.write_vector("/fit/curve/x", to_std(axes.curve_x));
    file.write_vector("/fit/curve/prediction", to_std(axes.curve_prediction));
  }

  const size_t rows = result.history.size();
  std::vector<long long> iteration, evaluations;
  std::vector<double> objective, damping;
  std::vector<std::string> step;
  Eigen::MatrixXd values(rows, n);
  for (size_t i = 0; i < rows; ++i) {
    const fitting::FitIteration& record = result.history[i];
    iteration.push_back(record.iteration);
    evaluations.push_back(record.evaluations);
    objective.push_back(record.objective);
    damping.push_back(record.damping);
    step.push_back(record.step);
    values.row(static_cast<Eigen::Index>(i)) = record.values.transpose();
  }
  file.write_int_vector("/fit/history/iteration", iteration);
  file.write_int_vector("/fit/history/evaluations", evaluations);
  file.write_vector("/fit/history/objective", objective);
  file.write_vector("/fit/history/damping", damping);
  file.write_strings("/fit/history/step", step);
  file.write_matrix("/fit/history/values", values);
  file.flush();
}

}  // namespace tirefe::io
