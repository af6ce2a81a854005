// Vehicle: a lightweight rigid-body vehicle on FE tires (docs/vehicle.md).
//
// A body (heave z; with more than one corner also pitch theta and roll phi, small
// angles) and corners. Each corner is a wheel carrier of mass m_w with two DOFs,
// vertical z_w and fore-aft x_w, joined to the body at (x_i, y_i) from its centre of
// mass (x forward, y left) by a suspension: a nonlinear spring and a damper table on
// the jounce d = z_w - (z + x_i theta + y_i phi) (wheel up relative to the body), a
// jounce bumper k_b (d - gap)^2 beyond its gap, and a fore-aft bushing (spring and
// damper) on x_w. The body is held fore-aft: the road moves under the car. Every DOF is
// a displacement from the design position, where the tires touch the road unloaded.
// Gravity acts on the body and the carriers (the tires carry no weight).
//
// Integration: the tires' own generalized-alpha scheme (Newmark, HHT, ...), step h.
// Its corrector is Newton on the end-of-step displacements q:
//     r(q) = M [(1-alpha_m) a + alpha_m a_n] + (1-alpha_f) f(q, v) + alpha_f f_n + W
//            + sum_i P_i^T f_s,i(q) = 0,
//     J    = (1-alpha_m) M / (beta h^2) + (1-alpha_f) (K + gamma/(beta h) C) + sum_i P_i^T H_i P_i,
// with f the suspension forces, W the weights, f_s,i the spindle force of tire i (the
// force the carrier applies to the tire, weighted by the tire: docs/spindle.md), P_i
// picking carrier i's (x_w, z_w), and H_i the tire's spindle Jacobian (eq. 27) or, for
// comparison, its forward finite difference (two more tire solves per tire).
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/state.hpp"
#include "solvers/integrator.hpp"
#include "solvers/step_controller.hpp"
#include "vehicle/force_curve.hpp"
#include "vehicle/tire_exchange.hpp"

namespace tirefe {

struct Suspension {
  ForceCurve spring;                // force [N] on the body (up) vs jounce d [m]
  ForceCurve damper;                // force [N] on the body (up) vs jounce rate [m/s]
  double bumper_gap = 0.0;          // jounce where the bumper starts [m]
  double bumper_stiffness = 0.0;    // k_b: bumper force k_b (d - gap)^2 [N/m^2]
  double fore_aft_stiffness = 0.0;  // carrier to body along x [N/m]
  double fore_aft_damping = 0.0;    // [N s/m]
};

struct Corner {
  std::string name;
  double x = 0.0, y = 0.0;  // attachment from the body's centre of mass: forward, left [m]
  double mass = 0.0;        // wheel carrier, without the tire (the tire model carries its rim) [kg]
  Suspension suspension;
};

struct Body {
  double mass = 0.0;           // sprung mass [kg]
  double pitch_inertia = 0.0;  // about the lateral axis through the centre of mass [kg m^2]
  double roll_inertia = 0.0;   // about the longitudinal axis [kg m^2]
};

enum class SpindleJacobianSource { Direct, FiniteDifference };

struct VehicleSettings {
  double gravity = 9.81;             // [m/s^2]
  double alpha = 0.0;                // HHT alpha, as the tires' integrator (0: Newmark) ...
  std::optional<Integrator> scheme;  // ... unless the tires' scheme is given here
  double residual_tolerance = 1e-8;  // on |r|_inf / total weight
  int max_iterations = 25;           // corrector iterations before the step is cut
  int max_cuts = 4;                  // halvings of one step
  SpindleJacobianSource jacobian = SpindleJacobianSource::Direct;
  double difference_step = 1e-7;  // spindle perturbation of the finite-difference Jacobian [m]
};

struct VehicleStatistics {
  int steps = 0;
  int corrector_iterations = 0;  // Newton iterations of the vehicle (Jacobian solves)
  int tire_solves = 0;           // spindle solves, each tire counted
  long tire_newton_iterations = 0;
  int cuts = 0;
  int backtracks = 0;  // corrector increments halved because a tire could not follow
};

class Vehicle : private SteppedSystem {
 public:
  /// Corner i rides on tires.tire(i) (spin free), whose current spindle position is the
  /// design position; the tires may be solved in threads or on other MPI ranks. A single corner makes a quarter car
  /// (heave only); more add pitch and roll. Starts at rest at the design position.
  Vehicle(Body body, std::vector<Corner> corners, TireExchange& tires, VehicleSettings settings);
  Vehicle(const Vehicle&) = delete;
  Vehicle& operator=(const Vehicle&) = delete;

  int dof_count() const { return static_cast<int>(mass_.size()); }
  int body_dofs() const { return body_dofs_; }
  /// DOF numbers: body heave 0, pitch 1, roll 2 (with pitch and roll); corner i's
  /// z_w and x_w follow the body's.
  int wheel_vertical_dof(int corner) const { return body_dofs_ + 2 * corner; }
  int wheel_fore_aft_dof(int corner) const { return body_dofs_ + 2 * corner + 1; }

  /// Advances by one step h (cut into halves if the corrector fails, growing back after
  /// easy convergence: the StepController; throws StepFailure).
  void step(double h) { advance(h, h); }
  void advance(double duration, double h) { advance(duration, h, {}); }
  /// Advances by 'duration' in steps h, and in steps of each window's own size while the
  /// time is inside it (windows in absolute time, e.g. around an obstacle's impacts).
  using StepWindow = tirefe::StepWindow;
  void advance(double duration, double h, std::vector<StepWindow> windows);

  const State& state() const { return committed_; }
  double time() const { return committed_.time; }
  /// Jounce of a corner's suspension at the committed state [m].
  double jounce(int corner) const;
  /// Spindle force of tire i at the committed state (the force on the tire, physical, in
  /// the model's plane), as its Commit reply gave it; wheel_load_from_reaction() turns it
  /// into the wheel axes users see (tire/wheel_axes.hpp).
  Eigen::Vector3d spindle_force(int corner) const { return tires_.committed_force(corner); }
  const VehicleStatistics& statistics() const { return statistics_; }
  VehicleSettings& settings() { return settings_; }
  const std::vector<Corner>& corners() const { return corners_; }
  /// Called after every accepted step.
  void add_step_observer(std::function<void(const Vehicle&)> observer) {
    controller_.add_observer([this, observer = std::move(observer)](const StepRecord&) { observer(*this); });
  }

 private:
  // SteppedSystem (with time()): the tires step by h on their own clocks, so the end time is theirs.
  bool try_step(double h, double end_time, StepRecord& record) override;
  void commit_step(double h, StepRecord& record) override;
  std::string failure_message(int cuts, double h) const override;
  /// The corrector of one step: true when it converged, with the tires at the trial state.
  bool solve_step(double h);
  /// The tires at the trial state; 'correcting': a corrector's trial, after the first of
  /// the step, solved without the Jacobians (the corrector mostly stops there).
  void solve_tires(double h, bool correcting);
  /// The Jacobians of the tires' last trials, if solve_tires() left them out; false, with
  /// last_failure_, when a tire fails.
  bool fetch_jacobians();
  void suspension_forces(const State& state, Eigen::VectorXd& forces) const;
  void suspension_tangent(const State& state, double stiffness_factor, double damping_factor,
                          Eigen::MatrixXd& tangent) const;
  const Eigen::VectorXd& attachment(int corner) const { return attachments_[corner]; }  // b_i: d = b_i . q
  void initialize_acceleration();
  void request_positions(double h, const Eigen::VectorXd& displacement, SpindleStart start = SpindleStart::Predictor,
                         bool jacobian = false);

  Body body_;
  /// "the tire of corner 'LF'", for messages.
  std::string tire_of(size_t corner) const;
  std::vector<Corner> corners_;
  TireExchange& tires_;
  VehicleSettings settings_;
  Integrator integrator_;
  int body_dofs_ = 1;
  Eigen::VectorXd mass_, weight_;
  std::vector<Eigen::Vector2d> design_spindle_;
  State committed_, trial_;
  Eigen::VectorXd old_forces_;  // f(q_n, v_n) for HHT
  bool started_ = false;
  VehicleStatistics statistics_;
  std::vector<SpindleRequest> requests_;
  std::vector<SpindleReply> replies_;
  std::vector<Eigen::Matrix2d> spindle_jacobians_;  // d f_s / d (x, y) of each tire, this iteration
  bool jacobians_current_ = false;                  // spindle_jacobians_ are of the tires' last trials
  std::vector<Eigen::Vector2d> perturbed_forces_;   // finite differences: f_s at q + delta e_j
  std::vector<Eigen::VectorXd> attachments_;
  std::string last_failure_;
  StepSizes steps_;
  StepController controller_{steps_};
  // Corrector work space.
  Eigen::VectorXd residual_, forces_, increment_;
  Eigen::MatrixXd jacobian_;
  Eigen::PartialPivLU<Eigen::MatrixXd> factors_;
};

}  // namespace tirefe
