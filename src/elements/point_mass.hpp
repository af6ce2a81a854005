// NodalSpringMass: one node tied to ground by a linear spring and a dashpot per
// component, carrying a point mass and a rotary inertia. Used for the rim/hub of the
// tire, for test rigs and for single-degree-of-freedom checks of the integrators.
//
// Per component i in (u_x, u_y, theta_z), with m_i = (m, m, J):
//   f_i = k_i u_i + c_i v_i + m_i a_i,
//   energy: strain = sum k_i u_i^2 / 2, kinetic = sum m_i v_i^2 / 2.
// The springs act along the global axes (no geometric stiffness), so the kernel is
// linear and its tangent is the diagonal cK k + cC c + cM m.
#pragma once

#include <Eigen/Dense>

#include "core/element.hpp"

namespace tirefe {

struct SpringMassProperties {
  Eigen::Vector3d stiffness = Eigen::Vector3d::Zero();  // k_x, k_y [N/m], k_rz [N m/rad]
  Eigen::Vector3d damping = Eigen::Vector3d::Zero();    // c_x, c_y [N s/m], c_rz [N m s/rad]
  double mass = 0.0;                                    // m [kg], on u_x and u_y
  double rotary_inertia = 0.0;                          // J [kg m^2], on theta_z

  /// Throws ModelError naming the first negative or non-finite value.
  void check() const;
  /// (m, m, J): the inertia of each component.
  Eigen::Vector3d inertia() const { return {mass, mass, rotary_inertia}; }
};

class NodalSpringMass : public KernelShape<1> {
 public:
  explicit NodalSpringMass(const SpringMassProperties& properties);

  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History& committed,
                History& trial, Vector& residual, Matrix* tangent) const;
  ElementEnergy energy(const LocalState<kDofs>& local, const History& history) const;
  /// M x: (m, m, J) times x.
  Vector mass_times(const Vector& x) const { return inertia_.cwiseProduct(x); }

  const SpringMassProperties& properties() const { return properties_; }

 private:
  SpringMassProperties properties_;
  Vector inertia_;  // (m, m, J), kept to avoid rebuilding it per evaluation
};

}  // namespace tirefe
