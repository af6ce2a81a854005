#include "fitting/fit_problem.hpp"

#include "fitting/brent.hpp"
#include "fitting/levenberg_marquardt.hpp"

namespace tirefe::fitting {

const char* status_name(FitStatus status) {
  switch (status) {
    case FitStatus::Converged: return "converged";
    case FitStatus::AtBound: return "at_bound";
    case FitStatus::NotIdentifiable: return "not_identifiable";
    case FitStatus::MaxEvaluations: return "max_evaluations";
  }
  return "?";
}

const char* method_name(FitMethod method, int parameter_count) {
  if (method == FitMethod::Automatic) method = parameter_count == 1 ? FitMethod::Brent : FitMethod::LevenbergMarquardt;
  return method == FitMethod::Brent ? "brent" : "levenberg_marquardt";
}

FitResult fit(const FitProblem& problem, const FitOptions& options) {
  const bool brent = std::string(method_name(options.method, static_cast<int>(problem.parameters.size()))) == "brent";
  return brent ? fit_brent(problem, options) : fit_levenberg_marquardt(problem, options);
}

}  // namespace tirefe::fitting
