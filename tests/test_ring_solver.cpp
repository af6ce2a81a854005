// The structured RingSolver against KLU and against dense linear algebra on the real
// 145 SR-12 tire, the paper's and the calibrated one with a tread layer (its contact nodes
// satellites of the belt nodes): solutions, the border Schur complement
// H = K_bb - K_bu K_uu^-1 K_ub and the condensed right-hand side f_b = R_b - K_bu K_uu^-1 R_u,
// with the spindle free, on a dead axle (ux, uy fixed) and fixed, and pressed on a road;
// patterns that do not fit are refused; whole analyses (quasi-static inflation, then
// Newmark steps) agree with both solvers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>
#include <random>
#include <string>

#include "core/assembler.hpp"
#include "contact/node_contact.hpp"
#include "elements/tread_beam.hpp"
#include "elements/tread_beam.hpp"
#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "solvers/ring_solver.hpp"
#include "tire/tire_builder.hpp"
#include "vehicle/tire_on_road.hpp"

using namespace tirefe;

namespace {

const char* const kSpindleCases[] = {"spindle free", "dead axle (ux, uy fixed)", "spindle fixed"};
const int kFixedComponents[] = {0, 2, 3};
// The paper's tire (a ring of belt nodes and the spindle) and the calibrated one.
const char* const kTires[] = {"tires.145SR12", "tires.145SR12_tread_layer"};

/// Hangs a new node 10 mm outside ring node 'host' on a short beam: a satellite of it.
int hang_satellite(Model& model, int host, const std::string& block = "hung") {
  const Eigen::Vector2d at = model.mesh().position(host) * 1.04;
  const int node = model.mesh().add_node(at);
  BeamSection section;  // about as stiff as the tread rubber under a node: 1e6 N/m
  section.axial_stiffness = 1e4;
  section.shear_stiffness = 1e4;
  section.bending_stiffness = 0.1;
  section.mass_per_length = 1.0;
  section.rotary_inertia_per_length = 1e-4;
  model.add_block<TreadBeam>(block).add({host, node}, TreadBeam(model.mesh().position(host), at, section));
  return node;
}

/// The tire with its spindle condensed, inflated quasi-statically with the hub held
/// (a free hub has rigid-body modes, quasi-statically), then the first 'fixed' spindle
/// components stay prescribed and the others are released.
struct InflatedTire {
  Model model;
  Tire tire;
  int satellite = -1;  // a node hung on tread node 30, if asked for
  std::unique_ptr<Analysis> analysis;

  InflatedTire(int fixed, bool ring_solver, const char* tire_set = kTires[0], bool satellite = false) {
    tire = build_tire(model, macros::load_tire_parameters(tire_set), LoadFunction::table({{0.0, 0.0}, {1.0, 1.0}}));
    if (satellite) {
      this->satellite = hang_satellite(model, tire.tread_nodes[30]);
      model.fix(this->satellite, kRz);  // its translations only, as a contact node's
    }
    model.condense_node(tire.spindle);
    for (int c = 0; c < kDofsPerNode; ++c) model.fix(tire.spindle, c);
    analysis = std::make_unique<Analysis>(model);
    if (ring_solver) analysis->use_ring_solver(tire.tread_nodes, {tire.spindle});
    analysis->set_time_step(0.25);
    analysis->advance(1.0);
    for (int c = fixed; c < kDofsPerNode; ++c) model.release(tire.spindle, c);
    analysis->assembler().update_pattern();
  }

  /// The tangent at the inflated state: Newmark's effective tangent for step h, or the static one (h = 0).
  const SparseMatrix& tangent(double h) {
    EvaluationContext context;
    context.time = analysis->state().time;
    if (h > 0.0) context.factors = {1.0, 1.0, 1.0, 1.0, 0.5 / (0.25 * h), 1.0 / (0.25 * h * h)};
    Eigen::VectorXd residual;
    analysis->assembler().assemble(context, analysis->state(), residual);
    model.revert_history();
    return analysis->assembler().tangent();
  }
};

/// A cantilever of kCantileverElements tread beams along x, clamped at node 0, its tip loaded down (ramped).
constexpr int kCantileverElements = 10;
void build_cantilever(Model& model) {
  BeamSection section;
  section.axial_stiffness = 1e6;
  section.shear_stiffness = 1e6;
  section.bending_stiffness = 10.0;
  for (int i = 0; i <= kCantileverElements; ++i) model.mesh().add_node({0.1 * i, 0.0});
  auto& beams = model.add_block<TreadBeam>("beam");
  for (int i = 0; i < kCantileverElements; ++i)
    beams.add({i, i + 1}, TreadBeam(model.mesh().position(i), model.mesh().position(i + 1), section));
  for (int c = 0; c < kDofsPerNode; ++c) model.fix(0, c);
  model.add_nodal_load(kCantileverElements, kUy, -50.0, Model::kRampLoadFunction);
}

double relative_difference(const Eigen::MatrixXd& value, const Eigen::MatrixXd& reference) {
  return (value - reference).norm() / reference.norm();
}

/// Large-deflection Newton steps of two copies of a model, one with KLU, one with the
/// RingSolver on 'ring' (no border): the same displacements.
void check_steps_against_klu(Model& klu_model, Model& ring_model, const std::vector<int>& ring) {
  Analysis klu_analysis(klu_model), ring_analysis(ring_model);
  ring_analysis.use_ring_solver(ring, {});
  for (Analysis* analysis : {&klu_analysis, &ring_analysis}) {
    analysis->set_time_step(0.25);
    analysis->advance(1.0);
  }
  const Eigen::VectorXd& reference = klu_analysis.state().displacement;
  CHECK(reference.norm() > 0.01);
  CHECK(relative_difference(ring_analysis.state().displacement, reference) <= 1e-9);
  CHECK(ring_analysis.linear_solver().factorization_count() >= 4);
}

Eigen::MatrixXd random_columns(int rows, int columns, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd values(rows, columns);
  for (int j = 0; j < columns; ++j)
    for (int i = 0; i < rows; ++i) values(i, j) = uniform(random);
  return values;
}

/// Solves with both solvers and checks the RingSolver against KLU.
void check_against_klu(RingSolver& ring, const SparseMatrix& matrix, double tolerance = 1e-10) {
  KluSolver klu;
  klu.analyze(matrix);
  klu.factorize(matrix);
  ring.analyze(matrix);
  ring.factorize(matrix);
  const Eigen::MatrixXd rhs = random_columns(static_cast<int>(matrix.rows()), 3, 7);
  Eigen::MatrixXd x_klu = rhs, x_ring = rhs;
  klu.solve(x_klu);
  ring.solve(x_ring);
  CHECK(relative_difference(x_ring, x_klu) <= tolerance);
  Eigen::VectorXd single = rhs.col(1);
  ring.solve(single);
  CHECK(relative_difference(single, x_klu.col(1)) <= tolerance);
  // And the residual of the ring solution itself.
  CHECK((matrix * x_ring - rhs).norm() <= 1e-10 * matrix.norm() * x_ring.norm());
}

/// H and f_b of a condensed spindle (its equations last) by dense linear algebra.
void check_border_against_dense(const RingSolver& ring, const SparseMatrix& matrix) {
  const int n = static_cast<int>(matrix.rows()), border = ring.border_size(), interior = n - border;
  for (int i = 0; i < border; ++i) REQUIRE(ring.border_equations()[i] == interior + i);
  const Eigen::MatrixXd dense = Eigen::MatrixXd(matrix);
  const Eigen::PartialPivLU<Eigen::MatrixXd> k_uu(dense.topLeftCorner(interior, interior));
  const Eigen::MatrixXd k_bu = dense.bottomLeftCorner(border, interior);
  const Eigen::MatrixXd schur =
      dense.bottomRightCorner(border, border) - k_bu * k_uu.solve(dense.topRightCorner(interior, border));
  const Eigen::VectorXd rhs = random_columns(n, 1, 11);
  Eigen::VectorXd condensed;
  ring.condense(rhs, condensed);
  REQUIRE(condensed.size() == border);
  REQUIRE(ring.border_schur_complement().rows() == border);
  REQUIRE(ring.border_schur_complement().cols() == border);
  if (border == 0) return;
  CHECK(relative_difference(ring.border_schur_complement(), schur) <= 1e-9);
  CHECK(relative_difference(condensed, rhs.tail(border) - k_bu * k_uu.solve(rhs.head(interior))) <= 1e-9);
}

/// solve_condensed() after condense(), its border right-hand side moved: the solution of the
/// right-hand side moved alike in its border rows (f_b = R_b - K_bu K_uu^-1 R_u).
void check_solve_condensed(const RingSolver& ring, const SparseMatrix& matrix) {
  const int n = static_cast<int>(matrix.rows());
  const Eigen::VectorXd rhs = random_columns(n, 1, 13);
  Eigen::VectorXd condensed, x(n), expected = rhs;
  ring.condense(rhs, condensed);
  for (int i = 0; i < ring.border_size(); ++i) {
    const double move = 0.25 * (i + 1);
    condensed[i] += move;
    expected[ring.border_equations()[i]] += move;
  }
  ring.solve_condensed(condensed, x);
  ring.solve(expected);
  CHECK(relative_difference(x, expected) <= 1e-12);
  CHECK_THROWS_AS(ring.solve_condensed(condensed, x), std::logic_error);  // one per condense()
}

}  // namespace

TEST_CASE("ring solver: solutions, spindle Schur complement and condensed rhs of the inflated tire", "[ring_solver]") {
  for (const char* tire_set : kTires)
    for (int c = 0; c < 3; ++c) {
      DYNAMIC_SECTION(tire_set << ", " << kSpindleCases[c]) {
        const int fixed = kFixedComponents[c];
        InflatedTire inflated(fixed, false, tire_set);
        const SparseMatrix& tangent = inflated.tangent(1e-4);
        const int border = kDofsPerNode - fixed;
        RingSolver ring(inflated.model.dof_map(), inflated.tire.tread_nodes, {inflated.tire.spindle});
        check_against_klu(ring, tangent);
        // The condensed spindle is numbered last: H's rows are the last 'border' equations.
        REQUIRE(ring.border_size() == border);
        check_border_against_dense(ring, tangent);
        check_solve_condensed(ring, tangent);

        // The partial factorisation alone gives the same H and f_b.
        RingSolver partial(inflated.model.dof_map(), inflated.tire.tread_nodes, {inflated.tire.spindle});
        partial.analyze(tangent);
        partial.factorize_interior(tangent);
        check_border_against_dense(partial, tangent);
        Eigen::VectorXd unsolvable = Eigen::VectorXd::Ones(tangent.rows());
        CHECK_THROWS_AS(partial.solve(unsolvable), std::logic_error);  // H is not factored
        Eigen::VectorXd condensed;
        partial.condense(unsolvable, condensed);
        CHECK_THROWS_AS(partial.solve_condensed(condensed, unsolvable), std::logic_error);

        // The static tangent where it is regular (hub fixed); any ring start and direction.
        if (fixed == 3) {
          const SparseMatrix& stiffness = inflated.tangent(0.0);
          check_against_klu(ring, stiffness);
          std::vector<int> turned(inflated.tire.tread_nodes.rbegin(), inflated.tire.tread_nodes.rend());
          std::rotate(turned.begin(), turned.begin() + 37, turned.end());
          RingSolver clockwise(inflated.model.dof_map(), turned, {inflated.tire.spindle});
          check_against_klu(clockwise, stiffness);
        }
      }
    }
}

TEST_CASE("ring solver: held border equations are taken out of the system; a held ring equation is refused",
          "[ring_solver]") {
  for (const char* tire_set : kTires) {
    INFO(tire_set);
    InflatedTire inflated(0, false, tire_set);  // spindle free: ux, uy, rz in the border
    const SparseMatrix& tangent = inflated.tangent(1e-4);
    const DofMap& dofs = inflated.model.dof_map();
    const int spindle = inflated.tire.spindle;
    const std::vector<int> held = {dofs.equation(dof_index(spindle, kUx)), dofs.equation(dof_index(spindle, kUy))};
    const RingSolver whole(dofs, inflated.tire.tread_nodes, {spindle});
    std::unique_ptr<RingSolver> holding = whole.holding(held);
    holding->analyze(tangent);
    holding->factorize(tangent);
    REQUIRE(holding->border_size() == 1);
    CHECK(holding->border_equations()[0] == dofs.equation(dof_index(spindle, kRz)));

    // Against dense linear algebra on the matrix without the held rows and columns.
    const int n = static_cast<int>(tangent.rows());
    std::vector<int> kept;
    for (int i = 0; i < n; ++i)
      if (std::find(held.begin(), held.end(), i) == held.end()) kept.push_back(i);
    const Eigen::MatrixXd dense = Eigen::MatrixXd(tangent);
    const Eigen::MatrixXd reduced = dense(kept, kept);
    const Eigen::VectorXd rhs = random_columns(n, 1, 17);
    Eigen::VectorXd x = rhs;
    holding->solve(x);
    const Eigen::VectorXd expected = reduced.partialPivLu().solve(Eigen::VectorXd(rhs(kept)));
    CHECK(relative_difference(x(kept), expected) <= 1e-10);
    for (int equation : held) CHECK(x[equation] == 0.0);

    // H onto rz alone: K_rr - K_ru K_uu^-1 K_ur with ux, uy held.
    const int rz = static_cast<int>(kept.size()) - 1;
    const Eigen::MatrixXd interior = reduced.topLeftCorner(rz, rz);
    const double schur =
        reduced(rz, rz) - reduced.row(rz).head(rz).dot(interior.partialPivLu().solve(reduced.col(rz).head(rz)));
    CHECK(holding->border_schur_complement()(0, 0) == Approx(schur).epsilon(1e-9));

    // Only border equations can be held.
    const int belt = dofs.equation(dof_index(inflated.tire.tread_nodes[5], kUy));
    std::unique_ptr<RingSolver> wrong = whole.holding({belt});
    CHECK_THROWS_WITH(wrong->analyze(tangent), Catch::Contains("is held but is no border equation"));
  }
}

TEST_CASE("ring solver: pivots of rows far smaller than the rest are judged against their own rows", "[ring_solver]") {
  // Rows of a ring node and of a satellite scaled by 1e-12: their pivots fall far below
  // kPivotTolerance times the matrix's largest entry, but not below their own rows', so
  // the matrix is as regular as before and solves as KLU solves it (and with a residual
  // as small).
  InflatedTire inflated(1, false, kTires[1], true);
  SparseMatrix scaled = inflated.tangent(1e-4);
  const DofMap& dofs = inflated.model.dof_map();
  std::vector<int> small_rows;
  for (int node : {inflated.tire.tread_nodes[10], inflated.satellite})
    for (int c = 0; c < kDofsPerNode; ++c) small_rows.push_back(dofs.equation(dof_index(node, c)));
  double largest = 0.0, largest_small = 0.0;
  for (int column = 0; column < scaled.outerSize(); ++column)
    for (SparseMatrix::InnerIterator entry(scaled, column); entry; ++entry) {
      const bool small = std::find(small_rows.begin(), small_rows.end(), entry.row()) != small_rows.end();
      if (small) entry.valueRef() *= 1e-12;
      double& bound = small ? largest_small : largest;
      bound = std::max(bound, std::abs(entry.value()));
    }
  CHECK(largest_small < 1e-11 * largest);  // every pivot of these rows is below the matrix's bound
  RingSolver ring(dofs, inflated.tire.tread_nodes, {inflated.tire.spindle});
  check_against_klu(ring, scaled, 1e-8);  // the scaling costs digits (KLU equilibrates rows first)
}

TEST_CASE("ring solver: the calibrated tire pressed on a road with friction, its tread contact on the ring's chords",
          "[ring_solver]") {
  // The tread contact couples a chord's two nodes (as the tread beam does), so the pressed
  // tire keeps the pattern of a ring and a border: TireOnRoad solves it with the RingSolver.
  TireOnRoad on_road(
      macros::load_tire_parameters(kTires[1]),
      [](double level) { return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level)); }, RoadContact{0.8});
  const double load = -on_road.press(0.015);
  CHECK(load > 1000.0);
  CHECK(summarize_contact(on_road.contact()).nodes_in_contact >= 5);
  REQUIRE(on_road.analysis().ring_solver() != nullptr);
  CHECK(on_road.analysis().linear_solver().factorization_count() >= 4);

  // The effective tangent with the contact stiffness, the spindle on a dead axle.
  Model& model = on_road.model();
  model.release(on_road.tire().spindle, kRz);
  Analysis& analysis = on_road.analysis();
  analysis.assembler().update_pattern();
  EvaluationContext context;
  context.time = analysis.state().time;
  const double h = 1e-4;
  context.factors = {1.0, 1.0, 1.0, 1.0, 0.5 / (0.25 * h), 1.0 / (0.25 * h * h)};
  Eigen::VectorXd residual;
  analysis.assembler().assemble(context, analysis.state(), residual);
  model.revert_history();
  const SparseMatrix& tangent = analysis.assembler().tangent();
  RingSolver ring(model.dof_map(), on_road.tire().tread_nodes, {on_road.tire().spindle});
  check_against_klu(ring, tangent);
  REQUIRE(ring.border_size() == 1);
  check_border_against_dense(ring, tangent);
}

TEST_CASE("ring solver: an uncondensed spindle and a two-node border give the same solutions and H", "[ring_solver]") {
  // Spindle numbered first (not condensed): H follows border_equations().
  Model model;
  const Tire tire = build_tire(model, macros::load_tire_parameters("tires.145SR12"), LoadFunction::linear());
  model.fix(tire.spindle, kUx);
  Analysis analysis(model);
  analysis.assembler().update_pattern();
  EvaluationContext context;
  const double h = 1e-3;
  context.factors = {1.0, 1.0, 1.0, 1.0, 0.5 / (0.25 * h), 1.0 / (0.25 * h * h)};
  State uninflated;
  uninflated.resize(model.mesh().dof_count());
  Eigen::VectorXd residual;
  analysis.assembler().assemble(context, uninflated, residual);
  const SparseMatrix& tangent = analysis.assembler().tangent();
  RingSolver ring(model.dof_map(), tire.tread_nodes, {tire.spindle});
  check_against_klu(ring, tangent);
  REQUIRE(ring.border_equations() == std::vector<int>{0, 1});

  // H by the dense route with the border equations permuted last.
  const int n = static_cast<int>(tangent.rows());
  const Eigen::MatrixXd dense = Eigen::MatrixXd(tangent);
  const Eigen::MatrixXd k_uu = dense.bottomRightCorner(n - 2, n - 2);
  const Eigen::MatrixXd schur =
      dense.topLeftCorner(2, 2) -
      dense.topRightCorner(2, n - 2) * k_uu.partialPivLu().solve(dense.bottomLeftCorner(n - 2, 2));
  CHECK(relative_difference(ring.border_schur_complement(), schur) <= 1e-9);

  // Spindle and tread node 10 as the border (width 9: the dynamic-size path); the ring
  // then skips node 10, whose neighbours are not coupled to each other, which is allowed.
  std::vector<int> ring_nodes = tire.tread_nodes;
  ring_nodes.erase(ring_nodes.begin() + 10);
  RingSolver wide(model.dof_map(), ring_nodes, {tire.spindle, tire.tread_nodes[10]});
  check_against_klu(wide, tangent);
  CHECK(wide.border_size() == 5);
}

TEST_CASE("ring solver: the tangent assembled straight into its blocks factors to the same numbers, bit for bit",
          "[ring_solver]") {
  // The same additions in the same order land in the blocks either way, so the factors,
  // H and the solutions are the same doubles; solving the sparse matrix's values copied
  // into the blocks is the reference.
  for (const char* tire_set : kTires) {
    INFO(tire_set);
    InflatedTire inflated(2, false, tire_set);  // a dead axle
    const double h = 1e-4;
    const SparseMatrix& tangent = inflated.tangent(h);
    RingSolver ring(inflated.model.dof_map(), inflated.tire.tread_nodes, {inflated.tire.spindle});
    ring.analyze(tangent);
    const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(tangent.rows(), 1.0, 2.0);
    ring.factorize(tangent);
    const Eigen::MatrixXd schur = ring.border_schur_complement();
    Eigen::VectorXd reference = rhs;
    ring.solve(reference);

    Assembler& assembler = inflated.analysis->assembler();
    EvaluationContext context;
    context.time = inflated.analysis->state().time;
    context.factors = {1.0, 1.0, 1.0, 1.0, 0.5 / (0.25 * h), 1.0 / (0.25 * h * h)};
    Eigen::VectorXd residual;
    CHECK_THROWS_WITH(
        assembler.assemble_into_solver(context, inflated.analysis->state(), residual, ring.begin_assembly()),
        Catch::Contains("not bound"));
    CHECK_THROWS_AS(assembler.bind_solver_layout({0, 1, 2}), std::logic_error);
    assembler.bind_solver_layout(ring.entry_destinations());
    assembler.assemble_into_solver(context, inflated.analysis->state(), residual, ring.begin_assembly());
    inflated.model.revert_history();
    Eigen::VectorXd x = rhs;
    CHECK_THROWS_AS(ring.solve(x), std::logic_error);  // the storage holds a tangent, not factors
    ring.factorize_assembled();
    CHECK_THROWS_AS(ring.factorize_assembled(), std::logic_error);  // factored in place: assemble again
    CHECK((ring.border_schur_complement() - schur).cwiseAbs().maxCoeff() == 0.0);
    ring.solve(x);
    CHECK((x - reference).cwiseAbs().maxCoeff() == 0.0);
    CHECK(reference.norm() > 0.0);
  }
}

TEST_CASE("ring solver: a cantilever is an open ring; in the wrong node order it is refused", "[ring_solver]") {
  auto build = [](Model& model) {
    build_cantilever(model);
    std::vector<int> nodes;
    for (int i = 0; i <= kCantileverElements; ++i) nodes.push_back(i);
    return nodes;
  };
  Model scrambled_model;
  const std::vector<int> nodes = build(scrambled_model);
  std::vector<int> scrambled;
  for (int i = 0; i < static_cast<int>(nodes.size()); i += 2) scrambled.push_back(i);
  for (int i = 1; i < static_cast<int>(nodes.size()); i += 2) scrambled.push_back(i);
  Analysis refused(scrambled_model);
  CHECK_THROWS_AS(refused.use_ring_solver(scrambled, {}), ModelError);
  CHECK_THROWS_WITH(refused.use_ring_solver(scrambled, {}), Catch::Contains("not ring neighbours"));
  CHECK(std::string(refused.linear_solver().name()) == "KLU");  // a refused solver is not installed

  // In node order: large-deflection Newton steps give KLU's answer (no border, the
  // clamped node 0 all padding).
  Model klu_model, ring_model;
  build(klu_model);
  build(ring_model);
  check_steps_against_klu(klu_model, ring_model, nodes);
}

TEST_CASE("ring solver: analyze() refuses tires that do not fit and misuse of the factors", "[ring_solver]") {
  Model model;
  const Tire tire = build_tire(model, macros::load_tire_parameters("tires.145SR12"), LoadFunction::linear());
  model.condense_node(tire.spindle);
  Analysis analysis(model);

  SECTION("a node in no list") {
    CHECK_THROWS_WITH(analysis.use_ring_solver(tire.tread_nodes, {}),
                      Catch::Contains("belongs to neither a ring nor a border node"));
  }
  SECTION("a node listed twice") {
    CHECK_THROWS_WITH(analysis.use_ring_solver(tire.tread_nodes, {tire.spindle, tire.tread_nodes[3]}),
                      Catch::Contains("listed twice"));
  }
  SECTION("an extra coupling across the ring") {
    BeamSection section;
    section.axial_stiffness = section.shear_stiffness = 1e5;
    section.bending_stiffness = 1.0;
    const int a = tire.tread_nodes[0], b = tire.tread_nodes[50];
    model.add_block<TreadBeam>("spoke").add({a, b},
                                            TreadBeam(model.mesh().position(a), model.mesh().position(b), section));
    CHECK_THROWS_WITH(analysis.use_ring_solver(tire.tread_nodes, {tire.spindle}),
                      Catch::Contains("not ring neighbours"));
  }
  SECTION("a structure change after the choice is checked before the next step") {
    analysis.use_ring_solver(tire.tread_nodes, {tire.spindle});
    const int a = tire.tread_nodes[0], b = tire.tread_nodes[50];
    BeamSection section;
    section.axial_stiffness = section.shear_stiffness = 1e5;
    section.bending_stiffness = 1.0;
    model.add_block<TreadBeam>("spoke").add({a, b},
                                            TreadBeam(model.mesh().position(a), model.mesh().position(b), section));
    CHECK_THROWS_AS(analysis.advance(0.1), ModelError);
  }
  SECTION("factors of another pattern, solves before factoring") {
    model.fix(tire.spindle, kUx);
    analysis.assembler().update_pattern();
    RingSolver ring(model.dof_map(), tire.tread_nodes, {tire.spindle});
    ring.analyze(analysis.assembler().tangent());
    Eigen::VectorXd rhs = Eigen::VectorXd::Ones(model.dof_map().equation_count());
    CHECK_THROWS_AS(ring.solve(rhs), std::logic_error);
    SparseMatrix other = analysis.assembler().tangent();
    other.insert(0, model.dof_map().equation_count() - 2) = 1.0;  // a new entry: another pattern
    other.makeCompressed();
    CHECK_THROWS_AS(ring.factorize(other), std::logic_error);
  }
}

TEST_CASE("ring solver: a satellite with its rotation free, or held, solves as KLU does", "[ring_solver]") {
  // The cantilever's tip node left out of the ring: a satellite of the node before it,
  // with all three DOFs (a beam end), or with its rotation held (as a contact node's is).
  for (bool rotation_held : {false, true}) {
    INFO("tip rotation held: " << rotation_held);
    Model klu_model, ring_model;
    for (Model* model : {&klu_model, &ring_model}) {
      build_cantilever(*model);
      if (rotation_held) model->fix(kCantileverElements, kRz);
    }
    std::vector<int> ring;
    for (int i = 0; i < kCantileverElements; ++i) ring.push_back(i);
    check_steps_against_klu(klu_model, ring_model, ring);
  }
}

TEST_CASE("ring solver: a node outside the lists is taken only as a satellite of one ring node", "[ring_solver]") {
  // Node s_5 hangs on belt node b_5 (and s_6 on b_6); a second beam from s_5 to b_6, to
  // the spindle or to s_6, or a node with no coupling, does not fit.
  Model model;
  const Tire tire = build_tire(model, macros::load_tire_parameters(kTires[1]), LoadFunction::linear());
  const int hung[] = {hang_satellite(model, tire.tread_nodes[5]), hang_satellite(model, tire.tread_nodes[6], "hung6")};
  model.condense_node(tire.spindle);
  for (int c = 0; c < kDofsPerNode; ++c) model.fix(tire.spindle, c);  // regular quasi-statically
  Analysis analysis(model);
  analysis.use_ring_solver(tire.tread_nodes, {tire.spindle});  // fits as built
  auto couple = [&](int other) {
    BeamSection section;
    section.axial_stiffness = section.shear_stiffness = 1e6;
    section.bending_stiffness = 1.0;
    section.mass_per_length = 1.0;
    model.add_block<TreadBeam>("extra").add(
        {hung[0], other}, TreadBeam(model.mesh().position(hung[0]), model.mesh().position(other), section));
  };
  auto refused = [&](const std::string& reason) {
    CHECK_THROWS_WITH(analysis.use_ring_solver(tire.tread_nodes, {tire.spindle}),
                      Catch::Contains("belongs to neither a ring nor a border node") && Catch::Contains(reason));
  };
  SECTION("coupled to two belt nodes") {
    couple(tire.tread_nodes[6]);
    refused("ring node " + std::to_string(tire.tread_nodes[5]) + " (position 5 of 100 in the ring) and to ring node " +
            std::to_string(tire.tread_nodes[6]));
    // Preferred, the ring solver gives way to KLU.
    analysis.prefer_ring_solver(tire.tread_nodes, {tire.spindle});
    analysis.set_time_step(0.5);
    analysis.advance(0.5);
    CHECK(analysis.ring_solver() == nullptr);
  }
  SECTION("coupled to the spindle") {
    model.release(tire.spindle, kRz);
    couple(tire.spindle);
    refused("and to border node " + std::to_string(tire.spindle));
  }
  SECTION("coupled to another satellite") {
    couple(hung[1]);
    refused("and to satellite node");
  }
  SECTION("coupled to nothing") {
    model.mesh().add_node({1.0, 1.0});
    CHECK_THROWS_WITH(analysis.use_ring_solver(tire.tread_nodes, {tire.spindle}),
                      Catch::Contains("coupled to no ring node"));
  }
}

TEST_CASE("ring solver: a singular tangent throws SingularMatrix; the partial factorisation still gives H",
          "[ring_solver]") {
  // Quasi-statically, a tire free on its spindle moves as a rigid body: K is singular,
  // K_uu (the tread with the spindle held) is not, and H (the spindle stiffness through
  // the tire) is zero up to round-off.
  InflatedTire inflated(0, false);
  const SparseMatrix& stiffness = inflated.tangent(0.0);
  RingSolver ring(inflated.model.dof_map(), inflated.tire.tread_nodes, {inflated.tire.spindle});
  ring.analyze(stiffness);
  CHECK_THROWS_AS(ring.factorize(stiffness), SingularMatrix);
  CHECK_THROWS_WITH(ring.factorize(stiffness), Catch::Contains("border node"));
  ring.factorize_interior(stiffness);
  const int n = static_cast<int>(stiffness.rows());
  const Eigen::MatrixXd dense = Eigen::MatrixXd(stiffness);
  const double spindle_scale = dense.bottomRightCorner(3, 3).norm();
  CHECK(ring.border_schur_complement().norm() <= 1e-8 * spindle_scale);

  // A zero row (a DOF no element stiffens) is caught on the ring too.
  SparseMatrix zeroed = stiffness;
  const int row = 40;
  for (int column = 0; column < n; ++column)
    for (SparseMatrix::InnerIterator entry(zeroed, column); entry; ++entry)
      if (entry.row() == row) entry.valueRef() = 0.0;
  CHECK_THROWS_WITH(ring.factorize(zeroed), Catch::Contains("zero row") && Catch::Contains("ring node 14"));

  // Newton turns it into a step cut, and the analysis fails with the reason.
  Model model;
  const Tire tire = build_tire(model, macros::load_tire_parameters("tires.145SR12"), LoadFunction::linear());
  Analysis analysis(model);
  analysis.use_ring_solver(tire.tread_nodes, {tire.spindle});
  analysis.step_control().max_cuts = 1;
  CHECK_THROWS_WITH(analysis.advance(0.5), Catch::Contains("singular"));
}

TEST_CASE(
    "ring solver: inflation and Newmark steps of the tire match KLU's with the spindle free, on a dead "
    "axle and fixed",
    "[ring_solver]") {
  for (const char* tire_set : kTires)
    for (int c = 0; c < 3; ++c) {
      DYNAMIC_SECTION(tire_set << ", " << kSpindleCases[c]) {
        const int fixed = kFixedComponents[c];
        std::unique_ptr<InflatedTire> runs[2];
        for (int solver = 0; solver < 2; ++solver) {
          runs[solver] = std::make_unique<InflatedTire>(fixed, solver == 1, tire_set);
          InflatedTire& run = *runs[solver];
          // After the inflation: a push on the bottom of the tread, a torque and a pull on the hub.
          Model& model = run.model;
          const int kick = model.add_load_function(LoadFunction::table({{1.0, 0.0}, {1.0005, 1.0}}));
          model.add_nodal_load(run.tire.tread_nodes[75], kUy, 800.0, kick);
          model.add_nodal_load(run.tire.spindle, kRz, 60.0, kick);
          model.add_nodal_load(run.tire.spindle, kUx, -300.0, kick);
          run.analysis->set_integrator(Integrator::newmark());
          run.analysis->set_time_step(1e-4);
          run.analysis->advance(2e-3);
        }
        const Analysis& klu = *runs[0]->analysis;
        const Analysis& ring = *runs[1]->analysis;
        CHECK(std::string(runs[1]->analysis->linear_solver().name()) == "ring");
        CHECK(runs[1]->analysis->linear_solver().factorization_count() >= 24);
        CHECK(ring.accepted_steps() == klu.accepted_steps());
        const Eigen::VectorXd& u = klu.state().displacement;
        INFO("|u| = " << u.norm() << ", spindle rotation " << u[dof_index(runs[0]->tire.spindle, kRz)]);
        CHECK(relative_difference(ring.state().displacement, u) <= 1e-9);
        CHECK(relative_difference(ring.state().velocity, klu.state().velocity) <= 1e-9);
        if (fixed < 3) CHECK(std::abs(u[dof_index(runs[0]->tire.spindle, kRz)]) > 1e-6);  // the hub did turn
      }
    }
}
