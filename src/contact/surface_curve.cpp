#include "contact/surface_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include "core/mesh.hpp"

namespace tirefe {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kWindowedPieces = 8;  // an x-monotone curve of this many pieces is searched in a window

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
/// k x v: the left normal.
Eigen::Vector2d left_normal(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

std::string where(const Eigen::Vector2d& point) {
  std::ostringstream text;
  text << "(" << point.x() << ", " << point.y() << ")";
  return text.str();
}

Eigen::Vector2d unit(const Eigen::Vector2d& direction, const char* what) {
  const double norm = direction.norm();
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw ModelError(std::string(what) + ": the direction must be a non-zero vector");
  return direction / norm;
}

/// Angle in [0, 2 pi).
double wrapped_angle(double angle) {
  // fmod leaves an angle within one turn as it is; only the others pay for it.
  if (!(std::abs(angle) < 2.0 * kPi)) angle = std::fmod(angle, 2.0 * kPi);
  return angle < 0.0 ? angle + 2.0 * kPi : angle;
}

}  // namespace

// ---- pieces ------------------------------------------------------------------------

SurfaceCurve::Piece SurfaceCurve::Piece::segment(const Eigen::Vector2d& start, const Eigen::Vector2d& end) {
  Piece piece;
  const double length = (end - start).norm();
  if (!(length > 0.0)) throw ModelError("surface: zero-length segment at " + where(start) + " (repeated point)");
  piece.origin_ = start;
  piece.direction_ = (end - start) / length;
  piece.end_ = length;
  return piece;
}

SurfaceCurve::Piece SurfaceCurve::Piece::ray_to(const Eigen::Vector2d& end, const Eigen::Vector2d& direction) {
  Piece piece;
  piece.origin_ = end;
  piece.direction_ = unit(direction, "surface ray");
  piece.begin_ = -kInfinity;
  return piece;
}

SurfaceCurve::Piece SurfaceCurve::Piece::ray_from(const Eigen::Vector2d& start, const Eigen::Vector2d& direction) {
  Piece piece;
  piece.origin_ = start;
  piece.direction_ = unit(direction, "surface ray");
  piece.end_ = kInfinity;
  return piece;
}

SurfaceCurve::Piece SurfaceCurve::Piece::line(const Eigen::Vector2d& point, const Eigen::Vector2d& direction) {
  Piece piece;
  piece.origin_ = point;
  piece.direction_ = unit(direction, "surface line");
  piece.begin_ = -kInfinity;
  piece.end_ = kInfinity;
  return piece;
}

SurfaceCurve::Piece SurfaceCurve::Piece::arc(const Eigen::Vector2d& centre, double radius, double start_angle,
                                             double sweep) {
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw ModelError("surface arc: the radius must be positive (got " + std::to_string(radius) + ")");
  if (!(std::abs(sweep) > 0.0) || std::abs(sweep) > 2.0 * kPi * (1.0 + 1e-12))
    throw ModelError("surface arc: the sweep must be non-zero and at most 2 pi");
  Piece piece;
  piece.arc_ = true;
  piece.origin_ = centre;
  piece.radius_ = radius;
  piece.start_angle_ = start_angle;
  piece.orientation_ = sweep > 0.0 ? 1.0 : -1.0;
  piece.end_ = radius * std::min(std::abs(sweep), 2.0 * kPi);
  piece.keep_ends();
  return piece;
}

void SurfaceCurve::Piece::keep_ends() {
  if (!arc_) return;
  point_and_tangent(begin_, begin_point_, begin_tangent_);
  point_and_tangent(end_, end_point_, end_tangent_);
}

Eigen::Vector2d SurfaceCurve::Piece::point(double l) const {
  if (!arc_) return origin_ + l * direction_;
  const double angle = start_angle_ + orientation_ * l / radius_;
  return origin_ + radius_ * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

Eigen::Vector2d SurfaceCurve::Piece::tangent(double l) const {
  if (!arc_) return direction_;
  const double angle = start_angle_ + orientation_ * l / radius_;
  return orientation_ * Eigen::Vector2d(-std::sin(angle), std::cos(angle));
}

void SurfaceCurve::Piece::arc_point_and_tangent(double l, Eigen::Vector2d& point, Eigen::Vector2d& tangent) const {
  const double angle = start_angle_ + orientation_ * l / radius_;
  const double cosine = std::cos(angle), sine = std::sin(angle);
  point = origin_ + radius_ * Eigen::Vector2d(cosine, sine);
  tangent = orientation_ * Eigen::Vector2d(-sine, cosine);
}

double SurfaceCurve::Piece::arc_closest(const Eigen::Vector2d& x) const {
  const Eigen::Vector2d radial = x - origin_;
  if (radial.squaredNorm() == 0.0) return begin_;  // the centre: every point is as near
  const double l = radius_ * wrapped_angle(orientation_ * (std::atan2(radial.y(), radial.x()) - start_angle_));
  if (l <= end_) return l;
  // Outside the arc's span: the nearer end.
  return (x - begin_point_).squaredNorm() <= (x - end_point_).squaredNorm() ? begin_ : end_;
}

void SurfaceCurve::Piece::arc_closest_point(const Eigen::Vector2d& x, double l, Eigen::Vector2d& point,
                                            Eigen::Vector2d& tangent) const {
  // An arc's closest() gives an end (x beyond the span, or at the centre) or a point inside.
  if (l == begin_ || l == end_) {
    point = l == begin_ ? begin_point_ : end_point_;
    tangent = l == begin_ ? begin_tangent_ : end_tangent_;
    return;
  }
  const Eigen::Vector2d radial = x - origin_;
  const Eigen::Vector2d outward = radial / radial.norm();
  point = origin_ + radius_ * outward;
  tangent = orientation_ * Eigen::Vector2d(-outward.y(), outward.x());
}

// ---- building ----------------------------------------------------------------------

namespace {

using Piece = SurfaceCurve::Piece;

/// Unclamped local arc length of a point lying on the piece's line or circle (an arc's
/// points just before its start come out slightly negative).
double local_parameter(const Piece& piece, const Eigen::Vector2d& point) {
  const Eigen::Vector2d start = piece.point(0.0);
  if (!piece.is_arc()) return (point - start).dot(piece.tangent(0.0));
  const Eigen::Vector2d from = start - piece.centre(), to = point - piece.centre();
  // Travel angle from the start in the arc's own sense of rotation (clockwise when convex).
  const double sense = piece.curvature() > 0.0 ? -1.0 : 1.0;
  const double l = piece.radius() * wrapped_angle(sense * std::atan2(cross(from, to), from.dot(to)));
  const double circumference = 2.0 * kPi * piece.radius();
  return l > circumference * (1.0 - 1e-9) ? l - circumference : l;
}

/// Centre of the circle of radius r tangent to both pieces on their solid side, nearest the
/// vertex: where the pieces, offset by r toward the solid, intersect.
Eigen::Vector2d fillet_centre(const Piece& a, const Piece& b, double r, const Eigen::Vector2d& vertex) {
  auto offset_line = [r](const Piece& line, Eigen::Vector2d& origin, Eigen::Vector2d& direction) {
    direction = line.tangent(0.0);
    origin = line.point(0.0) - r * left_normal(direction);
  };
  if (!a.is_arc() && !b.is_arc()) {
    Eigen::Vector2d pa, da, pb, db;
    offset_line(a, pa, da);
    offset_line(b, pb, db);
    Eigen::Matrix2d system;
    system << da, -db;
    const Eigen::Vector2d parameters = system.partialPivLu().solve(pb - pa);
    return pa + parameters[0] * da;
  }
  if (a.is_arc() && b.is_arc())
    throw ModelError("surface: rounding the corner at " + where(vertex) + " between two arcs is not supported");
  const Piece& arc = a.is_arc() ? a : b;
  Eigen::Vector2d origin, direction;
  offset_line(a.is_arc() ? b : a, origin, direction);
  // The solid lies inside a convex (clockwise) arc, outside a concave one.
  const double radius = arc.radius() - std::copysign(r, arc.curvature());
  const auto misfit = [&] {
    return ModelError("surface: the edge radius " + std::to_string(r) + " does not fit the corner at " + where(vertex));
  };
  if (!(radius > 0.0)) throw misfit();
  // |origin + t direction - centre| = radius
  const Eigen::Vector2d f = origin - arc.centre();
  const double half_b = direction.dot(f), c = f.squaredNorm() - radius * radius;
  const double discriminant = half_b * half_b - c;
  if (discriminant < 0.0) throw misfit();
  const Eigen::Vector2d first = origin + (-half_b - std::sqrt(discriminant)) * direction;
  const Eigen::Vector2d second = origin + (-half_b + std::sqrt(discriminant)) * direction;
  return (first - vertex).squaredNorm() <= (second - vertex).squaredNorm() ? first : second;
}

/// Foot of the fillet centre on a piece's line or circle: the tangent point.
Eigen::Vector2d tangent_point(const Piece& piece, const Eigen::Vector2d& centre, double r) {
  if (!piece.is_arc()) return centre + r * left_normal(piece.tangent(0.0));
  const Eigen::Vector2d radial = centre - piece.centre();
  return piece.centre() + piece.radius() * radial / radial.norm();
}

}  // namespace

SurfaceCurve::SurfaceCurve(std::vector<Piece> pieces, bool closed, double edge_radius)
    : pieces_(std::move(pieces)), closed_(closed) {
  if (pieces_.empty()) throw ModelError("surface: no pieces");
  if (!(edge_radius >= 0.0) || !std::isfinite(edge_radius))
    throw ModelError("surface: the edge radius must be non-negative (got " + std::to_string(edge_radius) + ")");
  const int count = static_cast<int>(pieces_.size());
  scale_ = 1.0;
  for (const Piece& piece : pieces_) {
    if (std::isfinite(piece.begin_)) scale_ = std::max(scale_, piece.point(piece.begin_).norm());
    if (std::isfinite(piece.end_)) scale_ = std::max(scale_, piece.point(piece.end_).norm());
  }
  if (!closed_ && (std::isfinite(pieces_.front().begin_) || std::isfinite(pieces_.back().end_)))
    throw ModelError("surface: an open surface must start and end with rays (no free ends)");
  for (int i = 0; i < count; ++i) {
    const bool last = i == count - 1;
    if ((i > 0 || closed_) && !std::isfinite(pieces_[i].begin_))
      throw ModelError("surface: only the first piece of an open surface may start at infinity");
    if ((!last || closed_) && !std::isfinite(pieces_[i].end_))
      throw ModelError("surface: only the last piece of an open surface may run to infinity");
    if (last && !closed_) break;
    const Piece& next = pieces_[last ? 0 : i + 1];
    const Eigen::Vector2d end = pieces_[i].point(pieces_[i].end_), start = next.point(next.begin_);
    if ((end - start).norm() > 1e-9 * scale_)
      throw ModelError("surface: piece " + std::to_string(i + 1) + " ends at " + where(end) +
                       " but the next one starts at " + where(start));
    const Eigen::Vector2d t_end = pieces_[i].tangent(pieces_[i].end_), t_start = next.tangent(next.begin_);
    if (t_end.dot(t_start) < 0.0 && std::abs(cross(t_end, t_start)) < 1e-9)
      throw ModelError("surface: the surface folds back on itself at " + where(end));
  }
  if (edge_radius > 0.0) round_convex_corners(edge_radius);
  for (Piece& piece : pieces_) piece.keep_ends();  // the rounding trims arcs
  number_arc_length();
}

void SurfaceCurve::round_convex_corners(double radius) {
  const int count = static_cast<int>(pieces_.size());
  const int joints = closed_ ? count : count - 1;
  std::vector<std::optional<Piece>> fillet_after(count);
  for (int i = 0; i < joints; ++i) {
    Piece& a = pieces_[i];
    Piece& b = pieces_[(i + 1) % count];
    const Eigen::Vector2d vertex = a.point(a.end_);
    const Eigen::Vector2d t_a = a.tangent(a.end_), t_b = b.tangent(b.begin_);
    const double turn = std::atan2(cross(t_a, t_b), t_a.dot(t_b));
    if (turn > -1e-9) continue;  // smooth, or concave: not rounded
    const Eigen::Vector2d centre = fillet_centre(a, b, radius, vertex);
    const Eigen::Vector2d on_a = tangent_point(a, centre, radius), on_b = tangent_point(b, centre, radius);
    const double l_a = local_parameter(a, on_a), l_b = local_parameter(b, on_b);
    const double slack = 1e-12 * scale_;
    if (!(l_a > a.begin_ + slack && l_a <= a.end_ + slack && l_b >= b.begin_ - slack && l_b < b.end_ - slack))
      throw ModelError("surface: the edge radius " + std::to_string(radius) + " does not fit the corner at " +
                       where(vertex) + " (the pieces next to it are too short)");
    // Trim a to end at on_a and b to start at on_b.
    a.end_ = std::min(l_a, a.end_);
    if (b.arc_) {
      const double cut = std::max(l_b, 0.0);
      b.start_angle_ += b.orientation_ * cut / b.radius_;
      b.end_ -= cut;
    } else {
      b.begin_ = std::max(l_b, b.begin_);
    }
    const Eigen::Vector2d from = on_a - centre;
    const Eigen::Vector2d tangent_a = a.tangent(a.end_), tangent_b = b.tangent(b.begin_);
    const double sweep = std::atan2(cross(tangent_a, tangent_b), tangent_a.dot(tangent_b));
    fillet_after[i] = Piece::arc(centre, radius, std::atan2(from.y(), from.x()), sweep);
  }
  std::vector<Piece> rounded;
  rounded.reserve(pieces_.size() * 2);
  for (int i = 0; i < count; ++i) {
    rounded.push_back(pieces_[i]);
    if (fillet_after[i]) rounded.push_back(*fillet_after[i]);
  }
  pieces_ = std::move(rounded);
}

void SurfaceCurve::number_arc_length() {
  const int count = static_cast<int>(pieces_.size());
  Piece& first = pieces_[0];
  first.shift_ = std::isfinite(first.begin_) ? -first.begin_ : (std::isfinite(first.end_) ? -first.end_ : 0.0);
  for (int i = 1; i < count; ++i) pieces_[i].shift_ = pieces_[i - 1].shift_ + pieces_[i - 1].end_ - pieces_[i].begin_;
  const Piece& last = pieces_.back();
  length_ = (last.shift_ + last.end_) - (first.shift_ + first.begin_);
  if (!std::isfinite(length_)) length_ = kInfinity;

  // Joints that stay corners (concave ones, or all when not rounded) follow the vertex rule.
  const int joints = closed_ ? count : count - 1;
  joints_.assign(count, Joint{});
  corners_.clear();
  for (int i = 0; i < joints; ++i) {
    const Piece& a = pieces_[i];
    const Piece& b = pieces_[(i + 1) % count];
    const Eigen::Vector2d t_a = a.tangent(a.end_), t_b = b.tangent(b.begin_);
    Joint& joint = joints_[i];
    joint.corner = std::atan2(std::abs(cross(t_a, t_b)), t_a.dot(t_b)) > 1e-9;
    joint.convex = cross(t_a, t_b) < 0.0;
    joint.mean_normal = (left_normal(t_a) + left_normal(t_b)).normalized();
    if (joint.corner) corners_.push_back({a.point(a.end_), a.shift_ + a.end_, joint.convex});
  }

  // Search window: on a curve whose pieces advance in x, the pieces near a point are a
  // contiguous run, found from the cell of x (long road profiles).
  x_min_.resize(count);
  x_max_.resize(count);
  for (int i = 0; i < count; ++i) {
    const Piece& p = pieces_[i];
    double low = kInfinity, high = -kInfinity;
    auto include = [&](double x) { low = std::min(low, x), high = std::max(high, x); };
    if (p.arc_) {
      include(p.point(p.begin_).x());
      include(p.point(p.end_).x());
      // Leftmost and rightmost points of the circle, if the arc passes them.
      for (double extreme : {0.0, kPi}) {
        const double l = p.radius_ * wrapped_angle(p.orientation_ * (extreme - p.start_angle_));
        if (l <= p.end_) include(p.origin_.x() + p.radius_ * std::cos(extreme));
      }
    } else {
      // A ray runs to x = +-infinity unless it is vertical.
      for (double l : {p.begin_, p.end_})
        include(std::isfinite(l) || p.direction_.x() == 0.0 ? p.point(std::isfinite(l) ? l : 0.0).x()
                                                            : l * p.direction_.x());
    }
    x_min_[i] = low;
    x_max_[i] = high;
  }
  // Balls around the bounded pieces: a segment's middle and half its length; an arc's
  // middle and its chord to either end, 2 r sin(sweep / 4).
  balls_.assign(count, Ball{});
  for (int i = 0; i < count; ++i) {
    const Piece& p = pieces_[i];
    if (!std::isfinite(p.begin_) || !std::isfinite(p.end_)) continue;
    balls_[i].centre = p.point(0.5 * (p.begin_ + p.end_));
    balls_[i].radius =
        p.arc_ ? 2.0 * p.radius_ * std::sin(std::min(p.length() / p.radius_, 2.0 * kPi) / 4.0) : 0.5 * p.length();
  }
  x_monotone_ = !closed_;
  for (int i = 1; i < count && x_monotone_; ++i) x_monotone_ = x_min_[i] >= x_min_[i - 1] && x_max_[i] >= x_max_[i - 1];
  index_cells();
}

namespace {

/// std::lower_bound over non-decreasing values, walked from index i: the same index (for a
/// NaN too) in as many steps as lie between.
int lower_bound_from(const std::vector<double>& values, double x, int i) {
  const int count = static_cast<int>(values.size());
  while (i < count && values[i] < x) ++i;
  while (i > 0 && !(values[i - 1] < x)) --i;
  return i;
}

/// std::upper_bound over non-decreasing values, walked from index i.
int upper_bound_from(const std::vector<double>& values, double x, int i) {
  const int count = static_cast<int>(values.size());
  while (i < count && !(x < values[i])) ++i;
  while (i > 0 && x < values[i - 1]) --i;
  return i;
}

}  // namespace

void SurfaceCurve::index_cells() {
  // As many cells as pieces over the finite part, from the end of the leading ray to the
  // start of the trailing one: a road sampled evenly has a piece or two per cell.
  cell_first_.clear();
  const int count = static_cast<int>(pieces_.size());
  if (!x_monotone_ || count < kWindowedPieces) return;
  const double low = x_max_.front(), high = x_min_.back();
  if (!(high > low) || !std::isfinite(high - low)) return;
  cell_origin_ = low;
  cells_per_x_ = count / (high - low);
  cell_first_.resize(count);
  for (int c = 0; c < count; ++c)
    cell_first_[c] = lower_bound_from(x_max_, low + c / cells_per_x_, c > 0 ? cell_first_[c - 1] : 0);
}

// ---- queries -----------------------------------------------------------------------

const SurfaceCurve::Joint* SurfaceCurve::joint_after(int piece) const {
  const int count = static_cast<int>(pieces_.size());
  if (piece == count - 1 && !closed_) return nullptr;
  return &joints_[piece];
}

const SurfaceCurve::Joint* SurfaceCurve::joint_before(int piece) const {
  const int count = static_cast<int>(pieces_.size());
  if (piece == 0) return closed_ ? &joints_[count - 1] : nullptr;
  return &joints_[piece - 1];
}

int SurfaceCurve::first_reaching(double x) const {
  if (cell_first_.empty()) return static_cast<int>(std::lower_bound(x_max_.begin(), x_max_.end(), x) - x_max_.begin());
  const double cell = (x - cell_origin_) * cells_per_x_;
  const int last_cell = static_cast<int>(cell_first_.size()) - 1;
  const int c = cell > 0.0 ? (cell < last_cell ? static_cast<int>(cell) : last_cell) : 0;  // a NaN: the first
  return lower_bound_from(x_max_, x, cell_first_[c]);
}

// Inline: the search's inner step, on every piece it does not skip.
inline SurfaceCurve::Candidate SurfaceCurve::candidate(int i, const Eigen::Vector2d& x) const {
  Candidate c;
  c.piece = i;
  pieces_[i].closest_point(x, c.l, c.point, c.tangent);
  c.distance = (x - c.point).squaredNorm();
  return c;
}

void SurfaceCurve::candidate_range(const Eigen::Vector2d& x, int& first, int& last, Candidate& centre) const {
  const int count = static_cast<int>(pieces_.size());
  first = 0;
  last = count - 1;
  if (!x_monotone_ || count < kWindowedPieces) return;
  // The piece above or below x, then every piece whose x-range comes within that distance.
  const int below = std::min(first_reaching(x.x()), count - 1);
  centre = candidate(below, x);
  // An arc's reach from Piece::point at its angle, not from the direction to its centre:
  // the window holds the same pieces to the last bit however the point is found.
  const Piece& piece = pieces_[below];
  const double reach = piece.arc_ ? (x - piece.point(piece.closest(x))).norm() : std::sqrt(centre.distance);
  first = std::clamp(lower_bound_from(x_max_, x.x() - reach, below), 0, below);
  last = std::clamp(upper_bound_from(x_min_, x.x() + reach, below) - 1, below, count - 1);
}

bool SurfaceCurve::beyond(int i, const Eigen::Vector2d& x, double reach) const {
  if ((x - balls_[i].centre).norm() - balls_[i].radius > reach) return true;
  // Every point of an arc lies on its circle: |x - y| >= | |x - c| - r |.
  const Piece& piece = pieces_[i];
  return piece.arc_ && std::abs((x - piece.origin_).norm() - piece.radius_) > reach;
}

SurfaceProjection SurfaceCurve::project(const Eigen::Vector2d& x) const {
  int first = 0, last = 0;
  Candidate centre;
  candidate_range(x, first, last, centre);
  // The nearest piece, the first of them at a tie; the search starts from the window's
  // centre when its distance is known.
  Candidate nearest;
  nearest.piece = first;
  const int known = centre.distance < kInfinity ? centre.piece : -1;
  if (known >= 0) nearest = centre;
  auto reach_of = [&](double distance) {  // sqrt(distance) + margin
    return distance < kInfinity ? std::sqrt(distance) + 1e-9 * scale_ : kInfinity;
  };
  double reach = reach_of(nearest.distance);
  for (int i = first; i <= last; ++i) {
    // A piece that cannot come nearer than the nearest so far is not projected on (a drum's
    // cleat, away from it: its arcs' arctangents are most of a projection's cost). The
    // margin keeps round-off in the bound from skipping a piece as near.
    if (i == known || (reach < kInfinity && beyond(i, x, reach))) continue;
    const Candidate c = candidate(i, x);
    if (c.distance < nearest.distance || (c.distance == nearest.distance && i < nearest.piece)) {
      nearest = c;
      reach = reach_of(nearest.distance);
    }
  }
  const Piece& piece = pieces_[nearest.piece];
  // No piece nearer than infinity (x not finite or immensely far): the first piece's start.
  if (!(nearest.distance < kInfinity)) piece.point_and_tangent(nearest.l, nearest.point, nearest.tangent);
  SurfaceProjection p;
  p.point = nearest.point;
  p.coordinate = piece.shift_ + nearest.l;

  // At a corner, the vertex rule (header comment).
  const Joint* joint = nullptr;
  if (nearest.l <= piece.begin_)
    joint = joint_before(nearest.piece);
  else if (nearest.l >= piece.end_)
    joint = joint_after(nearest.piece);
  if (joint && joint->corner) {
    const Eigen::Vector2d from_vertex = x - p.point;
    const double distance = from_vertex.norm();
    const double side = joint->convex ? 1.0 : -1.0;
    // Only points on the corner's own side: round-off can bring a point just across a face to its vertex.
    if (side * from_vertex.dot(joint->mean_normal) >= 0.0) {
      p.at_vertex = true;
      p.arc_rate = 0.0;
      p.curvature = side * kInfinity;
      if (distance <= 1e-14 * scale_) {  // on the vertex: its mean normal, no rotation rate
        p.normal = joint->mean_normal;
        p.gap = 0.0;
        p.normal_rate = 0.0;
      } else {
        p.normal = side * from_vertex / distance;
        p.gap = side * distance;
        p.normal_rate = 1.0 / p.gap;
      }
      p.tangent = Eigen::Vector2d(p.normal.y(), -p.normal.x());
      return p;
    }
  }
  p.tangent = nearest.tangent;
  p.normal = left_normal(p.tangent);
  p.gap = (x - p.point).dot(p.normal);
  p.curvature = piece.curvature();
  // Past the centre of curvature the projection is meaningless; keep the rates finite.
  const double stretch = std::max(1.0 + p.curvature * p.gap, 1e-9);
  p.arc_rate = 1.0 / stretch;
  p.normal_rate = p.curvature / stretch;
  return p;
}

int SurfaceCurve::piece_at(double s) const {
  // The last piece starting at or before s (pieces start at increasing s).
  const auto after = std::upper_bound(pieces_.begin() + 1, pieces_.end(), s, [](double value, const Piece& piece) {
    return value < piece.shift_ + piece.begin_;
  });
  return static_cast<int>(after - pieces_.begin()) - 1;
}

Eigen::Vector2d SurfaceCurve::point(double s) const {
  if (closed_) s = std::fmod(s, length_) + (s < 0.0 ? length_ : 0.0);
  const Piece& piece = pieces_[piece_at(s)];
  return piece.point(s - piece.shift_);
}

Eigen::Vector2d SurfaceCurve::tangent(double s) const {
  if (closed_) s = std::fmod(s, length_) + (s < 0.0 ? length_ : 0.0);
  const Piece& piece = pieces_[piece_at(s)];
  return piece.tangent(s - piece.shift_);
}

SurfaceCurve::Outline SurfaceCurve::outline(double tolerance) const {
  Outline outline;
  std::vector<Eigen::Vector2d>& points = outline.points;
  for (const Piece& piece : pieces_) {
    const bool bounded_start = std::isfinite(piece.begin_), bounded_end = std::isfinite(piece.end_);
    if (!bounded_start && !bounded_end) {
      points.push_back(piece.origin_);
      continue;
    }
    if (points.empty()) points.push_back(piece.point(bounded_start ? piece.begin_ : piece.end_));
    if (!bounded_start || !bounded_end) continue;  // a ray adds only its finite end
    int chords = 1;
    if (piece.arc_) {
      const double step = std::min(kPi / 4.0, 2.0 * std::acos(std::max(0.0, 1.0 - tolerance / piece.radius_)));
      chords = std::max(1, static_cast<int>(std::ceil(piece.length() / piece.radius_ / step)));
    }
    for (int i = 1; i <= chords; ++i) points.push_back(piece.point(piece.begin_ + piece.length() * i / chords));
  }
  if (closed_) {
    points.pop_back();  // where it started
    return outline;
  }
  const Piece &first = pieces_.front(), &last = pieces_.back();
  outline.leading = -first.direction_;
  outline.trailing = last.direction_;
  return outline;
}

double SurfaceCurve::arc_difference(double to, double from) const {
  const double difference = to - from;
  return closed_ ? std::remainder(difference, length_) : difference;
}

}  // namespace tirefe
