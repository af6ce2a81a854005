/* fmi_master: a co-simulation master for FMI 2.0 FMUs, written from the standard (sections
 * 2 and 4) in the manner of generic masters such as the Modelica Reference-FMUs' fmusim:
 * fixed communication steps, Real inputs read from a CSV file and handed over at the start
 * of each step (start-of-step semantics: the inputs at t, then fmi2DoStep(t, h)), the
 * outputs sampled at every communication point into a CSV file.
 *
 *   fmi_master UNPACKED_FMU --step H --stop T [--start T0] [--input IN.csv] [--output OUT.csv]
 *              [--set NAME=VALUE]... [--log]
 *
 * IN.csv: a header "time,NAME,..." naming Real inputs, then rows of numbers with rising
 * times; an input is interpolated linearly between rows (held before the first and after
 * the last). OUT.csv: "time,OUTPUT,..." with every output, one row per communication point.
 * --set sets a parameter before initialization (Real, Integer, Boolean true/false, String).
 * On stderr at the end: the steps, the simulated time and the CPU time spent in fmi2DoStep.
 * A step the FMU discards ends the run (exit 3) after a last row at
 * fmi2LastSuccessfulTime; any other failure exits 1, bad arguments 2. */
#define _XOPEN_SOURCE 700
#include <ctype.h>
#include <dlfcn.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fmi_support.h"

enum { kMaxVariables = 256, kMaxColumns = 64 };

typedef struct {
  char name[128];
  char type[16]; /* Real, Integer, Boolean, String */
  char causality[24];
  fmi2ValueReference reference;
} Variable;

typedef struct {
  char guid[128], identifier[128];
  Variable variables[kMaxVariables];
  int count;
} Description;

typedef struct {
  int columns;               /* inputs, besides time */
  int variable[kMaxColumns]; /* index into the description per input column */
  double* rows;              /* (1 + columns) per row */
  size_t count;
} Inputs;

static void fail(int code, const char* format, ...) {
  va_list arguments;
  va_start(arguments, format);
  fputs("fmi_master: ", stderr);
  vfprintf(stderr, format, arguments);
  fputc('\n', stderr);
  va_end(arguments);
  exit(code);
}

/* The value of attribute 'name' in the element text [start, end), into 'value'. */
static int attribute(const char* start, const char* end, const char* name, char* value, size_t size) {
  char key[64];
  snprintf(key, sizeof key, " %s=\"", name);
  const size_t length = strlen(key);
  for (const char* at = start; at + length < end; ++at) {
    if (!isspace((unsigned char)*at) || strncmp(at + 1, key + 1, length - 1) != 0) continue;
    const char* first = at + length;
    const char* last = memchr(first, '"', (size_t)(end - first));
    if (!last || (size_t)(last - first) >= size) return 0;
    memcpy(value, first, (size_t)(last - first));
    value[last - first] = '\0';
    return 1;
  }
  return 0;
}

static char* read_file(const char* path) {
  FILE* file = fopen(path, "rb");
  if (!file) fail(1, "cannot open %s", path);
  fseek(file, 0, SEEK_END);
  const long size = ftell(file);
  rewind(file);
  char* text = malloc((size_t)size + 1);
  if (!text || fread(text, 1, (size_t)size, file) != (size_t)size) fail(1, "cannot read %s", path);
  text[size] = '\0';
  fclose(file);
  return text;
}

/* The GUID, the co-simulation model identifier and the scalar variables of modelDescription.xml. */
static void read_description(const char* dir, Description* description) {
  char path[PATH_MAX];
  snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
  char* text = read_file(path);
  const char* root = strstr(text, "<fmiModelDescription");
  const char* cosimulation = strstr(text, "<CoSimulation");
  if (!root || !cosimulation || !attribute(root, strchr(root, '>'), "guid", description->guid, 128) ||
      !attribute(cosimulation, strchr(cosimulation, '>'), "modelIdentifier", description->identifier, 128))
    fail(1, "%s: no fmiModelDescription guid or CoSimulation modelIdentifier", path);
  description->count = 0;
  for (const char* at = strstr(text, "<ScalarVariable"); at; at = strstr(at + 1, "<ScalarVariable")) {
    if (description->count == kMaxVariables) fail(1, "%s: more than %d variables", path, kMaxVariables);
    const char* close = strstr(at, "</ScalarVariable>");
    const char* tag_end = strchr(at, '>');
    if (!close || !tag_end) fail(1, "%s: an unclosed ScalarVariable", path);
    Variable* variable = &description->variables[description->count++];
    char reference[32];
    if (!attribute(at, tag_end, "name", variable->name, sizeof variable->name) ||
        !attribute(at, tag_end, "valueReference", reference, sizeof reference))
      fail(1, "%s: a ScalarVariable without name or valueReference", path);
    variable->reference = (fmi2ValueReference)strtoul(reference, NULL, 10);
    if (!attribute(at, tag_end, "causality", variable->causality, sizeof variable->causality))
      strcpy(variable->causality, "local");
    const char* types[] = {"Real", "Integer", "Boolean", "String", "Enumeration"};
    variable->type[0] = '\0';
    for (int t = 0; t < 5; ++t) {
      char tag[32];
      snprintf(tag, sizeof tag, "<%s", types[t]);
      const char* found = strstr(tag_end, tag);
      if (found && found < close) strcpy(variable->type, types[t]);
    }
  }
  free(text);
}

static int find_variable(const Description* description, const char* name) {
  for (int i = 0; i < description->count; ++i)
    if (strcmp(description->variables[i].name, name) == 0) return i;
  return -1;
}

/* IN.csv: the header names Real inputs; the rows are numbers with rising times. */
static void read_inputs(const char* path, const Description* description, Inputs* inputs) {
  char* text = read_file(path);
  char* save = NULL;
  char* line = strtok_r(text, "\r\n", &save);
  if (!line) fail(2, "%s: empty", path);
  inputs->columns = -1;
  for (char *cell_save = NULL, *cell = strtok_r(line, ",", &cell_save); cell; cell = strtok_r(NULL, ",", &cell_save)) {
    while (isspace((unsigned char)*cell)) ++cell;
    if (inputs->columns < 0) {
      if (strcmp(cell, "time") != 0) fail(2, "%s: the first column must be 'time', not '%s'", path, cell);
    } else {
      const int index = find_variable(description, cell);
      if (index < 0 || strcmp(description->variables[index].causality, "input") != 0 ||
          strcmp(description->variables[index].type, "Real") != 0)
        fail(2, "%s: '%s' is not a Real input of the FMU", path, cell);
      if (inputs->columns == kMaxColumns) fail(2, "%s: more than %d columns", path, kMaxColumns);
      inputs->variable[inputs->columns] = index;
    }
    ++inputs->columns;
  }
  size_t capacity = 1024;
  inputs->rows = malloc(capacity * (size_t)(1 + inputs->columns) * sizeof(double));
  inputs->count = 0;
  for (int number = 2; (line = strtok_r(NULL, "\r\n", &save)) != NULL; ++number) {
    if (inputs->count == capacity) {
      capacity *= 2;
      inputs->rows = realloc(inputs->rows, capacity * (size_t)(1 + inputs->columns) * sizeof(double));
    }
    double* row = inputs->rows + inputs->count * (size_t)(1 + inputs->columns);
    char* at = line;
    for (int c = 0; c <= inputs->columns; ++c) {
      char* end = NULL;
      row[c] = strtod(at, &end);
      if (end == at || !isfinite(row[c]) || (c < inputs->columns && *end != ',') || (c == inputs->columns && *end))
        fail(2, "%s:%d: expected %d numbers separated by commas", path, number, 1 + inputs->columns);
      at = end + 1;
    }
    if (inputs->count > 0 && row[0] <= row[-(1 + inputs->columns)]) fail(2, "%s:%d: the times must rise", path, number);
    ++inputs->count;
  }
  if (inputs->count == 0) fail(2, "%s: no rows", path);
  free(text);
}

/* The input of column c at time t: linear between rows, held outside them. */
static double input_at(const Inputs* inputs, int c, double t) {
  const int width = 1 + inputs->columns;
  const double* first = inputs->rows;
  const double* last = inputs->rows + (inputs->count - 1) * (size_t)width;
  if (t <= first[0]) return first[1 + c];
  if (t >= last[0]) return last[1 + c];
  size_t low = 0, high = inputs->count - 1; /* rows[low].time <= t < rows[high].time */
  while (high - low > 1) {
    const size_t middle = (low + high) / 2;
    if (inputs->rows[middle * (size_t)width] <= t)
      low = middle;
    else
      high = middle;
  }
  const double* a = inputs->rows + low * (size_t)width;
  const double* b = inputs->rows + high * (size_t)width;
  const double s = (t - a[0]) / (b[0] - a[0]);
  return a[1 + c] + s * (b[1 + c] - a[1 + c]);
}

/* The FMI functions the master calls, by their standard names. */
typedef struct {
  fmi2Component (*Instantiate)(fmi2String, fmi2Type, fmi2String, fmi2String, const fmi2CallbackFunctions*, fmi2Boolean,
                               fmi2Boolean);
  void (*FreeInstance)(fmi2Component);
  fmi2Status (*SetupExperiment)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
  fmi2Status (*EnterInitializationMode)(fmi2Component);
  fmi2Status (*ExitInitializationMode)(fmi2Component);
  fmi2Status (*Terminate)(fmi2Component);
  fmi2Status (*SetReal)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2Real[]);
  fmi2Status (*GetReal)(fmi2Component, const fmi2ValueReference[], size_t, fmi2Real[]);
  fmi2Status (*SetInteger)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2Integer[]);
  fmi2Status (*SetBoolean)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2Boolean[]);
  fmi2Status (*SetString)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2String[]);
  fmi2Status (*DoStep)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
  fmi2Status (*GetRealStatus)(fmi2Component, const fmi2StatusKind, fmi2Real*);
  fmi2Status (*GetBooleanStatus)(fmi2Component, const fmi2StatusKind, fmi2Boolean*);
} Functions;

/* POSIX's way to a function pointer from dlsym, which ISO C has no cast for. */
static void load(void* library, const char* binary, const char* name, void* function) {
  *(void**)function = dlsym(library, name);
  if (!*(void**)function) fail(1, "%s does not export %s", binary, name);
}

/* A running co-simulation: the FMU, its inputs and where its outputs go. */
typedef struct {
  Functions fmi;
  fmi2Component fmu;
  const Inputs* inputs;
  fmi2ValueReference input_references[kMaxColumns];
  fmi2ValueReference output_references[kMaxVariables];
  int outputs;
  FILE* output;
} Run;

static void apply_inputs(const Run* run, double t) {
  fmi2Real values[kMaxColumns];
  const int columns = run->inputs->columns;
  for (int c = 0; c < columns; ++c) values[c] = input_at(run->inputs, c, t);
  if (columns > 0 && run->fmi.SetReal(run->fmu, run->input_references, (size_t)columns, values) > fmi2Warning)
    fail(1, "fmi2SetReal of the inputs failed at t = %g", t);
}

static void sample(const Run* run, double t) {
  fmi2Real values[kMaxVariables];
  if (run->fmi.GetReal(run->fmu, run->output_references, (size_t)run->outputs, values) > fmi2Warning)
    fail(1, "fmi2GetReal of the outputs failed at t = %g", t);
  if (!run->output) return;
  fprintf(run->output, "%.17g", t);
  for (int o = 0; o < run->outputs; ++o) fprintf(run->output, ",%.17g", values[o]);
  fprintf(run->output, "\n");
}

/* --set NAME=VALUE before initialization, by the variable's type. */
static void set_parameter(const Run* run, const Description* description, const char* assignment) {
  char name[128];
  const char* equals = strchr(assignment, '=');
  if (!equals || (size_t)(equals - assignment) >= sizeof name) fail(2, "--set '%s' is not NAME=VALUE", assignment);
  memcpy(name, assignment, (size_t)(equals - assignment));
  name[equals - assignment] = '\0';
  const int index = find_variable(description, name);
  if (index < 0) fail(2, "--set: the FMU has no variable '%s'", name);
  const Variable* variable = &description->variables[index];
  const char* value = equals + 1;
  fmi2Status status = fmi2Error;
  if (strcmp(variable->type, "Real") == 0) {
    const fmi2Real real = atof(value);
    status = run->fmi.SetReal(run->fmu, &variable->reference, 1, &real);
  } else if (strcmp(variable->type, "Integer") == 0 || strcmp(variable->type, "Enumeration") == 0) {
    const fmi2Integer integer = atoi(value);
    status = run->fmi.SetInteger(run->fmu, &variable->reference, 1, &integer);
  } else if (strcmp(variable->type, "Boolean") == 0) {
    const fmi2Boolean boolean = strcmp(value, "true") == 0 || strcmp(value, "1") == 0;
    status = run->fmi.SetBoolean(run->fmu, &variable->reference, 1, &boolean);
  } else if (strcmp(variable->type, "String") == 0) {
    status = run->fmi.SetString(run->fmu, &variable->reference, 1, &value);
  }
  if (status > fmi2Warning) fail(1, "cannot set %s", assignment);
}

static double cpu_seconds(void) {
  struct timespec now;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return (double)now.tv_sec + 1e-9 * (double)now.tv_nsec;
}

static const char* const kUsage =
    "usage: fmi_master UNPACKED_FMU --step H --stop T [--start T0] [--input IN.csv] [--output OUT.csv] "
    "[--set NAME=VALUE]... [--log]";

int main(int argc, char** argv) {
  const char *dir = NULL, *input_path = NULL, *output_path = NULL;
  double step = 0.0, stop = -1.0, start = 0.0;
  int logging = 0, sets = 0;
  const char* set[kMaxVariables];
  for (int i = 1; i < argc; ++i) {
    const char* option = argv[i];
    const int has_value = i + 1 < argc;
    if (strcmp(option, "--step") == 0 && has_value)
      step = atof(argv[++i]);
    else if (strcmp(option, "--stop") == 0 && has_value)
      stop = atof(argv[++i]);
    else if (strcmp(option, "--start") == 0 && has_value)
      start = atof(argv[++i]);
    else if (strcmp(option, "--input") == 0 && has_value)
      input_path = argv[++i];
    else if (strcmp(option, "--output") == 0 && has_value)
      output_path = argv[++i];
    else if (strcmp(option, "--set") == 0 && has_value && sets < kMaxVariables)
      set[sets++] = argv[++i];
    else if (strcmp(option, "--log") == 0)
      logging = 1;
    else if (option[0] != '-' && !dir)
      dir = option;
    else
      fail(2, "unknown or incomplete argument '%s'\n%s", option, kUsage);
  }
  if (!dir || !(step > 0.0) || !(stop >= start))
    fail(2, "give the unpacked FMU, --step H > 0 and --stop T >= start\n%s", kUsage);

  Description description;
  read_description(dir, &description);
  Inputs inputs = {0, {0}, NULL, 0};
  if (input_path) read_inputs(input_path, &description, &inputs);
  char binary[PATH_MAX], resources[PATH_MAX], uri[3 * PATH_MAX];
  snprintf(binary, sizeof binary, "%s/binaries/linux64/%s.so", dir, description.identifier);
  snprintf(resources, sizeof resources, "%s/resources", dir);
  if (!folder_uri(resources, uri, sizeof uri)) fail(1, "no folder %s", resources);
  void* library = dlopen(binary, RTLD_NOW | RTLD_LOCAL);
  if (!library) fail(1, "cannot load %s: %s", binary, dlerror());
  Run run = {.inputs = &inputs};
  Functions* fmi = &run.fmi;
  load(library, binary, "fmi2Instantiate", &fmi->Instantiate);
  load(library, binary, "fmi2FreeInstance", &fmi->FreeInstance);
  load(library, binary, "fmi2SetupExperiment", &fmi->SetupExperiment);
  load(library, binary, "fmi2EnterInitializationMode", &fmi->EnterInitializationMode);
  load(library, binary, "fmi2ExitInitializationMode", &fmi->ExitInitializationMode);
  load(library, binary, "fmi2Terminate", &fmi->Terminate);
  load(library, binary, "fmi2SetReal", &fmi->SetReal);
  load(library, binary, "fmi2GetReal", &fmi->GetReal);
  load(library, binary, "fmi2SetInteger", &fmi->SetInteger);
  load(library, binary, "fmi2SetBoolean", &fmi->SetBoolean);
  load(library, binary, "fmi2SetString", &fmi->SetString);
  load(library, binary, "fmi2DoStep", &fmi->DoStep);
  load(library, binary, "fmi2GetRealStatus", &fmi->GetRealStatus);
  load(library, binary, "fmi2GetBooleanStatus", &fmi->GetBooleanStatus);

  const fmi2CallbackFunctions callbacks = {fmi_logger, calloc, free, NULL, NULL};
  run.fmu = fmi->Instantiate("fmu", fmi2CoSimulation, description.guid, uri, &callbacks, fmi2False,
                             logging ? fmi2True : fmi2False);
  if (!run.fmu) fail(1, "fmi2Instantiate failed");
  for (int s = 0; s < sets; ++s) set_parameter(&run, &description, set[s]);
  for (int c = 0; c < inputs.columns; ++c)
    run.input_references[c] = description.variables[inputs.variable[c]].reference;
  if (output_path && !(run.output = fopen(output_path, "w"))) fail(1, "cannot write %s", output_path);
  if (run.output) fprintf(run.output, "time");
  for (int i = 0; i < description.count; ++i) {
    const Variable* variable = &description.variables[i];
    if (strcmp(variable->causality, "output") != 0 || strcmp(variable->type, "Real") != 0) continue;
    run.output_references[run.outputs++] = variable->reference;
    if (run.output) fprintf(run.output, ",%s", variable->name);
  }
  if (run.output) fprintf(run.output, "\n");

  /* The inputs at the start are set before initialization: the FMU starts from them. */
  apply_inputs(&run, start);
  if (fmi->SetupExperiment(run.fmu, fmi2False, 0.0, start, fmi2True, stop) > fmi2Warning ||
      fmi->EnterInitializationMode(run.fmu) > fmi2Warning || fmi->ExitInitializationMode(run.fmu) > fmi2Warning)
    fail(1, "the FMU could not be initialized");

  double cpu = 0.0;
  long steps = 0;
  int code = 0;
  for (long k = 0;; ++k) {
    const double t = start + (double)k * step; /* a product, not a sum of steps: no drift */
    sample(&run, t);
    if (t >= stop - 1e-9 * step) break;
    apply_inputs(&run, t);
    const double before = cpu_seconds();
    const fmi2Status status = fmi->DoStep(run.fmu, t, step, fmi2True);
    cpu += cpu_seconds() - before;
    ++steps;
    if (status == fmi2Discard) {
      fmi2Boolean terminated = fmi2False;
      fmi2Real last = t;
      fmi->GetBooleanStatus(run.fmu, fmi2Terminated, &terminated);
      fmi->GetRealStatus(run.fmu, fmi2LastSuccessfulTime, &last);
      sample(&run, last);
      fprintf(stderr, "fmi_master: the FMU discarded the step from t = %g at t = %.9g%s\n", t, last,
              terminated ? " and asks to terminate" : "");
      code = 3;
      break;
    }
    if (status > fmi2Warning) fail(1, "fmi2DoStep failed at t = %g (status %d)", t, (int)status);
  }
  fprintf(stderr, "fmi_master: %ld steps of %g s to t = %g s, %.6f s of CPU in fmi2DoStep (%.6f s per simulated s)\n",
          steps, step, start + (double)steps * step, cpu, steps > 0 ? cpu / ((double)steps * step) : 0.0);
  if (run.output) fclose(run.output);
  fmi->Terminate(run.fmu);
  fmi->FreeInstance(run.fmu);
  free(inputs.rows);
  dlclose(library);
  return code;
}
