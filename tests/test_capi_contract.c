/* The contract of the C API (include/tirefe.h), checked from C: statuses and messages for
 * bad calls, the tire untouched by a failed or reverted step, the velocity form against
 * the position form, two tires solved in two threads as they are in one, and the
 * Jacobian in ISO wheel axes against differences of the forces, for both headings.
 * Prints one line per failed check; exits 1 if any failed. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "tirefe.h"

static int failures = 0;

static void check(int ok, const char* what, const char* detail) {
  if (!ok) {
    ++failures;
    printf("FAILED: %s (%s)\n", what, detail ? detail : "");
  }
}

static void check_close(double got, double expected, double tolerance, const char* what) {
  char detail[128];
  snprintf(detail, sizeof detail, "got %.17g, expected %.17g +- %.3g", got, expected, tolerance);
  check(fabs(got - expected) <= tolerance, what, detail);
}

static tirefe_tire* open_tire(void) {
  char error[512];
  tirefe_tire* tire = NULL;
  if (tirefe_open("tires.145SR12", NULL, 0, NULL, &tire, error, sizeof error) != TIREFE_OK)
    printf("FAILED: open tires.145SR12 (%s)\n", error);
  return tire;
}

/* Presses the spindle down 'steps' ms at 0.25 m/s; the last reply in 'reply'. */
static tirefe_status press(tirefe_tire* tire, int steps, tirefe_spindle_force* reply) {
  for (int step = 1; step <= steps; ++step) {
    const tirefe_spindle_motion motion = {1e-3, 0.0, -0.25e-3 * step, 0.0};
    tirefe_status status = tirefe_solve(tire, &motion, reply);
    if (status == TIREFE_OK) status = tirefe_commit(tire);
    if (status != TIREFE_OK) return status;
  }
  return TIREFE_OK;
}

static void check_open_errors(void) {
  char error[512];
  tirefe_tire* tire = (tirefe_tire*)&error; /* set to NULL on failure */
  const tirefe_parameter misspelt[] = {{"k_sww", 1000.0}};
  check(tirefe_open("tires.145SR12", misspelt, 1, NULL, &tire, error, sizeof error) == TIREFE_MODEL_ERROR,
        "a misspelt parameter is a model error", error);
  check(tire == NULL, "no tire after a failed open", NULL);
  check(strstr(error, "k_sww") != NULL, "the message names the parameter", error);

  const tirefe_parameter negative[] = {{"pressure", -1.0}};
  check(tirefe_open("tires.145SR12", negative, 1, NULL, &tire, error, sizeof error) == TIREFE_MODEL_ERROR,
        "a negative pressure is a model error", error);
  check(strstr(error, "pressure") != NULL, "the message names the pressure", error);

  check(tirefe_open("no_such_tire.tir", NULL, 0, NULL, &tire, error, sizeof error) == TIREFE_MODEL_ERROR,
        "a missing property file is a model error", error);
  check(strstr(error, "no_such_tire.tir") != NULL, "the message names the file", error);

  const tirefe_parameter not_finite[] = {{"pressure", NAN}};
  check(tirefe_open("tires.145SR12", not_finite, 1, NULL, &tire, error, sizeof error) == TIREFE_INVALID_ARGUMENT,
        "a NaN override is an invalid argument", error);

  tirefe_options options;
  tirefe_default_options(&options);
  options.hht_alpha = 0.5;
  check(tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) == TIREFE_MODEL_ERROR,
        "alpha = 0.5 is refused", error);
  check(strstr(error, "alpha") != NULL, "the message names alpha", error);
  tirefe_default_options(&options);
  options.heading = 0;
  check(tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) == TIREFE_INVALID_ARGUMENT,
        "a heading other than +1 or -1 is an invalid argument", error);
  check(strstr(error, "options.heading must be +1") != NULL, "the message says what a heading is", error);
  check(tirefe_open(NULL, NULL, 0, NULL, &tire, error, sizeof error) == TIREFE_INVALID_ARGUMENT,
        "a NULL source is an invalid argument", error);
}

static void check_call_errors(tirefe_tire* tire) {
  tirefe_spindle_force reply;
  check(tirefe_commit(tire) == TIREFE_INVALID_CALL, "commit without a trial step", tirefe_message(tire));
  const tirefe_spindle_motion nan_motion = {1e-3, 0.0, NAN, 0.0};
  check(tirefe_solve(tire, &nan_motion, &reply) == TIREFE_INVALID_ARGUMENT, "NaN spindle height", tirefe_message(tire));
  const tirefe_spindle_motion no_step = {0.0, 0.0, 0.0, 0.0};
  check(tirefe_solve(tire, &no_step, &reply) == TIREFE_INVALID_ARGUMENT, "zero time step", tirefe_message(tire));
  check(strstr(tirefe_message(tire), "time step") != NULL, "the message names the time step", tirefe_message(tire));
  check(tirefe_solve(NULL, &no_step, &reply) == TIREFE_INVALID_ARGUMENT, "NULL tire", NULL);
  check(tirefe_solve(tire, NULL, &reply) == TIREFE_INVALID_ARGUMENT, "NULL motion", NULL);
}

/* A step that cannot converge leaves the committed state as it was, and the tire goes on. */
static void check_failed_step(tirefe_tire* tire) {
  tirefe_spindle_state before, after;
  tirefe_state(tire, &before);
  tirefe_spindle_force reply;
  const tirefe_spindle_motion crush = {1e-3, 0.0, -0.4, 0.0}; /* through the rim in 1 ms */
  const tirefe_status status = tirefe_solve(tire, &crush, &reply);
  check(status == TIREFE_STEP_FAILED, "a crushing step fails", tirefe_message(tire));
  check(strlen(tirefe_message(tire)) > 0, "the failure says why", NULL);
  check(tirefe_commit(tire) == TIREFE_INVALID_CALL, "no commit of a failed step", tirefe_message(tire));
  tirefe_state(tire, &after);
  check(after.time == before.time && after.position[1] == before.position[1] && after.force[1] == before.force[1],
        "the committed state is unchanged by the failed step", NULL);
}

/* Revert, and the velocity form against the position form. */
static void check_trial_steps(tirefe_tire* tire) {
  tirefe_spindle_state state;
  tirefe_state(tire, &state);
  const double h = 1e-3;
  tirefe_spindle_force first, trial, again, by_velocity;
  const tirefe_spindle_motion down = {h, 0.0, state.position[1] - 2e-4, 0.0};
  const tirefe_spindle_motion up = {h, 0.0, state.position[1] + 2e-4, 0.0};
  tirefe_solve(tire, &down, &first);
  tirefe_solve(tire, &up, &trial);
  check(tirefe_revert(tire) == TIREFE_OK, "revert", tirefe_message(tire));
  tirefe_solve(tire, &down, &again);
  check(again.force[1] == first.force[1] && again.jacobian[1][1] == first.jacobian[1][1],
        "a trial after other trials and a revert starts from the committed state", NULL);
  check(trial.force[1] < first.force[1], "lifting the spindle unloads the tire (Fz falls towards 0)", NULL);

  /* Newmark (beta 1/4, gamma 1/2): u_{n+1} - u_n = h (v_n + v_{n+1}) / 2, so the end
   * velocities that put the spindle at 'down' (x unchanged). */
  const double dz = down.z - state.position[1];
  const double v_end[3] = {-state.velocity[0], 2.0 * dz / h - state.velocity[1], 0.0};
  check(tirefe_solve_velocity(tire, h, v_end, &by_velocity) == TIREFE_OK, "solve by velocity", tirefe_message(tire));
  check_close(by_velocity.force[1], first.force[1], 1e-9 * fabs(first.force[1]), "Fz by velocity = Fz by position");
  check_close(by_velocity.jacobian[1][1], first.jacobian[1][1] * 0.25 * h / 0.5, 1e-9 * fabs(first.jacobian[1][1] * h),
              "dFz/dvz = dFz/dz beta h / gamma");
  tirefe_revert(tire);
}

/* The C API's Jacobian in ISO wheel axes against central differences of its own forces,
 * for a driven wheel heading +x and -x: pressed 2 mm, then a trial step that moves it
 * along x, so that every force and moment is loaded. Each difference quotient agrees
 * with the Jacobian's entry to 1e-6 of the largest entry of its row (found: 1e-9), which
 * checks the small cross terms' signs too. Returns the trial step's reply: the tire is
 * mirror-symmetric, so both headings must answer alike. */
static tirefe_spindle_force check_jacobian_by_differences(int heading) {
  tirefe_options options;
  tirefe_default_options(&options);
  options.free_spin = 0;
  options.heading = heading;
  char error[512];
  tirefe_tire* tire = NULL;
  tirefe_spindle_force at;
  memset(&at, 0, sizeof at);
  if (tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) != TIREFE_OK) {
    check(0, "open a driven tire", error);
    return at;
  }
  /* Steps of 50 ms: the hub's inertia hardly stiffens the tire, which is pressed nearly
   * statically. */
  const double h = 0.05;
  for (int step = 1; step <= 6; ++step) {
    const tirefe_spindle_motion pressed = {h, 0.0, -0.5e-3 * (step < 4 ? step : 4), 0.0};
    if (tirefe_solve(tire, &pressed, &at) != TIREFE_OK || tirefe_commit(tire) != TIREFE_OK) {
      check(0, "press a driven tire 2 mm", tirefe_message(tire));
      tirefe_close(tire);
      return at;
    }
  }
  check(at.force[1] > 0.0, "a pressed tire carries the wheel: Fz > 0 whatever the heading", NULL);
  const double base[3] = {2e-4, -2.2e-3, 0.0}; /* x, z [m], spin [rad] */
  const double delta[3] = {1e-6, 1e-6, 1e-5};
  const tirefe_spindle_motion motion = {h, base[0], base[1], base[2]};
  check(tirefe_solve(tire, &motion, &at) == TIREFE_OK, "solve the loaded trial step", tirefe_message(tire));
  check(at.force[0] < 0.0, "pushed ahead against the road's friction: Fx < 0", NULL);
  check(at.jacobian[0][0] < 0.0 && at.jacobian[1][1] < 0.0 && at.jacobian[2][2] < 0.0,
        "the tire resists each motion: dFx/dx, dFz/dz and dMy/dspin < 0", NULL);
  for (int j = 0; j < 3; ++j) {
    tirefe_spindle_force plus, minus;
    double q[3] = {base[0], base[1], base[2]};
    q[j] = base[j] + delta[j];
    const tirefe_spindle_motion ahead = {h, q[0], q[1], q[2]};
    q[j] = base[j] - delta[j];
    const tirefe_spindle_motion behind = {h, q[0], q[1], q[2]};
    tirefe_solve(tire, &ahead, &plus);
    tirefe_solve(tire, &behind, &minus);
    for (int i = 0; i < 3; ++i) {
      const double scale = fmax(fmax(fabs(at.jacobian[i][0]), fabs(at.jacobian[i][1])), fabs(at.jacobian[i][2]));
      char what[96];
      snprintf(what, sizeof what, "heading %+d: d force[%d] / d motion[%d] by central differences", heading, i, j);
      const double fd = (plus.force[i] - minus.force[i]) / (2.0 * delta[j]);
      check_close(fd, at.jacobian[i][j], 1e-6 * scale, what);
    }
  }
  /* The velocity form in the same axes: the end velocities that put the wheel at 'base'
   * (Newmark: q_{n+1} - q_n = h (v_n + v_{n+1}) / 2) give its force, and the Jacobian
   * times beta h / gamma. */
  tirefe_spindle_state state;
  tirefe_state(tire, &state);
  double v_end[3];
  for (int c = 0; c < 3; ++c) v_end[c] = 2.0 * (base[c] - state.position[c]) / h - state.velocity[c];
  tirefe_spindle_force by_velocity;
  check(tirefe_solve_velocity(tire, h, v_end, &by_velocity) == TIREFE_OK, "solve a driven wheel by velocity",
        tirefe_message(tire));
  for (int i = 0; i < 3; ++i) {
    check_close(by_velocity.force[i], at.force[i], 1e-9 * fabs(at.force[1]), "the force by velocity, any heading");
    for (int j = 0; j < 3; ++j)
      check_close(by_velocity.jacobian[i][j], at.jacobian[i][j] * 0.25 * h / 0.5, 1e-9 * fabs(at.jacobian[1][1] * h),
                  "the Jacobian by velocity, any heading");
  }
  tirefe_close(tire);
  return at;
}

static void check_headings_alike(void) {
  const tirefe_spindle_force plus = check_jacobian_by_differences(+1);
  const tirefe_spindle_force minus = check_jacobian_by_differences(-1);
  for (int i = 0; i < 3; ++i) {
    check_close(minus.force[i], plus.force[i], 1e-9 * fabs(plus.force[1]), "heading -x: the force of heading +x");
    for (int j = 0; j < 3; ++j)
      check_close(minus.jacobian[i][j], plus.jacobian[i][j], 1e-9 * fabs(plus.jacobian[1][1]),
                  "heading -x: the Jacobian of heading +x");
  }
}

struct pressing {
  tirefe_tire* tire;
  tirefe_spindle_force reply;
  tirefe_status status;
};

static void* press_in_thread(void* argument) {
  struct pressing* job = (struct pressing*)argument;
  job->status = press(job->tire, 8, &job->reply);
  return NULL;
}

static void check_threads(void) {
  struct pressing jobs[2];
  pthread_t threads[2];
  for (int i = 0; i < 2; ++i) {
    jobs[i].tire = open_tire();
    if (!jobs[i].tire) return;
    pthread_create(&threads[i], NULL, press_in_thread, &jobs[i]);
  }
  for (int i = 0; i < 2; ++i) pthread_join(threads[i], NULL);
  tirefe_tire* alone = open_tire();
  tirefe_spindle_force reply;
  check(press(alone, 8, &reply) == TIREFE_OK, "press alone", tirefe_message(alone));
  for (int i = 0; i < 2; ++i) {
    check(jobs[i].status == TIREFE_OK, "press in a thread", tirefe_message(jobs[i].tire));
    check(jobs[i].reply.force[1] == reply.force[1] && jobs[i].reply.jacobian[1][1] == reply.jacobian[1][1],
          "a tire solved in a thread beside another gives the same bits", NULL);
    tirefe_close(jobs[i].tire);
  }
  tirefe_close(alone);
}

int main(void) {
  check_open_errors();
  tirefe_tire* tire = open_tire();
  if (!tire) return 1;
  tirefe_spindle_force reply;
  check(press(tire, 8, &reply) == TIREFE_OK, "press 2 mm", tirefe_message(tire));
  check(reply.jacobian[1][1] < 0.0, "the vertical stiffness is positive: lifting the wheel unloads it, dFz/dz < 0",
        NULL);
  check_call_errors(tire);
  check_failed_step(tire);
  check_trial_steps(tire);
  tirefe_close(tire);
  check_threads();
  check_headings_alike();
  tirefe_close(NULL);
  printf("%s\n", failures ? "C API contract: failed" : "C API contract: passed");
  return failures ? 1 : 0;
}
