// The spindle force interface (docs/model.md section 6): the condensed Jacobian H_ss against
// central finite differences of the converged spindle force on a tire rolling with
// friction on a moving flat road; trial solves leave the tire's history alone; a
// corrector's trial started on its residual alone against plain Newton's.
#include <catch2/catch.hpp>

#include "contact/rigid_motion.hpp"
#include "macros/macro_table.hpp"
#include "vehicle/tire_on_road.hpp"
#include "vehicle/tire_spindle.hpp"
#include "solvers/driven_solver.hpp"
#include "solvers/ring_solver.hpp"

using namespace tirefe;

namespace {

constexpr double kDeflection = 0.02;  // spindle pressed down [m]
constexpr double kStep = 1e-3;        // [s]
constexpr double kAlpha = -0.05;

/// The 145 SR-12 tire pressed 20 mm onto a road that starts moving at t = 2 s
/// (ramped to 5 m/s in 0.05 s, mu = 0.8): the tire spins up under a dead axle, rolling
/// with part of the patch slipping. The spin is free; the spindle is held by a TireSpindle.
struct RollingTire {
  TireOnRoad tire{macros::load_tire_parameters("tires.145SR12"),
                  [](double level) {
                    return std::make_shared<FlatRoad>(
                        Eigen::Vector2d(0.0, level), Eigen::Vector2d::UnitX(),
                        RigidMotion::translation(MotionFunction::ramped_rate(-5.0, 0.05, 2.0)));
                  },
                  RoadContact{0.8}};
  std::unique_ptr<TireSpindle> spindle;
  SpinMode spin_mode;

  explicit RollingTire(SpinMode spin = SpinMode::Free) : spin_mode(spin) {
    Model& model = tire.model();
    const int press = model.add_load_function(LoadFunction::table({{1.0, 0.0}, {2.0, 1.0}}));
    model.prescribe(tire.tire().spindle, 1, -kDeflection, press);
    tire.analysis().set_time_step(0.25);
    tire.analysis().advance(1.0);
    tire.analysis().set_integrator(Integrator::hht(kAlpha));
    spindle = std::make_unique<TireSpindle>(tire.analysis(), tire.tire().spindle, spin);
  }

  /// A driven spin turns the wheel 10% slower than free rolling on the road (braking):
  /// the angle follows the road's travel over a rolling radius of 0.264 m.
  double braked_spin(double time) const {
    const double t = time - 2.0, v = 5.0, ramp = 0.05;
    const double travel = t <= 0.0 ? 0.0 : t < ramp ? 0.5 * v * t * t / ramp : v * (t - 0.5 * ramp);
    return -0.9 * travel / 0.264;
  }
  SpindleReply solve(double x, double y, double spin_offset = 0.0) {
    const double spin = spin_mode == SpinMode::Driven ? braked_spin(spindle->time() + kStep) + spin_offset : 0.0;
    return spindle->solve_step({kStep, x, y, spin});
  }
  void roll(int steps) {
    for (int i = 0; i < steps; ++i) {
      solve(0.0, -kDeflection);
      spindle->commit();
    }
  }
};

}  // namespace

TEST_CASE("spindle Jacobian H_ss equals central differences of the spindle force, rolling with friction",
          "[spindle][vehicle]") {
  RollingTire rolling;  // free spin
  // Uzawa updates change the multipliers with the spindle position outside Newton; H_ss
  // is the derivative of the step equations with the step's multipliers, so compare with them held.
  rolling.tire.analysis().step_control().max_augmentations = 0;
  rolling.tire.analysis().newton_settings().residual_tolerance = 1e-12;
  rolling.roll(60);
  const ContactSummary summary = summarize_contact(rolling.tire.contact());
  REQUIRE(summary.nodes_in_contact >= 3);
  CHECK(std::abs(summary.force.x()) > 0.01 * std::abs(summary.force.y()));  // friction acts in the patch
  const double spin_rate = rolling.tire.analysis().state().velocity[dof_index(rolling.tire.tire().spindle, 2)];
  CHECK(spin_rate < -1.0);  // the road drags the tire into rolling (clockwise)

  const SpindleReply centre = rolling.solve(0.0, -kDeflection);
  const SpindleJacobian jacobian = jacobian_of(centre);
  CHECK(force_of(centre)[1] < -1000.0);  // the spindle is held down against the road
  // Central differences: truncation ~ delta^2 f''' and the Newton tolerance / delta are
  // both far below 1e-5 of the structural stiffness for delta = 1e-7 m (measured: 2e-10;
  // the margin covers a patch-edge node whose gap changes sign within +-delta).
  const double delta = 1e-7;
  SpindleJacobian difference = SpindleJacobian::Zero();
  for (int j = 0; j < 2; ++j) {
    const double dx = j == 0 ? delta : 0.0, dy = j == 1 ? delta : 0.0;
    const SpindleReply plus = rolling.solve(dx, -kDeflection + dy);
    const SpindleReply minus = rolling.solve(-dx, -kDeflection - dy);
    difference.col(j) = (force_of(plus) - force_of(minus)) / (2.0 * delta);
  }
  // H holds the rim's inertia m / (beta h^2) on its diagonal (exactly, in both); judge the
  // agreement against the tire's own stiffness, what is left without it.
  const Integrator& integrator = rolling.tire.analysis().integrator();
  const double rim_mass = macros::load_tire_parameters("tires.145SR12").rim_mass;
  SpindleJacobian structural = jacobian;
  structural.diagonal().head<2>().array() -= rim_mass / (integrator.beta() * kStep * kStep);
  const double scale = structural.topLeftCorner<2, 2>().cwiseAbs().maxCoeff();
  const double error = (jacobian - difference).topLeftCorner<2, 2>().cwiseAbs().maxCoeff();
  INFO("H_ss\n" << jacobian << "\nfinite differences\n" << difference << "\nstructural part\n" << structural);
  CHECK(scale > 1e5);  // a loaded tire: of order 1e5 - 1e6 N/m
  CHECK(error < 1e-5 * scale);
  CHECK(jacobian.row(2).isZero());  // free spin: no moment, no rz column
  CHECK(jacobian.col(2).isZero());
}

TEST_CASE("a corrector's trial started on its residual alone, rolling with slip, gives plain Newton's answer",
          "[spindle][vehicle]") {
  RollingTire lean, plain;  // plain: every Newton evaluation with its tangent
  plain.tire.analysis().newton_settings().residual_only_when_converging = false;
  for (RollingTire* tire : {&lean, &plain}) tire->roll(10);  // the spin-up, slip in the patch
  REQUIRE(summarize_contact(lean.tire.contact()).nodes_slipping >= 1);
  auto trial = [](RollingTire& tire, double dx, SpindleStart start, bool jacobian) {
    SpindleInput input{kStep, dx, -kDeflection, 0.0, start};
    input.jacobian = jacobian;
    return tire.spindle->solve_step(input);
  };
  REQUIRE((force_of(trial(lean, 0.0, SpindleStart::Predictor, true)) -
           force_of(trial(plain, 0.0, SpindleStart::Predictor, true)))
              .norm() == 0.0);
  // A corrector's increments, fore-aft: one that converges at once, one that iterates
  // (its start made again with the tangent, from the history it began with).
  for (const double dx : {1e-9, 2e-5}) {
    const SpindleReply lean_reply = trial(lean, dx, SpindleStart::LastTrial, false);
    const NewtonReport lean_report = lean.tire.analysis().last_newton_report();
    const SpindleReply plain_reply = trial(plain, dx, SpindleStart::LastTrial, false);
    INFO("dx " << dx << ": Newton " << lean_reply.newton_iterations << " and " << plain_reply.newton_iterations);
    CHECK(lean_report.residual_only == 1);
    CHECK((lean_reply.newton_iterations == 0) == (dx < 1e-6));
    CHECK(lean_reply.newton_iterations == plain_reply.newton_iterations);
    CHECK((force_of(lean_reply) - force_of(plain_reply)).norm() == 0.0);
    SpindleRequest request;
    request.command = SpindleCommand::Jacobian;
    const SpindleReply lean_jacobian = lean.spindle->serve(request), plain_jacobian = plain.spindle->serve(request);
    CHECK((jacobian_of(lean_jacobian) - jacobian_of(plain_jacobian)).norm() == 0.0);
  }
  // The committed steps alike: the contact history the trials leave is plain Newton's.
  for (RollingTire* tire : {&lean, &plain}) tire->spindle->commit();
  lean.roll(3);
  plain.roll(3);
  CHECK((lean.spindle->committed_force() - plain.spindle->committed_force()).norm() == 0.0);
}

TEST_CASE("spindle trial solves do not advance the tire; commit and revert do what they say", "[spindle][vehicle]") {
  RollingTire rolling;
  rolling.roll(5);
  const double time = rolling.spindle->time();
  const SpindleReply first = rolling.solve(0.0, -kDeflection);
  rolling.solve(0.001, -kDeflection - 0.002);  // a trial elsewhere ...
  rolling.spindle->revert();
  CHECK(rolling.spindle->time() == time);
  const SpindleReply again = rolling.solve(0.0, -kDeflection);  // ... leaves no trace
  CHECK((force_of(again) - force_of(first)).norm() <= 1e-9 * force_of(first).norm());
  CHECK((jacobian_of(again) - jacobian_of(first)).norm() <= 1e-9 * jacobian_of(first).norm());
  rolling.spindle->commit();
  CHECK(rolling.spindle->time() == Approx(time + kStep).epsilon(1e-14));
  CHECK((rolling.spindle->committed_position().head<2>() - Eigen::Vector2d(0.0, -kDeflection)).norm() < 1e-15);

  SpindleRequest request;
  request.command = SpindleCommand::Commit;  // nothing to commit now
  const SpindleReply refused = rolling.spindle->serve(request);
  CHECK(refused.status == SpindleStatus::Failed);
  CHECK(std::string(refused.message).find("no trial step") != std::string::npos);
}

TEST_CASE("driven-DOF solves and the Schur complement equal dense linear algebra, with KLU factors",
          "[spindle][linear]") {
  // An unsymmetric, regular 12 x 12 sparse matrix; the last three equations are driven.
  const int n = 12, s = 3;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    dense(i, i) = 10.0 + i;
    dense(i, (i + 1) % n) = -2.0 + 0.1 * i;
    dense((i + 3) % n, i) = 1.5 - 0.2 * i;
  }
  const SparseMatrix sparse = dense.sparseView();
  KluSolver klu;
  DrivenDofSolver driven(klu, {n - 3, n - 2, n - 1});
  driven.analyze(sparse);
  driven.factorize(sparse);

  const int u = n - s;
  const Eigen::MatrixXd schur =
      dense.bottomRightCorner(s, s) -
      dense.bottomLeftCorner(s, u) * dense.topLeftCorner(u, u).lu().solve(dense.topRightCorner(u, s));
  CHECK((Eigen::MatrixXd(driven.schur_complement()) - schur).norm() < 1e-13 * schur.norm());

  Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0), x = rhs;
  driven.solve(x);
  const Eigen::VectorXd expected = dense.topLeftCorner(u, u).lu().solve(rhs.head(u));
  CHECK((x.head(u) - expected).norm() < 1e-13 * expected.norm());
  CHECK(x.tail(s).isZero(0.0));
}

TEST_CASE("spindle Jacobian H_ss with a driven spin (a braked wheel) equals central differences, moment included",
          "[spindle][vehicle]") {
  RollingTire rolling(SpinMode::Driven);
  rolling.tire.analysis().step_control().max_augmentations = 0;
  rolling.tire.analysis().newton_settings().residual_tolerance = 1e-12;
  rolling.roll(60);
  const SpindleReply centre = rolling.solve(0.0, -kDeflection);
  CHECK(force_of(centre)[0] > 100.0);          // the axle holds the braked wheel against the road ...
  CHECK(force_of(centre)[2] > 10.0);           // ... and the brake a moment against its clockwise spin
  const double delta[3] = {1e-7, 1e-7, 1e-6};  // m, m, rad
  SpindleJacobian difference;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d d = delta[j] * Eigen::Vector3d::Unit(j);
    const SpindleReply plus = rolling.solve(d.x(), -kDeflection + d.y(), d.z());
    const SpindleReply minus = rolling.solve(-d.x(), -kDeflection - d.y(), -d.z());
    difference.col(j) = (force_of(plus) - force_of(minus)) / (2.0 * delta[j]);
  }
  const SpindleJacobian jacobian = jacobian_of(centre);
  INFO("H_ss\n" << jacobian << "\nfinite differences\n" << difference);
  // Column by column against the column's structural size (the rim's inertia m/(beta h^2)
  // and I/(beta h^2) on the diagonal removed): N/m, N/m and N m/rad do not mix.
  const TireParameters parameters = macros::load_tire_parameters("tires.145SR12");
  const double inertia_factor = 1.0 / (rolling.tire.analysis().integrator().beta() * kStep * kStep);
  SpindleJacobian structural = jacobian;
  structural.diagonal() -=
      inertia_factor * Eigen::Vector3d(parameters.rim_mass, parameters.rim_mass, parameters.rim_rotary_inertia);
  for (int j = 0; j < 3; ++j) {
    const double scale = structural.col(j).cwiseAbs().maxCoeff();
    CHECK(scale > 0.0);
    CHECK((jacobian.col(j) - difference.col(j)).cwiseAbs().maxCoeff() < 1e-5 * scale);
  }
}

TEST_CASE("driven-DOF solves and H_ss through the RingSolver's border equal those through KLU, on a rolling tire",
          "[spindle][linear]") {
  // The ring route reads H from the border Schur complement and needs no column solves;
  // the general route solves for the columns with KLU's factors; the assembled route
  // condenses from the held ring's factors and the held rows and columns kept beside them.
  // Same matrix: the effective tangent of a tire rolling with friction (stick and slip in
  // the patch), assembled here at the trial the spindle solve converged to.
  RollingTire rolling;
  rolling.roll(20);
  rolling.solve(0.0, -kDeflection);
  Analysis& analysis = rolling.tire.analysis();
  EvaluationContext context;
  context.time = analysis.driven_stepper().trial().time;
  context.time_step = kStep;
  context.factors = analysis.integrator().factors(kStep);
  context.want_tangent = true;
  Eigen::VectorXd residual;
  analysis.assembler().query(context, analysis.driven_stepper().trial(), residual);
  const SparseMatrix& tangent = analysis.assembler().tangent();
  const DofMap& dofs = analysis.model().dof_map();
  const int spindle = rolling.tire.tire().spindle;
  for (int driven_count : {2, 3}) {  // free spin, driven spin
    INFO(driven_count << " driven equations");
    std::vector<int> driven;
    for (int c = 0; c < driven_count; ++c) driven.push_back(dofs.equation(dof_index(spindle, c)));
    KluSolver klu;
    RingSolver ring(dofs, rolling.tire.tire().tread_nodes, {spindle});
    DrivenDofSolver general(klu, driven), structured(ring, driven);
    for (DrivenDofSolver* solver : {&general, &structured}) {
      solver->analyze(tangent);
      solver->factorize_with_schur(tangent);
    }
    const Eigen::MatrixXd h_general = general.schur_complement(), h_ring = structured.schur_complement();
    CHECK((h_ring - h_general).norm() <= 1e-9 * h_general.norm());
    const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(tangent.rows(), -1.0, 2.0);
    Eigen::VectorXd x_general = rhs, x_ring = rhs, x_held = rhs;
    general.solve(x_general);
    structured.solve(x_ring);
    CHECK((x_ring - x_general).norm() <= 1e-9 * x_general.norm());
    for (int equation : driven) CHECK(x_ring[equation] == 0.0);

    // Newton's factorisation holds the driven equations out of the ring's border: the
    // same solution, and no H to read from it.
    structured.factorize(tangent);
    structured.solve(x_held);
    CHECK((x_held - x_general).norm() <= 1e-9 * x_general.norm());
    for (int equation : driven) CHECK(x_held[equation] == 0.0);
    CHECK_THROWS_AS(structured.schur_complement(), std::logic_error);

    // The tangent assembled into the held ring's storage, entry by entry as the assembler
    // adds the elements' entries there: the same H, solves and driven columns.
    double* storage = structured.begin_assembly();
    const std::vector<int>& destinations = structured.assembly_solver()->entry_destinations();
    for (int entry = 0; entry < static_cast<int>(tangent.nonZeros()); ++entry)
      storage[destinations[entry]] += tangent.valuePtr()[entry];
    structured.factorize_with_schur_assembled();
    const Eigen::MatrixXd h_assembled = structured.schur_complement();
    CHECK((h_assembled - h_general).norm() <= 1e-9 * h_general.norm());
    Eigen::VectorXd x_assembled = rhs;
    structured.solve(x_assembled);
    CHECK((x_assembled - x_general).norm() <= 1e-9 * x_general.norm());
    Eigen::VectorXd move = Eigen::VectorXd::Zero(tangent.rows()), product;
    for (int i = 0; i < driven_count; ++i) move[driven[i]] = 1e-3 * (i + 1);
    structured.multiply_driven_columns(move, product);
    const Eigen::VectorXd expected = tangent * move;
    CHECK((product - expected).norm() <= 1e-12 * expected.norm());
  }
}

TEST_CASE("a tire on the road without pressure, or one that cannot be inflated, is a model error saying why",
          "[spindle][vehicle]") {
  // Without pressure the tire is slack where it meets the road; the contact stiffness
  // scaled from it would fail with a message about the contact, not about the pressure.
  const auto road = [](double level) { return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level)); };
  TireParameters slack = macros::load_tire_parameters("tires.145SR12");
  slack.pressure = 0.0;
  CHECK_THROWS_WITH(TireOnRoad(slack, road, RoadContact{0.8}),
                    "parameter 'pressure' is 0 Pa: a tire on the road is inflated before it touches it; give a "
                    "pressure > 0");
  // A pressure no step size can inflate: the parameters are at fault, not the steps.
  TireParameters bursting = macros::load_tire_parameters("tires.145SR12");
  bursting.pressure = 1e300;
  CHECK_THROWS_WITH(TireOnRoad(bursting, road, RoadContact{0.8}),
                    Catch::StartsWith("the tire cannot be inflated on its hub with these parameters (") &&
                        Catch::EndsWith("); check the pressure and the stiffnesses"));
}
