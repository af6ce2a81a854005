// SurfaceCurve: the boundary of a rigid body in its own (material) frame, a chain of
// straight pieces and circular arcs parametrised by arc length s, with the closest-point
// projection that node-to-surface contact needs (docs/model.md eq. 14).
//
// Orientation: walking along increasing s the solid lies on the right, so the outward unit
// normal is nu = k x tau (k out of the plane, tau the unit tangent). The curvature kappa is
// defined by d(tau)/ds = -kappa nu: positive where the body is convex (a drum seen from
// outside: kappa = 1/R), negative in hollows, zero on straight pieces.
//
// Projection of a point x onto a smooth part, with y the closest point and g = (x - y).nu:
//     dg/dx = nu^T,   ds/dx = tau^T / (1 + kappa g),   dnu/dx = kappa/(1 + kappa g) tau tau^T.
// Vertex rule: where two pieces meet at an angle (a corner) the closest point of every x in
// the corner's wedge is the vertex v itself. There the normal is the unit vector from the
// vertex to the node, with the gap its distance,
//     nu = sigma (x - v)/|x - v|,   g = sigma |x - v|,   sigma = +1 at a convex corner
//                                                               (-1 at a concave one),
// which turns continuously from one face's normal to the other's as x passes around the
// corner (gap and normal are continuous). This is the limit of a fillet of radius -> 0:
//     ds/dx = 0,   dnu/dx = tau tau^T / g.
// Inside a sharp convex corner (a penetrating node) the nearer face wins: the normal jumps
// on the corner's bisector. Rounding the convex corners (edge_radius > 0) with tangent
// circular fillets removes that jump for penetrations smaller than the radius.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <vector>

namespace tirefe {

/// Closest-point projection of a point onto a surface, and what the contact tangent needs.
struct SurfaceProjection {
  double gap = 0.0;                                    // g = (x - y).nu [m]; negative: penetration
  double coordinate = 0.0;                             // s of y: arc length in the surface's own frame [m]
  Eigen::Vector2d point = Eigen::Vector2d::Zero();     // y
  Eigen::Vector2d normal = Eigen::Vector2d::UnitY();   // nu, outward
  Eigen::Vector2d tangent = Eigen::Vector2d::UnitX();  // tau, toward increasing s; nu = k x tau
  double curvature = 0.0;                              // kappa at y [1/m] (+-infinity at a vertex)
  double arc_rate = 1.0;                               // ds/dx = arc_rate tau^T:  1/(1 + kappa g); 0 at a vertex
  double normal_rate = 0.0;  // dnu/dx = normal_rate tau tau^T:  kappa/(1 + kappa g); 1/g at a vertex
  bool at_vertex = false;
};

class SurfaceCurve {
 public:
  /// One straight piece or circular arc. Pieces are given in order along the curve, each
  /// starting where the previous one ends.
  class Piece {
   public:
    static Piece segment(const Eigen::Vector2d& start, const Eigen::Vector2d& end);
    /// Comes from infinitely far back along 'direction' and ends at 'end'.
    static Piece ray_to(const Eigen::Vector2d& end, const Eigen::Vector2d& direction);
    /// Starts at 'start' and runs to infinity along 'direction'.
    static Piece ray_from(const Eigen::Vector2d& start, const Eigen::Vector2d& direction);
    /// An infinite straight line through 'point' (s = 0 there).
    static Piece line(const Eigen::Vector2d& point, const Eigen::Vector2d& direction);
    /// Arc of a circle from start_angle, sweeping 'sweep' radians (negative: clockwise).
    static Piece arc(const Eigen::Vector2d& centre, double radius, double start_angle, double sweep);

    bool is_arc() const { return arc_; }
    double length() const { return end_ - begin_; }
    /// An arc's centre and radius.
    const Eigen::Vector2d& centre() const { return origin_; }
    double radius() const { return radius_; }
    /// Point, unit tangent and curvature at local arc length l (l = 0 at the line's
    /// anchor point or the arc's start).
    Eigen::Vector2d point(double l) const;
    Eigen::Vector2d tangent(double l) const;
    /// Point and tangent together (an arc's sine and cosine once), the values of point()
    /// and tangent().
    void point_and_tangent(double l, Eigen::Vector2d& point, Eigen::Vector2d& tangent) const {
      if (arc_) return arc_point_and_tangent(l, point, tangent);
      point = origin_ + l * direction_;
      tangent = direction_;
    }
    double curvature() const { return arc_ ? -orientation_ / radius_ : 0.0; }
    /// Local arc length of the point of this piece closest to x.
    double closest(const Eigen::Vector2d& x) const {
      return arc_ ? arc_closest(x) : std::clamp((x - origin_).dot(direction_), begin_, end_);
    }
    /// closest(x) with the point and tangent there; inside an arc's span they come from
    /// the direction of x from the centre rather than from the sine and cosine of an angle.
    void closest_point(const Eigen::Vector2d& x, double& l, Eigen::Vector2d& point, Eigen::Vector2d& tangent) const {
      l = closest(x);
      if (arc_) return arc_closest_point(x, l, point, tangent);
      point_and_tangent(l, point, tangent);
    }

   private:
    friend class SurfaceCurve;
    bool arc_ = false;
    Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();             // line: anchor point; arc: centre
    Eigen::Vector2d direction_ = Eigen::Vector2d::UnitX();         // line: unit direction
    double radius_ = 0.0, start_angle_ = 0.0, orientation_ = 1.0;  // arc (+1 counter-clockwise)
    double begin_ = 0.0, end_ = 0.0;                               // local range of l (lines may reach +-infinity)
    double shift_ = 0.0;                                           // s = shift + l on the finished curve
    // An arc's point and tangent at its two ends, kept by keep_ends() once its span is final:
    // a point outside the span is projected onto the nearer end, without a sine or cosine.
    Eigen::Vector2d begin_point_ = Eigen::Vector2d::Zero(), begin_tangent_ = Eigen::Vector2d::Zero();
    Eigen::Vector2d end_point_ = Eigen::Vector2d::Zero(), end_tangent_ = Eigen::Vector2d::Zero();
    void keep_ends();
    // The arc's side of point_and_tangent, closest and closest_point (the straight side inline:
    // a long road's projections are mostly on straight pieces).
    void arc_point_and_tangent(double l, Eigen::Vector2d& point, Eigen::Vector2d& tangent) const;
    double arc_closest(const Eigen::Vector2d& x) const;
    void arc_closest_point(const Eigen::Vector2d& x, double l, Eigen::Vector2d& point, Eigen::Vector2d& tangent) const;
  };

  /// A corner left after rounding: where the vertex rule applies.
  struct Corner {
    Eigen::Vector2d point;
    double coordinate;
    bool convex;
  };

  /// Chains the pieces (each must start where the previous ends; a closed curve's last
  /// piece ends where the first starts, an open one starts and ends with rays), rounds every convex corner with a
  /// tangent fillet of edge_radius (> 0), and numbers the arc length from the first piece's start (from the end of a
  /// leading ray). Throws ModelError for gaps, fold-backs, or a radius that does not fit.
  SurfaceCurve(std::vector<Piece> pieces, bool closed, double edge_radius = 0.0);

  SurfaceProjection project(const Eigen::Vector2d& x) const;
  /// Point and tangent at arc length s (taken modulo length() on a closed curve).
  Eigen::Vector2d point(double s) const;
  Eigen::Vector2d tangent(double s) const;
  bool closed() const { return closed_; }
  /// Total arc length (infinite for a curve with rays).
  double length() const { return length_; }
  /// to - from, wrapped into [-length/2, length/2] on a closed curve.
  double arc_difference(double to, double from) const;
  const std::vector<Piece>& pieces() const { return pieces_; }
  const std::vector<Corner>& corners() const { return corners_; }

  /// The curve as a polyline to draw: the ends of every piece, arcs divided into chords
  /// whose sagitta r (1 - cos(step / 2)) stays within 'tolerance' (at least 8 to a circle),
  /// in the order of s. A closed curve goes round once (its last point joins the first);
  /// an open one ends at its rays' finite ends (a straight line: at its anchor point), with
  /// the rays' unit directions pointing away from the curve.
  struct Outline {
    std::vector<Eigen::Vector2d> points;
    Eigen::Vector2d leading = Eigen::Vector2d::Zero(), trailing = Eigen::Vector2d::Zero();
  };
  Outline outline(double tolerance) const;

 private:
  struct Joint {  // between piece i and the next one
    bool corner = false, convex = false;
    Eigen::Vector2d mean_normal = Eigen::Vector2d::UnitY();
  };
  void round_convex_corners(double radius);
  void number_arc_length();
  int piece_at(double s) const;
  const Joint* joint_after(int piece) const;
  const Joint* joint_before(int piece) const;
  /// The closest point to x of one piece, as the search keeps it.
  struct Candidate {
    int piece = -1;  // -1: none
    double l = 0.0;
    double distance = std::numeric_limits<double>::infinity();  // squared
    Eigen::Vector2d point = Eigen::Vector2d::Zero(), tangent = Eigen::Vector2d::Zero();
  };
  Candidate candidate(int i, const Eigen::Vector2d& x) const;
  /// The pieces first..last that may hold the closest point to x. On an x-monotone curve of
  /// many pieces a window around the piece above or below x, whose projection is 'centre'
  /// (none elsewhere).
  void candidate_range(const Eigen::Vector2d& x, int& first, int& last, Candidate& centre) const;
  /// The first piece whose x-range reaches x (std::lower_bound over x_max_), from its cell.
  int first_reaching(double x) const;
  void index_cells();
  /// True if piece i lies farther than 'reach' from x, by bounds without trigonometry (a
  /// ball around the piece; an arc's circle). Never for a ray or a line.
  bool beyond(int i, const Eigen::Vector2d& x, double reach) const;

  std::vector<Piece> pieces_;
  std::vector<Joint> joints_;  // joints_[i] follows pieces_[i]; the last one only when closed
  std::vector<Corner> corners_;
  std::vector<double> x_min_, x_max_;  // per piece, for the search window of x-monotone curves
  // Cells of equal width over the x-monotone curve's finite part, each with the first piece
  // whose x-range reaches its left edge: where the search for the piece at x starts.
  std::vector<int> cell_first_;
  double cell_origin_ = 0.0, cells_per_x_ = 0.0;
  struct Ball {  // holds a bounded piece: its middle and the distance from there to its ends
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    double radius = std::numeric_limits<double>::infinity();
  };
  std::vector<Ball> balls_;  // per piece
  bool closed_ = false;
  bool x_monotone_ = false;
  double length_ = 0.0;
  double scale_ = 1.0;  // size of the curve, for round-off thresholds
};

}  // namespace tirefe
