/* The FMI 2.0 functions the suite's dlopen hosts (fmu_host.c, fmi_abuser.c) call, as
 * pointers named like the standard's functions without "fmi2", and their loader. */
#ifndef TIREFE_FMI_FUNCTIONS_H
#define TIREFE_FMI_FUNCTIONS_H

#include <dlfcn.h>
#include <stddef.h>

#include "fmu/fmi2.h"

// clang-format off
#define FMI_FUNCTIONS(X)                                                                            \
  X(Instantiate) X(FreeInstance) X(SetupExperiment) X(EnterInitializationMode)                      \
  X(ExitInitializationMode) X(Terminate) X(Reset) X(SetReal) X(GetReal) X(SetInteger)               \
  X(GetInteger) X(SetBoolean) X(GetBoolean) X(SetString) X(GetString) X(DoStep) X(CancelStep)       \
  X(GetFMUstate) X(SetFMUstate) X(FreeFMUstate) X(SerializedFMUstateSize)                           \
  X(GetDirectionalDerivative) X(GetRealStatus) X(GetBooleanStatus)
// clang-format on

#define FMI_DECLARE(name) static __typeof__(fmi2##name)* name;
FMI_FUNCTIONS(FMI_DECLARE)
#undef FMI_DECLARE

/* Loads every function from 'library': NULL, or the name of one it does not export. */
static const char* load_fmi_functions(void* library) {
#define FMI_LOAD(name) \
  if (!(*(void**)(&name) = dlsym(library, "fmi2" #name))) return "fmi2" #name;
  FMI_FUNCTIONS(FMI_LOAD)
#undef FMI_LOAD
  return NULL;
}

#endif /* TIREFE_FMI_FUNCTIONS_H */
