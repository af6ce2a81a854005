#include "solvers/driven_stepper.hpp"

#include <cmath>

namespace tirefe {

const StepRecord& DrivenStepper::solve(const Eigen::Ref<const Eigen::VectorXd>& displacements, double step,
                                       bool near_last_trial) {
  if (!(step > 0.0) || !std::isfinite(step))
    throw ModelError("the time step must be positive and finite (got " + std::to_string(step) + ")");
  driven_.set_displacements(displacements);
  const bool from_last_trial = near_last_trial && pending_ && step == step_ && problem_.start_from_driven_move(step);
  if (!from_last_trial) {
    revert();
    problem_.prepare();
    problem_.predict(step, problem_.committed_time() + step);
  }
  pending_ = false;
  record_ = StepRecord{};
  if (!problem_.solve(newton_, controller_.settings().max_augmentations, record_, log_))
    throw StepFailure("the step from t = " + std::to_string(problem_.committed_time()) +
                      " (dt = " + std::to_string(step) + ") failed: " + problem_.failure());
  pending_ = true;
  step_ = step;
  return record_;
}

const DrivenDofSolver::SmallMatrix& DrivenStepper::jacobian() {
  if (!pending_) throw ModelError("the driven tangent needs a solved trial step");
  return problem_.driven_tangent();
}

void DrivenStepper::commit() {
  prepare_commit();
  prepared_ = false;
  controller_.notify(record_);
}

void DrivenStepper::prepare_commit() {
  if (prepared_) return;
  if (!pending_) throw ModelError("there is no trial step to accept");
  pending_ = false;
  problem_.commit(step_, energy_, record_);
  prepared_ = true;
}

void DrivenStepper::revert() {
  if (prepared_) throw ModelError("a recorded trial step can only be accepted");
  if (!pending_) return;
  problem_.revert();
  pending_ = false;
}

}  // namespace tirefe
