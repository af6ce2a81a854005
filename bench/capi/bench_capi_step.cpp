// The cost of the C API and the FMU over the C++ spindle exchange: three identical tires,
// one driven through TireSpindle (C++), one through tirefe_solve / tirefe_commit (C), one
// through fmi2SetReal / fmi2DoStep / fmi2GetReal of the FMU's binary (loaded with dlopen),
// pressed onto the road by the same spindle motions, steps interleaved so that all see the
// same machine load. Prints the time per step of each, the differences (median over the
// steps and from the totals), and the cost of a C call that does no work (the lock and
// the guard). The C++ and C tires are the same code in libtirefe.so and must agree bit
// for bit, the C++ reaction seen in the C API's ISO wheel axes (heading +x); the FMU's (its
// own copy of the code, its tire read from its property file, set to Newmark and steps of
// 1 ms as the others)
// is compared too: its inputs are the start of each step and the rate that ends it where
// the others are put, so that its one step of the communication step is theirs (to the
// round-off of its step size, which it takes from its master's times).
//
//   bench_capi_step [STEPS]      (default 400)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <stdexcept>
#include <vector>

#include <dlfcn.h>

#include "fmu/fmi2.h"
#include "macros/macro_table.hpp"
#include "tire/wheel_axes.hpp"
#include "tirefe.h"
#include "vehicle/tire_on_road.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double microseconds(Clock::duration d) { return std::chrono::duration<double, std::micro>(d).count(); }

/// The spindle at step k of h: pressed 10 mm onto the road smoothly in 200 steps, then held.
tirefe::SpindleInput motion(int k, double h) {
  const double s = std::min(k, 200) / 200.0;
  return {h, 0.0, -0.01 * s * s * (3.0 - 2.0 * s), 0.0};
}

/// The FMU of the build tree, driven through its FMI functions only.
class FmuTire {
 public:
  FmuTire() {
    library_ = dlopen(TIREFE_FMU_BINARY, RTLD_NOW | RTLD_LOCAL);
    if (!library_) throw std::runtime_error(std::string("cannot load the FMU: ") + dlerror());
    load(instantiate_, "fmi2Instantiate");
    load(setup_, "fmi2SetupExperiment");
    load(enter_, "fmi2EnterInitializationMode");
    load(exit_, "fmi2ExitInitializationMode");
    load(set_real_, "fmi2SetReal");
    load(get_real_, "fmi2GetReal");
    load(do_step_, "fmi2DoStep");
    load(free_, "fmi2FreeInstance");
    static const fmi2CallbackFunctions callbacks = {nullptr, std::calloc, std::free, nullptr, nullptr};
    component_ = instantiate_("bench", fmi2CoSimulation, TIREFE_FMU_GUID, "file://" TIREFE_FMU_RESOURCES, &callbacks,
                              fmi2False, fmi2False);
    static const fmi2ValueReference hht_alpha_max_step[] = {13, 15};
    static const fmi2Real newmark_1ms[] = {0.0, 1e-3};
    if (!component_ || setup_(component_, fmi2False, 0.0, 0.0, fmi2False, 0.0) != fmi2OK ||
        set_real_(component_, hht_alpha_max_step, 2, newmark_1ms) != fmi2OK || enter_(component_) != fmi2OK ||
        exit_(component_) != fmi2OK)
      throw std::runtime_error("cannot initialize the FMU");
  }
  ~FmuTire() {
    free_(component_);
    dlclose(library_);
  }
  /// One communication step from the wheel position 'from' (x, z, spin) at its start to 'to'
  /// at its end; the force (Fx, Fz, My) out. The rates given make the FMU's extrapolation,
  /// from + h r + h (r - r_before) / 2, end at 'to'.
  void step(double time_step, const Eigen::Vector3d& from, const Eigen::Vector3d& to, double force[3]) {
    static const fmi2ValueReference inputs[] = {0, 1, 2, 6, 7, 8}, outputs[] = {3, 4, 5};
    const double h = time_step;
    const Eigen::Vector3d rate =
        time_ > 0.0 ? Eigen::Vector3d((to - from + 0.5 * h * rate_) / (1.5 * h)) : Eigen::Vector3d((to - from) / h);
    rate_ = rate;
    const fmi2Real start[] = {from.x(), from.y(), from.z(), rate.x(), rate.y(), rate.z()};
    if (set_real_(component_, inputs, 6, start) != fmi2OK ||
        do_step_(component_, time_, time_step, fmi2True) != fmi2OK ||
        get_real_(component_, outputs, 3, force) != fmi2OK)
      throw std::runtime_error("an FMU step failed");
    time_ += time_step;
  }

 private:
  template <class Function>
  void load(Function& function, const char* name) {
    function = reinterpret_cast<Function>(dlsym(library_, name));
    if (!function) throw std::runtime_error(std::string("the FMU lacks ") + name);
  }

  void* library_ = nullptr;
  fmi2Component component_ = nullptr;
  double time_ = 0.0;
  Eigen::Vector3d rate_ = Eigen::Vector3d::Zero();  // the rates of the last step
  fmi2Component (*instantiate_)(fmi2String, fmi2Type, fmi2String, fmi2String, const fmi2CallbackFunctions*, fmi2Boolean,
                                fmi2Boolean) = nullptr;
  fmi2Status (*setup_)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real) = nullptr;
  fmi2Status (*enter_)(fmi2Component) = nullptr;
  fmi2Status (*exit_)(fmi2Component) = nullptr;
  fmi2Status (*set_real_)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2Real[]) = nullptr;
  fmi2Status (*get_real_)(fmi2Component, const fmi2ValueReference[], size_t, fmi2Real[]) = nullptr;
  fmi2Status (*do_step_)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean) = nullptr;
  void (*free_)(fmi2Component) = nullptr;
};

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 400;
  const double h = 1e-3;
  using namespace tirefe;
  TireOnRoad cpp_tire(
      macros::load_tire_parameters("tires.145SR12"),
      [](double level) { return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level)); }, RoadContact{0.8});
  TireSpindle& spindle = cpp_tire.drive(Integrator::newmark());
  char error[512];
  tirefe_tire* c_tire = nullptr;
  if (tirefe_open("tires.145SR12", nullptr, 0, nullptr, &c_tire, error, sizeof error) != TIREFE_OK) {
    std::fprintf(stderr, "bench_capi_step: %s\n", error);
    return 1;
  }

  FmuTire fmu_tire;

  std::vector<double> cpp_times, c_times, fmu_times, differences, fmu_differences;
  int mismatches = 0;
  double fmu_difference = 0.0;  // [N]: the FMU's step ends at its master's time, which rounds otherwise
  for (int k = 1; k <= steps; ++k) {
    const SpindleInput input = motion(k, h), before = motion(k - 1, h);
    const Eigen::Vector3d wheel = plane_motion(Eigen::Vector3d(input.x, input.y, input.spin), Heading::PlusX);
    const Eigen::Vector3d wheel_before = plane_motion(Eigen::Vector3d(before.x, before.y, before.spin), Heading::PlusX);
    SpindleReply reply;
    tirefe_spindle_force c_reply;
    double fmu_force[3];
    double elapsed[3];  // [us] of the C++, C and FMU steps
    auto cpp_step = [&] {
      reply = spindle.solve_step(input);
      spindle.commit();
    };
    auto c_step = [&] {
      const tirefe_spindle_motion c_motion{input.time_step, wheel.x(), wheel.y(), wheel.z()};
      if (tirefe_solve(c_tire, &c_motion, &c_reply) != TIREFE_OK || tirefe_commit(c_tire) != TIREFE_OK)
        throw std::runtime_error(tirefe_message(c_tire));
    };
    auto fmu_step = [&] { fmu_tire.step(input.time_step, wheel_before, wheel, fmu_force); };
    // Each goes first, second and third in turn: the one after the others finds the caches cold.
    const std::function<void()> runs[3] = {cpp_step, c_step, fmu_step};
    for (int turn = 0; turn < 3; ++turn) {
      const int which = (k + turn) % 3;
      const Clock::time_point start = Clock::now();
      runs[which]();
      elapsed[which] = microseconds(Clock::now() - start);
    }
    const Eigen::Vector3d load = wheel_load_from_reaction(force_of(reply), Heading::PlusX);
    const double stiffness = wheel_load_jacobian(jacobian_of(reply), Heading::PlusX)(1, 1);
    mismatches += load[0] != c_reply.force[0] || load[1] != c_reply.force[1] || stiffness != c_reply.jacobian[1][1];
    fmu_difference = std::max({fmu_difference, std::abs(load[0] - fmu_force[0]), std::abs(load[1] - fmu_force[1])});
    cpp_times.push_back(elapsed[0]);
    c_times.push_back(elapsed[1]);
    fmu_times.push_back(elapsed[2]);
    differences.push_back(c_times.back() - cpp_times.back());
    fmu_differences.push_back(fmu_times.back() - cpp_times.back());
  }

  const int calls = 1000000;  // a call that does no work: what the C layer itself costs
  tirefe_spindle_state state;
  const Clock::time_point s0 = Clock::now();
  for (int i = 0; i < calls; ++i) tirefe_state(c_tire, &state);
  const double per_call = microseconds(Clock::now() - s0) / calls;
  tirefe_close(c_tire);

  auto median = [](std::vector<double> values) {
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
  };
  double cpp_total = 0, c_total = 0, fmu_total = 0;
  for (int k = 0; k < steps; ++k) cpp_total += cpp_times[k], c_total += c_times[k], fmu_total += fmu_times[k];
  std::printf("steps: %d (solve + commit, 1 ms each)\n", steps);
  std::printf("C++ TireSpindle: %.1f us per step (median %.1f)\n", cpp_total / steps, median(cpp_times));
  std::printf("C API:           %.1f us per step (median %.1f)\n", c_total / steps, median(c_times));
  std::printf("C API - C++:     %+.2f us per step (median of the step pairs %+.2f)\n", (c_total - cpp_total) / steps,
              median(differences));
  std::printf("FMU doStep:      %.1f us per step (median %.1f)\n", fmu_total / steps, median(fmu_times));
  std::printf("FMU - C++:       %+.2f us per step (median of the step pairs %+.2f)\n", (fmu_total - cpp_total) / steps,
              median(fmu_differences));
  std::printf("a C call doing no work (tirefe_state): %.3f us\n", per_call);
  std::printf(
      "forces and stiffness differing between C++ and C: %d steps; forces between C++ and the FMU: up to "
      "%.3g N apart\n",
      mismatches, fmu_difference);
  return mismatches == 0 ? 0 : 1;
}
