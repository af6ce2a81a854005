// SidewallWedge and TreadPressure: the arch solution of eq. 1, the membrane law against
// the circular membrane, the near-straight regularisation, tangents against central
// finite differences, rigid-body invariance, the sign of the shear term, the pressure
// resultants, and the inflated ring against docs/model.md section 3's hoop-force formula.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <complex>
#include <memory>
#include <random>
#include <vector>

#include "elements/sidewall.hpp"
#include "elements/tread_beam.hpp"
#include "elements/tread_pressure.hpp"
#include "solvers/analysis.hpp"
#include "test_support.hpp"

using namespace tirefe;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTreadRadius = 0.27, kRimRadius = 0.1524, kTreadWidth = 0.11, kPressure = 0.208e6;
// 145 SR-12-like sidewall. l_sw = 0.14 m keeps the inflated hoop in tension: at L = 0.118 m
// it needs l_sw > 0.133 m (N = R p (w - L cot(alpha)) > 0).
constexpr double kCordLength = 0.14;
// k_gamma [N/m per rad]: 2e5 N/m^2 of tangential foundation stiffness times L = 0.118 m.
constexpr double kShearStiffness = 2.4e4;

SidewallProperties test_properties() {
  SidewallProperties properties;
  properties.rim_radius = kRimRadius;
  properties.cord_length = kCordLength;
  properties.bending_stiffness = 100.0;
  properties.shear_stiffness = kShearStiffness;
  properties.radial_damping = 80.0;
  properties.circumferential_damping = 40.0;
  return properties;
}

std::shared_ptr<const PressureSchedule> constant_pressure(double pressure) {
  return std::make_shared<const PressureSchedule>(PressureSchedule::constant(pressure));
}

Eigen::Vector2d on_circle(double radius, double angle) { return {radius * std::cos(angle), radius * std::sin(angle)}; }

/// One wedge of a 100-element ring, spindle slightly off the origin.
struct WedgeGeometry {
  Eigen::Vector2d spindle{0.01, -0.02};
  Eigen::Vector2d tread_a = spindle + on_circle(kTreadRadius, 0.7);
  Eigen::Vector2d tread_b = spindle + on_circle(kTreadRadius, 0.7 + 2.0 * kPi / 100.0);
  SidewallWedge wedge(const SidewallProperties& properties, double pressure) const {
    return SidewallWedge(spindle, tread_a, tread_b, properties, constant_pressure(pressure));
  }
  /// Displacements that move the whole wedge rigidly: rotation 'angle' about the origin, then 'shift'.
  SidewallWedge::Vector rigid_motion(double angle, const Eigen::Vector2d& shift) const {
    const Eigen::Rotation2Dd rotation(angle);
    SidewallWedge::Vector u;
    int n = 0;
    for (const Eigen::Vector2d* node : {&spindle, &tread_a, &tread_b}) {
      u.segment<2>(3 * n) = rotation * (*node) + shift - *node;
      u[3 * n + 2] = angle;
      ++n;
    }
    return u;
  }
};

LocalState<9> at_rest(const SidewallWedge::Vector& displacement) {
  LocalState<9> local;
  local.displacement = displacement;
  local.velocity.setZero();
  local.acceleration.setZero();
  return local;
}

template <class Kernel>
void check_tangent(const Kernel& kernel, const LocalState<Kernel::kDofs>& local, const EvaluationContext& context,
                   double tolerance = 1e-6) {
  typename Kernel::Vector residual;
  typename Kernel::Matrix tangent;
  typename Kernel::History history;
  kernel.evaluate(local, context, history, history, residual, &tangent);
  const typename Kernel::Matrix numerical = testing::finite_difference_tangent(kernel, local, context, history);
  INFO("analytic\n" << tangent << "\nnumerical\n" << numerical);
  CHECK(residual.allFinite());
  CHECK((tangent - numerical).norm() <= tolerance * tangent.norm());
}

}  // namespace

TEST_CASE("arch: theta(L) solves eq. 1 to 1e-12 for L/l_sw in (0.05, 0.999), theta < 0 included", "[sidewall]") {
  const double l = kCordLength;
  int negative_theta = 0;
  for (int i = 0; i <= 400; ++i) {
    const double ratio = (i < 400) ? 0.05 + (0.999 - 0.05) * i / 400.0 : 0.999;
    const double chord = ratio * l;
    const ArchShape arch = solve_arch(chord, l);
    const double theta = arch.meridian_angle();
    INFO("L/l_sw = " << ratio << ", theta = " << theta);
    // Eq. 1: (l_sw/2) cos(theta) + (L/2)(theta - pi/2) = 0, relative to l_sw.
    CHECK(std::abs(0.5 * l * std::cos(theta) + 0.5 * chord * (theta - 0.5 * kPi)) <= 1e-12 * l);
    CHECK(theta > -0.5 * kPi);
    CHECK(theta < 0.5 * kPi);
    if (theta < 0.0) ++negative_theta;
    // dtheta/dL = -dalpha/dL against a central difference.
    const double h = 1e-7 * l;
    const double numerical =
        (solve_arch(chord + h, l).meridian_angle() - solve_arch(chord - h, l).meridian_angle()) / (2.0 * h);
    CHECK(-arch.dhalf_angle_dchord == Approx(numerical).epsilon(1e-6));
  }
  CHECK(negative_theta > 50);  // L/l_sw < 2/pi bulges past a semicircle
  // The arch over its own chord is recovered: alpha -> L = l_sw sin(alpha)/alpha -> alpha,
  // to the conditioning of that chord: dalpha/alpha = (3/alpha^2) dL/L near straight.
  for (double alpha : {0.06, 0.4, 1.0, 1.5708, 2.2, 3.0}) {
    CHECK(solve_arch(l * std::sin(alpha) / alpha, l).half_angle ==
          Approx(alpha).epsilon(1e-15 * (1.0 + 3.0 / (alpha * alpha))));
  }
  CHECK_THROWS_AS(solve_arch(l, l), std::domain_error);
  CHECK_THROWS_AS(solve_arch(1.1 * l, l), std::domain_error);
}

TEST_CASE("arch: many half-angles at once are one arch's at a time, bit for bit, for 0 <= L/l_sw < 1", "[sidewall]") {
  // Service ratios end after the vectorised first step; small ones (a poor series start)
  // and exact roots take the one-arch solve; 0 and 0.999 are the ends.
  std::vector<double> ratios{0.0, 1e-9, 0.02, 0.3, 2.0 / kPi, 0.999, std::sin(1.0) / 1.0};
  for (int i = 0; i < 997; ++i) ratios.push_back(i / 997.0);
  for (double& ratio : ratios) ratio = ratio * kCordLength / kCordLength;  // as solve_arch forms it
  const int count = static_cast<int>(ratios.size());
  std::vector<double> half_angle(count), cos_half(count), sin_half(count);
  tirefe::solve_half_angles(ratios.data(), count, half_angle.data(), cos_half.data(), sin_half.data());
  int different = 0;
  for (int i = 0; i < count; ++i) {
    const double chord = ratios[i] * kCordLength;
    const double alpha = solve_arch(chord, kCordLength).half_angle;
    INFO("L/l_sw = " << ratios[i] << std::setprecision(3) << ", cos error " << cos_half[i] - std::cos(alpha)
                     << ", sin error " << sin_half[i] - std::sin(alpha));
    different += half_angle[i] != alpha;
    // The cosine and sine go with the angle (the last step's Taylor terms leave a few 1e-15).
    CHECK(std::abs(cos_half[i] - std::cos(alpha)) <= 5e-15);
    CHECK(std::abs(sin_half[i] - std::sin(alpha)) <= 5e-15);
  }
  CHECK(different == 0);
}

TEST_CASE("membrane law: the chord force of a pressurised circular arc, p r cos(half angle) per sidewall",
          "[sidewall]") {
  SidewallProperties properties = test_properties();
  properties.bending_stiffness = 0.0;
  const double l = properties.cord_length;
  for (int sidewalls : {1, 2}) {
    properties.sidewall_count = sidewalls;
    const SidewallLaw law(properties);
    // An arc of length l_sw with half-angle alpha: radius r = l_sw/(2 alpha), chord
    // 2 r sin(alpha); Laplace's law gives the membrane tension T = p r, whose end makes
    // the angle alpha with the chord. Past a semicircle (alpha > pi/2) it pushes outward.
    for (double alpha : {0.3, 0.8, 1.2, 1.9, 2.8}) {
      const double radius = l / (2.0 * alpha);
      const double chord = 2.0 * radius * std::sin(alpha);
      const double theta = 0.5 * kPi - alpha;
      const SidewallLaw::CordForce cord = law.cord_force(chord, 0.9, kPressure);
      INFO("n_sw = " << sidewalls << ", alpha = " << alpha);
      CHECK(cord.force == Approx(sidewalls * kPressure * radius * std::cos(alpha)).epsilon(1e-12));
      CHECK(cord.force == Approx(sidewalls * kPressure * 0.5 * chord * std::tan(theta)).epsilon(1e-12));
      const double h = 1e-6 * chord;
      const double numerical =
          (law.cord_force(chord + h, 0.9, kPressure).force - law.cord_force(chord - h, 0.9, kPressure).force) /
          (2.0 * h);
      // Margin: the round-off of the difference quotient, relative to F/L.
      CHECK(cord.stiffness == Approx(numerical).epsilon(1e-6).margin(1e-8 * std::abs(cord.force) / chord));
    }
  }
}

TEST_CASE("bending term: s k_sw (1/r^2 - 1/(r r0)) sin(theta), zero in the reference state", "[sidewall]") {
  SidewallProperties properties = test_properties();
  for (double sign : {1.0, -1.0}) {
    properties.bending_sign = sign;
    const SidewallLaw law(properties);
    const double reference_chord = 0.118, chord = 0.112;
    const double alpha0 = law.reference_half_angle(reference_chord);
    CHECK(law.cord_force(reference_chord, alpha0, 0.0).force == Approx(0.0).margin(1e-9));
    const ArchShape arch = solve_arch(chord, kCordLength);
    const double r = arch.radius(kCordLength), r0 = solve_arch(reference_chord, kCordLength).radius(kCordLength);
    const double expected =
        sign * properties.bending_stiffness * (1.0 / (r * r) - 1.0 / (r * r0)) * std::sin(arch.meridian_angle());
    CHECK(law.cord_force(chord, alpha0, 0.0).force == Approx(expected).epsilon(1e-12));
  }
}

TEST_CASE("near-straight cords: the law continues linearly past L*, finite, continuous, C1", "[sidewall]") {
  const SidewallLaw law(test_properties());
  const double l = kCordLength, switch_chord = law.switch_chord();
  CHECK(switch_chord == Approx(l * std::sin(0.1) / 0.1).epsilon(1e-15));
  const double alpha0 = law.reference_half_angle(0.118);
  for (double pressure : {0.0, kPressure}) {
    INFO("p = " << pressure);
    const double epsilon = 1e-10 * switch_chord;
    const SidewallLaw::CordForce below = law.cord_force(switch_chord - epsilon, alpha0, pressure);
    const SidewallLaw::CordForce above = law.cord_force(switch_chord + epsilon, alpha0, pressure);
    // The jump across the switch is only the slope times the gap 2 epsilon.
    CHECK(std::abs(above.force - below.force) <= 2.0 * epsilon * std::abs(above.stiffness) * 1.001 + 1e-12);
    CHECK(above.stiffness == Approx(below.stiffness).epsilon(1e-6));
    // Far past l_sw: finite, linear, tangent = slope.
    for (double ratio : {0.99, 0.9985, 1.0, 1.01, 1.5}) {
      const double chord = ratio * l, h = 1e-7 * l;
      const SidewallLaw::CordForce cord = law.cord_force(chord, alpha0, pressure);
      REQUIRE(std::isfinite(cord.force));
      REQUIRE(std::isfinite(cord.stiffness));
      const double numerical =
          (law.cord_force(chord + h, alpha0, pressure).force - law.cord_force(chord - h, alpha0, pressure).force) /
          (2.0 * h);
      CHECK(cord.stiffness == Approx(numerical).epsilon(1e-6));
    }
  }
  // With pressure the continued cord is a stiff spring: about 1.5 n_sw p / alpha*^3.
  const double stretch_stiffness =
      law.cord_force(1.01 * l, alpha0, kPressure).stiffness - law.cord_force(1.01 * l, alpha0, 0.0).stiffness;
  CHECK(stretch_stiffness == Approx(1.5 * 2.0 * kPressure / 1e-3).epsilon(0.02));
}

TEST_CASE("sidewall tangent equals central finite differences, deformed, rotated and translated", "[sidewall]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const WedgeGeometry geometry;
  SidewallProperties properties = test_properties();
  int stretched = 0;
  for (int trial = 0; trial < 40; ++trial) {
    properties.bending_sign = (trial % 2 == 0) ? 1.0 : -1.0;
    const double pressure = (trial % 4 < 2) ? kPressure : 0.0;
    const SidewallWedge wedge = geometry.wedge(properties, pressure);
    // A large rigid motion plus a deformation of a few centimetres and degrees.
    LocalState<9> local = testing::random_local_state<9>(random, 0.015, 0.06);
    local.displacement += geometry.rigid_motion(kPi * uniform(random), {0.5 * uniform(random), 0.5 * uniform(random)});
    local.velocity[2] *= 50.0;  // spin rates of a rolling tire
    for (int q = 0; q < SidewallWedge::kQuadraturePoints; ++q) {
      const double chord = wedge.cord_state(local.displacement, q).chord;
      stretched += chord > wedge.law().switch_chord();
    }
    INFO("trial " << trial << ", p = " << pressure);
    EvaluationContext statics;
    check_tangent(wedge, local, statics);
    check_tangent(wedge, local, testing::dynamic_context(1e-3));
    CHECK(testing::declared_zero_magnitude(wedge, local, testing::dynamic_context(1e-3)) == 0.0);
  }
  CHECK(stretched > 0);  // both branches of the law were exercised
}

TEST_CASE("sidewall batch path: every wedge of a perturbed ring as evaluate() gives it, to 1e-14", "[sidewall]") {
  // 100 wedges round a spindle, a few undamped, deformed by centimetres (some cords past
  // the straight-cord switch), each group of ten with its own spindle angle.
  std::mt19937 random(11);
  constexpr int kWedges = 100;
  const Eigen::Vector2d spindle(0.01, -0.02);
  std::vector<SidewallWedge> wedges;
  for (int e = 0; e < kWedges; ++e) {
    SidewallProperties properties = test_properties();
    if (e % 7 == 3) properties.radial_damping = properties.circumferential_damping = 0.0;
    properties.bending_sign = e % 2 == 0 ? 1.0 : -1.0;
    const double angle = 2.0 * kPi * e / kWedges;
    wedges.emplace_back(spindle, spindle + on_circle(kTreadRadius, angle),
                        spindle + on_circle(kTreadRadius, angle + 2.0 * kPi / kWedges), properties,
                        constant_pressure(e < 50 ? kPressure : 0.5 * kPressure));
  }
  std::vector<LocalState<9>> locals;
  std::vector<double> displacement(9 * kWedges), velocity(9 * kWedges);
  int stretched = 0;
  for (int e = 0; e < kWedges; ++e) {
    LocalState<9> local = testing::random_local_state<9>(random, 0.015, 0.06);
    if (e % 10 == 5) local.displacement.segment<2>(3) *= 3.0;
    local.displacement[2] = 0.3 * (e / 10) - 1.0;
    local.velocity[2] *= 50.0;
    for (int k = 0; k < 9; ++k) {
      displacement[k * kWedges + e] = local.displacement[k];
      velocity[k * kWedges + e] = local.velocity[k];
    }
    stretched += wedges[e].cord_state(local.displacement, 0).chord > wedges[e].law().switch_chord();
    locals.push_back(local);
  }
  CHECK(stretched > 0);
  const BlockValues values{kWedges, displacement.data(), velocity.data(), nullptr};
  SidewallWedge::Batch batch(wedges);
  EvaluationContext statics;
  statics.time = 0.5;
  for (const EvaluationContext& context : {statics, testing::dynamic_context(1e-4)}) {
    for (bool with_tangent : {true, false}) {
      batch.evaluate(values, context, with_tangent);
      double worst = 0.0;
      for (int e = 0; e < kWedges; ++e) {
        SidewallWedge::Vector residual;
        SidewallWedge::Matrix tangent;
        NoHistory history;
        wedges[e].evaluate(locals[e], context, history, history, residual, with_tangent ? &tangent : nullptr);
        SidewallWedge::Vector batch_residual;
        for (int k = 0; k < 9; ++k) batch_residual[k] = batch.residual()[k * kWedges + e];
        worst = std::max(worst, (batch_residual - residual).norm() / residual.norm());
        if (!with_tangent) continue;
        SidewallWedge::Matrix batch_tangent;
        for (int k = 0; k < 81; ++k)
          batch_tangent.data()[k] = (k / 9 == 5 || k / 9 == 8 || k % 9 == 5 || k % 9 == 8)
                                        ? 0.0  // the idle tread rotations: never read
                                        : batch.tangent()[k * kWedges + e];
        worst = std::max(worst, (batch_tangent - tangent).norm() / tangent.norm());
      }
      INFO("tangent " << with_tangent << ", damping factor " << context.factors.force_damping);
      CHECK(worst <= 1e-14);
    }
  }
}

TEST_CASE("sidewall: FD tangent from a bulged to a stretched cord, continuous at the straight-cord switch",
          "[sidewall]") {
  const WedgeGeometry geometry;
  const SidewallProperties properties = test_properties();
  // Radial push of both tread nodes along the wedge's midline: both Gauss points see the same L.
  const Eigen::Vector2d outward = (0.5 * (geometry.tread_a + geometry.tread_b) - geometry.spindle).normalized();
  auto pushed = [&](double push) {
    SidewallWedge::Vector u = SidewallWedge::Vector::Zero();
    u.segment<2>(3) = u.segment<2>(6) = push * outward;
    return u;
  };
  for (double pressure : {kPressure, 0.0}) {
    const SidewallWedge wedge = geometry.wedge(properties, pressure);
    const double reference_chord = wedge.cord_state(SidewallWedge::Vector::Zero(), 0).chord;
    // L/l_sw from 0.3 (bulged past a semicircle, theta < 0) to 1.3 (stretched past l_sw).
    for (double ratio = 0.3; ratio <= 1.3; ratio += 0.025) {
      const SidewallWedge::Vector u = pushed(ratio * kCordLength - reference_chord);
      INFO("p = " << pressure << ", L/l_sw = " << wedge.cord_state(u, 0).chord / kCordLength);
      check_tangent(wedge, at_rest(u), EvaluationContext{});
    }
    // The push at which the cords reach the switch chord L*, by bisection.
    double low = 0.0, high = 0.05;
    for (int i = 0; i < 200; ++i) {
      const double middle = 0.5 * (low + high);
      (wedge.cord_state(pushed(middle), 0).chord < wedge.law().switch_chord() ? low : high) = middle;
    }
    const double push = 0.5 * (low + high), epsilon = 1e-9;
    NoHistory history;
    SidewallWedge::Vector below, above, residual;
    SidewallWedge::Matrix tangent;
    wedge.evaluate(at_rest(pushed(push - epsilon)), EvaluationContext{}, history, history, below, nullptr);
    wedge.evaluate(at_rest(pushed(push + epsilon)), EvaluationContext{}, history, history, above, nullptr);
    wedge.evaluate(at_rest(pushed(push)), EvaluationContext{}, history, history, residual, &tangent);
    // Across the switch the force changes by what the tangent predicts: no jump.
    const SidewallWedge::Vector predicted = tangent * (pushed(push + epsilon) - pushed(push - epsilon));
    INFO("p = " << pressure << ": change " << (above - below).transpose() << ", predicted " << predicted.transpose());
    CHECK((above - below - predicted).norm() <= 1e-3 * predicted.norm());
    CHECK(predicted.norm() <= 1e-4 * residual.norm());
  }
}

TEST_CASE("sidewall forces are invariant under large rigid-body motions", "[sidewall]") {
  const WedgeGeometry geometry;
  NoHistory history;
  EvaluationContext statics;
  for (double pressure : {0.0, kPressure}) {
    const SidewallWedge wedge = geometry.wedge(test_properties(), pressure);
    SidewallWedge::Vector reference;
    wedge.evaluate(at_rest(SidewallWedge::Vector::Zero()), statics, history, history, reference, nullptr);
    if (pressure == 0.0) CHECK(reference.norm() <= 1e-9);
    for (double angle : {0.3, 1.7, -2.9, 6.0}) {
      const Eigen::Rotation2Dd rotation(angle);
      SidewallWedge::Vector residual;
      wedge.evaluate(at_rest(geometry.rigid_motion(angle, {0.7, -0.4})), statics, history, history, residual, nullptr);
      SidewallWedge::Vector expected = reference;
      for (int node = 0; node < 3; ++node) expected.segment<2>(3 * node) = rotation * reference.segment<2>(3 * node);
      INFO("p = " << pressure << ", angle = " << angle);
      CHECK((residual - expected).norm() <= 1e-12 * reference.norm() + 1e-9);
    }
  }
  // p > 0 in the reference state: a net pull on the tread toward the rim, balanced by the spindle.
  const SidewallWedge wedge = geometry.wedge(test_properties(), kPressure);
  SidewallWedge::Vector residual;
  wedge.evaluate(at_rest(SidewallWedge::Vector::Zero()), statics, history, history, residual, nullptr);
  const Eigen::Vector2d total = residual.segment<2>(0) + residual.segment<2>(3) + residual.segment<2>(6);
  CHECK(total.norm() <= 1e-12 * residual.norm());
  CHECK(residual.segment<2>(3).dot(geometry.tread_a - geometry.spindle) > 0.0);  // -(force) points outward
}

TEST_CASE("sidewall damping resists deformation rates only, not a rigid spin", "[sidewall]") {
  const WedgeGeometry geometry;
  const SidewallWedge wedge = geometry.wedge(test_properties(), kPressure);
  EvaluationContext damping_only;
  damping_only.factors = {0.0, 1.0, 0.0, 0.0, 0.0, 0.0};
  NoHistory history;
  const double spin = 52.0;  // rad/s, 51 km/h on a 0.27 m radius
  const Eigen::Vector2d drift(3.0, -1.0);
  LocalState<9> local = at_rest(geometry.rigid_motion(0.4, {0.01, 0.02}));
  int n = 0;
  for (const Eigen::Vector2d* node : {&geometry.spindle, &geometry.tread_a, &geometry.tread_b}) {
    const Eigen::Vector2d position = *node + local.displacement.segment<2>(3 * n);
    const Eigen::Vector2d spindle = geometry.spindle + local.displacement.segment<2>(0);
    local.velocity.segment<2>(3 * n) =
        drift + spin * Eigen::Vector2d(-(position - spindle).y(), (position - spindle).x());
    local.velocity[3 * n + 2] = spin;
    ++n;
  }
  SidewallWedge::Vector residual;
  wedge.evaluate(local, damping_only, history, history, residual, nullptr);
  CHECK(residual.norm() <= 1e-10);
  // A radial tread velocity is resisted by c_r: -(force) on the tread points along +v.
  local = at_rest(SidewallWedge::Vector::Zero());
  const Eigen::Vector2d outward = (0.5 * (geometry.tread_a + geometry.tread_b) - geometry.spindle).normalized();
  local.velocity.segment<2>(3) = local.velocity.segment<2>(6) = outward;
  wedge.evaluate(local, damping_only, history, history, residual, nullptr);
  const double chord_length = (geometry.tread_b - geometry.tread_a).norm();
  CHECK((residual.segment<2>(3) + residual.segment<2>(6)).dot(outward) ==
        Approx(test_properties().radial_damping * chord_length).epsilon(1e-3));
}

TEST_CASE("k_gamma is restoring: windup stiffness k_gamma r_rim R l / L", "[sidewall]") {
  SidewallProperties properties = test_properties();
  properties.bending_stiffness = 0.0;
  const WedgeGeometry geometry;
  const SidewallWedge wedge = geometry.wedge(properties, 0.0);
  NoHistory history;
  SidewallWedge::Vector residual;
  SidewallWedge::Matrix tangent;
  wedge.evaluate(at_rest(SidewallWedge::Vector::Zero()), EvaluationContext{}, history, history, residual, &tangent);
  // Rim rotated by d with the tread held: gamma = -d R/L at a point at radius R, so the
  // rim feels the moment -k_gamma (R/L) d r_rim per unit length. The Gauss points sit
  // slightly inside the tread circle, hence the 1e-3 tolerance.
  const double chord_length = (geometry.tread_b - geometry.tread_a).norm();
  const double cord = kTreadRadius - kRimRadius;
  CHECK(tangent(2, 2) == Approx(kShearStiffness * kRimRadius * kTreadRadius * chord_length / cord).epsilon(1e-3));
  // Tread moved counter-clockwise relative to the rim: the sidewall pulls it back.
  const Eigen::Vector2d tangential = Eigen::Rotation2Dd(0.5 * kPi) * (geometry.tread_a - geometry.spindle).normalized();
  SidewallWedge::Vector u = SidewallWedge::Vector::Zero();
  u.segment<2>(3) = u.segment<2>(6) = 1e-3 * tangential;
  wedge.evaluate(at_rest(u), EvaluationContext{}, history, history, residual, nullptr);
  CHECK((residual.segment<2>(3) + residual.segment<2>(6)).dot(tangential) > 0.0);
  CHECK(wedge.cord_state(u, 0).shear_angle > 0.0);  // measured counter-clockwise

  // Eqs. 10-11 apply -T_t at the rim point, so the forces sum to zero but the shear pair
  // is offset by the cord: the element's forces carry the couple (-P) x (S e_x) =
  // -L k_gamma gamma per unit length. Sum over nodes of x x f + moments, f = -residual.
  const Eigen::Vector2d* positions[3] = {&geometry.spindle, &geometry.tread_a, &geometry.tread_b};
  double moment = 0.0, expected = 0.0;
  Eigen::Vector2d force = Eigen::Vector2d::Zero();
  for (int node = 0; node < 3; ++node) {
    const Eigen::Vector2d x = *positions[node] + u.segment<2>(3 * node), f = -residual.segment<2>(3 * node);
    moment += x.x() * f.y() - x.y() * f.x() - residual[3 * node + 2];
    force += f;
  }
  const double deformed_chord = (geometry.tread_b + u.segment<2>(6) - geometry.tread_a - u.segment<2>(3)).norm();
  for (int q = 0; q < SidewallWedge::kQuadraturePoints; ++q) {
    const SidewallWedge::CordState cord = wedge.cord_state(u, q);
    expected -= 0.5 * deformed_chord * cord.chord * kShearStiffness * cord.shear_angle;
  }
  CHECK(force.norm() <= 1e-12 * residual.norm());
  CHECK(moment == Approx(expected).epsilon(1e-10));
}

TEST_CASE("shear angle gamma: from the turned reference cord to the deformed cord, windups up to 170 degrees",
          "[sidewall]") {
  // The spindle turns by w with the tread held: the rim point swings round the spindle and
  // gamma is the angle from -R(w) e_r to P = x_r - x_t, measured here with complex numbers.
  const WedgeGeometry geometry;
  const SidewallWedge wedge = geometry.wedge(test_properties(), kPressure);
  const double gauss_points[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  for (double windup : {-2.95, -1.9, -0.8, -0.3, -1e-3, 0.0, 2e-3, 0.25, 0.7, 0.9, 1.6, 2.95}) {
    SidewallWedge::Vector u = SidewallWedge::Vector::Zero();
    u[2] = windup;
    for (int q = 0; q < SidewallWedge::kQuadraturePoints; ++q) {
      const Eigen::Vector2d tread = (1.0 - gauss_points[q]) * geometry.tread_a + gauss_points[q] * geometry.tread_b;
      const Eigen::Vector2d radial = (tread - geometry.spindle).normalized();
      const Eigen::Vector2d rim_offset = Eigen::Rotation2Dd(windup) * (kRimRadius * radial);
      const Eigen::Vector2d cord = geometry.spindle + rim_offset - tread;
      const std::complex<double> turned_reference(-rim_offset.x(), -rim_offset.y()), deformed(cord.x(), cord.y());
      const double expected = std::arg(deformed / turned_reference);
      INFO("windup " << windup << " rad, q = " << q << ", gamma = " << expected);
      CHECK(std::abs(wedge.cord_state(u, q).shear_angle - expected) <= 1e-14);
    }
  }
}

TEST_CASE("sidewall rejects impossible geometry and parameters", "[sidewall]") {
  const WedgeGeometry geometry;
  SidewallProperties properties = test_properties();
  properties.cord_length = 0.11;  // shorter than the reference cord 0.118 m
  CHECK_THROWS_WITH(geometry.wedge(properties, 0.0), Catch::Contains("shorter than"));
  properties = test_properties();
  properties.bending_sign = 0.5;
  CHECK_THROWS_WITH(geometry.wedge(properties, 0.0), Catch::Contains("bending sign"));
  properties = test_properties();
  properties.rim_radius = 0.3;
  CHECK_THROWS_WITH(geometry.wedge(properties, 0.0), Catch::Contains("inside the rim"));
}

TEST_CASE("tread pressure tangent equals central finite differences and is unsymmetric", "[pressure]") {
  std::mt19937 random(3);
  const TreadPressure load(on_circle(kTreadRadius, 0.2), on_circle(kTreadRadius, 0.2 + 2.0 * kPi / 100.0), kTreadWidth,
                           constant_pressure(kPressure));
  for (int trial = 0; trial < 10; ++trial) {
    const LocalState<6> local = testing::random_local_state<6>(random, 0.02, 1.0);
    check_tangent(load, local, testing::dynamic_context());
    CHECK(testing::declared_zero_magnitude(load, local, testing::dynamic_context()) == 0.0);
    TreadPressure::Vector residual;
    TreadPressure::Matrix tangent;
    NoHistory history;
    load.evaluate(local, EvaluationContext{}, history, history, residual, &tangent);
    CHECK((tangent - tangent.transpose()).norm() >= 0.5 * tangent.norm());
  }
}

TEST_CASE("tread pressure batch path: every load of a perturbed ring as evaluate() gives it, to 1e-14", "[pressure]") {
  // 100 loads round a circle on two schedules (one ramped), deformed by centimetres.
  std::mt19937 random(17);
  constexpr int kLoads = 100;
  const auto ramped = std::make_shared<const PressureSchedule>(kPressure, LoadFunction::linear());
  const auto held = constant_pressure(0.5 * kPressure);
  std::vector<TreadPressure> loads;
  std::vector<LocalState<6>> locals;
  for (int e = 0; e < kLoads; ++e) {
    const double angle = 2.0 * kPi * e / kLoads;
    loads.emplace_back(on_circle(kTreadRadius, angle), on_circle(kTreadRadius, angle + 2.0 * kPi / kLoads),
                       kTreadWidth * (1.0 + 0.01 * e), e < 60 ? ramped : held);
    locals.push_back(testing::random_local_state<6>(random, 0.015, 1.0));
  }
  for (const EvaluationContext& context : testing::batch_contexts())
    for (bool with_tangent : {true, false}) {
      INFO("tangent " << with_tangent << ", time " << context.time);
      CHECK(testing::batch_deviation(loads, locals, context, with_tangent) <= 1e-14);
    }
}

TEST_CASE("tread pressure: p w l on each chord, outward, and zero net force on a closed ring", "[pressure]") {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const int count = 37;
  auto pressure = std::make_shared<const PressureSchedule>(kPressure, LoadFunction::linear());
  std::vector<Eigen::Vector2d> reference(count), deformed(count);
  for (int i = 0; i < count; ++i) {
    reference[i] = on_circle(kTreadRadius, 2.0 * kPi * i / count);
    deformed[i] = reference[i] + Eigen::Vector2d(0.01 * uniform(random), 0.01 * uniform(random));
  }
  EvaluationContext context;
  context.time = 0.5;  // half the pressure on the linear ramp
  Eigen::Vector2d total = Eigen::Vector2d::Zero();
  double largest = 0.0;
  for (int i = 0; i < count; ++i) {
    const int j = (i + 1) % count;
    const TreadPressure load(reference[i], reference[j], kTreadWidth, pressure);
    LocalState<6> local;
    local.velocity.setZero();
    local.acceleration.setZero();
    local.displacement << deformed[i] - reference[i], 0.3, deformed[j] - reference[j], -0.2;
    TreadPressure::Vector residual;
    NoHistory history;
    load.evaluate(local, context, history, history, residual, nullptr);
    const Eigen::Vector2d force = -(residual.segment<2>(0) + residual.segment<2>(3));
    const Eigen::Vector2d chord = deformed[j] - deformed[i];
    CHECK(force.norm() == Approx(0.5 * kPressure * kTreadWidth * chord.norm()).epsilon(1e-13));
    CHECK(std::abs(force.dot(chord)) <= 1e-12 * force.norm() * chord.norm());
    CHECK(force.dot(deformed[i] + deformed[j]) > 0.0);                       // away from the centre
    CHECK((residual.segment<2>(0) - residual.segment<2>(3)).norm() == 0.0);  // split equally
    CHECK(residual[2] == 0.0);
    CHECK(residual[5] == 0.0);
    total += force;
    largest = std::max(largest, force.norm());
  }
  CHECK(total.norm() <= 1e-13 * count * largest);
}

namespace {

struct InflatedRing {
  Model model;
  SidewallProperties sidewall;
  BeamSection tread;
  int count = 100;
};

void build_ring(InflatedRing& ring, std::shared_ptr<const PressureSchedule> pressure) {
  Model& model = ring.model;
  const int spindle = model.mesh().add_node({0.0, 0.0});
  for (int i = 0; i < ring.count; ++i) model.mesh().add_node(on_circle(kTreadRadius, 2.0 * kPi * i / ring.count));
  auto& beams = model.add_block<TreadBeam>("tread");
  auto& sidewalls = model.add_block<SidewallWedge>("sidewall");
  auto& loads = model.add_block<TreadPressure>("pressure");
  for (int i = 0; i < ring.count; ++i) {
    const int a = 1 + i, b = 1 + (i + 1) % ring.count;
    const Eigen::Vector2d& xa = model.mesh().position(a);
    const Eigen::Vector2d& xb = model.mesh().position(b);
    beams.add({a, b}, TreadBeam(xa, xb, ring.tread));
    sidewalls.add({spindle, a, b}, SidewallWedge(model.mesh().position(spindle), xa, xb, ring.sidewall, pressure));
    loads.add({a, b}, TreadPressure(xa, xb, kTreadWidth, pressure));
  }
  for (int c = 0; c < kDofsPerNode; ++c) model.fix(spindle, c);
}

}  // namespace

TEST_CASE("inflated ring: round, no spindle reaction, hoop force N = R (p w - F_sw) (docs/model.md section 3)",
          "[sidewall][pressure]") {
  for (double bending : {0.0, 100.0, -100.0}) {
    InflatedRing ring;
    ring.sidewall = test_properties();
    ring.sidewall.bending_stiffness = std::abs(bending);
    ring.sidewall.bending_sign = bending < 0.0 ? -1.0 : 1.0;
    ring.tread.axial_stiffness = 3e5;
    ring.tread.shear_stiffness = 8e4;
    ring.tread.bending_stiffness = 20.0;
    auto pressure = std::make_shared<const PressureSchedule>(kPressure, LoadFunction::linear());
    build_ring(ring, pressure);
    Analysis analysis(ring.model);
    analysis.set_time_step(0.25);
    const std::vector<StepRecord> records = analysis.advance(1.0);
    INFO("k_sw = " << bending);
    CHECK(records.size() == 4);
    for (const StepRecord& record : records) {
      CHECK(record.cuts == 0);
      CHECK(record.newton_iterations <= 6);
    }
    const State& state = analysis.state();
    const Mesh& mesh = ring.model.mesh();
    double smallest = 1e9, largest = 0.0;
    for (int node = 1; node <= ring.count; ++node) {
      const double radius = (mesh.position(node) + state.displacement.segment<2>(dof_index(node, kUx))).norm();
      smallest = std::min(smallest, radius);
      largest = std::max(largest, radius);
    }
    const double radius = 0.5 * (smallest + largest);
    CHECK(largest - smallest <= 1e-9 * radius);
    CHECK(analysis.reactions().head<3>().norm() <= 1e-10 * 2.0 * kPi * kTreadRadius * kPressure * kTreadWidth);

    // Hoop force from the tread strain of every beam against the closed form at the
    // inflated geometry: L at the sidewall's quadrature points (on the chord), where the
    // sidewall samples it; the rest is O((2 pi/N)^2) = 0.2 %.
    const auto& beams = dynamic_cast<const ElementBlockOf<TreadBeam>&>(ring.model.block("tread"));
    const auto& sidewalls = dynamic_cast<const ElementBlockOf<SidewallWedge>&>(ring.model.block("sidewall"));
    auto element_displacement = [&](const ElementBlock& block, int e, auto& vector) {
      const std::vector<int> nodes = block.element_nodes(e);
      for (size_t n = 0; n < nodes.size(); ++n)
        vector.template segment<3>(3 * n) = state.displacement.segment<3>(dof_index(nodes[n], 0));
    };
    SidewallWedge::Vector wedge_displacement;
    element_displacement(sidewalls, 0, wedge_displacement);
    const double chord = sidewalls.kernel(0).cord_state(wedge_displacement, 0).chord;
    const ArchShape arch = solve_arch(chord, kCordLength);
    const double theta = arch.meridian_angle(), r = arch.radius(kCordLength);
    const double r0 = kCordLength / (2.0 * sidewalls.kernel(0).reference_half_angle(0));
    const double sidewall_force =
        2.0 * kPressure * 0.5 * chord * std::tan(theta) + bending * (1.0 / (r * r) - 1.0 / (r * r0)) * std::sin(theta);
    const double hoop = radius * (kPressure * kTreadWidth - sidewall_force);
    INFO("R = " << radius << ", L = " << chord << ", theta = " << theta << ", N = " << hoop);
    CHECK(hoop > 1000.0);  // the tread is in tension
    for (int e = 0; e < ring.count; ++e) {
      TreadBeam::Vector beam_displacement;
      element_displacement(beams, e, beam_displacement);
      const double tension = ring.tread.axial_stiffness * beams.kernel(e).strains(beam_displacement).axial;
      CHECK(tension == Approx(hoop).epsilon(5e-3));
    }
  }
}
