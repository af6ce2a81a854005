/* Presses a tirefe tire 5 mm onto the road, smoothly in 100 steps of 1 ms, holds it there
 * 20 steps and prints the vertical force Fz the tire exerts on the wheel and its
 * derivative dFz/dz (ISO wheel axes): the same numbers from every copy of the library. */
#include <stdio.h>

#include "tirefe.h"

int main(void) {
  const tirefe_parameter overrides[] = {{"pressure", 180e3}};
  char error[512];
  tirefe_tire* tire = NULL;
  if (tirefe_open("tires.145SR12", overrides, 1, NULL, &tire, error, sizeof error) != TIREFE_OK) {
    fprintf(stderr, "press_tire: %s\n", error);
    return 1;
  }
  tirefe_spindle_force reply;
  for (int step = 1; step <= 120; ++step) {
    const double s = step < 100 ? step / 100.0 : 1.0;
    const tirefe_spindle_motion motion = {1e-3, 0.0, -0.005 * s * s * (3.0 - 2.0 * s), 0.0};
    if (tirefe_solve(tire, &motion, &reply) != TIREFE_OK || tirefe_commit(tire) != TIREFE_OK) {
      fprintf(stderr, "press_tire: %s\n", tirefe_message(tire));
      tirefe_close(tire);
      return 1;
    }
  }
  printf("Fz %.17g\nH_zz %.17g\n", reply.force[1], reply.jacobian[1][1]);
  tirefe_close(tire);
  return 0;
}
