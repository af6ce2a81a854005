// Contact: rigid surfaces (projection, vertex rule, fillets, motion, profile files), the
// node-to-surface kernel (tangent vs finite differences in stick and slip on flat, drum,
// fillet and vertex; the secant of a slip that reverses between iterates), and solved
// problems with closed forms: the Uzawa convergence law,
// stick/slip under a ramped load, a block sliding to rest, a moving road dragging a node,
// nodes passing a cleat's edge and a pothole, and a clear failure for hopeless contact.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

#include "contact/node_contact.hpp"
#include "deck_support.hpp"
#include "elements/point_mass.hpp"
#include "io/hdf5_file.hpp"
#include "deck/contact_output.hpp"
#include "solvers/analysis.hpp"
#include "test_support.hpp"
#include "tire/contact_penalty.hpp"
#include "tirefe/test_paths.hpp"

using namespace tirefe;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using tirefe::testing::TempDir;

constexpr double kPi = 3.14159265358979323846;

/// The drum-cleat deck's cleat: 25 mm high, 660 mm long, 5 mm edges, its middle at 'angle'.
Cleat deck_cleat(double angle) {
  Cleat cleat;
  cleat.height = 0.025;
  cleat.arc_length = 0.66;
  cleat.angle = angle;
  cleat.edge_radius = 0.005;
  return cleat;
}

double angle_between(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
}

// ---- one node on springs against a surface ------------------------------------------

struct Rig {
  Model model;
  int node = 0;
  ContactBlock* contact = nullptr;
};

/// A node at 'position' tied to ground by springs (k_x, k_y), with an optional mass, its
/// rotation fixed, in contact with 'surface'.
void build_rig(Rig& rig, const Eigen::Vector2d& position, double k_x, double k_y, double mass,
               std::shared_ptr<const RigidSurface> surface, const ContactParameters& parameters) {
  rig.node = rig.model.mesh().add_node(position);
  SpringMassProperties properties;
  properties.stiffness = {k_x, k_y, 0.0};
  properties.mass = mass;
  rig.model.add_block<NodalSpringMass>("spring").add({rig.node}, NodalSpringMass(properties));
  rig.model.fix(rig.node, kRz);
  rig.contact = &add_contact_block(rig.model, "contact", std::move(surface), {rig.node}, parameters);
}

int constant_function(Model& model) { return model.add_load_function(LoadFunction::constant(1.0)); }

/// Starts the rig's node in contact, sticking where it is, its multiplier carrying 'normal'.
void press(Rig& rig, double normal) {
  ContactHistory start;
  start.state = ContactState::Stick;
  start.normal_multiplier = start.normal_force = normal;
  start.coordinate = start.stick_coordinate =
      rig.contact->kernel(0).surface().project(rig.model.mesh().position(rig.node), 0.0).coordinate;
  rig.contact->set_history(0, start);
}

const ContactHistory& history(const Rig& rig) { return rig.contact->committed_history(0); }

// ---- tangent checks ------------------------------------------------------------------

/// The kernel's tangent equals central differences of its residual (relative 1e-6), with
/// HHT-like weights so that the factor handling is checked too.
void check_tangent(const NodeSurfaceContact& kernel, const Eigen::Vector2d& displacement, double time,
                   const ContactHistory& base, ContactState expected, double step = 1e-8,
                   bool first_evaluation = false) {
  LocalState<3> local;
  local.displacement << displacement, 0.0;
  local.velocity << 0.3, -0.1, 0.0;
  local.acceleration.setZero();
  EvaluationContext context;
  context.time = time;
  context.factors = {0.9, 0.0, 0.0, 0.9, 0.0, 0.0};
  context.first_evaluation = first_evaluation;
  ContactHistory trial = base;
  NodeSurfaceContact::Vector residual;
  NodeSurfaceContact::Matrix tangent;
  kernel.evaluate(local, context, base, trial, residual, &tangent);
  REQUIRE(trial.state == expected);
  const auto numeric = testing::finite_difference_tangent(kernel, local, context, base, step);
  INFO("tangent\n" << tangent << "\nfinite differences\n" << numeric);
  CHECK((tangent - numeric).norm() <= 1e-6 * tangent.norm());
  CHECK(tangent.row(2).isZero());
  CHECK(tangent.col(2).isZero());
}

ContactHistory touching(double normal_multiplier, double tangential_multiplier, double stick_coordinate,
                        ContactState state = ContactState::Stick) {
  ContactHistory base;
  base.state = state;
  base.normal_multiplier = normal_multiplier;
  base.tangential_multiplier = tangential_multiplier;
  base.stick_coordinate = stick_coordinate;
  return base;
}

ContactParameters penalties(double normal, double tangential, double friction) {
  ContactParameters parameters;
  parameters.normal_penalty = normal;
  parameters.tangential_penalty = tangential;
  parameters.friction = friction;
  return parameters;
}

}  // namespace

// ======================================================================================
// Surfaces
// ======================================================================================

TEST_CASE("flat road: gap, normal, convected coordinate and velocity of a moving road", "[contact][surface]") {
  // A road tilted by 30 degrees, translating with x(t) = 2 t.
  const Eigen::Vector2d direction(std::cos(kPi / 6), std::sin(kPi / 6));
  const FlatRoad road(Eigen::Vector2d(1.0, 0.5), direction, RigidMotion::translation(MotionFunction::linear(2.0)));
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  const Eigen::Vector2d x = Eigen::Vector2d(1.0, 0.5) + 0.3 * direction + 0.02 * normal;
  const SurfaceProjection at_rest = road.project(x, 0.0);
  CHECK(at_rest.gap == Approx(0.02).epsilon(1e-12));
  CHECK(at_rest.coordinate == Approx(0.3).epsilon(1e-12));
  CHECK((at_rest.normal - normal).norm() < 1e-14);
  CHECK((at_rest.tangent - direction).norm() < 1e-14);
  CHECK(at_rest.curvature == 0.0);
  CHECK(at_rest.arc_rate == 1.0);
  CHECK(at_rest.normal_rate == 0.0);
  // At t = 0.1 the road has moved 0.2 along x: the same spatial point sits over the
  // material point 0.2 cos(30) further back, and 0.2 sin(30) higher above the road.
  const SurfaceProjection moved = road.project(x, 0.1);
  CHECK(moved.coordinate == Approx(0.3 - 0.2 * direction.x()).epsilon(1e-12));
  CHECK(moved.gap == Approx(0.02 + 0.2 * direction.y()).epsilon(1e-12));
  CHECK((road.velocity(0.7, 0.1) - Eigen::Vector2d(2.0, 0.0)).norm() < 1e-12);
  CHECK((road.point(moved.coordinate, 0.1) - moved.point).norm() < 1e-12);
}

TEST_CASE("drum: gap, curvature rates, convected coordinate and rim speed of a spinning drum", "[contact][surface]") {
  const double radius = 0.85, speed = 3.0;  // rad/s, counter-clockwise
  const Eigen::Vector2d centre(0.1, -0.85);
  const Drum drum(2.0 * radius, centre, MotionFunction::linear(speed));
  const double gap = -0.002, angle = 1.2;
  const Eigen::Vector2d radial(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d x = centre + (radius + gap) * radial;
  const SurfaceProjection p0 = drum.project(x, 0.0);
  CHECK(p0.gap == Approx(gap).epsilon(1e-12));
  CHECK((p0.normal - radial).norm() < 1e-14);
  CHECK(p0.curvature == Approx(1.0 / radius).epsilon(1e-14));
  CHECK(p0.arc_rate == Approx(radius / (radius + gap)).epsilon(1e-14));
  CHECK(p0.normal_rate == Approx(1.0 / (radius + gap)).epsilon(1e-14));
  // Arc length runs clockwise from angle 0.
  CHECK(p0.coordinate == Approx(radius * (2.0 * kPi - angle)).epsilon(1e-12));
  // After the drum turned by 0.2 rad the spatial point lies over a material point 0.2 R
  // further along s (clockwise in the drum's frame).
  const SurfaceProjection p1 = drum.project(x, 0.2 / speed);
  CHECK(drum.curve().arc_difference(p1.coordinate, p0.coordinate) == Approx(0.2 * radius).epsilon(1e-12));
  CHECK(p1.gap == Approx(gap).epsilon(1e-12));
  // Rim speed omega R along the counter-clockwise tangent (-tau).
  const Eigen::Vector2d rim = drum.velocity(p1.coordinate, 0.2 / speed);
  CHECK((rim - speed * radius * (-p1.tangent)).norm() < 1e-12);
  // Slip across s = 0 is wrapped.
  CHECK(drum.arc_difference(0.01, drum.curve().length() - 0.01) == Approx(0.02).epsilon(1e-12));
}

TEST_CASE("motion functions: ramped rate and load-function motion with their rates", "[contact][surface]") {
  const MotionFunction spin = MotionFunction::ramped_rate(10.0, 4.0, 2.0);
  CHECK(spin.value(1.0) == 0.0);
  CHECK(spin.rate(1.0) == 0.0);
  CHECK(spin.value(4.0) == Approx(0.5 * 10.0 * 4.0 / 4.0).epsilon(1e-14));  // 1/2 (omega/T) t^2
  CHECK(spin.rate(4.0) == Approx(5.0).epsilon(1e-14));
  CHECK(spin.value(8.0) == Approx(10.0 * (6.0 - 2.0)).epsilon(1e-14));
  CHECK(spin.rate(8.0) == Approx(10.0).epsilon(1e-14));
  const MotionFunction table = MotionFunction::from_load_function(LoadFunction::table({{0.0, 0.0}, {2.0, 1.0}}), 3.0);
  CHECK(table.value(1.0) == Approx(1.5).epsilon(1e-12));
  CHECK(table.rate(1.0) == Approx(1.5).epsilon(1e-6));
}

TEST_CASE("motion functions: a (1 - cos) spin-up, its value the integral of its rate", "[contact][surface]") {
  // omega = 10 rad/s over T = 4 s from 2 s: the rate is omega / 2 halfway up, the value at
  // the ramp's end omega T / 2 as the linear ramp's, omega (t - t0 - T / 2) after.
  const MotionFunction spin = MotionFunction::ramped_rate(10.0, 4.0, 2.0, RampLaw::Cosine);
  CHECK(spin.value(1.0) == 0.0);
  CHECK(spin.rate(1.0) == 0.0);
  CHECK(spin.rate(4.0) == Approx(5.0).epsilon(1e-14));
  CHECK(spin.value(6.0) == Approx(20.0).epsilon(1e-14));
  CHECK(spin.value(8.0) == Approx(10.0 * (6.0 - 2.0)).epsilon(1e-14));
  CHECK(spin.rate(8.0) == Approx(10.0).epsilon(1e-14));
  const double h = 1e-5;
  for (double t : {2.5, 4.0, 5.9})
    CHECK((spin.value(t + h) - spin.value(t - h)) / (2.0 * h) == Approx(spin.rate(t)).epsilon(1e-8));
  CHECK(ramp_law_named("linear") == RampLaw::Linear);
  CHECK(ramp_law_named("cosine") == RampLaw::Cosine);
  CHECK_THROWS_AS(ramp_law_named("smooth"), ModelError);
}

TEST_CASE("vertex rule: gap and normal are continuous as a point passes around a sharp corner",
          "[contact][surface][vertex]") {
  // A cleat 20 mm high on a flat road; its top leading corner at (0, 0.02) is convex.
  const RoadProfile road(RoadProfile::cleat_points(0.0, 0.1, 0.02));
  const Eigen::Vector2d vertex(0.0, 0.02);
  REQUIRE(road.curve().corners().size() == 4);
  // A point on a circle of radius rho about the corner, from above the top face round
  // to beside the leading face (angles 135 -> -45 degrees measured from +x... mirrored: the
  // outside of the corner is the quadrant x < 0, y > 0.02).
  const double rho = 0.003;
  SurfaceProjection previous;
  const int samples = 2000;
  const double first = 0.25 * kPi, last = 1.25 * kPi, step = (last - first) / samples;
  int on_vertex = 0;
  for (int i = 0; i <= samples; ++i) {
    const double angle = first + i * step;
    const Eigen::Vector2d x = vertex + rho * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const SurfaceProjection p = road.project(x, 0.0);
    // In the wedge between the face normals (90..180 degrees) the closest point is the
    // vertex, the gap is rho and the normal points from the vertex to x.
    if (angle > 0.5 * kPi + 1e-9 && angle < kPi - 1e-9) {
      CHECK(p.at_vertex);
      CHECK(p.gap == Approx(rho).epsilon(1e-12));
      CHECK((p.normal - (x - vertex) / rho).norm() < 1e-12);
      CHECK(p.arc_rate == 0.0);
      CHECK(p.normal_rate == Approx(1.0 / rho).epsilon(1e-12));
      ++on_vertex;
    }
    if (i > 0) {
      INFO("angle " << angle);
      CHECK(std::abs(p.gap - previous.gap) <= rho * step * 1.000001);
      CHECK(angle_between(p.normal, previous.normal) <= step * 1.000001);
    }
    previous = p;
  }
  CHECK(on_vertex > samples / 3);
}

TEST_CASE("vertex rule at the cleat on a drum, and rounding removes the convex corners", "[contact][surface][vertex]") {
  Cleat cleat;
  cleat.height = 0.025;
  cleat.arc_length = 0.66;
  cleat.angle = 0.5 * kPi;
  const double radius = 0.85;
  const Drum sharp(2.0 * radius, Eigen::Vector2d::Zero(), MotionFunction(), cleat);
  REQUIRE(sharp.curve().corners().size() == 4);
  int convex = 0;
  for (const auto& corner : sharp.curve().corners()) convex += corner.convex ? 1 : 0;
  CHECK(convex == 2);
  // The top edge at angle pi/2 + L/(2R): a point just outside, radially above the top,
  // and one beside the side face, bracket the vertex region continuously.
  const double edge = 0.5 * kPi + 0.5 * cleat.arc_length / radius;
  const Eigen::Vector2d vertex = (radius + cleat.height) * Eigen::Vector2d(std::cos(edge), std::sin(edge));
  SurfaceProjection previous;
  for (int i = 0; i <= 400; ++i) {
    // Along a line at constant 4 mm above the top arc's level, past the edge.
    const double angle = edge - 0.01 + 0.02 * i / 400.0;
    const Eigen::Vector2d x = (radius + cleat.height + 0.004) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const SurfaceProjection p = sharp.project(x, 0.0);
    CHECK(p.gap > 0.0);
    if (i > 0) {
      CHECK(std::abs(p.gap - previous.gap) < 1e-4);
      CHECK(angle_between(p.normal, previous.normal) < 0.05);
    }
    if (p.at_vertex) CHECK((p.point - vertex).norm() < 1e-12);
    previous = p;
  }

  cleat.edge_radius = 0.008;
  const Drum rounded(2.0 * radius, Eigen::Vector2d::Zero(), MotionFunction(), cleat);
  REQUIRE(rounded.curve().corners().size() == 2);  // the two concave feet remain
  for (const auto& corner : rounded.curve().corners()) CHECK_FALSE(corner.convex);
  // The tangent is continuous along the rounded drum, and the fillets have curvature 1/r.
  const SurfaceCurve& curve = rounded.curve();
  int fillets = 0;
  for (const auto& piece : curve.pieces())
    if (piece.is_arc() && std::abs(piece.curvature() - 1.0 / cleat.edge_radius) < 1e-9) ++fillets;
  CHECK(fillets == 2);
  const int samples = 20000;
  for (int i = 0; i < samples; ++i) {
    const double s = curve.length() * i / samples, ds = curve.length() / samples;
    const double turn = angle_between(curve.tangent(s), curve.tangent(s + ds));
    const bool near_foot = [&] {
      for (const auto& corner : curve.corners())
        if (std::abs(curve.arc_difference(corner.coordinate, s)) < 2 * ds) return true;
      return false;
    }();
    if (!near_foot) CHECK(turn <= ds / cleat.edge_radius * 1.0001);
  }
}

TEST_CASE("rounded profile edges: projection on a fillet has the fillet's curvature", "[contact][surface]") {
  const double r = 0.005;
  const RoadProfile road(RoadProfile::cleat_points(0.0, 0.1, 0.02), r);
  const Eigen::Vector2d centre(r, 0.02 - r);  // fillet of the leading top edge
  const double angle = 0.7 * kPi, depth = 0.0007;
  const Eigen::Vector2d radial(std::cos(angle), std::sin(angle));
  const SurfaceProjection p = road.project(centre + (r - depth) * radial, 0.0);
  CHECK_FALSE(p.at_vertex);
  CHECK(p.gap == Approx(-depth).epsilon(1e-12));
  CHECK((p.normal - radial).norm() < 1e-12);
  CHECK(p.curvature == Approx(1.0 / r).epsilon(1e-12));
  CHECK(p.arc_rate == Approx(1.0 / (1.0 - depth / r)).epsilon(1e-12));
  // Arc length: leading face (0.02 - r) then the fillet from its start to the angle.
  CHECK(p.coordinate == Approx((0.02 - r) + r * (kPi - angle)).epsilon(1e-12));
  CHECK_THROWS_WITH(RoadProfile(RoadProfile::cleat_points(0.0, 0.1, 0.02), 0.03), Contains("does not fit"));
}

TEST_CASE("road profile files: comments, vertical steps, and errors naming file and line", "[contact][surface]") {
  TempDir folder;
  const std::string good = folder.write("road.txt",
                                        "# x y\n"
                                        "0.0 0.0   # start\n"
                                        "\n"
                                        "1.0 0.0\n"
                                        "1.0 -0.1\n"
                                        "1.76 -0.1\n"
                                        "1.76 0.0\n"
                                        "3.0 0.0\n");
  const auto points = RoadProfile::read_points(good);
  REQUIRE(points.size() == 6);
  const RoadProfile road(points);
  CHECK(road.project(Eigen::Vector2d(1.4, -0.09), 0.0).gap == Approx(0.01).epsilon(1e-12));
  CHECK(road.project(Eigen::Vector2d(-5.0, 0.2), 0.0).gap == Approx(0.2).epsilon(1e-12));  // level beyond the ends
  CHECK(road.project(Eigen::Vector2d(9.0, 0.2), 0.0).gap == Approx(0.2).epsilon(1e-12));

  const std::string decreasing = folder.write("back.txt", "0 0\n1 0\n0.5 0\n");
  CHECK_THROWS_WITH(RoadProfile::read_points(decreasing),
                    Contains("back.txt', line 3") && Contains("must not decrease"));
  const std::string garbage = folder.write("bad.txt", "0 0\n# fine\n1 zero\n");
  CHECK_THROWS_WITH(RoadProfile::read_points(garbage), Contains("bad.txt', line 3") && Contains("two numbers"));
  const std::string extra = folder.write("three.txt", "0 0 0\n");
  CHECK_THROWS_WITH(RoadProfile::read_points(extra), Contains("line 1"));
  CHECK_THROWS_WITH(RoadProfile::read_points(folder.path("missing.txt")),
                    Contains("missing.txt") && Contains("cannot open"));
  CHECK_THROWS_WITH(RoadProfile::read_points(folder.write("one.txt", "0 0\n")), Contains("at least two"));
}

TEST_CASE("long road profiles are searched in a window and give the same projection", "[contact][surface]") {
  // A wavy road of 2000 points; the windowed search must agree with brute force.
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 2000; ++i) points.emplace_back(0.01 * i, 0.003 * std::sin(0.37 * i) + (i % 97 == 0 ? 0.01 : 0.0));
  const RoadProfile road(points);
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector2d x(0.0667 * k - 0.5, 0.02 * std::cos(1.3 * k));
    const SurfaceProjection p = road.project(x, 0.0);
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& piece : road.curve().pieces())
      nearest = std::min(nearest, (x - piece.point(piece.closest(x))).norm());
    CHECK(std::abs(p.gap) == Approx(nearest).epsilon(1e-12));
  }
}

TEST_CASE("a long road's projection is the first nearest of all its pieces to the bit", "[contact][surface]") {
  // A random profile of 4000 points at uneven spacing with vertical steps, its convex edges
  // rounded, and points near it, right above its points, beyond its ends and far above it:
  // point, tangent and gap are those of the first piece nearest among all, found by
  // projecting on every piece with the same arithmetic.
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector2d> points{{-0.3, 0.0}};
  bool stepped = false;
  for (int i = 1; i < 4000; ++i) {
    const Eigen::Vector2d& last = points.back();
    stepped = !stepped && unit(random) < 0.03;
    const double dx = stepped ? 0.0 : 0.005 + 0.035 * unit(random);
    const double dy = stepped ? (unit(random) < 0.5 ? -1.0 : 1.0) * (0.005 + 0.01 * unit(random))
                              : 0.3 * dx * (2.0 * unit(random) - 1.0);
    points.emplace_back(last.x() + dx, last.y() + dy);
  }
  const RoadProfile road(points, 0.001);
  const SurfaceCurve& curve = road.curve();
  REQUIRE(curve.pieces().size() > points.size() + 50);  // fillets among the segments

  struct Nearest {
    double distance = std::numeric_limits<double>::infinity();
    Eigen::Vector2d point = Eigen::Vector2d::Zero(), tangent = Eigen::Vector2d::Zero();
  };
  auto nearest_of_all = [&](const Eigen::Vector2d& x) {
    Nearest nearest;
    for (const SurfaceCurve::Piece& piece : curve.pieces()) {
      double l = 0.0;
      Eigen::Vector2d point, tangent;
      piece.closest_point(x, l, point, tangent);
      const double distance = (x - point).squaredNorm();
      if (distance < nearest.distance) nearest = {distance, point, tangent};
    }
    return nearest;
  };
  std::vector<Eigen::Vector2d> queries;
  for (int k = 0; k < 3000; ++k) {  // near the profile
    const int i = static_cast<int>(unit(random) * (points.size() - 1));
    const Eigen::Vector2d on = points[i] + unit(random) * (points[i + 1] - points[i]);
    queries.push_back(on + Eigen::Vector2d(0.06 * unit(random) - 0.03, 0.06 * unit(random) - 0.02));
  }
  for (int k = 0; k < 1000; ++k) {  // right above (and below) a point: equal x
    const Eigen::Vector2d& point = points[static_cast<int>(unit(random) * points.size())];
    queries.push_back(point + Eigen::Vector2d(0.0, 0.04 * unit(random) - 0.01));
  }
  for (double x : {-5.0, -0.3, points.back().x(), points.back().x() + 5.0}) queries.emplace_back(x, 0.01);
  for (int k = 0; k < 20; ++k) queries.emplace_back(points.back().x() * unit(random), 0.5 + unit(random));
  int at_vertex = 0;
  for (const Eigen::Vector2d& x : queries) {
    const SurfaceProjection p = road.project(x, 0.0);
    const Nearest nearest = nearest_of_all(x);
    REQUIRE(p.point == nearest.point);
    if (p.at_vertex) {
      CHECK(std::abs(p.gap) == std::sqrt(nearest.distance));
      ++at_vertex;
    } else {
      CHECK(p.tangent == nearest.tangent);
      CHECK(p.gap == (x - nearest.point).dot(Eigen::Vector2d(-nearest.tangent.y(), nearest.tangent.x())));
    }
    CHECK((curve.point(p.coordinate) - p.point).norm() <= 1e-12);
  }
  CHECK(at_vertex > 10);
}

TEST_CASE("a drum's projection skips the pieces that cannot be nearer and gives the nearest", "[contact][surface]") {
  // Points all round a drum with a rounded cleat, on the drum and up to 40 mm off it, near
  // the cleat's faces and fillets: the projection's point is the one of the nearest piece,
  // found by projecting on every piece.
  const Cleat cleat = deck_cleat(0.5 * kPi);
  const Drum drum(1.7, Eigen::Vector2d(0.1, -0.2), MotionFunction(), cleat);
  int near_cleat = 0, same_tangent = 0;
  for (int k = 0; k < 4000; ++k) {
    const double angle = 2.0 * kPi * k / 4000.0, lift = -0.005 + 0.045 * ((k * 37) % 101) / 100.0;
    const Eigen::Vector2d x = drum.centre() + (0.85 + lift) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const SurfaceProjection p = drum.project(x, 0.0);
    double nearest = std::numeric_limits<double>::infinity();
    Eigen::Vector2d point = Eigen::Vector2d::Zero(), tangent = Eigen::Vector2d::Zero();
    for (const auto& piece : drum.curve().pieces()) {
      const double l = piece.closest(x);
      const Eigen::Vector2d candidate = piece.point(l);
      if ((x - candidate).squaredNorm() < nearest)
        nearest = (x - candidate).squaredNorm(), point = candidate, tangent = piece.tangent(l);
    }
    // To round-off: an arc's point and tangent come from the direction to its centre here,
    // from the angle of its arc length there (an error of a few 1e-16 rad times 2 pi).
    CHECK((p.point - point).norm() <= 4e-15);
    if ((p.point - point).norm() <= 4e-15 && !p.at_vertex) {
      CHECK((p.tangent - tangent).norm() <= 4e-15);
      ++same_tangent;
    }
    near_cleat += std::abs(std::remainder(angle - cleat.angle, 2.0 * kPi)) < 0.5 ? 1 : 0;
  }
  CHECK(near_cleat > 500);
  CHECK(same_tangent > 3500);
}

TEST_CASE("a surface's pose kept for one time gives the numbers of the motion evaluated afresh",
          "[contact][surface][pose]") {
  // A drum and a moving road asked in runs at one time, then the other surface, then
  // another time and back (each change evaluates the pose again): projection and velocity
  // equal, bit for bit, the plain formulas with the motion's functions, sine and cosine
  // evaluated for the one query.
  const Cleat cleat = deck_cleat(-0.5 * kPi);
  const Eigen::Vector2d centre(0.1, -0.2);
  const Drum drum(1.7, centre, MotionFunction::ramped_rate(-16.8, 4.0, 2.0), cleat);
  const RoadProfile road(RoadProfile::cleat_points(-0.05, 0.08, 0.01), 0.002,
                         RigidMotion(MotionFunction::linear(-0.3), MotionFunction::linear(0.02),
                                     MotionFunction::linear(0.1), Eigen::Vector2d(0.01, 0.0)));
  struct Case {
    const RigidSurface* surface;
    std::function<Eigen::Vector2d(int)> point;
    std::function<Eigen::Vector3d(double)> rates;  // x', y', theta'
  };
  const Case cases[] = {
      {&drum,
       [&](int k) {
         const double angle = 2.0 * kPi * k / 400.0, lift = -0.004 + 0.05 * ((k * 37) % 101) / 100.0;
         return Eigen::Vector2d(centre + (0.85 + lift) * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
       },
       [](double t) { return Eigen::Vector3d(0.0, 0.0, t - 2.0 < 4.0 ? -16.8 * (t - 2.0) / 4.0 : -16.8); }},
      {&road, [](int k) { return Eigen::Vector2d(-0.1 + 0.2 * k / 400.0, -0.004 + 0.03 * ((k * 37) % 101) / 100.0); },
       [](double) { return Eigen::Vector3d(-0.3, 0.02, 0.1); }}};
  int queries = 0;
  for (double time : {2.7, 6.1, 2.7}) {
    for (const Case& c : cases) {
      const RigidMotion& motion = c.surface->motion();
      const double angle = motion.angle_at(time);
      Eigen::Matrix2d rotation;
      rotation << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
      const Eigen::Vector2d o = motion.centre(), d = motion.translation_at(time);
      const Eigen::Vector3d rates = c.rates(time);
      for (int k = 0; k < 400; ++k) {
        const Eigen::Vector2d x = c.point(k);
        SurfaceProjection plain = c.surface->curve().project(o + rotation.transpose() * (x - o - d));
        plain.point = o + d + rotation * (plain.point - o);
        const SurfaceProjection p = c.surface->project(x, time);
        CHECK(p.point == plain.point);
        CHECK(p.normal == rotation * plain.normal);
        CHECK(p.tangent == rotation * plain.tangent);
        CHECK(p.gap == plain.gap);
        CHECK(p.coordinate == plain.coordinate);
        const Eigen::Vector2d arm = x - o - d;
        CHECK(c.surface->velocity_at(x, time) ==
              Eigen::Vector2d(rates.x() - rates.z() * arm.y(), rates.y() + rates.z() * arm.x()));
        ++queries;
      }
    }
  }
  CHECK(queries == 2400);
}

TEST_CASE("a node beyond the search distance gets the full projection's answer without it",
          "[contact][surface][pose]") {
  // The deck's drum and cleat, turned part way: one kernel skips nodes whose clearance
  // exceeds the search distance, its twin projects every node. Beyond the distance both
  // give an open node with no force, no tangent and no multipliers (the skip reports the
  // clearance, a lower bound of the gap, and keeps the last coordinate); within it, and in
  // contact on the drum or on the cleat's rounded edge, the same numbers bit for bit.
  const Cleat cleat = deck_cleat(-0.5 * kPi);
  const Eigen::Vector2d centre(0.0, 0.0);
  auto drum = std::make_shared<Drum>(1.7, centre, MotionFunction::ramped_rate(-16.8, 4.0, 2.0), cleat);
  const double time = 2.3, turned = drum->motion().angle_at(time), top = 0.85 + 0.025;
  ContactParameters parameters = penalties(2e7, 2e6, 0.3);
  ContactParameters projecting = parameters;
  projecting.search_distance = 1e3;
  const Eigen::Vector2d reference(0.0, 1.2);
  const NodeSurfaceContact skipping_kernel(drum, reference, parameters), full_kernel(drum, reference, projecting);
  auto evaluate = [&](const NodeSurfaceContact& kernel, const Eigen::Vector2d& x, const ContactHistory& base,
                      ContactHistory& trial, NodeSurfaceContact::Vector& residual,
                      NodeSurfaceContact::Matrix& tangent) {
    LocalState<3> local;
    local.displacement << x - reference, 0.0;
    local.velocity << 0.3, -0.1, 0.0;
    local.acceleration.setZero();
    EvaluationContext context;
    context.time = time;
    context.factors = {0.9, 0.0, 0.0, 0.9, 0.0, 0.0};
    trial = base;
    kernel.evaluate(local, context, base, trial, residual, &tangent);
  };
  ContactHistory open;
  open.coordinate = 0.4;  // projected at an earlier step
  const Eigen::Vector2d up(0.0, 1.0);
  const double middle = cleat.angle + turned;
  const Eigen::Vector2d cleat_direction(std::cos(middle), std::sin(middle));
  // On the fillet of the cleat's top edge at angle + L/(2R), where it is at this time,
  // 0.1 mm inside: the fillet's centre lies r below the top and r from the side face.
  const double r = cleat.edge_radius, side = cleat.angle + 0.5 * cleat.arc_length / 0.85 + turned;
  const double fillet_angle = side - std::asin(r / (top - r));
  const Eigen::Vector2d fillet = centre + (top - r) * Eigen::Vector2d(std::cos(fillet_angle), std::sin(fillet_angle));
  const Eigen::Vector2d corner = centre + top * Eigen::Vector2d(std::cos(side), std::sin(side));
  const Eigen::Vector2d edge = fillet + (r - 1e-4) * (corner - fillet).normalized();
  const struct {
    const char* what;
    Eigen::Vector2d x;
    ContactHistory base;
    bool skipped;
  } nodes[] = {
      // Above the drum's top, far from the cleat: the clearance is the drum's own.
      {"just beyond the search distance", centre + (0.85 + 0.05 * (1.0 + 1e-9)) * up, open, true},
      {"far beyond it", centre + (top + 0.3) * up, open, true},
      {"just within it", centre + (0.85 + 0.05 * (1.0 - 1e-9)) * up, open, false},
      // Above the cleat's top (where the cleat is at this time): the clearance is the cleat's.
      {"just beyond it above the cleat", centre + (top + 0.05 * (1.0 + 1e-9)) * cleat_direction, open, true},
      {"just within it above the cleat", centre + (top + 0.05 * (1.0 - 1e-9)) * cleat_direction, open, false},
      {"touching down on the drum", centre + (0.85 - 2e-4) * up, open, false},
      {"sticking on the drum", centre + (0.85 - 2e-4) * up, touching(500.0, 20.0, 0.5 * kPi * 0.85), false},
      {"on the cleat's edge", edge, touching(300.0, -10.0, 0.0), false},
  };
  for (const auto& node : nodes) {
    INFO(node.what);
    ContactHistory fast, full;
    NodeSurfaceContact::Vector fast_residual, full_residual;
    NodeSurfaceContact::Matrix fast_tangent, full_tangent;
    evaluate(skipping_kernel, node.x, node.base, fast, fast_residual, fast_tangent);
    evaluate(full_kernel, node.x, node.base, full, full_residual, full_tangent);
    CHECK(fast_residual == full_residual);
    CHECK(fast_tangent == full_tangent);
    CHECK(fast.state == full.state);
    CHECK(fast.force == full.force);
    CHECK(fast.normal_multiplier == full.normal_multiplier);
    CHECK(fast.tangential_multiplier == full.tangential_multiplier);
    CHECK(fast.normal_force == full.normal_force);
    CHECK(fast.tangential_force == full.tangential_force);
    CHECK(fast.sliding_velocity == full.sliding_velocity);
    if (node.skipped) {
      CHECK(full.state == ContactState::Open);
      CHECK(fast_residual.isZero());
      CHECK(fast_tangent.isZero());
      CHECK(fast.coordinate == node.base.coordinate);
      CHECK(fast.gap > parameters.search_distance);
      CHECK(fast.gap <= full.gap);
    } else {
      CHECK(std::memcmp(&fast, &full, sizeof(ContactHistory)) == 0);
    }
  }
  // The contact cases do touch (the comparisons above are of forces, not of zeros).
  ContactHistory trial;
  NodeSurfaceContact::Vector residual;
  NodeSurfaceContact::Matrix tangent;
  evaluate(skipping_kernel, nodes[7].x, nodes[7].base, trial, residual, tangent);
  CHECK(trial.state != ContactState::Open);
  CHECK(drum->project(nodes[7].x, time).curvature == Approx(1.0 / 0.005));
  for (int k : {5, 6}) {
    evaluate(skipping_kernel, nodes[k].x, nodes[k].base, trial, residual, tangent);
    CHECK(trial.state != ContactState::Open);
  }
}

// ======================================================================================
// The kernel's tangent
// ======================================================================================

TEST_CASE("contact tangent equals finite differences in stick and slip on a moving flat road", "[contact][tangent]") {
  // A tilted road translating and turning: the tangent is taken at fixed time.
  auto road = std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 0.1),
                                         RigidMotion(MotionFunction::linear(0.2), MotionFunction::linear(0.01),
                                                     MotionFunction::linear(0.1), Eigen::Vector2d(0.5, 0.0)));
  const NodeSurfaceContact kernel(road, Eigen::Vector2d(0.1, 0.01), penalties(1e6, 5e5, 0.3));
  const double time = 0.7;
  // 4 mm into the road below the material point s = 0.12.
  const Eigen::Vector2d target = road->point(0.12, time) - 0.004 * road->project(road->point(0.12, time), time).normal;
  const Eigen::Vector2d u = target - Eigen::Vector2d(0.1, 0.01);
  const SurfaceProjection p = road->project(target, time);
  REQUIRE(p.gap == Approx(-0.004));
  check_tangent(kernel, u, time, touching(200.0, 50.0, p.coordinate - 1e-4), ContactState::Stick);
  check_tangent(kernel, u, time, touching(200.0, 50.0, p.coordinate - 1e-2), ContactState::Slip);
  check_tangent(kernel, u, time, touching(200.0, 50.0, p.coordinate + 1e-2), ContactState::Slip);
  // Open: nothing at all.
  ContactHistory base = touching(0.0, 0.0, 0.0);
  ContactHistory trial = base;
  LocalState<3> local;
  local.displacement << 0.0, 0.1, 0.0;
  local.velocity.setZero();
  NodeSurfaceContact::Vector residual;
  NodeSurfaceContact::Matrix tangent;
  kernel.evaluate(local, EvaluationContext{}, base, trial, residual, &tangent);
  CHECK(trial.state == ContactState::Open);
  CHECK(residual.isZero());
  CHECK(tangent.isZero());
}

TEST_CASE("contact tangent equals finite differences on a spinning drum (curvature terms)", "[contact][tangent]") {
  const double radius = 0.85;
  auto drum = std::make_shared<Drum>(2.0 * radius, Eigen::Vector2d(0.0, -radius), MotionFunction::linear(2.0));
  const Eigen::Vector2d position(0.05, 0.0);
  const NodeSurfaceContact kernel(drum, position, penalties(1e6, 1e6, 0.4));
  const double time = 0.3;
  const Eigen::Vector2d u(0.004, -0.003);
  const SurfaceProjection p = drum->project(position + u, time);
  REQUIRE(p.gap < 0.0);
  REQUIRE(p.normal_rate > 0.0);
  check_tangent(kernel, u, time, touching(500.0, -80.0, p.coordinate + 5e-5), ContactState::Stick);
  check_tangent(kernel, u, time, touching(500.0, -80.0, p.coordinate + 1e-2), ContactState::Slip);
  check_tangent(kernel, u, time, touching(500.0, 80.0, p.coordinate - 1e-2), ContactState::Slip);
}

TEST_CASE("contact tangent equals finite differences on a rounded edge and at a sharp vertex",
          "[contact][tangent][vertex]") {
  SECTION("on the fillet of a rounded cleat edge") {
    const double r = 0.005;
    auto road = std::make_shared<RoadProfile>(RoadProfile::cleat_points(0.0, 0.1, 0.02), r,
                                              RigidMotion::translation(MotionFunction::linear(-1.0)));
    const double time = 0.01;  // the cleat has moved 10 mm to the left
    const Eigen::Vector2d centre(r - 0.01, 0.02 - r);
    const Eigen::Vector2d position = centre + (r - 0.0005) * Eigen::Vector2d(std::cos(2.0), std::sin(2.0));
    const NodeSurfaceContact kernel(road, position, penalties(1e6, 1e6, 0.3));
    const SurfaceProjection p = road->project(position, time);
    REQUIRE(p.curvature == Approx(1.0 / r));
    check_tangent(kernel, Eigen::Vector2d::Zero(), time, touching(100.0, 10.0, p.coordinate - 1e-5),
                  ContactState::Stick);
    check_tangent(kernel, Eigen::Vector2d::Zero(), time, touching(100.0, 10.0, p.coordinate - 1e-2),
                  ContactState::Slip);
  }
  SECTION("outside a sharp convex corner, pressed by its multiplier") {
    auto road = std::make_shared<RoadProfile>(RoadProfile::cleat_points(0.0, 0.1, 0.02));
    const Eigen::Vector2d position = Eigen::Vector2d(0.0, 0.02) + 2e-4 * Eigen::Vector2d(std::cos(2.1), std::sin(2.1));
    const NodeSurfaceContact kernel(road, position, penalties(1e6, 1e6, 0.3));
    const SurfaceProjection p = road->project(position, 0.0);
    REQUIRE(p.at_vertex);
    REQUIRE(p.gap == Approx(2e-4));
    // t_N = 500 - 1e6 * 2e-4 = 300 N at a positive gap.
    check_tangent(kernel, Eigen::Vector2d::Zero(), 0.0, touching(500.0, 20.0, p.coordinate - 1e-5),
                  ContactState::Stick);
    check_tangent(kernel, Eigen::Vector2d::Zero(), 0.0, touching(500.0, 20.0, p.coordinate - 1e-3), ContactState::Slip);
  }
}

TEST_CASE("a node in contact when its step began, lifted off by the predictor, is held in the first evaluation",
          "[contact][tangent][hold]") {
  // A drum's node 1 mm off the surface, sticking there at the step's start with lambda_N =
  // 500 N: the law alone leaves it open (500 - 1e6 * 1e-3 < 0); held, it is pulled back by
  // t_N = lambda_N - eps_N g = -500 N and its stick traction, and its tangent is the
  // derivative of that force.
  const double radius = 0.85, eps_n = 1e6, eps_t = 5e5;
  auto drum = std::make_shared<Drum>(2.0 * radius, Eigen::Vector2d(0.0, -radius), MotionFunction::linear(2.0));
  const Eigen::Vector2d position(0.05, 0.0);
  const double time = 0.3;
  const Eigen::Vector2d u(0.004, -0.003);
  const SurfaceProjection on = drum->project(position + u, time);
  const Eigen::Vector2d lifted = u + (1e-3 - on.gap) * on.normal;
  const SurfaceProjection p = drum->project(position + lifted, time);
  REQUIRE(p.gap == Approx(1e-3));
  const ContactHistory base = touching(500.0, -80.0, p.coordinate + 5e-5);
  ContactParameters holding = penalties(eps_n, eps_t, 0.4);
  holding.hold_first_evaluation = true;
  const NodeSurfaceContact kernel(drum, position, holding);

  // The held force, its tangent against central differences; the history says open.
  check_tangent(kernel, lifted, time, base, ContactState::Open, 1e-8, true);
  LocalState<3> local;
  local.displacement << lifted, 0.0;
  local.velocity.setZero();
  local.acceleration.setZero();
  EvaluationContext first;
  first.time = time;
  first.first_evaluation = true;
  ContactHistory trial = base;
  NodeSurfaceContact::Vector residual;
  NodeSurfaceContact::Matrix tangent;
  kernel.evaluate(local, first, base, trial, residual, &tangent);
  const double normal = 500.0 - eps_n * 1e-3;
  const double traction = -80.0 - eps_t * drum->arc_difference(p.coordinate, base.stick_coordinate);
  const Eigen::Vector2d expected = -(normal * p.normal + traction * p.tangent);
  CHECK((residual.head<2>() - expected).norm() <= 1e-9 * expected.norm());
  CHECK(normal == Approx(-500.0));
  CHECK(trial.state == ContactState::Open);
  CHECK(trial.normal_force == 0.0);
  CHECK(trial.force.isZero());
  CHECK(trial.normal_multiplier == 0.0);

  // Later evaluations, a node open when its step began, and the hold switched off: the law.
  ContactHistory open_base = base;
  open_base.state = ContactState::Open;
  const NodeSurfaceContact plain(drum, position, penalties(eps_n, eps_t, 0.4));  // the default: no hold
  const struct {
    const char* what;
    const NodeSurfaceContact& kernel;
    const ContactHistory& base;
    bool first;
  } laws[] = {{"a later evaluation", kernel, base, false},
              {"open when the step began", kernel, open_base, true},
              {"the hold off (the default)", plain, base, true}};
  for (const auto& law : laws) {
    INFO(law.what);
    EvaluationContext context = first;
    context.first_evaluation = law.first;
    trial = law.base;
    law.kernel.evaluate(local, context, law.base, trial, residual, &tangent);
    CHECK(trial.state == ContactState::Open);
    CHECK(residual.isZero());
    CHECK(tangent.isZero());
  }
}

// ======================================================================================
// Solved problems
// ======================================================================================

TEST_CASE("Uzawa: the penetration after m augmentations is F/(k+eps) (k/(k+eps))^m", "[contact][uzawa]") {
  // A node on a spring k pushed by F against a flat wall at y = 0. Penalty solve m:
  //   k u + eps u = lambda_m - F  =>  penetration p_m = (F - lambda_m)/(k + eps),
  //   lambda_{m+1} = lambda_m + eps p_m  =>  F - lambda_{m+1} = (F - lambda_m) k/(k + eps),
  // so with lambda_0 = 0:  p_m = F/(k + eps) (k/(k + eps))^m, and lambda* = F.
  const double k = 1e4, eps = 3e4, force = 100.0;
  for (int m = 0; m <= 4; ++m) {
    Rig rig;
    ContactParameters parameters = penalties(eps, 0.0, 0.0);
    parameters.penetration_tolerance = 0.0;  // always ask for another update
    parameters.multiplier_tolerance = 0.0;
    build_rig(rig, Eigen::Vector2d::Zero(), k, k, 0.0, std::make_shared<FlatRoad>(), parameters);
    rig.model.add_nodal_load(rig.node, kUy, -force, constant_function(rig.model));
    Analysis analysis(rig.model);
    analysis.newton_settings().residual_tolerance = 1e-13;
    analysis.step_control().max_augmentations = m;
    const auto& records = analysis.advance(1.0);
    REQUIRE(records.size() == 1);
    CHECK(records[0].augmentations == m);
    const double expected = force / (k + eps) * std::pow(k / (k + eps), m);
    INFO("m = " << m);
    CHECK(-analysis.state().displacement[dof_index(rig.node, kUy)] == Approx(expected).epsilon(1e-10));
    CHECK(-history(rig).gap == Approx(expected).epsilon(1e-10));
    CHECK(history(rig).normal_force == Approx(force - k * expected).epsilon(1e-10));
  }
}

TEST_CASE("stick/slip under a ramped tangential load follows the closed form", "[contact][friction]") {
  // A node pressed by N, pulled along x by T = T_max t, held back by a weak spring k_x.
  //   stick (eps_T u_x <= mu t_N):  u_x = T/(k_x + eps_T),  friction eps_T u_x
  //   slip:                          u_x = (T - mu t_N)/k_x,  friction mu t_N
  const double normal = 1000.0, mu = 0.5, eps = 1e5, k_x = 100.0, k_y = 100.0, t_max = 2.0 * mu * normal;
  SECTION("penalty regularisation: the elastic eps_T displacement while sticking") {
    Rig rig;
    build_rig(rig, Eigen::Vector2d::Zero(), k_x, k_y, 0.0, std::make_shared<FlatRoad>(), penalties(eps, eps, mu));
    rig.model.add_nodal_load(rig.node, kUy, -normal, constant_function(rig.model));
    rig.model.add_nodal_load(rig.node, kUx, t_max, Model::kRampLoadFunction);
    Analysis analysis(rig.model);
    analysis.newton_settings().residual_tolerance = 1e-12;
    analysis.step_control().max_augmentations = 0;
    const double normal_force = eps * normal / (k_y + eps);  // the spring k_y takes a little of N
    int sticking = 0, slipping = 0;
    analysis.add_step_observer([&](const Analysis& run, const StepRecord& record) {
      const double pull = t_max * record.time;
      const double u_x = run.state().displacement[dof_index(rig.node, kUx)];
      const ContactHistory& h = history(rig);
      INFO("T = " << pull);
      CHECK(h.normal_force == Approx(normal_force).epsilon(1e-10));
      if (eps * pull / (k_x + eps) <= mu * normal_force) {
        CHECK(h.state == ContactState::Stick);
        CHECK(u_x == Approx(pull / (k_x + eps)).epsilon(1e-9));
        CHECK(h.tangential_force == Approx(-eps * u_x).epsilon(1e-9));
        ++sticking;
      } else {
        CHECK(h.state == ContactState::Slip);
        CHECK(u_x == Approx((pull - mu * normal_force) / k_x).epsilon(1e-9));
        CHECK(h.tangential_force == Approx(-mu * normal_force).epsilon(1e-12));
        ++slipping;
      }
    });
    analysis.set_time_step(0.05);
    analysis.advance(1.0);
    CHECK(sticking >= 9);
    CHECK(slipping >= 9);
  }
  SECTION("augmented Lagrangian: exact stick, and slip at exactly mu N") {
    Rig rig;
    ContactParameters parameters = penalties(eps, eps, mu);
    parameters.penetration_tolerance = 1e-9;
    parameters.multiplier_tolerance = 1e-9;
    build_rig(rig, Eigen::Vector2d::Zero(), k_x, k_y, 0.0, std::make_shared<FlatRoad>(), parameters);
    rig.model.add_nodal_load(rig.node, kUy, -normal, constant_function(rig.model));
    rig.model.add_nodal_load(rig.node, kUx, t_max, Model::kRampLoadFunction);
    Analysis analysis(rig.model);
    analysis.newton_settings().residual_tolerance = 1e-12;
    analysis.add_step_observer([&](const Analysis& run, const StepRecord& record) {
      const double pull = t_max * record.time;
      const double u_x = run.state().displacement[dof_index(rig.node, kUx)];
      const ContactHistory& h = history(rig);
      INFO("T = " << pull << ", augmentations " << record.augmentations);
      CHECK(-h.gap <= 1e-9);
      CHECK(h.normal_force == Approx(normal).epsilon(1e-7));
      if (pull < mu * normal * (1.0 - 1e-6)) {
        CHECK(h.state == ContactState::Stick);
        CHECK(std::abs(u_x) <= 1e-9);
        CHECK(h.tangential_force == Approx(-pull).epsilon(1e-6));
      } else if (pull > mu * normal * (1.0 + 1e-6)) {
        CHECK(h.state == ContactState::Slip);
        CHECK(h.tangential_force == Approx(-mu * normal).epsilon(1e-7));
        CHECK(u_x == Approx((pull - mu * normal) / k_x).epsilon(1e-6));
      }
    });
    analysis.set_time_step(0.05);
    analysis.advance(1.0);
  }
}

TEST_CASE("a block sliding on a rough road stops at t = v0/(mu g) after v0^2/(2 mu g)",
          "[contact][friction][dynamics]") {
  const double mass = 2.0, gravity = 9.81, mu = 0.4, v0 = 3.0;
  const double stop_time = v0 / (mu * gravity), distance = v0 * v0 / (2.0 * mu * gravity);
  for (const Integrator& integrator : {Integrator::newmark(), Integrator::hht(-0.1)}) {
    INFO(integrator.name());
    Rig rig;
    build_rig(rig, Eigen::Vector2d::Zero(), 0.0, 0.0, mass, std::make_shared<FlatRoad>(), penalties(1e7, 1e7, mu));
    rig.model.add_nodal_load(rig.node, kUy, -mass * gravity, constant_function(rig.model));
    // Start sliding in equilibrium: the multipliers carry the weight and the friction.
    ContactHistory start;
    start.state = ContactState::Slip;
    start.normal_multiplier = mass * gravity;
    start.tangential_multiplier = -mu * mass * gravity;
    start.normal_force = mass * gravity;
    start.tangential_force = -mu * mass * gravity;
    start.stick_coordinate = 0.0;
    start.coordinate = 0.0;
    rig.contact->set_history(0, start);
    Analysis analysis(rig.model);
    analysis.set_integrator(integrator);
    analysis.set_initial_velocity(dof_index(rig.node, kUx), v0);
    const double dt = 1e-3;
    analysis.set_time_step(dt);
    double stopped_at = -1.0, stuck_at = -1.0, previous_v = v0;
    analysis.add_step_observer([&](const Analysis& run, const StepRecord& record) {
      const double v = run.state().velocity[dof_index(rig.node, kUx)];
      // The velocity's zero crossing, interpolated within the step.
      if (stopped_at < 0.0 && v <= 0.0) stopped_at = record.time - dt * (-v) / (previous_v - v);
      if (stuck_at < 0.0 && history(rig).state == ContactState::Stick) stuck_at = record.time;
      previous_v = v;
      if (stuck_at < 0.0 && v0 - mu * gravity * record.time > mu * gravity * dt) {
        // Sliding: uniform deceleration mu g, friction mu m g, sliding speed v.
        CHECK(history(rig).sliding_velocity == Approx(v).epsilon(1e-12));
        CHECK(v == Approx(v0 - mu * gravity * record.time).epsilon(1e-6));
        CHECK(history(rig).tangential_force == Approx(-mu * mass * gravity).epsilon(1e-6));
      }
    });
    analysis.advance(1.0);
    CHECK(stopped_at == Approx(stop_time).epsilon(1e-6));
    CHECK(stuck_at == Approx(stop_time).margin(3.0 * dt));  // sticks once the reversal settles
    CHECK(analysis.state().displacement[dof_index(rig.node, kUx)] == Approx(distance).epsilon(1e-4));
    CHECK(std::abs(analysis.state().velocity[dof_index(rig.node, kUx)]) < 1e-2);
    CHECK(std::abs(analysis.state().displacement[dof_index(rig.node, kUy)]) < 1e-5);
    // The kinetic energy went into friction.
    CHECK(analysis.energy().dissipated == Approx(0.5 * mass * v0 * v0).epsilon(1e-3));
  }
}

TEST_CASE("a moving road drags a node frame-indifferently: stick, then slip at mu N", "[contact][friction][moving]") {
  const double normal = 500.0, mu = 0.3, eps = 1e6, k_x = 2e4, travel = -0.02;
  SECTION("node held by a spring: it moves with the road, then slides") {
    // With road displacement d and a tangential penalty at the spring's scale (eps_T = 2 k_x):
    //   stick:  u_x = eps_T d/(k_x + eps_T),   slip:  u_x = -mu N/k_x.
    const double eps_t = 2.0 * k_x;
    Rig rig;
    auto road = std::make_shared<FlatRoad>(Eigen::Vector2d::Zero(), Eigen::Vector2d::UnitX(),
                                           RigidMotion::translation(MotionFunction::linear(travel)));
    build_rig(rig, Eigen::Vector2d::Zero(), k_x, 0.0, 0.0, road, penalties(eps, eps_t, mu));
    press(rig, normal);
    rig.model.add_nodal_load(rig.node, kUy, -normal, constant_function(rig.model));
    Analysis analysis(rig.model);
    analysis.newton_settings().residual_tolerance = 1e-12;
    analysis.step_control().max_augmentations = 0;
    int sticking = 0, slipping = 0;
    analysis.add_step_observer([&](const Analysis& run, const StepRecord& record) {
      const double d = travel * record.time;
      const double u_x = run.state().displacement[dof_index(rig.node, kUx)];
      const ContactHistory& h = history(rig);
      CHECK(h.normal_force == Approx(normal).epsilon(1e-10));
      if (std::abs(k_x * eps_t * d / (k_x + eps_t)) <= mu * normal) {
        CHECK(h.state == ContactState::Stick);
        CHECK(u_x == Approx(eps_t * d / (k_x + eps_t)).epsilon(1e-9));
        ++sticking;
      } else {
        CHECK(h.state == ContactState::Slip);
        CHECK(u_x == Approx(-mu * normal / k_x).epsilon(1e-9));
        CHECK(h.tangential_force == Approx(-mu * normal).epsilon(1e-12));  // along -x on the node
        ++slipping;
      }
    });
    analysis.set_time_step(0.05);
    analysis.advance(1.0);
    CHECK(sticking >= 5);
    CHECK(slipping >= 5);
  }
  SECTION("node and road translating together: stick with no tangential force") {
    Rig rig;
    auto road = std::make_shared<FlatRoad>(Eigen::Vector2d::Zero(), Eigen::Vector2d::UnitX(),
                                           RigidMotion::translation(MotionFunction::linear(0.5)));
    build_rig(rig, Eigen::Vector2d::Zero(), 0.0, 0.0, 0.0, road, penalties(eps, eps, mu));
    press(rig, normal);
    rig.model.prescribe(rig.node, kUx, 0.5, Model::kRampLoadFunction);
    rig.model.add_nodal_load(rig.node, kUy, -normal, constant_function(rig.model));
    Analysis analysis(rig.model);
    analysis.set_time_step(0.1);
    analysis.add_step_observer([&](const Analysis& run, const StepRecord&) {
      CHECK(history(rig).state == ContactState::Stick);
      CHECK(std::abs(history(rig).tangential_force) <= 1e-9 * normal);
      CHECK(std::abs(run.reactions()[dof_index(rig.node, kUx)]) <= 1e-9 * normal);
    });
    analysis.advance(1.0);
    CHECK(analysis.state().displacement[dof_index(rig.node, kUx)] == Approx(0.5));
  }
  SECTION("node turning with a spinning drum: stick with a purely radial force") {
    const double radius = 0.85, depth = 1e-4, speed = 2.0;
    Model model;
    const Eigen::Vector2d start(0.0, radius - depth);  // on top, pressed 0.1 mm into the drum
    const int node = model.mesh().add_node(start);
    SpringMassProperties torsion;  // the rotation is the model's only equation
    torsion.stiffness = {0.0, 0.0, 1.0};
    model.add_block<NodalSpringMass>("torsion").add({node}, NodalSpringMass(torsion));
    auto drum = std::make_shared<Drum>(2.0 * radius, Eigen::Vector2d::Zero(), MotionFunction::linear(speed));
    ContactBlock& contact = add_contact_block(model, "drum", drum, {node}, penalties(eps, eps, mu));
    // u(t) = R(speed t) X - X on both translations.
    const int along_x =
        model.add_load_function(LoadFunction([=](double t) { return -(radius - depth) * std::sin(speed * t); }));
    const int along_y =
        model.add_load_function(LoadFunction([=](double t) { return (radius - depth) * (std::cos(speed * t) - 1.0); }));
    model.prescribe(node, kUx, 1.0, along_x);
    model.prescribe(node, kUy, 1.0, along_y);
    Analysis analysis(model);
    analysis.step_control().max_augmentations = 0;  // the penetration is prescribed: penalty only
    analysis.set_time_step(0.05);
    analysis.add_step_observer([&](const Analysis& run, const StepRecord& record) {
      const ContactHistory& h = contact.committed_history(0);
      CHECK(h.state == ContactState::Stick);
      CHECK(h.normal_force == Approx(eps * depth).epsilon(1e-9));
      CHECK(std::abs(h.tangential_force) <= 1e-9 * eps * depth);
      // The support holds the node against a radial push (reaction = residual = -contact force).
      const Eigen::Vector2d reaction(run.reactions()[dof_index(node, kUx)], run.reactions()[dof_index(node, kUy)]);
      const Eigen::Vector2d radial(-std::sin(speed * record.time), std::cos(speed * record.time));
      CHECK((reaction + eps * depth * radial).norm() <= 1e-9 * eps * depth);
    });
    analysis.advance(1.5);
  }
}

TEST_CASE("a node whose slip reverses between Newton iterates gets the secant of its friction on the stick term",
          "[contact][tangent][reversal]") {
  // On a tilted road, a node pressed 1 mm in slips forwards in one iterate and backwards in
  // the next: its tangent there is the slip tangent plus sigma eps_T tau tau^T, sigma the
  // secant (t_T - t_T,last) / (t_T* - t_T*,last); its residual is the law's.
  auto road = std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 0.1));
  const double eps_n = 1e6, eps_t = 5e5, mu = 0.3;
  const NodeSurfaceContact kernel(road, Eigen::Vector2d::Zero(), penalties(eps_n, eps_t, mu));
  const SurfaceProjection start = road->project(Eigen::Vector2d::Zero(), 0.0);
  const ContactHistory base = touching(0.0, 0.0, start.coordinate);
  auto at = [&](double along) {  // 1 mm into the road, 'along' from the stick point
    LocalState<3> local;
    local.displacement << road->point(start.coordinate + along, 0.0) - 1e-3 * start.normal, 0.0;
    local.velocity.setZero();
    local.acceleration.setZero();
    return local;
  };
  EvaluationContext later;  // not a solve's first evaluation
  NodeSurfaceContact::Vector residual, plain_residual;
  NodeSurfaceContact::Matrix tangent, plain_tangent;
  ContactHistory forwards = base;
  kernel.evaluate(at(-2e-3), later, base, forwards, residual, &tangent);
  REQUIRE(forwards.state == ContactState::Slip);
  REQUIRE(forwards.tangential_force > 0.0);

  ContactHistory backwards = forwards, plain = base;
  kernel.evaluate(at(3e-3), later, base, backwards, residual, &tangent);
  kernel.evaluate(at(3e-3), later, base, plain, plain_residual, &plain_tangent);
  REQUIRE(backwards.state == ContactState::Slip);
  REQUIRE(backwards.tangential_force < 0.0);
  CHECK(std::memcmp(&backwards, &plain, sizeof(ContactHistory)) == 0);
  CHECK(residual == plain_residual);
  const double sigma =
      (backwards.tangential_force - forwards.tangential_force) / (backwards.trial_traction - forwards.trial_traction);
  CHECK(sigma == Approx(2.0 * mu * eps_n * 1e-3 / (eps_t * 5e-3)));
  const Eigen::Matrix2d secant = sigma * eps_t * start.tangent * start.tangent.transpose();
  CHECK((tangent.topLeftCorner<2, 2>() - plain_tangent.topLeftCorner<2, 2>() - secant).norm() <= 1e-9 * secant.norm());
  // The plain tangent is the law's (finite differences), so the secant is all that differs.
  check_tangent(kernel, at(3e-3).displacement.head<2>(), 0.0, base, ContactState::Slip);

  // A solve's first evaluation starts afresh: the last iterate was another step's.
  EvaluationContext first = later;
  first.first_evaluation = true;
  backwards = forwards;
  kernel.evaluate(at(3e-3), first, base, backwards, residual, &tangent);
  CHECK(tangent == plain_tangent);
}

TEST_CASE("a node slipping one way then the other around its stick zone converges to stick in three increments",
          "[contact][friction][reversal]") {
  // A node on a spring k_x, pressed by N onto a road that moves by d in one step, with
  // eps_T = 11 k_x (the drum-cleat deck's patch-edge nodes). The law's answer is stick,
  // u_x = eps_T d / (k_x + eps_T). The first iterate (u_x = 0) slips; the slip tangent
  // (k_x alone) sends the node to the slip equilibrium -mu N / k_x, where it slips the
  // other way. There the secant of its friction between the two iterates brings it into
  // the stick zone; with the slip tangent it would go back, and backtracking would take
  // two increments more (five). Over other ratios the secant takes as many or one more.
  const double normal = 500.0, mu = 0.3, k_x = 2e4, eps_t = 11.0 * k_x, d = -3e-3;
  const double stick = eps_t * d / (k_x + eps_t);
  const double slip = -mu * normal / k_x;
  REQUIRE(std::abs(k_x * stick) < mu * normal);  // the answer sticks,
  REQUIRE(eps_t * std::abs(d) > mu * normal);    // the first iterate slips,
  REQUIRE(eps_t * (slip - d) < -mu * normal);    // and the second slips the other way
  Rig rig;
  auto road = std::make_shared<FlatRoad>(Eigen::Vector2d::Zero(), Eigen::Vector2d::UnitX(),
                                         RigidMotion::translation(MotionFunction::linear(d)));
  build_rig(rig, Eigen::Vector2d::Zero(), k_x, 0.0, 0.0, road, penalties(1e6, eps_t, mu));
  press(rig, normal);
  rig.model.add_nodal_load(rig.node, kUy, -normal, constant_function(rig.model));
  Analysis analysis(rig.model);
  analysis.newton_settings().residual_tolerance = 1e-12;
  analysis.step_control().max_augmentations = 0;
  analysis.set_time_step(1.0);
  int iterations = 0;
  analysis.add_step_observer([&](const Analysis&, const StepRecord& record) { iterations = record.newton_iterations; });
  analysis.advance(1.0);
  CHECK(history(rig).state == ContactState::Stick);
  CHECK(analysis.state().displacement[dof_index(rig.node, kUx)] == Approx(stick).epsilon(1e-9));
  CHECK(iterations == 3);
}

TEST_CASE("a node passing a cleat's edge stays converged, outside the surface and without force spikes",
          "[contact][vertex]") {
  // The cleat (10 mm high) moves left under a node held by springs and pressed down; the
  // node rides along the top, then leaves the trailing edge: on the top t_N = F, off it
  // the node hangs free 5 mm above the road.
  const double force = 100.0, k_y = force / 0.005, k_x = 2e4, mu = 0.3, tolerance = 1e-6;
  for (double edge_radius : {0.0, 0.008}) {
    INFO("edge radius " << edge_radius);
    Rig rig;
    auto cleat = std::make_shared<RoadProfile>(RoadProfile::cleat_points(-0.05, 0.08, 0.01), edge_radius,
                                               RigidMotion::translation(MotionFunction::linear(-0.06)));
    // Stiff normal penalty, tangential one at the spring's scale (docs/contact.md).
    ContactParameters parameters = penalties(1e3 * k_y, k_x, mu);
    parameters.penetration_tolerance = tolerance;
    build_rig(rig, Eigen::Vector2d(0.0, 0.01), k_x, k_y, 0.0, cleat, parameters);
    rig.model.add_nodal_load(rig.node, kUy, -force, constant_function(rig.model));
    Analysis analysis(rig.model);
    double previous_force = -1.0, largest_jump = 0.0;
    int on_top = 0, free = 0;
    analysis.add_step_observer([&](const Analysis& run, const StepRecord&) {
      const ContactHistory& h = history(rig);
      CHECK(h.gap >= -tolerance);
      CHECK(h.force.allFinite());
      // Never more than the load and its friction: no spike at the edge.
      CHECK(h.force.norm() <= 1.02 * std::sqrt(1.0 + mu * mu) * force);
      if (previous_force >= 0.0) largest_jump = std::max(largest_jump, std::abs(h.force.norm() - previous_force));
      previous_force = h.force.norm();
      const Eigen::Vector2d x = run.model().mesh().position(rig.node) + run.state().displacement.segment<2>(0);
      if (h.state != ContactState::Open && std::abs(x.y() - 0.01) < 1e-5) {
        ++on_top;
        CHECK(h.normal_force == Approx(force - k_y * (0.01 - x.y())).epsilon(1e-6));
      }
      if (h.state == ContactState::Open) {
        ++free;
        CHECK(x.y() == Approx(0.005).epsilon(1e-9));
        CHECK(x.x() == Approx(0.0).margin(1e-12));
      }
    });
    analysis.set_time_step(0.005);
    analysis.advance(1.0);  // the road moves 60 mm: the trailing edge passes at 30 mm
    CHECK(on_top > 10);
    CHECK(free > 10);
    // A rounded edge lets go gradually; a sharp one within a step or two.
    if (edge_radius > 0.0) CHECK(largest_jump < 0.35 * force);
  }
}

TEST_CASE("a node dropping into a pothole and climbing out over a rounded edge stays converged", "[contact][vertex]") {
  // The node hangs 4 mm below road level when free; the pothole (20 mm deep) passes under it.
  const double force = 100.0, k_y = force / 0.004, k_x = 2e4, tolerance = 1e-6;
  for (double edge_radius : {0.0, 0.01}) {
    INFO("edge radius " << edge_radius);
    Rig rig;
    auto road = std::make_shared<RoadProfile>(RoadProfile::pothole_points(0.02, 0.06, 0.02), edge_radius,
                                              RigidMotion::translation(MotionFunction::linear(-0.1)));
    ContactParameters parameters = penalties(1e3 * k_y, k_x, 0.2);
    parameters.penetration_tolerance = tolerance;
    build_rig(rig, Eigen::Vector2d(0.0, 0.0), k_x, k_y, 0.0, road, parameters);
    rig.model.add_nodal_load(rig.node, kUy, -force, constant_function(rig.model));
    Analysis analysis(rig.model);
    int open_steps = 0;
    double lowest = 0.0;
    analysis.add_step_observer([&](const Analysis& run, const StepRecord&) {
      const ContactHistory& h = history(rig);
      CHECK(h.gap >= -tolerance);
      CHECK(h.force.norm() <= 1.3 * force);
      lowest = std::min(lowest, run.state().displacement[dof_index(rig.node, kUy)]);
      open_steps += h.state == ContactState::Open ? 1 : 0;
    });
    analysis.set_time_step(0.01);
    // Sharp edges: only the drop (a vertical far wall cannot be climbed quasi-statically).
    analysis.advance(edge_radius > 0.0 ? 1.0 : 0.5);
    CHECK(open_steps > 5);
    CHECK(lowest == Approx(-0.004).epsilon(1e-6));
    if (edge_radius > 0.0) {
      // Out again: back on the level road, pressed with the full load.
      CHECK(history(rig).state != ContactState::Open);
      CHECK(history(rig).normal_force == Approx(force).epsilon(1e-3));
    }
  }
}

TEST_CASE("hopeless contact ends with a clear StepFailure, never NaN", "[contact][failure]") {
  SECTION("an absurdly small penalty under a huge load") {
    Rig rig;
    build_rig(rig, Eigen::Vector2d::Zero(), 1.0, 1.0, 0.0, std::make_shared<FlatRoad>(), penalties(1.0, 1.0, 0.3));
    rig.model.add_nodal_load(rig.node, kUy, -1e6, constant_function(rig.model));
    Analysis analysis(rig.model);
    analysis.step_control().max_cuts = 3;
    CHECK_THROWS_MATCHES(analysis.advance(1.0), StepFailure,
                         Catch::Matchers::Predicate<StepFailure>(
                             [](const StepFailure& failure) {
                               const std::string text = failure.what();
                               return text.find("penetrates") != std::string::npos &&
                                      text.find("penalty is too small") != std::string::npos;
                             },
                             "names the penetration and the penalty"));
    CHECK(analysis.state().displacement.allFinite());
  }
  SECTION("an obstacle far too high for a node driven into it") {
    // A 0.5 m wall 10 mm ahead; the node is driven 50 mm into it.
    Rig rig;
    build_rig(rig, Eigen::Vector2d::Zero(), 0.0, 1e3, 0.0,
              std::make_shared<RoadProfile>(RoadProfile::cleat_points(0.01, 1.0, 0.5)), penalties(1e6, 1e6, 0.0));
    rig.model.prescribe(rig.node, kUx, 0.06, Model::kRampLoadFunction);
    Analysis analysis(rig.model);
    analysis.set_time_step(0.25);
    analysis.step_control().max_cuts = 2;
    try {
      analysis.advance(1.0);
      FAIL("the step should have failed");
    } catch (const StepFailure& failure) {
      CHECK_THAT(failure.what(), Contains("penetrates") && Contains("too high"));
    }
    CHECK(analysis.state().displacement.allFinite());
  }
}

TEST_CASE("default penalties: the structure's diagonal stiffness, and its own stiffness along the surface",
          "[contact][penalty]") {
  // Springs k_x, k_y on one node: the largest diagonal is k_y; along a road tilted by phi the
  // node's own stiffness is 1 / (cos^2 phi / k_x + sin^2 phi / k_y).
  const double k_x = 3e4, k_y = 5e4, phi = 0.3;
  Model model;
  const int node = model.mesh().add_node(Eigen::Vector2d::Zero());
  SpringMassProperties properties;
  properties.stiffness = {k_x, k_y, 1.0};
  model.add_block<NodalSpringMass>("spring").add({node}, NodalSpringMass(properties));
  Analysis analysis(model);
  CHECK(structural_penalty(analysis, {node}, 2.0) == Approx(2.0 * k_y).epsilon(1e-14));
  const FlatRoad road(Eigen::Vector2d(0.0, -0.01), Eigen::Vector2d(std::cos(phi), std::sin(phi)));
  const double along = 1.0 / (std::pow(std::cos(phi), 2) / k_x + std::pow(std::sin(phi), 2) / k_y);
  CHECK(structural_tangential_penalty(analysis, {node}, road, 0.5) == Approx(0.5 * along).epsilon(1e-12));
  // The model still solves afterwards (the analysis's assembler and solver stay consistent).
  model.add_nodal_load(node, kUy, 5.0, Model::kRampLoadFunction);
  analysis.advance(1.0);
  CHECK(analysis.state().displacement[dof_index(node, kUy)] == Approx(5.0 / k_y).epsilon(1e-12));

  // A bare point mass: no stiffness to scale from.
  Model bare;
  const int lonely = bare.mesh().add_node(Eigen::Vector2d::Zero());
  SpringMassProperties massive;
  massive.mass = 1.0;
  massive.rotary_inertia = 1.0;
  bare.add_block<NodalSpringMass>("mass").add({lonely}, NodalSpringMass(massive));
  Analysis bare_analysis(bare);
  CHECK_THROWS_WITH(structural_penalty(bare_analysis, {lonely}), Contains("no stiffness"));
  CHECK_THROWS_WITH(structural_tangential_penalty(bare_analysis, {lonely}, road), Contains("not supported"));
}

TEST_CASE("contact output: totals, patch length and per-node rows in the result file", "[contact][output]") {
  // Three nodes pressed onto a flat road by springs, 10 mm apart.
  TempDir folder;
  Model model;
  std::vector<int> nodes;
  SpringMassProperties properties;
  properties.stiffness = {1e3, 1e3, 0.0};
  auto& springs = model.add_block<NodalSpringMass>("springs");
  for (int i = 0; i < 3; ++i) {
    nodes.push_back(model.mesh().add_node(Eigen::Vector2d(0.01 * i, 0.0)));
    springs.add({nodes.back()}, NodalSpringMass(properties));
    model.fix(nodes.back(), kRz);
    model.add_nodal_load(nodes.back(), kUy, -10.0 * (i + 1), Model::kRampLoadFunction);
  }
  ContactBlock& contact =
      add_contact_block(model, "road", std::make_shared<FlatRoad>(), nodes, penalties(1e6, 1e6, 0.5));
  Analysis analysis(model);
  {
    io::ResultFile file(folder.path("contact.h5"), io::RunMetadata{"contact", "", "", {}});
    macros::add_contact_output(file, analysis, macros::contact_source(contact), "road", 1);
    analysis.add_step_observer(
        [&](const Analysis& run, const StepRecord& record) { file.record(run.model(), run.state(), record); });
    analysis.set_time_step(0.5);
    analysis.advance(1.0);
    const ContactSummary summary = summarize_contact(contact);
    CHECK(summary.nodes_in_contact == 3);
    CHECK(summary.patch_length == Approx(0.02).epsilon(1e-6));
    CHECK(summary.force.y() == Approx(60.0).epsilon(1e-3));  // the loads, bar what the springs take
    CHECK(std::abs(summary.force.x()) < 1e-9);
    // The rows are the block's named responses: asked by name, its points' committed values.
    const ElementResponses* responses = responses_of(contact);
    REQUIRE(responses != nullptr);
    CHECK(responses_of(springs) == nullptr);
    CHECK(responses->response_points() == 3);
    CHECK(responses->response_index("pressure") == -1);
    const int gap = responses->response_index("gap");
    REQUIRE(gap >= 0);
    std::vector<double> gaps;
    responses->response_values(gap, analysis.state(), gaps);
    REQUIRE(gaps.size() == 3);
    for (int e = 0; e < 3; ++e) CHECK(gaps[e] == contact.committed_history(e).gap);
  }
  const io::Hdf5File file = io::Hdf5File::open_read_only(folder.path("contact.h5"));
  std::vector<hsize_t> shape;
  const std::vector<double> normal = file.read_doubles("/contact/road/normal_force", &shape);
  REQUIRE(shape == std::vector<hsize_t>{2, 3});
  CHECK(normal[3] + normal[4] + normal[5] == Approx(60.0).epsilon(1e-3));
  CHECK(file.read_doubles("/contact/road/state")[5] == 1.0);
  CHECK(file.read_doubles("/history/road_fy").back() == Approx(60.0).epsilon(1e-3));
  CHECK(file.read_doubles("/history/road_patch_length").back() == Approx(0.02).epsilon(1e-6));
  CHECK(file.read_ints("/contact/road/nodes") == std::vector<long long>{0, 1, 2});
}

namespace {

/// One node on a spring (1e3 N/m in x and y), pushed down by 10 N on the ramp; returns it.
int add_loaded_spring_node(Model& model) {
  SpringMassProperties properties;
  properties.stiffness = {1e3, 1e3, 0.0};
  auto& springs = model.add_block<NodalSpringMass>("springs");
  const int node = model.mesh().add_node(Eigen::Vector2d(0.0, 0.0));
  springs.add({node}, NodalSpringMass(properties));
  model.fix(node, kRz);
  model.add_nodal_load(node, kUy, -10.0, Model::kRampLoadFunction);
  return node;
}

}  // namespace

TEST_CASE("a discarded result file creates no file and evaluates no channel", "[contact][output]") {
  // What an MPI rank keeps for a model another rank owns: the deck's output macros work,
  // nothing reaches the disk.
  TempDir folder;
  Model model;
  const int node = add_loaded_spring_node(model);
  ContactBlock& contact =
      add_contact_block(model, "road", std::make_shared<FlatRoad>(), {node}, penalties(1e6, 1e6, 0.5));
  Analysis analysis(model);
  int evaluated = 0;
  {
    io::ResultFile file(folder.path("elsewhere.h5"), io::RunMetadata{"elsewhere", "", "", {}},
                        io::ResultStorage::Discarded);
    file.set_field_interval(1);
    macros::add_contact_output(file, analysis, macros::contact_source(contact), "road", 1);
    file.add_channel("counted", "", [&](const State&, const StepRecord&) { return ++evaluated; });
    CHECK_THROWS_AS(file.add_channel("counted", "", nullptr), io::IoError);  // the deck's errors stay the same
    analysis.add_step_observer(
        [&](const Analysis& run, const StepRecord& record) { file.record(run.model(), run.state(), record); });
    analysis.set_time_step(0.5);
    analysis.advance(1.0);
    CHECK(file.steps_recorded() == 2);
  }
  CHECK(evaluated == 0);
  CHECK(std::filesystem::is_empty(folder.path("")));
}

TEST_CASE("a history channel added mid-run holds NaN for the steps before it", "[contact][output]") {
  // A contact defined after inflation adds its channels after steps were recorded.
  TempDir folder;
  Model model;
  const int node = add_loaded_spring_node(model);
  Analysis analysis(model);
  int steps_before = 0;
  {
    io::ResultFile file(folder.path("late.h5"), io::RunMetadata{"late", "", "", {}});
    analysis.add_step_observer(
        [&](const Analysis& run, const StepRecord& record) { file.record(run.model(), run.state(), record); });
    analysis.set_time_step(0.5);
    analysis.advance(1.0);
    steps_before = file.steps_recorded();
    file.add_channel("late_uy", "m", [node](const State& state, const StepRecord&) {
      return state.displacement[dof_index(node, kUy)];
    });
    analysis.advance(1.5);
  }
  const io::Hdf5File file = io::Hdf5File::open_read_only(folder.path("late.h5"));
  const std::vector<double> late = file.read_doubles("/history/late_uy");
  REQUIRE(late.size() == file.read_doubles("/history/time").size());
  REQUIRE(steps_before >= 1);
  REQUIRE(late.size() > static_cast<size_t>(steps_before));
  for (int row = 0; row < steps_before; ++row) CHECK(std::isnan(late[row]));
  CHECK(!std::isnan(late[steps_before]));
  CHECK(late.back() == Approx(-2.5 * 10.0 / 1e3).epsilon(1e-9));  // u = F / k at t = 1 + 1.5
}

// ======================================================================================
// Deck macros
// ======================================================================================

namespace {

struct DeckRun {
  int exit_status;
  std::string output;  // standard output and error
};

DeckRun run_deck(const std::string& deck, const std::string& output_dir) {
  const std::string command = std::string(TIREFE_BINARY) + " " + deck + " --quiet --output-dir " + output_dir + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), output};
}

}  // namespace

TEST_CASE("deck macros: a post pressed on a moving road profile checks itself", "[contact][macros]") {
  // A post (one beam) clamped at the top presses its tip on a road read from a file that
  // moves left: the tip sticks, then slides with friction mu N. The penalties come from the
  // structure: 10 x the largest diagonal (EA/L = 1e6), and the tip's lateral stiffness GA/L.
  TempDir folder;
  folder.write("road.txt", "# a level road\n-1 0\n1 0\n");
  const std::string deck = folder.write("post.lua", R"(
local p = tirefe.parameters{ mu = 0.3, load = 100.0 }
local model = tirefe.model{ title = "post on a moving road" }
local top = model:node{ x = 0.0, y = 0.1 }
local tip = model:node{ x = 0.0, y = 0.0 }
model:node_set{ name = "tip", nodes = { tip } }
model:section{ name = "post", EA = 1e5, GA = 1e5, EI = 10.0 }
model:beam{ section = "post", nodes = { top, tip } }
model:fix{ node = top }
model:fix{ node = tip, dofs = { "rz" } }
model:output{ file = "post.h5" }
model:surface{ name = "road", type = "profile", file = "road.txt", speed = -0.05 }
local normal, tangential = model:contact{ surface = "road", set = "tip", friction = p.mu, penalty_factor = 10,
                                         tolerance = 1e-10, history = "tip", output_every = 2 }
model:load{ set = "tip", fy = -p.load, load_function = "constant" }
model:solve{ to = 1.0, dt = 0.05 }
local function contact(quantity) return model:contact_value{ name = "contact_road", quantity = quantity } end
tirefe.check{ name = "normal force = load", value = contact("fy"), expected = p.load, relative = 1e-6 }
tirefe.check{ name = "friction = mu N, against the road's motion", value = contact("fx") / contact("fy"),
              expected = -p.mu, relative = 1e-12 }
tirefe.check{ name = "the node slips", value = contact("nodes_slipping"), expected = 1 }
tirefe.check{ name = "normal penalty = 10 EA/L", value = normal, expected = 1e7, relative = 1e-9 }
tirefe.check{ name = "tangential penalty = GA/L, the post's own lateral stiffness", value = tangential,
              expected = 1e6, relative = 1e-9 }
)");
  const DeckRun run = run_deck(deck, folder.path("out"));
  INFO(run.output);
  REQUIRE(run.exit_status == 0);
  const io::Hdf5File file = io::Hdf5File::open_read_only(folder.path("out/post.h5"));
  const std::vector<double> friction = file.read_doubles("/history/tip_fx");
  REQUIRE(friction.size() == 20);
  CHECK(friction.back() == Approx(-30.0).epsilon(1e-6));
  std::vector<hsize_t> shape;
  file.read_doubles("/contact/contact_road/state", &shape);
  CHECK(shape == std::vector<hsize_t>{10, 1});  // every second step, one node
}

TEST_CASE("deck macros: contact mistakes are reported at the deck line", "[contact][macros]") {
  TempDir folder;
  const std::string prologue =
      "local model = tirefe.model{}\nlocal n = model:node{ x = 0, y = 0 }\nmodel:node_set{ name = \"tread\", nodes = { "
      "n } }\n";
  struct Case {
    std::string body, expected;
  };
  const Case cases[] = {
      {"model:contact{ surface = \"road\", set = \"tread\", penalty = 1e5 }", "no surface named 'road'"},
      {"model:surface{ name = \"road\", type = \"flat\" }\nmodel:contact{ surface = \"road\", set = \"tread\" }",
       "no stiffness"},
      {"model:surface{ name = \"drum\", type = \"drum\" }", "needs 'diameter'"},
      {"model:surface{ name = \"road\", type = \"profile\", points = {{0, 0}, {1, 0}}, diameter = 2 }",
       "'diameter' does not apply to a profile surface"},
      {"model:surface{ name = \"road\", type = \"profile\", file = \"nowhere.txt\" }", "nowhere.txt"},
      {"model:surface{ name = \"road\", type = \"profile\", points = {{0, 0}, {1, 0}, {0.5, 0}} }",
       "must not decrease"},
  };
  int index = 0;
  for (const Case& c : cases) {
    const std::string deck = folder.write("bad" + std::to_string(index++) + ".lua", prologue + c.body + "\n");
    const DeckRun run = run_deck(deck, folder.path("out"));
    INFO(run.output);
    CHECK(run.exit_status == 1);
    CHECK_THAT(run.output, Contains(c.expected) && Contains(".lua:"));
  }
}

TEST_CASE("deck macros: surfaces belong to their model, and decks in one process keep their own", "[contact][macros]") {
  TempDir folder;
  // Two models of one deck may each name a surface "road"; a model sees its own only.
  const std::string two_models = folder.write("two_models.lua", R"(
local first, second = tirefe.model{}, tirefe.model{}
first:surface{ name = "road", type = "flat", point = { 0, 1 } }
second:surface{ name = "road", type = "flat", point = { 0, -1 } }
second:surface{ name = "kerb", type = "flat", point = { 0, 2 } }
tirefe.check{ name = "first road", value = first:surface_projection{ surface = "road", point = { 0, 0 } }.gap,
              expected = -1, tolerance = 1e-12 }
tirefe.check{ name = "second road", value = second:surface_projection{ surface = "road", point = { 0, 0 } }.gap,
              expected = 1, tolerance = 1e-12 }
first:surface_projection{ surface = "kerb", point = { 0, 0 } }
)");
  const testing::InProcessRun run = testing::run_deck_in_process(two_models, folder.path("out"));
  CHECK(run.checks == 2);
  CHECK(run.failed_checks == 0);
  CHECK_THAT(run.error, Contains("two_models.lua:10") && Contains("no surface named 'kerb' (defined: road)"));

  // A deck run while another's model is alive in the same process sees none of its surfaces.
  const std::string keeps = folder.write("keeps.lua",
                                         "kept = tirefe.model{}\n"
                                         "kept:surface{ name = \"road\", type = \"flat\" }\n");
  const std::string asks = folder.write("asks.lua",
                                        "local m = tirefe.model{}\n"
                                        "m:surface_projection{ surface = \"road\", point = { 0, 0 } }\n");
  macros::DeckSession session;
  session.output_dir = folder.path("out_kept");
  session.quiet = true;
  macros::LuaSandbox alive(TIREFE_LUA_DIR);
  macros::install_macros(alive, session);
  alive.run_file(keeps);
  const testing::InProcessRun other = testing::run_deck_in_process(asks, folder.path("out_asks"));
  CHECK_THAT(other.error,
             Contains("asks.lua:2") && Contains("no surface named 'road' (define one with model:surface{...})"));
}
