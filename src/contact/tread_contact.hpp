// TreadContact: a tire's tread surface against a rigid moving surface through its tread
// rubber, a massless compliant layer (docs/contact.md, "Tread contact").
//
// Why: a node with mass that meets a stiff penalty rattles on it, in any implicit scheme,
// when the contact's period is shorter than the step (an impact); refining the step makes
// it worse. Contact acting on massless points does not (Khenous, Laborde and Renard 2008:
// mass redistribution). The tread rubber between the belt and the road is that massless
// layer: its compliance, not a penalty, sets the contact force, and its far side follows
// the road. Condensed, a massless layer of radial stiffness k_N and shear stiffness k_T
// whose far side sits on (or sticks to) a rigid surface is a compliant contact law at the
// belt: the normal force is k_N times the layer's compression and the shear is k_T times
// the belt point's travel along the surface since its rubber stuck, capped by Coulomb
// friction.
//
// One element is one chord of the belt between tread nodes a and b (counter-clockwise).
// The law acts at kSamples points x_q = (1 - xi_q) x_a + xi_q x_b, xi_q = (q + 1/2)/Q, each
// carrying the rubber of its share l_q = L_0 / Q of the reference chord, so that an edge
// narrower than a node spacing is felt wherever it meets the tread. At a sample, with the
// closest-point projection of x_q (gap g, normal nu, tangent tau, curvature rate b:
// contact/surface_curve.hpp) and v_rel = v_q - v_surface(x_q) its velocity relative to the
// surface's material point at x_q:
//   normal  t_N = l_q (k_N (-g) + e c_N (-v_rel.nu))  while -g > 0 and t_N > 0, else open;
//           e = min(1, -g / d_0): the dashpot builds up over the first d_0 = 0.5 mm of
//           compression (Hunt and Crossley 1975: a contact's damping grows with its
//           indentation), so the force neither jumps at first touch, which would make
//           Newton cycle on the patch's edge, nor pulls at separation;
//   shear   the rubber's shear d grows with the sample's travel relative to the surface,
//           measured by the material point X_n of the surface where the sample was when
//           the step began: d* = d_n + tau.(x_q - Y), Y = X_n carried to the present
//           (0 for a sample that lands: it sticks where it lands);
//           stick:  t_T = -l_q (k_T d* + c_T v_rel.tau),  d = d*;
//           slip (|t_T| > mu t_N):  t_T = mu t_N sign, and the layer relaxes toward it,
//                   l_q (k_T d + c_T (d - d_n) / h) = -t_T (backward Euler: the layer's
//                   own viscosity keeps acting while its far side slides);
//   force on the belt  f = t_N nu + t_T tau, shared as (1 - xi_q) f on a and xi_q f on b.
// The shear follows the travel, not the closest point's coordinate, which jumps from face
// to face inside a corner: such a jump is no sliding, and neither stores nor dissipates.
// The residual is -wK f on each node (as an internal force; the rotations carry nothing;
// the dashpots act only where the integrator weighs damping, wC > 0, and wC = wK there)
// and the tangent cK (-df/dx) + cC (-df/dv), with (as for the node contact, node_contact.hpp)
//   d(-g)/dx = -nu^T,  dnu/dx = b tau tau^T,  dtau/dx = -b nu tau^T,
//   dd*/dx = (1 - b nu.(x_q - Y)) tau^T,
//   d(-v_rel.nu)/dx = (omega - b v_rel.tau) tau^T,  d(v_rel.tau)/dx = -b (v_rel.nu) tau^T + omega nu^T
// (omega the surface's spin).
// Energy (EnergyBalance): the layer stores l_q (k_N g^2 + k_T d^2) / 2; a sample books,
// per step of size h, the work the moving surface does on the tire, (P_n + P_n+1) h / 2
// with P = f.v_surface; the dashpots' dissipation as the trapezoid of their forces over the
// sample's travel relative to the surface, -(f_d,n + f_d,n+1)/2 . (x_q - Y), as the
// integrator sums the work of forces (sliding, the tangential one's l_q c_T (d - d_n)^2 / h);
// and the friction's, |t_T| |d* - d|, the slip. A sample that lets go of the surface
// dissipates what its layer stored, less the work the belt did on it meanwhile.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "contact/node_contact.hpp"
#include "contact/rigid_surface.hpp"
#include "core/element.hpp"
#include "core/model.hpp"

namespace tirefe {

/// The tread rubber's law, per metre of the tread's reference circumference.
struct TreadRubber {
  double normal_stiffness = 0.0;      // k_N [N/m^2]: force per m of tread per m of compression
  double tangential_stiffness = 0.0;  // k_T [N/m^2]: shear force per m of tread per m of shear
  double normal_damping = 0.0;        // c_N [N s/m^2]
  double tangential_damping = 0.0;    // c_T [N s/m^2]
  double friction = 0.0;              // mu
  double search_distance = 0.005;     // [m]: samples farther from the surface are not projected

  /// Throws ModelError naming the first non-physical value.
  void check() const;
};

/// One sample point's contact state.
struct TreadSample {
  Eigen::Vector2d force = Eigen::Vector2d::Zero();     // t_N nu + t_T tau on the tire [N]
  Eigen::Vector2d material = Eigen::Vector2d::Zero();  // X: where the sample is, in the surface's own frame [m]
  Eigen::Vector2d dashpot = Eigen::Vector2d::Zero();   // the dashpots' share of the force, sticking [N]
  double shear = 0.0;                                  // d, the rubber's elastic shear [m]
  double coordinate = std::numeric_limits<double>::quiet_NaN();  // s at the last projection [m]
  double gap = std::numeric_limits<double>::infinity();          // [m]
  double normal_force = 0.0;                                     // t_N [N]
  double tangential_force = 0.0;                                 // t_T [N], along tau
  double sliding_velocity = 0.0;                                 // v_rel.tau [m/s]
  double surface_power = 0.0;                                    // f.v_surface [W]
  double surface_work = 0.0;                                     // booked since the start [J]
  double dissipated = 0.0;                                       // friction + dashpots, since the start [J]
  ContactState state = ContactState::Open;
  std::int32_t unused_after_state = 0;  // explicit padding: checkpoints copy every byte
};
static_assert(sizeof(TreadSample) == 16 * sizeof(double), "TreadSample must have no implicit padding");

class TreadContact : public KernelShape<2, std::array<TreadSample, 8>> {
 public:
  static constexpr int kSamples = 8;
  static constexpr double kDampingDepth = 0.5e-3;  // d_0 [m]
  static constexpr KernelTraits traits() {
    KernelTraits traits;
    traits.reads_acceleration = false;  // massless
    traits.reads_last_trial = true;     // evaluate() writes every field of 'trial' (no copy of 'base')
    traits.books_energy = true;         // its dashpots and friction (energy())
    traits.idle_dofs = {2, 5};          // the rotations
    return traits;
  }

  /// The chord's reference end points (counter-clockwise about the tire's centre).
  TreadContact(std::shared_ptr<const RigidSurface> surface, const Eigen::Vector2d& start, const Eigen::Vector2d& end,
               const TreadRubber& rubber);

  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History& base, History& trial,
                Vector& residual, Matrix* tangent) const;
  /// The layer's stored energy, and what the samples booked (surface work, dissipation).
  ElementEnergy energy(const LocalState<kDofs>& local, const History& history) const;

  // Named responses (core/element_response.hpp): each sample's contact point after a step.
  static constexpr int kResponsePoints = kSamples;
  static const std::vector<ResponseName>& response_names() { return contact_point_responses(); }
  double response(int index, int sample, const LocalState<kDofs>&, const History& committed) const {
    return contact_point_response(index, committed[sample]);
  }

  const RigidSurface& surface() const { return *surface_; }
  const TreadRubber& rubber() const { return rubber_; }
  /// Reference position of sample q.
  Eigen::Vector2d sample_position(int q) const;
  static double sample_weight(int q) { return (q + 0.5) / kSamples; }  // xi_q

 private:
  /// The law at one sample at x with velocity v, the surface at 'pose': its force on the
  /// tire (returned), and -df/dx, -df/dv when 'stiffness' is given.
  Eigen::Vector2d sample_force(const Eigen::Vector2d& x, const Eigen::Vector2d& v, const EvaluationContext& context,
                               const RigidPose& pose, const TreadSample& base, TreadSample& trial,
                               Eigen::Matrix2d* stiffness, Eigen::Matrix2d* damping) const;

  std::shared_ptr<const RigidSurface> surface_;
  Eigen::Vector2d start_, end_;
  TreadRubber rubber_;
  double share_;  // l_q [m]
};

using TreadContactBlock = ElementBlockOf<TreadContact>;

/// Adds a block of tread contact elements on the chords of a ring of tread nodes
/// (counter-clockwise, closed) against one surface.
TreadContactBlock& add_tread_contact_block(Model& model, const std::string& name,
                                           std::shared_ptr<const RigidSurface> surface,
                                           const std::vector<int>& tread_nodes, const TreadRubber& rubber);

ContactSummary summarize_contact(const TreadContactBlock& block);

}  // namespace tirefe
