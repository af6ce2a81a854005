// Writes a fit to HDF5 (docs/fitting.md):
//   /                        attributes tirefe_version, git_commit, deck_path, method, status,
//                            message, objective, evaluations, iterations
//   /fit/parameters/name, initial, lower, upper, log, value, standard_error   one entry per parameter
//   /fit/correlation         parameters x parameters
//   /fit/data, /fit/weights  the measured values (attribute "label") and their weights
//   /fit/prediction          the model at the fitted values
//   /fit/x                   abscissa of the data points (if known), attribute "label"
//                            (/fit/x and /fit/data: also "to_si", the SI value of one unit of
//                            the data file, and "file_unit", that unit, if it has one)
//   /fit/curve/x, prediction the model at the fitted values on a fine grid of x (if asked for)
//   /fit/history/iteration, evaluations, objective, damping, step    one row per iteration
//   /fit/history/values      iterations x parameters
#pragma once

#include <string>

#include "fitting/fit_problem.hpp"

namespace tirefe::io {

/// What the data points are, for plots.
struct FitAxes {
  Eigen::VectorXd x;                    // abscissa of each data point; empty: none
  std::string x_label = "x";            // e.g. "deflection [m]"
  std::string data_label = "measured";  // e.g. "force [N]"
  // The data file's units as written (e.g. "mm") and the SI value of one of them; the
  // values above are SI. "" and 1: the values are as given.
  std::string x_unit, data_unit;
  double x_to_si = 1.0, data_to_si = 1.0;
  // The model at the fitted values on a fine grid of x (SI); empty: not evaluated.
  Eigen::VectorXd curve_x, curve_prediction;
};

/// Creates (truncates) 'path' and writes the problem's data and the result.
void write_fit_file(const std::string& path, const fitting::FitProblem& problem, const fitting::FitResult& result,
                    const FitAxes& axes = {}, const std::string& deck_path = "");

}  // namespace tirefe::io
