// Modal analysis against closed forms: damped single DOFs (under- and overdamped), a
// two-mass chain with Rayleigh and with non-proportional damping, a mass on a spring and
// a ring seen from a turning frame (Bryan's factor), the rigid-body test of a beam whose
// shear stiffness dwarfs its axial one, and the degenerate pairs of an unsymmetric
// tangent (the inflated tire on a held hub).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

#include "core/assembler.hpp"
#include "elements/beam_mesh.hpp"
#include "elements/point_mass.hpp"
#include "io/hdf5_file.hpp"
#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "solvers/modal.hpp"
#include "test_support.hpp"
#include "tire/tire_builder.hpp"
#include "tirefe/test_paths.hpp"

using namespace tirefe;

namespace {

constexpr double kPi = 3.14159265358979323846;
using Complex = std::complex<double>;

/// A spring k and a dashpot c between the u_x of two nodes, massless.
struct AxialLink : KernelShape<2> {
  double stiffness = 0.0, damping = 0.0;

  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&, History&,
                Vector& residual, Matrix* tangent) const {
    const IntegratorFactors& f = context.factors;
    const double force = f.force_stiffness * stiffness * (local.displacement[3] - local.displacement[0]) +
                         f.force_damping * damping * (local.velocity[3] - local.velocity[0]);
    residual.setZero();
    residual[0] = -force;
    residual[3] = force;
    if (!tangent) return;
    const double k = f.tangent_stiffness * stiffness + f.tangent_damping * damping;
    tangent->setZero();
    (*tangent)(0, 0) = (*tangent)(3, 3) = k;
    (*tangent)(0, 3) = (*tangent)(3, 0) = -k;
  }
  ElementEnergy energy(const LocalState<kDofs>&, const History&) const { return {}; }
};

/// Grounded springs with a one-way coupling (an unsymmetric K), unit mass on every component.
struct OneWaySpring : KernelShape<1> {
  Matrix stiffness;

  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&, History&,
                Vector& residual, Matrix* tangent) const {
    const IntegratorFactors& f = context.factors;
    residual = f.force_stiffness * stiffness * local.displacement + f.force_mass * local.acceleration;
    if (tangent) *tangent = f.tangent_stiffness * stiffness + f.tangent_mass * Matrix::Identity();
  }
  ElementEnergy energy(const LocalState<kDofs>&, const History&) const { return {}; }
};

/// Masses on the u_x of nodes 1..n, linked by springs and dashpots to each other and node 0
/// (held): ground -k1,c1- m1 -k2,c2- m2 ..., each mass also on a dashpot to ground. Only u_x moves.
struct Chain {
  Model model;
  Chain(const std::vector<double>& masses, const std::vector<double>& stiffnesses,
        const std::vector<double>& link_damping, const std::vector<double>& ground_damping) {
    for (size_t i = 0; i <= masses.size(); ++i) model.mesh().add_node({static_cast<double>(i), 0.0});
    auto& links = model.add_block<AxialLink>("links");
    auto& points = model.add_block<NodalSpringMass>("masses");
    for (size_t i = 0; i < masses.size(); ++i) {
      AxialLink link;
      link.stiffness = stiffnesses[i];
      link.damping = link_damping[i];
      links.add({static_cast<int>(i), static_cast<int>(i + 1)}, link);
      SpringMassProperties point;
      point.mass = masses[i];
      point.damping = {ground_damping[i], 0.0, 0.0};
      points.add({static_cast<int>(i + 1)}, NodalSpringMass(point));
    }
    for (int node = 0; node <= static_cast<int>(masses.size()); ++node) {
      model.fix(node, kUy);
      model.fix(node, kRz);
    }
    model.fix(0, kUx);
  }
};

/// MAC of two shapes: 1 for parallel, 0 for orthogonal ones.
double mac(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double cross = a.dot(b);
  return cross * cross / (a.squaredNorm() * b.squaredNorm());
}

/// A 145 SR-12 inflated on a held hub (spindle fixed in all three DOFs).
struct HeldHubTire {
  Model model;
  Tire tire;
  std::unique_ptr<Analysis> analysis;
  explicit HeldHubTire(const std::string& module) {
    tire = build_tire(model, macros::load_tire_parameters(module), LoadFunction::linear());
    for (int c = 0; c < kDofsPerNode; ++c) model.fix(tire.spindle, c);
    analysis = std::make_unique<Analysis>(model);
    analysis->set_time_step(0.25);
    analysis->advance(1.0);
  }
};

/// M over the free equations at a state, and a shape restricted to them.
Eigen::MatrixXd free_mass(Model& model, const State& state) {
  Assembler assembler(model);
  assembler.update_pattern();
  EvaluationContext context;
  context.factors = {0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  Eigen::VectorXd residual;
  assembler.assemble(context, state, residual);
  model.revert_history();
  return Eigen::MatrixXd(assembler.tangent());
}
Eigen::VectorXd free_part(const Model& model, const Eigen::VectorXd& shape) {
  const DofMap& dofs = model.dof_map();
  Eigen::VectorXd free(dofs.equation_count());
  for (int equation = 0; equation < dofs.equation_count(); ++equation) free[equation] = shape[dofs.dof(equation)];
  return free;
}

}  // namespace

// ---- damped modes against closed forms ---------------------------------------------

TEST_CASE("damped single DOF: omega_d = omega_n sqrt(1 - zeta^2), zeta = c / (2 sqrt(k m))", "[modal][damped]") {
  const double mass = 2.5, stiffness = 4.0e4, damping = 60.0;
  Chain oscillator({mass}, {stiffness}, {damping}, {0.0});
  const DampedModalResult modes = damped_modal_analysis(oscillator.model, State{}, 3);
  // One DOF, one complex pair: one mode however many are asked for.
  REQUIRE(modes.frequencies_hz.size() == 1);
  const double natural = std::sqrt(stiffness / mass), zeta = damping / (2.0 * std::sqrt(stiffness * mass));
  CHECK_FALSE(modes.rigid_body[0]);
  CHECK(modes.natural_frequencies_hz[0] == Approx(natural / (2 * kPi)).epsilon(1e-10));
  CHECK(modes.damping_ratios[0] == Approx(zeta).epsilon(1e-10));
  CHECK(modes.frequencies_hz[0] == Approx(natural * std::sqrt(1.0 - zeta * zeta) / (2 * kPi)).epsilon(1e-10));
  CHECK(modes.roots[0].real() == Approx(-zeta * natural).epsilon(1e-10));
  // phi^H M phi = 1 with phi real positive; the held node takes -(k + lambda c) phi.
  const Complex shape = modes.shapes(dof_index(1, kUx), 0);
  CHECK(shape.real() == Approx(1.0 / std::sqrt(mass)).epsilon(1e-12));
  CHECK(shape.imag() == 0.0);
  const Complex reaction = -(stiffness + modes.roots[0] * damping) * shape;
  CHECK(std::abs(modes.reactions(dof_index(0, kUx), 0) - reaction) <= 1e-8 * std::abs(reaction));
  CHECK(modes.reactions(dof_index(1, kUx), 0) == Complex(0.0));

  SECTION("overdamped: two real roots -omega_n (zeta +- sqrt(zeta^2 - 1))") {
    const double heavy = 2.0 * 2.0 * std::sqrt(stiffness * mass);  // zeta = 2
    Chain sluggish({mass}, {stiffness}, {heavy}, {0.0});
    const DampedModalResult roots = damped_modal_analysis(sluggish.model, State{}, 3);
    REQUIRE(roots.frequencies_hz.size() == 2);
    const double slow = -natural * (2.0 - std::sqrt(3.0)), fast = -natural * (2.0 + std::sqrt(3.0));
    CHECK(roots.roots[0].real() == Approx(slow).epsilon(1e-10));
    CHECK(roots.roots[1].real() == Approx(fast).epsilon(1e-10));
    for (int i = 0; i < 2; ++i) {
      CHECK(roots.roots[i].imag() == 0.0);
      CHECK(roots.frequencies_hz[i] == 0.0);
      CHECK(roots.damping_ratios[i] == 1.0);  // -Re lambda / |lambda| of a decaying real root
      CHECK(roots.natural_frequencies_hz[i] == Approx(std::abs(roots.roots[i].real()) / (2 * kPi)).epsilon(1e-14));
    }
    // The pair's product and sum give back omega_n and zeta = 2.
    const double product = roots.roots[0].real() * roots.roots[1].real();
    CHECK(std::sqrt(product) == Approx(natural).epsilon(1e-10));
    CHECK(-(roots.roots[0].real() + roots.roots[1].real()) / (2.0 * std::sqrt(product)) == Approx(2.0).epsilon(1e-10));
  }
}

TEST_CASE("damped two-mass chain: Rayleigh damping and a non-proportional dashpot", "[modal][damped]") {
  const double m1 = 3.0, m2 = 1.5, k1 = 2.0e4, k2 = 1.0e4;
  // Undamped: m1 m2 w^4 - (m1 k2 + m2 (k1 + k2)) w^2 + k1 k2 = 0.
  const double b = m1 * k2 + m2 * (k1 + k2), root = std::sqrt(b * b - 4.0 * m1 * m2 * k1 * k2);
  const double omega[2] = {std::sqrt((b - root) / (2.0 * m1 * m2)), std::sqrt((b + root) / (2.0 * m1 * m2))};

  SECTION("C = a M + b K: zeta_i = a / (2 omega_i) + b omega_i / 2, the undamped shapes") {
    const double alpha = 4.0, beta = 2.0e-4;
    Chain chain({m1, m2}, {k1, k2}, {beta * k1, beta * k2}, {alpha * m1, alpha * m2});
    const DampedModalResult modes = damped_modal_analysis(chain.model, State{}, 2);
    REQUIRE(modes.frequencies_hz.size() == 2);
    for (int i = 0; i < 2; ++i) {
      const double zeta = alpha / (2.0 * omega[i]) + beta * omega[i] / 2.0;
      INFO("mode " << i + 1 << ": zeta " << modes.damping_ratios[i] << ", expected " << zeta);
      CHECK(modes.natural_frequencies_hz[i] == Approx(omega[i] / (2 * kPi)).epsilon(1e-10));
      CHECK(modes.damping_ratios[i] == Approx(zeta).epsilon(1e-10));
      CHECK(modes.frequencies_hz[i] == Approx(omega[i] * std::sqrt(1.0 - zeta * zeta) / (2 * kPi)).epsilon(1e-10));
      // Proportional damping keeps the real undamped shape: (k1 + k2 - w^2 m1) phi_1 = k2 phi_2.
      const Complex first = modes.shapes(dof_index(1, kUx), i), second = modes.shapes(dof_index(2, kUx), i);
      CHECK(std::abs(first.imag()) + std::abs(second.imag()) <= 1e-10 * std::abs(first));
      CHECK((second / first).real() == Approx((k1 + k2 - omega[i] * omega[i] * m1) / k2).epsilon(1e-10));
      // phi^H M phi = 1.
      CHECK(m1 * std::norm(first) + m2 * std::norm(second) == Approx(1.0).epsilon(1e-12));
    }
  }
  SECTION("one dashpot c1 beside k1: the roots of the characteristic quartic") {
    // det(lambda^2 M + lambda C + K) = m1 m2 l^4 + c1 m2 l^3 + b l^2 + c1 k2 l + k1 k2.
    const double c1 = 150.0;
    Chain chain({m1, m2}, {k1, k2}, {c1, 0.0}, {0.0, 0.0});
    const DampedModalResult modes = damped_modal_analysis(chain.model, State{}, 2);
    REQUIRE(modes.frequencies_hz.size() == 2);
    const double coefficients[5] = {k1 * k2, c1 * k2, b, c1 * m2, m1 * m2};
    double sum = 0.0, product = 1.0;
    for (int i = 0; i < 2; ++i) {
      const Complex lambda = modes.roots[i];
      Complex value = 0.0, slope = 0.0;
      for (int p = 4; p >= 0; --p) {
        slope = slope * lambda + value;
        value = value * lambda + coefficients[p];
      }
      // A Newton step on the quartic moves the root by less than 1e-12 of itself.
      INFO("root " << lambda << ", Newton step " << value / slope);
      CHECK(lambda.imag() > 0.0);
      CHECK(std::abs(value / slope) <= 1e-12 * std::abs(lambda));
      CHECK(modes.damping_ratios[i] == Approx(-lambda.real() / std::abs(lambda)).epsilon(1e-14));
      sum += 2.0 * lambda.real();
      product *= std::norm(lambda);
    }
    // The two pairs are the quartic's four roots (Vieta): they add to -c1 / m1 and multiply to k1 k2 / (m1 m2).
    CHECK(sum == Approx(-c1 / m1).epsilon(1e-10));
    CHECK(product == Approx(k1 * k2 / (m1 * m2)).epsilon(1e-10));
    // Non-proportional damping: complex shapes, the held node takes -(k1 + lambda c1) phi_1.
    for (int i = 0; i < 2; ++i) {
      const Complex first = modes.shapes(dof_index(1, kUx), i), second = modes.shapes(dof_index(2, kUx), i);
      CHECK(std::abs(first.imag()) + std::abs(second.imag()) > 1e-3 * std::abs(first));
      const Complex reaction = -(k1 + modes.roots[i] * c1) * first;
      CHECK(std::abs(modes.reactions(dof_index(0, kUx), i) - reaction) <= 1e-8 * std::abs(reaction));
    }
  }
}

TEST_CASE("shift-invert Krylov gives the dense solver's modes: damped chain, damped inflated tire", "[modal][damped]") {
  DampedModalSettings krylov, dense;
  krylov.solver = DampedSolver::ShiftInvert;
  dense.solver = DampedSolver::Dense;
  SECTION("two-mass chain with one dashpot (the Krylov space is the whole space)") {
    Chain chain({3.0, 1.5}, {2.0e4, 1.0e4}, {150.0, 0.0}, {0.0, 0.0});
    const DampedModalResult a = damped_modal_analysis(chain.model, State{}, 2, krylov);
    const DampedModalResult b = damped_modal_analysis(chain.model, State{}, 2, dense);
    CHECK(a.shift_invert);
    CHECK_FALSE(b.shift_invert);
    REQUIRE(a.roots.size() == 2);
    for (int i = 0; i < 2; ++i) CHECK(std::abs(a.roots[i] - b.roots[i]) <= 1e-12 * std::abs(b.roots[i]));
  }
  SECTION("the paper's tire inflated on a held hub, sidewall dampers: a degenerate pair found twice") {
    HeldHubTire inflated("tires.145SR12");
    const Tire& tire = inflated.tire;
    const DampedModalResult a = damped_modal_analysis(*inflated.analysis, 8, krylov);
    const DampedModalResult b = damped_modal_analysis(*inflated.analysis, 8, dense);
    CHECK(a.shift_invert);
    REQUIRE(a.roots.size() == 8);
    REQUIRE(b.roots.size() == 8);
    // Axle force |F|^2 summed over each group of equal roots (a degenerate pair comes in
    // any basis of its plane), against the largest.
    const auto axle = [&](const DampedModalResult& modes, int i) {
      return modes.reactions.block<2, 1>(dof_index(tire.spindle, kUx), i).squaredNorm();
    };
    double largest = 0.0;
    for (int i = 0; i < 8; ++i) largest = std::max(largest, axle(b, i));
    int pairs = 0;
    double group_a = 0.0, group_b = 0.0;
    for (int i = 0; i < 8; ++i) {
      INFO("mode " << i + 1 << ": " << a.frequencies_hz[i] << " Hz, zeta " << a.damping_ratios[i] << "; dense "
                   << b.frequencies_hz[i] << " Hz, zeta " << b.damping_ratios[i]);
      CHECK(std::abs(a.roots[i] - b.roots[i]) <= 1e-9 * std::abs(b.roots[i]));
      const bool twin = i > 0 && std::abs(a.roots[i] - a.roots[i - 1]) <= 1e-8 * std::abs(a.roots[i]);
      if (!twin) group_a = group_b = 0.0;
      pairs += twin ? 1 : 0;
      group_a += axle(a, i);
      group_b += axle(b, i);
      const bool group_ends = i == 7 || std::abs(a.roots[i + 1] - a.roots[i]) > 1e-8 * std::abs(a.roots[i]);
      if (group_ends) CHECK(std::abs(group_a - group_b) <= 1e-8 * largest);
    }
    // The belt's n = 1 translation and the n >= 2 bending come in degenerate pairs.
    CHECK(pairs >= 2);
  }
  SECTION("a K whose symmetric part is indefinite (friction, follower loads)") {
    // K = k [1 3 0; 0 2 0; 0 0 3]: eigenvalues k, 2k, 3k, symmetric part indefinite.
    Model model;
    model.mesh().add_node({0.0, 0.0});
    OneWaySpring spring;
    spring.stiffness << 1.0, 3.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 3.0;
    spring.stiffness *= 400.0;
    model.add_block<OneWaySpring>("spring").add({0}, spring);
    const DampedModalResult modes = damped_modal_analysis(model, State{}, 3, krylov);
    CHECK(modes.shift_invert);
    REQUIRE(modes.roots.size() == 3);
    for (int i = 0; i < 3; ++i)
      CHECK(modes.frequencies_hz[i] == Approx(20.0 * std::sqrt(i + 1.0) / (2 * kPi)).epsilon(1e-12));
  }
  SECTION("rigid-body modes (a singular K) go to the dense solver") {
    Model model;
    BeamSection section;
    section.axial_stiffness = section.shear_stiffness = 1e4;
    section.bending_stiffness = section.mass_per_length = 1.0;
    section.rotary_inertia_per_length = 1e-4;
    add_beam_line(model, "beam", {0.0, 0.0}, {1.0, 0.0}, 10, section);
    const DampedModalResult modes = damped_modal_analysis(model, State{}, 5, krylov);
    CHECK_FALSE(modes.shift_invert);
    for (int i = 0; i < 5; ++i) CHECK(modes.rigid_body[i] == (i < 3));
  }
}

TEST_CASE("mass on an isotropic spring in a turning frame: omega_0 - Omega and omega_0 + Omega", "[modal][damped]") {
  const double mass = 2.0, stiffness = 800.0, omega0 = std::sqrt(stiffness / mass);
  Model model;
  model.mesh().add_node({0.3, -0.2});
  SpringMassProperties point;
  point.mass = mass;
  point.stiffness = {stiffness, stiffness, 0.0};
  model.add_block<NodalSpringMass>("point").add({0}, NodalSpringMass(point));
  model.fix(0, kRz);
  for (double spin : {0.0, 5.0, 30.0}) {
    DampedModalSettings settings;
    settings.spin_rate = spin;
    const DampedModalResult modes = damped_modal_analysis(model, State{}, 2, settings);
    REQUIRE(modes.frequencies_hz.size() == 2);
    // m (q'' + 2 Omega J q' - Omega^2 q) + k q = 0 has the roots i (+-omega_0 -+ Omega).
    const double slow = std::abs(omega0 - spin), fast = omega0 + spin;
    INFO("Omega = " << spin << ": " << modes.frequencies_hz[0] << ", " << modes.frequencies_hz[1] << " Hz");
    CHECK(modes.frequencies_hz[0] == Approx(slow / (2 * kPi)).epsilon(1e-12));
    CHECK(modes.frequencies_hz[1] == Approx(fast / (2 * kPi)).epsilon(1e-12));
    for (int i = 0; i < 2; ++i) CHECK(std::abs(modes.damping_ratios[i]) <= 1e-13);
  }
  SECTION("a node with one translation held cannot turn") {
    model.fix(0, kUy);
    DampedModalSettings settings;
    settings.spin_rate = 1.0;
    try {
      damped_modal_analysis(model, State{}, 2, settings);
      FAIL("a half-held node should be refused");
    } catch (const ModelError& error) {
      CHECK(std::string(error.what()).find("node 1 has u_y held and u_x free") != std::string::npos);
    }
  }
}

namespace {

/// A free ring of 72 beams (radius 1, EI = 1, rho A = 1, EA R^2 / EI = 1e5) pre-stressed by
/// its centrifugal load at a spin Omega: radial nodal loads Omega^2 (M r)_i, the
/// consistent mass of the linear beams, solved statically with two tangential supports
/// that are released afterwards. The hoop tension is rho A Omega^2 R^2.
struct SpinningRing {
  static constexpr int kElements = 72;
  Model model;
  std::vector<int> nodes;
  State state;

  explicit SpinningRing(double spin) {
    BeamSection section;
    section.bending_stiffness = 1.0;
    section.axial_stiffness = section.shear_stiffness = 1e5;
    section.mass_per_length = 1.0;
    section.rotary_inertia_per_length = 1e-5;  // rho I = rho A I / A
    nodes = add_beam_ring(model, "ring", {0.0, 0.0}, 1.0, kElements, section);
    const double step = 2.0 * kPi / kElements, chord = 2.0 * std::sin(step / 2.0);
    const double load = spin * spin * chord * (2.0 + std::cos(step)) / 3.0;  // rho A l (4 r_i + r_i-1 + r_i+1) / 6
    for (int k = 0; k < kElements; ++k) {
      model.add_nodal_load(nodes[k], kUx, load * std::cos(k * step), Model::kRampLoadFunction);
      model.add_nodal_load(nodes[k], kUy, load * std::sin(k * step), Model::kRampLoadFunction);
    }
    model.fix(nodes[0], kUy);
    model.fix(nodes[kElements / 4], kUx);
    Analysis analysis(model);
    analysis.advance(1.0);
    state = analysis.state();
    model.release(nodes[0], kUy);
    model.release(nodes[kElements / 4], kUx);
  }
};

}  // namespace

TEST_CASE("spinning ring in the turning frame: its bending pairs split by Bryan's factor 2 n / (n^2 + 1)",
          "[modal][damped]") {
  // A thin inextensible ring spinning at Omega, seen from the turning frame: the n-th
  // bending pair splits into waves at omega_n -+ 2 n Omega / (n^2 + 1) (Bryan 1890):
  //   (omega_+ - omega_-) / (2 Omega) = 2 n / (n^2 + 1), 0.8 at n = 2, 0.6 at n = 3.
  // The rigid-body rotation stays a (double) root at 0, balanced by the hoop tension; the
  // two translations turn at Omega.
  const double omega2 = 6.0 / std::sqrt(5.0);  // n = 2 of an inextensible ring, rad/s
  double split_at_rest = 1.0;
  for (double spin : {0.0, 1e-2 * omega2}) {
    SpinningRing ring(spin);
    DampedModalSettings settings;
    settings.spin_rate = spin;
    const DampedModalResult modes = damped_modal_analysis(ring.model, ring.state, 8, settings);
    REQUIRE(modes.frequencies_hz.size() == 8);
    INFO("Omega = " << spin);
    // Three rigid-body modes, each once: at rest six roots at 0; turning, a double root 0
    // (the rotation) and i Omega (a circular translation: both translations).
    for (int i = 0; i < 8; ++i) CHECK(modes.rigid_body[i] == (i < 3));
    // The modes above the rigid ones and the translations (at Omega): n = 2 and n = 3 pairs.
    std::vector<double> bending;
    for (size_t i = 0; i < modes.frequencies_hz.size(); ++i)
      if (!modes.rigid_body[i] && 2 * kPi * modes.frequencies_hz[i] > 0.5 * omega2)
        bending.push_back(2 * kPi * modes.frequencies_hz[i]);
    REQUIRE(bending.size() >= 4);
    for (int n = 2; n <= 3; ++n) {
      const double lower = bending[2 * (n - 2)], upper = bending[2 * (n - 2) + 1];
      const double bryan = 2.0 * n / (n * n + 1.0);
      INFO("n = " << n << ": " << lower << " and " << upper << " rad/s");
      // No damping: zeta = 0 to the round-off of the first-order form (about eps |K~| / omega^2).
      for (size_t i = 0; i < modes.frequencies_hz.size(); ++i) CHECK(std::abs(modes.damping_ratios[i]) <= 1e-6);
      if (spin == 0.0) {
        CHECK(upper == Approx(lower).epsilon(1e-6));
        if (n == 2) split_at_rest = upper - lower;
        continue;
      }
      // The linear beams' shapes move the factor by about (n h)^2 / 25, h = 2 pi / 72
      // (with 96 beams 6.5e-4 at n = 2 and 2.3e-3 at n = 3, a quarter of that with 192).
      const double h = 2.0 * kPi / SpinningRing::kElements;
      CHECK((upper - lower) / (2.0 * spin) == Approx(bryan).epsilon(n * n * h * h / 10.0));
    }
  }
  CHECK(split_at_rest <= 1e-6 * omega2);
}

TEST_CASE("free-free beam with GA / EA = 1e8: exactly three rigid-body modes, and the axial mode", "[modal]") {
  // Linear elements with consistent mass sample the bar's first free-free mode
  // cos(pi x / L) exactly, at omega_h = (c / h) sqrt(6 (1 - cos k h) / (2 + cos k h)),
  // c = sqrt(EA / rhoA), k = pi / L, h = L / n; omega_h tends to omega = c k as (k h)^2 / 24.
  // A stubby section (radius of gyration 0.3 L, rho I / rho A = EI / EA) puts the first
  // bending mode near the axial one; a shear stiffness 1e8 above EA dominates the norm of K.
  const double length = 1.0, axial = 1.0, mass_per_length = 1.0, gyration = 0.3 * length;
  const int elements = 40;
  BeamSection section;
  section.axial_stiffness = axial;
  section.shear_stiffness = 1e8 * axial;
  section.bending_stiffness = axial * gyration * gyration;
  section.mass_per_length = mass_per_length;
  section.rotary_inertia_per_length = mass_per_length * gyration * gyration;
  Model model;
  const std::vector<int> nodes = add_beam_line(model, "beam", {0.0, 0.0}, {length, 0.0}, elements, section);
  const ModalResult modes = modal_analysis(model, State{}, 8);

  const double k = kPi / length, h = length / elements, wave_speed = std::sqrt(axial / mass_per_length);
  const double discrete = wave_speed / h * std::sqrt(6.0 * (1.0 - std::cos(k * h)) / (2.0 + std::cos(k * h)));
  int rigid = 0, axial_mode = -1;
  for (int m = 0; m < 8; ++m) {
    rigid += modes.rigid_body[m] ? 1 : 0;
    // The axial mode moves u_x; the dense solve mixes in the bending mode 20 % below it by
    // about (round-off of the largest omega^2, 1e11) / (their gap) = 1e-5.
    double along = 0.0, across = 0.0;
    for (int node : nodes) {
      along = std::max(along, std::abs(modes.shapes(dof_index(node, kUx), m)));
      across = std::max(
          {across, std::abs(modes.shapes(dof_index(node, kUy), m)), std::abs(modes.shapes(dof_index(node, kRz), m))});
    }
    if (axial_mode < 0 && !modes.rigid_body[m] && across <= 1e-3 * along) axial_mode = m;
  }
  INFO("frequencies " << modes.frequencies_hz[3] << ", " << modes.frequencies_hz[4] << ", " << modes.frequencies_hz[5]
                      << " Hz; axial: discrete " << discrete / (2 * kPi) << ", bar " << k * wave_speed / (2 * kPi));
  CHECK(rigid == 3);
  for (int i = 0; i < 3; ++i) CHECK(modes.rigid_body[i]);
  REQUIRE(axial_mode >= 3);
  CHECK(modes.frequencies_hz[axial_mode] == Approx(discrete / (2 * kPi)).epsilon(1e-11));
  CHECK(modes.frequencies_hz[axial_mode] == Approx(k * wave_speed / (2 * kPi)).epsilon(1e-3));

  SECTION("the damped analysis (of this undamped beam) agrees") {
    const DampedModalResult damped = damped_modal_analysis(model, State{}, 8);
    REQUIRE(damped.frequencies_hz.size() == 8);
    // Six roots at 0, each rigid-body shape once.
    for (int i = 0; i < 8; ++i) CHECK(damped.rigid_body[i] == (i < 3));
    for (int i = 3; i < 8; ++i) {
      INFO("mode " << i + 1 << ": " << damped.frequencies_hz[i] << " Hz, undamped " << modes.frequencies_hz[i]);
      // The first-order form resolves omega to about eps |K~| / omega: up to 4e-6 relative here.
      CHECK(damped.frequencies_hz[i] == Approx(modes.frequencies_hz[i]).epsilon(1e-5));
    }
  }
}

TEST_CASE("inflated tire on a held hub (unsymmetric tangent): the n = 1 pair has two shapes and two axle forces",
          "[modal][tire]") {
  HeldHubTire inflated("tires.145SR12");
  Model& model = inflated.model;
  const Tire& tire = inflated.tire;
  Analysis& analysis = *inflated.analysis;
  const ModalResult modes = modal_analysis(analysis, 8);
  REQUIRE_FALSE(modes.symmetric);  // follower pressure and the sidewall shear

  // The belt's translation along x and y (n = 1): the two modes that correlate best with them.
  Eigen::VectorXd along_x = Eigen::VectorXd::Zero(model.mesh().dof_count()), along_y = along_x;
  for (int node : tire.tread_nodes) along_x[dof_index(node, kUx)] = along_y[dof_index(node, kUy)] = 1.0;
  std::vector<int> pair;
  for (int m = 0; m < static_cast<int>(modes.frequencies_hz.size()); ++m)
    if (mac(modes.shapes.col(m), along_x) + mac(modes.shapes.col(m), along_y) > 0.5) pair.push_back(m);
  REQUIRE(pair.size() == 2);
  const Eigen::VectorXd first = modes.shapes.col(pair[0]), second = modes.shapes.col(pair[1]);
  INFO("n = 1 pair: modes " << pair[0] + 1 << " and " << pair[1] + 1 << " at " << modes.frequencies_hz[pair[0]] << " / "
                            << modes.frequencies_hz[pair[1]] << " Hz, MAC between them " << mac(first, second));
  CHECK(modes.frequencies_hz[pair[1]] == Approx(modes.frequencies_hz[pair[0]]).epsilon(1e-6));
  // M-orthonormal: two distinct shapes spanning the pair.
  const Eigen::MatrixXd mass = free_mass(model, analysis.state());
  const Eigen::VectorXd a = free_part(model, first), b = free_part(model, second);
  CHECK(a.dot(mass * a) == Approx(1.0).epsilon(1e-10));
  CHECK(b.dot(mass * b) == Approx(1.0).epsilon(1e-10));
  CHECK(std::abs(a.dot(mass * b)) <= 1e-10);
  // Axle forces: perpendicular and of equal size, so the pair holds one mode pushing
  // the axle along x and one along y in some orientation of the pair's plane.
  const Eigen::Vector2d force_a = modes.reactions.block<2, 1>(dof_index(tire.spindle, kUx), pair[0]);
  const Eigen::Vector2d force_b = modes.reactions.block<2, 1>(dof_index(tire.spindle, kUx), pair[1]);
  INFO("axle forces (" << force_a.transpose() << ") and (" << force_b.transpose() << ")");
  CHECK(force_a.norm() > 0.0);
  CHECK(std::abs(force_a.dot(force_b)) <= 1e-6 * force_a.norm() * force_b.norm());
  CHECK(force_b.norm() == Approx(force_a.norm()).epsilon(1e-6));
}

TEST_CASE("model:modal{ damped = true }: the deck's lists and /modes/<label>", "[modal][damped][macros]") {
  // A clamped cantilever with curvature damping c_kappa = beta EI: its bending modes, whose
  // energy is almost all bending (EA L^2 / EI = 1e6), have zeta = beta omega / 2.
  testing::TempDir folder;
  const std::string deck = folder.write("cantilever.lua", R"(
local beta, EI = 1e-3, 10.0
local model = tirefe.model{ title = "damped cantilever" }
local nodes = {}
for i = 0, 20 do nodes[#nodes + 1] = model:node{ x = 0.05 * i, y = 0 } end
model:section{ name = "beam", EA = 1e7, GA = 1e7, EI = EI, rhoA = 2.0, rhoI = 2e-6, curvature_damping = beta * EI }
model:beam{ section = "beam", nodes = nodes }
model:fix{ node = nodes[1] }
model:output{ file = "cantilever.h5" }
local undamped = model:modal{ modes = 3, label = "plain" }
local f, axle, zeta = model:modal{ modes = 3, damped = true, label = "damped", reaction_node = nodes[1] }
tirefe.check{ name = "three modes", value = #f + #axle + #zeta, expected = 9, tolerance = 0 }
for i = 1, 2 do
  local omega = 2 * math.pi * undamped[i]
  tirefe.check{ name = "zeta = beta omega / 2", value = zeta[i], expected = beta * omega / 2, relative = 1e-3 }
  tirefe.check{ name = "damped frequency", value = f[i], expected = undamped[i] * math.sqrt(1 - zeta[i] ^ 2),
                relative = 1e-3 }
  tirefe.check{ name = "the clamp takes a shear force", value = axle[i][2] > 0 and 1 or 0, expected = 1, tolerance = 0 }
end
local _, none, zeta_spun = model:modal{ modes = 3, damped = true, spin_rate = 2.0, label = "turning" }
tirefe.check{ name = "no reaction_node: nil", value = none == nil and 1 or 0, expected = 1, tolerance = 0 }
)");
  const std::string command = std::string(TIREFE_BINARY) + " " + deck + " --quiet --output-dir " + folder.path() +
                              " > " + folder.path("log.txt") + " 2>&1";
  const int status = std::system(command.c_str());
  INFO("log: " << std::ifstream(folder.path("log.txt")).rdbuf());
  REQUIRE(status == 0);
  const io::Hdf5File file = io::Hdf5File::open_read_only(folder.path("cantilever.h5"));
  std::vector<hsize_t> real_shape, imaginary_shape;
  const std::vector<double> zeta = file.read_doubles("/modes/damped/damping_ratio");
  const std::vector<double> frequency = file.read_doubles("/modes/damped/frequency");
  const std::vector<double> natural = file.read_doubles("/modes/damped/natural_frequency");
  file.read_doubles("/modes/damped/shapes", &real_shape);
  file.read_doubles("/modes/damped/shapes_imag", &imaginary_shape);
  REQUIRE(zeta.size() == 3);
  CHECK(real_shape == imaginary_shape);
  CHECK(real_shape == std::vector<hsize_t>{3, 21 * 3});
  for (int i = 0; i < 3; ++i) {
    CHECK(zeta[i] > 0.0);
    CHECK(frequency[i] == Approx(natural[i] * std::sqrt(1.0 - zeta[i] * zeta[i])).epsilon(1e-12));
  }
  CHECK(file.read_double_attribute("/modes/turning", "spin_rate") == 2.0);
  CHECK(file.read_double_attribute("/modes/damped", "spin_rate") == 0.0);
  // The undamped group keeps its layout and has no damped datasets.
  CHECK(file.exists("/modes/plain/shapes"));
  CHECK_FALSE(file.exists("/modes/plain/damping_ratio"));
}
