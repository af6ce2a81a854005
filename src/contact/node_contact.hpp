// NodeSurfaceContact: one node against a rigid moving surface, with Coulomb friction, by
// the augmented Lagrangian method (docs/model.md sec. 4, eqs. 14-19; Laursen and Simo 1993).
//
// With x = X + u the node's position and the closest-point projection of x on the surface
// at time t giving gap g, outward normal nu, tangent tau and convected coordinate s:
//   normal (eqs. 14-16):  g = (x - y).nu,   t_N = max(0, lambda_N - eps_N g)
//       (compression positive, g < 0 penetration: g >= 0, t_N >= 0, t_N g = 0 in the limit);
//   friction (eqs. 17-18), a return map on the convected coordinate:
//       trial  t_T* = lambda_T - eps_T (s - s_stick),   Phi = |t_T*| - mu t_N,
//       stick  (Phi <= 0):  t_T = t_T*,
//       slip   (Phi > 0):   t_T = mu t_N sign(t_T*),  s_stick moves so that
//                           lambda_T - eps_T (s - s_stick) = t_T.
//   Slip s - s_stick is measured in the surface's own frame (wrapped on a drum), so a rigid
//   motion of node and surface together gives no tangential force (frame indifference).
//   The force on the node is f = t_N nu + t_T tau; it enters the residual as an internal
//   force, r = -f (u_x, u_y; nothing on theta_z).
// Consistent tangent dr/dx (unsymmetric in slip), with ds/dx = a tau^T, dnu/dx = b tau tau^T,
// dtau/dx = -b nu tau^T from the projection (a = 1/(1 + kappa g), b = kappa/(1 + kappa g);
// at a vertex a = 0, b = 1/g):
//   K = eps_N nu nu^T - t_N b tau tau^T + t_T b nu tau^T + { eps_T a tau tau^T          stick
//                                                          { mu sign eps_N tau nu^T      slip
// Uzawa (augment): after a converged solve lambda_N <- t_N, and for a sticking node
// lambda_T <- t_T with its stick point kept (the stick constraint s = s_stick); a slipping
// node keeps the tangential multiplier and stick point of the step's start, so its friction
// mu t_N follows the updated t_N through the same return map. The step is solved again
// while the node penetrates more than penetration_tolerance or its multipliers change by
// more than multiplier_tolerance (relative; changes below multiplier_tolerance * eps_N *
// penetration_tolerance are ignored). A converged node leaves its multipliers alone, so
// the last solve's history stays consistent with the multipliers it used. A converged
// penetration beyond penetration_limit is a failure (ContactFailure: the step is cut).
// First evaluation (hold_first_evaluation, off by default): a Newton solve starts at the
// predicted state, where a node that was in contact when the step began may have been
// lifted off. Held, such a node's force and stick tangent at the predicted gap (t_N =
// lambda_N - eps_N g < 0, a pull back onto the surface) enter the residual and tangent,
// while its history records it open; every later evaluation applies the law above. The
// converged state is the law's, to Newton's tolerance. It pays where the predictor lifts
// light nodes off that stay (their rates alternating at HHT's high-frequency limit: the
// drum-cleat deck), and costs an increment where nodes truly leave (docs/contact.md).
// Slip reversal: a node slipping one way in one Newton iterate and the other way in the
// next has jumped over its stick zone; the slip tangent (nothing along tau) would send it
// back, and the two iterates repeat (a patch edge's node, eps_T tens of times the
// structure's stiffness there). Its tangent then takes the secant of t_T over t_T*
// between the two iterates, sigma = (t_T - t_T,last) / (t_T* - t_T*,last) in (0, 1), on
// the stick term: K = ... + sigma eps_T a tau tau^T + mu sign eps_N tau nu^T. Only the
// tangent changes; the residual, and so the converged state, is the law's.
// Dynamics: the kernel has no mass or damping; the contact force is weighted by wK like
// every internal force, so HHT-alpha enforces (1 + alpha) f_{n+1} - alpha f_n.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact/rigid_surface.hpp"
#include "core/element.hpp"
#include "core/model.hpp"

namespace tirefe {

/// A converged state the contact cannot accept (a node pushed through the surface).
class ContactFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ContactState : int { Open = 0, Stick = 1, Slip = 2 };

struct ContactParameters {
  double normal_penalty = 0.0;          // eps_N [N/m]
  double tangential_penalty = 0.0;      // eps_T [N/m]; 0: equal to eps_N
  double friction = 0.0;                // mu
  double penetration_tolerance = 5e-4;  // [m], Uzawa stops below it ...
  double multiplier_tolerance = 1e-2;   // ... and below this relative multiplier change
  double penetration_limit = 1e-2;      // [m], deeper after a converged solve is a failure
  double search_distance = 0.05;        // [m], open nodes farther than this skip the projection
  bool hold_first_evaluation = false;   // a solve's first evaluation keeps the step start's contacts (below)

  /// Throws ModelError naming the first non-physical value.
  void check() const;
  double effective_tangential_penalty() const { return tangential_penalty > 0.0 ? tangential_penalty : normal_penalty; }
};

struct ContactHistory {
  // Carried from step to step.
  double stick_coordinate = 0.0;       // s_stick [m]
  double normal_multiplier = 0.0;      // lambda_N [N]
  double tangential_multiplier = 0.0;  // lambda_T [N]
  ContactState state = ContactState::Open;
  std::int32_t unused_after_state = 0;                           // explicit padding: checkpoints copy every byte
  double coordinate = std::numeric_limits<double>::quiet_NaN();  // s at the last evaluation [m]
  // Results of the last evaluation (output).
  double gap = std::numeric_limits<double>::infinity();  // [m]
  double normal_force = 0.0;                             // t_N [N]
  double tangential_force = 0.0;                         // t_T [N], along tau
  double sliding_velocity = 0.0;                         // (v_node - v_surface).tau [m/s]
  double trial_traction = 0.0;                           // t_T* [N] (0 when open): the slip reversal's secant
  Eigen::Vector2d force = Eigen::Vector2d::Zero();       // t_N nu + t_T tau, on the node [N]
};
// No implicit padding, whose bytes would be uninitialised in a checkpoint.
static_assert(sizeof(ContactHistory) == 12 * sizeof(double), "ContactHistory must have no implicit padding");

/// A contact point's named responses (core/element_response.hpp; docs/output.md): a node's
/// ContactHistory or a tread's TreadSample, which carry the same names. The result file
/// writes each as /contact/<block>/<name>; a new one is a name here and its value below.
inline const std::vector<ResponseName>& contact_point_responses() {
  static const std::vector<ResponseName> names{
      {"gap", "m"},        {"normal_force", "N"},      {"tangential_force", "N"}, {"state", "0 open, 1 stick, 2 slip"},
      {"coordinate", "m"}, {"sliding_velocity", "m/s"}};
  return names;
}
template <class Point>
double contact_point_response(int index, const Point& point) {
  switch (index) {
    case 0: return point.gap;
    case 1: return point.normal_force;
    case 2: return point.tangential_force;
    case 3: return static_cast<double>(point.state);
    case 4: return point.coordinate;
    case 5: return point.sliding_velocity;
    default: throw std::out_of_range("a contact point has no response " + std::to_string(index));
  }
}

class NodeSurfaceContact : public KernelShape<1, ContactHistory> {
 public:
  /// 'node' (0-based) only names the node in messages. A node that touches down in its
  /// first step sticks to the surface point below its reference position at start_time.
  NodeSurfaceContact(std::shared_ptr<const RigidSurface> surface, const Eigen::Vector2d& reference_position,
                     const ContactParameters& parameters, int node = -1, double start_time = 0.0);

  static constexpr KernelTraits traits() {
    KernelTraits traits;
    traits.reads_acceleration = false;  // no mass
    traits.reads_last_trial = true;     // the slip reversal's secant (above)
    return traits;
  }

  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History& base, History& trial,
                Vector& residual, Matrix* tangent) const;
  /// Energy of the penalty springs, ((t_N - lambda_N)^2 / eps_N + (t_T - lambda_T)^2 / eps_T) / 2.
  ElementEnergy energy(const LocalState<kDofs>& local, const History& history) const;
  /// Uzawa update; true if this node wants another solve. Throws ContactFailure beyond the
  /// penetration limit.
  bool augment(History& base, const History& trial) const;

  // Named responses (core/element_response.hpp): the node's contact point after a step.
  static constexpr int kResponsePoints = 1;
  static const std::vector<ResponseName>& response_names() { return contact_point_responses(); }
  double response(int index, int, const LocalState<kDofs>&, const History& committed) const {
    return contact_point_response(index, committed);
  }

  const RigidSurface& surface() const { return *surface_; }
  const ContactParameters& parameters() const { return parameters_; }

 private:
  std::shared_ptr<const RigidSurface> surface_;
  Eigen::Vector2d reference_position_;
  ContactParameters parameters_;
  double tangential_penalty_;
  double reference_coordinate_;
  int node_;
};

using ContactBlock = ElementBlockOf<NodeSurfaceContact>;

/// Adds a block of contact elements, one per node, against one surface.
ContactBlock& add_contact_block(Model& model, const std::string& name, std::shared_ptr<const RigidSurface> surface,
                                const std::vector<int>& nodes, const ContactParameters& parameters,
                                double start_time = 0.0);

/// Block totals of the last accepted step.
struct ContactSummary {
  Eigen::Vector2d force = Eigen::Vector2d::Zero();  // sum of t_N nu + t_T tau on the structure [N]
  double patch_length = 0.0;                        // arc length spanned by the points in contact [m]
  int nodes_in_contact = 0;                         // points: nodes, or a tread's samples
  int nodes_slipping = 0;
  double max_penetration = 0.0;  // [m]

  /// Counts one point in contact at surface coordinate 'coordinate' (open points are skipped).
  void add_point(const RigidSurface& surface, const Eigen::Vector2d& point_force, double gap, ContactState state,
                 double coordinate);

 private:
  // Arc lengths relative to the first point in contact (wrapped on a drum).
  double first_ = 0.0, low_ = 0.0, high_ = 0.0;
};
ContactSummary summarize_contact(const ContactBlock& block);

}  // namespace tirefe
