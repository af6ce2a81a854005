// BumpRoad: a level road (y = 0) carrying a half-round bump of radius r centred at x = c,
// the worked surface of docs/extending.md. Its shape is three pieces of a SurfaceCurve in
// the road's own frame, walked along +x with the solid on the right (below the road):
//     the road up to the bump's foot, the arc over its top (clockwise), the road beyond.
// The feet are concave corners (the curve's vertex rule); the top's curvature is +1/r.
#pragma once

#include <Eigen/Dense>
#include <utility>
#include <vector>

#include "contact/rigid_surface.hpp"

namespace tirefe::examples {

class BumpRoad : public RigidSurface {
 public:
  BumpRoad(double centre, double radius, RigidMotion motion = {})
      : RigidSurface("bump", SurfaceCurve(pieces(centre, radius), false), std::move(motion)), radius_(radius) {}

  /// A lower bound of the distance to the road: the height above the bump's top, in the
  /// road's own frame (the contact skips the projection of points farther than a step's reach).
  double clearance(const Eigen::Vector2d& x, double time) const override {
    return motion().to_material(x, time).y() - radius_;
  }

 private:
  static std::vector<SurfaceCurve::Piece> pieces(double centre, double radius) {
    if (!(radius > 0.0)) throw ModelError("bump road: the radius must be positive");
    const Eigen::Vector2d along = Eigen::Vector2d::UnitX();
    const Eigen::Vector2d left(centre - radius, 0.0), right(centre + radius, 0.0);
    constexpr double kPi = 3.14159265358979323846;
    return {SurfaceCurve::Piece::ray_to(left, along),
            SurfaceCurve::Piece::arc(Eigen::Vector2d(centre, 0.0), radius, kPi, -kPi),
            SurfaceCurve::Piece::ray_from(right, along)};
  }

  double radius_;
};

}  // namespace tirefe::examples
