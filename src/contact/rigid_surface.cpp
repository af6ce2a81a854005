#include "contact/rigid_surface.hpp"

#include <algorithm>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/mesh.hpp"

namespace tirefe {

namespace {
constexpr double kPi = 3.14159265358979323846;
using Piece = SurfaceCurve::Piece;

void require(bool condition, const std::string& message) {
  if (!condition) throw ModelError(message);
}
}  // namespace

// ---- RigidSurface ------------------------------------------------------------------

SurfaceProjection RigidSurface::project(const Eigen::Vector2d& x, const RigidPose& pose) const {
  SurfaceProjection projection = curve_.project(motion_.to_material(x, pose));
  projection.point = motion_.to_space(projection.point, pose);
  projection.normal = pose.rotation * projection.normal;
  projection.tangent = pose.rotation * projection.tangent;
  return projection;
}

Eigen::Vector2d RigidSurface::point(double coordinate, double time) const {
  return motion_.to_space(curve_.point(coordinate), time);
}

Eigen::Vector2d RigidSurface::velocity(double coordinate, double time) const {
  return motion_.velocity(point(coordinate, time), time);
}

std::vector<Eigen::Vector2d> RigidSurface::outline(double time, const Eigen::Vector2d& centre, double reach,
                                                   double tolerance) const {
  const SurfaceCurve::Outline shape = curve_.outline(tolerance);
  std::vector<Eigen::Vector2d> points;
  points.reserve(shape.points.size() + 2);
  for (const Eigen::Vector2d& material : shape.points) points.push_back(motion_.to_space(material, time));
  if (curve_.closed()) return points;
  // A ray from p along d, cut where it is 'reach' past the centre's foot on it (or at p).
  const Eigen::Matrix2d rotation = motion_.rotation_at(time);
  auto ray_end = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& direction) -> Eigen::Vector2d {
    const Eigen::Vector2d d = rotation * direction;
    return from + std::max(0.0, d.dot(centre - from) + reach) * d;
  };
  points.insert(points.begin(), ray_end(points.front(), shape.leading));
  points.push_back(ray_end(points.back(), shape.trailing));
  return points;
}

// ---- FlatRoad ----------------------------------------------------------------------

FlatRoad::FlatRoad(const Eigen::Vector2d& point, const Eigen::Vector2d& direction, RigidMotion motion)
    : RigidSurface("flat", SurfaceCurve({Piece::line(point, direction)}, false), std::move(motion)),
      point_(point),
      normal_(Eigen::Vector2d(-direction.y(), direction.x()).normalized()) {}

double FlatRoad::clearance(const Eigen::Vector2d& x, double time) const {
  return (motion().to_material(x, time) - point_).dot(normal_);
}

// ---- Drum --------------------------------------------------------------------------

namespace {
constexpr double kNearCleat = 0.1;  // [rad]: the angular margin of Drum::clearance beyond the cleat
}

namespace {

/// The drum's outline, clockwise (solid on the right): the bare drum from the cleat's foot
/// at angle - half round to its foot at angle + half, up that side, back along the top
/// (clockwise), and down the first side.
SurfaceCurve drum_curve(double radius, const Eigen::Vector2d& centre, const Cleat& cleat) {
  require(radius > 0.0 && std::isfinite(radius), "drum: the diameter must be positive");
  require(cleat.height >= 0.0 && cleat.arc_length >= 0.0 && cleat.edge_radius >= 0.0,
          "drum: cleat height, length and edge radius must be non-negative");
  if (cleat.height == 0.0) return SurfaceCurve({Piece::arc(centre, radius, 0.0, -2.0 * kPi)}, true);
  const double half = 0.5 * cleat.arc_length / radius;  // half the cleat's angular width
  require(cleat.arc_length > 0.0 && half < kPi,
          "drum: the cleat's arc length must be positive and shorter than the circumference");
  const double top = radius + cleat.height;
  const double low = cleat.angle - half, high = cleat.angle + half;
  auto radial = [&](double angle, double from, double to) {
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    return Piece::segment(centre + from * direction, centre + to * direction);
  };
  return SurfaceCurve({Piece::arc(centre, radius, low, -(2.0 * kPi - 2.0 * half)), radial(high, radius, top),
                       Piece::arc(centre, top, high, -2.0 * half), radial(low, top, radius)},
                      true, cleat.edge_radius);
}

}  // namespace

Drum::Drum(double diameter, const Eigen::Vector2d& centre, MotionFunction angle, const Cleat& cleat)
    : RigidSurface("drum", drum_curve(0.5 * diameter, centre, cleat), RigidMotion::rotation(std::move(angle), centre)),
      radius_(0.5 * diameter),
      cleat_(cleat),
      cleat_middle_(std::cos(cleat.angle), std::sin(cleat.angle)) {
  const double reach = 0.5 * cleat.arc_length / radius_ + kNearCleat;
  if (cleat.height > 0.0 && reach < kPi) near_cleat_cos_ = std::cos(reach);
}

// ---- RoadProfile -------------------------------------------------------------------

namespace {

SurfaceCurve profile_curve(const std::vector<Eigen::Vector2d>& points, double edge_radius) {
  require(points.size() >= 2, "road profile: at least two points are needed");
  for (size_t i = 0; i < points.size(); ++i) {
    require(points[i].allFinite(), "road profile: point " + std::to_string(i + 1) + " is not finite");
    if (i == 0) continue;
    require(points[i].x() >= points[i - 1].x(),
            "road profile: x decreases at point " + std::to_string(i + 1) + " (x must not decrease)");
    require(points[i] != points[i - 1], "road profile: point " + std::to_string(i + 1) + " repeats the one before");
  }
  std::vector<Piece> pieces;
  pieces.reserve(points.size() + 1);
  pieces.push_back(Piece::ray_to(points.front(), Eigen::Vector2d::UnitX()));
  for (size_t i = 1; i < points.size(); ++i) pieces.push_back(Piece::segment(points[i - 1], points[i]));
  pieces.push_back(Piece::ray_from(points.back(), Eigen::Vector2d::UnitX()));
  return SurfaceCurve(std::move(pieces), false, edge_radius);
}

}  // namespace

RoadProfile::RoadProfile(const std::vector<Eigen::Vector2d>& points, double edge_radius, RigidMotion motion)
    : RigidSurface("profile", profile_curve(points, edge_radius), std::move(motion)) {
  highest_ = points.front().y();
  for (const Eigen::Vector2d& point : points) highest_ = std::max(highest_, point.y());
}

double RoadProfile::clearance(const Eigen::Vector2d& x, double time) const {
  // Every point of the profile, its level ends included, lies at or below its highest point.
  return motion().to_material(x, time).y() - highest_;
}

std::vector<Eigen::Vector2d> RoadProfile::read_points(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ModelError("road profile '" + path + "': cannot open the file");
  std::vector<Eigen::Vector2d> points;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string data = line.substr(0, line.find('#'));
    std::istringstream fields(data);
    double x = 0.0, y = 0.0;
    std::string rest;
    if (data.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank or comment
    const auto fail = [&](const std::string& what) {
      throw ModelError("road profile '" + path + "', line " + std::to_string(number) + ": " + what);
    };
    if (!(fields >> x >> y) || (fields >> rest)) fail("expected two numbers 'x y', got '" + data + "'");
    if (!std::isfinite(x) || !std::isfinite(y)) fail("the values must be finite");
    if (!points.empty() && x < points.back().x())
      fail("x = " + std::to_string(x) + " is smaller than the previous x = " + std::to_string(points.back().x()) +
           " (x must not decrease)");
    if (!points.empty() && points.back() == Eigen::Vector2d(x, y)) fail("the point repeats the one before");
    points.emplace_back(x, y);
  }
  if (points.size() < 2)
    throw ModelError("road profile '" + path + "': at least two points are needed (found " +
                     std::to_string(points.size()) + ")");
  return points;
}

std::vector<Eigen::Vector2d> RoadProfile::pothole_points(double start, double length, double depth, double level) {
  require(length > 0.0 && depth > 0.0, "pothole: length and depth must be positive");
  return {{start, level}, {start, level - depth}, {start + length, level - depth}, {start + length, level}};
}

std::vector<Eigen::Vector2d> RoadProfile::cleat_points(double start, double length, double height, double level) {
  require(length > 0.0 && height > 0.0, "cleat: length and height must be positive");
  return {{start, level}, {start, level + height}, {start + length, level + height}, {start + length, level}};
}

double Drum::clearance(const Eigen::Vector2d& x, double time) const {
  // A drum turns about its fixed axis (its motion is a rotation alone).
  const Eigen::Vector2d arm = x - centre();
  const double distance = arm.norm();
  if (near_cleat_cos_ > -1.0 && arm.dot(motion().pose(time).rotation * cleat_middle_) < near_cleat_cos_ * distance) {
    // More than kNearCleat beyond the cleat's span in angle: no nearer to the cleat than
    // 2 R sin(kNearCleat / 2) (two points at radii >= R that far apart in angle).
    return std::min(distance - radius_, 2.0 * radius_ * std::sin(0.5 * kNearCleat));
  }
  return distance - (radius_ + std::max(cleat_.height, 0.0));
}

}  // namespace tirefe
