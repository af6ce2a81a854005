// tirefe_tire.fmu: the tire behind its spindle as an FMI 2.0 co-simulation FMU, over the
// C API (include/tirefe.h). Inputs: the spindle's x, z and spin at the end of the step;
// outputs: the force the tire exerts on the wheel (Fx, Fz, My), both in the C API's ISO
// 8855 wheel axes heading +x; parameters: the tire's pressure and k_sw, the road
// friction, the integrator's HHT alpha and whether the spin is free. fmi2DoStep is a solve
// and a commit; a step that does not converge is discarded (the tire stays at the last
// communication point); FMU states are tirefe_save_state copies; the directional
// derivative is the spindle Jacobian of the last step (docs/coupling.md).
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <utility>

#include "fmu/fmi2.h"
#include "tirefe.h"

namespace {

// Value references: as in modelDescription.xml (cmake/modelDescription.xml.in).
enum Reference : fmi2ValueReference {
  kX = 0,
  kZ = 1,
  kSpin = 2,  // inputs [m, m, rad]
  kFx = 3,
  kFz = 4,
  kMy = 5,  // outputs [N, N, N m]
  kPressure = 10,
  kKsw = 11,
  kFriction = 12,
  kHhtAlpha = 13,  // Real parameters
  kFreeSpin = 14   // Boolean parameter
};

enum class Phase { Instantiated, Initializing, Stepping, Terminated };

/// What one FMU instance holds besides the tire: the variables' values and the last step's Jacobian.
struct Variables {
  double input[3] = {0.0, 0.0, 0.0};
  double force[3] = {0.0, 0.0, 0.0};
  double jacobian[3][3] = {};
  double time = 0.0;  // the FMU's communication time
};

struct Instance {
  Instance(std::string name, std::string resources, const fmi2CallbackFunctions& callbacks)
      : name(std::move(name)), resources(std::move(resources)), callbacks(callbacks) {}

  std::string name, resources;
  fmi2CallbackFunctions callbacks;
  Phase phase = Phase::Instantiated;
  double pressure = 208e3, k_sw = 100.0;  // the 145 SR-12's (resources/145SR12.tir)
  tirefe_options options{};
  tirefe_tire* tire = nullptr;
  Variables now;
};

/// An FMU state: the tire's checkpoint and the instance's variables.
struct SavedInstance {
  tirefe_saved_state* tire = nullptr;
  Variables variables;
};

Instance* instance_of(fmi2Component c) { return static_cast<Instance*>(c); }

fmi2Status report(const Instance& instance, fmi2Status status, const std::string& message) {
  if (instance.callbacks.logger)
    instance.callbacks.logger(instance.callbacks.componentEnvironment, instance.name.c_str(), status,
                              status == fmi2OK ? "logAll" : "logStatusError", "%s", message.c_str());
  return status;
}

/// "file:///a/b" or "file:/a/b" as a path.
std::string path_of_uri(const char* uri) {
  std::string text = uri ? uri : "";
  if (text.rfind("file://", 0) == 0)
    text = text.substr(7);
  else if (text.rfind("file:", 0) == 0)
    text = text.substr(5);
  while (text.size() > 1 && text.back() == '/') text.pop_back();
  return text;
}

fmi2Status open_tire(Instance& instance) {
  const tirefe_parameter overrides[] = {{"pressure", instance.pressure}, {"k_sw", instance.k_sw}};
  const std::string source = instance.resources + "/145SR12.tir";
  char error[512];
  if (tirefe_open(source.c_str(), overrides, 2, &instance.options, &instance.tire, error, sizeof error) != TIREFE_OK)
    return report(instance, fmi2Error, std::string("cannot build the tire: ") + error);
  tirefe_spindle_state state;
  tirefe_state(instance.tire, &state);
  for (int c = 0; c < 3; ++c) instance.now.force[c] = state.force[c];
  return fmi2OK;
}

double* real_variable(Instance& instance, fmi2ValueReference reference) {
  switch (reference) {
    case kX:
    case kZ:
    case kSpin: return &instance.now.input[reference - kX];
    case kFx:
    case kFz:
    case kMy: return &instance.now.force[reference - kFx];
    case kPressure: return &instance.pressure;
    case kKsw: return &instance.k_sw;
    case kFriction: return &instance.options.friction;
    case kHhtAlpha: return &instance.options.hht_alpha;
    default: return nullptr;
  }
}

bool is_parameter(fmi2ValueReference reference) { return reference >= kPressure; }

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Status fmi2SetDebugLogging(fmi2Component, fmi2Boolean, size_t, const fmi2String[]) { return fmi2OK; }

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions, fmi2Boolean,
                              fmi2Boolean) {
  if (fmuType != fmi2CoSimulation || !fmuGUID || std::strcmp(fmuGUID, TIREFE_FMU_GUID) != 0 || !functions)
    return nullptr;
  Instance* instance =
      new (std::nothrow) Instance(instanceName ? instanceName : "tire", path_of_uri(fmuResourceLocation), *functions);
  if (!instance) return nullptr;
  tirefe_default_options(&instance->options);
  return instance;
}

void fmi2FreeInstance(fmi2Component c) {
  Instance* instance = instance_of(c);
  if (!instance) return;
  tirefe_close(instance->tire);
  delete instance;
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real startTime, fmi2Boolean, fmi2Real) {
  instance_of(c)->now.time = startTime;
  return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  instance_of(c)->phase = Phase::Initializing;
  return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  Instance& instance = *instance_of(c);
  const fmi2Status status = open_tire(instance);
  if (status == fmi2OK) instance.phase = Phase::Stepping;
  return status;
}

fmi2Status fmi2Terminate(fmi2Component c) {
  instance_of(c)->phase = Phase::Terminated;
  return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c) {
  Instance& instance = *instance_of(c);
  tirefe_close(instance.tire);
  instance.tire = nullptr;
  instance.now = Variables{};
  instance.phase = Phase::Instantiated;
  return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  Instance& instance = *instance_of(c);
  for (size_t i = 0; i < nvr; ++i) {
    const double* variable = real_variable(instance, vr[i]);
    if (!variable) return report(instance, fmi2Error, "no Real variable with value reference " + std::to_string(vr[i]));
    value[i] = *variable;
  }
  return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  Instance& instance = *instance_of(c);
  for (size_t i = 0; i < nvr; ++i) {
    double* variable = real_variable(instance, vr[i]);
    if (!variable || (vr[i] >= kFx && vr[i] <= kMy))
      return report(instance, fmi2Error, "no settable Real with value reference " + std::to_string(vr[i]));
    if (is_parameter(vr[i]) && instance.phase == Phase::Stepping)
      return report(instance, fmi2Error, "the tire's parameters are fixed once it is initialized");
    if (!std::isfinite(value[i])) return report(instance, fmi2Error, "a Real that is not finite");
    *variable = value[i];
  }
  return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Integer[]) {
  return nvr == 0 ? fmi2OK : report(*instance_of(c), fmi2Error, "the tire has no Integer variables");
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2Integer[]) {
  return nvr == 0 ? fmi2OK : report(*instance_of(c), fmi2Error, "the tire has no Integer variables");
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2String[]) {
  return nvr == 0 ? fmi2OK : report(*instance_of(c), fmi2Error, "the tire has no String variables");
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2String[]) {
  return nvr == 0 ? fmi2OK : report(*instance_of(c), fmi2Error, "the tire has no String variables");
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
  Instance& instance = *instance_of(c);
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] != kFreeSpin)
      return report(instance, fmi2Error, "no Boolean with value reference " + std::to_string(vr[i]));
    value[i] = instance.options.free_spin ? fmi2True : fmi2False;
  }
  return fmi2OK;
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
  Instance& instance = *instance_of(c);
  for (size_t i = 0; i < nvr; ++i) {
    if (vr[i] != kFreeSpin)
      return report(instance, fmi2Error, "no Boolean with value reference " + std::to_string(vr[i]));
    if (instance.phase == Phase::Stepping)
      return report(instance, fmi2Error, "the tire's parameters are fixed once it is initialized");
    instance.options.free_spin = value[i] ? 1 : 0;
  }
  return fmi2OK;
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
  Instance& instance = *instance_of(c);
  if (!instance.tire || !FMUstate) return report(instance, fmi2Error, "no tire to save (initialize it first)");
  SavedInstance* saved = static_cast<SavedInstance*>(*FMUstate);
  if (!saved) saved = new (std::nothrow) SavedInstance;
  if (!saved) return report(instance, fmi2Error, "out of memory");
  tirefe_free_state(saved->tire);
  saved->tire = nullptr;
  if (tirefe_save_state(instance.tire, &saved->tire) != TIREFE_OK) {
    delete saved;
    *FMUstate = nullptr;
    return report(instance, fmi2Error, tirefe_message(instance.tire));
  }
  saved->variables = instance.now;
  *FMUstate = saved;
  return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
  Instance& instance = *instance_of(c);
  const SavedInstance* saved = static_cast<const SavedInstance*>(FMUstate);
  if (!instance.tire || !saved) return report(instance, fmi2Error, "no tire or no state to restore");
  if (tirefe_restore_state(instance.tire, saved->tire) != TIREFE_OK)
    return report(instance, fmi2Error, tirefe_message(instance.tire));
  instance.now = saved->variables;
  return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component, fmi2FMUstate* FMUstate) {
  if (!FMUstate || !*FMUstate) return fmi2OK;
  SavedInstance* saved = static_cast<SavedInstance*>(*FMUstate);
  tirefe_free_state(saved->tire);
  delete saved;
  *FMUstate = nullptr;
  return fmi2OK;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate, size_t*) {
  return report(*instance_of(c), fmi2Error, "FMU states are not serialized (canSerializeFMUstate=\"false\")");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate, fmi2Byte[], size_t) {
  return report(*instance_of(c), fmi2Error, "FMU states are not serialized (canSerializeFMUstate=\"false\")");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte[], size_t, fmi2FMUstate*) {
  return report(*instance_of(c), fmi2Error, "FMU states are not serialized (canSerializeFMUstate=\"false\")");
}

// d outputs / d inputs: the consistent spindle Jacobian of the last step (docs/spindle.md).
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                        const fmi2ValueReference vKnown_ref[], size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[]) {
  Instance& instance = *instance_of(c);
  for (size_t i = 0; i < nUnknown; ++i) {
    if (vUnknown_ref[i] < kFx || vUnknown_ref[i] > kMy)
      return report(instance, fmi2Error, "derivatives are of the outputs Fx, Fz, My only");
    dvUnknown[i] = 0.0;
    for (size_t j = 0; j < nKnown; ++j) {
      if (vKnown_ref[j] > kSpin) return report(instance, fmi2Error, "derivatives are with respect to x, z, spin only");
      dvUnknown[i] += instance.now.jacobian[vUnknown_ref[i] - kFx][vKnown_ref[j] - kX] * dvKnown[j];
    }
  }
  return fmi2OK;
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                       const fmi2Real[]) {
  return report(*instance_of(c), fmi2Error, "input derivatives are not used (canInterpolateInputs=\"false\")");
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                        fmi2Real[]) {
  return report(*instance_of(c), fmi2Error, "output derivatives are not provided (maxOutputDerivativeOrder=\"0\")");
}

// The inputs set before the step are where the spindle is at its end; a step the tire
// cannot solve is discarded, leaving the FMU at the communication point.
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean) {
  Instance& instance = *instance_of(c);
  if (instance.phase != Phase::Stepping || !instance.tire)
    return report(instance, fmi2Error, "fmi2DoStep before the tire is initialized");
  if (std::abs(currentCommunicationPoint - instance.now.time) > 1e-9 * (1.0 + std::abs(instance.now.time)))
    return report(instance, fmi2Error,
                  "fmi2DoStep from t = " + std::to_string(currentCommunicationPoint) +
                      ", the FMU is at t = " + std::to_string(instance.now.time));
  const tirefe_spindle_motion motion = {communicationStepSize, instance.now.input[0], instance.now.input[1],
                                        instance.now.input[2]};
  tirefe_spindle_force reply;
  if (tirefe_solve(instance.tire, &motion, &reply) != TIREFE_OK)
    return report(instance, fmi2Discard, tirefe_message(instance.tire));
  if (tirefe_commit(instance.tire) != TIREFE_OK) return report(instance, fmi2Discard, tirefe_message(instance.tire));
  std::memcpy(instance.now.force, reply.force, sizeof reply.force);
  std::memcpy(instance.now.jacobian, reply.jacobian, sizeof reply.jacobian);
  instance.now.time = currentCommunicationPoint + communicationStepSize;
  return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c) {
  return report(*instance_of(c), fmi2Error, "steps are not asynchronous: nothing to cancel");
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  return report(*instance_of(c), fmi2Discard, "no asynchronous status");
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  Instance& instance = *instance_of(c);
  if (s != fmi2LastSuccessfulTime || !value) return report(instance, fmi2Discard, "only fmi2LastSuccessfulTime");
  *value = instance.now.time;
  return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return report(*instance_of(c), fmi2Discard, "no Integer status");
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  if (s != fmi2Terminated || !value) return report(*instance_of(c), fmi2Discard, "only fmi2Terminated");
  *value = fmi2False;  // the tire never ends a simulation by itself
  return fmi2OK;
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return report(*instance_of(c), fmi2Discard, "no String status");
}

}  // extern "C"
