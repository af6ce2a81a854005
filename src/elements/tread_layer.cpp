#include "elements/tread_layer.hpp"

#include <cmath>

namespace tirefe {

namespace {
const Eigen::Matrix2d kQuarterTurn = (Eigen::Matrix2d() << 0.0, -1.0, 1.0, 0.0).finished();  // J
}

TreadLayer::TreadLayer(const Eigen::Vector2d& radial, const TreadLayerProperties& properties)
    : radial_(radial.normalized()), properties_(properties) {
  damped_ = properties.radial_damping != 0.0 || properties.circumferential_damping != 0.0;
}

Eigen::Matrix2d TreadLayer::in_frame(double radial, double circumferential, const Eigen::Vector2d& e) {
  return circumferential * Eigen::Matrix2d::Identity() + ((radial - circumferential) * e) * e.transpose();
}

Eigen::Vector2d TreadLayer::turning_rate(double radial, double circumferential, const Eigen::Vector2d& e,
                                         const Eigen::Vector2d& x) {
  const Eigen::Vector2d e_t = kQuarterTurn * e;
  return (radial - circumferential) * (e_t * e.dot(x) + e * e_t.dot(x));
}

Eigen::Vector2d TreadLayer::turned_radial(double angle) const {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * radial_.x() - s * radial_.y(), s * radial_.x() + c * radial_.y()};
}

void TreadLayer::evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&, History&,
                          Vector& residual, Matrix* tangent) const {
  const IntegratorFactors& f = context.factors;
  const Eigen::Vector2d d = local.displacement.segment<2>(0) - local.displacement.segment<2>(3);
  const Eigen::Vector2d e = turned_radial(local.displacement[5]);
  const double k_r = properties_.radial_stiffness, k_t = properties_.circumferential_stiffness;
  const Eigen::Matrix2d B = in_frame(k_r, k_t, e);
  const Eigen::Vector2d force = B * d;
  const Eigen::Vector2d turned = kQuarterTurn * d;  // J d; d x f = (J d) . f

  residual.setZero();
  residual.segment<2>(0) =
      f.force_stiffness * force + (f.force_mass * properties_.mass) * local.acceleration.segment<2>(0);
  residual.segment<2>(3) = -f.force_stiffness * force;
  residual[5] = -f.force_stiffness * turned.dot(force);
  if (!tangent) {
    if (damped_) add_damping(local, context, e, residual, nullptr);
    return;
  }

  const Eigen::Vector2d g = turning_rate(k_r, k_t, e, d);
  const double cK = f.tangent_stiffness;
  tangent->setZero();
  tangent->block<2, 2>(0, 0) = cK * B + (f.tangent_mass * properties_.mass) * Eigen::Matrix2d::Identity();
  tangent->block<2, 2>(0, 3) = -cK * B;
  tangent->block<2, 2>(3, 0) = -cK * B;
  tangent->block<2, 2>(3, 3) = cK * B;
  tangent->block<2, 1>(0, 5) = cK * g;
  tangent->block<1, 2>(5, 0) = cK * g.transpose();
  tangent->block<2, 1>(3, 5) = -cK * g;
  tangent->block<1, 2>(5, 3) = -cK * g.transpose();
  (*tangent)(5, 5) = cK * (turned.dot(B * turned) - d.dot(force));
  if (damped_) add_damping(local, context, e, residual, tangent);
}

void TreadLayer::add_damping(const LocalState<kDofs>& local, const EvaluationContext& context, const Eigen::Vector2d& e,
                             Vector& residual, Matrix* tangent) const {
  const IntegratorFactors& f = context.factors;
  if (f.force_damping == 0.0 && (!tangent || f.tangent_damping == 0.0)) return;  // quasi-static
  const Eigen::Vector2d d = local.displacement.segment<2>(0) - local.displacement.segment<2>(3);
  const Eigen::Vector2d d_rate = local.velocity.segment<2>(0) - local.velocity.segment<2>(3);
  const double spin = local.velocity[5];
  const double c_r = properties_.radial_damping, c_t = properties_.circumferential_damping;
  const Eigen::Matrix2d C = in_frame(c_r, c_t, e);
  const Eigen::Vector2d turned = kQuarterTurn * d;
  const Eigen::Vector2d w = d_rate - spin * turned;  // rate of d in the turning frame
  const Eigen::Vector2d force = C * w;
  const double wD = f.force_damping, cC = f.tangent_damping;
  residual.segment<2>(0) += wD * force;
  residual.segment<2>(3) -= wD * force;
  residual[5] -= wD * turned.dot(force);
  if (!tangent) return;

  // Derivatives of f_d: by d (through w) -spin C J, by theta (C turns) (J C - C J) w,
  // by d' C, by theta' -C J d; the moment -(J d).f_d adds -(J^T f_d) by d.
  const Eigen::Matrix2d by_d = wD * (-spin * C * kQuarterTurn);
  const Eigen::Vector2d by_theta = wD * turning_rate(c_r, c_t, e, w);
  const Eigen::Matrix2d by_rate = cC * C;
  const Eigen::Vector2d by_spin = cC * (-C * turned);
  const Eigen::Matrix2d force_by_d = by_d + by_rate;          // d and d' enter as u_c - u_b
  const Eigen::Vector2d force_by_theta = by_theta + by_spin;  // theta and theta' of the belt node
  Matrix& K = *tangent;
  K.block<2, 2>(0, 0) += force_by_d;
  K.block<2, 2>(0, 3) -= force_by_d;
  K.block<2, 2>(3, 0) -= force_by_d;
  K.block<2, 2>(3, 3) += force_by_d;
  K.block<2, 1>(0, 5) += force_by_theta;
  K.block<2, 1>(3, 5) -= force_by_theta;
  const Eigen::RowVector2d moment_by_d =
      -(turned.transpose() * force_by_d) - wD * (kQuarterTurn.transpose() * force).transpose();
  K.block<1, 2>(5, 0) += moment_by_d;
  K.block<1, 2>(5, 3) -= moment_by_d;
  K(5, 5) += -turned.dot(force_by_theta);
}

ElementEnergy TreadLayer::energy(const LocalState<kDofs>& local, const History&) const {
  const Eigen::Vector2d d = local.displacement.segment<2>(0) - local.displacement.segment<2>(3);
  ElementEnergy energy;
  const Eigen::Matrix2d B = in_frame(properties_.radial_stiffness, properties_.circumferential_stiffness,
                                     turned_radial(local.displacement[5]));
  energy.strain = 0.5 * d.dot(B * d);
  energy.kinetic = 0.5 * properties_.mass * local.velocity.segment<2>(0).squaredNorm();
  return energy;
}

}  // namespace tirefe
