// Cost of one quasi-static force-deflection curve of the 145 SR-12 on a flat road: the
// evaluation a k_sw fit repeats (docs/fitting.md; the paper: under a minute per run).
// The tire is built, inflated to 208 kPa on a held hub in 4 steps, the contact added with
// penalties scaled from the inflated tire, and the spindle pressed 30 mm in 2 mm steps.
// Prints wall time per curve (and of its pressing part), steps, Newton iterations per
// step and time per iteration, for 100 and 200 elements.
//   build/bench_force_deflection [repetitions]
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "contact/tread_contact.hpp"
#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "tire/tire_builder.hpp"

using namespace tirefe;
using Clock = std::chrono::steady_clock;

namespace {

struct CurveCost {
  double total_ms = 0.0, press_ms = 0.0, load_30 = 0.0;
  int steps = 0, iterations = 0;
};

CurveCost run_curve(int elements) {
  CurveCost cost;
  const auto start = Clock::now();
  Model model;
  TireParameters parameters = macros::load_tire_parameters("tires.145SR12");
  parameters.elements = elements;
  const Tire tire = build_tire(model, parameters, LoadFunction::table({{0.0, 0.0}, {1.0, 1.0}}));
  for (int c = 0; c < kDofsPerNode; ++c) model.fix(tire.spindle, c);
  const int press = model.add_load_function(LoadFunction::table({{1.0, 0.0}, {2.0, 1.0}}));
  model.prescribe(tire.spindle, kUy, -0.030, press);
  Analysis analysis(model);
  analysis.set_time_step(0.25);
  analysis.advance(1.0);
  double lowest = 1e9;
  for (int node : tire.tread_nodes)
    lowest = std::min(lowest, model.mesh().position(node).y() + analysis.state().displacement[dof_index(node, kUy)]);
  auto road = std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, lowest));
  add_tread_contact_block(model, "road", road, tire.tread_nodes, tread_rubber(parameters, 0.0));
  const auto press_start = Clock::now();
  analysis.set_time_step(1.0 / 15);
  for (const StepRecord& record : analysis.advance(1.0)) {
    ++cost.steps;
    cost.iterations += record.newton_iterations;
  }
  const auto end = Clock::now();
  cost.total_ms = std::chrono::duration<double, std::milli>(end - start).count();
  cost.press_ms = std::chrono::duration<double, std::milli>(end - press_start).count();
  cost.load_30 = -analysis.reactions()[dof_index(tire.spindle, kUy)];
  return cost;
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::atoi(argv[1]) : 20;
  std::printf("145 SR-12, flat road, 208 kPa, 0-30 mm in 15 steps (%d repetitions)\n", repetitions);
  std::printf("%9s %12s %12s %7s %13s %14s %10s\n", "elements", "curve [ms]", "press [ms]", "steps", "Newton/step",
              "us/iteration", "F30 [N]");
  for (int elements : {100, 200}) {
    run_curve(elements);  // warm-up
    CurveCost sum;
    for (int r = 0; r < repetitions; ++r) {
      const CurveCost cost = run_curve(elements);
      sum.total_ms += cost.total_ms;
      sum.press_ms += cost.press_ms;
      sum.steps = cost.steps;
      sum.iterations = cost.iterations;
      sum.load_30 = cost.load_30;
    }
    std::printf("%9d %12.2f %12.2f %7d %13.2f %14.1f %10.3f\n", elements, sum.total_ms / repetitions,
                sum.press_ms / repetitions, sum.steps, static_cast<double>(sum.iterations) / sum.steps,
                1e3 * sum.press_ms / repetitions / sum.iterations, sum.load_30);
  }
  return 0;
}
