#include "vehicle/vehicle.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solvers/analysis.hpp"

namespace tirefe {

namespace {

/// A tire that could not solve its step: the vehicle cuts its step.
struct TireFailure {
  std::string message;
};

constexpr int kMaxBacktracks = 4;

}  // namespace

Vehicle::Vehicle(Body body, std::vector<Corner> corners, TireExchange& tires, VehicleSettings settings)
    : body_(std::move(body)),
      corners_(std::move(corners)),
      tires_(tires),
      settings_(settings),
      integrator_(settings.scheme ? *settings.scheme : Integrator::hht_or_average_acceleration(settings.alpha)) {
  if (corners_.empty()) throw ModelError("a vehicle needs at least one corner");
  if (tires_.size() != static_cast<int>(corners_.size()))
    throw ModelError("a vehicle with " + std::to_string(corners_.size()) + " corners needs as many tires (got " +
                     std::to_string(tires_.size()) + ")");
  if (!(body_.mass > 0.0)) throw ModelError("the body mass must be positive");
  body_dofs_ = corners_.size() == 1 ? 1 : 3;
  if (body_dofs_ == 3 && !(body_.pitch_inertia > 0.0 && body_.roll_inertia > 0.0))
    throw ModelError("a vehicle with several corners needs positive pitch and roll inertias");
  const int dofs = body_dofs_ + 2 * static_cast<int>(corners_.size());
  mass_.setZero(dofs);
  weight_.setZero(dofs);
  mass_[0] = body_.mass;
  weight_[0] = body_.mass * settings_.gravity;
  if (body_dofs_ == 3) {
    mass_[1] = body_.pitch_inertia;
    mass_[2] = body_.roll_inertia;
  }
  for (size_t i = 0; i < corners_.size(); ++i) {
    const Corner& corner = corners_[i];
    if (!(corner.mass > 0.0)) throw ModelError("corner '" + corner.name + "': the carrier mass must be positive");
    mass_[wheel_vertical_dof(static_cast<int>(i))] = mass_[wheel_fore_aft_dof(static_cast<int>(i))] = corner.mass;
    weight_[wheel_vertical_dof(static_cast<int>(i))] = corner.mass * settings_.gravity;
    if (tires_.tire(static_cast<int>(i)).spin() != SpinMode::Free)
      throw ModelError("corner '" + corner.name + "': the tire's spin must be free (no drive torque)");
    design_spindle_.push_back(tires_.tire(static_cast<int>(i)).committed_position().head<2>());
  }
  for (int i = 0; i < static_cast<int>(corners_.size()); ++i) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(dofs);  // jounce d = z_w - (z + x_i theta + y_i phi)
    b[wheel_vertical_dof(i)] = 1.0;
    b[0] = -1.0;
    if (body_dofs_ == 3) {
      b[1] = -corners_[i].x;
      b[2] = -corners_[i].y;
    }
    attachments_.push_back(b);
  }
  committed_.resize(dofs);
  committed_.time = tires_.tire(0).time();
  trial_ = committed_;
  requests_.resize(corners_.size());
  jacobian_.setZero(dofs, dofs);
  factors_ = Eigen::PartialPivLU<Eigen::MatrixXd>(dofs);
  perturbed_forces_.resize(2 * corners_.size());
  spindle_jacobians_.assign(corners_.size(), Eigen::Matrix2d::Zero());
}

double Vehicle::jounce(int corner) const { return attachment(corner).dot(committed_.displacement); }

void Vehicle::suspension_forces(const State& state, Eigen::VectorXd& forces) const {
  forces.setZero(dof_count());
  for (int i = 0; i < static_cast<int>(corners_.size()); ++i) {
    const Suspension& s = corners_[i].suspension;
    const Eigen::VectorXd& b = attachment(i);
    const double d = b.dot(state.displacement), rate = b.dot(state.velocity);
    const double bump = d > s.bumper_gap ? s.bumper_stiffness * (d - s.bumper_gap) * (d - s.bumper_gap) : 0.0;
    forces.noalias() += (s.spring(d) + s.damper(rate) + bump) * b;  // pushes the body up and the carrier down
    const int x = wheel_fore_aft_dof(i);
    forces[x] += s.fore_aft_stiffness * state.displacement[x] + s.fore_aft_damping * state.velocity[x];
  }
}

void Vehicle::suspension_tangent(const State& state, double stiffness_factor, double damping_factor,
                                 Eigen::MatrixXd& tangent) const {
  for (int i = 0; i < static_cast<int>(corners_.size()); ++i) {
    const Suspension& s = corners_[i].suspension;
    const Eigen::VectorXd& b = attachment(i);
    const double d = b.dot(state.displacement), rate = b.dot(state.velocity);
    const double bump = d > s.bumper_gap ? 2.0 * s.bumper_stiffness * (d - s.bumper_gap) : 0.0;
    const double k = stiffness_factor * (s.spring.derivative(d) + bump) + damping_factor * s.damper.derivative(rate);
    tangent.noalias() += k * b * b.transpose();
    const int x = wheel_fore_aft_dof(i);
    tangent(x, x) += stiffness_factor * s.fore_aft_stiffness + damping_factor * s.fore_aft_damping;
  }
}

void Vehicle::request_positions(double h, const Eigen::VectorXd& displacement, SpindleStart start, bool jacobian) {
  for (size_t i = 0; i < corners_.size(); ++i) {
    SpindleRequest& request = requests_[i];
    request.command = SpindleCommand::Solve;
    request.input.time_step = h;
    request.input.start = start;
    request.input.jacobian = jacobian;
    request.input.x = design_spindle_[i].x() + displacement[wheel_fore_aft_dof(static_cast<int>(i))];
    request.input.y = design_spindle_[i].y() + displacement[wheel_vertical_dof(static_cast<int>(i))];
  }
}

std::string Vehicle::tire_of(size_t corner) const { return "the tire of corner '" + corners_[corner].name + "'"; }

void Vehicle::solve_tires(double h, bool correcting) {
  auto serve = [this]() {
    tires_.serve(requests_, replies_);
    for (size_t i = 0; i < replies_.size(); ++i) {
      const SpindleReply& reply = replies_[i];
      if (reply.status == SpindleStatus::Failed) throw TireFailure{tire_of(i) + " failed: " + reply.message};
      ++statistics_.tire_solves;
      statistics_.tire_newton_iterations += reply.newton_iterations;
    }
  };
  const size_t count = corners_.size();
  if (settings_.jacobian == SpindleJacobianSource::FiniteDifference) {
    // Perturbed solves first, so that the last trial of every tire is at q itself.
    for (int column = 0; column < 2; ++column) {
      request_positions(h, trial_.displacement);
      for (auto& request : requests_) (column == 0 ? request.input.x : request.input.y) += settings_.difference_step;
      serve();
      for (size_t i = 0; i < count; ++i)
        perturbed_forces_[2 * i + column] = Eigen::Vector2d(replies_[i].force[0], replies_[i].force[1]);
    }
    request_positions(h, trial_.displacement);
    serve();
    for (size_t i = 0; i < count; ++i) {
      const Eigen::Vector2d base(replies_[i].force[0], replies_[i].force[1]);
      for (int column = 0; column < 2; ++column)
        spindle_jacobians_[i].col(column) = (perturbed_forces_[2 * i + column] - base) / settings_.difference_step;
    }
    jacobians_current_ = true;
    return;
  }
  // A corrector's trial starts every tire from its last, moved by its linear response.
  // The predictor's Jacobians are nearly always used; a corrector's, rarely (the step
  // has mostly converged with it), so those are fetched when needed.
  request_positions(h, trial_.displacement, correcting ? SpindleStart::LastTrial : SpindleStart::Predictor,
                    !correcting);
  serve();
  jacobians_current_ = false;
  if (!correcting) {
    for (size_t i = 0; i < count; ++i) spindle_jacobians_[i] = jacobian_of(replies_[i]).topLeftCorner<2, 2>();
    jacobians_current_ = true;
  }
}

bool Vehicle::fetch_jacobians() {
  if (jacobians_current_) return true;
  for (auto& request : requests_) request.command = SpindleCommand::Jacobian;
  tires_.serve(requests_, replies_);
  for (size_t i = 0; i < replies_.size(); ++i) {
    if (replies_[i].status == SpindleStatus::Failed) {
      last_failure_ = tire_of(i) + " failed: " + replies_[i].message;
      return false;
    }
    spindle_jacobians_[i] = jacobian_of(replies_[i]).topLeftCorner<2, 2>();
  }
  jacobians_current_ = true;
  return true;
}

void Vehicle::initialize_acceleration() {
  // M a_0 = -(f(q_0, v_0) + W + sum P^T f_s) with the tires' committed spindle forces.
  suspension_forces(committed_, forces_);
  residual_ = forces_ + weight_;
  for (int i = 0; i < static_cast<int>(corners_.size()); ++i) {
    const Eigen::Vector3d force = spindle_force(i);
    residual_[wheel_fore_aft_dof(i)] += force.x();
    residual_[wheel_vertical_dof(i)] += force.y();
  }
  committed_.acceleration = -residual_.cwiseQuotient(mass_);
  old_forces_ = forces_;
  started_ = true;
}

bool Vehicle::solve_step(double h) {
  const IntegratorFactors factors = integrator_.factors(h);
  const double reference = weight_.sum();
  integrator_.predict(committed_, h, trial_);
  for (int iteration = 0;; ++iteration) {
    // A tire that cannot reach the corrected position (a wild Newton increment near an
    // impact) gets half the increment instead, a few times, before the step is cut.
    for (int backtrack = 0;; ++backtrack) {
      for (int dof = 0; dof < dof_count(); ++dof) integrator_.update_rates(committed_, h, dof, trial_);
      try {
        solve_tires(h, iteration > 0);
        break;
      } catch (const TireFailure& failure) {
        if (iteration == 0 || backtrack == kMaxBacktracks) {
          last_failure_ = failure.message;
          return false;
        }
        increment_ *= 0.5;
        trial_.displacement -= increment_;
        ++statistics_.backtracks;
      }
    }
    suspension_forces(trial_, forces_);
    residual_ = mass_.cwiseProduct(factors.force_mass * trial_.acceleration +
                                   integrator_.old_inertia_weight() * committed_.acceleration) +
                integrator_.new_force_weight() * forces_ + integrator_.old_force_weight() * old_forces_ + weight_;
    for (int i = 0; i < static_cast<int>(corners_.size()); ++i) {
      residual_[wheel_fore_aft_dof(i)] += replies_[i].force[0];
      residual_[wheel_vertical_dof(i)] += replies_[i].force[1];
    }
    if (!residual_.allFinite()) {
      last_failure_ = "the vehicle residual is not finite";
      return false;
    }
    if (residual_.lpNorm<Eigen::Infinity>() <= settings_.residual_tolerance * reference) return true;
    if (iteration == settings_.max_iterations) {
      std::ostringstream message;
      message << "no corrector convergence in " << iteration
              << " iterations (|r| = " << residual_.lpNorm<Eigen::Infinity>() << " N)";
      last_failure_ = message.str();
      return false;
    }
    if (!fetch_jacobians()) return false;
    jacobian_ = (factors.tangent_mass * mass_).asDiagonal();
    suspension_tangent(trial_, factors.tangent_stiffness, factors.tangent_damping, jacobian_);
    for (int i = 0; i < static_cast<int>(corners_.size()); ++i) {
      const int dofs[2] = {wheel_fore_aft_dof(i), wheel_vertical_dof(i)};
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) jacobian_(dofs[r], dofs[c]) += spindle_jacobians_[i](r, c);
    }
    factors_.compute(jacobian_);
    increment_.noalias() = factors_.solve(-residual_);
    trial_.displacement += increment_;
    ++statistics_.corrector_iterations;
  }
}

bool Vehicle::try_step(double h, double, StepRecord& record) {
  const int iterations = statistics_.corrector_iterations;
  const bool solved = solve_step(h);
  record.newton_iterations = statistics_.corrector_iterations - iterations;
  if (!solved) tires_.serve_all(SpindleCommand::Revert, replies_);
  return solved;
}

void Vehicle::commit_step(double h, StepRecord& record) {
  std::swap(committed_, trial_);  // first: the tires' output may read the vehicle's new state
  suspension_forces(committed_, old_forces_);
  tires_.serve_all(SpindleCommand::Commit, replies_);
  for (size_t i = 0; i < replies_.size(); ++i)
    if (replies_[i].status == SpindleStatus::Failed)
      throw StepFailure(tire_of(i) + " could not commit: " + replies_[i].message);
  ++statistics_.steps;
  statistics_.cuts += record.cuts;
  record.step = statistics_.steps;
  record.time = committed_.time;
  record.step_size = h;
  record.residual = residual_.lpNorm<Eigen::Infinity>();
}

std::string Vehicle::failure_message(int, double h) const {
  // The controller gives up when the step would fall below h / 2^max_cuts: all cuts taken.
  return "vehicle step from t = " + std::to_string(committed_.time) + " (dt = " + std::to_string(h) +
         ") failed after " + std::to_string(settings_.max_cuts) + " cuts: " + last_failure_;
}

void Vehicle::advance(double duration, double h, std::vector<StepWindow> windows) {
  if (!(h > 0.0) || !std::isfinite(h)) throw ModelError("the vehicle time step must be positive and finite");
  controller_.set_windows(std::move(windows));
  if (!started_) initialize_acceleration();
  StepControl& control = controller_.settings();
  // Halvings of h, never below h / 2^max_cuts: its cuts bound the steps.
  control.max_cuts = settings_.max_cuts;
  control.depth = std::max(settings_.max_cuts, 1);
  control.step_budget = 0;
  steps_ = {h, h};
  controller_.advance_to(*this, committed_.time + duration);
}

}  // namespace tirefe
