// Identifiability and the linearised statistics of a least-squares estimate.
//
// Input: the Jacobian J = dr/dp of the weighted residuals r at the estimate (m x n, in the
// parameters' own units), r itself, and for every parameter a scale t_j (|p_j|, or a typical
// size when p_j is zero). Two tests, on the free parameters (those not held on a bound):
//
//  1. Sensitivity. s_j = |J_:j| t_j is how much the weighted predictions move when p_j
//     changes by 100 %. If s_j <= threshold * max(|sqrt(w) y|, |r|) the data say nothing
//     about p_j.
//  2. Separability. With D = diag(|J_:j|), the scaled normal matrix N = D^-1 J^T J D^-1
//     has a unit diagonal and off-diagonal correlations of the columns; its condition
//     number kappa(N) = lambda_max / lambda_min is independent of units. kappa above the
//     limit means the predictions depend (almost) only on a combination of parameters;
//     the eigenvector of lambda_min names them.
//
// If both pass: s^2 = |r|^2 / (m - n_free), Cov = s^2 (J^T J)^-1 = s^2 D^-1 N^-1 D^-1,
// standard errors sqrt(Cov_jj) and correlations Cov_ij / (se_i se_j). Parameters held on a
// bound, and every parameter when m == n_free (no degrees of freedom left), get NaN.
#pragma once

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace tirefe::fitting {

struct Assessment {
  bool identifiable = true;
  std::vector<int> not_identifiable;  // parameter indices
  std::string reason;                 // names the parameters and says why
  double condition_number = 0.0;      // of N over the free parameters (NaN if not computed)
  Eigen::VectorXd standard_errors;    // parameter units, NaN where unavailable
  Eigen::MatrixXd correlation;        // NaN rows/columns where unavailable
};

struct AssessmentLimits {
  double sensitivity_threshold = 1e-6;
  double max_condition = 1e10;
};

/// An assessment with nothing computed yet: identifiable, NaN statistics for n parameters.
Assessment unassessed(int parameter_count);

Assessment assess_estimate(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                           const Eigen::VectorXd& parameter_scales, double data_norm, const std::vector<bool>& free,
                           const std::vector<std::string>& names, const AssessmentLimits& limits);

}  // namespace tirefe::fitting
