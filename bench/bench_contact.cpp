// Time per evaluation pass of the drum-cleat deck's contact: 100 tread nodes of a
// 145 SR-12-sized ring pressed 3 mm onto the 1.7 m drum with its 25 mm cleat, at full speed,
// with the deck's penalties and search distance. A pass evaluates every node with its
// tangent at one time, four passes per step (as Newton does), the histories committed after
// each step; the cleat passes under the ring during the run. Prints microseconds per pass,
// the nodes projected (within the search distance) and in contact per pass.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "contact/node_contact.hpp"

using namespace tirefe;

int main() {
  constexpr double kPi = 3.14159265358979323846;
  const double drum_radius = 0.85, tire_radius = 0.27, press = 0.003, speed = 51.3 / 3.6;
  Cleat cleat;
  cleat.height = 0.025;
  cleat.arc_length = 0.66;
  cleat.angle = -0.5 * kPi;
  cleat.edge_radius = 0.005;
  // Spun up from 2 s over 4 s to the full speed, clockwise (the top moves to +x).
  auto drum = std::make_shared<Drum>(2.0 * drum_radius, Eigen::Vector2d::Zero(),
                                     MotionFunction::ramped_rate(-speed / drum_radius, 4.0, 2.0), cleat);
  ContactParameters parameters;
  parameters.normal_penalty = 2e7;
  parameters.tangential_penalty = 2e6;
  parameters.friction = 0.3;

  const int count = 100;
  const Eigen::Vector2d hub(0.0, drum_radius + tire_radius - press);
  std::vector<NodeSurfaceContact> kernels;
  std::vector<LocalState<3>> locals(count);
  for (int e = 0; e < count; ++e) {
    const double angle = 2.0 * kPi * e / count;
    const Eigen::Vector2d x = hub + tire_radius * Eigen::Vector2d(std::sin(angle), -std::cos(angle));
    // The footprint flattened onto the drum: nodes inside it sit 0.1 mm deep.
    const double lift = std::max(x.norm(), drum_radius - 1e-4) - x.norm();
    kernels.emplace_back(drum, x, parameters, e, 6.5);
    locals[e].displacement << lift * x.normalized(), 0.0;
    locals[e].velocity << 0.0, 0.0, 0.0;
    locals[e].acceleration.setZero();
  }
  std::vector<ContactHistory> base(count), trial(count);
  NodeSurfaceContact::Vector residual;
  NodeSurfaceContact::Matrix tangent;
  EvaluationContext context;
  context.factors = {0.9, 0.9, 1.0, 0.9, 0.0, 0.0};

  const int steps = 4000, passes_per_step = 4;
  const double dt = 2.5e-4;  // 1 s at full speed: the cleat passes the ring about 2.7 times
  long projected = 0, touching = 0;
  double sink = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (int step = 0; step < steps; ++step) {
    context.time = 6.5 + (step + 1) * dt;
    for (int pass = 0; pass < passes_per_step; ++pass)
      for (int e = 0; e < count; ++e) {
        trial[e] = base[e];
        kernels[e].evaluate(locals[e], context, base[e], trial[e], residual, &tangent);
        sink += residual[0] + tangent(0, 0);
      }
    for (int e = 0; e < count; ++e) {
      projected += trial[e].gap <= parameters.search_distance || trial[e].state != ContactState::Open ? 1 : 0;
      touching += trial[e].state != ContactState::Open ? 1 : 0;
    }
    base = trial;
  }
  const auto stop = std::chrono::steady_clock::now();
  const double passes = double(steps) * passes_per_step;
  std::printf("contact pass of %d nodes on the drum with its cleat: %.2f us (%.1f projected, %.1f in contact)%s\n",
              count, std::chrono::duration<double, std::micro>(stop - start).count() / passes,
              double(projected) / steps, double(touching) / steps, std::isfinite(sink) ? "" : " non-finite");
  return 0;
}
