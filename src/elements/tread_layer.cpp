#include "elements/tread_layer.hpp"

namespace tirefe {

namespace {
const Eigen::Matrix2d kQuarterTurn = (Eigen::Matrix2d() << 0.0, -1.0, 1.0, 0.0).finished();  // J
}

TreadLayer::TreadLayer(const Eigen::Vector2d& radial, const TreadLayerProperties& properties)
    : mass_(properties.mass) {
  const Eigen::Vector2d e_r = radial.normalized();
  const Eigen::Vector2d e_t = kQuarterTurn * e_r;
  reference_stiffness_ = properties.radial_stiffness * e_r * e_r.transpose() +
                         properties.circumferential_stiffness * e_t * e_t.transpose();
}

Eigen::Matrix2d TreadLayer::stiffness_in_frame(double theta) const {
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(theta).toRotationMatrix();
  return rotation * reference_stiffness_ * rotation.transpose();
}

void TreadLayer::evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&,
                          History&, Vector& residual, Matrix* tangent) const {
  const IntegratorFactors& f = context.factors;
  const Eigen::Vector2d d = local.displacement.segment<2>(0) - local.displacement.segment<2>(3);
  const Eigen::Matrix2d B = stiffness_in_frame(local.displacement[5]);
  const Eigen::Vector2d force = B * d;
  const Eigen::Vector2d turned = kQuarterTurn * d;  // J d; d x f = (J d) . f

  residual.setZero();
  residual.segment<2>(0) = f.force_stiffness * force + f.force_mass * mass_ * local.acceleration.segment<2>(0);
  residual.segment<2>(3) = -f.force_stiffness * force;
  residual[5] = -f.force_stiffness * turned.dot(force);
  if (!tangent) return;

  const Eigen::Vector2d g = (kQuarterTurn * B - B * kQuarterTurn) * d;
  const double cK = f.tangent_stiffness;
  tangent->setZero();
  tangent->block<2, 2>(0, 0) = cK * B + (f.tangent_mass * mass_) * Eigen::Matrix2d::Identity();
  tangent->block<2, 2>(0, 3) = -cK * B;
  tangent->block<2, 2>(3, 0) = -cK * B;
  tangent->block<2, 2>(3, 3) = cK * B;
  tangent->block<2, 1>(0, 5) = cK * g;
  tangent->block<1, 2>(5, 0) = cK * g.transpose();
  tangent->block<2, 1>(3, 5) = -cK * g;
  tangent->block<1, 2>(5, 3) = -cK * g.transpose();
  (*tangent)(5, 5) = cK * (turned.dot(B * turned) - d.dot(force));
}

ElementEnergy TreadLayer::energy(const LocalState<kDofs>& local, const History&) const {
  const Eigen::Vector2d d = local.displacement.segment<2>(0) - local.displacement.segment<2>(3);
  ElementEnergy energy;
  energy.strain = 0.5 * d.dot(stiffness_in_frame(local.displacement[5]) * d);
  energy.kinetic = 0.5 * mass_ * local.velocity.segment<2>(0).squaredNorm();
  return energy;
}

}  // namespace tirefe
