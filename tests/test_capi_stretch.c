/* The C API's stretches, starting press and roads (include/tirefe.h), checked from C:
 * tirefe_advance lands where and when asked, in equal steps of at most the size asked, and
 * says where it stopped when it cannot go on; a tire opened at start_z holds the static force of that press and
 * keeps it while held there (the spindle handed over at rest); a road file's flat track is
 * the flat road, its hole is where the heading says; an OpenCRG road's track is chosen by
 * its lateral offset; bad options are refused naming them.
 * Prints one line per failed check; exits 1 if any failed.
 *
 *   capi_stretch ROAD_CSV ROAD_CRG   (inputs/roads/chuckhole.csv: a hole from x = 0 to 0.76 m;
 *                                     inputs/roads/handmade_straight.crg) */
#include <math.h>
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

static tirefe_tire* open_with(const tirefe_options* options) {
  char error[512];
  tirefe_tire* tire = NULL;
  if (tirefe_open("tires.145SR12", NULL, 0, options, &tire, error, sizeof error) != TIREFE_OK)
    printf("FAILED: open tires.145SR12 (%s)\n", error);
  return tire;
}

/* Opened 1 mm down, frictionless: the static curve's force there, bit for bit (the same
 * press), and held there 20 steps it stays (before, the first held step doubled it and the
 * next emptied it: the rim's acceleration under its load). */
static void check_start_z(void) {
  tirefe_options options;
  tirefe_default_options(&options);
  options.friction = 0.0;
  options.start_z = -1e-3;
  tirefe_tire* tire = open_with(&options);
  if (!tire) return;
  double expected = 0.0;
  const double deflection = 1e-3;
  char error[512];
  check(tirefe_static_forces("tires.145SR12", NULL, 0, &deflection, 1, &expected, error, sizeof error) == TIREFE_OK,
        "static forces", error);
  tirefe_spindle_state state;
  tirefe_state(tire, &state);
  check(state.position[1] == -1e-3 && state.force[1] == expected && expected > 100.0,
        "opened at start_z: there, with the static force", NULL);
  double largest = 0.0;
  for (int step = 0; step < 20; ++step) {
    const tirefe_spindle_motion held = {1e-3, 0.0, -1e-3, 0.0};
    tirefe_spindle_force reply;
    check(tirefe_solve(tire, &held, &reply) == TIREFE_OK && tirefe_commit(tire) == TIREFE_OK, "a held step",
          tirefe_message(tire));
    largest = fmax(largest, fabs(reply.force[1] - expected));
  }
  char detail[64];
  snprintf(detail, sizeof detail, "|Fz - static| up to %.3g N", largest);
  check(largest < 1e-9 * expected, "held where it started, the force stays", detail);
  tirefe_close(tire);
}

/* 2.5 ms in steps of at most 1 ms: three equal steps (not 1, 1 and 0.5 ms: a change of
 * step size sets a fast rolling tire's contact patch ringing), so the force of three
 * tirefe_solve steps of 2.5/3 ms to the cubic's points (rest to rest: a smoothstep). */
static void check_equal_steps(void) {
  tirefe_tire* advanced = open_with(NULL);
  tirefe_tire* stepped = open_with(NULL);
  if (!advanced || !stepped) return;
  const double depth = -1e-4, duration = 2.5e-3;
  tirefe_advance_report report;
  const tirefe_spindle_path path = {duration, {0.0, 0.0, 0.0}, {0.0, depth, 0.0}, {0.0, 0.0, 0.0}};
  check(tirefe_advance(advanced, &path, 1e-3, &report) == TIREFE_OK && report.steps == 3, "three steps",
        tirefe_message(advanced));
  tirefe_spindle_force reply;
  for (int k = 1; k <= 3; ++k) {
    const double s = k / 3.0;
    const tirefe_spindle_motion motion = {duration / 3.0, 0.0, depth * s * s * (3.0 - 2.0 * s), 0.0};
    check(tirefe_solve(stepped, &motion, &reply) == TIREFE_OK && tirefe_commit(stepped) == TIREFE_OK,
          "a third of the stretch", tirefe_message(stepped));
  }
  tirefe_spindle_state by_advance, by_steps;
  tirefe_state(advanced, &by_advance);
  tirefe_state(stepped, &by_steps);
  char detail[128];
  snprintf(detail, sizeof detail, "Fz %.17g N stretched, %.17g N stepped", by_advance.force[1], by_steps.force[1]);
  check(fabs(by_advance.force[1] - by_steps.force[1]) < 1e-9 * fabs(by_steps.force[1]) && by_steps.force[1] != 0.0,
        "the stretch's steps are equal", detail);
  tirefe_close(advanced);
  tirefe_close(stepped);
}

static void check_stretches(void) {
  tirefe_tire* tire = open_with(NULL);
  if (!tire) return;
  tirefe_advance_report report;
  const tirefe_spindle_path nowhere = {0.0, {0.0, 0.0, 0.0}, {0.0, -1e-3, 0.0}, {0.0, 0.0, 0.0}};
  check(tirefe_advance(tire, &nowhere, 1e-3, &report) == TIREFE_INVALID_ARGUMENT, "a stretch of no time",
        tirefe_message(tire));
  check(strstr(tirefe_message(tire), "duration") != NULL, "the message names the duration", tirefe_message(tire));
  const tirefe_spindle_path nan_rate = {1e-2, {NAN, 0.0, 0.0}, {0.0, -1e-3, 0.0}, {0.0, 0.0, 0.0}};
  check(tirefe_advance(tire, &nan_rate, 1e-3, &report) == TIREFE_INVALID_ARGUMENT, "a NaN rate", tirefe_message(tire));
  check(tirefe_advance(tire, &nowhere, 0.0, &report) == TIREFE_INVALID_ARGUMENT, "max_step 0", tirefe_message(tire));
  check(tirefe_advance(tire, NULL, 1e-3, &report) == TIREFE_INVALID_ARGUMENT, "a NULL path", NULL);

  /* 2 mm down in 50 ms, in steps of 5 ms: ten of them, ending where and when asked. */
  tirefe_spindle_state before, after;
  tirefe_state(tire, &before);
  const tirefe_spindle_path press = {5e-2, {0.0, 0.0, 0.0}, {0.0, -2e-3, 0.0}, {0.0, 0.0, 0.0}};
  check(tirefe_advance(tire, &press, 5e-3, &report) == TIREFE_OK, "a 50 ms stretch", tirefe_message(tire));
  tirefe_state(tire, &after);
  check(report.steps == 10 && report.cuts == 0 && report.time == after.time, "ten steps of 5 ms, the time reported",
        NULL);
  char detail[160];
  snprintf(detail, sizeof detail, "after %.17g s at z = %.17g m, Fz = %g N", after.time - before.time,
           after.position[1], after.force[1]);
  check(
      fabs(after.time - before.time - 5e-2) < 1e-14 && fabs(after.position[1] + 2e-3) < 1e-15 && after.force[1] > 200.0,
      "at the end, where asked and loaded", detail);

  /* Through the rim in 1 ms: the steps are cut, the tire stays at the last it committed,
   * and the message says where along the stretch, not the tire's own clock. */
  const tirefe_spindle_path crush = {1e-3, {0.0, 0.0, 0.0}, {0.0, -0.4, 0.0}, {0.0, 0.0, 0.0}};
  check(tirefe_advance(tire, &crush, 1e-3, &report) == TIREFE_STEP_FAILED, "a crushing stretch fails",
        tirefe_message(tire));
  check(strstr(tirefe_message(tire), "s into its 0.001 s") != NULL && strstr(tirefe_message(tire), " t = ") == NULL,
        "the message says where along the stretch", tirefe_message(tire));
  tirefe_state(tire, &before);
  check(report.cuts > 0 && report.time == before.time && before.time >= after.time && before.time < after.time + 1e-3,
        "it stopped within the stretch, where the report says", NULL);
  tirefe_close(tire);
}

/* The wheel pressed 5 mm at x = 0, then rolled 0.175 m ahead in 0.2 s on 'options' road.
 * Returns Fz before and after. */
static void roll_on(tirefe_options* options, double fz[2]) {
  options->start_z = -5e-3;
  options->hht_alpha = -0.1;
  tirefe_tire* tire = open_with(options);
  fz[0] = fz[1] = NAN;
  if (!tire) return;
  tirefe_spindle_state state;
  tirefe_state(tire, &state);
  fz[0] = state.force[1];
  double rate = 0.0;
  for (int k = 1; k <= 20; ++k) { /* 1 m/s, reached smoothly in 50 ms */
    const double t = k * 0.01, s = fmin(t / 0.05, 1.0);
    const double x = t <= 0.05 ? 0.05 * s * s * s * (1.0 - 0.5 * s) : 0.025 + (t - 0.05);
    const double end_rate = s * s * (3.0 - 2.0 * s);
    const tirefe_spindle_path path = {0.01, {rate, 0.0, 0.0}, {x, -5e-3, 0.0}, {end_rate, 0.0, 0.0}};
    if (tirefe_advance(tire, &path, 1e-3, NULL) != TIREFE_OK) {
      check(0, "rolling on the road", tirefe_message(tire));
      break;
    }
    rate = end_rate;
  }
  tirefe_state(tire, &state);
  fz[1] = state.force[1];
  tirefe_close(tire);
}

/* Rolled from 0.1 m before the hole (along its heading): then it is over the hole,
 * whichever way it heads, touching the road no more (what is left is the belt's swing).
 * The track "right" of the file is flat: then the same as a flat road. */
static void roll_toward_the_hole(const char* road, const char* track, int heading, double fz[2]) {
  tirefe_options options;
  tirefe_default_options(&options);
  options.road = road;
  options.road_track = track;
  options.road_start = 0.1;
  options.heading = heading;
  roll_on(&options, fz);
}

static void check_roads(const char* road) {
  double flat[2], right[2], plus[2], minus[2];
  roll_toward_the_hole(NULL, NULL, 1, flat);
  roll_toward_the_hole(road, "right", 1, right);
  roll_toward_the_hole(road, "left", 1, plus);
  roll_toward_the_hole(road, "left", -1, minus);
  char detail[160];
  snprintf(detail, sizeof detail, "flat %g -> %g N, right %g -> %g N", flat[0], flat[1], right[0], right[1]);
  check(fabs(right[0] - flat[0]) < 1e-9 * flat[0] && fabs(right[1] - flat[1]) < 1e-6 * flat[0] && flat[1] > 500.0,
        "the file's flat track is the flat road", detail);
  snprintf(detail, sizeof detail, "heading +x %g -> %g N, -x %g -> %g N", plus[0], plus[1], minus[0], minus[1]);
  check(fabs(plus[0] - flat[0]) < 1e-9 * flat[0] && fabs(minus[0] - flat[0]) < 1e-9 * flat[0] &&
            fabs(plus[1]) < 0.05 * flat[0] && fabs(minus[1]) < 0.05 * flat[0],
        "the hole lies ahead along the heading, either way", detail);

  tirefe_options options;
  tirefe_default_options(&options);
  options.road = road;
  options.road_track = "middle";
  char error[512];
  tirefe_tire* tire = NULL;
  check(tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) == TIREFE_INVALID_ARGUMENT &&
            strstr(error, "road_track") && strstr(error, "middle"),
        "an unknown track is refused, naming it", error);
  options.road_track = NULL;
  check(tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) == TIREFE_MODEL_ERROR &&
            strstr(error, "chuckhole.csv") && strstr(error, "track"),
        "a file with two tracks and none chosen is refused, naming the file", error);
  options.road = "road.txt";
  check(tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) == TIREFE_MODEL_ERROR &&
            strstr(error, "road.txt") && strstr(error, ".rdf"),
        "a road file of another kind is refused, naming what is read", error);
  check(tire == NULL, "no tire after a refused road", NULL);
}

/* Rolled from u = 1 m of handmade_straight.crg on the track road_lateral picks: 1 m left of
 * the reference line it is flat to u = 2 m (the flat road's forces); 0.75 m left it rises
 * 5.6 mm per metre from u = 1 m (loaded more). Returns the rise of Fz over the roll. */
static double roll_on_the_crg(const char* crg, double lateral, double fz[2]) {
  tirefe_options options;
  tirefe_default_options(&options);
  options.road = crg;
  options.road_lateral = lateral;
  options.road_start = -1.0;
  roll_on(&options, fz);
  return fz[1] - fz[0];
}

static void check_opencrg(const char* crg) {
  double flat[2], left[2], rising[2];
  tirefe_options options;
  tirefe_default_options(&options);
  roll_on(&options, flat);
  roll_on_the_crg(crg, 1.0, left);
  char detail[160];
  snprintf(detail, sizeof detail, "flat %g -> %g N, v = 1 m %g -> %g N", flat[0], flat[1], left[0], left[1]);
  check(fabs(left[0] - flat[0]) < 1e-9 * flat[0] && fabs(left[1] - flat[1]) < 1e-6 * flat[0],
        "the OpenCRG road's flat track 1 m left is the flat road", detail);
  const double gain = roll_on_the_crg(crg, 0.75, rising) - (flat[1] - flat[0]);
  snprintf(detail, sizeof detail, "v = 0.75 m: %g -> %g N; flat: %g -> %g N", rising[0], rising[1], flat[0], flat[1]);
  /* 168 N more than on the flat road: the road under the wheel rose 0.97 mm in the roll. */
  check(gain > 140.0 && gain < 200.0, "its track 0.75 m left rises under the wheel", detail);

  options.road = crg;
  char error[512];
  tirefe_tire* tire = NULL;
  options.road_lateral = 1.6;
  check(tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) == TIREFE_MODEL_ERROR &&
            strstr(error, "handmade_straight.crg:") &&
            strstr(error, "lateral position v = 1.6 m lies outside the road's long sections (v from -1.5 to 1.5 m)"),
        "a track beside the road is refused, naming the file and the road's width", error);
  options.road_lateral = NAN;
  check(tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) == TIREFE_INVALID_ARGUMENT &&
            strstr(error, "options.road_lateral must be a finite"),
        "a NaN offset is refused, naming road_lateral", error);
  options.road_lateral = 0.0;
  options.road_track = "left";
  check(tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) == TIREFE_INVALID_ARGUMENT &&
            strstr(error, "road_track") && strstr(error, "road_lateral"),
        "road_track on an OpenCRG road is refused, naming road_lateral", error);
  options.road_track = NULL;
  options.road = NULL;
  options.road_lateral = 0.5;
  check(tirefe_open("tires.145SR12", NULL, 0, &options, &tire, error, sizeof error) == TIREFE_INVALID_ARGUMENT &&
            strstr(error, "road_lateral"),
        "road_lateral on the flat road is refused", error);
  check(tire == NULL, "no tire after a refused road", NULL);
}

int main(int argc, char** argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: capi_stretch ROAD_CSV ROAD_CRG\n");
    return 2;
  }
  check_start_z();
  check_stretches();
  check_equal_steps();
  check_roads(argv[1]);
  check_opencrg(argv[2]);
  printf("%s\n", failures ? "C API stretches and roads: failed" : "C API stretches and roads: passed");
  return failures ? 1 : 0;
}
