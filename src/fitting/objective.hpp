// Objective: a FitProblem as the optimisers see it. It works in internal coordinates
// z (z_j = ln p_j for log parameters, z_j = p_j otherwise) with the bounds mapped the same
// way, evaluates the weighted residuals r(z) and S = |r|^2 counting every model call,
// differentiates r by finite differences, and keeps the iteration history and log.
//
// Every length in z is measured against a scale: 1 for a log parameter (a step dz is the
// relative change dp/p), max(|p|, 1e-3 t) for the others, t the parameter's typical size
// (|initial|, else the bound range, else 1). The tolerance and the finite-difference steps
// are relative to that scale:
//     forward  J_:j = (r(z + h e_j) - r(z)) / h,                 h = relative_step * scale_j
//     central  J_:j = (r(z + h e_j) - r(z - h e_j)) / (2 h)
// A step that would leave the box is taken on the other side.
#pragma once

#include <string>
#include <vector>

#include "fitting/fit_problem.hpp"
#include "fitting/identifiability.hpp"

namespace tirefe::fitting {

class Objective {
 public:
  struct Evaluation {
    bool ok = false;
    Eigen::VectorXd predictions, residuals;  // residuals weighted
    double objective = std::numeric_limits<double>::infinity();
  };

  /// Validates the problem (std::invalid_argument). 'result' receives history and outcome.
  Objective(const FitProblem& problem, const FitOptions& options, FitResult& result);

  int parameter_count() const { return static_cast<int>(problem_.parameters.size()); }
  int data_count() const { return static_cast<int>(problem_.data.size()); }

  Eigen::VectorXd initial() const;  // internal coordinates
  Eigen::VectorXd physical(const Eigen::VectorXd& z) const;
  double lower(int j) const { return lower_[j]; }
  double upper(int j) const { return upper_[j]; }
  Eigen::VectorXd clamp(const Eigen::VectorXd& z) const;
  bool on_lower(int j, double z_j) const { return z_j <= lower_[j]; }
  bool on_upper(int j, double z_j) const { return z_j >= upper_[j]; }
  double scale(int j, double z_j) const;
  /// Every |step_j| within tolerance * scale_j.
  bool within_tolerance(const Eigen::VectorXd& step, const Eigen::VectorXd& z) const;

  int evaluations() const { return evaluations_; }
  bool exhausted() const { return evaluations_ >= options_.max_evaluations; }

  /// One model call. A model failure (EvaluationError or a non-finite prediction) gives
  /// ok = false and S = infinity; a wrong number of predictions throws std::invalid_argument.
  Evaluation evaluate(const Eigen::VectorXd& z);
  /// Like evaluate(), but a failure throws EvaluationError naming the parameter values.
  Evaluation evaluate_initial(const Eigen::VectorXd& z);
  /// dr/dz at z (r = at.residuals); throws EvaluationError if a column cannot be formed.
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& z, const Evaluation& at);

  /// Identifiability and standard errors at z; 'free' marks parameters not held on a bound.
  Assessment assess(const Eigen::VectorXd& z, const Evaluation& at, const Eigen::MatrixXd& jacobian_z,
                    const std::vector<bool>& free) const;

  /// Appends to the history, prints the log line and calls on_iteration.
  void record(const Eigen::VectorXd& z, double objective, const std::string& step,
              double damping = std::numeric_limits<double>::quiet_NaN());
  /// A free-form log line (rejected steps, failed evaluations).
  void note(const std::string& line) const;
  /// "k_sw = 123.4, c = 5" for the log and messages.
  std::string describe(const Eigen::VectorXd& z) const;

  /// Fills the result: values, prediction, objective, statistics, status and message. A
  /// failed assessment overrides 'status' with NotIdentifiable and removes the values it
  /// names; 'fitted' = false (stopped before iterating) removes every value.
  void finish(const Eigen::VectorXd& z, const Evaluation& at, const Assessment& assessment, FitStatus status,
              const std::string& message, bool fitted = true);

 private:
  struct Outcome {
    Evaluation evaluation;
    std::string failure;  // why the model could not be evaluated
  };
  Outcome call_model(const Eigen::VectorXd& z);

  const FitProblem& problem_;
  const FitOptions& options_;
  FitResult& result_;
  Eigen::VectorXd sqrt_weights_, lower_, upper_, typical_;
  double data_norm_ = 0.0;  // |sqrt(w) y|
  int evaluations_ = 0;
};

}  // namespace tirefe::fitting
