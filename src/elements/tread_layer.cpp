#include "elements/tread_layer.hpp"

#include <cmath>

#include "core/simd_clones.hpp"
#include "elements/sine_cosine.hpp"

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

TreadLayer::Vector TreadLayer::mass_times(const Vector& x) const {
  Vector product = Vector::Zero();
  product.segment<2>(0) = properties_.mass * x.segment<2>(0);
  return product;
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

// The batch path. Its arithmetic is evaluate()'s, term for term, written per layer on
// arrays indexed by the layer, so that the loop over layers vectorises. The contact node's
// rotation (local DOF 2) is idle: its residual entry and tangent row and column stay zero.
TreadLayer::Batch::Batch(const std::vector<TreadLayer>& layers) : count_(static_cast<int>(layers.size())) {
  for (auto* field : {&radial_x_, &radial_y_, &radial_stiffness_, &circumferential_stiffness_, &mass_, &radial_damping_,
                      &circumferential_damping_})
    field->assign(count_, 0.0);
  residual_.assign(static_cast<size_t>(kDofs) * count_, 0.0);
  tangent_.assign(static_cast<size_t>(kDofs) * kDofs * count_, 0.0);
  for (int e = 0; e < count_; ++e) {
    const TreadLayer& layer = layers[e];
    radial_x_[e] = layer.radial_.x();
    radial_y_[e] = layer.radial_.y();
    radial_stiffness_[e] = layer.properties_.radial_stiffness;
    circumferential_stiffness_[e] = layer.properties_.circumferential_stiffness;
    mass_[e] = layer.properties_.mass;
    // An undamped layer's dashpot terms are zero in a damped block.
    radial_damping_[e] = layer.damped_ ? layer.properties_.radial_damping : 0.0;
    circumferential_damping_[e] = layer.damped_ ? layer.properties_.circumferential_damping : 0.0;
    damped_ = damped_ || layer.damped_;
  }
}

TIREFE_SIMD_CLONES ElementEnergy TreadLayer::Batch::energy(const BlockValues& values) const {
  const int n = count_;
  const double* u = values.displacement;
  const double* v = values.velocity;
  return sum_energies(n, [&](int e) {
    const double d[2] = {u[e] - u[3 * n + e], u[n + e] - u[4 * n + e]};
    const SineCosine turn = sine_cosine(u[5 * n + e]);
    const double radial[2] = {turn.cos * radial_x_[e] - turn.sin * radial_y_[e],
                              turn.sin * radial_x_[e] + turn.cos * radial_y_[e]};
    // d.B d with B = k_t I + (k_r - k_t) e e^T.
    const double along = radial[0] * d[0] + radial[1] * d[1];
    const double k_r = radial_stiffness_[e], k_t = circumferential_stiffness_[e];
    ElementEnergy energy;
    energy.strain = 0.5 * (k_t * (d[0] * d[0] + d[1] * d[1]) + (k_r - k_t) * along * along);
    energy.kinetic = 0.5 * mass_[e] * (v[e] * v[e] + v[n + e] * v[n + e]);
    return energy;
  });
}

template <bool Tangent, bool Damped>
TIREFE_SIMD_CLONES void TreadLayer::Batch::evaluate_layers(const BlockValues& values, const IntegratorFactors& f) {
  const int n = count_;
  const double* u = values.displacement;
  const double* v = values.velocity;
  const double* a = values.acceleration;
  double* residual = residual_.data();
  double* tangent = tangent_.data();
  constexpr int kTranslations[4] = {0, 1, 3, 4};  // contact node, then belt node
#pragma omp simd
  for (int e = 0; e < n; ++e) {
    const double d[2] = {u[e] - u[3 * n + e], u[n + e] - u[4 * n + e]};
    const SineCosine turn = sine_cosine(u[5 * n + e]);  // the turned radial direction
    const double radial[2] = {turn.cos * radial_x_[e] - turn.sin * radial_y_[e],
                              turn.sin * radial_x_[e] + turn.cos * radial_y_[e]};
    const double across[2] = {-radial[1], radial[0]};  // J e
    const double k_r = radial_stiffness_[e], k_t = circumferential_stiffness_[e];
    double B[2][2];
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) B[r][c] = (r == c ? k_t : 0.0) + ((k_r - k_t) * radial[r]) * radial[c];
    const double force[2] = {B[0][0] * d[0] + B[0][1] * d[1], B[1][0] * d[0] + B[1][1] * d[1]};
    const double turned[2] = {-d[1], d[0]};  // J d; d x f = (J d) . f
    double rows[6];                          // residual entries 0, 1, 3, 4, then the moment
    for (int c = 0; c < 2; ++c) {
      rows[c] = f.force_stiffness * force[c] + (f.force_mass * mass_[e]) * a[c * n + e];
      rows[2 + c] = -f.force_stiffness * force[c];
    }
    rows[4] = -f.force_stiffness * (turned[0] * force[0] + turned[1] * force[1]);

    double C[2][2] = {}, damping[2] = {0.0, 0.0}, rate[2] = {0.0, 0.0}, spin = 0.0;
    if (Damped) {
      const double c_r = radial_damping_[e], c_t = circumferential_damping_[e];
      spin = v[5 * n + e];
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) C[r][c] = (r == c ? c_t : 0.0) + ((c_r - c_t) * radial[r]) * radial[c];
      // The rate of d in the turning frame, and the dashpot force on it.
      for (int c = 0; c < 2; ++c) rate[c] = (v[c * n + e] - v[(3 + c) * n + e]) - spin * turned[c];
      for (int c = 0; c < 2; ++c) {
        damping[c] = C[c][0] * rate[0] + C[c][1] * rate[1];
        rows[c] += f.force_damping * damping[c];
        rows[2 + c] -= f.force_damping * damping[c];
      }
      rows[4] -= f.force_damping * (turned[0] * damping[0] + turned[1] * damping[1]);
    }
    for (int k = 0; k < 4; ++k) residual[kTranslations[k] * n + e] = rows[k];
    residual[5 * n + e] = rows[4];
    if (!Tangent) continue;

    // The frame's turning rate g = (J B - B J) d, and the blocks of evaluate().
    const double cK = f.tangent_stiffness;
    const double along_d = radial[0] * d[0] + radial[1] * d[1], across_d = across[0] * d[0] + across[1] * d[1];
    double by_d[2][2], by_theta[2], moment_by_d[2];
    for (int r = 0; r < 2; ++r) {
      by_theta[r] = cK * ((k_r - k_t) * (across[r] * along_d + radial[r] * across_d));
      for (int c = 0; c < 2; ++c) by_d[r][c] = cK * B[r][c];
      moment_by_d[r] = by_theta[r];  // the spring's tangent is symmetric
    }
    const double turned_B_turned = turned[0] * (B[0][0] * turned[0] + B[0][1] * turned[1]) +
                                   turned[1] * (B[1][0] * turned[0] + B[1][1] * turned[1]);
    double spin_spin = cK * (turned_B_turned - (d[0] * force[0] + d[1] * force[1]));
    double mass_diagonal = f.tangent_mass * mass_[e];
    if (Damped) {
      const double c_r = radial_damping_[e], c_t = circumferential_damping_[e];
      const double wD = f.force_damping, cC = f.tangent_damping;
      const double along_w = radial[0] * rate[0] + radial[1] * rate[1];
      const double across_w = across[0] * rate[0] + across[1] * rate[1];
      double force_by_d[2][2], force_by_theta[2];
      for (int r = 0; r < 2; ++r) {
        // By d (through w) -spin C J, by d' C; by theta (C turns) (J C - C J) w, by theta' -C J d.
        force_by_d[r][0] = wD * (-spin * C[r][1]) + cC * C[r][0];
        force_by_d[r][1] = wD * (spin * C[r][0]) + cC * C[r][1];
        force_by_theta[r] = wD * ((c_r - c_t) * (across[r] * along_w + radial[r] * across_w)) +
                            cC * -(C[r][0] * turned[0] + C[r][1] * turned[1]);
      }
      const double turned_damping[2] = {damping[1], -damping[0]};  // J^T f_d
      for (int c = 0; c < 2; ++c) {
        for (int r = 0; r < 2; ++r) by_d[r][c] += force_by_d[r][c];
        moment_by_d[c] += -(turned[0] * force_by_d[0][c] + turned[1] * force_by_d[1][c]) - wD * turned_damping[c];
      }
      for (int r = 0; r < 2; ++r) by_theta[r] += force_by_theta[r];
      spin_spin += -(turned[0] * force_by_theta[0] + turned[1] * force_by_theta[1]);
    }
    // Rows and columns 0, 1 (contact node) and 3, 4 (belt node) enter as d = u_c - u_b.
    for (int r = 0; r < 4; ++r) {
      const double row_sign = r < 2 ? 1.0 : -1.0;
      for (int c = 0; c < 4; ++c) {
        const double column_sign = c < 2 ? 1.0 : -1.0;
        const double mass = (r == c && r < 2) ? mass_diagonal : 0.0;
        tangent[(kTranslations[r] * kDofs + kTranslations[c]) * n + e] =
            row_sign * column_sign * by_d[r % 2][c % 2] + mass;
      }
      tangent[(kTranslations[r] * kDofs + 5) * n + e] = row_sign * by_theta[r % 2];
      tangent[(5 * kDofs + kTranslations[r]) * n + e] = row_sign * moment_by_d[r % 2];
    }
    tangent[(5 * kDofs + 5) * n + e] = spin_spin;
  }
}

void TreadLayer::Batch::evaluate(const BlockValues& values, const EvaluationContext& context, bool with_tangent) {
  const IntegratorFactors& f = context.factors;
  const bool damped = damped_ && (f.force_damping != 0.0 || (with_tangent && f.tangent_damping != 0.0));
  if (with_tangent)
    damped ? evaluate_layers<true, true>(values, f) : evaluate_layers<true, false>(values, f);
  else
    damped ? evaluate_layers<false, true>(values, f) : evaluate_layers<false, false>(values, f);
}

}  // namespace tirefe
