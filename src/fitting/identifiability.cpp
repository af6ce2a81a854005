#include "fitting/identifiability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fitting/format.hpp"

namespace tirefe::fitting {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string quoted_list(const std::vector<int>& indices, const std::vector<std::string>& names) {
  std::string out;
  for (size_t k = 0; k < indices.size(); ++k) {
    if (k > 0) out += k + 1 == indices.size() ? " and " : ", ";
    out += "'" + names[indices[k]] + "'";
  }
  return out;
}

}  // namespace

Assessment unassessed(int parameter_count) {
  Assessment assessment;
  assessment.condition_number = kNaN;
  assessment.standard_errors = Eigen::VectorXd::Constant(parameter_count, kNaN);
  assessment.correlation = Eigen::MatrixXd::Constant(parameter_count, parameter_count, kNaN);
  return assessment;
}

Assessment assess_estimate(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                           const Eigen::VectorXd& parameter_scales, double data_norm, const std::vector<bool>& free,
                           const std::vector<std::string>& names, const AssessmentLimits& limits) {
  const int m = static_cast<int>(jacobian.rows()), n = static_cast<int>(jacobian.cols());
  Assessment assessment = unassessed(n);

  // 1. Sensitivity of the predictions to a 100 % change of each free parameter.
  const double residual_scale = std::max(data_norm, residuals.norm());
  std::vector<int> columns;  // free parameters, in order
  for (int j = 0; j < n; ++j) {
    if (!free[j]) continue;
    columns.push_back(j);
    const double sensitivity = jacobian.col(j).norm() * parameter_scales[j];
    if (!(sensitivity > limits.sensitivity_threshold * residual_scale)) assessment.not_identifiable.push_back(j);
  }
  if (!assessment.not_identifiable.empty()) {
    const bool one = assessment.not_identifiable.size() == 1;
    assessment.identifiable = false;
    assessment.reason = "the data are insensitive to " + quoted_list(assessment.not_identifiable, names) +
                        ": a 100 % change of " + (one ? "it" : "each") +
                        " moves the weighted predictions by less than " +
                        formatted("%.1e", limits.sensitivity_threshold) + " of the data's size";
    return assessment;
  }
  if (columns.empty()) return assessment;

  // 2. Separability: condition number of the column-scaled normal matrix.
  const int k = static_cast<int>(columns.size());
  Eigen::MatrixXd scaled(m, k);
  Eigen::VectorXd column_norms(k);
  for (int c = 0; c < k; ++c) {
    column_norms[c] = jacobian.col(columns[c]).norm();
    scaled.col(c) = jacobian.col(columns[c]) / column_norms[c];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled.transpose() * scaled);
  const Eigen::VectorXd lambda = eigen.eigenvalues();  // ascending
  assessment.condition_number = lambda[0] > 0.0 ? lambda[k - 1] / lambda[0] : std::numeric_limits<double>::infinity();
  if (!(assessment.condition_number <= limits.max_condition)) {
    // The weakest direction: the parameters with a large share in it act only together.
    const Eigen::VectorXd direction = eigen.eigenvectors().col(0);
    std::vector<int> involved;
    for (int c = 0; c < k; ++c)
      if (std::abs(direction[c]) >= 0.2 * direction.cwiseAbs().maxCoeff()) involved.push_back(columns[c]);
    assessment.identifiable = false;
    assessment.not_identifiable = involved;
    assessment.reason = quoted_list(involved, names) +
                        " cannot be told apart by these data: the predictions depend (almost) only on a "
                        "combination of them (condition number of the scaled J^T J " +
                        formatted("%.2e", assessment.condition_number) + " > " +
                        formatted("%.0e", limits.max_condition) + ")";
    return assessment;
  }

  // Covariance s^2 D^-1 N^-1 D^-1 over the free parameters.
  if (m <= k) return assessment;
  const double variance = residuals.squaredNorm() / (m - k);
  const Eigen::MatrixXd n_inverse =
      eigen.eigenvectors() * lambda.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
  for (int a = 0; a < k; ++a) {
    assessment.standard_errors[columns[a]] = std::sqrt(variance * n_inverse(a, a)) / column_norms[a];
    for (int b = 0; b < k; ++b)
      assessment.correlation(columns[a], columns[b]) = n_inverse(a, b) / std::sqrt(n_inverse(a, a) * n_inverse(b, b));
  }
  return assessment;
}

}  // namespace tirefe::fitting
