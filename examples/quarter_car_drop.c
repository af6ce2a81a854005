/* A quarter car dropped onto a tirefe tire: a 300 kg mass on the spindle, sliding on a
 * vertical guide with a viscous damper (4000 N s/m: the tire alone hardly damps the
 * bounce), let go at rest with the tire just touching the road. The host integrates with
 * Newmark (beta = 1/4, the tire's own scheme) and a Newton corrector on the spindle
 * height that uses the tire's spindle Jacobian. It settles where the tire carries the
 * weight.
 *
 *   quarter_car_drop [TIRE] [STEPS]      TIRE: "tires.145SR12" (default) or a .tir file
 *
 * Prints the spindle height and force at the end; exits 1 if a call fails. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tirefe.h"

int main(int argc, char** argv) {
  const char* source = argc > 1 ? argv[1] : "tires.145SR12";
  const int steps = argc > 2 ? atoi(argv[2]) : 1000;
  const double m = 300.0, c = 4000.0, g = 9.81, h = 1e-3;

  char error[512];
  tirefe_tire* tire = NULL;
  if (tirefe_open(source, NULL, 0, NULL, &tire, error, sizeof error) != TIREFE_OK) {
    fprintf(stderr, "quarter_car_drop: %s\n", error);
    return 1;
  }
  double z = 0.0, v = 0.0, a = -g; /* the spindle: height z [m], velocity, acceleration */
  tirefe_spindle_force reply;
  double carried = 0.0; /* mean of Fz over the last 20 steps (Newmark leaves a small step-to-step ringing) */
  for (int step = 0; step < steps; ++step) {
    double z_new = z + h * v + 0.5 * h * h * a; /* predictor: the same acceleration */
    double a_new = a, v_new = v;
    for (int iteration = 0; iteration < 20; ++iteration) { /* corrector */
      a_new = 4.0 / (h * h) * (z_new - z - h * v) - a;
      v_new = v + 0.5 * h * (a + a_new);
      const tirefe_spindle_motion motion = {h, 0.0, z_new, 0.0};
      if (tirefe_solve(tire, &motion, &reply) != TIREFE_OK) {
        fprintf(stderr, "quarter_car_drop: step %d: %s\n", step, tirefe_message(tire));
        tirefe_close(tire);
        return 1;
      }
      /* The mass: m a = -c v - m g + Fz (the force the tire exerts on the wheel). */
      const double residual = m * a_new + c * v_new + m * g - reply.force[1];
      if (fabs(residual) < 1e-8 * m * g) break;
      z_new -= residual / (4.0 * m / (h * h) + 2.0 * c / h - reply.jacobian[1][1]);
    }
    if (tirefe_commit(tire) != TIREFE_OK) {
      fprintf(stderr, "quarter_car_drop: step %d: %s\n", step, tirefe_message(tire));
      tirefe_close(tire);
      return 1;
    }
    v = v_new;
    z = z_new;
    a = a_new;
    if (step >= steps - 20) carried += reply.force[1] / 20.0;
  }
  tirefe_spindle_state state;
  tirefe_state(tire, &state);
  printf("t = %.3f s  z = %.6e m  Fz = %.6e N  carried %.6e N (weight %.1f N)\n", state.time, z, state.force[1],
         carried, m * g);
  tirefe_close(tire);
  return 0;
}
