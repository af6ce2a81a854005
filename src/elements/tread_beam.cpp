#include "elements/tread_beam.hpp"

#include <cmath>
#include <string>

#include "core/batch_of_one.hpp"
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
/// The strains of one beam (tread_beam.hpp) from its local displacements u[k * stride],
/// with the direction t and normal n of beta: written once for every path.
struct BeamStrains {
  SineCosine beta;  // t = (cos, sin), n = (-sin, cos)
  double axial, shear, curvature;
};
inline BeamStrains beam_strains(double length, double direction_x, double direction_y, double reference_angle,
                                const double* u, int stride) {
  const double stretch_x = direction_x + (u[3 * stride] - u[0]) / length;  // x'
  const double stretch_y = direction_y + (u[4 * stride] - u[stride]) / length;
  const SineCosine turn = sine_cosine(reference_angle + 0.5 * (u[2 * stride] + u[5 * stride]));  // beta
  BeamStrains strains;
  strains.beta = turn;
  strains.axial = stretch_x * turn.cos + stretch_y * turn.sin - 1.0;
  strains.shear = -stretch_x * turn.sin + stretch_y * turn.cos;
  strains.curvature = (u[5 * stride] - u[2 * stride]) / length;
  return strains;
}

/// Row k of the consistent mass of linear shape functions, L0/6 [2 1; 1 2] per component
/// ('scale' = its per-length inertia times L0/6), times x[k * stride].
inline double consistent_mass_times(double scale, const double* x, int k, int stride) {
  const int other = k < 3 ? k + 3 : k - 3;
  return scale * (2.0 * x[k * stride] + x[other * stride]);
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
  const BeamStrains strains =
      beam_strains(length_, reference_direction_.x(), reference_direction_.y(), reference_angle_, d.data(), 1);
  return {strains.axial, strains.shear, strains.curvature};
}

void TreadBeam::evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&, History&,
                         Vector& residual, Matrix* tangent) const {
  evaluate_as_batch(*this, local, context, residual, tangent);
}

TreadBeam::Vector TreadBeam::mass_times(const Vector& x) const {
  const double per_length[3] = {section_.mass_per_length, section_.mass_per_length, section_.rotary_inertia_per_length};
  Vector product;
  for (int k = 0; k < kDofs; ++k) product[k] = consistent_mass_times(per_length[k % 3] * length_ / 6.0, x.data(), k, 1);
  return product;
}

ElementEnergy TreadBeam::energy(const LocalState<kDofs>& local, const History&) const {
  return batch_energy_of_one(*this, local);
}

// The batch path: the beam's physics, written once per beam on arrays indexed by the
// beam, so that the loop over beams vectorises; evaluate() and energy() are its block of one.
TreadBeam::Batch::Batch(const std::vector<TreadBeam>& beams) { assign(beams); }

void TreadBeam::Batch::assign(const std::vector<TreadBeam>& beams) {
  count_ = static_cast<int>(beams.size());
  for (auto* field : {&length_, &reference_angle_, &direction_x_, &direction_y_, &axial_, &shear_, &bending_, &mass_,
                      &rotary_inertia_, &curvature_damping_})
    field->resize(count_);
  // The entries the passes never write (idle DOFs') stay zero: cleared for a new layout alone,
  // so that a batch given other elements of the same number allocates and clears nothing.
  if (residual_.size() != static_cast<size_t>(kDofs) * count_) {
    residual_.assign(static_cast<size_t>(kDofs) * count_, 0.0);
    tangent_.assign(static_cast<size_t>(kDofs) * kDofs * count_, 0.0);
  }
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
    const BeamStrains s = beam_strains(length, direction_x_[e], direction_y_[e], reference_angle_[e], u + e, n);
    ElementEnergy energy;
    energy.strain =
        0.5 * length *
        (axial_[e] * s.axial * s.axial + shear_[e] * s.shear * s.shear + bending_[e] * s.curvature * s.curvature);
    // v.M v with the consistent mass (rho A, rho A, rho I).
    const double per_length[3] = {mass_[e], mass_[e], rotary_inertia_[e]};
    for (int k = 0; k < kDofs; ++k)
      energy.kinetic += 0.5 * v[k * n + e] * consistent_mass_times(per_length[k % 3] * length / 6.0, v + e, k, n);
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
    const BeamStrains s = beam_strains(length, direction_x_[e], direction_y_[e], reference_angle_[e], u + e, n);
    const double t[2] = {s.beta.cos, s.beta.sin}, normal[2] = {-s.beta.sin, s.beta.cos};
    const double axial = s.axial, shear = s.shear, curvature = s.curvature;
    const double N = axial_[e] * axial, V = shear_[e] * shear, M = bending_[e] * curvature;
    // Strain gradients: x' depends on the translations (+-1/L0), beta on the rotations (1/2 each).
    const double d_axial[6] = {-h * t[0], -h * t[1], 0.5 * shear, h * t[0], h * t[1], 0.5 * shear};
    const double d_shear[6] = {-h * normal[0], -h * normal[1], -0.5 * (1.0 + axial),
                               h * normal[0],  h * normal[1],  -0.5 * (1.0 + axial)};
    const double d_curvature[6] = {0.0, 0.0, -h, 0.0, 0.0, h};
    const double damping_moment = curvature_damping_[e] * (v[5 * n + e] - v[2 * n + e]) / length;
    // Consistent mass L0/6 [2 1; 1 2] per component (rho A, rho A, rho I).
    const double per_length[3] = {mass_[e], mass_[e], rotary_inertia_[e]};
    for (int k = 0; k < kDofs; ++k) {
      const double inertia = consistent_mass_times(per_length[k % 3] * length / 6.0, a + e, k, n);
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
    // Geometric stiffness N d2(eps) + V d2(gam): x' is linear in u and beta in theta, so only
    // translation-rotation and rotation-rotation couplings are non-zero;
    // d2(eps) = Bx^T n b^T + b n^T Bx - (1+eps) b b^T,  d2(gam) = -Bx^T t b^T - b t^T Bx - gam b b^T.
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
