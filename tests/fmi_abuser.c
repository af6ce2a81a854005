/* A hostile FMI master of tirefe_tire.fmu, the FMU's side of the bad-deck catalogue:
 * every call out of the FMI 2.0 sequence, every bad argument, and NULL, freed and made-up
 * instances and FMU states, each with the status it must get and the text of the one-line
 * message the FMU must log (none where there is no instance to log through). Nothing may
 * crash, hang or be accepted silently. Prints one line per probe that got something else
 * and a summary; exits 1 if any probe failed.
 *
 *   fmi_abuser              (FMI_ABUSER_VERBOSE=1: every probe's status and message) */
#define _XOPEN_SOURCE 700
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi_functions.h"
#include "fmi_support.h"

/* What the FMU logged since the last probe: its messages, one after the other. */
static char logged[4096];
static int logged_lines = 0;

static void capture(fmi2ComponentEnvironment environment, fmi2String instance, fmi2Status status, fmi2String category,
                    fmi2String message, ...) {
  (void)environment, (void)instance, (void)status, (void)category;
  va_list arguments;
  va_start(arguments, message);
  const size_t used = strlen(logged);
  vsnprintf(logged + used, sizeof logged - used, message, arguments);
  va_end(arguments);
  ++logged_lines;
}

static const fmi2CallbackFunctions callbacks = {capture, calloc, free, NULL, NULL};
static char resources[3 * PATH_MAX];
static int probes = 0, failures = 0;

static void forget_log(void) {
  logged[0] = '\0';
  logged_lines = 0;
}

/* One probe: 'got' must be 'expected'; 'text' NULL: nothing may be logged (there is no
 * instance to log through); "": anything; else one logged line holding 'text'. */
static void expect(const char* what, fmi2Status got, fmi2Status expected, const char* text) {
  ++probes;
  if (getenv("FMI_ABUSER_VERBOSE")) printf("%-64s %d  %s\n", what, (int)got, logged);
  const int text_ok = text == NULL ? logged_lines == 0
                                   : text[0] == '\0' || (logged_lines == 1 && strstr(logged, text) != NULL &&
                                                         strchr(logged, '\n') == NULL);
  if (got != expected || !text_ok) {
    ++failures;
    printf("FAILED: %s: status %d (expected %d), logged %d line(s) '%s' (expected '%s')\n", what, (int)got,
           (int)expected, logged_lines, logged, text ? text : "(nothing)");
  }
  forget_log();
}

#define PROBE(what, call, status, text) \
  do {                                  \
    forget_log();                       \
    const fmi2Status got_ = (call);     \
    expect(what, got_, status, text);   \
  } while (0)

static const fmi2ValueReference X_Z_SPIN[] = {0, 1, 2}, FZ[] = {4}, PRESSURE[] = {10}, FRICTION[] = {12},
                                MAX_STEP[] = {15}, FREE_SPIN[] = {14}, TIRE[] = {20}, ROAD_TRACK[] = {22},
                                TIRE_PARAMETERS[] = {23}, MAX_ITERATIONS[] = {17}, UNKNOWN[] = {99};

static fmi2Component instantiated(void) {
  fmi2Component fmu =
      Instantiate("abused", fmi2CoSimulation, TIREFE_FMU_GUID, resources, &callbacks, fmi2False, fmi2False);
  if (!fmu) {
    printf("FAILED: fmi2Instantiate of a good instance (%s)\n", logged);
    exit(1);
  }
  return fmu;
}

static fmi2Component initialized(void) {
  fmi2Component fmu = instantiated();
  if (SetupExperiment(fmu, fmi2False, 0.0, 0.0, fmi2False, 0.0) != fmi2OK || EnterInitializationMode(fmu) != fmi2OK ||
      ExitInitializationMode(fmu) != fmi2OK) {
    printf("FAILED: initializing a good instance (%s)\n", logged);
    exit(1);
  }
  forget_log();
  return fmu;
}

/* fmi2Instantiate with what is not this FMU's: NULL, and the reason logged. */
static void abuse_instantiate(void) {
  forget_log();
  fmi2Component fmu = Instantiate("x", fmi2ModelExchange, TIREFE_FMU_GUID, resources, &callbacks, fmi2False, fmi2False);
  expect("instantiate for model exchange", fmu ? fmi2OK : fmi2Error, fmi2Error, "co-simulation only");
  fmu = Instantiate("x", fmi2CoSimulation, "{not-this-guid}", resources, &callbacks, fmi2False, fmi2False);
  expect("instantiate with another GUID", fmu ? fmi2OK : fmi2Error, fmi2Error, "the GUID is not this FMU's");
  fmu = Instantiate("x", fmi2CoSimulation, NULL, resources, &callbacks, fmi2False, fmi2False);
  expect("instantiate with a NULL GUID", fmu ? fmi2OK : fmi2Error, fmi2Error, "the GUID is not this FMU's");
  fmu = Instantiate("x", fmi2CoSimulation, TIREFE_FMU_GUID, "http://example.com/resources", &callbacks, fmi2False,
                    fmi2False);
  expect("instantiate with an http resource location", fmu ? fmi2OK : fmi2Error, fmi2Error, "resource location");
  fmu = Instantiate("x", fmi2CoSimulation, TIREFE_FMU_GUID, resources, NULL, fmi2False, fmi2False);
  expect("instantiate without callbacks", fmu ? fmi2OK : fmi2Error, fmi2Error, NULL);
  fmu = Instantiate(NULL, fmi2CoSimulation, TIREFE_FMU_GUID, resources, &callbacks, fmi2False, fmi2False);
  expect("instantiate without a name", fmu ? fmi2OK : fmi2Error, fmi2OK, "");
  FreeInstance(fmu);
}

/* Instances that are none: NULL, made up, freed. Nothing is logged (no logger to log to),
 * nothing is followed. */
static void abuse_instances(void) {
  long garbage[16] = {0};
  fmi2Component made_up = garbage, freed = instantiated();
  FreeInstance(freed);
  fmi2Real value = 0.0;
  const fmi2Component none[] = {NULL, made_up, freed};
  const char* names[] = {"NULL", "a made-up", "a freed"};
  char what[128];
  for (int i = 0; i < 3; ++i) {
#define ON_NONE(call_name, call)                                         \
  snprintf(what, sizeof what, "%s on %s instance", call_name, names[i]); \
  PROBE(what, call, fmi2Error, NULL)
    ON_NONE("fmi2SetupExperiment", SetupExperiment(none[i], fmi2False, 0.0, 0.0, fmi2False, 0.0));
    ON_NONE("fmi2EnterInitializationMode", EnterInitializationMode(none[i]));
    ON_NONE("fmi2ExitInitializationMode", ExitInitializationMode(none[i]));
    ON_NONE("fmi2GetReal", GetReal(none[i], FZ, 1, &value));
    ON_NONE("fmi2SetReal", SetReal(none[i], PRESSURE, 1, &value));
    ON_NONE("fmi2DoStep", DoStep(none[i], 0.0, 1e-3, fmi2True));
    ON_NONE("fmi2Terminate", Terminate(none[i]));
    ON_NONE("fmi2Reset", Reset(none[i]));
    ON_NONE("fmi2GetRealStatus", GetRealStatus(none[i], fmi2LastSuccessfulTime, &value));
#undef ON_NONE
    forget_log();
    FreeInstance(none[i]); /* harmless */
    expect(names[i], logged_lines == 0 ? fmi2OK : fmi2Error, fmi2OK, NULL);
  }
}

/* Calls out of the FMI 2.0 sequence: refused, naming the call and the state. */
static void abuse_sequence(void) {
  fmi2Component fmu = instantiated();
  PROBE("fmi2DoStep before initialization", DoStep(fmu, 0.0, 1e-3, fmi2True), fmi2Error,
        "fmi2DoStep is not allowed in instantiated");
  PROBE("fmi2ExitInitializationMode before entering", ExitInitializationMode(fmu), fmi2Error,
        "fmi2ExitInitializationMode is not allowed in instantiated");
  PROBE("fmi2Terminate before initialization", Terminate(fmu), fmi2Error, "fmi2Terminate is not allowed");
  PROBE("fmi2SetupExperiment from t = NaN", SetupExperiment(fmu, fmi2False, 0.0, NAN, fmi2False, 0.0), fmi2Error,
        "the start time must be finite");
  PROBE("fmi2GetFMUstate before initialization", GetFMUstate(fmu, &(fmi2FMUstate){NULL}), fmi2Error,
        "initialize the FMU first");
  PROBE("fmi2EnterInitializationMode", EnterInitializationMode(fmu), fmi2OK, "");
  PROBE("fmi2EnterInitializationMode twice", EnterInitializationMode(fmu), fmi2Error,
        "fmi2EnterInitializationMode is not allowed in initialization mode");
  PROBE("fmi2SetupExperiment in initialization mode", SetupExperiment(fmu, fmi2False, 0.0, 0.0, fmi2False, 0.0),
        fmi2Error, "fmi2SetupExperiment is not allowed in initialization mode");
  PROBE("fmi2ExitInitializationMode", ExitInitializationMode(fmu), fmi2OK, "");
  PROBE("fmi2ExitInitializationMode twice", ExitInitializationMode(fmu), fmi2Error,
        "fmi2ExitInitializationMode is not allowed in step mode");
  PROBE("fmi2Terminate", Terminate(fmu), fmi2OK, "");
  PROBE("fmi2DoStep once terminated", DoStep(fmu, 0.0, 1e-3, fmi2True), fmi2Error,
        "fmi2DoStep is not allowed in terminated");
  const fmi2Real z = -1e-3;
  PROBE("an input set once terminated", SetReal(fmu, &X_Z_SPIN[1], 1, &z), fmi2Error,
        "inputs are not set once terminated");
  PROBE("fmi2Terminate twice", Terminate(fmu), fmi2Error, "fmi2Terminate is not allowed in terminated");
  PROBE("fmi2Reset once terminated", Reset(fmu), fmi2OK, "");
  PROBE("fmi2SetupExperiment after fmi2Reset", SetupExperiment(fmu, fmi2False, 0.0, 0.0, fmi2False, 0.0), fmi2OK, "");
  FreeInstance(fmu);
}

/* Variables: unknown references, outputs set, values out of range, NULL arrays. */
static void abuse_variables(void) {
  fmi2Component fmu = instantiated();
  fmi2Real value = 1.0;
  const fmi2Real not_a_number = NAN, zero = 0.0, negative = -1.0;
  PROBE("fmi2GetReal of an unknown reference", GetReal(fmu, UNKNOWN, 1, &value), fmi2Error,
        "no Real variable with value reference 99");
  PROBE("fmi2SetReal of an unknown reference", SetReal(fmu, UNKNOWN, 1, &value), fmi2Error,
        "no settable Real with value reference 99");
  PROBE("fmi2SetReal of the output Fz", SetReal(fmu, FZ, 1, &value), fmi2Error,
        "no settable Real with value reference 4");
  PROBE("fmi2SetReal of NaN", SetReal(fmu, PRESSURE, 1, &not_a_number), fmi2Error,
        "the Real with value reference 10 is not finite");
  PROBE("fmi2SetReal of max_step 0", SetReal(fmu, MAX_STEP, 1, &zero), fmi2Error, "max_step must be at least 1e-07 s");
  PROBE("fmi2SetReal of max_step 1e-12", SetReal(fmu, MAX_STEP, 1, &(fmi2Real){1e-12}), fmi2Error,
        "max_step must be at least 1e-07 s");
  PROBE("fmi2SetReal of a negative pressure", SetReal(fmu, PRESSURE, 1, &negative), fmi2Error,
        "pressure must be >= 0 (0: the tire file's)");
  PROBE("fmi2SetReal with NULL arrays", SetReal(fmu, NULL, 1, NULL), fmi2Error, "fmi2SetReal: NULL arrays");
  PROBE("fmi2GetReal with NULL arrays", GetReal(fmu, NULL, 1, NULL), fmi2Error, "fmi2GetReal: NULL arrays");
  PROBE("fmi2SetInteger of an unknown reference", SetInteger(fmu, UNKNOWN, 1, &(fmi2Integer){1}), fmi2Error,
        "no Integer with value reference 99");
  PROBE("fmi2SetInteger of a negative max_iterations", SetInteger(fmu, MAX_ITERATIONS, 1, &(fmi2Integer){-1}),
        fmi2Error, "max_iterations must be >= 0 (0: Newton to convergence)");
  PROBE("fmi2GetInteger with NULL arrays", GetInteger(fmu, NULL, 1, NULL), fmi2Error, "fmi2GetInteger: NULL arrays");
  PROBE("fmi2SetBoolean of an unknown reference", SetBoolean(fmu, UNKNOWN, 1, &(fmi2Boolean){fmi2True}), fmi2Error,
        "no Boolean with value reference 99");
  PROBE("fmi2GetBoolean with NULL arrays", GetBoolean(fmu, NULL, 1, NULL), fmi2Error, "fmi2GetBoolean: NULL arrays");
  PROBE("fmi2SetString of an unknown reference", SetString(fmu, UNKNOWN, 1, &(fmi2String){"x"}), fmi2Error,
        "no String with value reference 99");
  PROBE("fmi2GetString with NULL arrays", GetString(fmu, NULL, 1, NULL), fmi2Error, "fmi2GetString: NULL arrays");

  /* Parameters that build no tire: the initialization is refused, saying why. */
  PROBE("a negative friction", SetReal(fmu, FRICTION, 1, &negative), fmi2OK, "");
  PROBE("fmi2SetupExperiment", SetupExperiment(fmu, fmi2False, 0.0, 0.0, fmi2False, 0.0), fmi2OK, "");
  PROBE("fmi2EnterInitializationMode", EnterInitializationMode(fmu), fmi2OK, "");
  PROBE("initializing with a negative friction", ExitInitializationMode(fmu), fmi2Error, "friction");
  PROBE("the friction back to 0.8", SetReal(fmu, FRICTION, 1, &(fmi2Real){0.8}), fmi2OK, "");
  PROBE("a tire file that does not exist", SetString(fmu, TIRE, 1, &(fmi2String){"no_such.tir"}), fmi2OK, "");
  PROBE("initializing with a missing tire file", ExitInitializationMode(fmu), fmi2Error, "no_such.tir");
  PROBE("the tire back to 145SR12.tir", SetString(fmu, TIRE, 1, &(fmi2String){"145SR12.tir"}), fmi2OK, "");
  PROBE("tire_parameters without '='", SetString(fmu, TIRE_PARAMETERS, 1, &(fmi2String){"k_sw"}), fmi2OK, "");
  PROBE("initializing with tire_parameters 'k_sw'", ExitInitializationMode(fmu), fmi2Error,
        "tire_parameters: 'k_sw' is not key=number");
  PROBE("tire_parameters with a misspelt key", SetString(fmu, TIRE_PARAMETERS, 1, &(fmi2String){"k_sww=1"}), fmi2OK,
        "");
  PROBE("initializing with tire_parameters 'k_sww=1'", ExitInitializationMode(fmu), fmi2Error, "k_sww");
  PROBE("a road track without a road", SetString(fmu, ROAD_TRACK, 1, &(fmi2String){"left"}), fmi2OK, "");
  PROBE("initializing with a road track but no road", ExitInitializationMode(fmu), fmi2Error,
        "options.road_track is \"left\" but options.road names no road file");
  PROBE("the road track cleared", SetString(fmu, ROAD_TRACK, 1, &(fmi2String){""}), fmi2OK, "");
  PROBE("tire_parameters cleared", SetString(fmu, TIRE_PARAMETERS, 1, &(fmi2String){NULL}), fmi2OK, "");
  PROBE("initializing as it should be", ExitInitializationMode(fmu), fmi2OK, "");
  PROBE("a parameter set in step mode", SetReal(fmu, PRESSURE, 1, &(fmi2Real){2e5}), fmi2Error,
        "the tire's parameters are fixed once it is initialized (value reference 10)");
  PROBE("a Boolean parameter set in step mode", SetBoolean(fmu, FREE_SPIN, 1, &(fmi2Boolean){fmi2False}), fmi2Error,
        "the tire's parameters are fixed once it is initialized (value reference 14)");
  PROBE("a String parameter set in step mode", SetString(fmu, TIRE, 1, &(fmi2String){"145SR12.tir"}), fmi2Error,
        "the tire's parameters are fixed once it is initialized (value reference 20)");
  FreeInstance(fmu);
}

/* fmi2DoStep with times and steps that are no such thing, or that do not start where the
 * FMU is. */
static void abuse_steps(void) {
  fmi2Component fmu = initialized();
  PROBE("fmi2DoStep from t = NaN", DoStep(fmu, NAN, 1e-3, fmi2True), fmi2Error,
        "fmi2DoStep needs a finite time and a finite step > 0 (got t = nan s, h = 0.001 s)");
  PROBE("fmi2DoStep over h = NaN", DoStep(fmu, 0.0, NAN, fmi2True), fmi2Error, "a finite step > 0");
  PROBE("fmi2DoStep over h = -1 ms", DoStep(fmu, 0.0, -1e-3, fmi2True), fmi2Error, "a finite step > 0");
  PROBE("fmi2DoStep over h = 0", DoStep(fmu, 0.0, 0.0, fmi2True), fmi2Error, "a finite step > 0");
  PROBE("fmi2DoStep over h = inf", DoStep(fmu, 0.0, INFINITY, fmi2True), fmi2Error, "a finite step > 0");
  PROBE("fmi2DoStep from a time the FMU is not at", DoStep(fmu, 0.5, 1e-3, fmi2True), fmi2Error,
        "fmi2DoStep from t = 0.5 s, but the FMU is at t = 0 s");
  PROBE("fmi2DoStep over 1e-12 s", DoStep(fmu, 0.0, 1e-12, fmi2True), fmi2Error,
        "fmi2DoStep over 1e-12 s: the tire takes no step below 1e-07 s");
  PROBE("fmi2DoStep over a year", DoStep(fmu, 0.0, 3.15e7, fmi2True), fmi2Error,
        "would take more than the 1000000 steps one call may take");
  PROBE("fmi2DoStep as it should be", DoStep(fmu, 0.0, 1e-3, fmi2True), fmi2OK, "");
  fmi2Real time = -1.0;
  PROBE("fmi2GetRealStatus(fmi2LastSuccessfulTime)", GetRealStatus(fmu, fmi2LastSuccessfulTime, &time), fmi2OK, "");
  expect("the FMU at t = 1 ms after the refused steps", time == 1e-3 ? fmi2OK : fmi2Error, fmi2OK, "");
  PROBE("fmi2GetRealStatus of another kind", GetRealStatus(fmu, fmi2DoStepStatus, &time), fmi2Discard,
        "only fmi2LastSuccessfulTime");
  PROBE("fmi2GetRealStatus into NULL", GetRealStatus(fmu, fmi2LastSuccessfulTime, NULL), fmi2Discard,
        "only fmi2LastSuccessfulTime");
  PROBE("fmi2GetBooleanStatus into NULL", GetBooleanStatus(fmu, fmi2Terminated, NULL), fmi2Discard,
        "only fmi2Terminated");
  PROBE("fmi2CancelStep", CancelStep(fmu), fmi2Error, "steps are not asynchronous");
  PROBE("fmi2GetDirectionalDerivative", GetDirectionalDerivative(fmu, FZ, 1, X_Z_SPIN, 1, &time, &time), fmi2Error,
        "no directional derivatives");
  FreeInstance(fmu);
}

/* FMU states: NULL, made up, freed, of another instance; not serialized. */
static void abuse_states(void) {
  fmi2Component fmu = initialized(), other = initialized();
  fmi2FMUstate state = NULL, copy = NULL, others = NULL;
  long garbage[16] = {0};
  size_t size = 0;
  PROBE("fmi2GetFMUstate into NULL", GetFMUstate(fmu, NULL), fmi2Error, "FMUstate is NULL");
  fmi2FMUstate made_up = garbage;
  PROBE("fmi2GetFMUstate into a made-up state", GetFMUstate(fmu, &made_up), fmi2Error,
        "*FMUstate is neither NULL nor a state of this instance");
  PROBE("fmi2GetFMUstate", GetFMUstate(fmu, &state), fmi2OK, "");
  PROBE("fmi2GetFMUstate of another instance", GetFMUstate(other, &others), fmi2OK, "");
  PROBE("fmi2SetFMUstate of another instance's state", SetFMUstate(fmu, others), fmi2Error,
        "not a state of this instance");
  PROBE("fmi2SetFMUstate of a made-up state", SetFMUstate(fmu, garbage), fmi2Error, "not a state of this instance");
  PROBE("fmi2SetFMUstate of NULL", SetFMUstate(fmu, NULL), fmi2Error, "not a state of this instance");
  PROBE("fmi2FreeFMUstate of another instance's state", FreeFMUstate(fmu, &others), fmi2Error,
        "not a state of this instance");
  PROBE("fmi2SerializedFMUstateSize", SerializedFMUstateSize(fmu, state, &size), fmi2Error, "not serialized");
  copy = state;
  PROBE("fmi2FreeFMUstate", FreeFMUstate(fmu, &state), fmi2OK, "");
  PROBE("fmi2FreeFMUstate twice", FreeFMUstate(fmu, &copy), fmi2Error, "not a state of this instance");
  PROBE("fmi2SetFMUstate of a freed state", SetFMUstate(fmu, copy), fmi2Error, "not a state of this instance");
  PROBE("fmi2FreeFMUstate of NULL", FreeFMUstate(fmu, &state), fmi2OK, "");
  PROBE("fmi2FreeFMUstate into NULL", FreeFMUstate(fmu, NULL), fmi2OK, "");
  FreeInstance(other); /* frees its state */
  FreeInstance(fmu);
}

/* fmi2Reset: the parameters back at their start values (modelDescription.xml's). */
static void abuse_reset(void) {
  fmi2Component fmu = instantiated();
  const fmi2Real pressure = 2e5, friction = 0.3;
  SetReal(fmu, PRESSURE, 1, &pressure);
  SetReal(fmu, FRICTION, 1, &friction);
  SetString(fmu, TIRE_PARAMETERS, 1, &(fmi2String){"k_sw=1"});
  PROBE("fmi2Reset", Reset(fmu), fmi2OK, "");
  fmi2Real values[2] = {-1.0, -1.0};
  fmi2String text = NULL;
  GetReal(fmu, PRESSURE, 1, &values[0]);
  GetReal(fmu, FRICTION, 1, &values[1]);
  GetString(fmu, TIRE_PARAMETERS, 1, &text);
  expect("the parameters at their start values after fmi2Reset",
         values[0] == 0.0 && values[1] == 0.8 && text && text[0] == '\0' ? fmi2OK : fmi2Error, fmi2OK, "");
  FreeInstance(fmu);
}

int main(void) {
  (void)fmi_logger; /* the suite's printing logger: this master keeps what it logs */
  if (!folder_uri(TIREFE_FMU_RESOURCES, resources, sizeof resources)) {
    printf("FAILED: no resources folder %s\n", TIREFE_FMU_RESOURCES);
    return 1;
  }
  void* library = dlopen(TIREFE_FMU_BINARY, RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    printf("FAILED: loading %s: %s\n", TIREFE_FMU_BINARY, dlerror());
    return 1;
  }
  const char* missing = load_fmi_functions(library);
  if (missing) {
    printf("FAILED: the binary does not export %s\n", missing);
    return 1;
  }
  abuse_instantiate();
  abuse_instances();
  abuse_sequence();
  abuse_variables();
  abuse_steps();
  abuse_states();
  abuse_reset();
  dlclose(library);
  printf("%d probes, %d failed\n", probes, failures);
  return failures ? 1 : 0;
}
