// Writes a fit to HDF5 (docs/fitting.md):
//   /                        attributes tirefe_version, git_commit, deck_path, method, status,
//                            message, objective, evaluations, iterations
//   /fit/parameters/name, initial, lower, upper, log, value, standard_error   one entry per parameter
//   /fit/correlation         parameters x parameters
//   /fit/data, /fit/weights  the measured values (attribute "label") and their weights
//   /fit/prediction          the model at the fitted values
//   /fit/x                   abscissa of the data points (if known), attribute "label"
//   /fit/history/iteration, evaluations, objective, damping, step    one row per iteration
//   /fit/history/values      iterations x parameters
#pragma once

#include <string>

#include "fitting/fit_problem.hpp"

namespace tirefe::fitting {

/// What the data points are, for plots.
struct FitAxes {
  Eigen::VectorXd x;                  // abscissa of each data point; empty: none
  std::string x_label = "x";          // e.g. "deflection [m]"
  std::string data_label = "measured";  // e.g. "force [N]"
};

/// Creates (truncates) 'path' and writes the problem's data and the result.
void write_fit_file(const std::string& path, const FitProblem& problem, const FitResult& result,
                    const FitAxes& axes = {}, const std::string& deck_path = "");

}  // namespace tirefe::fitting
