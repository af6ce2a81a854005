// The step budget of the C API (tirefe_set_step_budget): Newton ends at the budget's
// iterations with the step taken and its residual reported, close to the converged step,
// or goes on where the residual is above the budget's bound (an overrun); a wall-time
// budget ends it after its first iteration and counts every step over it; a budget starts
// the steps from the zero-acceleration predictor; no budget is the default, and {0, 0, 0}
// gives it back; bad budgets are refused naming the field.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "deck_support.hpp"
#include "include/tirefe.h"
#include "test_support.hpp"

namespace {

tirefe_tire* open_pressed() {
  tirefe_options options;
  tirefe_default_options(&options);
  options.hht_alpha = -0.1;
  options.start_z = -0.01;
  char error[512] = "";
  tirefe_tire* tire = nullptr;
  INFO(error);
  REQUIRE(tirefe_open("tires.145SR12", nullptr, 0, &options, &tire, error, sizeof error) == TIREFE_OK);
  return tire;
}

/// Step k of 1 ms: the wheel rolls off from rest (5 m/s^2) and is pressed 1 mm further in
/// 20 ms, smoothly (no jump of its velocity).
tirefe_spindle_motion motion(int k) {
  const double t = 1e-3 * k, s = std::min(k / 20.0, 1.0);
  return {1e-3, 2.5 * t * t, -0.01 - 1e-3 * s * s * (3.0 - 2.0 * s), 0.0};
}

struct Run {
  double largest_fz = 0.0;  // [N]
  int most_iterations = 0;
  tirefe_spindle_force last{};
};

Run run(tirefe_tire* tire, int first, int last) {
  Run result;
  for (int k = first; k <= last; ++k) {
    const tirefe_spindle_motion m = motion(k);
    INFO("step " << k << ": " << tirefe_message(tire));
    REQUIRE(tirefe_solve(tire, &m, &result.last) == TIREFE_OK);
    REQUIRE(tirefe_commit(tire) == TIREFE_OK);
    result.largest_fz = std::max(result.largest_fz, result.last.force[1]);
    result.most_iterations = std::max(result.most_iterations, result.last.newton_iterations);
  }
  return result;
}

}  // namespace

TEST_CASE("a step budget of Newton iterations ends the step there, reports its residual and stays near the default",
          "[capi][budget]") {
  tirefe_tire* plain = open_pressed();
  tirefe_tire* budgeted = open_pressed();
  const tirefe_step_budget one{1, 0.0, HUGE_VAL};  // a fixed count: whatever the residual
  REQUIRE(tirefe_set_step_budget(budgeted, &one) == TIREFE_OK);
  const Run converged = run(plain, 1, 20), limited = run(budgeted, 1, 20);
  CHECK(converged.most_iterations >= 2);  // the budget has something to cut
  CHECK(limited.most_iterations == 1);

  tirefe_budget_report plain_report{}, report{};
  REQUIRE(tirefe_step_budget_report(plain, &plain_report) == TIREFE_OK);
  REQUIRE(tirefe_step_budget_report(budgeted, &report) == TIREFE_OK);
  CHECK(plain_report.steps == 20);
  CHECK(plain_report.unconverged == 0);
  CHECK(plain_report.overruns == 0);
  CHECK(plain_report.worst_residual == 0.0);
  CHECK(plain_report.worst_time > 0.0);
  CHECK(report.steps == 20);
  CHECK(report.unconverged > 0);
  CHECK(report.worst_residual > 1e-9);  // above Newton's tolerance: unconverged
  CHECK(report.overruns == 0);
  CHECK(report.time_misses == 0);  // no time budget
  // The force of the unconverged steps: within 1e-3 N of the converged ones' (5e-6 N found).
  INFO("Fz " << converged.last.force[1] << " N converged, " << limited.last.force[1] << " N in one iteration; largest "
             << converged.largest_fz << " N, " << limited.largest_fz << " N; apart "
             << limited.last.force[1] - converged.last.force[1] << ", " << limited.largest_fz - converged.largest_fz);
  CHECK(converged.largest_fz > 1000.0);
  CHECK(std::abs(limited.last.force[1] - converged.last.force[1]) < 1e-3);
  CHECK(std::abs(limited.largest_fz - converged.largest_fz) < 1e-3);

  // The bound on the residual: a step ends at the budget only within it, else goes on.
  const tirefe_step_budget bounded{1, 0.0, 1e-7};
  REQUIRE(tirefe_set_step_budget(budgeted, &bounded) == TIREFE_OK);
  const Run within = run(budgeted, 21, 30);
  CHECK(within.most_iterations >= 2);
  REQUIRE(tirefe_step_budget_report(budgeted, &report) == TIREFE_OK);
  CHECK(report.steps == 10);
  CHECK(report.overruns > 0);
  CHECK(report.worst_residual <= 1e-7);

  // No budget again: Newton converges, and the report starts afresh.
  const tirefe_step_budget none{0, 0.0, 0.0};
  REQUIRE(tirefe_set_step_budget(budgeted, &none) == TIREFE_OK);
  const Run again = run(budgeted, 31, 35);
  CHECK(again.most_iterations >= 2);
  REQUIRE(tirefe_step_budget_report(budgeted, &report) == TIREFE_OK);
  CHECK(report.steps == 5);
  CHECK(report.unconverged == 0);
  CHECK(report.overruns == 0);
  tirefe_close(plain);
  tirefe_close(budgeted);
}

TEST_CASE("a wall-time step budget ends Newton after its first iteration and counts every step over it",
          "[capi][budget]") {
  tirefe_tire* tire = open_pressed();
  const tirefe_step_budget instant{0, 1e-9, HUGE_VAL};  // no step is that quick
  REQUIRE(tirefe_set_step_budget(tire, &instant) == TIREFE_OK);
  const Run limited = run(tire, 1, 10);
  CHECK(limited.most_iterations == 1);
  tirefe_budget_report report{};
  REQUIRE(tirefe_step_budget_report(tire, &report) == TIREFE_OK);
  CHECK(report.steps == 10);
  CHECK(report.time_misses == 10);
  CHECK(report.unconverged > 0);
  CHECK(report.worst_time > 1e-9);
  tirefe_close(tire);
}

TEST_CASE("bad step budgets are refused, naming the field", "[capi][budget]") {
  tirefe_tire* tire = open_pressed();
  const tirefe_step_budget negative{-1, 0.0, 0.0}, not_a_number{0, std::nan(""), 0.0}, below{0, -1e-3, 0.0},
      no_residual{1, 0.0, std::nan("")};
  CHECK(tirefe_set_step_budget(tire, &negative) == TIREFE_INVALID_ARGUMENT);
  CHECK(std::string(tirefe_message(tire)).find("max_iterations") != std::string::npos);
  CHECK(tirefe_set_step_budget(tire, &not_a_number) == TIREFE_INVALID_ARGUMENT);
  CHECK(std::string(tirefe_message(tire)).find("max_time") != std::string::npos);
  CHECK(tirefe_set_step_budget(tire, &below) == TIREFE_INVALID_ARGUMENT);
  CHECK(tirefe_set_step_budget(tire, &no_residual) == TIREFE_INVALID_ARGUMENT);
  CHECK(std::string(tirefe_message(tire)).find("max_residual") != std::string::npos);
  CHECK(tirefe_set_step_budget(tire, nullptr) == TIREFE_OK);  // NULL: no budget
  CHECK(tirefe_step_budget_report(tire, nullptr) == TIREFE_INVALID_ARGUMENT);
  tirefe_budget_report report{};
  CHECK(tirefe_step_budget_report(nullptr, &report) == TIREFE_INVALID_ARGUMENT);
  CHECK(tirefe_set_step_budget(nullptr, nullptr) == TIREFE_INVALID_ARGUMENT);
  tirefe_close(tire);
}

TEST_CASE("a step budget starts the steps from the zero-acceleration predictor, and no budget from the tire's own",
          "[capi][budget]") {
  // A bound on the residual below Newton's tolerance: every step converges, so that only
  // the predictor differs: the same forces to the tolerance, from other iterates.
  tirefe_tire* plain = open_pressed();
  tirefe_tire* budgeted = open_pressed();
  const tirefe_step_budget converging{1, 0.0, 1e-300};
  REQUIRE(tirefe_set_step_budget(budgeted, &converging) == TIREFE_OK);
  int plain_iterations = 0, budgeted_iterations = 0;
  double largest_difference = 0.0;
  for (int k = 1; k <= 20; ++k) {
    const tirefe_spindle_motion m = motion(k);
    tirefe_spindle_force a{}, b{};
    REQUIRE(tirefe_solve(plain, &m, &a) == TIREFE_OK);
    REQUIRE(tirefe_solve(budgeted, &m, &b) == TIREFE_OK);
    REQUIRE(tirefe_commit(plain) == TIREFE_OK);
    REQUIRE(tirefe_commit(budgeted) == TIREFE_OK);
    plain_iterations += a.newton_iterations;
    budgeted_iterations += b.newton_iterations;
    largest_difference = std::max(largest_difference, std::abs(a.force[1] - b.force[1]));
  }
  INFO(plain_iterations << " iterations from the tire's predictor, " << budgeted_iterations
                        << " from zero acceleration; Fz up to " << largest_difference << " N apart");
  CHECK(largest_difference > 0.0);  // another start: not the same iterates (1.3e-11 N found)
  CHECK(largest_difference < 1e-3);
  // No budget again: the tire's own predictor, the same iterations as the plain tire's.
  REQUIRE(tirefe_set_step_budget(budgeted, nullptr) == TIREFE_OK);
  tirefe_saved_state* saved = nullptr;
  REQUIRE(tirefe_save_state(plain, &saved) == TIREFE_OK);
  REQUIRE(tirefe_restore_state(budgeted, saved) == TIREFE_OK);
  for (int k = 21; k <= 25; ++k) {
    const tirefe_spindle_motion m = motion(k);
    tirefe_spindle_force a{}, b{};
    REQUIRE(tirefe_solve(plain, &m, &a) == TIREFE_OK);
    REQUIRE(tirefe_solve(budgeted, &m, &b) == TIREFE_OK);
    CHECK(a.newton_iterations == b.newton_iterations);
    CHECK(a.force[1] == b.force[1]);
    REQUIRE(tirefe_commit(plain) == TIREFE_OK);
    REQUIRE(tirefe_commit(budgeted) == TIREFE_OK);
  }
  tirefe_free_state(saved);
  tirefe_close(plain);
  tirefe_close(budgeted);
}

TEST_CASE("a deck's step budget (model:newton budget_iterations) ends steps early within its residual bound",
          "[newton][budget][lua]") {
  // A cantilever (EI = 1, L = 1) under a tip load of 1 N in 100 load steps, Newton to 1e-12:
  // about 5 iterations a step; with a budget of one iteration within 1e-3, two evaluations a
  // step (the step and its residual check) and a tip deflection within 1e-4 of the converged.
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("budget_deck.lua", R"(
local function run(newton)
  local model = tirefe.model{ title = "cantilever under a step budget" }
  local first, last
  for i = 0, 10 do
    local node = model:node{ x = i / 10, y = 0.0 }
    first = first or node
    last = node
  end
  model:section{ name = "beam", EA = 1e7, GA = 1e7, EI = 1.0 }
  local chain = {}
  for node = first, last do chain[#chain + 1] = node end
  model:beam{ section = "beam", nodes = chain }
  model:fix{ node = first }
  model:load{ node = last, fy = -1.0 }
  model:output{ file = newton.budget_iterations and "budget.h5" or "plain.h5" }
  model:newton(newton)
  local run = model:solve{ to = 1.0, dt = 0.01 }
  return run, model:value{ node = last, dof = "uy" }
end
local plain, plain_tip = run{ tolerance = 1e-12 }
local budget, budget_tip = run{ tolerance = 1e-12, budget_iterations = 1, budget_residual = 1e-3 }
tirefe.check{ name = "Newton to 1e-12: iterations per step", value = plain.newton_iterations / plain.steps,
              expected = 4.95, tolerance = 0.5 }
tirefe.check{ name = "a budget of one: evaluations per step", value = budget.newton_iterations / budget.steps,
              expected = 2, tolerance = 0 }
tirefe.check{ name = "tip deflection under the budget [m]", value = budget_tip, expected = plain_tip, relative = 1e-4 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 3);
}
