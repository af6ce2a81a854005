// Cost of the vehicle on FE tires (docs/model.md sections 6-7): a quarter car crossing a
// 760 mm long pothole, with the direct spindle Jacobian H_ss and with forward finite
// differences of the spindle force (the paper's comparison): steps, corrector
// iterations per step, tire solves, tire Newton iterations per solve, wall time, and the
// process's CPU time per tire Newton iteration (every lane's work, the vehicle's, and the
// waits a lane spins through, over all the tires' iterations). Then a
// full car (left wheels over the pothole, right wheels on a flat road) with its four
// tires solved in one thread, in two lanes and in four (TireGroup). The road starts 0.1 s
// after the tires are pressed and reaches its speed in 0.5 s; the pothole arrives 0.4 s
// later. Tires and vehicle as inputs/vehicle_pothole.lua sets them: HHT alpha = -0.05,
// the zero-acceleration predictor, tire Newton and vehicle corrector to 1e-6.
//   build/bench_vehicle [seconds simulated, default 1.4] [quarter|car|all]
// Environment: SPEED [km/h, default 36], DEPTH [m, default 0.05], STEP [s, default 5e-4].
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <memory>
#include <string>

#include "contact/rigid_motion.hpp"
#include "macros/macro_table.hpp"
#include "vehicle/tire_group.hpp"
#include "vehicle/tire_on_road.hpp"
#include "vehicle/vehicle.hpp"

using namespace tirefe;
using Clock = std::chrono::steady_clock;

namespace {

double setting(const char* name, double fallback) {
  const char* value = std::getenv(name);
  return value ? std::atof(value) : fallback;
}

const double kSpeed = setting("SPEED", 36.0) / 3.6;  // road speed after the ramp [m/s]
constexpr double kRamp = 0.5;                        // [s]
const double kStep = setting("STEP", 5e-4);          // [s]
const double kDepth = setting("DEPTH", 0.05);        // pothole depth [m]
constexpr double kCornerMass = 350.0, kCarrierMass = 35.0, kGravity = 9.81;

/// A tire at 0.243 MPa pressed 20 mm onto a road that starts 0.1 s after the press and
/// reaches kSpeed after kRamp; with the pothole (edges rounded 2 cm), or flat.
std::unique_ptr<TireOnRoad> road_tire(bool pothole) {
  TireParameters parameters = macros::load_tire_parameters("tires.145SR12");
  parameters.pressure = 0.243e6;
  const double start = 3.1;  // inflation 1 s, press 1 s + 1 s
  auto tire = std::make_unique<TireOnRoad>(
      parameters,
      [pothole, start](double level) -> std::shared_ptr<const RigidSurface> {
        const RigidMotion motion = RigidMotion::translation(MotionFunction::ramped_rate(-kSpeed, kRamp, start));
        const double ahead = 0.5 * kSpeed * kRamp + kSpeed * 0.4;
        if (!pothole) return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level), Eigen::Vector2d::UnitX(), motion);
        return std::make_shared<RoadProfile>(RoadProfile::pothole_points(ahead, 0.76, kDepth, level), 0.02, motion);
      },
      RoadContact{0.9});
  tire->press(0.010);
  tire->press(0.020);
  tire->analysis().newton_settings().residual_tolerance = 1e-6;
  tire->drive(Integrator::hht(-0.05).with_predictor(Integrator::Predictor::ZeroAcceleration));
  return tire;
}

Corner corner(double x, double y) {
  Corner c;
  c.x = x;
  c.y = y;
  c.mass = kCarrierMass;
  c.suspension.spring = ForceCurve({{-0.1, kCornerMass * kGravity - 2500.0},
                                    {0.0, kCornerMass * kGravity},
                                    {0.05, kCornerMass * kGravity + 1500.0}});  // progressive
  c.suspension.damper = ForceCurve({{-1.0, -3000.0}, {0.0, 0.0}, {1.0, 1500.0}});
  c.suspension.bumper_gap = 0.05;
  c.suspension.bumper_stiffness = 5e6;
  c.suspension.fore_aft_stiffness = 2e5;
  c.suspension.fore_aft_damping = 2e3;
  return c;
}

struct Run {
  VehicleStatistics statistics;
  double seconds = 0.0;
  double cpu_seconds = 0.0;  // of the process: every lane
  double peak_force = 0.0;   // largest |Fy| on the (first) tire
};

double process_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

Run run(std::vector<std::unique_ptr<TireOnRoad>>& tires, std::vector<Corner> corners, const Body& body,
        SpindleJacobianSource source, int lanes, double duration) {
  std::vector<TireSpindle*> spindles;
  for (auto& tire : tires) spindles.push_back(&tire->spindle());
  TireGroup group(spindles, lanes > 1, lanes);
  VehicleSettings settings;
  settings.alpha = -0.05;
  settings.residual_tolerance = 1e-6;
  settings.jacobian = source;
  Vehicle car(body, std::move(corners), group, settings);
  Run result;
  car.add_step_observer([&result](const Vehicle& v) {
    result.peak_force = std::max(result.peak_force, std::abs(v.spindle_force(0).y()));
  });
  const auto start = Clock::now();
  const double cpu_start = process_cpu_seconds();
  car.advance(duration, kStep);
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  result.cpu_seconds = process_cpu_seconds() - cpu_start;
  result.statistics = car.statistics();
  return result;
}

void print(const char* label, const Run& r, double duration) {
  const VehicleStatistics& s = r.statistics;
  std::printf(
      "%-34s steps %5d  corrector/step %5.2f  tire solves %6d  tire Newton/solve %5.2f  cuts %d  "
      "wall %7.2f s (%.2f x real time)  CPU %6.2f s (%5.1f us per tire iteration)  peak |Fy| %.0f N\n",
      label, s.steps, double(s.corrector_iterations) / s.steps, s.tire_solves,
      double(s.tire_newton_iterations) / s.tire_solves, s.cuts, r.seconds, r.seconds / duration, r.cpu_seconds,
      1e6 * r.cpu_seconds / double(s.tire_newton_iterations), r.peak_force);
}

}  // namespace

int main(int argc, char** argv) {
  const double duration = argc > 1 ? std::atof(argv[1]) : 1.4;
  const std::string parts = argc > 2 ? argv[2] : "all";
  std::printf("pothole 760 x %.0f mm at %.0f km/h, h = %g s, %.2f s simulated\n", kDepth * 1e3, kSpeed * 3.6, kStep,
              duration);
  if (parts != "car") {
    std::printf("quarter car (%.0f kg corner, %.0f kg carrier)\n", kCornerMass, kCarrierMass);
    for (SpindleJacobianSource source : {SpindleJacobianSource::Direct, SpindleJacobianSource::FiniteDifference}) {
      std::vector<std::unique_ptr<TireOnRoad>> tires;
      tires.push_back(road_tire(true));
      const Run r = run(tires, {corner(0, 0)}, Body{kCornerMass}, source, 1, duration);
      print(source == SpindleJacobianSource::Direct ? "  direct Jacobian H_ss" : "  finite-difference Jacobian", r,
            duration);
    }
  }
  if (parts != "quarter") {
    std::printf("full car (4 x %.0f kg), left wheels over the pothole\n", kCornerMass);
    for (int lanes : {1, 2, 4}) {
      std::vector<std::unique_ptr<TireOnRoad>> tires;
      for (bool pothole : {true, false, true, false}) tires.push_back(road_tire(pothole));
      const std::vector<Corner> corners{corner(1.3, 0.75), corner(1.3, -0.75), corner(-1.4, 0.75), corner(-1.4, -0.75)};
      const Run r =
          run(tires, corners, Body{4 * kCornerMass, 2500.0, 550.0}, SpindleJacobianSource::Direct, lanes, duration);
      const std::string label = "  4 tires, " + std::to_string(lanes) + (lanes == 1 ? " thread" : " threads");
      print(label.c_str(), r, duration);
    }
  }
  return 0;
}
