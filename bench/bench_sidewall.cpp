// Time per evaluate() of the sidewall wedge and the tread pressure kernels, with and
// without the tangent, on a cycle of deformed states of a 145 SR-12-like wedge.
// Prints nanoseconds per call; a Newton iteration of a 100-element tire makes 100 of each.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "elements/sidewall.hpp"
#include "elements/tread_pressure.hpp"

using namespace tirefe;

namespace {

template <class Kernel>
double nanoseconds_per_call(const Kernel& kernel, const std::vector<LocalState<Kernel::kDofs>>& states,
                            const EvaluationContext& context, bool with_tangent, int repeats) {
  typename Kernel::Vector residual;
  typename Kernel::Matrix tangent;
  typename Kernel::History history;
  double sink = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r)
    for (const auto& local : states) {
      kernel.evaluate(local, context, history, history, residual, with_tangent ? &tangent : nullptr);
      sink += residual[0] + (with_tangent ? tangent(2, 2) : 0.0);
    }
  const auto stop = std::chrono::steady_clock::now();
  if (!std::isfinite(sink)) std::printf("non-finite result\n");
  return std::chrono::duration<double, std::nano>(stop - start).count() / (double(repeats) * states.size());
}

}  // namespace

int main() {
  constexpr double kPi = 3.14159265358979323846;
  SidewallProperties properties;
  properties.rim_radius = 0.1524;
  properties.cord_length = 0.14;
  properties.bending_stiffness = 100.0;
  properties.shear_stiffness = 2.4e4;
  properties.radial_damping = 80.0;
  properties.circumferential_damping = 40.0;
  auto pressure = std::make_shared<const PressureSchedule>(0.208e6, LoadFunction::linear());
  const Eigen::Vector2d spindle(0.0, 0.0), a(0.27, 0.0),
      b(0.27 * std::cos(2 * kPi / 100), 0.27 * std::sin(2 * kPi / 100));
  const SidewallWedge wedge(spindle, a, b, properties, pressure);
  const TreadPressure load(a, b, 0.11, pressure);

  std::mt19937 random(1);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<LocalState<9>> wedge_states(64);
  std::vector<LocalState<6>> load_states(64);
  for (size_t i = 0; i < wedge_states.size(); ++i) {
    for (int k = 0; k < 9; ++k) {
      wedge_states[i].displacement[k] = (k % 3 == 2 ? 0.05 : 0.01) * uniform(random);
      wedge_states[i].velocity[k] = uniform(random);
      wedge_states[i].acceleration[k] = uniform(random);
    }
    load_states[i].displacement = wedge_states[i].displacement.tail<6>();
  }
  EvaluationContext statics, dynamics;
  statics.time = dynamics.time = 1.0;
  dynamics.factors = {1.0, 1.0, 1.0, 1.0, 0.5 / (0.25 * 1e-3), 1.0 / (0.25 * 1e-6)};
  const int repeats = 20000;
  std::printf("SidewallWedge residual + tangent, static : %6.0f ns\n",
              nanoseconds_per_call(wedge, wedge_states, statics, true, repeats));
  std::printf("SidewallWedge residual + tangent, dynamic: %6.0f ns\n",
              nanoseconds_per_call(wedge, wedge_states, dynamics, true, repeats));
  std::printf("SidewallWedge residual only, dynamic     : %6.0f ns\n",
              nanoseconds_per_call(wedge, wedge_states, dynamics, false, repeats));
  std::printf("TreadPressure residual + tangent         : %6.0f ns\n",
              nanoseconds_per_call(load, load_states, statics, true, repeats));
  return 0;
}
