// The minimal C++ host of docs/spindle.md: the quarter car of examples/quarter_car_drop.c
// (a 300 kg mass on a damped vertical guide, let go at rest with the tire touching the
// road, Newmark with a Newton corrector on the spindle height) driving the tire through
// the internal C++ spindle exchange. That exchange works in the tire's plane (x right,
// y up) and returns the reaction R that holds the spindle, the force the host applies to
// the tire: the tire pushes the mass with -R. Prints the height, the weight carried
// (the mean of -R_y over the last 20 steps) and the weight.
#include <cmath>
#include <cstdio>
#include <memory>

#include "macros/macro_table.hpp"
#include "vehicle/tire_on_road.hpp"
#include "vehicle/tire_spindle.hpp"

int main() {
  using namespace tirefe;
  // A 145 SR-12 tire inflated on a held hub over a flat road (the spindle at y = 0).
  TireOnRoad tire(
      macros::load_tire_parameters("tires.145SR12"),
      [](double level) { return std::make_shared<FlatRoad>(Eigen::Vector2d(0, level)); }, RoadContact{0.8});
  TireSpindle& spindle = tire.drive(Integrator::newmark());  // the host's scheme: Newmark, beta = 1/4

  const double m = 300.0, c = 4000.0, g = 9.81, h = 1e-3;
  const int steps = 1000;
  double y = 0.0, v = 0.0, a = -g;  // the spindle: height [m], velocity, acceleration
  double carried = 0.0;
  for (int step = 0; step < steps; ++step) {
    double y_new = y + h * v + 0.5 * h * h * a;  // predictor: the same acceleration
    double a_new = a, v_new = v;
    SpindleReply reply;
    for (int iteration = 0; iteration < 20; ++iteration) {  // corrector
      a_new = 4.0 / (h * h) * (y_new - y - h * v) - a;
      v_new = v + 0.5 * h * (a + a_new);
      reply = spindle.solve_step({h, 0.0, y_new, 0.0});
      // The mass: m a = -c v - m g - R_y (the tire pushes it with -R).
      const double residual = m * a_new + c * v_new + m * g + reply.force[1];
      if (std::abs(residual) < 1e-8 * m * g) break;
      y_new -= residual / (4.0 * m / (h * h) + 2.0 * c / h + reply.jacobian[1][1]);
    }
    spindle.commit();
    v = v_new;
    y = y_new;
    a = a_new;
    if (step >= steps - 20) carried -= reply.force[1] / 20.0;
  }
  std::printf("y = %.6e m  carried %.6e N (weight %.1f N)\n", y, carried, m * g);
  return 0;
}
