// TreadLayer: the compliance of the tread rubber between a belt node and the point of
// the tread surface that touches the road (the contact node), as a spring with a radial
// and a circumferential stiffness in the belt node's rotating frame, and the mass of the
// rubber at the contact node.
//
// Nodes: c (the contact node: u_x, u_y; its rotation carries nothing and is held by the
// tire builder) and b (the belt node: u_x, u_y, theta). In the reference state the two
// coincide (a layer of zero thickness: only its compliance matters); E_r is the outward
// radial direction at the node, E_t = k x E_r. The frame turns with the belt section,
// R = R(theta_b), so a rigid motion of the tire strains nothing:
//     d = x_c - x_b = u_c - u_b,     B = R (k_r E_r E_r^T + k_t E_t E_t^T) R^T,
//     W = d^T B d / 2,
//     force on c   f = B d,   on b  -f,   moment on b  m = -(d x f)   (moments balance),
// k_r, k_t the stiffness of the node's share of the circumference [N/m]. With J the
// rotation by +90 degrees (dB/dtheta = J B - B J) and g = (J B - B J) d, the tangent is
// symmetric:
//     K_cc = B, K_cb = -B, K_c theta = g,  K_bb = B, K_b theta = -g,
//     K_theta theta = (J d)^T B (J d) - d^T B d.
// Inertia: m a_c on the contact node (m the node's share of the layer mass).
// Damping (the rubber's hysteresis, as a Kelvin-Voigt dashpot in the same frame): the rate
// of d seen from the turning frame, w = d' - theta_b' J d, so that a strained layer carried
// round by the rolling belt is not damped; f_d = C w with C = R (c_r E_r E_r^T + c_t E_t E_t^T) R^T,
// on c, -f_d on b, and the moment -(d x f_d) on b. Its tangent is unsymmetric.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "core/element.hpp"

namespace tirefe {

struct TreadLayerProperties {
  double radial_stiffness = 0.0;           // k_r [N/m]
  double circumferential_stiffness = 0.0;  // k_t [N/m]
  double mass = 0.0;                       // m on the contact node [kg]
  double radial_damping = 0.0;             // c_r [N s/m]
  double circumferential_damping = 0.0;    // c_t [N s/m]
};

class TreadLayer : public KernelShape<2> {
 public:
  static constexpr std::array<int, 1> kIdleDofs = {2};  // the contact node's rotation
  /// 'radial' is the outward direction at the node in the reference state (normalised here).
  TreadLayer(const Eigen::Vector2d& radial, const TreadLayerProperties& properties);

  /// Local DOFs: contact node (u_x, u_y, theta unused), belt node (u_x, u_y, theta).
  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History& committed,
                History& trial, Vector& residual, Matrix* tangent) const;
  ElementEnergy energy(const LocalState<kDofs>& local, const History& history) const;
  /// M x: the mass on the contact node's translations.
  Vector mass_times(const Vector& x) const;
  /// The block's batch path (element.hpp): every layer at once, the same numbers.
  class Batch;

 private:
  /// Radial/circumferential values a_r, a_t in the frame turned to the radial direction e:
  /// a_t I + (a_r - a_t) e e^T (= R (a_r E_r E_r^T + a_t E_t E_t^T) R^T).
  static Eigen::Matrix2d in_frame(double radial, double circumferential, const Eigen::Vector2d& e);
  /// (J A - A J) x for that A: its rate as the frame turns, (a_r - a_t)(J e (e.x) + e (J e . x)).
  static Eigen::Vector2d turning_rate(double radial, double circumferential, const Eigen::Vector2d& e,
                                      const Eigen::Vector2d& x);
  /// The outward radial direction R(theta_b) E_r of the belt node's turned frame.
  Eigen::Vector2d turned_radial(double angle) const;
  void add_damping(const LocalState<kDofs>& local, const EvaluationContext& context, const Eigen::Vector2d& e,
                   Vector& residual, Matrix* tangent) const;

  Eigen::Vector2d radial_;  // E_r, unit
  TreadLayerProperties properties_;
  bool damped_ = false;
};

/// Layers over structure-of-arrays data: one loop vectorised across layers turns the
/// frame (the sine and cosine of theta_b inline, sine_cosine.hpp) and forms the spring and
/// dashpot forces and the element vectors and matrices of evaluate().
class TreadLayer::Batch {
 public:
  explicit Batch(const std::vector<TreadLayer>& layers);
  int size() const { return count_; }
  void evaluate(const BlockValues& values, const EvaluationContext& context, bool with_tangent);
  const double* residual() const { return residual_.data(); }
  const double* tangent() const { return tangent_.data(); }
  /// The layers' strain and kinetic energy, summed: energy()'s terms.
  ElementEnergy energy(const BlockValues& values) const;

 private:
  template <bool Tangent, bool Damped>
  void evaluate_layers(const BlockValues& values, const IntegratorFactors& f);

  int count_ = 0;
  bool damped_ = false;  // some layer has dashpots
  // Per layer: E_r, k_r, k_t, m, c_r, c_t.
  std::vector<double> radial_x_, radial_y_, radial_stiffness_, circumferential_stiffness_, mass_, radial_damping_,
      circumferential_damping_;
  std::vector<double> residual_, tangent_;  // [k * size + e]
};

}  // namespace tirefe
