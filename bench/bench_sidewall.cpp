// Time per evaluate() of the sidewall wedge and the tread pressure kernels (each their batch
// on a block of one), with and without the tangent, on a cycle of deformed states of a
// 145 SR-12-like wedge.
// Prints nanoseconds per call; a Newton iteration of a 100-element tire makes 100 of each.
// The wedge's batch path (a ring of 100 on one spindle) is timed per wedge.
#include <algorithm>
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

/// The same per wedge through the batch path, a ring of wedges at once (tread states
/// cycled, one spindle state for all, as in a tire).
double nanoseconds_per_wedge(const SidewallWedge::Batch& prototype, const std::vector<LocalState<9>>& states,
                             const EvaluationContext& context, bool with_tangent, int repeats) {
  SidewallWedge::Batch batch = prototype;
  const int n = batch.size();
  std::vector<double> displacement(9 * n), velocity(9 * n);
  for (int e = 0; e < n; ++e)
    for (int k = 0; k < 9; ++k) {
      const LocalState<9>& local = states[k < 3 ? 0 : e % states.size()];
      displacement[k * n + e] = local.displacement[k];
      velocity[k * n + e] = local.velocity[k];
    }
  const BlockValues values{n, displacement.data(), velocity.data(), nullptr};
  double sink = 0.0;
  const int calls = std::max(1, repeats * static_cast<int>(states.size()) / n);
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < calls; ++r) {
    batch.evaluate(values, context, with_tangent);
    sink += batch.residual()[0] + (with_tangent ? batch.tangent()[20 * n] : 0.0);
  }
  const auto stop = std::chrono::steady_clock::now();
  if (!std::isfinite(sink)) std::printf("non-finite result\n");
  return std::chrono::duration<double, std::nano>(stop - start).count() / (double(calls) * n);
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
  std::vector<SidewallWedge> ring;  // 100 wedges on one spindle, as in a tire
  for (int e = 0; e < 100; ++e) {
    const double angle = 2 * kPi * e / 100, next = 2 * kPi * (e + 1) / 100;
    ring.emplace_back(spindle, Eigen::Vector2d(0.27 * std::cos(angle), 0.27 * std::sin(angle)),
                      Eigen::Vector2d(0.27 * std::cos(next), 0.27 * std::sin(next)), properties, pressure);
  }
  const SidewallWedge::Batch batch(ring);

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
  std::printf("SidewallWedge batch of 100, static       : %6.0f ns per wedge\n",
              nanoseconds_per_wedge(batch, wedge_states, statics, true, repeats));
  std::printf("SidewallWedge batch of 100, dynamic      : %6.0f ns per wedge\n",
              nanoseconds_per_wedge(batch, wedge_states, dynamics, true, repeats));
  std::printf("SidewallWedge batch residual only, dynamic: %5.0f ns per wedge\n",
              nanoseconds_per_wedge(batch, wedge_states, dynamics, false, repeats));
  std::printf("TreadPressure residual + tangent         : %6.0f ns\n",
              nanoseconds_per_call(load, load_states, statics, true, repeats));
  return 0;
}
