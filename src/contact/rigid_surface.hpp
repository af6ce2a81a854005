// Rigid contact surfaces: a shape in its own (material) frame (surface_curve.hpp) carried
// by a prescribed rigid motion (rigid_motion.hpp).
//
// project(x, t) maps x into the material frame, projects there, and rotates normal and
// tangent back: the gap g, the convected coordinate s and the curvature do not depend on
// the motion, so slip measured in s is frame-indifferent (docs/model.md sec. 4). velocity()
// gives the velocity of the surface's material point (a spinning drum's rim speed, a
// moving road's speed), from which the sliding velocity V_T = (v_node - v_surface).tau.
//
// The surfaces of the model (docs/contact.md):
//   FlatRoad     a straight line through a point along a direction (solid on its right).
//   Drum         a circle of diameter D seen from outside, spinning about its centre by an
//                angle theta(t), optionally carrying a cleat (a step of height h and arc
//                length L on the drum surface at an angular position), convex edges rounded.
//   RoadProfile  a polyline y(x) from points or a file, level beyond its ends, with helpers
//                for a pothole and a cleat on a flat road; moves with a translation.
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

#include "contact/rigid_motion.hpp"
#include "contact/surface_curve.hpp"

namespace tirefe {

class RigidSurface {
 public:
  RigidSurface(std::string kind, SurfaceCurve curve, RigidMotion motion)
      : kind_(std::move(kind)), curve_(std::move(curve)), motion_(std::move(motion)) {}
  virtual ~RigidSurface() = default;

  /// Closest-point projection of the spatial point x at time t.
  SurfaceProjection project(const Eigen::Vector2d& x, double time) const { return project(x, motion_.pose(time)); }
  /// The same with the surface at 'pose', its motion's pose at that time (RigidMotion::pose):
  /// for a caller that asks several things at one time.
  SurfaceProjection project(const Eigen::Vector2d& x, const RigidPose& pose) const;
  /// Spatial position and velocity of the material point s at time t.
  Eigen::Vector2d point(double coordinate, double time) const;
  Eigen::Vector2d velocity(double coordinate, double time) const;
  /// Velocity of the material point that occupies 'spatial' at time t (no projection).
  Eigen::Vector2d velocity_at(const Eigen::Vector2d& spatial, double time) const {
    return motion_.velocity(spatial, time);
  }
  /// A lower bound of the distance from x (outside the solid) to the surface at time t,
  /// cheap enough to skip the projection of nodes far away; -infinity when unknown.
  virtual double clearance(const Eigen::Vector2d& /*x*/, double /*time*/) const {
    return -std::numeric_limits<double>::infinity();
  }
  /// Slip measure s_to - s_from (wrapped around a closed surface).
  double arc_difference(double to, double from) const { return curve_.arc_difference(to, from); }

  /// The surface at time t as a polyline to draw (SurfaceCurve::outline in its place):
  /// the same number of points at every time, an open surface's rays drawn until they are
  /// 'reach' past 'centre' (as measured along them).
  std::vector<Eigen::Vector2d> outline(double time, const Eigen::Vector2d& centre, double reach,
                                       double tolerance) const;

  const std::string& kind() const { return kind_; }
  const SurfaceCurve& curve() const { return curve_; }
  const RigidMotion& motion() const { return motion_; }

 private:
  std::string kind_;
  SurfaceCurve curve_;
  RigidMotion motion_;
};

class FlatRoad : public RigidSurface {
 public:
  /// The line through 'point' along 'direction'; the solid lies on the right of the
  /// direction (below, for the default +x). s = 0 at 'point'.
  explicit FlatRoad(const Eigen::Vector2d& point = Eigen::Vector2d::Zero(),
                    const Eigen::Vector2d& direction = Eigen::Vector2d::UnitX(), RigidMotion motion = {});
  /// The signed distance from the line.
  double clearance(const Eigen::Vector2d& x, double time) const override;

 private:
  Eigen::Vector2d point_, normal_;  // in the road's own frame
};

struct Cleat {
  double height = 0.0;                // radial height of the step [m]; 0: no cleat
  double arc_length = 0.0;            // length of the step along the drum surface (radius R) [m]
  double angle = 1.5707963267948966;  // angular position of its middle at theta = 0 [rad, from +x, ccw]
  double edge_radius = 0.0;           // rounding of the two top (convex) edges [m]
};

class Drum : public RigidSurface {
 public:
  /// A drum of 'diameter' about 'centre' turned by angle(t) (counter-clockwise positive).
  /// Arc length runs clockwise (the solid on the right); s = 0 at the cleat's foot at
  /// angle - L/(2R) (at angle 0 without a cleat), in the drum's frame.
  Drum(double diameter, const Eigen::Vector2d& centre, MotionFunction angle, const Cleat& cleat = {});
  double radius() const { return radius_; }
  const Eigen::Vector2d& centre() const { return motion().centre(); }
  /// Distance from x to the drum's circle, or to the circle through the cleat's top where
  /// x is within 0.1 rad of the cleat's angular span: no trigonometry.
  double clearance(const Eigen::Vector2d& x, double time) const override;
  const Cleat& cleat() const { return cleat_; }

 private:
  double radius_;
  Cleat cleat_;
  Eigen::Vector2d cleat_middle_;  // at rest, unit
  double near_cleat_cos_ = -1.0;  // cos of the cleat's half span + 0.1 rad (-1: every direction)
};

class RoadProfile : public RigidSurface {
 public:
  /// The polyline through 'points' (x must not decrease; equal x makes a vertical step),
  /// continued level beyond its first and last points; convex corners rounded with
  /// edge_radius. s = 0 at the first point.
  RoadProfile(const std::vector<Eigen::Vector2d>& points, double edge_radius = 0.0, RigidMotion motion = {});
  /// The height above the profile's highest point.
  double clearance(const Eigen::Vector2d& x, double time) const override;

  /// Two columns "x y" per line, '#' starts a comment. Throws ModelError naming the file and
  /// line for unreadable, short or non-monotonic data.
  static std::vector<Eigen::Vector2d> read_points(const std::string& path);
  /// A flat road at height 'level' with a rectangular pothole of 'length' and 'depth'
  /// starting at x = start (vertical walls).
  static std::vector<Eigen::Vector2d> pothole_points(double start, double length, double depth, double level = 0.0);
  /// A flat road at height 'level' with a rectangular cleat of 'length' and 'height' starting at x = start.
  static std::vector<Eigen::Vector2d> cleat_points(double start, double length, double height, double level = 0.0);

 private:
  double highest_ = 0.0;  // the largest y of the points (the profile's own frame)
};

}  // namespace tirefe
