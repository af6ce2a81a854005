// Prescribed rigid motion of a contact surface: a translation d(t) and a rotation
// theta(t) about a centre c that travels with the translation.
//
// The surface's shape is described once in its own (material) frame; the material point
// xi sits at time t at
//     x(xi, t) = c + d(t) + R(theta(t)) (xi - c),
// and moves with the velocity
//     v = d'(t) + theta'(t) k x (x - c - d(t))      (k the out-of-plane unit vector).
// A spinning drum is a rotation about its axis, a road moving under a vehicle a
// translation. Closest-point projections are computed in the material frame, so gap and
// arc-length coordinate do not depend on the motion (frame indifference, docs/model.md sec. 4).
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <string>

#include "core/load_function.hpp"

namespace tirefe {

/// How a ramped rate rises from rest to its final value over the ramp time T.
enum class RampLaw {
  Linear,  // in proportion to the time since the start
  Cosine,  // as (1 - cos(pi t / T)) / 2: the rate's own rate neither jumps at the start nor at the end
};
/// The law named "linear" or "cosine"; ModelError for any other name.
RampLaw ramp_law_named(const std::string& name);

/// A scalar function of time with its rate: a translation component [m] or an angle [rad].
class MotionFunction {
 public:
  /// At rest at 'value'.
  static MotionFunction constant(double value = 0.0);
  /// value = rate * t: uniform motion.
  static MotionFunction linear(double rate);
  /// The rate rises by 'law' from 0 at start_time to final_rate at start_time + ramp_time
  /// and is held after; the value is its integral, 0 before start_time. A drum that spins
  /// up (the decks' drum kinematics: lua/drum.lua asks it through tirefe.spin_up), or a
  /// road that accelerates under a vehicle. ramp_time = 0 jumps.
  static MotionFunction ramped_rate(double final_rate, double ramp_time, double start_time = 0.0,
                                    RampLaw law = RampLaw::Linear);
  /// value = scale * f(t) for a load function f; the rate by central differences
  /// (at the kinks of a table it is the mean of the two slopes).
  static MotionFunction from_load_function(LoadFunction function, double scale = 1.0);

  MotionFunction() : MotionFunction(constant(0.0)) {}
  MotionFunction(std::function<double(double)> value, std::function<double(double)> rate)
      : value_(std::move(value)), rate_(std::move(rate)) {}

  double value(double time) const { return value_(time); }
  double rate(double time) const { return rate_(time); }

 private:
  std::function<double(double)> value_, rate_;
};

/// A rigid motion at one time: what the positions and velocities of its points need.
struct RigidPose {
  Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity();      // R(theta(t))
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();       // d(t)
  Eigen::Vector2d translation_rate = Eigen::Vector2d::Zero();  // d'(t)
  double spin = 0.0;                                           // theta'(t)
};

class RigidMotion {
 public:
  /// At rest.
  RigidMotion() = default;
  RigidMotion(MotionFunction x, MotionFunction y, MotionFunction angle, const Eigen::Vector2d& centre)
      : x_(std::move(x)), y_(std::move(y)), angle_(std::move(angle)), centre_(centre) {}
  static RigidMotion translation(MotionFunction x, MotionFunction y = MotionFunction()) {
    return RigidMotion(std::move(x), std::move(y), MotionFunction(), Eigen::Vector2d::Zero());
  }
  static RigidMotion rotation(MotionFunction angle, const Eigen::Vector2d& centre) {
    return RigidMotion(MotionFunction(), MotionFunction(), std::move(angle), centre);
  }

  Eigen::Vector2d translation_at(double time) const { return {x_.value(time), y_.value(time)}; }
  double angle_at(double time) const { return angle_.value(time); }
  Eigen::Matrix2d rotation_at(double time) const;

  /// The pose at time t. Every node of an evaluation pass asks at the same time, so the
  /// last pose is kept (one per thread) and the motion's functions, sine and cosine run
  /// once per pass rather than once per node. The functions must depend on time alone
  /// (as their rates by differences already assume). The reference holds until the next
  /// pose() on this thread.
  const RigidPose& pose(double time) const;

  /// Spatial position at time t of the material point 'material'.
  Eigen::Vector2d to_space(const Eigen::Vector2d& material, double time) const {
    return to_space(material, pose(time));
  }
  Eigen::Vector2d to_space(const Eigen::Vector2d& material, const RigidPose& pose) const {
    return centre_ + pose.translation + pose.rotation * (material - centre_);
  }
  /// Material point that occupies 'spatial' at time t.
  Eigen::Vector2d to_material(const Eigen::Vector2d& spatial, double time) const {
    return to_material(spatial, pose(time));
  }
  Eigen::Vector2d to_material(const Eigen::Vector2d& spatial, const RigidPose& pose) const {
    return centre_ + pose.rotation.transpose() * (spatial - centre_ - pose.translation);
  }
  /// Velocity of the material point that occupies 'spatial' at time t.
  Eigen::Vector2d velocity(const Eigen::Vector2d& spatial, double time) const { return velocity(spatial, pose(time)); }
  Eigen::Vector2d velocity(const Eigen::Vector2d& spatial, const RigidPose& pose) const {
    const Eigen::Vector2d arm = spatial - centre_ - pose.translation;
    return Eigen::Vector2d(pose.translation_rate.x() - pose.spin * arm.y(),
                           pose.translation_rate.y() + pose.spin * arm.x());
  }

  const Eigen::Vector2d& centre() const { return centre_; }

 private:
  /// The pose from the motion's functions, without the kept one.
  RigidPose evaluate_pose(double time) const;

  MotionFunction x_, y_, angle_;
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();
  // Names the motion for the kept pose: copies share it (they have the same functions).
  std::uint64_t identity_ = new_identity();
  static std::uint64_t new_identity();
};

}  // namespace tirefe
