// The cost of the C API over the C++ spindle exchange: two identical tires, one driven
// through TireSpindle (C++), one through tirefe_solve / tirefe_commit (C), pressed onto
// the road by the same spindle motions, steps interleaved so that both see the same machine
// load. Prints the time per step of each, their difference (median over the steps and
// from the totals), and the cost of a C call that does no work (the lock and the guard).
// Both tires are the same code in libtirefe.so; their forces must agree bit for bit.
//
//   bench_capi_step [STEPS]      (default 400)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "macros/macro_table.hpp"
#include "tirefe.h"
#include "vehicle/tire_on_road.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double microseconds(Clock::duration d) { return std::chrono::duration<double, std::micro>(d).count(); }

/// The spindle at step k of h: pressed 10 mm onto the road smoothly in 200 steps, then held.
tirefe::SpindleInput motion(int k, double h) {
  const double s = std::min(k, 200) / 200.0;
  return {h, 0.0, -0.01 * s * s * (3.0 - 2.0 * s), 0.0};
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 400;
  const double h = 1e-3;
  using namespace tirefe;
  TireOnRoad cpp_tire(macros::load_tire_parameters("tires.145SR12"),
                      [](double level) { return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level)); },
                      RoadContact{0.8});
  TireSpindle& spindle = cpp_tire.drive(Integrator::newmark());
  char error[512];
  tirefe_tire* c_tire = nullptr;
  if (tirefe_open("tires.145SR12", nullptr, 0, nullptr, &c_tire, error, sizeof error) != TIREFE_OK) {
    std::fprintf(stderr, "bench_capi_step: %s\n", error);
    return 1;
  }

  std::vector<double> cpp_times, c_times, differences;
  int mismatches = 0;
  for (int k = 1; k <= steps; ++k) {
    const SpindleInput input = motion(k, h);
    const Clock::time_point t0 = Clock::now();
    const SpindleReply reply = spindle.solve_step(input);
    spindle.commit();
    const Clock::time_point t1 = Clock::now();
    const tirefe_spindle_motion c_motion{input.time_step, input.x, input.y, input.spin};
    tirefe_spindle_force c_reply;
    if (tirefe_solve(c_tire, &c_motion, &c_reply) != TIREFE_OK || tirefe_commit(c_tire) != TIREFE_OK) {
      std::fprintf(stderr, "bench_capi_step: step %d: %s\n", k, tirefe_message(c_tire));
      return 1;
    }
    const Clock::time_point t2 = Clock::now();
    mismatches += reply.force[0] != c_reply.force[0] || reply.force[1] != c_reply.force[1] ||
                  reply.jacobian[1][1] != c_reply.jacobian[1][1];
    cpp_times.push_back(microseconds(t1 - t0));
    c_times.push_back(microseconds(t2 - t1));
    differences.push_back(c_times.back() - cpp_times.back());
  }

  const int calls = 1000000;  // a call that does no work: what the C layer itself costs
  tirefe_spindle_state state;
  const Clock::time_point s0 = Clock::now();
  for (int i = 0; i < calls; ++i) tirefe_state(c_tire, &state);
  const double per_call = microseconds(Clock::now() - s0) / calls;
  tirefe_close(c_tire);

  auto median = [](std::vector<double> values) {
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
  };
  double cpp_total = 0, c_total = 0;
  for (int k = 0; k < steps; ++k) cpp_total += cpp_times[k], c_total += c_times[k];
  std::printf("steps: %d (solve + commit, 1 ms each)\n", steps);
  std::printf("C++ TireSpindle: %.1f us per step (median %.1f)\n", cpp_total / steps, median(cpp_times));
  std::printf("C API:           %.1f us per step (median %.1f)\n", c_total / steps, median(c_times));
  std::printf("C API - C++:     %+.2f us per step (median of the step pairs %+.2f)\n", (c_total - cpp_total) / steps,
              median(differences));
  std::printf("a C call doing no work (tirefe_state): %.3f us\n", per_call);
  std::printf("forces and stiffness differing between the two: %d steps\n", mismatches);
  return mismatches == 0 ? 0 : 1;
}
