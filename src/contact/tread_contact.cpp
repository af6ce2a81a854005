#include "contact/tread_contact.hpp"

#include <algorithm>
#include <cmath>

namespace tirefe {

void TreadRubber::check() const {
  auto require = [](bool ok, const std::string& what, double value) {
    if (!ok || !std::isfinite(value))
      throw ModelError("tread contact: " + what + " (got " + std::to_string(value) + ")");
  };
  require(normal_stiffness > 0.0, "the tread rubber's normal stiffness must be positive", normal_stiffness);
  require(tangential_stiffness > 0.0, "the tread rubber's tangential stiffness must be positive", tangential_stiffness);
  require(normal_damping >= 0.0, "the tread rubber's normal damping must not be negative", normal_damping);
  require(tangential_damping >= 0.0, "the tread rubber's tangential damping must not be negative", tangential_damping);
  require(friction >= 0.0, "the friction coefficient must not be negative", friction);
  require(search_distance > 0.0, "the search distance must be positive", search_distance);
}

TreadContact::TreadContact(std::shared_ptr<const RigidSurface> surface, const Eigen::Vector2d& start,
                           const Eigen::Vector2d& end, const TreadRubber& rubber)
    : surface_(std::move(surface)), start_(start), end_(end), rubber_(rubber), share_((end - start).norm() / kSamples) {
  if (!surface_) throw ModelError("tread contact: no surface");
  rubber_.check();
  if (!(share_ > 0.0)) throw ModelError("tread contact: a chord of zero length");
}

Eigen::Vector2d TreadContact::sample_position(int q) const {
  const double xi = sample_weight(q);
  return (1.0 - xi) * start_ + xi * end_;
}

namespace {

/// An open sample: no force; what it booked carries over, with the second half of the
/// surface's trapezoid begun when the step began. Sets every field but the gap and
/// coordinate.
void open_sample(const TreadSample& base, double step, TreadSample& trial) {
  trial.state = ContactState::Open;
  trial.material = base.material;
  trial.shear = 0.0;
  trial.normal_force = trial.tangential_force = trial.sliding_velocity = 0.0;
  trial.force.setZero();
  trial.dashpot.setZero();
  trial.surface_power = 0.0;
  trial.surface_work = base.surface_work + 0.5 * step * base.surface_power;
  trial.dissipated = base.dissipated;
}

/// A sample open when its step began and farther than the search distance: not projected;
/// the gap reported is the clearance, a lower bound, the coordinate the last projected.
void far_sample(const TreadSample& base, double step, double clearance, TreadSample& trial) {
  open_sample(base, step, trial);
  trial.gap = clearance;
  trial.coordinate = base.coordinate;
}

}  // namespace

Eigen::Vector2d TreadContact::sample_force(const Eigen::Vector2d& x, const Eigen::Vector2d& v,
                                           const EvaluationContext& context, const RigidPose& pose,
                                           const TreadSample& base, TreadSample& trial, Eigen::Matrix2d* stiffness,
                                           Eigen::Matrix2d* damping) const {
  const double t = context.time, h = context.time_step;
  if (base.state == ContactState::Open) {
    const double clearance = surface_->clearance(x, t);
    if (clearance > rubber_.search_distance) {
      far_sample(base, h, clearance, trial);
      return Eigen::Vector2d::Zero();
    }
  }
  const SurfaceProjection p = surface_->project(x, pose);
  trial.coordinate = p.coordinate;
  trial.gap = p.gap;
  const Eigen::Vector2d& nu = p.normal;
  const Eigen::Vector2d& tau = p.tangent;
  const RigidMotion& motion = surface_->motion();
  // Relative to the surface's material point at x: a sample stuck to a spinning drum turns
  // with it, also when it has sunk into the drum.
  const Eigen::Vector2d surface_velocity = motion.velocity(x, pose);
  const Eigen::Vector2d relative = v - surface_velocity;
  const double v_n = relative.dot(nu), v_t = relative.dot(tau);
  // The dashpots act in dynamics only (their force is weighted as the stiffness's: wC = wK),
  // and give the damping matrix a query asks for alone.
  const bool damped = context.factors.force_damping != 0.0 || context.factors.tangent_damping != 0.0;
  const double k_n = share_ * rubber_.normal_stiffness, c_n = damped ? share_ * rubber_.normal_damping : 0.0;
  const double k_t = share_ * rubber_.tangential_stiffness, c_t = damped ? share_ * rubber_.tangential_damping : 0.0;
  const double penetration = -p.gap;
  const double engaged = std::min(1.0, penetration / kDampingDepth);  // the dashpot's build-up (header)
  const double closing = std::max(0.0, -v_n);                         // it acts while the rubber is compressed
  const double normal_force = k_n * penetration + engaged * c_n * closing;
  const bool landing = base.state == ContactState::Open;  // sticks where it lands, unsheared
  // The sample's travel relative to the surface in this step: from the material point where
  // it was projected when the step began (none known for one that was far then).
  const bool traced = !(base.gap > rubber_.search_distance);
  const Eigen::Vector2d travel =
      traced ? Eigen::Vector2d(x - motion.to_space(base.material, pose)) : Eigen::Vector2d::Zero();
  if (!(penetration > 0.0 && normal_force > 0.0)) {
    // Clear of the surface, or leaving it faster than the rubber springs back: the layer's
    // far side lifts off, and lands again where it next touches. Lifted off still
    // compressed, the layer's dashpot takes what its spring still held; its dashpots' work
    // over the step is the trapezoid's first half.
    open_sample(base, h, trial);
    trial.material = motion.to_material(x, pose);
    if (!landing) {
      // What the layer's springs still held once the belt's work on them is taken (its
      // shear's, and its compression's if it lifted off compressed) goes as it relaxes.
      const double held = std::max(0.0, penetration);
      trial.dissipated += 0.5 * k_n * held * held + 0.5 * k_t * base.shear * (base.shear + tau.dot(travel)) -
                          0.5 * base.dashpot.dot(travel);
    }
    return Eigen::Vector2d::Zero();
  }

  // The rubber's shear d. Sticking, its rate is the sample's sliding velocity; sliding, the
  // layer relaxes toward the friction it carries, k_T d + c_T (d - d_n) / h = -t_T
  // (backward Euler: its own viscosity keeps acting while its far side slides).
  const double trial_shear = landing ? 0.0 : base.shear + tau.dot(travel);  // (a landing's base shear is 0)
  const double trial_traction = -k_t * trial_shear - c_t * v_t;
  const double limit = rubber_.friction * normal_force;
  const bool stick = rubber_.friction > 0.0 && std::abs(trial_traction) <= limit;
  const double sign = trial_traction >= 0.0 ? 1.0 : -1.0;
  const double tangential_force = stick ? trial_traction : sign * limit;
  const Eigen::Vector2d force = normal_force * nu + tangential_force * tau;
  const double viscous = h > 0.0 ? c_t / h : 0.0;
  const double shear = stick ? trial_shear : (viscous * base.shear - tangential_force) / (k_t + viscous);
  const double shear_step = shear - base.shear;

  trial.state = stick ? ContactState::Stick : ContactState::Slip;
  trial.material = motion.to_material(x, pose);
  trial.shear = shear;
  trial.normal_force = normal_force;
  trial.tangential_force = tangential_force;
  trial.sliding_velocity = v_t;
  trial.force = force;
  trial.dashpot = (engaged * c_n * closing) * nu + (stick ? -c_t * v_t : 0.0) * tau;
  trial.surface_power = force.dot(surface_velocity);
  trial.surface_work = base.surface_work + 0.5 * h * (base.surface_power + trial.surface_power);
  // The dashpots' forces over the travel (sliding, the tangential one's c_T (d - d_n)^2 / h),
  // and the friction over the slip.
  // A sample that went on sliding the same way books the mean of its two frictions.
  const bool slid_on = !stick && base.state == ContactState::Slip && base.tangential_force * tangential_force > 0.0;
  const double friction = slid_on ? 0.5 * (std::abs(base.tangential_force) + limit) : limit;
  trial.dissipated = base.dissipated - 0.5 * (base.dashpot + trial.dashpot).dot(travel) +
                     (stick ? 0.0 : viscous * shear_step * shear_step + friction * std::abs(trial_shear - shear));
  if (!stiffness) return force;

  // -df/dx and -df/dv, f = t_N nu + t_T tau (header).
  const double b = p.normal_rate, spin = pose.spin;
  const Eigen::RowVector2d tau_t = tau.transpose(), nu_t = nu.transpose();
  const double closing_rate = closing > 0.0 ? engaged * c_n : 0.0;  // d(e c_N closing)/d(-v_n)
  const double engaging = penetration < kDampingDepth ? c_n * closing / kDampingDepth : 0.0;  // of e c_N closing, by -g
  const Eigen::RowVector2d normal_by_x =
      -(k_n + engaging) * nu_t + (closing_rate * (spin - b * v_t)) * tau_t;  // dt_N/dx
  const Eigen::RowVector2d normal_by_v = -closing_rate * nu_t;               // dt_N/dv
  Eigen::RowVector2d tangential_by_x, tangential_by_v;
  if (stick) {
    const double shear_rate = landing ? 0.0 : k_t * (1.0 - b * nu.dot(travel));
    tangential_by_x = (c_t * b * v_n - shear_rate) * tau_t - (c_t * spin) * nu_t;
    tangential_by_v = -c_t * tau_t;
  } else {
    tangential_by_x = (sign * rubber_.friction) * normal_by_x;
    tangential_by_v = (sign * rubber_.friction) * normal_by_v;
  }
  *stiffness = -nu * normal_by_x - tau * tangential_by_x + b * (tangential_force * nu - normal_force * tau) * tau_t;
  *damping = -nu * normal_by_v - tau * tangential_by_v;
  return force;
}

void TreadContact::evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History& base,
                            History& trial, Vector& residual, Matrix* tangent) const {
  residual.setZero();
  if (tangent) tangent->setZero();
  const Eigen::Vector2d xa = start_ + local.displacement.segment<2>(0);
  const Eigen::Vector2d xb = end_ + local.displacement.segment<2>(3);
  const Eigen::Vector2d va = local.velocity.segment<2>(0), vb = local.velocity.segment<2>(3);
  const IntegratorFactors& f = context.factors;
  // A chord whose samples were all open when the step began and whose every point lies
  // beyond the search distance (a clearance changes no faster than the distance moved
  // along the chord) is not looked at sample by sample: most of a tire's chords.
  if (std::all_of(base.begin(), base.end(), [](const TreadSample& s) { return s.state == ContactState::Open; })) {
    const double clearance = surface_->clearance(0.5 * (xa + xb), context.time) - 0.5 * (xb - xa).norm();
    if (clearance > rubber_.search_distance) {
      for (int q = 0; q < kSamples; ++q) far_sample(base[q], context.time_step, clearance, trial[q]);
      return;
    }
  }
  // The surface's pose once for the chord's samples.
  const RigidPose pose = surface_->motion().pose(context.time);
  Eigen::Matrix2d stiffness, damping;
  for (int q = 0; q < kSamples; ++q) {
    const double xi = sample_weight(q), shares[2] = {1.0 - xi, xi};
    const Eigen::Vector2d force =
        sample_force((1.0 - xi) * xa + xi * xb, (1.0 - xi) * va + xi * vb, context, pose, base[q], trial[q],
                     tangent ? &stiffness : nullptr, tangent ? &damping : nullptr);
    if (trial[q].state == ContactState::Open) continue;
    for (int i = 0; i < 2; ++i) residual.segment<2>(3 * i) -= (f.force_stiffness * shares[i]) * force;
    if (!tangent) continue;
    const Eigen::Matrix2d sample = f.tangent_stiffness * stiffness + f.tangent_damping * damping;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) tangent->block<2, 2>(3 * i, 3 * j) += (shares[i] * shares[j]) * sample;
  }
}

ElementEnergy TreadContact::energy(const LocalState<kDofs>&, const History& history) const {
  ElementEnergy energy;
  for (const TreadSample& sample : history) {
    energy.supplied += sample.surface_work;
    energy.dissipated += sample.dissipated;
    if (sample.state == ContactState::Open) continue;
    energy.strain += 0.5 * share_ *
                     (rubber_.normal_stiffness * sample.gap * sample.gap +
                      rubber_.tangential_stiffness * sample.shear * sample.shear);
  }
  return energy;
}

TreadContactBlock& add_tread_contact_block(Model& model, const std::string& name,
                                           std::shared_ptr<const RigidSurface> surface,
                                           const std::vector<int>& tread_nodes, const TreadRubber& rubber) {
  if (tread_nodes.size() < 3) throw ModelError("tread contact '" + name + "': a ring needs at least 3 tread nodes");
  rubber.check();
  auto& block = model.add_block<TreadContact>(name);
  const Mesh& mesh = model.mesh();
  const size_t count = tread_nodes.size();
  for (size_t i = 0; i < count; ++i) {
    const int a = mesh.checked(tread_nodes[i]), b = mesh.checked(tread_nodes[(i + 1) % count]);
    block.add({a, b}, TreadContact(surface, mesh.position(a), mesh.position(b), rubber));
  }
  return block;
}

ContactSummary summarize_contact(const TreadContactBlock& block) {
  ContactSummary summary;
  for (int e = 0; e < block.size(); ++e)
    for (const TreadSample& sample : block.committed_history(e))
      summary.add_point(block.kernel(e).surface(), sample.force, sample.gap, sample.state, sample.coordinate);
  return summary;
}

}  // namespace tirefe
