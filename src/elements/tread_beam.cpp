#include "elements/tread_beam.hpp"

#include <cmath>
#include <string>

#include "core/simd_clones.hpp"
#include "elements/sine_cosine.hpp"

namespace tirefe {

namespace {
void require_nonnegative(double value, const char* name) {
  if (!std::isfinite(value) || value < 0.0)
    throw ModelError(std::string("beam section: ") + name + " must be a non-negative finite number (got " +
                     std::to_string(value) + ")");
}
void require_positive(double value, const char* name) {
  if (!std::isfinite(value) || value <= 0.0)
    throw ModelError(std::string("beam section: ") + name + " must be positive (got " + std::to_string(value) + ")");
}
}  // namespace

void BeamSection::check() const {
  require_positive(axial_stiffness, "EA");
  require_positive(shear_stiffness, "GA");
  require_positive(bending_stiffness, "EI");
  require_nonnegative(mass_per_length, "rhoA");
  require_nonnegative(rotary_inertia_per_length, "rhoI");
  require_nonnegative(curvature_damping, "curvature damping");
}

TreadBeam::TreadBeam(const Eigen::Vector2d& start, const Eigen::Vector2d& end, const BeamSection& section)
    : section_(section) {
  section_.check();
  const Eigen::Vector2d chord = end - start;
  length_ = chord.norm();
  if (!(length_ > 0.0)) throw ModelError("beam element with coincident nodes (zero length)");
  reference_angle_ = std::atan2(chord.y(), chord.x());
  reference_direction_ = chord / length_;
}

TreadBeam::Strains TreadBeam::strains(const Vector& d) const {
  const Eigen::Vector2d stretch = reference_direction_ + (d.segment<2>(3) - d.segment<2>(0)) / length_;
  const double beta = reference_angle_ + 0.5 * (d[2] + d[5]);
  const double c = std::cos(beta), s = std::sin(beta);
  return {stretch.x() * c + stretch.y() * s - 1.0, -stretch.x() * s + stretch.y() * c, (d[5] - d[2]) / length_};
}

void TreadBeam::evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&, History&,
                         Vector& residual, Matrix* tangent) const {
  const Vector& d = local.displacement;
  const Eigen::Vector2d stretch = reference_direction_ + (d.segment<2>(3) - d.segment<2>(0)) / length_;  // x'
  const double beta = reference_angle_ + 0.5 * (d[2] + d[5]);
  const double cos_beta = std::cos(beta), sin_beta = std::sin(beta);
  const Eigen::Vector2d t(cos_beta, sin_beta), n(-sin_beta, cos_beta);
  const double axial = stretch.dot(t) - 1.0, shear = stretch.dot(n), curvature = (d[5] - d[2]) / length_;
  const double N = section_.axial_stiffness * axial, V = section_.shear_stiffness * shear,
               M = section_.bending_stiffness * curvature;

  // Strain gradients: x' depends on the translations (+-1/L0), beta on the rotations (1/2 each).
  const double h = 1.0 / length_;
  Vector d_axial, d_shear, d_curvature;
  d_axial << -h * t.x(), -h * t.y(), 0.5 * shear, h * t.x(), h * t.y(), 0.5 * shear;
  d_shear << -h * n.x(), -h * n.y(), -0.5 * (1.0 + axial), h * n.x(), h * n.y(), -0.5 * (1.0 + axial);
  d_curvature << 0.0, 0.0, -h, 0.0, 0.0, h;

  const IntegratorFactors& f = context.factors;
  residual = (f.force_stiffness * length_) * (N * d_axial + V * d_shear + M * d_curvature);
  const double damping_moment = section_.curvature_damping * (local.velocity[5] - local.velocity[2]) / length_;
  if (f.force_damping != 0.0) residual += (f.force_damping * length_ * damping_moment) * d_curvature;
  if (f.force_mass != 0.0) residual += f.force_mass * mass_times(local.acceleration);
  if (!tangent) return;

  Matrix& K = *tangent;
  const double scale = f.tangent_stiffness * length_;
  K.noalias() = (scale * section_.axial_stiffness * d_axial) * d_axial.transpose();
  K.noalias() += (scale * section_.shear_stiffness * d_shear) * d_shear.transpose();
  // Bending and curvature damping couple the two rotations alone (d_curvature = (-h, h) there).
  double bending = scale * section_.bending_stiffness * h * h;
  if (f.tangent_damping != 0.0) bending += f.tangent_damping * section_.curvature_damping * length_ * h * h;
  // Geometric stiffness: N d2(eps) + V d2(gam). Only translation-rotation and
  // rotation-rotation couplings are non-zero since x' is linear in u and beta in theta.
  // d2(eps) = Bx^T n b^T + b n^T Bx - (1+eps) b b^T,  d2(gam) = -Bx^T t b^T - b t^T Bx - gam b b^T.
  const Eigen::Vector2d coupling = (0.5 * h * scale) * (N * n - V * t);  // per unit of dx'/du sign
  const double rotation_rotation = 0.25 * scale * (-N * (1.0 + axial) - V * shear);
  const int translations[2] = {0, 3};
  const double signs[2] = {-1.0, 1.0};
  const int rotations[2] = {2, 5};
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c)
      for (int rot : rotations) {
        K(translations[a] + c, rot) += signs[a] * coupling[c];
        K(rot, translations[a] + c) += signs[a] * coupling[c];
      }
  for (int r1 : rotations)
    for (int r2 : rotations) K(r1, r2) += rotation_rotation + (r1 == r2 ? bending : -bending);
  if (f.tangent_mass != 0.0) add_mass(f.tangent_mass, K);
}

TreadBeam::Vector TreadBeam::mass_times(const Vector& x) const {
  // Consistent mass of linear shape functions: L0/6 [2 1; 1 2] per component.
  const double per_length[3] = {section_.mass_per_length, section_.mass_per_length, section_.rotary_inertia_per_length};
  Vector product;
  for (int c = 0; c < 3; ++c) {
    const double scale = per_length[c] * length_ / 6.0;
    product[c] = scale * (2.0 * x[c] + x[c + 3]);
    product[c + 3] = scale * (x[c] + 2.0 * x[c + 3]);
  }
  return product;
}

void TreadBeam::add_mass(double factor, Matrix& tangent) const {
  const double per_length[3] = {section_.mass_per_length, section_.mass_per_length, section_.rotary_inertia_per_length};
  for (int c = 0; c < 3; ++c) {
    const double scale = factor * per_length[c] * length_ / 6.0;
    tangent(c, c) += 2.0 * scale;
    tangent(c + 3, c + 3) += 2.0 * scale;
    tangent(c, c + 3) += scale;
    tangent(c + 3, c) += scale;
  }
}

ElementEnergy TreadBeam::energy(const LocalState<kDofs>& local, const History&) const {
  const Strains e = strains(local.displacement);
  ElementEnergy energy;
  energy.strain = 0.5 * length_ *
                  (section_.axial_stiffness * e.axial * e.axial + section_.shear_stiffness * e.shear * e.shear +
                   section_.bending_stiffness * e.curvature * e.curvature);
  energy.kinetic = 0.5 * local.velocity.dot(mass_times(local.velocity));
  return energy;
}

// The batch path. Its arithmetic is evaluate()'s, term for term, written per beam on
// arrays indexed by the beam, so that the loop over beams vectorises.
TreadBeam::Batch::Batch(const std::vector<TreadBeam>& beams) : count_(static_cast<int>(beams.size())) {
  for (auto* field : {&length_, &reference_angle_, &direction_x_, &direction_y_, &axial_, &shear_, &bending_, &mass_,
                      &rotary_inertia_, &curvature_damping_})
    field->assign(count_, 0.0);
  residual_.assign(static_cast<size_t>(kDofs) * count_, 0.0);
  tangent_.assign(static_cast<size_t>(kDofs) * kDofs * count_, 0.0);
  for (int e = 0; e < count_; ++e) {
    const TreadBeam& beam = beams[e];
    length_[e] = beam.length_;
    reference_angle_[e] = beam.reference_angle_;
    direction_x_[e] = beam.reference_direction_.x();
    direction_y_[e] = beam.reference_direction_.y();
    axial_[e] = beam.section_.axial_stiffness;
    shear_[e] = beam.section_.shear_stiffness;
    bending_[e] = beam.section_.bending_stiffness;
    mass_[e] = beam.section_.mass_per_length;
    rotary_inertia_[e] = beam.section_.rotary_inertia_per_length;
    curvature_damping_[e] = beam.section_.curvature_damping;
  }
}

TIREFE_SIMD_CLONES ElementEnergy TreadBeam::Batch::energy(const BlockValues& values) const {
  const int n = count_;
  const double* u = values.displacement;
  const double* v = values.velocity;
  return sum_energies(n, [&](int e) {
    const double length = length_[e];
    const double stretch_x = direction_x_[e] + (u[3 * n + e] - u[e]) / length;
    const double stretch_y = direction_y_[e] + (u[4 * n + e] - u[n + e]) / length;
    const SineCosine turn = sine_cosine(reference_angle_[e] + 0.5 * (u[2 * n + e] + u[5 * n + e]));
    const double axial = stretch_x * turn.cos + stretch_y * turn.sin - 1.0;
    const double shear = -stretch_x * turn.sin + stretch_y * turn.cos;
    const double curvature = (u[5 * n + e] - u[2 * n + e]) / length;
    ElementEnergy energy;
    energy.strain =
        0.5 * length * (axial_[e] * axial * axial + shear_[e] * shear * shear + bending_[e] * curvature * curvature);
    // v.M v with the consistent mass L0/6 [2 1; 1 2] per component (rho A, rho A, rho I).
    const double per_length[3] = {mass_[e], mass_[e], rotary_inertia_[e]};
    for (int c = 0; c < 3; ++c) {
      const double first = v[c * n + e], second = v[(c + 3) * n + e];
      energy.kinetic +=
          0.5 * (per_length[c] * length / 6.0) * (first * (2.0 * first + second) + second * (first + 2.0 * second));
    }
    return energy;
  });
}

template <bool Tangent>
TIREFE_SIMD_CLONES void TreadBeam::Batch::evaluate_beams(const BlockValues& values, const IntegratorFactors& f) {
  const int n = count_;
  const double* u = values.displacement;
  const double* v = values.velocity;
  const double* a = values.acceleration;
  double* residual = residual_.data();
  double* tangent = tangent_.data();
#pragma omp simd
  for (int e = 0; e < n; ++e) {
    const double length = length_[e], h = 1.0 / length;
    const double stretch_x = direction_x_[e] + (u[3 * n + e] - u[e]) / length;  // x'
    const double stretch_y = direction_y_[e] + (u[4 * n + e] - u[n + e]) / length;
    const SineCosine turn = sine_cosine(reference_angle_[e] + 0.5 * (u[2 * n + e] + u[5 * n + e]));  // beta
    const double t[2] = {turn.cos, turn.sin}, normal[2] = {-turn.sin, turn.cos};
    const double axial = stretch_x * t[0] + stretch_y * t[1] - 1.0;
    const double shear = stretch_x * normal[0] + stretch_y * normal[1];
    const double curvature = (u[5 * n + e] - u[2 * n + e]) / length;
    const double N = axial_[e] * axial, V = shear_[e] * shear, M = bending_[e] * curvature;
    const double d_axial[6] = {-h * t[0], -h * t[1], 0.5 * shear, h * t[0], h * t[1], 0.5 * shear};
    const double d_shear[6] = {-h * normal[0], -h * normal[1], -0.5 * (1.0 + axial),
                               h * normal[0],  h * normal[1],  -0.5 * (1.0 + axial)};
    const double d_curvature[6] = {0.0, 0.0, -h, 0.0, 0.0, h};
    const double damping_moment = curvature_damping_[e] * (v[5 * n + e] - v[2 * n + e]) / length;
    // Consistent mass L0/6 [2 1; 1 2] per component (rho A, rho A, rho I).
    const double per_length[3] = {mass_[e], mass_[e], rotary_inertia_[e]};
    for (int k = 0; k < kDofs; ++k) {
      const int c = k % 3, other = k < 3 ? k + 3 : k - 3;
      const double inertia = per_length[c] * length / 6.0 * (2.0 * a[k * n + e] + a[other * n + e]);
      residual[k * n + e] = (f.force_stiffness * length) * (N * d_axial[k] + V * d_shear[k] + M * d_curvature[k]) +
                            (f.force_damping * length * damping_moment) * d_curvature[k] + f.force_mass * inertia;
    }
    if (!Tangent) continue;

    const double scale = f.tangent_stiffness * length;
    double K[kDofs][kDofs];
    for (int r = 0; r < kDofs; ++r)
      for (int c = 0; c < kDofs; ++c)
        K[r][c] = (scale * axial_[e] * d_axial[r]) * d_axial[c] + (scale * shear_[e] * d_shear[r]) * d_shear[c];
    const double bending = scale * bending_[e] * h * h + f.tangent_damping * curvature_damping_[e] * length * h * h;
    // The geometric terms N d2(eps) + V d2(gam) couple translations and rotations.
    const double coupling[2] = {(0.5 * h * scale) * (N * normal[0] - V * t[0]),
                                (0.5 * h * scale) * (N * normal[1] - V * t[1])};
    const double rotation_rotation = 0.25 * scale * (-N * (1.0 + axial) - V * shear);
    for (int c = 0; c < 2; ++c)
      for (int rot = 2; rot < kDofs; rot += 3) {
        K[c][rot] -= coupling[c];
        K[rot][c] -= coupling[c];
        K[3 + c][rot] += coupling[c];
        K[rot][3 + c] += coupling[c];
      }
    K[2][2] += rotation_rotation + bending;
    K[5][5] += rotation_rotation + bending;
    K[2][5] += rotation_rotation - bending;
    K[5][2] += rotation_rotation - bending;
    for (int c = 0; c < 3; ++c) {
      const double mass = f.tangent_mass * per_length[c] * length / 6.0;
      K[c][c] += 2.0 * mass;
      K[c + 3][c + 3] += 2.0 * mass;
      K[c][c + 3] += mass;
      K[c + 3][c] += mass;
    }
    for (int r = 0; r < kDofs; ++r)
      for (int c = 0; c < kDofs; ++c) tangent[(r * kDofs + c) * n + e] = K[r][c];
  }
}

void TreadBeam::Batch::evaluate(const BlockValues& values, const EvaluationContext& context, bool with_tangent) {
  with_tangent ? evaluate_beams<true>(values, context.factors) : evaluate_beams<false>(values, context.factors);
}

}  // namespace tirefe
