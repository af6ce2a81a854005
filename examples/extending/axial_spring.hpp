// AxialSpring: a linear spring between two nodes that acts along the line joining them as
// they move (a truss bar), the worked element of docs/extending.md. With x_a, x_b the
// current positions, l = |x_b - x_a|, n = (x_b - x_a) / l and L the rest length:
//     axial force N = k (l - L),   f_b = -f_a = N n,   energy k (l - L)^2 / 2,
//     dF/du on the b-b block = k n n^T + (N / l) (I - n n^T), the a-b blocks its negative.
// It has no mass and no damping, and leaves the node rotations alone. Its axial force is a
// named response (core/element_response.hpp) that output asks for by name.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "core/element.hpp"

namespace tirefe::examples {

class AxialSpring : public KernelShape<2> {
 public:
  // Promises that let the block loop skip work (KernelTraits, element.hpp); the element
  // tests check them.
  static constexpr KernelTraits traits() {
    KernelTraits traits;
    traits.reads_acceleration = false;
    traits.reads_velocity = false;
    traits.idle_dofs = {2, 5};  // the two rotations
    return traits;
  }

  AxialSpring(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double stiffness)
      : reference_(b - a), rest_length_(reference_.norm()), stiffness_(stiffness) {
    if (!(stiffness > 0.0) || !(rest_length_ > 0.0))
      throw ModelError("axial spring: needs a positive stiffness (got " + std::to_string(stiffness) +
                       ") between two distinct nodes");
  }

  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&, History&,
                Vector& residual, Matrix* tangent) const {
    const Eigen::Vector2d d = current(local);
    const double length = d.norm();
    const Eigen::Vector2d n = d / length;
    const double force = stiffness_ * (length - rest_length_);
    residual.setZero();
    residual.segment<2>(0) = -context.factors.force_stiffness * force * n;
    residual.segment<2>(3) = context.factors.force_stiffness * force * n;
    if (!tangent) return;
    const Eigen::Matrix2d nn = n * n.transpose();
    const Eigen::Matrix2d k =
        context.factors.tangent_stiffness * (stiffness_ * nn + force / length * (Eigen::Matrix2d::Identity() - nn));
    tangent->setZero();
    tangent->block<2, 2>(0, 0) = k;
    tangent->block<2, 2>(0, 3) = -k;
    tangent->block<2, 2>(3, 0) = -k;
    tangent->block<2, 2>(3, 3) = k;
  }

  ElementEnergy energy(const LocalState<kDofs>& local, const History&) const {
    const double stretch = current(local).norm() - rest_length_;
    ElementEnergy energy;
    energy.strain = 0.5 * stiffness_ * stretch * stretch;
    return energy;
  }

  // Its named response: the axial force N, at one point.
  static constexpr int kResponsePoints = 1;
  static const std::vector<ResponseName>& response_names() {
    static const std::vector<ResponseName> names{{"axial_force", "N"}};
    return names;
  }
  double response(int, int, const LocalState<kDofs>& local, const History&) const {
    return stiffness_ * (current(local).norm() - rest_length_);
  }

 private:
  /// x_b - x_a in the current configuration.
  Eigen::Vector2d current(const LocalState<kDofs>& local) const {
    return reference_ + local.displacement.segment<2>(3) - local.displacement.segment<2>(0);
  }

  Eigen::Vector2d reference_;  // X_b - X_a
  double rest_length_;
  double stiffness_;
};

}  // namespace tirefe::examples
