// The worked examples of docs/extending.md (examples/extending/), built and checked: an
// element, a surface, a macro and an output quantity. docs/extending.md quotes the files,
// and tests/test_docs.cpp checks that the quotes are these files.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "examples/extending/axial_spring.hpp"
#include "examples/extending/axial_spring_macro.hpp"
#include "examples/extending/block_energy_channel.hpp"
#include "examples/extending/bump_road.hpp"
#include "deck_support.hpp"
#include "io/hdf5_file.hpp"
#include "solvers/analysis.hpp"
#include "test_support.hpp"

using namespace tirefe;
using examples::AxialSpring;

namespace {

/// A spring of stiffness k from a held node at the origin to a node at 'end', which is held
/// in the component 'held' and in rotation and loaded by 'force' times the ramp in 'loaded'.
/// Returns the loaded node.
int add_held_spring(Model& model, const Eigen::Vector2d& end, double k, int held, int loaded, double force) {
  const int a = model.mesh().add_node({0.0, 0.0}), b = model.mesh().add_node(end);
  model.add_block<AxialSpring>("springs").add({a, b}, AxialSpring({0.0, 0.0}, end, k));
  for (int component : {kUx, kUy, kRz}) model.fix(a, component);
  model.fix(b, held);
  model.fix(b, kRz);
  model.add_nodal_load(b, loaded, force, Model::kRampLoadFunction);
  return b;
}

}  // namespace

TEST_CASE("AxialSpring: its tangent is its residual's derivative, and its declarations hold", "[extending]") {
  const AxialSpring spring({0.1, 0.2}, {0.9, 0.6}, 3e4);
  std::mt19937 random(7);
  for (int sample = 0; sample < 20; ++sample) {
    const LocalState<6> local = testing::random_local_state<6>(random, 0.2, 0.5);
    for (const EvaluationContext& context : {EvaluationContext{}, testing::dynamic_context()}) {
      CHECK(testing::relative_tangent_error(spring, local, context) < 1e-7);
      CHECK(testing::declared_zero_magnitude(spring, local, context) == 0.0);
    }
  }
  CHECK_THROWS_AS(AxialSpring({0, 0}, {0, 0}, 1.0), ModelError);
  CHECK_THROWS_AS(AxialSpring({0, 0}, {1, 0}, -1.0), ModelError);
}

TEST_CASE("AxialSpring at 45 degrees, pushed down at its free end: the large-rotation equilibrium", "[extending]") {
  // a = (0, 0) held, b = (1, 1) held in x, pushed by F down: with y = 1 + v, l = sqrt(1 + y^2),
  // the spring's force k (l - sqrt 2) along it balances F: k (l - sqrt 2) y / l = -F.
  const double k = 1e4, push = 500.0;
  Model model;
  const int b = add_held_spring(model, {1.0, 1.0}, k, kUx, kUy, -push);
  Analysis analysis(model);
  analysis.set_time_step(0.25);
  analysis.advance(1.0);
  const double v = analysis.state().displacement[dof_index(b, kUy)];

  auto imbalance = [&](double deflection) {
    const double y = 1.0 + deflection, l = std::sqrt(1.0 + y * y);
    return k * (l - std::sqrt(2.0)) * y / l + push;
  };
  double low = -0.5, high = 0.0;  // imbalance(low) < 0 < imbalance(high)
  for (int i = 0; i < 200; ++i) (imbalance(0.5 * (low + high)) < 0.0 ? low : high) = 0.5 * (low + high);
  CHECK(v == Approx(0.5 * (low + high)).epsilon(1e-9));
  // Beyond the linear 2 F / k (a spring at 45 degrees has k / 2 vertically): compressed, it softens.
  CHECK(v == Approx(-0.109494).epsilon(1e-5));
}

TEST_CASE("BumpRoad: gaps, normals and curvature over the level road and the bump", "[extending]") {
  const double centre = 2.0, radius = 0.05;
  const examples::BumpRoad road(centre, radius);
  const SurfaceProjection top = road.project({centre, radius + 0.01}, 0.0);
  CHECK(top.gap == Approx(0.01).epsilon(1e-12));
  CHECK(top.normal.y() == Approx(1.0).epsilon(1e-12));
  CHECK(top.curvature == Approx(1.0 / radius).epsilon(1e-12));
  const SurfaceProjection flank =
      road.project(Eigen::Vector2d(centre, 0.0) + 0.06 * Eigen::Vector2d(1, 1).normalized(), 0.0);
  CHECK(flank.gap == Approx(0.01).epsilon(1e-12));
  CHECK(flank.normal.x() == Approx(std::sqrt(0.5)).epsilon(1e-12));
  const SurfaceProjection level = road.project({centre + 1.0, -0.002}, 0.0);
  CHECK(level.gap == Approx(-0.002).epsilon(1e-12));
  CHECK(level.curvature == 0.0);
  CHECK(road.clearance({centre + 1.0, 0.3}, 0.0) == Approx(0.25).epsilon(1e-12));
  // Moving with the road: 1 m along x after 1 s at 1 m/s.
  const examples::BumpRoad moving(centre, radius, RigidMotion::translation(MotionFunction::ramped_rate(1.0, 0.0, 0.0)));
  CHECK(moving.project({centre + 1.0, radius + 0.01}, 1.0).gap == Approx(0.01).epsilon(1e-9));
  CHECK_THROWS_AS(examples::BumpRoad(centre, 0.0), ModelError);
}

namespace {

/// What registering the macro with add(axial_spring_spec(), axial_spring_macro) in a
/// group's add_*_macros does, done here at run time: the handler behind a model method.
int call_axial_spring(lua_State* L) {
  std::string failure;
  try {
    macros::DeckModel& deck = macros::check_model(L, 1);
    const macros::MacroArguments arguments(L, 2, examples::axial_spring_spec());
    return examples::axial_spring_macro(L, deck, arguments);
  } catch (const std::exception& error) {
    failure = std::string("macro 'axial_spring': ") + error.what();
  }
  macros::raise_deck_error(L, failure);
}

/// Makes model:axial_spring a method of the deck's models.
void add_axial_spring_method(macros::LuaSandbox& sandbox) {
  lua_State* L = sandbox.state();
  luaL_getmetatable(L, "tirefe.model");
  lua_getfield(L, -1, "__index");
  lua_getupvalue(L, -1, 1);  // the models' methods
  lua_pushcfunction(L, call_axial_spring);
  lua_setfield(L, -2, "axial_spring");
  lua_pop(L, 3);
}

std::string deck_error(const std::string& deck, const std::string& output_dir) {
  return testing::run_deck_in_process(deck, output_dir, add_axial_spring_method).error;
}

}  // namespace

TEST_CASE("model:axial_spring: the example deck passes its checks, and bad arguments name the deck line",
          "[extending][decks]") {
  testing::TempDir folder;
  const testing::InProcessRun run =
      testing::run_deck_in_process(std::string(TIREFE_SOURCE_DIR) + "/examples/extending/axial_spring.lua",
                                   folder.path("out"), add_axial_spring_method);
  CHECK(run.error == "");
  CHECK(run.checks == 3);
  CHECK(run.failed_checks == 0);
  const std::string bad = folder.write("bad.lua",
                                       "local model = tirefe.model{}\n"
                                       "local a, b = model:node{ x = 0, y = 0 }, model:node{ x = 1, y = 0 }\n"
                                       "model:axial_spring{ nodes = { a, b }, stifness = 1 }\n");
  CHECK_THAT(deck_error(bad, folder.path("out")),
             Catch::Contains("bad.lua:3:") && Catch::Contains("stifness") && Catch::Contains("stiffness"));
  const std::string three = folder.write("three.lua",
                                         "local model = tirefe.model{}\n"
                                         "model:node{ x = 0, y = 0 }\n"
                                         "model:axial_spring{ nodes = { 1, 1, 1 }, stiffness = 1 }\n");
  CHECK_THAT(deck_error(three, folder.path("out")),
             Catch::Contains("three.lua:3:") && Catch::Contains("'nodes' takes two node numbers"));
  // Its reference section, as docs/macros.md's pages would show it.
  CHECK_THAT(macros::markdown_reference({examples::axial_spring_spec()}),
             Catch::Contains("| `stiffness` | number > 0 | N/m | required | spring stiffness k |"));
}

TEST_CASE("model:history asks an element block for a response by name, and names what it has", "[extending][decks]") {
  testing::TempDir folder;
  const std::string spring =
      "local model = tirefe.model{}\n"
      "local a, b = model:node{ x = 0, y = 0 }, model:node{ x = 1, y = 0 }\n"
      "model:axial_spring{ nodes = { a, b }, stiffness = 1 }\n";
  const std::string unknown = folder.write(
      "unknown.lua", spring + "model:history{ name = \"n\", block = \"springs\", response = \"force\" }\n");
  CHECK_THAT(deck_error(unknown, folder.path("out")),
             Catch::Contains("unknown.lua:4:") && Catch::Contains("no response 'force' (it has axial_force)"));
  const std::string point = folder.write(
      "point.lua",
      spring + "model:history{ name = \"n\", block = \"springs\", response = \"axial_force\", point = 2 }\n");
  CHECK_THAT(deck_error(point, folder.path("out")),
             Catch::Contains("point.lua:4:") && Catch::Contains("point 2 of element block 'springs', which has 1"));
  const std::string alone = folder.write("alone.lua", spring + "model:history{ name = \"n\", block = \"springs\" }\n");
  CHECK_THAT(deck_error(alone, folder.path("out")), Catch::Contains("'block' needs 'response'"));
}

TEST_CASE("The strain energy channel of a block: k u^2 / 2 at every step in /history", "[extending][hdf5]") {
  const double k = 2e4, pull = 100.0;
  testing::TempDir folder;
  {
    Model model;
    add_held_spring(model, {1.0, 0.0}, k, kUy, kUx, pull);  // pulled by F t
    Analysis analysis(model);
    io::ResultFile file(folder.path("spring.h5"), io::RunMetadata{"spring", "", "", {}});
    examples::add_strain_energy_channel(file, model, "springs");
    CHECK_THROWS_AS(examples::add_strain_energy_channel(file, model, "beams"), ModelError);
    analysis.add_step_observer(
        [&](const Analysis& run, const StepRecord& record) { file.record(run.model(), run.state(), record); });
    analysis.set_time_step(0.25);
    analysis.advance(1.0);
  }
  const io::Hdf5File file = io::Hdf5File::open_read_only(folder.path("spring.h5"));
  const std::vector<double> time = file.read_doubles("/history/time");
  const std::vector<double> energy = file.read_doubles("/history/springs_strain_energy");
  REQUIRE(energy.size() == 4);
  for (size_t i = 0; i < energy.size(); ++i) {
    const double force = pull * time[i];
    CHECK(energy[i] == Approx(force * force / (2.0 * k)).epsilon(1e-12));
  }
}
