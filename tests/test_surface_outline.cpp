// Tests of the outlines result files draw rigid surfaces with (SurfaceCurve::outline,
// RigidSurface::outline): a drum and its cleat on their circles within the chord
// tolerance, turned by the drum's angle; a road's profile exact, its rays drawn out to the
// given reach past the structure, the same number of points at every time.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>

#include "contact/rigid_surface.hpp"

using namespace tirefe;

namespace {

constexpr double kPi = 3.14159265358979323846;

double angle_of(const Eigen::Vector2d& point) { return std::atan2(point.y(), point.x()); }

}  // namespace

TEST_CASE("a plain drum's outline: chords with the sagitta of the tolerance, at least eight to a circle",
          "[contact][outline]") {
  const double radius = 0.85, tolerance = 2.5e-4;
  const Drum drum(2.0 * radius, Eigen::Vector2d::Zero(), MotionFunction());
  const std::vector<Eigen::Vector2d> points = drum.outline(0.0, Eigen::Vector2d::Zero(), 1.0, tolerance);
  REQUIRE(points.size() > 100);
  double largest = 0.0, smallest = 1.0;
  for (size_t i = 0; i < points.size(); ++i) {
    CHECK(points[i].norm() == Approx(radius).epsilon(1e-14));
    const Eigen::Vector2d middle = 0.5 * (points[i] + points[(i + 1) % points.size()]);  // the last joins the first
    largest = std::max(largest, radius - middle.norm());
    smallest = std::min(smallest, radius - middle.norm());
  }
  CHECK(largest <= tolerance);
  CHECK(smallest > 0.9 * tolerance);  // no finer than it needs to be
  CHECK(drum.outline(0.0, Eigen::Vector2d::Zero(), 1.0, 10.0).size() == 8);
}

TEST_CASE("a drum's outline carries its cleat and turns with the drum's angle", "[contact][outline]") {
  const double radius = 0.85, height = 0.025, length = 0.66, edge = 0.005;
  const Eigen::Vector2d centre(0.3, -0.2);
  Cleat cleat;
  cleat.height = height;
  cleat.arc_length = length;
  cleat.angle = kPi / 2;
  cleat.edge_radius = edge;
  const Drum drum(2.0 * radius, centre, MotionFunction::linear(-2.0), cleat);  // -2 rad/s
  const std::vector<Eigen::Vector2d> start = drum.outline(0.0, centre, 1.0, 2.5e-4);
  const double half = 0.5 * length / radius;
  int on_top = 0, on_steps = 0;
  double top_end = 0.0;  // how far the top reaches from the cleat's middle
  for (const Eigen::Vector2d& point : start) {
    const Eigen::Vector2d radial = point - centre;
    const double r = radial.norm(), from_middle = std::abs(angle_of(radial) - kPi / 2);
    CHECK(r >= radius - 1e-12);
    CHECK(r <= radius + height + 1e-12);
    if (r > radius + 1e-9 && r < radius + height - edge - 1e-9) {
      ++on_steps;  // the cleat's sides: radial, at its ends
      CHECK(from_middle == Approx(half).epsilon(1e-12));
    }
    if (r > radius + height - 1e-12) {
      ++on_top;
      top_end = std::max(top_end, from_middle);
    }
  }
  CHECK(on_steps == 2);
  CHECK(on_top > 10);
  // The top ends where the edges' fillets touch it: at the angle of the fillets' centres.
  CHECK(top_end == Approx(half - std::asin(edge / (radius + height - edge))).epsilon(1e-12));
  // 0.7 s later: the same points, turned by -1.4 rad about the drum's axis.
  const std::vector<Eigen::Vector2d> later = drum.outline(0.7, centre, 1.0, 2.5e-4);
  REQUIRE(later.size() == start.size());
  const Eigen::Matrix2d turn = Eigen::Rotation2Dd(-1.4).toRotationMatrix();
  double worst = 0.0;
  for (size_t i = 0; i < start.size(); ++i)
    worst = std::max(worst, (later[i] - (centre + turn * (start[i] - centre))).norm());
  CHECK(worst < 1e-14);
}

TEST_CASE("a road's outline: the profile exact where the road moved, its rays out to the reach", "[contact][outline]") {
  const std::vector<Eigen::Vector2d> pothole = RoadProfile::pothole_points(1.0, 0.3, 0.05);
  const RoadProfile road(pothole, 0.0, RigidMotion::translation(MotionFunction::linear(-3.0)));
  const Eigen::Vector2d centre(0.2, 0.3);
  const double reach = 2.0;
  const std::vector<Eigen::Vector2d> points = road.outline(0.5, centre, reach, 1e-4);
  REQUIRE(points.size() == pothole.size() + 2);
  for (size_t i = 0; i < pothole.size(); ++i)
    CHECK((points[i + 1] - (pothole[i] - Eigen::Vector2d(1.5, 0.0))).norm() < 1e-15);
  CHECK((points.front() - Eigen::Vector2d(centre.x() - reach, 0.0)).norm() < 1e-15);
  CHECK((points.back() - Eigen::Vector2d(centre.x() + reach, 0.0)).norm() < 1e-15);
  // The pothole 30 m away: the ray behind it ends at it, the count stays.
  const std::vector<Eigen::Vector2d> far = road.outline(10.0, centre, reach, 1e-4);
  REQUIRE(far.size() == points.size());
  CHECK(far.front() == far[1]);
  CHECK(far.back().x() == Approx(centre.x() + reach).epsilon(1e-15));
}

TEST_CASE("a tilted flat road's outline: its anchor between two ends the reach past the centre", "[contact][outline]") {
  const Eigen::Vector2d anchor(0.0, -0.1), direction = Eigen::Vector2d(1.0, 0.1).normalized();
  const FlatRoad road(anchor, direction);
  const Eigen::Vector2d centre(0.4, 0.5);
  const std::vector<Eigen::Vector2d> points = road.outline(0.0, centre, 1.5, 1e-4);
  REQUIRE(points.size() == 3);
  CHECK(points[1] == anchor);
  CHECK(direction.dot(points.front() - centre) == Approx(-1.5).epsilon(1e-14));
  CHECK(direction.dot(points.back() - centre) == Approx(1.5).epsilon(1e-14));
  CHECK(std::abs((points.back() - anchor).x() * direction.y() - (points.back() - anchor).y() * direction.x()) < 1e-15);
}
