/* An FMI call-sequence player: loads an unpacked tirefe_tire.fmu with dlopen and drives it
 * through the FMI 2.0 functions only, in the sequences a master may call them and in ones
 * it should not, and prints one "key value" line per finding:
 *   Fz_start        Fz after initialization with the inputs z = -1 mm (the starting press)
 *   first_jump      the largest |Fz - Fz_start| / Fz_start over 50 steps of 1 ms held there
 *   repeat          1 if restoring a saved FMU state and stepping again gives the same bits
 *   discard         1 if the wheel centre held through the rim has a step discarded where
 *                   the tire stopped, with fmi2Terminated true and the next fmi2DoStep refused
 *   stopped_at      fmi2LastSuccessfulTime after that discard [s]
 *   second_exit     1 if a second fmi2ExitInitializationMode is refused and the FMU goes on
 *   reset           1 if fmi2Reset brings the parameters back to their start values and the
 *                   FMU then runs as a fresh instance does (the same bits)
 *   bad_time        1 if fmi2DoStep from t = NaN and from another time are refused, the FMU
 *                   staying at its time
 *   stray_handles   1 if a freed instance, a stray pointer and NULL get fmi2Error, and freeing
 *                   twice is harmless; the same for FMU states
 *   moving_start    1 if nonzero initial rates are refused with a message
 *   strings         1 if the String parameters read back, and the tire and road given on disk
 *                   as file://localhost/... URIs build the tire
 * The FMU's log goes to stderr as "[instance category status N] message". Exits 1 when a
 * call fails unexpectedly.
 *
 *   fmu_host UNPACKED_FMU_DIR TIRE_FILE ROAD_FILE */
#define _XOPEN_SOURCE 700
#include <ctype.h>
#include <dlfcn.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi_functions.h"
#include "fmi_support.h"

/* The FMI functions, by their standard names. */
static const fmi2CallbackFunctions callbacks = {fmi_logger, calloc, free, NULL, NULL};
static char guid[128], resources[3 * PATH_MAX];

static const fmi2ValueReference X_Z_SPIN[] = {0, 1, 2}, RATES[] = {6, 7, 8}, FORCES[] = {3, 4, 5}, FZ[] = {4},
                                PRESSURE[] = {10}, TIRE[] = {20}, ROAD[] = {21}, ROAD_TRACK[] = {22};

static void require(int condition, const char* what) {
  if (!condition) {
    fprintf(stderr, "fmu_host: %s failed\n", what);
    exit(1);
  }
}

/* An instance set up and initialized with pressure 180 kPa and the wheel centre at z. */
static fmi2Component started(const char* name, double z) {
  fmi2Component fmu = Instantiate(name, fmi2CoSimulation, guid, resources, &callbacks, fmi2False, fmi2False);
  const fmi2Real kilopascals_180[] = {180e3}, start[] = {0.0, z, 0.0};
  require(fmu && SetupExperiment(fmu, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK &&
              SetReal(fmu, PRESSURE, 1, kilopascals_180) == fmi2OK && SetReal(fmu, X_Z_SPIN, 3, start) == fmi2OK &&
              EnterInitializationMode(fmu) == fmi2OK && ExitInitializationMode(fmu) == fmi2OK,
          "instantiating and initializing");
  return fmu;
}

/* The press of tests/install/press_tire.c, as start-of-step inputs: z and its rate. */
static void press_step(fmi2Component fmu, int step) {
  const double s = step < 100 ? step / 100.0 : 1.0;
  const fmi2Real position[] = {0.0, -0.005 * s * s * (3.0 - 2.0 * s), 0.0};
  const fmi2Real rates[] = {0.0, step < 100 ? -0.005 * 6.0 * s * (1.0 - s) / 0.1 : 0.0, 0.0};
  require(SetReal(fmu, X_Z_SPIN, 3, position) == fmi2OK && SetReal(fmu, RATES, 3, rates) == fmi2OK &&
              DoStep(fmu, step * 1e-3, 1e-3, fmi2True) == fmi2OK,
          "a step of the press");
}

static double fz(fmi2Component fmu) {
  fmi2Real value = 0.0;
  require(GetReal(fmu, FZ, 1, &value) == fmi2OK, "fmi2GetReal(Fz)");
  return value;
}

/* Initial inputs z = -1 mm held: the tire starts pressed there and stays. */
static void starting_press(void) {
  fmi2Component fmu = started("tire", -1e-3);
  const double start = fz(fmu);
  double jump = 0.0;
  const fmi2Real held[] = {0.0, -1e-3, 0.0};
  for (int step = 0; step < 50; ++step) {
    require(SetReal(fmu, X_Z_SPIN, 3, held) == fmi2OK && DoStep(fmu, step * 1e-3, 1e-3, fmi2True) == fmi2OK,
            "a held step");
    jump = fmax(jump, fabs(fz(fmu) - start) / start);
  }
  printf("Fz_start %.17g\nfirst_jump %.17g\n", start, jump);
  FreeInstance(fmu);
}

/* Saved half-way through the press, restored, stepped again; then a step through the rim. */
static void states_and_discard(void) {
  fmi2Component fmu = started("tire", 0.0);
  fmi2FMUstate saved = NULL;
  for (int step = 0; step < 120; ++step) {
    if (step == 60) require(GetFMUstate(fmu, &saved) == fmi2OK, "fmi2GetFMUstate");
    press_step(fmu, step);
  }
  fmi2Real force[3], again[3];
  GetReal(fmu, FORCES, 3, force);
  require(SetFMUstate(fmu, saved) == fmi2OK, "fmi2SetFMUstate");
  for (int step = 60; step < 120; ++step) press_step(fmu, step);
  GetReal(fmu, FORCES, 3, again);
  require(FreeFMUstate(fmu, &saved) == fmi2OK && saved == NULL, "fmi2FreeFMUstate");
  printf("repeat %d\n", memcmp(force, again, sizeof force) == 0);

  /* Held 0.4 m down, through the rim: within a few steps the tire cannot go on. */
  const fmi2Real crush[] = {0.0, -0.4, 0.0};
  fmi2Status crushed = fmi2OK;
  int step = 120;
  for (; step < 130 && crushed == fmi2OK; ++step)
    crushed = SetReal(fmu, X_Z_SPIN, 3, crush) == fmi2OK ? DoStep(fmu, step * 1e-3, 1e-3, fmi2True) : fmi2Fatal;
  const double from = (step - 1) * 1e-3;
  fmi2Real stopped = -1.0;
  fmi2Boolean terminated = fmi2False;
  GetRealStatus(fmu, fmi2LastSuccessfulTime, &stopped);
  GetBooleanStatus(fmu, fmi2Terminated, &terminated);
  const int refused = DoStep(fmu, stopped, 1e-3, fmi2True) == fmi2Error;
  printf("discard %d\nstopped_at %.17g\n",
         crushed == fmi2Discard && terminated && refused && stopped >= from && stopped < from + 1e-3, stopped);
  FreeInstance(fmu);
}

/* A second fmi2ExitInitializationMode: refused; the tire goes on where it was. */
static void second_exit(void) {
  fmi2Component fmu = started("tire", 0.0);
  for (int step = 0; step < 10; ++step) press_step(fmu, step);
  const double before = fz(fmu);
  const int refused = ExitInitializationMode(fmu) == fmi2Error && EnterInitializationMode(fmu) == fmi2Error;
  const int same = fz(fmu) == before;
  press_step(fmu, 10);
  printf("second_exit %d\n", refused && same && fz(fmu) != before);
  Terminate(fmu);
  FreeInstance(fmu);
}

/* fmi2Reset: parameters and inputs back at their start values; a new run is a fresh one's. */
static void reset(void) {
  fmi2Component fmu = started("tire", -1e-3);
  for (int step = 0; step < 5; ++step) press_step(fmu, step);
  require(Reset(fmu) == fmi2OK, "fmi2Reset");
  fmi2Real pressure = -1.0, z = -1.0;
  GetReal(fmu, PRESSURE, 1, &pressure);
  GetReal(fmu, &X_Z_SPIN[1], 1, &z);
  require(SetupExperiment(fmu, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK &&
              EnterInitializationMode(fmu) == fmi2OK && ExitInitializationMode(fmu) == fmi2OK,
          "initializing after fmi2Reset");
  fmi2Component fresh = Instantiate("fresh", fmi2CoSimulation, guid, resources, &callbacks, fmi2False, fmi2False);
  require(fresh && SetupExperiment(fresh, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK &&
              EnterInitializationMode(fresh) == fmi2OK && ExitInitializationMode(fresh) == fmi2OK,
          "a fresh instance");
  for (int step = 0; step < 20; ++step) {
    press_step(fmu, step);
    press_step(fresh, step);
  }
  printf("reset %d\n", pressure == 0.0 && z == 0.0 && fz(fmu) == fz(fresh));
  FreeInstance(fresh);
  FreeInstance(fmu);
}

/* fmi2DoStep from t = NaN, or from a time the FMU is not at. */
static void bad_time(void) {
  fmi2Component fmu = started("tire", 0.0);
  press_step(fmu, 0);
  const int refused = DoStep(fmu, NAN, 1e-3, fmi2True) == fmi2Error && DoStep(fmu, 0.5, 1e-3, fmi2True) == fmi2Error &&
                      DoStep(fmu, 1e-3, NAN, fmi2True) == fmi2Error && DoStep(fmu, 1e-3, -1e-3, fmi2True) == fmi2Error;
  fmi2Real time = -1.0;
  GetRealStatus(fmu, fmi2LastSuccessfulTime, &time);
  press_step(fmu, 1); /* and it goes on from where it was */
  printf("bad_time %d\n", refused && time == 1e-3);
  FreeInstance(fmu);
}

/* Calls with a freed instance, a stray pointer or NULL, and FMU states freed twice. */
static void stray_handles(void) {
  fmi2Component fmu = started("tire", 0.0);
  fmi2FMUstate state = NULL;
  require(GetFMUstate(fmu, &state) == fmi2OK, "fmi2GetFMUstate");
  fmi2FMUstate copy = state;
  int stray_value = 42;
  fmi2FMUstate stray_state = &stray_value;
  const int states = FreeFMUstate(fmu, &state) == fmi2OK && FreeFMUstate(fmu, &copy) == fmi2Error &&
                     SetFMUstate(fmu, stray_state) == fmi2Error && SetFMUstate(fmu, NULL) == fmi2Error;
  FreeInstance(fmu);
  FreeInstance(fmu); /* twice: nothing happens */
  fmi2Real value = 0.0;
  fmi2Component stray = &stray_value;
  const int instances = GetReal(fmu, FZ, 1, &value) == fmi2Error && DoStep(fmu, 0.0, 1e-3, fmi2True) == fmi2Error &&
                        GetReal(stray, FZ, 1, &value) == fmi2Error && DoStep(NULL, 0.0, 1e-3, fmi2True) == fmi2Error &&
                        Reset(NULL) == fmi2Error;
  FreeInstance(NULL);
  FreeInstance(stray);
  printf("stray_handles %d\n", states && instances);
}

/* Nonzero initial rates: the tire starts at rest, so initialization is refused, saying so. */
static void moving_start(void) {
  fmi2Component fmu = Instantiate("tire", fmi2CoSimulation, guid, resources, &callbacks, fmi2False, fmi2False);
  const fmi2Real rolling[] = {10.0, 0.0, 0.0};
  require(fmu && SetupExperiment(fmu, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK &&
              SetReal(fmu, RATES, 3, rolling) == fmi2OK && EnterInitializationMode(fmu) == fmi2OK,
          "setting up a moving start");
  printf("moving_start %d\n", ExitInitializationMode(fmu) == fmi2Error);
  FreeInstance(fmu);
}

/* The String parameters: their start values, and a tire and a road named by file URIs. */
static void strings(const char* tire_file, const char* road_file) {
  fmi2Component fmu = Instantiate("tire", fmi2CoSimulation, guid, resources, &callbacks, fmi2False, fmi2False);
  fmi2String values[2] = {NULL, NULL};
  require(fmu && GetString(fmu, TIRE, 1, &values[0]) == fmi2OK && GetString(fmu, ROAD, 1, &values[1]) == fmi2OK,
          "fmi2GetString");
  const int starts = strcmp(values[0], "145SR12.tir") == 0 && strcmp(values[1], "") == 0;
  char tire_uri[PATH_MAX + 32], road_uri[PATH_MAX + 32];
  snprintf(tire_uri, sizeof tire_uri, "file://localhost%s", tire_file);
  snprintf(road_uri, sizeof road_uri, "file://localhost%s", road_file);
  const fmi2String tire[] = {tire_uri}, road[] = {road_uri}, left[] = {"left"};
  require(SetString(fmu, TIRE, 1, tire) == fmi2OK && SetString(fmu, ROAD, 1, road) == fmi2OK &&
              SetString(fmu, ROAD_TRACK, 1, left) == fmi2OK &&
              SetupExperiment(fmu, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK &&
              EnterInitializationMode(fmu) == fmi2OK && ExitInitializationMode(fmu) == fmi2OK,
          "a tire and a road on disk");
  const int fixed = SetString(fmu, TIRE, 1, tire) == fmi2Error;
  printf("strings %d\n", starts && fixed && DoStep(fmu, 0.0, 1e-3, fmi2True) == fmi2OK);
  FreeInstance(fmu);
}

/* The guid="..." of modelDescription.xml. */
static void read_guid(const char* dir) {
  char path[PATH_MAX];
  snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
  FILE* file = fopen(path, "r");
  require(file != NULL, "opening modelDescription.xml");
  static char text[1 << 16];
  const size_t length = fread(text, 1, sizeof text - 1, file);
  fclose(file);
  text[length] = '\0';
  const char* start = strstr(text, "guid=\"");
  require(start != NULL, "finding the GUID");
  start += 6;
  const char* end = strchr(start, '"');
  require(end && (size_t)(end - start) < sizeof guid, "reading the GUID");
  memcpy(guid, start, (size_t)(end - start));
  guid[end - start] = '\0';
}

int main(int argc, char** argv) {
  if (argc != 4) {
    fprintf(stderr, "usage: fmu_host UNPACKED_FMU_DIR TIRE_FILE ROAD_FILE\n");
    return 2;
  }
  char path[PATH_MAX], folder[PATH_MAX];
  snprintf(path, sizeof path, "%s/binaries/linux64/tirefe_tire.so", argv[1]);
  snprintf(folder, sizeof folder, "%s/resources", argv[1]);
  require(folder_uri(folder, resources, sizeof resources), "finding the FMU's resources");
  void* library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  require(library != NULL, "loading the binary");
  require(load_fmi_functions(library) == NULL, "finding the FMI functions");
  read_guid(argv[1]);

  starting_press();
  states_and_discard();
  second_exit();
  reset();
  bad_time();
  stray_handles();
  moving_start();
  strings(argv[2], argv[3]);
  dlclose(library);
  return 0;
}
