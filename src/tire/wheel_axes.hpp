// The one axis system and sign convention of spindle forces (docs/output.md, "Axes and
// signs"): ISO 8855 wheel axes as TYDEX and MF-Tyre use them, at the wheel centre.
//   x_ISO along the wheel's heading (its direction of travel over the road): +x or -x of
//         the model's plane (x right, y up, theta_z counter-clockwise);
//   z_ISO up, the plane's y;
//   y_ISO = z_ISO x x_ISO, the spin axis (left of the heading): into the page for heading
//         +x, out of it for heading -x.
// Reported: the force and moment the tire exerts on the wheel, read from the spindle
// node's support reaction R (the force the axle puts on the wheel): F = -R in the plane,
//   Fx = h F_x,  Fz = F_y,  My = -h M_z,  spin rate = -h d(theta_z)/dt,  h = +1 or -1.
// A loaded standing tire gives Fz = +load, a driving torque Fx > 0, a cleat's strike Fx < 0,
// and forward rolling a positive spin rate.
#pragma once

#include <Eigen/Dense>
#include <string>

namespace tirefe {

/// The wheel's heading in the model's plane.
enum class Heading { PlusX, MinusX };

/// The text every result file carries as its "axes" attribute.
inline const char* wheel_axes_statement() {
  return "ISO 8855 wheel axes (C): x heading, y left, z up; forces the tire exerts on the wheel";
}

inline double heading_sign(Heading heading) { return heading == Heading::PlusX ? 1.0 : -1.0; }
inline const char* heading_name(Heading heading) { return heading == Heading::PlusX ? "+x" : "-x"; }
/// "+x" or "-x"; anything else is not a heading (returns false).
inline bool parse_heading(const std::string& text, Heading& heading) {
  if (text != "+x" && text != "-x") return false;
  heading = text == "+x" ? Heading::PlusX : Heading::MinusX;
  return true;
}

/// Fx, Fz [N] and My [N m] in wheel axes from the spindle's support reaction (R_x, R_y, M_z)
/// in the plane.
inline Eigen::Vector3d wheel_load_from_reaction(const Eigen::Vector3d& reaction, Heading heading) {
  const double h = heading_sign(heading);
  return {-h * reaction.x(), -reaction.y(), h * reaction.z()};
}

/// Spin rate about y_ISO [rad/s] (positive rolling forward) from d(theta_z)/dt.
inline double wheel_spin_rate(double theta_z_rate, Heading heading) { return -heading_sign(heading) * theta_z_rate; }

/// A spindle motion (x [m] along the heading, z [m] up, spin [rad] about y_ISO), or its
/// rates, as the plane's (x, y, theta_z): (h x, z, -h spin). The map is its own inverse,
/// so it also gives the wheel-axes motion of a plane one.
inline Eigen::Vector3d plane_motion(const Eigen::Vector3d& motion, Heading heading) {
  const double h = heading_sign(heading);
  return {h * motion.x(), motion.y(), -h * motion.z()};
}

/// d(Fx, Fz, My)/d(x, z, spin) in wheel axes from the plane's d(R_x, R_y, M_z)/d(x, y,
/// theta_z): T_F J T_q with the diagonal signs of wheel_load_from_reaction (T_F) and
/// plane_motion (T_q).
inline Eigen::Matrix3d wheel_load_jacobian(const Eigen::Matrix3d& reaction_jacobian, Heading heading) {
  const double h = heading_sign(heading);
  const Eigen::Vector3d load_signs(-h, -1.0, h), motion_signs(h, 1.0, -h);
  return load_signs.asDiagonal() * reaction_jacobian * motion_signs.asDiagonal();
}

}  // namespace tirefe
