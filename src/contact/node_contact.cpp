#include "contact/node_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/model.hpp"

namespace tirefe {

void ContactParameters::check() const {
  auto require = [](bool ok, const std::string& what, double value) {
    if (!ok) throw ModelError("contact: " + what + " (got " + std::to_string(value) + ")");
  };
  require(normal_penalty > 0.0 && std::isfinite(normal_penalty), "the normal penalty must be positive", normal_penalty);
  require(tangential_penalty >= 0.0 && std::isfinite(tangential_penalty),
          "the tangential penalty must be non-negative (0: the normal penalty)", tangential_penalty);
  require(friction >= 0.0 && std::isfinite(friction), "the friction coefficient must be non-negative", friction);
  require(penetration_tolerance >= 0.0 && std::isfinite(penetration_tolerance),
          "the penetration tolerance must be non-negative", penetration_tolerance);
  require(multiplier_tolerance >= 0.0 && std::isfinite(multiplier_tolerance),
          "the multiplier tolerance must be non-negative", multiplier_tolerance);
  require(penetration_limit > penetration_tolerance, "the penetration limit must exceed the penetration tolerance",
          penetration_limit);
  require(search_distance > 0.0, "the search distance must be positive", search_distance);
}

NodeSurfaceContact::NodeSurfaceContact(std::shared_ptr<const RigidSurface> surface,
                                       const Eigen::Vector2d& reference_position, const ContactParameters& parameters,
                                       int node, double start_time)
    : surface_(std::move(surface)),
      reference_position_(reference_position),
      parameters_(parameters),
      tangential_penalty_(parameters.effective_tangential_penalty()),
      node_(node) {
  if (!surface_) throw ModelError("contact: no surface");
  parameters_.check();
  reference_coordinate_ = surface_->project(reference_position_, start_time).coordinate;
}

void NodeSurfaceContact::evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History& base,
                                  History& trial, Vector& residual, Matrix* tangent) const {
  residual.setZero();
  if (tangent) tangent->setZero();
  // 'trial' holds the last evaluation's history until it is overwritten (traits().reads_last_trial).
  const bool last_slipped = trial.state == ContactState::Slip;
  const double last_traction = trial.trial_traction, last_tangential_force = trial.tangential_force;
  trial.trial_traction = 0.0;
  const Eigen::Vector2d x = reference_position_ + local.displacement.head<2>();
  if (base.state == ContactState::Open) {
    // Far from the surface: open, and no projection (most of a tire's nodes). The gap
    // reported is the clearance, a lower bound; the coordinate stays the last projected.
    const double clearance = surface_->clearance(x, context.time);
    if (clearance > parameters_.search_distance) {
      trial.state = ContactState::Open;
      trial.coordinate = base.coordinate;
      trial.gap = clearance;
      trial.normal_multiplier = trial.tangential_multiplier = 0.0;
      trial.stick_coordinate = base.coordinate;
      trial.normal_force = trial.tangential_force = trial.sliding_velocity = 0.0;
      trial.force.setZero();
      return;
    }
  }
  // The surface's pose once for the projection and the sliding velocity.
  const RigidPose pose = surface_->motion().pose(context.time);
  const SurfaceProjection p = surface_->project(x, pose);
  trial.coordinate = p.coordinate;
  trial.gap = p.gap;

  const double eps_n = parameters_.normal_penalty, eps_t = tangential_penalty_, mu = parameters_.friction;
  const double normal_force = base.normal_multiplier - eps_n * p.gap;
  const bool open = !(normal_force >= 0.0);
  if (open) {
    // Open: no force; the multipliers lapse and a later touch-down sticks where it lands.
    // (A node exactly touching counts as closed: its stiffness holds a structure that
    // rests on the surface from the first iteration.)
    trial.state = ContactState::Open;
    trial.normal_multiplier = trial.tangential_multiplier = 0.0;
    trial.stick_coordinate = p.coordinate;
    trial.normal_force = trial.tangential_force = trial.sliding_velocity = 0.0;
    trial.force.setZero();
  }
  // Held: a node in contact when the step began that the predictor has lifted off keeps
  // that contact in the solve's first evaluation, sticking, its penalty force pulling it
  // back (t_N < 0). The predictor extrapolates the patch's light nodes from rates that
  // alternate from step to step, and a node left open there gets no contact stiffness:
  // the first increment would push it millimetres into the surface and the next undo it.
  // Only the first linearisation changes: the history records the node open, and every
  // later evaluation applies the contact law itself.
  const bool held =
      open && context.first_evaluation && parameters_.hold_first_evaluation && base.state != ContactState::Open;
  if (open && !held) return;

  // A node open at the start of the step sticks to the surface point it was above then.
  const bool touching_down = base.state == ContactState::Open;
  const double anchor = !touching_down                ? base.stick_coordinate
                        : std::isnan(base.coordinate) ? reference_coordinate_
                                                      : base.coordinate;
  const double tangential_multiplier = touching_down ? 0.0 : base.tangential_multiplier;
  const double trial_traction = tangential_multiplier - eps_t * surface_->arc_difference(p.coordinate, anchor);
  const double slip_limit = mu * normal_force;
  const bool stick = held || (mu > 0.0 && std::abs(trial_traction) <= slip_limit);
  const double slip_sign = trial_traction >= 0.0 ? 1.0 : -1.0;
  const double tangential_force = stick ? trial_traction : slip_sign * slip_limit;
  const Eigen::Vector2d force = normal_force * p.normal + tangential_force * p.tangent;

  if (!held) {
    trial.state = stick ? ContactState::Stick : ContactState::Slip;
    trial.stick_coordinate = stick ? anchor : p.coordinate - (tangential_multiplier - tangential_force) / eps_t;
    trial.normal_multiplier = base.normal_multiplier;
    trial.tangential_multiplier = tangential_multiplier;
    trial.normal_force = normal_force;
    trial.tangential_force = tangential_force;
    trial.trial_traction = trial_traction;
    trial.force = force;
    trial.sliding_velocity = (local.velocity.head<2>() - surface_->motion().velocity(p.point, pose)).dot(p.tangent);
  }

  residual.head<2>() = -context.factors.force_stiffness * force;
  if (!tangent) return;
  const Eigen::Vector2d& nu = p.normal;
  const Eigen::Vector2d& tau = p.tangent;
  Eigen::Matrix2d stiffness = eps_n * nu * nu.transpose() - (normal_force * p.normal_rate) * tau * tau.transpose() +
                              (tangential_force * p.normal_rate) * nu * tau.transpose();
  if (stick) {
    stiffness += (eps_t * p.arc_rate) * tau * tau.transpose();
  } else {
    stiffness += (mu * slip_sign * eps_n) * tau * nu.transpose();
    const bool reversed = last_slipped && !context.first_evaluation && (last_traction >= 0.0) != (slip_sign > 0.0);
    if (reversed) {
      const double secant = (tangential_force - last_tangential_force) / (trial_traction - last_traction);
      stiffness += (std::clamp(secant, 0.0, 1.0) * eps_t * p.arc_rate) * tau * tau.transpose();
    }
  }
  tangent->topLeftCorner<2, 2>() = context.factors.tangent_stiffness * stiffness;
}

ElementEnergy NodeSurfaceContact::energy(const LocalState<kDofs>&, const History& history) const {
  ElementEnergy energy;
  if (history.state == ContactState::Open) return energy;
  const double normal = history.normal_force - history.normal_multiplier;
  const double tangential = history.tangential_force - history.tangential_multiplier;
  energy.strain = 0.5 * (normal * normal / parameters_.normal_penalty + tangential * tangential / tangential_penalty_);
  return energy;
}

bool NodeSurfaceContact::augment(History& base, const History& trial) const {
  if (trial.state == ContactState::Open) return false;
  const double penetration = std::max(0.0, -trial.gap);
  if (penetration > parameters_.penetration_limit) {
    std::ostringstream message;
    message << "contact with the " << surface_->kind() << " surface: node " << node_ << " (0-based) penetrates by "
            << penetration << " m in a converged solve, more than the limit of " << parameters_.penetration_limit
            << " m: the penalty is too small for the load, or the obstacle too high or too fast for the step";
    throw ContactFailure(message.str());
  }
  // The constraints Uzawa enforces: impenetrability, and no relative motion while sticking.
  // A slipping node's friction follows from t_N and its step's return map, so its
  // tangential multiplier and stick point stay as the step began.
  const bool stick = trial.state == ContactState::Stick;
  const double change = std::hypot(trial.normal_force - trial.normal_multiplier,
                                   stick ? trial.tangential_force - trial.tangential_multiplier : 0.0);
  const double size = std::max({std::hypot(trial.normal_force, trial.tangential_force),
                                std::hypot(trial.normal_multiplier, trial.tangential_multiplier),
                                parameters_.normal_penalty * parameters_.penetration_tolerance});
  if (penetration <= parameters_.penetration_tolerance && change <= parameters_.multiplier_tolerance * size)
    return false;
  base.normal_multiplier = trial.normal_force;
  if (stick) {
    base.state = ContactState::Stick;  // also for a node that touched down in this step
    base.tangential_multiplier = trial.tangential_force;
    base.stick_coordinate = trial.stick_coordinate;
  }
  return true;
}

ContactBlock& add_contact_block(Model& model, const std::string& name, std::shared_ptr<const RigidSurface> surface,
                                const std::vector<int>& nodes, const ContactParameters& parameters, double start_time) {
  if (nodes.empty()) throw ModelError("contact block '" + name + "': no nodes");
  parameters.check();
  auto& block = model.add_block<NodeSurfaceContact>(name);
  for (int node : nodes)
    block.add({model.mesh().checked(node)},
              NodeSurfaceContact(surface, model.mesh().position(node), parameters, node, start_time));
  return block;
}

void ContactSummary::add_point(const RigidSurface& surface, const Eigen::Vector2d& point_force, double gap,
                               ContactState state, double coordinate) {
  if (state == ContactState::Open) return;
  force += point_force;
  max_penetration = std::max(max_penetration, -gap);
  if (state == ContactState::Slip) ++nodes_slipping;
  const double offset = nodes_in_contact == 0 ? 0.0 : surface.arc_difference(coordinate, first_);
  if (nodes_in_contact++ == 0) first_ = coordinate;
  low_ = std::min(low_, offset);
  high_ = std::max(high_, offset);
  patch_length = high_ - low_;
}

ContactSummary summarize_contact(const ContactBlock& block) {
  ContactSummary summary;
  for (int e = 0; e < block.size(); ++e) {
    const ContactHistory& h = block.committed_history(e);
    summary.add_point(block.kernel(e).surface(), h.force, h.gap, h.state, h.coordinate);
  }
  return summary;
}

}  // namespace tirefe
