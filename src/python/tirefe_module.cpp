// The Python module `tirefe` (pybind11): a deck run with parameters, and the tire behind
// its spindle as a class over the C API (include/tirefe.h), forces and Jacobians as
// numpy arrays (docs/coupling.md).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "macros/deck_runner.hpp"
#include "tirefe.h"

namespace py = pybind11;

namespace {

/// Raised for a step the tire could not solve: it stays at its committed state.
PyObject* step_failed_type = nullptr;

void raise_on_failure(tirefe_status status, const char* message) {
  if (status == TIREFE_OK) return;
  if (status == TIREFE_STEP_FAILED) {
    PyErr_SetString(step_failed_type, message);
    throw py::error_already_set();
  }
  if (status == TIREFE_INVALID_ARGUMENT) throw py::value_error(message);
  throw std::runtime_error(message);
}

class Tire {
 public:
  Tire(const std::string& source, const std::map<std::string, double>& parameters, double friction, double hht_alpha,
       bool free_spin, const std::string& heading) {
    std::vector<tirefe_parameter> overrides;
    for (const auto& [name, value] : parameters) overrides.push_back({name.c_str(), value});
    tirefe_options options;
    tirefe_default_options(&options);
    options.friction = friction;
    options.hht_alpha = hht_alpha;
    options.free_spin = free_spin ? 1 : 0;
    if (heading != "+x" && heading != "-x")
      throw py::value_error("heading must be \"+x\" or \"-x\", not \"" + heading + "\"");
    options.heading = heading == "+x" ? 1 : -1;
    char error[512] = "";
    raise_on_failure(
        tirefe_open(source.c_str(), overrides.data(), overrides.size(), &options, &tire_, error, sizeof error), error);
  }
  ~Tire() { tirefe_close(tire_); }
  Tire(const Tire&) = delete;
  Tire& operator=(const Tire&) = delete;

  py::tuple solve(double time_step, double x, double z, double spin) {
    const tirefe_spindle_motion motion{time_step, x, z, spin};
    tirefe_spindle_force out;
    tirefe_status status;
    {
      py::gil_scoped_release unlocked;  // other Python threads run while the tire solves
      status = tirefe_solve(tire_, &motion, &out);
    }
    raise_on_failure(status, tirefe_message(tire_));
    return reply(out);
  }
  py::tuple solve_velocity(double time_step, double vx, double vz, double spin_rate) {
    const double velocity[3] = {vx, vz, spin_rate};
    tirefe_spindle_force out;
    tirefe_status status;
    {
      py::gil_scoped_release unlocked;
      status = tirefe_solve_velocity(tire_, time_step, velocity, &out);
    }
    raise_on_failure(status, tirefe_message(tire_));
    return reply(out);
  }
  void commit() { raise_on_failure(tirefe_commit(tire_), tirefe_message(tire_)); }
  void revert() { raise_on_failure(tirefe_revert(tire_), tirefe_message(tire_)); }
  py::dict state() {
    tirefe_spindle_state state;
    raise_on_failure(tirefe_state(tire_, &state), tirefe_message(tire_));
    py::dict result;
    result["time"] = state.time;
    result["position"] = vector(state.position);
    result["velocity"] = vector(state.velocity);
    result["force"] = vector(state.force);
    return result;
  }
  double road_level() {
    double level = 0.0;
    raise_on_failure(tirefe_road_level(tire_, &level), tirefe_message(tire_));
    return level;
  }

 private:
  static py::array_t<double> vector(const double (&values)[3]) {
    py::array_t<double> array(3);
    for (int i = 0; i < 3; ++i) array.mutable_at(i) = values[i];
    return array;
  }
  static py::tuple reply(const tirefe_spindle_force& out) {
    py::array_t<double> jacobian({3, 3});
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) jacobian.mutable_at(i, j) = out.jacobian[i][j];
    return py::make_tuple(vector(out.force), jacobian);
  }

  tirefe_tire* tire_ = nullptr;
};

/// tirefe_static_forces: Fz [N] at each deflection [m] of a quasi-static press.
py::array_t<double> static_forces(const std::string& source, const std::map<std::string, double>& parameters,
                                  const std::vector<double>& deflections) {
  std::vector<tirefe_parameter> overrides;
  for (const auto& [name, value] : parameters) overrides.push_back({name.c_str(), value});
  py::array_t<double> forces(static_cast<py::ssize_t>(deflections.size()));
  char error[512] = "";
  tirefe_status status;
  {
    py::gil_scoped_release unlocked;
    status = tirefe_static_forces(source.c_str(), overrides.data(), overrides.size(), deflections.data(),
                                  deflections.size(), forces.mutable_data(), error, sizeof error);
  }
  raise_on_failure(status, error);
  return forces;
}

/// Runs a deck as `tirefe DECK key=value ... --output-dir DIR --quiet` would, in this
/// process; the result files are the .h5 files the run wrote in the output folder.
py::dict run_deck(const std::string& deck, const std::map<std::string, py::object>& parameters,
                  const std::string& output_dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> arguments{"tirefe", deck};
  for (const auto& [name, value] : parameters) arguments.push_back(name + "=" + std::string(py::str(value)));
  arguments.insert(arguments.end(), {"--output-dir", output_dir, "--quiet"});
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  const auto started = fs::file_time_type::clock::now() - std::chrono::seconds(1);
  // The GIL stays held: no two decks write HDF5 files at once (the library is not thread-safe).
  const tirefe::macros::DeckOutcome outcome =
      tirefe::macros::run_deck_command(static_cast<int>(argv.size()), argv.data(), {});
  std::vector<std::string> files;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(output_dir, error))
    if (entry.path().extension() == ".h5" && entry.last_write_time() >= started) files.push_back(entry.path().string());
  py::dict result;
  result["status"] = outcome.status;
  result["error"] = outcome.error;
  result["files"] = files;
  return result;
}

}  // namespace

PYBIND11_MODULE(tirefe, module) {
  module.doc() = "tirefe: a 2D FE tire behind its spindle, and its deck runner (docs/coupling.md)";
  module.attr("__version__") = tirefe_version();
  static py::exception<std::runtime_error> step_failed(module, "StepFailed");
  step_failed_type = step_failed.ptr();

  module.def("run_deck", &run_deck, py::arg("deck"), py::arg("parameters") = std::map<std::string, py::object>{},
             py::arg("output_dir") = "results",
             "Runs a deck with parameters (overriding tirefe.parameters{...}); returns {status, error, files}: "
             "the exit status of `tirefe`, its error text, and the result files (.h5) written.");

  module.def("static_forces", &static_forces, py::arg("source"), py::arg("parameters"), py::arg("deflections"),
             "The tire's static vertical curve on a flat frictionless road: Fz [N] the tire exerts on the wheel at "
             "each spindle deflection [m] below first touch (positive when pressed).");

  py::class_<Tire>(module, "Tire",
                   "A tire on a flat road driven through its spindle (the C API's tirefe_open), in ISO 8855 wheel "
                   "axes (x the heading, z up, y the spin axis): motions (x, z, spin) [m, m, rad], forces (Fx, Fz, "
                   "My) [N, N, N m] the tire exerts on the wheel (a loaded tire: Fz > 0).")
      .def(py::init<const std::string&, const std::map<std::string, double>&, double, double, bool,
                    const std::string&>(),
           py::arg("source") = "tires.145SR12", py::arg("parameters") = std::map<std::string, double>{},
           py::arg("friction") = 0.8, py::arg("hht_alpha") = 0.0, py::arg("free_spin") = true,
           py::arg("heading") = "+x")
      .def("solve", &Tire::solve, py::arg("time_step"), py::arg("x"), py::arg("z"), py::arg("spin") = 0.0,
           "Trial step to the wheel centre's position: (force[3], jacobian[3, 3]) with jacobian[i, j] = d force_i / d "
           "(x, z, spin)_j.")
      .def("solve_velocity", &Tire::solve_velocity, py::arg("time_step"), py::arg("vx"), py::arg("vz"),
           py::arg("spin_rate") = 0.0,
           "Trial step to the end-of-step spindle velocities; the Jacobian is d force / d v.")
      .def("commit", &Tire::commit, "Accepts the last trial step.")
      .def("revert", &Tire::revert, "Forgets the last trial step.")
      .def("state", &Tire::state, "The committed time and spindle position, velocity and force.")
      .def("road_level", &Tire::road_level, "Height of the road below the spindle's design position [m].");
}
