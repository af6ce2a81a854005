#include "contact/rigid_motion.hpp"

#include <algorithm>
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

MotionFunction MotionFunction::ramped_rate(double final_rate, double ramp_time, double start_time) {
  if (!(ramp_time >= 0.0) || !std::isfinite(ramp_time))
    throw ModelError("a motion's ramp time must be non-negative (got " + std::to_string(ramp_time) + ")");
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

Eigen::Vector2d RigidMotion::to_space(const Eigen::Vector2d& material, double time) const {
  return centre_ + translation_at(time) + rotation_at(time) * (material - centre_);
}

Eigen::Vector2d RigidMotion::to_material(const Eigen::Vector2d& spatial, double time) const {
  return centre_ + rotation_at(time).transpose() * (spatial - centre_ - translation_at(time));
}

Eigen::Vector2d RigidMotion::velocity(const Eigen::Vector2d& spatial, double time) const {
  const Eigen::Vector2d arm = spatial - centre_ - translation_at(time);
  const double spin = angle_.rate(time);
  return Eigen::Vector2d(x_.rate(time) - spin * arm.y(), y_.rate(time) + spin * arm.x());
}

}  // namespace tirefe
