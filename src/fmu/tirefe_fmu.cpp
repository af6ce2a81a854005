// tirefe_tire.fmu: the tire behind its spindle as an FMI 2.0 co-simulation FMU, over the
// C API (include/tirefe.h). Inputs: the wheel centre's x, z and spin and their rates at the
// communication point (start-of-step values, as generic masters hand them over); outputs:
// the force the tire exerts on the wheel (Fx, Fz, My) at the communication point, both in
// the C API's ISO 8855 wheel axes heading +x. fmi2DoStep moves the spindle along the
// inputs extrapolated with their rates (tirefe_advance: the tire's own steps, no kink where
// communication steps meet); a step the tire cannot finish is discarded where it stopped.
// The tire, its road, its integrator and steps are parameters; FMU states are
// tirefe_save_state copies (docs/fmu.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <new>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fmu/fmi2.h"
#include "fmu/fmu_files.hpp"
#include "tirefe.h"

namespace {

// Value references: as in modelDescription.xml (cmake/modelDescription.xml.in).
enum Reference : fmi2ValueReference {
  kX = 0,  // inputs at the communication point [m, m, rad]
  kZ = 1,
  kSpin = 2,
  kFx = 3,  // outputs [N, N, N m]
  kFz = 4,
  kMy = 5,
  kVx = 6,  // inputs: the rates of x, z, spin [m/s, m/s, rad/s]
  kVz = 7,
  kSpinRate = 8,
  kPressure = 10,  // Real parameters
  kFriction = 12,
  kHhtAlpha = 13,
  kMaxStep = 15,
  kRoadEdgeRadius = 16,
  kRoadLateral = 24,
  kRhoInf = 25,
  kMaxTime = 18,
  kMaxResidual = 19,
  kMaxIterations = 17,  // Integer parameter
  kFreeSpin = 14,       // Boolean parameter
  kTire = 20,           // String parameters
  kRoad = 21,
  kRoadTrack = 22,
  kTireParameters = 23,
  kIntegrator = 26
};

// The C API's shortest step (include/tirefe.h).
constexpr double kMinCommunicationStep = 1e-7;
// The most of the tire's steps one fmi2DoStep may take (some 15 min of stepping).
constexpr double kMaxTireSteps = 1e6;

// The FMI 2.0 co-simulation states (section 4.2.4) an instance is in.
enum class Phase { Instantiated, Initializing, Stepping, Terminated };

const char* phase_name(Phase phase) {
  switch (phase) {
    case Phase::Instantiated: return "instantiated";
    case Phase::Initializing: return "initialization mode";
    case Phase::Stepping: return "step mode";
    case Phase::Terminated: return "terminated";
  }
  return "";
}

/// The parameters with their start values (modelDescription.xml's).
struct Parameters {
  std::string tire = "145SR12.tir", road, road_track, tire_parameters, integrator;
  double pressure = 0.0;  // 0: the tire file's
  double friction = 0.8, hht_alpha = -0.1, max_step = 5e-4, road_edge_radius = 0.0, road_lateral = 0.0, rho_inf = 0.9;
  double max_time = 0.0, max_residual = 0.0;  // the step budget (tirefe_set_step_budget); 0: none
  int max_iterations = 0;                     // 0: Newton to convergence
  bool free_spin = true;
};

/// What changes as the FMU steps: the inputs, outputs and times an FMU state saves with the tire.
struct Variables {
  double input[9] = {};  // by value reference: x, z, spin, (outputs), vx, vz, spin rate
  double force[3] = {};
  double time = 0.0;         // the master's communication time
  double last_rate[3] = {};  // the rates the last step started from (the tire starts at rest)
  double last_step = 0.0;    // that step's size; 0: none yet
  double path_rate[3] = {};  // the rates the spindle's path ended the last step with
  bool stopped = false;      // a discarded step left the FMU where it stopped
};

struct SavedInstance {
  tirefe_saved_state* tire = nullptr;
  Variables variables;
};

struct Instance {
  Instance(std::string name, std::string resources, const fmi2CallbackFunctions& callbacks, bool logging)
      : name(std::move(name)), resources(std::move(resources)), callbacks(callbacks), logging(logging) {}

  std::string name, resources;
  fmi2CallbackFunctions callbacks;
  bool logging;
  Phase phase = Phase::Instantiated;
  Parameters parameters;
  Variables now;
  double start_time = 0.0;  // the master's, from fmi2SetupExperiment
  double tire_start = 0.0;  // the tire's committed time at the master's start_time
  double x_origin = 0.0;    // the inputs x and spin when the tire was built: where it stands
  double spin_origin = 0.0;
  tirefe_tire* tire = nullptr;
  bool tire_current = false;  // built with the parameters and inputs set now
  std::set<SavedInstance*> states;
  std::string string_value[kIntegrator - kTire + 1];  // what fmi2GetString hands out, by value reference
};

// Every live instance: a call with anything else (a freed instance, a stray pointer, NULL)
// is refused instead of followed. An address reused by a later instance is not caught.
std::mutex registry_mutex;
std::set<const void*> registry;

Instance* instance_of(fmi2Component c) {
  const std::lock_guard<std::mutex> lock(registry_mutex);
  return registry.count(c) ? static_cast<Instance*>(c) : nullptr;
}

/// Runs 'body' on the instance 'c', or answers fmi2Error when 'c' is none (there is no
/// logger to tell).
template <class Body>
fmi2Status on_instance(fmi2Component c, Body&& body) {
  Instance* instance = instance_of(c);
  return instance ? body(*instance) : fmi2Error;
}

/// Logs through the importer's logger; the message is its own format ('%' escaped).
fmi2Status report(const Instance& instance, fmi2Status status, const std::string& message) {
  if (!instance.callbacks.logger || (status == fmi2OK && !instance.logging)) return status;
  static const char* const categories[] = {"logAll",         "logStatusWarning", "logStatusDiscard",
                                           "logStatusError", "logStatusFatal",   "logStatusPending"};
  std::string format;
  for (char c : message) format += c == '%' ? std::string("%%") : std::string(1, c);
  instance.callbacks.logger(instance.callbacks.componentEnvironment, instance.name.c_str(), status,
                            categories[static_cast<int>(status)], format.c_str());
  return status;
}

/// A call allowed only in 'allowed' phases; fmi2Error with the reason otherwise.
template <class... Phases>
bool refused_in_phase(Instance& instance, const char* function, Phases... allowed) {
  if (((instance.phase == allowed) || ...)) return false;
  report(instance, fmi2Error, std::string(function) + " is not allowed in " + phase_name(instance.phase));
  return true;
}

std::string seconds(double value) {
  std::ostringstream text;
  text << value << " s";
  return text.str();
}

/// "key=value" pairs separated by commas, semicolons or blanks, for tirefe_open's overrides.
std::vector<std::pair<std::string, double>> parse_tire_parameters(std::string text) {
  for (char& c : text)
    if (c == ',' || c == ';') c = ' ';
  std::vector<std::pair<std::string, double>> values;
  std::istringstream items(text);
  for (std::string item; items >> item;) {
    const size_t equals = item.find('=');
    const char* number = equals == std::string::npos ? "" : item.c_str() + equals + 1;
    char* end = nullptr;
    const double value = std::strtod(number, &end);
    if (equals == 0 || end == number || *end != '\0' || !std::isfinite(value))
      throw std::invalid_argument("tire_parameters: '" + item + "' is not key=number");
    values.emplace_back(item.substr(0, equals), value);
  }
  return values;
}

/// Builds the tire with the parameters and the inputs set: pressed to the input z, standing
/// at the input x and spin; fmi2Error with the reason when it cannot be built.
fmi2Status build_tire(Instance& instance) {
  if (instance.tire_current) return fmi2OK;
  tirefe_close(instance.tire);
  instance.tire = nullptr;
  const Parameters& p = instance.parameters;
  const double* input = instance.now.input;
  if (input[kVx] != 0.0 || input[kVz] != 0.0 || (!p.free_spin && input[kSpinRate] != 0.0))
    return report(instance, fmi2Error,
                  "the tire starts at rest: set the initial vx, vz and spin_rate to 0 (they are " +
                      std::to_string(input[kVx]) + ", " + std::to_string(input[kVz]) + ", " +
                      std::to_string(input[kSpinRate]) + ")");
  std::string tire, road;
  std::vector<std::pair<std::string, double>> values;
  try {
    // A .tir file in the resources or on disk; anything else names a shipped parameter module.
    const bool file = p.tire.size() > 4 && p.tire.compare(p.tire.size() - 4, 4, ".tir") == 0;
    tire = file ? tirefe::fmu::resolve_file(p.tire, instance.resources) : p.tire;
    if (!p.road.empty()) road = tirefe::fmu::resolve_file(p.road, instance.resources);
    if (p.pressure > 0.0) values.emplace_back("pressure", p.pressure);
    for (const auto& value : parse_tire_parameters(p.tire_parameters)) values.push_back(value);
  } catch (const std::invalid_argument& error) {
    return report(instance, fmi2Error, std::string("cannot build the tire: ") + error.what());
  }
  std::vector<tirefe_parameter> overrides;
  for (const auto& [name, value] : values) overrides.push_back({name.c_str(), value});
  tirefe_options options;
  tirefe_default_options(&options);
  options.friction = p.friction;
  options.hht_alpha = p.hht_alpha;
  options.integrator = p.integrator.empty() ? nullptr : p.integrator.c_str();
  options.rho_inf = p.rho_inf;
  options.free_spin = p.free_spin ? 1 : 0;
  options.road = road.empty() ? nullptr : road.c_str();
  options.road_track = p.road_track.empty() ? nullptr : p.road_track.c_str();
  options.road_lateral = p.road_lateral;
  options.road_start = -input[kX];  // the tire is built at x = 0 of its own: the road moves under it
  options.road_edge_radius = p.road_edge_radius;
  options.start_z = input[kZ];
  char error[512];
  if (tirefe_open(tire.c_str(), overrides.data(), overrides.size(), &options, &instance.tire, error, sizeof error) !=
      TIREFE_OK)
    return report(instance, fmi2Error, std::string("cannot build the tire: ") + error);
  const tirefe_step_budget budget{p.max_iterations, p.max_time, p.max_residual};
  if (tirefe_set_step_budget(instance.tire, &budget) != TIREFE_OK)
    return report(instance, fmi2Error, std::string("cannot set the step budget: ") + tirefe_message(instance.tire));
  tirefe_spindle_state state;
  tirefe_state(instance.tire, &state);
  std::memcpy(instance.now.force, state.force, sizeof state.force);
  instance.tire_start = state.time;
  instance.x_origin = input[kX];
  instance.spin_origin = input[kSpin];
  instance.tire_current = true;
  return report(instance, fmi2OK, "built the tire '" + tire + "' on " + (road.empty() ? "a flat road" : road));
}

/// A Real variable: an input, an output or a parameter; null for another reference.
double* real_variable(Instance& instance, fmi2ValueReference reference) {
  Parameters& p = instance.parameters;
  switch (reference) {
    case kX:
    case kZ:
    case kSpin:
    case kVx:
    case kVz:
    case kSpinRate: return &instance.now.input[reference];
    case kFx:
    case kFz:
    case kMy: return &instance.now.force[reference - kFx];
    case kPressure: return &p.pressure;
    case kFriction: return &p.friction;
    case kHhtAlpha: return &p.hht_alpha;
    case kMaxStep: return &p.max_step;
    case kRoadEdgeRadius: return &p.road_edge_radius;
    case kRoadLateral: return &p.road_lateral;
    case kMaxTime: return &p.max_time;
    case kMaxResidual: return &p.max_residual;
    case kRhoInf: return &p.rho_inf;
    default: return nullptr;
  }
}

std::string* string_variable(Instance& instance, fmi2ValueReference reference) {
  Parameters& p = instance.parameters;
  switch (reference) {
    case kTire: return &p.tire;
    case kRoad: return &p.road;
    case kRoadTrack: return &p.road_track;
    case kTireParameters: return &p.tire_parameters;
    case kIntegrator: return &p.integrator;
    default: return nullptr;
  }
}

bool is_input(fmi2ValueReference reference) {
  return reference <= kSpinRate && !(reference >= kFx && reference <= kMy);
}

/// Parameters are set before the tire is built; inputs at any time before termination.
fmi2Status check_settable(Instance& instance, fmi2ValueReference reference) {
  if (is_input(reference)) {
    if (instance.phase == Phase::Terminated) return report(instance, fmi2Error, "inputs are not set once terminated");
    return fmi2OK;
  }
  if (instance.phase != Phase::Instantiated && instance.phase != Phase::Initializing)
    return report(
        instance, fmi2Error,
        "the tire's parameters are fixed once it is initialized (value reference " + std::to_string(reference) + ")");
  return fmi2OK;
}

void free_state(Instance& instance, SavedInstance* saved) {
  instance.states.erase(saved);
  tirefe_free_state(saved->tire);
  delete saved;
}

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t, const fmi2String[]) {
  return on_instance(c, [&](Instance& instance) {
    instance.logging = loggingOn != fmi2False;
    return fmi2OK;
  });
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions, fmi2Boolean,
                              fmi2Boolean loggingOn) {
  if (!functions) return nullptr;
  Instance probe(instanceName ? instanceName : "tire", "", *functions, true);  // to log why it is refused
  std::string refusal, resources;
  if (fmuType != fmi2CoSimulation) refusal = "this FMU is for co-simulation only";
  if (!fmuGUID || std::strcmp(fmuGUID, TIREFE_FMU_GUID) != 0)
    refusal = "the GUID is not this FMU's (" TIREFE_FMU_GUID "): a modelDescription.xml of another FMU?";
  try {
    if (fmuResourceLocation && *fmuResourceLocation) resources = tirefe::fmu::path_of_file_uri(fmuResourceLocation);
  } catch (const std::invalid_argument& error) {
    refusal = std::string("the resource location: ") + error.what();
  }
  Instance* instance = refusal.empty() ? new (std::nothrow)
                                             Instance(probe.name, resources, *functions, loggingOn != fmi2False)
                                       : nullptr;
  if (!instance) {
    report(probe, fmi2Error, refusal.empty() ? "out of memory" : refusal);
    return nullptr;
  }
  const std::lock_guard<std::mutex> lock(registry_mutex);
  registry.insert(instance);
  return instance;
}

void fmi2FreeInstance(fmi2Component c) {
  {
    const std::lock_guard<std::mutex> lock(registry_mutex);
    if (!registry.erase(c)) return;  // not an instance (any more): nothing to free
  }
  Instance* instance = static_cast<Instance*>(c);
  while (!instance->states.empty()) free_state(*instance, *instance->states.begin());
  tirefe_close(instance->tire);
  delete instance;
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real startTime, fmi2Boolean, fmi2Real) {
  return on_instance(c, [&](Instance& instance) {
    if (refused_in_phase(instance, "fmi2SetupExperiment", Phase::Instantiated)) return fmi2Error;
    if (!std::isfinite(startTime)) return report(instance, fmi2Error, "the start time must be finite");
    instance.start_time = instance.now.time = startTime;
    return fmi2OK;
  });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return on_instance(c, [&](Instance& instance) {
    if (refused_in_phase(instance, "fmi2EnterInitializationMode", Phase::Instantiated)) return fmi2Error;
    instance.phase = Phase::Initializing;
    return fmi2OK;
  });
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return on_instance(c, [&](Instance& instance) {
    if (refused_in_phase(instance, "fmi2ExitInitializationMode", Phase::Initializing)) return fmi2Error;
    const fmi2Status status = build_tire(instance);
    if (status == fmi2OK) instance.phase = Phase::Stepping;
    return status;
  });
}

fmi2Status fmi2Terminate(fmi2Component c) {
  return on_instance(c, [&](Instance& instance) {
    if (refused_in_phase(instance, "fmi2Terminate", Phase::Stepping)) return fmi2Error;
    instance.phase = Phase::Terminated;
    tirefe_budget_report budget{};
    tirefe_step_budget_report(instance.tire, &budget);
    std::ostringstream text;
    text << "step budget: " << budget.steps << " steps, " << budget.unconverged << " ended unconverged (worst |R|/Rref "
         << budget.worst_residual << "), " << budget.overruns << " overran max_iterations, " << budget.time_misses
         << " max_time; the longest " << budget.worst_time << " s";
    return report(instance, fmi2OK, text.str());
  });
}

// Back to the state fmi2Instantiate left: no tire, every variable at its start value.
// FMU states saved before stay valid until freed.
fmi2Status fmi2Reset(fmi2Component c) {
  return on_instance(c, [&](Instance& instance) {
    tirefe_close(instance.tire);
    instance.tire = nullptr;
    instance.tire_current = false;
    instance.parameters = Parameters{};
    instance.now = Variables{};
    instance.start_time = 0.0;
    instance.phase = Phase::Instantiated;
    return fmi2OK;
  });
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  return on_instance(c, [&](Instance& instance) {
    if (nvr > 0 && (!vr || !value)) return report(instance, fmi2Error, "fmi2GetReal: NULL arrays");
    for (size_t i = 0; i < nvr; ++i) {
      const double* variable = real_variable(instance, vr[i]);
      if (!variable)
        return report(instance, fmi2Error, "no Real variable with value reference " + std::to_string(vr[i]));
      // The outputs in initialization mode are those of the tire built as things stand.
      if (vr[i] >= kFx && vr[i] <= kMy && instance.phase == Phase::Initializing && build_tire(instance) != fmi2OK)
        return fmi2Error;
      value[i] = *variable;
    }
    return fmi2OK;
  });
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  return on_instance(c, [&](Instance& instance) {
    if (nvr > 0 && (!vr || !value)) return report(instance, fmi2Error, "fmi2SetReal: NULL arrays");
    for (size_t i = 0; i < nvr; ++i) {
      double* variable = real_variable(instance, vr[i]);
      if (!variable || (vr[i] >= kFx && vr[i] <= kMy))
        return report(instance, fmi2Error, "no settable Real with value reference " + std::to_string(vr[i]));
      if (check_settable(instance, vr[i]) != fmi2OK) return fmi2Error;
      if (!std::isfinite(value[i]))
        return report(instance, fmi2Error, "the Real with value reference " + std::to_string(vr[i]) + " is not finite");
      if (vr[i] == kMaxStep && !(value[i] >= kMinCommunicationStep))
        return report(instance, fmi2Error, "max_step must be at least " + seconds(kMinCommunicationStep));
      if (vr[i] == kPressure && value[i] < 0.0)
        return report(instance, fmi2Error, "pressure must be >= 0 (0: the tire file's)");
      if ((vr[i] == kMaxTime || vr[i] == kMaxResidual) && value[i] < 0.0)
        return report(instance, fmi2Error, "max_time and max_residual must be >= 0 (0: none, 1e-4)");
      *variable = value[i];
      if (instance.phase != Phase::Stepping) instance.tire_current = false;
    }
    return fmi2OK;
  });
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
  return on_instance(c, [&](Instance& instance) {
    if (nvr > 0 && (!vr || !value)) return report(instance, fmi2Error, "fmi2GetInteger: NULL arrays");
    for (size_t i = 0; i < nvr; ++i) {
      if (vr[i] != kMaxIterations)
        return report(instance, fmi2Error, "no Integer with value reference " + std::to_string(vr[i]));
      value[i] = instance.parameters.max_iterations;
    }
    return fmi2OK;
  });
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
  return on_instance(c, [&](Instance& instance) {
    if (nvr > 0 && (!vr || !value)) return report(instance, fmi2Error, "fmi2SetInteger: NULL arrays");
    for (size_t i = 0; i < nvr; ++i) {
      if (vr[i] != kMaxIterations)
        return report(instance, fmi2Error, "no Integer with value reference " + std::to_string(vr[i]));
      if (check_settable(instance, vr[i]) != fmi2OK) return fmi2Error;
      if (value[i] < 0) return report(instance, fmi2Error, "max_iterations must be >= 0 (0: Newton to convergence)");
      instance.parameters.max_iterations = value[i];
      instance.tire_current = false;
    }
    return fmi2OK;
  });
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[]) {
  return on_instance(c, [&](Instance& instance) {
    if (nvr > 0 && (!vr || !value)) return report(instance, fmi2Error, "fmi2GetString: NULL arrays");
    for (size_t i = 0; i < nvr; ++i) {
      const std::string* variable = string_variable(instance, vr[i]);
      if (!variable) return report(instance, fmi2Error, "no String with value reference " + std::to_string(vr[i]));
      std::string& copy = instance.string_value[vr[i] - kTire];  // valid until the next call, as FMI asks
      copy = *variable;
      value[i] = copy.c_str();
    }
    return fmi2OK;
  });
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[]) {
  return on_instance(c, [&](Instance& instance) {
    if (nvr > 0 && (!vr || !value)) return report(instance, fmi2Error, "fmi2SetString: NULL arrays");
    for (size_t i = 0; i < nvr; ++i) {
      std::string* variable = string_variable(instance, vr[i]);
      if (!variable) return report(instance, fmi2Error, "no String with value reference " + std::to_string(vr[i]));
      if (check_settable(instance, vr[i]) != fmi2OK) return fmi2Error;
      *variable = value[i] ? value[i] : "";
      instance.tire_current = false;
    }
    return fmi2OK;
  });
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
  return on_instance(c, [&](Instance& instance) {
    if (nvr > 0 && (!vr || !value)) return report(instance, fmi2Error, "fmi2GetBoolean: NULL arrays");
    for (size_t i = 0; i < nvr; ++i) {
      if (vr[i] != kFreeSpin)
        return report(instance, fmi2Error, "no Boolean with value reference " + std::to_string(vr[i]));
      value[i] = instance.parameters.free_spin ? fmi2True : fmi2False;
    }
    return fmi2OK;
  });
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
  return on_instance(c, [&](Instance& instance) {
    if (nvr > 0 && (!vr || !value)) return report(instance, fmi2Error, "fmi2SetBoolean: NULL arrays");
    for (size_t i = 0; i < nvr; ++i) {
      if (vr[i] != kFreeSpin)
        return report(instance, fmi2Error, "no Boolean with value reference " + std::to_string(vr[i]));
      if (check_settable(instance, vr[i]) != fmi2OK) return fmi2Error;
      instance.parameters.free_spin = value[i] != fmi2False;
      instance.tire_current = false;
    }
    return fmi2OK;
  });
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
  return on_instance(c, [&](Instance& instance) {
    if (!FMUstate) return report(instance, fmi2Error, "fmi2GetFMUstate: FMUstate is NULL");
    if (!instance.tire || !instance.tire_current)
      return report(instance, fmi2Error, "no tire to save: initialize the FMU first");
    SavedInstance* saved = static_cast<SavedInstance*>(*FMUstate);
    if (saved && !instance.states.count(saved))
      return report(instance, fmi2Error, "fmi2GetFMUstate: *FMUstate is neither NULL nor a state of this instance");
    tirefe_saved_state* tire_state = nullptr;
    if (tirefe_save_state(instance.tire, &tire_state) != TIREFE_OK)
      return report(instance, fmi2Error, tirefe_message(instance.tire));
    if (!saved) {
      saved = new (std::nothrow) SavedInstance;
      if (!saved) return tirefe_free_state(tire_state), report(instance, fmi2Error, "out of memory");
      instance.states.insert(saved);
    }
    tirefe_free_state(saved->tire);
    saved->tire = tire_state;
    saved->variables = instance.now;
    *FMUstate = saved;
    return fmi2OK;
  });
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
  return on_instance(c, [&](Instance& instance) {
    SavedInstance* saved = static_cast<SavedInstance*>(FMUstate);
    if (!saved || !instance.states.count(saved))
      return report(instance, fmi2Error, "fmi2SetFMUstate: not a state of this instance (freed, or never saved)");
    if (!instance.tire) return report(instance, fmi2Error, "no tire to restore into: initialize the FMU first");
    if (tirefe_restore_state(instance.tire, saved->tire) != TIREFE_OK)
      return report(instance, fmi2Error, tirefe_message(instance.tire));
    instance.now = saved->variables;
    return fmi2OK;
  });
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
  return on_instance(c, [&](Instance& instance) {
    if (!FMUstate || !*FMUstate) return fmi2OK;
    SavedInstance* saved = static_cast<SavedInstance*>(*FMUstate);
    if (!instance.states.count(saved))
      return report(instance, fmi2Error, "fmi2FreeFMUstate: not a state of this instance (freed already?)");
    free_state(instance, saved);
    *FMUstate = nullptr;
    return fmi2OK;
  });
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate, size_t*) {
  return on_instance(c, [&](Instance& instance) {
    return report(instance, fmi2Error, "FMU states are not serialized (canSerializeFMUstate=\"false\")");
  });
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate, fmi2Byte[], size_t) {
  return fmi2SerializedFMUstateSize(c, nullptr, nullptr);
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte[], size_t, fmi2FMUstate*) {
  return fmi2SerializedFMUstateSize(c, nullptr, nullptr);
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2ValueReference[],
                                        size_t, const fmi2Real[], fmi2Real[]) {
  return on_instance(c, [&](Instance& instance) {
    return report(instance, fmi2Error,
                  "no directional derivatives (providesDirectionalDerivative=\"false\"): the outputs at a "
                  "communication point do not depend on the inputs set there");
  });
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                       const fmi2Real[]) {
  return on_instance(c, [&](Instance& instance) {
    return report(instance, fmi2Error,
                  "input derivatives are not used (canInterpolateInputs=\"false\"): the rates are the inputs vx, vz, "
                  "spin_rate");
  });
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                        fmi2Real[]) {
  return on_instance(c, [&](Instance& instance) {
    return report(instance, fmi2Error, "output derivatives are not provided (maxOutputDerivativeOrder=\"0\")");
  });
}

// The inputs set before the step are the wheel centre's at its start; the spindle follows
// them extrapolated over the step, along the cubic that starts where the spindle is with the
// rates the last step ended with (tirefe_advance), in the tire's own steps. A step the tire
// cannot finish is discarded: the FMU stays where the tire stopped and asks to terminate.
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean) {
  return on_instance(c, [&](Instance& fmu) {
    if (refused_in_phase(fmu, "fmi2DoStep", Phase::Stepping)) return fmi2Error;
    const double t = currentCommunicationPoint, h = communicationStepSize;
    if (fmu.now.stopped)
      return report(fmu, fmi2Error,
                    "the tire stopped at t = " + seconds(fmu.now.time) +
                        " after a discarded step: restore a saved FMU state, or reset the FMU");
    if (!std::isfinite(t) || !(h > 0.0 && std::isfinite(h)))
      return report(
          fmu, fmi2Error,
          "fmi2DoStep needs a finite time and a finite step > 0 (got t = " + seconds(t) + ", h = " + seconds(h) + ")");
    if (h < kMinCommunicationStep)
      return report(fmu, fmi2Error,
                    "fmi2DoStep over " + seconds(h) + ": the tire takes no step below " +
                        seconds(kMinCommunicationStep) + " (round-off swamps its inertia there)");
    // No one can stop a call (fmi2CancelStep has nothing to cancel): its steps are bounded.
    if (h / fmu.parameters.max_step > kMaxTireSteps)
      return report(fmu, fmi2Error,
                    "fmi2DoStep over " + seconds(h) + " in the tire's steps of at most " +
                        seconds(fmu.parameters.max_step) +
                        " would take more than the 1000000 steps one call may take: communicate more often, or "
                        "set a larger max_step");
    if (std::abs(t - fmu.now.time) > 1e-9 * std::max(1.0, std::abs(t)))
      return report(fmu, fmi2Error,
                    "fmi2DoStep from t = " + seconds(t) + ", but the FMU is at t = " + seconds(fmu.now.time));
    // The inputs extrapolated to t + h, to second order: the rates' change over the last
    // step is their rate of change (the inputs' own acceleration) from here on.
    const double* in = fmu.now.input;
    const double position[3] = {in[kX] - fmu.x_origin, in[kZ], in[kSpin] - fmu.spin_origin};
    const double rate[3] = {in[kVx], in[kVz], in[kSpinRate]};
    tirefe_spindle_path path{};
    std::memcpy(path.start_velocity, fmu.now.path_rate, sizeof path.start_velocity);
    for (int c = 0; c < 3; ++c) {
      const double change = fmu.now.last_step > 0.0 ? (rate[c] - fmu.now.last_rate[c]) / fmu.now.last_step : 0.0;
      path.position[c] = position[c] + h * rate[c] + 0.5 * h * h * change;
      path.velocity[c] = rate[c] + h * change;
    }
    tirefe_spindle_state state;
    tirefe_state(fmu.tire, &state);
    path.duration = fmu.tire_start + (t + h - fmu.start_time) - state.time;  // lands on the master's t + h
    const tirefe_status status = tirefe_advance(fmu.tire, &path, fmu.parameters.max_step, nullptr);
    const std::string why = tirefe_message(fmu.tire);         // before the next call clears it
    if (status != TIREFE_OK && status != TIREFE_STEP_FAILED)  // refused before any step
      return report(fmu, fmi2Error, "fmi2DoStep from t = " + seconds(t) + ": " + why);
    tirefe_state(fmu.tire, &state);
    std::memcpy(fmu.now.force, state.force, sizeof state.force);
    if (status == TIREFE_OK) {
      fmu.now.time = t + h;
      std::memcpy(fmu.now.last_rate, rate, sizeof rate);
      std::memcpy(fmu.now.path_rate, path.velocity, sizeof path.velocity);
      fmu.now.last_step = h;
      return fmi2OK;
    }
    fmu.now.time = fmu.start_time + (state.time - fmu.tire_start);
    fmu.now.stopped = true;
    return report(fmu, fmi2Discard,
                  "fmi2DoStep from t = " + seconds(t) + " over " + seconds(h) +
                      " stopped at t = " + seconds(fmu.now.time) + ": " + why);
  });
}

fmi2Status fmi2CancelStep(fmi2Component c) {
  return on_instance(c, [&](Instance& instance) {
    return report(instance, fmi2Error, "steps are not asynchronous: nothing to cancel");
  });
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  return on_instance(c, [&](Instance& instance) { return report(instance, fmi2Discard, "no asynchronous status"); });
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  return on_instance(c, [&](Instance& instance) {
    if (s != fmi2LastSuccessfulTime || !value) return report(instance, fmi2Discard, "only fmi2LastSuccessfulTime");
    *value = instance.now.time;
    return fmi2OK;
  });
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return on_instance(c, [&](Instance& instance) { return report(instance, fmi2Discard, "no Integer status"); });
}
// fmi2Terminated: true once a discarded step stopped the tire (it cannot go on from there).
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  return on_instance(c, [&](Instance& instance) {
    if (s != fmi2Terminated || !value) return report(instance, fmi2Discard, "only fmi2Terminated");
    *value = instance.now.stopped ? fmi2True : fmi2False;
    return fmi2OK;
  });
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return on_instance(c, [&](Instance& instance) { return report(instance, fmi2Discard, "no String status"); });
}

}  // extern "C"
