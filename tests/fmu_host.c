/* A co-simulation master in miniature: loads an unpacked tirefe_tire.fmu with dlopen and
 * drives it through the FMI 2.0 functions only. It presses the spindle 5 mm onto the
 * road as tests/install/press_tire.c does through the C API (pressure 180 kPa), saving
 * the FMU state half-way, and prints
 *   Fz, H_zz      the vertical force the tire exerts on the wheel and
 *                 fmi2GetDirectionalDerivative dFz/dz after the press (ISO wheel axes)
 *   H_zz_fd       dFz/dz of the last step by central differences (the step repeated
 *                 from a saved FMU state with z moved up and down 1e-7 m)
 *   repeat        1 if restoring the saved state and stepping again gives the same bits
 *   discard       1 if an impossible step is discarded and the FMU stays where it was
 * Exits 1 when a call fails unexpectedly.
 *
 *   fmu_host UNPACKED_FMU_DIR */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu/fmi2.h"

/* POSIX's way to a function pointer from dlsym, which ISO C has no cast for. */
#define LOAD(name) \
  name##_t name;   \
  *(void**)(&name) = dlsym(library, #name)
typedef fmi2Component (*fmi2Instantiate_t)(fmi2String, fmi2Type, fmi2String, fmi2String, const fmi2CallbackFunctions*,
                                           fmi2Boolean, fmi2Boolean);
typedef void (*fmi2FreeInstance_t)(fmi2Component);
typedef fmi2Status (*fmi2SetupExperiment_t)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
typedef fmi2Status (*fmi2EnterInitializationMode_t)(fmi2Component);
typedef fmi2Status (*fmi2ExitInitializationMode_t)(fmi2Component);
typedef fmi2Status (*fmi2Terminate_t)(fmi2Component);
typedef fmi2Status (*fmi2SetReal_t)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2Real[]);
typedef fmi2Status (*fmi2GetReal_t)(fmi2Component, const fmi2ValueReference[], size_t, fmi2Real[]);
typedef fmi2Status (*fmi2DoStep_t)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
typedef fmi2Status (*fmi2GetFMUstate_t)(fmi2Component, fmi2FMUstate*);
typedef fmi2Status (*fmi2SetFMUstate_t)(fmi2Component, fmi2FMUstate);
typedef fmi2Status (*fmi2FreeFMUstate_t)(fmi2Component, fmi2FMUstate*);
typedef fmi2Status (*fmi2GetDirectionalDerivative_t)(fmi2Component, const fmi2ValueReference[], size_t,
                                                     const fmi2ValueReference[], size_t, const fmi2Real[], fmi2Real[]);
typedef fmi2Status (*fmi2GetRealStatus_t)(fmi2Component, const fmi2StatusKind, fmi2Real*);

static void logger(fmi2ComponentEnvironment environment, fmi2String instance, fmi2Status status, fmi2String category,
                   fmi2String message, ...) {
  (void)environment;
  (void)category;
  fprintf(stderr, "[%s, status %d] %s\n", instance, (int)status, message);
}

/* The guid="..." of modelDescription.xml, into 'guid'. */
static int read_guid(const char* dir, char* guid, size_t size) {
  char path[4096];
  snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
  FILE* file = fopen(path, "r");
  if (!file) return 0;
  static char text[1 << 16];
  const size_t length = fread(text, 1, sizeof text - 1, file);
  fclose(file);
  text[length] = '\0';
  const char* start = strstr(text, "guid=\"");
  if (!start) return 0;
  start += 6;
  const char* end = strchr(start, '"');
  if (!end || (size_t)(end - start) >= size) return 0;
  memcpy(guid, start, (size_t)(end - start));
  guid[end - start] = '\0';
  return 1;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: fmu_host UNPACKED_FMU_DIR\n");
    return 2;
  }
  char path[4096], guid[128], resources[4200];
  snprintf(path, sizeof path, "%s/binaries/linux64/tirefe_tire.so", argv[1]);
  snprintf(resources, sizeof resources, "file://%s/resources", argv[1]);
  void* library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!library || !read_guid(argv[1], guid, sizeof guid)) {
    fprintf(stderr, "fmu_host: cannot load %s or read its GUID: %s\n", path, library ? "" : dlerror());
    return 1;
  }
  LOAD(fmi2Instantiate);
  LOAD(fmi2FreeInstance);
  LOAD(fmi2SetupExperiment);
  LOAD(fmi2EnterInitializationMode);
  LOAD(fmi2ExitInitializationMode);
  LOAD(fmi2Terminate);
  LOAD(fmi2SetReal);
  LOAD(fmi2GetReal);
  LOAD(fmi2DoStep);
  LOAD(fmi2GetFMUstate);
  LOAD(fmi2SetFMUstate);
  LOAD(fmi2FreeFMUstate);
  LOAD(fmi2GetDirectionalDerivative);
  LOAD(fmi2GetRealStatus);
  if (!fmi2Instantiate || !fmi2DoStep || !fmi2GetDirectionalDerivative || !fmi2GetRealStatus || !fmi2FreeFMUstate) {
    fprintf(stderr, "fmu_host: an fmi2 function is missing\n");
    return 1;
  }
  const fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
  fmi2Component tire = fmi2Instantiate("tire", fmi2CoSimulation, guid, resources, &callbacks, fmi2False, fmi2False);
  const fmi2ValueReference x_z_spin[] = {0, 1, 2}, fx_fz_my[] = {3, 4, 5}, pressure[] = {10};
  const fmi2Real kilopascals_180[] = {180e3};
  if (!tire || fmi2SetupExperiment(tire, fmi2False, 0.0, 0.0, fmi2False, 0.0) != fmi2OK ||
      fmi2SetReal(tire, pressure, 1, kilopascals_180) != fmi2OK || fmi2EnterInitializationMode(tire) != fmi2OK ||
      fmi2ExitInitializationMode(tire) != fmi2OK) {
    fprintf(stderr, "fmu_host: cannot instantiate and initialize the FMU\n");
    return 1;
  }

  const double h = 1e-3;
  double t = 0.0, force[3], saved_force[3] = {0};
  fmi2FMUstate saved = NULL, before_last = NULL;
  for (int step = 1; step <= 120; ++step) {
    const double s = step < 100 ? step / 100.0 : 1.0;
    const fmi2Real motion[3] = {0.0, -0.005 * s * s * (3.0 - 2.0 * s), 0.0};
    if (step == 61 && fmi2GetFMUstate(tire, &saved) != fmi2OK) return 1;
    if (step == 120 && fmi2GetFMUstate(tire, &before_last) != fmi2OK) return 1;
    if (fmi2SetReal(tire, x_z_spin, 3, motion) != fmi2OK || fmi2DoStep(tire, t, h, fmi2True) != fmi2OK) {
      fprintf(stderr, "fmu_host: step %d failed\n", step);
      return 1;
    }
    t += h;
  }
  fmi2GetReal(tire, fx_fz_my, 3, force);
  const fmi2ValueReference fz[] = {4}, z[] = {1};
  const fmi2Real unit[] = {1.0};
  fmi2Real h_zz = 0.0;
  if (fmi2GetDirectionalDerivative(tire, fz, 1, z, 1, unit, &h_zz) != fmi2OK) return 1;

  /* The last step again from its start with z moved by +-dz: dFz/dz by differences. */
  const double dz = 1e-7;
  fmi2Real fz_moved[2];
  for (int side = 0; side < 2; ++side) {
    const fmi2Real moved[3] = {0.0, -0.005 + (side == 0 ? dz : -dz), 0.0};
    if (fmi2SetFMUstate(tire, before_last) != fmi2OK || fmi2SetReal(tire, x_z_spin, 3, moved) != fmi2OK ||
        fmi2DoStep(tire, t - h, h, fmi2True) != fmi2OK || fmi2GetReal(tire, fz, 1, &fz_moved[side]) != fmi2OK)
      return 1;
  }
  fmi2FreeFMUstate(tire, &before_last);
  const double h_zz_fd = (fz_moved[0] - fz_moved[1]) / (2.0 * dz);

  /* Back to step 61 and the same steps again. */
  if (fmi2SetFMUstate(tire, saved) != fmi2OK) return 1;
  t = 0.060;
  for (int step = 61; step <= 120; ++step) {
    const double s = step < 100 ? step / 100.0 : 1.0;
    const fmi2Real motion[3] = {0.0, -0.005 * s * s * (3.0 - 2.0 * s), 0.0};
    if (fmi2SetReal(tire, x_z_spin, 3, motion) != fmi2OK || fmi2DoStep(tire, t, h, fmi2True) != fmi2OK) return 1;
    t += h;
  }
  fmi2GetReal(tire, fx_fz_my, 3, saved_force);
  fmi2FreeFMUstate(tire, &saved);
  const int repeat = memcmp(force, saved_force, sizeof force) == 0;

  /* Through the rim in one step: discarded, and the FMU stays at its last time and force. */
  const fmi2Real crush[3] = {0.0, -0.4, 0.0};
  fmi2SetReal(tire, x_z_spin, 3, crush);
  const fmi2Status crushed = fmi2DoStep(tire, t, h, fmi2True);
  fmi2Real last_time = -1.0, after[3];
  fmi2GetRealStatus(tire, fmi2LastSuccessfulTime, &last_time);
  fmi2GetReal(tire, fx_fz_my, 3, after);
  const int discard = crushed == fmi2Discard && last_time == t && memcmp(after, force, sizeof force) == 0;

  printf("Fz %.17g\nH_zz %.17g\nH_zz_fd %.17g\nrepeat %d\ndiscard %d\n", force[1], h_zz, h_zz_fd, repeat, discard);
  fmi2Terminate(tire);
  fmi2FreeInstance(tire);
  dlclose(library);
  return 0;
}
