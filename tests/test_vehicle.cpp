// The vehicle module on FE tires: the quarter car's static ride height and tire load
// against weight / stiffness, its wheel-hop frequency against the linearised two-mass
// system, the direct spindle Jacobian against the finite-difference one (same answer,
// fewer tire solves), a Jacobian fetched after a solve without it against one solved with
// it, a corrector's trial started on its residual alone against plain Newton's, and four
// concurrent tires against sequential ones, bit for bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "contact/rigid_motion.hpp"
#include "macros/macro_table.hpp"
#include "vehicle/tire_group.hpp"
#include "vehicle/tire_on_road.hpp"
#include "vehicle/vehicle.hpp"

using namespace tirefe;

namespace {

constexpr double kGravity = 9.81;
constexpr double kBodyMass = 300.0, kCarrierMass = 30.0;
constexpr double kSpring = 2.0e4;  // N/m

/// The 145 SR-12 tire on a still flat road (mu = 0.8).
struct PressedTire {
  TireOnRoad tire{macros::load_tire_parameters("tires.145SR12"),
                  [](double level) { return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level)); },
                  RoadContact{0.8}};
  TireSpindle* spindle = nullptr;

  double press(double deflection) { return tire.press(deflection); }
  void drive(double alpha) { spindle = &tire.drive(Integrator::hht(alpha)); }
};

/// Pressed 15 mm and driven (HHT -0.05); solve() takes 1 ms steps to its design position moved by (dx, dy).
struct PressedAndDriven : PressedTire {
  Eigen::Vector3d design;
  PressedAndDriven() {
    press(0.015);
    drive(-0.05);
    design = spindle->committed_position();
  }
  SpindleReply solve(double dx, double dy, SpindleStart start, bool jacobian = true) {
    SpindleInput input{1e-3, design.x() + dx, design.y() + dy, 0.0, start};
    input.jacobian = jacobian;
    return spindle->solve_step(input);
  }
};

Corner quarter_corner(double preload, double damping) {
  Corner corner;
  corner.name = "quarter";
  corner.mass = kCarrierMass;
  corner.suspension.spring = ForceCurve({{0.0, preload}, {0.1, preload + 0.1 * kSpring}});
  corner.suspension.damper = ForceCurve::linear(damping);
  corner.suspension.bumper_gap = 0.05;
  corner.suspension.bumper_stiffness = 1e7;
  corner.suspension.fore_aft_stiffness = 1e5;
  corner.suspension.fore_aft_damping = 1e3;
  return corner;
}

}  // namespace

TEST_CASE("a corrector's trial from the tire's last trial moved by its linear response: the cold answer, less Newton",
          "[vehicle][spindle]") {
  PressedAndDriven tire;
  auto solve = [&](double dx, double dy, SpindleStart start) { return tire.solve(dx, dy, start); };
  const SpindleReply first = solve(0.0, -1e-4, SpindleStart::Predictor);  // a predicted trial
  const Eigen::Vector2d move(2e-6, -3e-6);                                // a corrector's increment
  const SpindleReply warm = solve(move.x(), -1e-4 + move.y(), SpindleStart::LastTrial);
  const SpindleReply cold = solve(move.x(), -1e-4 + move.y(), SpindleStart::Predictor);
  const Eigen::Vector2d linear = force_of(first).head<2>() + jacobian_of(first).topLeftCorner<2, 2>() * move;
  const Eigen::Vector2d change = linear - force_of(first).head<2>();
  INFO("force " << force_of(cold).transpose() << " N, warm - cold " << (force_of(warm) - force_of(cold)).transpose()
                << ", warm - linear " << (force_of(warm).head<2>() - linear).transpose() << ", Newton "
                << warm.newton_iterations << " vs " << cold.newton_iterations);
  // Both converge to the tire's Newton tolerance (1e-9 of the force level).
  CHECK((force_of(warm) - force_of(cold)).norm() <= 1e-7 * force_of(cold).norm());
  CHECK((jacobian_of(warm) - jacobian_of(cold)).norm() <= 1e-6 * jacobian_of(cold).norm());
  CHECK(change.norm() > 1.0);                                                // the move matters: ~1e5-1e6 N/m
  CHECK((force_of(warm).head<2>() - linear).norm() < 1e-3 * change.norm());  // second order in the move
  CHECK(warm.newton_iterations <= 1);
  CHECK(warm.newton_iterations < cold.newton_iterations);
  // With no trial of this step to start from (after a commit), the predictor: the cold answer, bit for bit.
  tire.spindle->commit();
  const SpindleReply from_commit = solve(0.0, -2e-4, SpindleStart::LastTrial);
  const Eigen::Vector3d fallback = force_of(from_commit);
  tire.spindle->revert();
  CHECK((fallback - force_of(solve(0.0, -2e-4, SpindleStart::Predictor))).norm() == 0.0);
}

TEST_CASE("a Jacobian asked after a solve without it: the solve's own, and a corrector's trial after it the same",
          "[vehicle][spindle]") {
  PressedAndDriven tire;
  auto solve = [&](double dy, SpindleStart start, bool jacobian) { return tire.solve(0.0, dy, start, jacobian); };
  auto ask_jacobian = [&] {
    SpindleRequest request;
    request.command = SpindleCommand::Jacobian;
    return tire.spindle->serve(request);
  };
  const SpindleReply with = solve(-1e-4, SpindleStart::Predictor, true);
  const SpindleReply warm_with = solve(-1.03e-4, SpindleStart::LastTrial, true);
  const SpindleReply without = solve(-1e-4, SpindleStart::Predictor, false);
  CHECK(jacobian_of(without).isZero());
  CHECK((force_of(without) - force_of(with)).norm() == 0.0);
  const SpindleReply later = ask_jacobian();
  REQUIRE(later.status == SpindleStatus::Ok);
  CHECK(jacobian_of(later).diagonal().head<2>().minCoeff() > 1e5);  // a loaded tire's H_ss, N/m
  CHECK((jacobian_of(later) - jacobian_of(with)).norm() == 0.0);    // bit for bit
  CHECK((force_of(later) - force_of(with)).norm() == 0.0);
  // The corrector's next trial moves from the last one as after a solve with the Jacobian.
  const SpindleReply warm_without = solve(-1.03e-4, SpindleStart::LastTrial, true);
  CHECK((force_of(warm_without) - force_of(warm_with)).norm() == 0.0);
  CHECK(warm_without.newton_iterations == warm_with.newton_iterations);
  // Never asked for, the last trial's factors are not kept: the next trial starts from
  // the predictor, the cold answer bit for bit.
  solve(-1e-4, SpindleStart::Predictor, false);
  const SpindleReply unfactored = solve(-1.03e-4, SpindleStart::LastTrial, true);
  const SpindleReply cold = solve(-1.03e-4, SpindleStart::Predictor, true);
  CHECK((force_of(unfactored) - force_of(cold)).norm() == 0.0);
  CHECK(unfactored.newton_iterations == cold.newton_iterations);
  CHECK(unfactored.newton_iterations > warm_with.newton_iterations);
  // No trial, no Jacobian.
  tire.spindle->revert();
  const SpindleReply refused = ask_jacobian();
  CHECK(refused.status == SpindleStatus::Failed);
  CHECK(std::string(refused.message).find("trial") != std::string::npos);
}

TEST_CASE("a corrector's trial started on its residual alone gives plain Newton's forces and H_ss",
          "[vehicle][spindle]") {
  // Two tires alike, one with plain Newton's every evaluation taking the tangent.
  PressedAndDriven lean, plain;
  plain.tire.analysis().newton_settings().residual_only_when_converging = false;
  auto ask_jacobian = [](PressedAndDriven& tire) {
    SpindleRequest request;
    request.command = SpindleCommand::Jacobian;
    return tire.spindle->serve(request);
  };
  const SpindleReply lean_first = lean.solve(0.0, -1e-4, SpindleStart::Predictor);
  const SpindleReply plain_first = plain.solve(0.0, -1e-4, SpindleStart::Predictor);
  REQUIRE((force_of(lean_first) - force_of(plain_first)).norm() == 0.0);
  // A corrector's increments: one small enough to converge at once, one that iterates
  // (its start made again with the tangent).
  for (const double dy : {-1e-4 - 1e-9, -1.03e-4}) {
    const SpindleReply lean_trial = lean.solve(0.0, dy, SpindleStart::LastTrial, false);
    const int lean_residual_only = lean.tire.analysis().last_newton_report().residual_only;
    const SpindleReply plain_trial = plain.solve(0.0, dy, SpindleStart::LastTrial, false);
    INFO("dy " << dy << ": Newton " << lean_trial.newton_iterations << " and " << plain_trial.newton_iterations);
    CHECK(lean_residual_only == 1);  // the start, of the residual alone
    CHECK(plain.tire.analysis().last_newton_report().residual_only == 0);
    CHECK(lean_trial.newton_iterations == plain_trial.newton_iterations);
    CHECK((lean_trial.newton_iterations == 0) == (dy > -1.01e-4));
    CHECK((force_of(lean_trial) - force_of(plain_trial)).norm() == 0.0);  // bit for bit
    const SpindleReply lean_jacobian = ask_jacobian(lean), plain_jacobian = ask_jacobian(plain);
    CHECK(jacobian_of(lean_jacobian).diagonal().head<2>().minCoeff() > 1e5);  // a loaded tire's H_ss, N/m
    CHECK((jacobian_of(lean_jacobian) - jacobian_of(plain_jacobian)).norm() == 0.0);
    CHECK((force_of(lean_jacobian) - force_of(plain_jacobian)).norm() == 0.0);
  }
}

TEST_CASE("quarter car: static ride height is weight over stiffness, the tire carries the whole weight",
          "[vehicle][quarter]") {
  PressedTire tire;
  tire.press(0.015);
  tire.drive(-0.05);
  TireGroup tires({tire.spindle}, false);
  // Spring preload 0.8 of the body weight: the suspension settles 0.2 m_b g / k_s into jounce.
  const double critical = 2.0 * std::sqrt(kSpring * kBodyMass);
  VehicleSettings settings;
  settings.alpha = -0.05;
  Vehicle car({kBodyMass}, {quarter_corner(0.8 * kBodyMass * kGravity, critical)}, tires, settings);
  car.advance(2.5, 2e-3);
  const double expected_jounce = 0.2 * kBodyMass * kGravity / kSpring;
  CHECK(car.jounce(0) == Approx(expected_jounce).epsilon(1e-3));
  CHECK(car.spindle_force(0).y() == Approx(-(kBodyMass + kCarrierMass) * kGravity).epsilon(2e-3));
  // The vehicle knows the force from the Commit replies only (a tire on another MPI rank
  // does not advance here): they carry the tire's own committed reaction.
  CHECK((car.spindle_force(0) - tire.spindle->committed_force()).lpNorm<Eigen::Infinity>() == 0.0);
  CHECK(std::abs(car.state().velocity[0]) < 1e-3);
  // The corrector converges in a few iterations with the direct Jacobian.
  const VehicleStatistics& statistics = car.statistics();
  CHECK(statistics.cuts == 0);
  CHECK(statistics.corrector_iterations <= 4 * statistics.steps);
  // 2.5 s in steps of 2 ms: 1250 of them, whatever the round-off of the summed times (no
  // sliver of a step at the end).
  CHECK(statistics.steps == 1250);
  const double start = car.time() - 2.5;
  car.advance(0.7, 0.1 / 3.0);  // 21 steps of a step size that is no binary fraction
  CHECK(car.statistics().steps == 1250 + 21);
  CHECK(car.time() == Approx(start + 3.2).epsilon(1e-14));
  // A window of quarter steps: 5 steps of 10 ms, 20 of 2.5 ms, then 10 of 10 ms.
  const double now = car.time();
  car.advance(0.2, 0.01, {{now + 0.05, now + 0.1, 0.0025}});
  CHECK(car.statistics().steps == 1271 + 35);
  CHECK(car.time() == Approx(now + 0.2).epsilon(1e-14));
  CHECK_THROWS_AS(car.advance(0.1, 0.01, {{now + 0.3, now + 0.25, 0.001}}), ModelError);
}

TEST_CASE("quarter car with generalized-alpha tires and body: the heave HHT gives, to its time-step error",
          "[vehicle][quarter]") {
  // The body integrates with its tires' scheme. Released at a fifth of its critical damping
  // from a preload of 0.8 of its weight, the body rings at about 1.3 Hz (sqrt(k_s / m_b)),
  // resolved by 2 ms steps (omega h = 0.016): two second-order schemes agree to well below
  // a per mille (measured 2e-6); leaving out the old inertia force alpha_m M a_n moves them
  // 23 % apart.
  auto heave = [](const Integrator& scheme) {
    PressedTire tire;
    tire.press(0.015);
    tire.spindle = &tire.tire.drive(scheme);
    TireGroup tires({tire.spindle}, false);
    VehicleSettings settings;
    settings.scheme = scheme;
    Vehicle car({kBodyMass}, {quarter_corner(0.8 * kBodyMass * kGravity, 0.4 * std::sqrt(kSpring * kBodyMass))}, tires,
                settings);
    std::vector<double> samples;
    for (int k = 0; k < 15; ++k) {
      car.advance(0.1, 2e-3);
      samples.push_back(car.state().displacement[0]);
    }
    CHECK(car.statistics().cuts == 0);
    return samples;
  };
  const std::vector<double> hht = heave(Integrator::hht(-0.05)), alpha = heave(Integrator::generalized_alpha(0.8));
  double largest = 0.0, difference = 0.0;
  for (size_t k = 0; k < hht.size(); ++k) {
    largest = std::max(largest, std::abs(hht[k]));
    difference = std::max(difference, std::abs(alpha[k] - hht[k]));
  }
  INFO("heave up to " << largest << " m, the schemes " << difference << " m apart");
  CHECK(largest > 5e-3);
  CHECK(difference <= 1e-3 * largest);
}

TEST_CASE("quarter car: the wheel-hop frequency is that of the linearised two-mass system", "[vehicle][quarter]") {
  PressedTire tire;
  // The tire's vertical stiffness k_t at the static load: the static deflection from two
  // quasi-static presses 10 mm apart, then the slope of two presses 2 mm either side of it.
  const double f1 = tire.press(0.010), f2 = tire.press(0.020);
  const double weight = (kBodyMass + kCarrierMass) * kGravity;
  const double static_deflection = 0.010 + (weight + f1) / ((f1 - f2) / 0.010);
  const double below = tire.press(static_deflection - 0.002), above = tire.press(static_deflection + 0.002);
  const double k_tire = (below - above) / 0.004;
  tire.press(static_deflection - 0.001);  // let go 1 mm short of equilibrium: a small hop
  tire.drive(0.0);
  TireGroup tires({tire.spindle}, false);
  Vehicle car({kBodyMass}, {quarter_corner(kBodyMass * kGravity, 50.0)}, tires, VehicleSettings{});
  std::vector<std::pair<double, double>> wheel;  // (t, z_w)
  car.add_step_observer([&wheel](const Vehicle& v) { wheel.emplace_back(v.time(), v.state().displacement[1]); });
  car.advance(0.35, 5e-4);

  std::vector<double> peaks;  // times of the wheel's local maxima
  for (size_t i = 1; i + 1 < wheel.size(); ++i)
    if (wheel[i].second > wheel[i - 1].second && wheel[i].second >= wheel[i + 1].second)
      peaks.push_back(wheel[i].first);
  REQUIRE(peaks.size() >= 3);
  const double measured = (peaks.size() - 1) / (peaks.back() - peaks.front());
  // Linearised quarter car: masses m_b and m_u, springs k_s and k_t; the higher
  // eigenfrequency is the hop. m_u = carrier + rim + belt: at ~11 Hz, far below its own
  // modes (~90 Hz), the belt ring moves with the hub (without the belt, 4% too high).
  const TireParameters parameters = macros::load_tire_parameters("tires.145SR12");
  const double unsprung =
      kCarrierMass + parameters.rim_mass + parameters.tread.mass_per_length * M_PI * parameters.outer_diameter;
  Eigen::Matrix2d stiffness, mass = Eigen::Vector2d(kBodyMass, unsprung).asDiagonal();
  stiffness << kSpring, -kSpring, -kSpring, kSpring + k_tire;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> modes(stiffness, mass);
  const double expected = std::sqrt(modes.eigenvalues()[1]) / (2.0 * M_PI);
  const double simple = std::sqrt((kSpring + k_tire) / unsprung) / (2.0 * M_PI);
  INFO("k_t = " << k_tire << " N/m, hop measured " << measured << " Hz, two-mass " << expected
                << " Hz, sqrt((k_s + k_t)/m_u)/2pi = " << simple << " Hz, " << peaks.size() << " peaks");
  CHECK(measured == Approx(expected).epsilon(0.02));
  CHECK(simple == Approx(expected).epsilon(0.01));  // the textbook formula: the body hardly moves
}

TEST_CASE("quarter car: the direct spindle Jacobian gives the finite-difference run's answer with fewer tire solves",
          "[vehicle][quarter]") {
  auto run = [](SpindleJacobianSource source) {
    auto tire = std::make_unique<PressedTire>();
    tire->press(0.015);
    tire->drive(-0.05);
    TireGroup tires({tire->spindle}, false);
    VehicleSettings settings;
    settings.alpha = -0.05;
    settings.jacobian = source;
    Vehicle car({kBodyMass}, {quarter_corner(0.8 * kBodyMass * kGravity, 1000.0)}, tires, settings);
    car.advance(0.1, 2e-3);
    return std::make_pair(Eigen::VectorXd(car.state().displacement), car.statistics());
  };
  const auto direct = run(SpindleJacobianSource::Direct);
  const auto difference = run(SpindleJacobianSource::FiniteDifference);
  // Both converge to the corrector tolerance (1e-8 of the weight, ~3e-5 N: ~1e-10 m).
  CHECK((direct.first - difference.first).lpNorm<Eigen::Infinity>() < 1e-8);
  CHECK(direct.second.corrector_iterations <= difference.second.corrector_iterations);
  CHECK(3 * direct.second.tire_solves < 2 * difference.second.tire_solves);
}

TEST_CASE("full car: four tires solved in two or four concurrent lanes give the sequential run bit for bit",
          "[vehicle][car]") {
  auto run = [](int lanes) {
    std::vector<std::unique_ptr<PressedTire>> tires;
    std::vector<TireSpindle*> spindles;
    std::vector<Corner> corners;
    const double positions[4][2] = {{1.3, 0.7}, {1.3, -0.7}, {-1.4, 0.7}, {-1.4, -0.7}};
    for (int i = 0; i < 4; ++i) {
      tires.push_back(std::make_unique<PressedTire>());
      tires.back()->press(0.010 + 0.002 * i);  // unequal: the body pitches and rolls
      tires.back()->drive(-0.05);
      spindles.push_back(tires.back()->spindle);
      Corner corner = quarter_corner(0.8 * kBodyMass * kGravity, 1500.0);
      corner.x = positions[i][0];
      corner.y = positions[i][1];
      corners.push_back(corner);
    }
    TireGroup group(spindles, lanes > 1, lanes);
    REQUIRE(group.lanes() == lanes);
    VehicleSettings settings;
    settings.alpha = -0.05;
    Vehicle car({4 * kBodyMass, 1500.0, 400.0}, corners, group, settings);
    car.advance(0.04, 2e-3);
    return Eigen::VectorXd(car.state().displacement);
  };
  const Eigen::VectorXd sequential = run(1);
  CHECK(std::abs(sequential[1]) > 1e-5);  // pitch
  CHECK(std::abs(sequential[2]) > 1e-5);  // roll
  CHECK((sequential - run(2)).lpNorm<Eigen::Infinity>() == 0.0);
  CHECK((sequential - run(4)).lpNorm<Eigen::Infinity>() == 0.0);
}
