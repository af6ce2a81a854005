#include "vehicle/tire_spindle.hpp"

#include <cstring>
#include <exception>

namespace tirefe {

TireSpindle::TireSpindle(Analysis& analysis, int spindle, SpinMode spin)
    : analysis_(analysis),
      spindle_(analysis.model().mesh().checked(spindle)),
      spin_(spin),
      driven_count_(spin == SpinMode::Free ? 2 : 3) {
  if (!analysis.integrator().is_dynamic())
    throw ModelError("the spindle force needs a dynamic tire analysis (newmark, hht, wbz or generalized_alpha)");
  Model& model = analysis.model();
  std::vector<int> dofs;
  for (int c = 0; c < kDofsPerNode; ++c) model.release(spindle_, c);
  for (int c = 0; c < driven_count_; ++c) dofs.push_back(dof_index(spindle_, c));
  analysis.drive_dofs(std::move(dofs));
}

Eigen::Vector3d TireSpindle::committed_position() const {
  const Eigen::Vector2d& reference = analysis_.model().mesh().position(spindle_);
  const Eigen::VectorXd& u = analysis_.state().displacement;
  const int first = dof_index(spindle_, 0);
  return {reference.x() + u[first], reference.y() + u[first + 1], u[first + 2]};
}

Eigen::Vector3d TireSpindle::committed_force() const {
  return analysis_.reactions().segment<3>(dof_index(spindle_, 0));
}

const SpindleReply& TireSpindle::solve_step(const SpindleInput& input) {
  reply_has_jacobian_ = false;  // until this trial's (a failed solve leaves no trial)
  const Eigen::Vector2d& reference = analysis_.model().mesh().position(spindle_);
  const Eigen::Vector3d target(input.x - reference.x(), input.y - reference.y(), input.spin);
  DrivenStepper& stepper = analysis_.driven_stepper();
  const StepRecord& record =
      stepper.solve(target.head(driven_count_), input.time_step, input.start == SpindleStart::LastTrial);
  reply_ = SpindleReply{};
  reply_.time = stepper.trial().time;
  reply_.newton_iterations = record.newton_iterations;
  reply_.augmentations = record.augmentations;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  stepper.forces(force.head(driven_count_));
  force_of(reply_) = force;
  return input.jacobian ? jacobian() : reply_;
}

const SpindleReply& TireSpindle::jacobian() {
  if (!reply_has_jacobian_) {
    jacobian_of(reply_).topLeftCorner(driven_count_, driven_count_) = analysis_.driven_stepper().jacobian();
    reply_has_jacobian_ = true;
  }
  return reply_;
}

void TireSpindle::commit() {
  reply_has_jacobian_ = false;
  if (!commit_failure_.empty()) {
    const std::string failure = std::move(commit_failure_);
    commit_failure_.clear();
    throw StepFailure(failure);
  }
  analysis_.driven_stepper().commit();
}

void TireSpindle::prepare_commit() {
  reply_has_jacobian_ = false;
  try {
    analysis_.driven_stepper().prepare_commit();
  } catch (const std::exception& failure) {
    commit_failure_ = failure.what();
  }
}

void TireSpindle::revert() {
  reply_has_jacobian_ = false;
  analysis_.driven_stepper().revert();
}

SpindleReply TireSpindle::serve(const SpindleRequest& request) {
  try {
    switch (request.command) {
      case SpindleCommand::Solve: return solve_step(request.input);
      case SpindleCommand::Jacobian: return jacobian();
      case SpindleCommand::Commit: commit(); break;
      case SpindleCommand::Revert: revert(); break;
    }
    // The committed step, for a host that does not hold this tire (another MPI rank).
    SpindleReply reply;
    reply.time = analysis_.state().time;
    force_of(reply) = committed_force();
    return reply;
  } catch (const std::exception& failure) {
    SpindleReply reply;
    reply.status = SpindleStatus::Failed;
    std::strncpy(reply.message, failure.what(), sizeof reply.message - 1);
    return reply;
  }
}

}  // namespace tirefe
