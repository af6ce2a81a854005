/* A hostile host of the C API (include/tirefe.h), the host's side of the bad-deck
 * catalogue: every misuse a careless or malicious host program commits (NULL, closed,
 * freed and made-up handles, calls out of order, arguments out of range, files that are
 * no files, decks that never end), each with the status and the text of the one-line
 * message it must get. Nothing may crash, hang or be accepted silently. Prints one line
 * per probe that got something else and a summary; exits 1 if any probe failed.
 *
 *   capi_abuser              (CAPI_ABUSER_VERBOSE=1: every probe's status and message) */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "tirefe.h"

static int probes = 0, failures = 0;
static char folder[] = "/tmp/tirefe_capi_abuser_XXXXXX";

/* One probe: 'got' must be 'expected' and the message must hold 'text' on one line (an
 * empty 'text': any message, or none after a success). */
static void expect(const char* what, tirefe_status got, tirefe_status expected, const char* message, const char* text) {
  ++probes;
  if (getenv("CAPI_ABUSER_VERBOSE")) printf("%-60s %d  %s\n", what, (int)got, message ? message : "");
  const int text_ok = text[0] == '\0' || (message && strstr(message, text) != NULL);
  const int one_line = !message || strchr(message, '\n') == NULL;
  const int said = expected == TIREFE_OK || (message && message[0] != '\0');
  if (got == expected && text_ok && one_line && said) return;
  ++failures;
  printf("FAILED: %s: status %d (expected %d), message '%s' (expected '%s')\n", what, (int)got, (int)expected,
         message ? message : "(null)", text);
}

/* A call on a handle, then its message: in one expect() call C would be free to read the
 * message first, before the call replaces it. */
#define EXPECT(handle, what, call, status, text)              \
  do {                                                        \
    const tirefe_status got_ = (call);                        \
    expect(what, got_, status, tirefe_message(handle), text); \
  } while (0)

/* A call with no message to read (tirefe_free_state; an error buffer not given): its status. */
static void expect_status(const char* what, tirefe_status got, tirefe_status expected) {
  expect(what, got, expected, "(no message to read)", "");
}

static const char* path_in(const char* name) {
  static char paths[8][512];
  static int next = 0;
  char* path = paths[next++ % 8];
  snprintf(path, sizeof paths[0], "%s/%s", folder, name);
  return path;
}

static const char* write_file(const char* name, const char* text) {
  const char* path = path_in(name);
  FILE* file = fopen(path, "w");
  if (file) {
    fputs(text, file);
    fclose(file);
  }
  return path;
}

static tirefe_tire* open_tire(const char* source) {
  char error[512];
  tirefe_tire* tire = NULL;
  if (tirefe_open(source, NULL, 0, NULL, &tire, error, sizeof error) != TIREFE_OK) {
    printf("FAILED: open %s (%s)\n", source, error);
    ++failures;
  }
  return tire;
}

static double seconds_since(const struct timespec* start) {
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return (double)(now.tv_sec - start->tv_sec) + 1e-9 * (double)(now.tv_nsec - start->tv_nsec);
}

/* Calls tirefe_cancel after 'delay' seconds: a host's deadline. */
static void* cancel_after(void* delay) {
  const double seconds = *(const double*)delay;
  const struct timespec wait = {(time_t)seconds, (long)(1e9 * (seconds - (double)(time_t)seconds))};
  nanosleep(&wait, NULL);
  tirefe_cancel();
  return NULL;
}

/* Handles: NULL, made up, closed, freed, of the other kind. None is dereferenced. */
static void abuse_handles(void) {
  tirefe_spindle_force reply;
  tirefe_spindle_state state;
  const tirefe_spindle_motion motion = {1e-3, 0.0, 0.0, 0.0};
  const double velocity[3] = {0.0, 0.0, 0.0};
  double level;
  tirefe_saved_state* saved = NULL;

  EXPECT(NULL, "solve on NULL", tirefe_solve(NULL, &motion, &reply), TIREFE_INVALID_ARGUMENT, "no tire (NULL handle)");
  EXPECT(NULL, "commit on NULL", tirefe_commit(NULL), TIREFE_INVALID_ARGUMENT, "NULL handle");
  expect("close NULL (as free(NULL))", tirefe_close(NULL), TIREFE_OK, NULL, "");
  expect("free_state NULL (as free(NULL))", tirefe_free_state(NULL), TIREFE_OK, NULL, "");

  long garbage_words[8] = {0};
  tirefe_tire* made_up = (tirefe_tire*)garbage_words;
  EXPECT(made_up, "solve on a made-up handle", tirefe_solve(made_up, &motion, &reply), TIREFE_INVALID_ARGUMENT,
         "not an open tire");
  EXPECT(made_up, "solve_velocity on a made-up handle", tirefe_solve_velocity(made_up, 1e-3, velocity, &reply),
         TIREFE_INVALID_ARGUMENT, "not an open tire");
  EXPECT(made_up, "state of a made-up handle", tirefe_state(made_up, &state), TIREFE_INVALID_ARGUMENT,
         "not an open tire");
  EXPECT(made_up, "road level of a made-up handle", tirefe_road_level(made_up, &level), TIREFE_INVALID_ARGUMENT,
         "not an open tire");
  EXPECT(made_up, "revert on a made-up handle", tirefe_revert(made_up), TIREFE_INVALID_ARGUMENT, "not an open tire");
  EXPECT(made_up, "save a made-up handle", tirefe_save_state(made_up, &saved), TIREFE_INVALID_ARGUMENT,
         "not an open tire");
  EXPECT(made_up, "close a made-up handle", tirefe_close(made_up), TIREFE_INVALID_ARGUMENT, "not an open tire");
  EXPECT((tirefe_tire*)1, "close a handle of 1", tirefe_close((tirefe_tire*)1), TIREFE_INVALID_ARGUMENT,
         "not an open tire");
  expect_status("free a made-up state", tirefe_free_state((tirefe_saved_state*)garbage_words), TIREFE_INVALID_ARGUMENT);

  tirefe_tire* tire = open_tire("tires.145SR12");
  tirefe_tire* closed = open_tire("tires.145SR12");
  if (!tire || !closed) return;
  expect("close", tirefe_close(closed), TIREFE_OK, NULL, "");
  EXPECT(closed, "solve on a closed tire", tirefe_solve(closed, &motion, &reply), TIREFE_INVALID_ARGUMENT,
         "not an open tire");
  EXPECT(closed, "close twice", tirefe_close(closed), TIREFE_INVALID_ARGUMENT, "not an open tire");

  EXPECT(tire, "save_state with NULL out", tirefe_save_state(tire, NULL), TIREFE_INVALID_ARGUMENT,
         "saved must not be NULL");
  EXPECT(tire, "save_state", tirefe_save_state(tire, &saved), TIREFE_OK, "");
  EXPECT(tire, "restore a tire handle as a state", tirefe_restore_state(tire, (const tirefe_saved_state*)tire),
         TIREFE_INVALID_ARGUMENT, "saved is no state of tirefe_save_state");
  EXPECT((tirefe_tire*)saved, "a state handle as a tire", tirefe_commit((tirefe_tire*)saved), TIREFE_INVALID_ARGUMENT,
         "not an open tire");
  EXPECT(tire, "restore NULL", tirefe_restore_state(tire, NULL), TIREFE_INVALID_ARGUMENT, "saved must not be NULL");
  expect("free_state", tirefe_free_state(saved), TIREFE_OK, NULL, "");
  EXPECT(tire, "restore a freed state", tirefe_restore_state(tire, saved), TIREFE_INVALID_ARGUMENT,
         "saved is no state of tirefe_save_state (freed, or never saved)");
  expect_status("free a state twice", tirefe_free_state(saved), TIREFE_INVALID_ARGUMENT);

  /* A state of another tire (another mesh) is refused by the checkpoint's checks. */
  char error[512];
  tirefe_tire* coarse = NULL;
  const tirefe_parameter elements[] = {{"elements", 60}};
  expect("open a coarser tire", tirefe_open("tires.145SR12", elements, 1, NULL, &coarse, error, sizeof error),
         TIREFE_OK, error, "");
  tirefe_saved_state* other = NULL;
  if (coarse && tirefe_save_state(coarse, &other) == TIREFE_OK) {
    EXPECT(tire, "restore another tire's state", tirefe_restore_state(tire, other), TIREFE_INVALID_ARGUMENT,
           "saved is the state of another tire (of 61 nodes, this one has 101): restore a state into a tire built "
           "with the same parameters");
    tirefe_free_state(other);
  }
  tirefe_close(coarse);
  tirefe_close(tire);
}

/* tirefe_open: arguments, options, overrides and sources that are no tire. */
static void abuse_open(void) {
  char error[512];
  tirefe_tire* tire = NULL;
  tirefe_options options;
#define OPEN_WITH(what, source, overrides, count, options, status, text)                                           \
  do {                                                                                                             \
    tire = (tirefe_tire*)error;                                                                                    \
    expect(what, tirefe_open(source, overrides, count, options, &tire, error, sizeof error), status, error, text); \
    if (tire != NULL) expect(what " leaves no handle", TIREFE_MODEL_ERROR, TIREFE_OK, "", "");                     \
  } while (0)
  OPEN_WITH("NULL source", NULL, NULL, 0, NULL, TIREFE_INVALID_ARGUMENT, "source and tire must not be NULL");
  expect("NULL tire out", tirefe_open("tires.145SR12", NULL, 0, NULL, NULL, error, sizeof error),
         TIREFE_INVALID_ARGUMENT, error, "source and tire must not be NULL");
  OPEN_WITH("NULL overrides with a count", "tires.145SR12", NULL, 2, NULL, TIREFE_INVALID_ARGUMENT,
            "nor overrides when count > 0");

  const tirefe_parameter no_name[] = {{NULL, 1.0}};
  OPEN_WITH("an override without a name", "tires.145SR12", no_name, 1, NULL, TIREFE_INVALID_ARGUMENT,
            "override 0 has no name");
  const tirefe_parameter infinite[] = {{"pressure", INFINITY}};
  OPEN_WITH("an infinite override", "tires.145SR12", infinite, 1, NULL, TIREFE_INVALID_ARGUMENT,
            "override 'pressure' is not a finite number");
  const tirefe_parameter twice[] = {{"pressure", 180e3}, {"pressure", 200e3}};
  OPEN_WITH("an override given twice", "tires.145SR12", twice, 2, NULL, TIREFE_INVALID_ARGUMENT,
            "override 'pressure' is given twice");
  const tirefe_parameter misspelt[] = {{"presure", 180e3}};
  OPEN_WITH("a misspelt override", "tires.145SR12", misspelt, 1, NULL, TIREFE_MODEL_ERROR, "presure");
  const tirefe_parameter empty_name[] = {{"", 1.0}};
  OPEN_WITH("an override named ''", "tires.145SR12", empty_name, 1, NULL, TIREFE_MODEL_ERROR, "unknown key ''");
  const tirefe_parameter no_elements[] = {{"elements", 0}};
  OPEN_WITH("zero elements", "tires.145SR12", no_elements, 1, NULL, TIREFE_MODEL_ERROR, "elements");
  const tirefe_parameter half_element[] = {{"elements", 100.5}};
  OPEN_WITH("a fractional element count", "tires.145SR12", half_element, 1, NULL, TIREFE_MODEL_ERROR,
            "key 'elements' must be an integer");
  const tirefe_parameter wrapping[] = {{"elements", 4294967396.0}};
  OPEN_WITH("an element count that would wrap", "tires.145SR12", wrapping, 1, NULL, TIREFE_MODEL_ERROR,
            "key 'elements' must be an integer from 1 to 100000");
  const tirefe_parameter no_pressure[] = {{"pressure", 0.0}};
  OPEN_WITH("zero pressure", "tires.145SR12", no_pressure, 1, NULL, TIREFE_MODEL_ERROR,
            "parameter 'pressure' is 0 Pa: a tire on the road is inflated before it touches it; give a "
            "pressure > 0");
  const tirefe_parameter huge_pressure[] = {{"pressure", 1e300}};
  OPEN_WITH("a pressure of 1e300 Pa", "tires.145SR12", huge_pressure, 1, NULL, TIREFE_MODEL_ERROR,
            "the tire cannot be inflated on its hub with these parameters (the residual is not finite");

  tirefe_default_options(&options);
  options.friction = NAN;
  OPEN_WITH("friction NaN", "tires.145SR12", NULL, 0, &options, TIREFE_INVALID_ARGUMENT,
            "options.friction must be a finite number >= 0");
  options.friction = -0.1;
  OPEN_WITH("negative friction", "tires.145SR12", NULL, 0, &options, TIREFE_INVALID_ARGUMENT, "options.friction");
  tirefe_default_options(&options);
  options.hht_alpha = NAN;
  OPEN_WITH("alpha NaN", "tires.145SR12", NULL, 0, &options, TIREFE_MODEL_ERROR, "alpha");
  options.hht_alpha = -0.5;
  OPEN_WITH("alpha below -1/3", "tires.145SR12", NULL, 0, &options, TIREFE_MODEL_ERROR, "alpha");
  tirefe_default_options(&options);
  options.free_spin = 2;
  OPEN_WITH("free_spin 2", "tires.145SR12", NULL, 0, &options, TIREFE_INVALID_ARGUMENT,
            "options.free_spin must be 1 (the wheel turns freely) or 0 (the host drives the spin)");
  tirefe_default_options(&options);
  options.road_track = "middle";
  OPEN_WITH("a road track without a road", "tires.145SR12", NULL, 0, &options, TIREFE_INVALID_ARGUMENT,
            "options.road_track is \"middle\" but options.road names no road file: give both, or neither");
  tirefe_default_options(&options);
  options.heading = 2;
  OPEN_WITH("heading 2", "tires.145SR12", NULL, 0, &options, TIREFE_INVALID_ARGUMENT, "options.heading must be +1");

  OPEN_WITH("a missing property file", path_in("missing.tir"), NULL, 0, NULL, TIREFE_MODEL_ERROR, "missing.tir");
  OPEN_WITH("an unknown module", "tires.no_such_tire", NULL, 0, NULL, TIREFE_MODEL_ERROR,
            "module 'tires.no_such_tire' not found");
  OPEN_WITH("a module name climbing out", "../etc/passwd", NULL, 0, NULL, TIREFE_MODEL_ERROR,
            "invalid module name '../etc/passwd'");
  OPEN_WITH("an empty source", "", NULL, 0, NULL, TIREFE_MODEL_ERROR, "invalid module name ''");
  mkdir(path_in("folder.tir"), 0755);
  OPEN_WITH("a folder named .tir", path_in("folder.tir"), NULL, 0, NULL, TIREFE_MODEL_ERROR,
            "folder.tir' is a folder; give a file");
  mkfifo(path_in("fifo.tir"), 0644);
  OPEN_WITH("a FIFO named .tir (would block)", path_in("fifo.tir"), NULL, 0, NULL, TIREFE_MODEL_ERROR,
            "fifo.tir' is no regular file (a FIFO or a device would block the read or never end it)");
  symlink("/dev/zero", path_in("zero.tir"));
  OPEN_WITH("a link to /dev/zero named .tir (would never end)", path_in("zero.tir"), NULL, 0, NULL, TIREFE_MODEL_ERROR,
            "zero.tir' is no regular file");
  OPEN_WITH("an empty property file", write_file("empty.tir", ""), NULL, 0, NULL, TIREFE_MODEL_ERROR, "empty.tir");

  /* The error buffer: truncated and terminated, or not written at all. */
  char tiny[4] = {'x', 'x', 'x', 'x'};
  tirefe_open(NULL, NULL, 0, NULL, &tire, tiny, sizeof tiny);
  expect("a 4-byte error buffer is terminated", tiny[3] == '\0' ? TIREFE_OK : TIREFE_INTERNAL_ERROR, TIREFE_OK, NULL,
         "");
  expect_status("no error buffer", tirefe_open(NULL, NULL, 0, NULL, &tire, NULL, 100), TIREFE_INVALID_ARGUMENT);
  expect_status("an error buffer of size 0", tirefe_open(NULL, NULL, 0, NULL, &tire, tiny, 0), TIREFE_INVALID_ARGUMENT);
#undef OPEN_WITH
}

/* Calls on an open tire: out of order, arguments NULL, not finite or out of range. */
static void abuse_steps(void) {
  tirefe_tire* tire = open_tire("tires.145SR12");
  if (!tire) return;
  tirefe_spindle_force reply;
  tirefe_spindle_state state;
  double level;
  const tirefe_spindle_motion still = {1e-3, 0.0, 0.0, 0.0};
#define SOLVE(what, h, x, z, spin, status, text)                           \
  do {                                                                     \
    const tirefe_spindle_motion motion = {h, x, z, spin};                  \
    EXPECT(tire, what, tirefe_solve(tire, &motion, &reply), status, text); \
  } while (0)
  EXPECT(tire, "commit before any solve", tirefe_commit(tire), TIREFE_INVALID_CALL,
         "tirefe_commit: no solved trial step to accept");
  EXPECT(tire, "solve with NULL motion", tirefe_solve(tire, NULL, &reply), TIREFE_INVALID_ARGUMENT,
         "motion and out must not be NULL");
  EXPECT(tire, "solve with NULL out", tirefe_solve(tire, &still, NULL), TIREFE_INVALID_ARGUMENT,
         "motion and out must not be NULL");
  SOLVE("a zero step", 0.0, 0.0, 0.0, 0.0, TIREFE_INVALID_ARGUMENT,
        "the time step must be a finite number > 0 (got 0)");
  SOLVE("a negative step", -1e-3, 0.0, 0.0, 0.0, TIREFE_INVALID_ARGUMENT, "the time step must be a finite number > 0");
  SOLVE("a NaN step", NAN, 0.0, 0.0, 0.0, TIREFE_INVALID_ARGUMENT, "the time step must be a finite number > 0");
  SOLVE("an infinite step", INFINITY, 0.0, 0.0, 0.0, TIREFE_INVALID_ARGUMENT, "the time step must be a finite number");
  SOLVE("a step of 1e-12 s", 1e-12, 0.0, 0.0, 0.0, TIREFE_INVALID_ARGUMENT,
        "the time step 1e-12 s is below 1e-07 s, where round-off swamps the tire's inertia");
  SOLVE("a NaN height", 1e-3, 0.0, NAN, 0.0, TIREFE_INVALID_ARGUMENT, "the spindle motion must be finite");
  SOLVE("an infinite x", 1e-3, INFINITY, 0.0, 0.0, TIREFE_INVALID_ARGUMENT, "the spindle motion must be finite");
  SOLVE("a NaN spin (ignored when free, refused all the same)", 1e-3, 0.0, 0.0, NAN, TIREFE_INVALID_ARGUMENT,
        "the spindle motion must be finite");
  SOLVE("the spindle through the road in one step", 1e-3, 0.0, -0.4, 0.0, TIREFE_STEP_FAILED, "");
  SOLVE("the spindle a kilometre away", 1e-3, 1000.0, 0.0, 0.0, TIREFE_STEP_FAILED, "");
  EXPECT(tire, "commit after a failed solve", tirefe_commit(tire), TIREFE_INVALID_CALL, "no solved trial step");
  SOLVE("the spindle held still", 1e-3, 0.0, 0.0, 0.0, TIREFE_OK, "");
  SOLVE("a step of 1e-7 s, the shortest", 1e-7, 0.0, 0.0, 0.0, TIREFE_OK, "");
  expect("a step of 1e-7 s: a finite, bounded force", fabs(reply.force[1]) < 1e3 ? TIREFE_OK : TIREFE_STEP_FAILED,
         TIREFE_OK, NULL, "");
  expect("commit", tirefe_commit(tire), TIREFE_OK, NULL, "");
  EXPECT(tire, "commit twice", tirefe_commit(tire), TIREFE_INVALID_CALL, "no solved trial step");
  expect("revert without a trial", tirefe_revert(tire), TIREFE_OK, NULL, "");

  const double velocity[3] = {0.0, NAN, 0.0}, still_velocity[3] = {0.0, 0.0, 0.0};
  EXPECT(tire, "solve_velocity with NULL velocity", tirefe_solve_velocity(tire, 1e-3, NULL, &reply),
         TIREFE_INVALID_ARGUMENT, "velocity and out must not be NULL");
  EXPECT(tire, "solve_velocity with a NaN velocity", tirefe_solve_velocity(tire, 1e-3, velocity, &reply),
         TIREFE_INVALID_ARGUMENT, "the spindle velocity must be finite");
  EXPECT(tire, "solve_velocity with a step of 1e-9 s", tirefe_solve_velocity(tire, 1e-9, still_velocity, &reply),
         TIREFE_INVALID_ARGUMENT, "the time step 1e-09 s is below 1e-07 s");
  EXPECT(tire, "state with NULL out", tirefe_state(tire, NULL), TIREFE_INVALID_ARGUMENT, "state must not be NULL");
  EXPECT(tire, "road level with NULL out", tirefe_road_level(tire, NULL), TIREFE_INVALID_ARGUMENT,
         "level must not be NULL");
  expect("state", tirefe_state(tire, &state), TIREFE_OK, NULL, "");
  expect("the message after a success is empty", tirefe_message(tire)[0] == '\0' ? TIREFE_OK : TIREFE_INTERNAL_ERROR,
         TIREFE_OK, NULL, "");
  expect("road level", tirefe_road_level(tire, &level), TIREFE_OK, NULL, "");

  tirefe_spindle_path path = {1e-3, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  EXPECT(tire, "advance along a NULL path", tirefe_advance(tire, NULL, 1e-3, NULL), TIREFE_INVALID_ARGUMENT,
         "path must not be NULL");
  EXPECT(tire, "advance with max_step 0", tirefe_advance(tire, &path, 0.0, NULL), TIREFE_INVALID_ARGUMENT,
         "the path's duration and max_step must be finite numbers > 0");
  EXPECT(tire, "advance with max_step NaN", tirefe_advance(tire, &path, NAN, NULL), TIREFE_INVALID_ARGUMENT,
         "max_step must be finite numbers > 0");
  path.position[1] = NAN;
  EXPECT(tire, "advance to a NaN height", tirefe_advance(tire, &path, 1e-3, NULL), TIREFE_INVALID_ARGUMENT,
         "the path's rates and end position must be finite");
  path.position[1] = 0.0;
  path.duration = 1e-12;
  EXPECT(tire, "advance over 1e-12 s", tirefe_advance(tire, &path, 1e-3, NULL), TIREFE_INVALID_ARGUMENT,
         "a path of 1e-12 s in steps of at most 0.001 s: the time step 1e-12 s is below 1e-07 s");
  path.duration = 1e-3;
  EXPECT(tire, "advance in steps of at most 1e-12 s", tirefe_advance(tire, &path, 1e-12, NULL), TIREFE_INVALID_ARGUMENT,
         "a path of 0.001 s in steps of at most 1e-12 s: the time step 1e-12 s is below");
  EXPECT(tire, "advance as it should be", tirefe_advance(tire, &path, 1e-3, NULL), TIREFE_OK, "");
#undef SOLVE
  tirefe_close(tire);
}

/* tirefe_static_forces: arguments, and a long curve cancelled by a watchdog thread. */
static void abuse_static_forces(void) {
  char error[512];
  double deflections[3] = {0.005, NAN, 0.01}, forces[3];
  expect("static forces: NULL source", tirefe_static_forces(NULL, NULL, 0, deflections, 1, forces, error, sizeof error),
         TIREFE_INVALID_ARGUMENT, error, "must not be NULL");
  expect("static forces: NULL deflections",
         tirefe_static_forces("tires.145SR12", NULL, 0, NULL, 3, forces, error, sizeof error), TIREFE_INVALID_ARGUMENT,
         error, "must not be NULL");
  expect("static forces: NULL forces",
         tirefe_static_forces("tires.145SR12", NULL, 0, deflections, 3, NULL, error, sizeof error),
         TIREFE_INVALID_ARGUMENT, error, "must not be NULL");
  expect("static forces: a NaN deflection",
         tirefe_static_forces("tires.145SR12", NULL, 0, deflections, 3, forces, error, sizeof error),
         TIREFE_INVALID_ARGUMENT, error, "deflection 1 is not a finite number");
  expect("static forces: none", tirefe_static_forces("tires.145SR12", NULL, 0, NULL, 0, NULL, error, sizeof error),
         TIREFE_OK, error, "");

  enum { kMany = 200000 };
  double* many = malloc(kMany * sizeof(double));
  double* out = malloc(kMany * sizeof(double));
  for (int i = 0; i < kMany; ++i) many[i] = 0.001 + 0.01 * (i % 10) / 10.0;
  const double delay = 0.5;
  pthread_t watchdog;
  pthread_create(&watchdog, NULL, cancel_after, (void*)&delay);
  struct timespec start;
  clock_gettime(CLOCK_MONOTONIC, &start);
  expect("static forces: 200 000 deflections cancelled after 0.5 s",
         tirefe_static_forces("tires.145SR12", NULL, 0, many, kMany, out, error, sizeof error), TIREFE_CANCELLED, error,
         "stopped by tirefe_cancel after");
  pthread_join(watchdog, NULL);
  expect("static forces: the cancel stops it within 3 s", seconds_since(&start) < 3.0 ? TIREFE_OK : TIREFE_CANCELLED,
         TIREFE_OK, NULL, "");
  expect("static forces: the cancel is answered, the next call runs",
         tirefe_static_forces("tires.145SR12", NULL, 0, many, 1, out, error, sizeof error), TIREFE_OK, error, "");
  free(many);
  free(out);
}

static const char* kDeckTire =
    "local p = tirefe.parameters{ depth = 0.01, loop = 0 }\n"
    "local model = tirefe.model{ title = 'a tire for the abuser' }\n"
    "local tire, level = require('tire_on_road').inflated(model, require('tires.145SR12'))\n"
    "model:surface{ name = 'road', type = 'flat', point = { 0, level } }\n"
    "model:contact{ surface = 'road', set = tire.tread_set }\n"
    "model:integrator{ type = 'newmark' }\n"
    "model:load_function{ name = 'stuck', fn = function(t) if p.loop == 1 and t > 1.0015 then while true do end end "
    "return 0 end }\n"
    "model:load{ node = tire.spindle, fx = 1, load_function = 'stuck' }\n"
    "host_tire = { model = model, spindle = tire.spindle }\n";

/* tirefe_open_deck: arguments, decks that are no decks, name no tire, or never end. */
static void abuse_decks(void) {
  char error[512];
  tirefe_tire* tire = NULL;
  const char* out = path_in("out");
  const char* deck = write_file("tire_deck.lua", kDeckTire);
  const char* endless = write_file("endless.lua", "local n = 0\nwhile true do\n  n = n + 1\nend\n");
  const char* nameless = write_file("nameless.lua", "local model = tirefe.model{ title = 'no tire' }\n");
  const char* broken = write_file("broken.lua", "local model = tirefe.model{ title = 'broken' \n");
  mkfifo(path_in("fifo.lua"), 0644);
#define OPEN_DECK(what, deck, overrides, count, status, text)                                                     \
  do {                                                                                                            \
    tire = NULL;                                                                                                  \
    expect(what, tirefe_open_deck(deck, overrides, count, out, &tire, error, sizeof error), status, error, text); \
    if (tire) tirefe_close(tire);                                                                                 \
  } while (0)
  OPEN_DECK("NULL deck", NULL, NULL, 0, TIREFE_INVALID_ARGUMENT, "deck and tire must not be NULL");
  expect("an empty output folder", tirefe_open_deck(deck, NULL, 0, "", &tire, error, sizeof error),
         TIREFE_INVALID_ARGUMENT, error, "output_dir is empty: name a folder, or give NULL for \"results\"");
  const char* null_entry[] = {"depth=0.01", NULL};
  OPEN_DECK("a NULL override", deck, null_entry, 2, TIREFE_INVALID_ARGUMENT, "override 1 is NULL");
  const char* no_equals[] = {"depth"};
  OPEN_DECK("an override without '='", deck, no_equals, 1, TIREFE_INVALID_ARGUMENT,
            "override 'depth' is not key=value");
  const char* no_key[] = {"=0.01"};
  OPEN_DECK("an override without a key", deck, no_key, 1, TIREFE_INVALID_ARGUMENT, "is not key=value");
  const char* twice[] = {"depth=0.01", "depth=0.02"};
  OPEN_DECK("an override given twice", deck, twice, 2, TIREFE_INVALID_ARGUMENT, "override 'depth' is given twice");
  const char* undeclared[] = {"speed=3"};
  OPEN_DECK("an undeclared parameter", deck, undeclared, 1, TIREFE_MODEL_ERROR,
            "command-line parameter 'speed' is not declared by the deck");
  const char* not_a_number[] = {"depth=deep"};
  OPEN_DECK("a parameter of the wrong type", deck, not_a_number, 1, TIREFE_MODEL_ERROR,
            "command-line parameter 'depth=deep' must be a number like its default 0.01");
  OPEN_DECK("a missing deck", path_in("missing.lua"), NULL, 0, TIREFE_MODEL_ERROR, "missing.lua");
  OPEN_DECK("a folder as the deck", folder, NULL, 0, TIREFE_MODEL_ERROR, "is a folder; give a file");
  OPEN_DECK("a FIFO as the deck (would block)", path_in("fifo.lua"), NULL, 0, TIREFE_MODEL_ERROR,
            "fifo.lua' is no regular file");
  OPEN_DECK("a deck with a syntax error", broken, NULL, 0, TIREFE_MODEL_ERROR, "broken.lua:");
  OPEN_DECK("a deck that names no tire", nameless, NULL, 0, TIREFE_MODEL_ERROR,
            "the deck names no tire for the host: end it with host_tire = { model = model, spindle = tire.spindle }");

  /* A deck that never ends, given a deadline by a watchdog thread. */
  const double delay = 0.5;
  pthread_t watchdog;
  pthread_create(&watchdog, NULL, cancel_after, (void*)&delay);
  struct timespec start;
  clock_gettime(CLOCK_MONOTONIC, &start);
  OPEN_DECK("an endless deck, cancelled after 0.5 s", endless, NULL, 0, TIREFE_CANCELLED,
            "endless.lua:3: stopped by tirefe_cancel while the deck ran Lua code");
  pthread_join(watchdog, NULL);
  expect("an endless deck: the cancel stops it within 3 s", seconds_since(&start) < 3.0 ? TIREFE_OK : TIREFE_CANCELLED,
         TIREFE_OK, NULL, "");
  tire = NULL;
  expect("a deck after the cancel opens", tirefe_open_deck(deck, NULL, 0, out, &tire, error, sizeof error), TIREFE_OK,
         error, "");
  if (tire) {
    double level;
    tirefe_saved_state* saved = NULL;
    EXPECT(tire, "road level of a deck's tire", tirefe_road_level(tire, &level), TIREFE_INVALID_CALL,
           "a deck's tire: its roads are the deck's own");
    EXPECT(tire, "save a deck's tire", tirefe_save_state(tire, &saved), TIREFE_INVALID_CALL,
           "a deck's tire is saved with the deck's model:checkpoint");
    tirefe_close(tire);
  }

  /* A load function of the deck that loops in the host's step: cancelled. */
  const char* looping[] = {"loop=1"};
  tire = NULL;
  expect("a deck whose load function will loop opens",
         tirefe_open_deck(deck, looping, 1, out, &tire, error, sizeof error), TIREFE_OK, error, "");
  if (tire) {
    tirefe_spindle_force reply;
    const tirefe_spindle_motion motion = {1e-3, 0.0, -0.005, 0.0};
    EXPECT(tire, "a step with a well-behaved load", tirefe_solve(tire, &motion, &reply), TIREFE_OK, "");
    EXPECT(tire, "commit it", tirefe_commit(tire), TIREFE_OK, "");
    pthread_create(&watchdog, NULL, cancel_after, (void*)&delay);
    EXPECT(tire, "a step whose load function loops, cancelled", tirefe_solve(tire, &motion, &reply), TIREFE_CANCELLED,
           "stopped by tirefe_cancel while the deck ran Lua code");
    pthread_join(watchdog, NULL);
    EXPECT(tire, "commit of the cancelled step", tirefe_commit(tire), TIREFE_INVALID_CALL, "no solved trial step");
    pthread_create(&watchdog, NULL, cancel_after, (void*)&delay);
    EXPECT(tire, "the deck's Lua state after a cancel: cancelled again", tirefe_solve(tire, &motion, &reply),
           TIREFE_CANCELLED, "tire_deck.lua:7: stopped by tirefe_cancel while the deck ran Lua code");
    pthread_join(watchdog, NULL);
    tirefe_close(tire);
  }
#undef OPEN_DECK
}

/* Two threads on one handle: one closes it while the other steps on it. */
static tirefe_tire* shared_tire;
static void* step_shared(void* status) {
  tirefe_spindle_force reply;
  const tirefe_spindle_motion motion = {1e-3, 0.0, -1e-4, 0.0};
  for (int i = 0; i < 100000; ++i) { /* until the handle is gone */
    *(tirefe_status*)status = tirefe_solve(shared_tire, &motion, &reply);
    if (*(tirefe_status*)status != TIREFE_OK) break;
  }
  return NULL;
}

static void abuse_threads(void) {
  shared_tire = open_tire("tires.145SR12");
  if (!shared_tire) return;
  tirefe_status status = TIREFE_OK;
  pthread_t stepper;
  pthread_create(&stepper, NULL, step_shared, &status);
  const struct timespec wait = {0, 20 * 1000 * 1000};
  nanosleep(&wait, NULL);
  expect("close while another thread steps", tirefe_close(shared_tire), TIREFE_OK, NULL, "");
  pthread_join(stepper, NULL);
  expect("the stepping thread then finds no tire", status, TIREFE_INVALID_ARGUMENT, tirefe_message(shared_tire),
         "not an open tire");
}

static void remove_folder(void) {
  const char* names[] = {"tire_deck.lua", "endless.lua", "nameless.lua", "broken.lua", "fifo.lua",
                         "fifo.tir",      "zero.tir",    "empty.tir",    "missing.tir"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) unlink(path_in(names[i]));
  rmdir(path_in("folder.tir"));
  char command[600];
  snprintf(command, sizeof command, "rm -rf '%s'", folder);
  if (system(command) != 0) printf("could not remove %s\n", folder);
}

int main(void) {
  if (!mkdtemp(folder)) return 2;
  abuse_handles();
  abuse_open();
  abuse_steps();
  abuse_static_forces();
  abuse_decks();
  abuse_threads();
  remove_folder();
  printf("%d probes, %d failed\n", probes, failures);
  return failures == 0 ? 0 : 1;
}
