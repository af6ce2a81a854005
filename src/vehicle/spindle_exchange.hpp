// The messages between a host and a tire behind its spindle (docs/spindle.md): plain,
// trivially copyable values with named fields, so that a request and its reply can be
// passed to a thread, written to a pipe or sent as bytes to an MPI rank unchanged.
// The host sends SpindleRequest{Solve} as often as its corrector needs, then one
// Commit (step accepted) or Revert (step rejected); the tire answers every request. A
// Solve may leave the Jacobian out (its factorisation is a large part of a solve); a
// Jacobian request then adds it, should the host's corrector need it after all.
#pragma once

#include <Eigen/Dense>
#include <type_traits>

namespace tirefe {

/// Spin of the spindle: driven by the host (rz prescribed: drive torque or brake), or
/// free (the wheel rolls freely on its bearing: rz is solved by the tire, Mz = 0).
enum class SpinMode { Driven, Free };

/// Where the tire's Newton starts: at its own predictor, or at its last trial of this
/// step moved by its linear response to the spindle's move (DrivenStepper::solve near the last trial):
/// a host corrector's next trial, a little away from the last. The same answer to the
/// tire's Newton tolerance; the predictor where the tire has no such trial.
enum class SpindleStart { Predictor, LastTrial };

/// The spindle at the end of the step being solved.
struct SpindleInput {
  double time_step = 0.0;  // h [s], from the committed time
  double x = 0.0;          // spindle centre [m], absolute, in the wheel plane
  double y = 0.0;          // (y up)
  double spin = 0.0;       // rotation from the reference [rad], counter-clockwise; ignored when free
  SpindleStart start = SpindleStart::Predictor;
  bool jacobian = true;  // false: the reply's Jacobian stays zero until a Jacobian request
};

/// Solve: the step to the spindle input. Jacobian: the reply to the last Solve, with the
/// Jacobian of its converged trial (asked for after a Solve without it; a LastTrial start
/// after it then moves from that trial as it would after a Solve with it). Commit, Revert:
/// accept or forget the last trial.
enum class SpindleCommand { Solve, Commit, Revert, Jacobian };

struct SpindleRequest {
  SpindleCommand command = SpindleCommand::Solve;
  SpindleInput input;  // for Solve
};

enum class SpindleStatus { Ok, Failed };

struct SpindleReply {
  SpindleStatus status = SpindleStatus::Ok;
  /// Force the host applies to the tire to hold the spindle there: (Fx [N], Fy [N],
  /// Mz [N m]); the tire pushes the host's wheel carrier with minus this. HHT-weighted
  /// like the tire's step equations (the physical reaction with Newmark, alpha = 0).
  /// The answer to Commit or Revert: the physical force at the committed step.
  double force[3] = {};
  /// jacobian[i][j] = d force_i / d (x, y, spin)_j: H_ss of docs/model.md eq. 27 (row and
  /// column 2 zero when the spin is free).
  double jacobian[3][3] = {};
  double time = 0.0;          // at the end of the solved step (Commit, Revert: the committed one) [s]
  int newton_iterations = 0;  // of the tire, this request
  int augmentations = 0;      // contact multiplier updates, this request
  char message[160] = {};     // why a request failed
};

using SpindleJacobian = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
inline Eigen::Map<Eigen::Vector3d> force_of(SpindleReply& reply) { return Eigen::Map<Eigen::Vector3d>(reply.force); }
inline Eigen::Map<const Eigen::Vector3d> force_of(const SpindleReply& reply) {
  return Eigen::Map<const Eigen::Vector3d>(reply.force);
}
inline Eigen::Map<SpindleJacobian> jacobian_of(SpindleReply& reply) {
  return Eigen::Map<SpindleJacobian>(&reply.jacobian[0][0]);
}
inline Eigen::Map<const SpindleJacobian> jacobian_of(const SpindleReply& reply) {
  return Eigen::Map<const SpindleJacobian>(&reply.jacobian[0][0]);
}

static_assert(std::is_trivially_copyable<SpindleRequest>::value, "requests travel as bytes");
static_assert(std::is_trivially_copyable<SpindleReply>::value, "replies travel as bytes");

}  // namespace tirefe
