#include "contact/rigid_motion.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "core/mesh.hpp"

namespace tirefe {

MotionFunction MotionFunction::constant(double value) {
  return MotionFunction([value](double) { return value; }, [](double) { return 0.0; });
}

MotionFunction MotionFunction::linear(double rate) {
  return MotionFunction([rate](double t) { return rate * t; }, [rate](double) { return rate; });
}

RampLaw ramp_law_named(const std::string& name) {
  if (name == "linear") return RampLaw::Linear;
  if (name == "cosine") return RampLaw::Cosine;
  throw ModelError("ramp '" + name + "' is no ramp law: give \"linear\" or \"cosine\"");
}

namespace {

/// rate(t) = final_rate (1 - cos(pi (t - t0) / T)) / 2 up to t0 + T; value = its integral from t0.
MotionFunction cosine_ramped_rate(double final_rate, double ramp_time, double start_time) {
  constexpr double kPi = 3.14159265358979323846;
  auto value = [=](double t) {
    const double elapsed = t - start_time;
    if (elapsed <= 0.0) return 0.0;
    if (elapsed <= ramp_time)
      return 0.5 * final_rate * (elapsed - ramp_time / kPi * std::sin(kPi * elapsed / ramp_time));
    return final_rate * (elapsed - 0.5 * ramp_time);
  };
  auto rate = [=](double t) {
    const double share = std::min(std::max(t - start_time, 0.0) / ramp_time, 1.0);
    return final_rate * 0.5 * (1.0 - std::cos(kPi * share));
  };
  return MotionFunction(value, rate);
}

}  // namespace

MotionFunction MotionFunction::ramped_rate(double final_rate, double ramp_time, double start_time, RampLaw law) {
  if (!(ramp_time >= 0.0) || !std::isfinite(ramp_time))
    throw ModelError("a motion's ramp time must be non-negative (got " + std::to_string(ramp_time) + ")");
  if (law == RampLaw::Cosine && ramp_time > 0.0) return cosine_ramped_rate(final_rate, ramp_time, start_time);
  // rate(t) = final_rate * clamp((t - t0) / T, 0, 1); value = its integral from t0.
  auto value = [=](double t) {
    const double elapsed = t - start_time;
    if (elapsed <= 0.0) return 0.0;
    if (elapsed < ramp_time) return 0.5 * final_rate * elapsed * elapsed / ramp_time;
    return final_rate * (elapsed - 0.5 * ramp_time);
  };
  auto rate = [=](double t) {
    const double elapsed = t - start_time;
    if (elapsed <= 0.0) return 0.0;
    return elapsed < ramp_time ? final_rate * elapsed / ramp_time : final_rate;
  };
  return MotionFunction(value, rate);
}

MotionFunction MotionFunction::from_load_function(LoadFunction function, double scale) {
  auto value = [function, scale](double t) { return scale * function(t); };
  auto rate = [function, scale](double t) {
    const double h = 1e-6 * std::max(1.0, std::abs(t));
    return scale * (function(t + h) - function(t - h)) / (2.0 * h);
  };
  return MotionFunction(value, rate);
}

Eigen::Matrix2d RigidMotion::rotation_at(double time) const {
  const double angle = angle_.value(time), c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix2d rotation;
  rotation << c, -s, s, c;
  return rotation;
}

RigidPose RigidMotion::evaluate_pose(double time) const {
  RigidPose pose;
  pose.rotation = rotation_at(time);
  pose.translation = translation_at(time);
  pose.translation_rate = Eigen::Vector2d(x_.rate(time), y_.rate(time));
  pose.spin = angle_.rate(time);
  return pose;
}

const RigidPose& RigidMotion::pose(double time) const {
  // One entry per thread: tires solved in parallel (TireGroup) never share it, and a
  // motion destroyed and another built at its address cannot be mistaken for it.
  struct Kept {
    std::uint64_t identity = 0;  // 0: none (identities start at 1)
    double time = 0.0;
    RigidPose pose;
  };
  static thread_local Kept kept;
  if (kept.identity != identity_ || !(kept.time == time)) {
    kept.pose = evaluate_pose(time);
    kept.identity = identity_;
    kept.time = time;
  }
  return kept.pose;
}

std::uint64_t RigidMotion::new_identity() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

}  // namespace tirefe
