#include "solvers/modal.hpp"

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <utility>

#include "core/assembler.hpp"
#include "solvers/analysis.hpp"

namespace tirefe {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;
// The modal analyses work on dense matrices, and the undamped one decomposes them whole:
// its time grows with the cube of the equations (1000: 1 s, 2000: 14 s, 3000: 53 s on the
// 2-core machine; 10 000 would take half an hour and 2.4 GB), far beyond any tire (a
// 100-element tire has a few hundred).
constexpr int kMaxModalEquations = 2000;
using Complex = std::complex<double>;

/// One query at a state with the given factors: the residual of every DOF (the tangent,
/// if asked for, stays in the assembler); the history stays as committed.
Eigen::VectorXd assembled_forces(Assembler& assembler, const State& state, const IntegratorFactors& factors,
                                 bool with_tangent) {
  EvaluationContext context;
  context.time = state.time;
  context.factors = factors;
  context.want_tangent = with_tangent;
  Eigen::VectorXd residual;
  assembler.query(context, state, residual);
  return residual;
}

/// Assembles the free-equation tangent for one set of tangent factors, densely.
Eigen::MatrixXd dense_tangent(Assembler& assembler, const State& state, const IntegratorFactors& factors) {
  assembled_forces(assembler, state, factors, true);
  // The assembler keeps one sparse matrix: copy it out before the next pass.
  return Eigen::MatrixXd(assembler.tangent());
}

/// K, C and M over the free equations at a state (padded to the model's DOFs), and M = L L^T.
struct Linearisation {
  State state;
  Eigen::MatrixXd stiffness, damping, mass;
  Eigen::LLT<Eigen::MatrixXd> mass_factor;

  Linearisation(Model& model, Assembler& assembler, const State& at, int mode_count, bool with_damping) : state(at) {
    if (mode_count < 1)
      throw ModelError("modal analysis: ask for at least one mode (got " + std::to_string(mode_count) + ")");
    assembler.update_pattern();
    if (model.dof_map().equation_count() > kMaxModalEquations)
      throw ModelError("modal analysis: the model has " + std::to_string(model.dof_map().equation_count()) +
                       " free equations, more than the " + std::to_string(kMaxModalEquations) +
                       " a dense modal analysis solves in seconds");
    const int dof_count = model.dof_map().dof_count();
    for (Eigen::VectorXd* field : {&state.displacement, &state.velocity, &state.acceleration}) {
      const Eigen::Index old_size = std::min<Eigen::Index>(field->size(), dof_count);
      field->conservativeResize(dof_count);
      field->tail(dof_count - old_size).setZero();
    }
    stiffness = dense_tangent(assembler, state, IntegratorFactors::stiffness_matrix());
    mass = dense_tangent(assembler, state, IntegratorFactors::mass_matrix());
    const int equations = model.dof_map().equation_count();
    damping = with_damping ? dense_tangent(assembler, state, IntegratorFactors::damping_matrix())
                           : Eigen::MatrixXd::Zero(equations, equations);
    mass = 0.5 * (mass + mass.transpose());
    mass_factor.compute(mass);
    if (mass_factor.info() != Eigen::Success)
      throw ModelError(
          "modal analysis: the mass matrix is not positive definite; every free DOF needs mass "
          "(give beams a rotary inertia rhoI > 0 and point masses a rotary inertia J > 0)");
  }
  /// L^-1 A L^-T.
  Eigen::MatrixXd whitened(const Eigen::MatrixXd& matrix) const {
    const auto lower = mass_factor.matrixL();
    const Eigen::MatrixXd left = lower.solve(matrix);
    return lower.solve(left.transpose()).transpose();
  }
};

/// The header's rigid-body test: |phi^H K phi| <= tolerance |phi|^T |K| |phi|, phi = a + i b.
bool barely_resisted(const Eigen::MatrixXd& stiffness, const Eigen::MatrixXd& magnitude, const Eigen::VectorXd& a,
                     const Eigen::VectorXd& b, double tolerance) {
  const Eigen::VectorXd Ka = stiffness * a, Kb = stiffness * b;
  const double energy = std::abs(Complex(a.dot(Ka) + b.dot(Kb), a.dot(Kb) - b.dot(Ka)));
  const Eigen::VectorXd size = (a.array().square() + b.array().square()).sqrt().matrix();
  return energy <= tolerance * size.dot(magnitude * size);
}

/// Per node, (u_x, u_y, theta_z) -> J (u_x, u_y) = (-u_y, u_x), 0 on theta_z.
Eigen::VectorXd quarter_turn(const Eigen::VectorXd& field) {
  Eigen::VectorXd turned = Eigen::VectorXd::Zero(field.size());
  for (Eigen::Index first = 0; first < field.size(); first += kDofsPerNode) {
    turned[first + kUx] = -field[first + kUy];
    turned[first + kUy] = field[first + kUx];
  }
  return turned;
}

/// Products of K, C and M with a direction over all DOFs, at every DOF (the prescribed
/// rows give the support reactions; the tangent covers only the free equations): K d by
/// a central difference of the residual along d, C d and M d from the residual itself,
/// linear in v and a by the element contract. Queries: the history stays as committed.
class ForceProbe {
 public:
  ForceProbe(Assembler& assembler, const State& state) : assembler_(assembler), state_(state) {}

  Eigen::VectorXd stiffness(const Eigen::VectorXd& direction) {
    const double size = direction.lpNorm<Eigen::Infinity>();
    if (size == 0.0) return Eigen::VectorXd::Zero(direction.size());
    const double step = 1e-7 / size;
    State shifted = state_;
    shifted.displacement = state_.displacement + step * direction;
    const Eigen::VectorXd plus = forces(shifted, IntegratorFactors::stiffness_force());
    shifted.displacement = state_.displacement - step * direction;
    return (plus - forces(shifted, IntegratorFactors::stiffness_force())) / (2.0 * step);
  }
  Eigen::VectorXd damping(const Eigen::VectorXd& direction) {
    State probe = state_;
    probe.velocity = direction;
    return forces(probe, IntegratorFactors::damping_force());
  }
  Eigen::VectorXd mass(const Eigen::VectorXd& direction) {
    State probe = state_;
    probe.acceleration = direction;
    return forces(probe, IntegratorFactors::inertia_force());
  }
  /// M_t d: the mass on the in-plane translations (theta_z entries of d and of M d dropped).
  Eigen::VectorXd translational_mass(const Eigen::VectorXd& direction) {
    Eigen::VectorXd product = mass(translations(direction));
    return translations(product);
  }

 private:
  static Eigen::VectorXd translations(Eigen::VectorXd field) {
    for (Eigen::Index first = 0; first < field.size(); first += kDofsPerNode) field[first + kRz] = 0.0;
    return field;
  }
  Eigen::VectorXd forces(const State& state, const IntegratorFactors& weights) {
    return assembled_forces(assembler_, state, weights, false);
  }

  Assembler& assembler_;
  const State& state_;
};

/// Keeps the prescribed rows of 'forces', zero elsewhere.
template <class Vector>
Vector prescribed_rows(const DofMap& dofs, Vector forces) {
  for (int dof = 0; dof < dofs.dof_count(); ++dof)
    if (!dofs.is_prescribed(dof)) forces[dof] = 0.0;
  return forces;
}

/// A free-equation vector spread over all DOFs (0 at prescribed ones).
template <class Vector>
Vector on_all_dofs(const DofMap& dofs, const Vector& free) {
  Vector all = Vector::Zero(dofs.dof_count());
  for (int equation = 0; equation < dofs.equation_count(); ++equation) all[dofs.dof(equation)] = free[equation];
  return all;
}

/// J over the free equations (header); every node must hold both translations or neither.
Eigen::SparseMatrix<double> quarter_turn_matrix(const Model& model) {
  const DofMap& dofs = model.dof_map();
  std::vector<Eigen::Triplet<double>> entries;
  for (int node = 0; node < model.mesh().node_count(); ++node) {
    const int x = dofs.equation(dof_index(node, kUx)), y = dofs.equation(dof_index(node, kUy));
    if ((x < 0) != (y < 0))
      throw ModelError("modal analysis: a spin rate turns both in-plane translations of a node together, but node " +
                       std::to_string(node + 1) + " has " + (x < 0 ? "u_x" : "u_y") + " held and " +
                       (x < 0 ? "u_y" : "u_x") + " free; hold both or neither");
    if (x < 0) continue;
    entries.emplace_back(x, y, -1.0);
    entries.emplace_back(y, x, 1.0);
  }
  Eigen::SparseMatrix<double> turn(dofs.equation_count(), dofs.equation_count());
  turn.setFromTriplets(entries.begin(), entries.end());
  return turn;
}

/// M_t: the mass with the rows and columns of rotational equations dropped.
Eigen::MatrixXd translational_mass(const Model& model, const Eigen::MatrixXd& mass) {
  const DofMap& dofs = model.dof_map();
  Eigen::MatrixXd result = mass;
  for (int equation = 0; equation < dofs.equation_count(); ++equation)
    if (dofs.dof(equation) % kDofsPerNode == kRz) {
      result.row(equation).setZero();
      result.col(equation).setZero();
    }
  return result;
}

/// An unsymmetric solver returns the two shapes of a degenerate pair in any combination,
/// generally not M-orthogonal, and a complex pair as the real and imaginary parts of its
/// eigenvector: modes whose omega^2 agree to 1e-6 relative span one invariant subspace and
/// become an M-orthonormal basis of it (Gram-Schmidt in ascending order).
void orthonormalise_clusters(const Eigen::VectorXd& eigenvalues, const std::vector<int>& order,
                             const Eigen::MatrixXd& mass, Eigen::MatrixXd& vectors) {
  size_t first = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    const double lead = eigenvalues[order[first]];
    if (std::abs(eigenvalues[order[i]] - lead) > 1e-6 * std::abs(lead)) first = i;
    auto shape = vectors.col(order[i]);
    for (size_t j = first; j < i; ++j) {
      const auto earlier = vectors.col(order[j]);
      shape -= earlier.dot(mass * shape) * earlier;
    }
    shape /= std::sqrt(shape.dot(mass * shape));
  }
}

/// Multiplies a shape by the phase that makes its largest entry real and positive.
void fix_phase(Eigen::VectorXcd& shape) {
  Eigen::Index largest = 0;
  shape.cwiseAbs().maxCoeff(&largest);
  if (std::abs(shape[largest]) > 0.0) shape *= std::conj(shape[largest]) / std::abs(shape[largest]);
}

/// (K + lambda (C + G) + lambda^2 M - Omega^2 J^T M_t J) phi over all DOFs, the real and
/// imaginary parts of phi apart: G phi = Omega (M_t J phi + J M_t phi), -J^T M_t J = J M_t J.
Eigen::VectorXcd support_reaction(ForceProbe& probe, const Eigen::VectorXcd& shape, Complex root, double spin,
                                  bool with_damping) {
  Eigen::VectorXcd force = Eigen::VectorXcd::Zero(shape.size());
  for (const bool real : {true, false}) {
    const Eigen::VectorXd part = real ? Eigen::VectorXd(shape.real()) : Eigen::VectorXd(shape.imag());
    const Complex unit = real ? Complex(1.0, 0.0) : Complex(0.0, 1.0);
    Eigen::VectorXd stiff = probe.stiffness(part), inertia = probe.mass(part);
    Eigen::VectorXd damp = with_damping ? probe.damping(part) : Eigen::VectorXd::Zero(part.size());
    if (spin != 0.0) {
      const Eigen::VectorXd mass_turned = probe.translational_mass(quarter_turn(part));
      damp += spin * (mass_turned + quarter_turn(probe.translational_mass(part)));
      stiff += (spin * spin) * quarter_turn(mass_turned);
    }
    force += unit * (stiff.cast<Complex>() + root * damp.cast<Complex>() + root * root * inertia.cast<Complex>());
  }
  return force;
}

/// A root lambda of (lambda^2 M + lambda C + K) phi = 0 and its shape over the free
/// equations, phi^H M phi = 1.
struct Root {
  Complex value;
  Eigen::VectorXcd shape;
};

/// Up to this size of the first-order form the dense solver runs by default.
constexpr int kDenseLimit = 400;

/// Every root with Im lambda >= 0, from the dense first-order form in y = L^T phi (header).
std::vector<Root> dense_roots(const Linearisation& linear, const Eigen::MatrixXd& stiffness,
                              const Eigen::MatrixXd& damping) {
  const Eigen::Index n = stiffness.rows();
  const Eigen::MatrixXd reduced_stiffness = linear.whitened(stiffness);
  const double largest_row = reduced_stiffness.cwiseAbs().rowwise().sum().maxCoeff();
  const double gamma = largest_row > 0.0 ? std::sqrt(largest_row) : 1.0;
  Eigen::MatrixXd first_order = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  first_order.topRightCorner(n, n).diagonal().setConstant(gamma);
  first_order.bottomLeftCorner(n, n) = -reduced_stiffness / gamma;
  first_order.bottomRightCorner(n, n) = -linear.whitened(damping);
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(first_order);

  const auto upper = linear.mass_factor.matrixU();
  std::vector<Root> roots;
  for (Eigen::Index j = 0; j < 2 * n; ++j) {
    if (solver.eigenvalues()[j].imag() < 0.0) continue;
    const Eigen::VectorXcd y = solver.eigenvectors().col(j).head(n).normalized();  // phi^H M phi = y^H y
    Eigen::VectorXcd shape(n);
    shape.real() = upper.solve(y.real());
    shape.imag() = upper.solve(y.imag());
    roots.push_back({solver.eigenvalues()[j], shape});
  }
  return roots;
}

/// The 'wanted' roots of lowest |lambda| by shift-invert block Krylov at 0 (header), or none
/// when they do not converge (a singular K among other reasons).
std::vector<Root> shift_invert_roots(const Eigen::MatrixXd& stiffness, const Eigen::MatrixXd& damping,
                                     const Linearisation& linear, int wanted) {
  const Eigen::MatrixXd& mass = linear.mass;
  const Eigen::Index n = stiffness.rows(), size_limit = std::min<Eigen::Index>(2 * n, 20 * wanted + 100);
  const Eigen::PartialPivLU<Eigen::MatrixXd> factor(stiffness);
  // Any positive definite R^T R serves as the inner product; the symmetric part of K, made
  // definite by the least multiple of M needed, keeps S nearly normal.
  const Eigen::MatrixXd symmetric = 0.5 * (stiffness + stiffness.transpose());
  const double shift_scale = std::abs(symmetric.trace() / mass.trace());
  Eigen::LLT<Eigen::MatrixXd> energy;
  for (const double shift : {0.0, 1e-6, 1e-4, 1e-2, 1.0}) {
    energy.compute(symmetric + shift * shift_scale * mass);
    if (energy.info() == Eigen::Success) break;
  }
  if (energy.info() != Eigen::Success) return {};
  const auto stiffness_root = energy.matrixU();         // K_s + s M = R^T R
  const auto mass_root = linear.mass_factor.matrixU();  // M = L L^T, L^T
  // In energy coordinates q = [R phi; L^T v], S q = T [-K^-1 (M v + C phi); phi], T = diag(R, L^T).
  const auto apply = [&](const Eigen::VectorXd& q) {
    const Eigen::VectorXd phi = stiffness_root.solve(q.head(n)), velocity = mass_root.solve(q.tail(n));
    Eigen::VectorXd image(2 * n);
    image.head(n) = stiffness_root * Eigen::VectorXd(-factor.solve(mass * velocity + damping * phi));
    image.tail(n) = mass_root * phi;
    return image;
  };
  const auto norm_1 = [](const Eigen::MatrixXd& matrix) { return matrix.cwiseAbs().colwise().sum().maxCoeff(); };
  const double scale_k = norm_1(stiffness), scale_c = norm_1(damping), scale_m = norm_1(mass);

  // Basis v_0..v_3 random, then v_j = S v_(j-4) orthogonalised against every earlier one
  // (twice): the block Krylov space of block size 4, which holds up to 4 copies of a
  // multiple root.
  constexpr int kBlock = 4;
  std::mt19937 random(20240601);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd basis(2 * n, size_limit), images(2 * n, size_limit);
  Eigen::Index size = 0, imaged = 0;
  const auto add = [&](Eigen::VectorXd candidate) {
    const double original = candidate.norm();
    for (int pass = 0; pass < 2; ++pass)
      candidate -= basis.leftCols(size) * (basis.leftCols(size).transpose() * candidate);
    const double length = candidate.norm();
    if (!(length > 1e-13 * original)) return false;  // in the span already (or not finite)
    basis.col(size++) = candidate / length;
    return true;
  };
  const auto random_vector = [&]() {
    return Eigen::VectorXd(Eigen::VectorXd::NullaryExpr(2 * n, [&]() { return normal(random); }));
  };
  while (size < std::min<Eigen::Index>(kBlock, size_limit)) add(random_vector());
  const auto image_up_to = [&](Eigen::Index last) {
    for (; imaged <= last; ++imaged) images.col(imaged) = apply(basis.col(imaged));
  };

  Eigen::Index target = std::min<Eigen::Index>(size_limit, 4 * wanted + 40);
  while (true) {
    while (size < target) {
      const Eigen::Index source = size - kBlock;
      image_up_to(source);
      if (!images.col(source).allFinite()) return {};
      if (!add(images.col(source)) && !add(random_vector())) return {};
    }
    image_up_to(size - 1);
    // Rayleigh-Ritz: theta = 1 / lambda.
    const Eigen::MatrixXd projected = basis.leftCols(size).transpose() * images.leftCols(size);
    const Eigen::EigenSolver<Eigen::MatrixXd> ritz(projected);
    std::vector<Root> roots;
    std::vector<double> errors;
    for (Eigen::Index j = 0; j < size; ++j) {
      const Complex theta = ritz.eigenvalues()[j];
      if (theta.imag() > 0.0 || std::abs(theta) == 0.0) continue;  // Im lambda >= 0 only
      const Complex lambda = 1.0 / theta;
      const Eigen::VectorXcd top = (basis.leftCols(size) * ritz.eigenvectors().col(j)).head(n);
      Eigen::VectorXcd shape(n);
      shape.real() = stiffness_root.solve(top.real());
      shape.imag() = stiffness_root.solve(top.imag());
      const Eigen::VectorXd a = shape.real(), b = shape.imag();
      shape /= std::sqrt(a.dot(mass * a) + b.dot(mass * b));
      // Backward error of the pair: |P(lambda) phi| / ((|K| + |lambda| |C| + |lambda|^2 |M|) |phi|).
      const auto times = [&](const Eigen::MatrixXd& matrix) {
        return Eigen::VectorXcd(matrix * shape.real() + Complex(0.0, 1.0) * (matrix * shape.imag()));
      };
      const Eigen::VectorXcd residual = times(stiffness) + lambda * times(damping) + lambda * lambda * times(mass);
      errors.push_back(residual.norm() /
                       ((scale_k + std::abs(lambda) * scale_c + std::norm(lambda) * scale_m) * shape.norm()));
      roots.push_back({lambda, shape});
    }
    std::vector<size_t> order(roots.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return std::abs(roots[a].value) < std::abs(roots[b].value); });
    // The wanted roots and two beyond them converged: none of lower |lambda| is missing.
    const size_t checked = std::min(order.size(), static_cast<size_t>(wanted) + 2);
    bool converged = size == 2 * n || checked == static_cast<size_t>(wanted) + 2;
    for (size_t k = 0; k < checked && converged; ++k) converged = errors[order[k]] <= 1e-10;
    if (converged) {
      std::vector<Root> lowest;
      for (size_t k = 0; k < std::min(order.size(), static_cast<size_t>(wanted)); ++k)
        lowest.push_back(roots[order[k]]);
      return lowest;
    }
    if (size >= size_limit) return {};
    target = std::min<Eigen::Index>(size_limit, size + 2 * wanted + 20);
  }
}

}  // namespace

ModalResult modal_analysis(Model& model, const State& state, int mode_count, const ModalSettings& settings) {
  Assembler assembler(model);  // its own pattern, so an Analysis' solver is never left out of date
  const Linearisation linear(model, assembler, state, mode_count, false);
  const DofMap& dofs = model.dof_map();
  const int equations = dofs.equation_count();
  const Eigen::MatrixXd& stiffness = linear.stiffness;
  const Eigen::MatrixXd& mass = linear.mass;

  ModalResult result;
  const int count = std::min(mode_count, equations);
  result.shapes.setZero(dofs.dof_count(), count);
  result.reactions.setZero(dofs.dof_count(), count);
  if (count == 0) return result;

  const double largest_entry = stiffness.cwiseAbs().maxCoeff();
  result.symmetric =
      (stiffness - stiffness.transpose()).cwiseAbs().maxCoeff() <= settings.symmetry_tolerance * largest_entry;
  Eigen::VectorXd eigenvalues(equations);
  Eigen::MatrixXd vectors(equations, equations);
  if (result.symmetric) {
    // L^-1 K L^-T y = omega^2 y with phi = L^-T y: mass-orthonormal shapes. This is what
    // Eigen's GeneralizedSelfAdjointEigenSolver does, but it ignores a failed Cholesky.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(
        linear.whitened(0.5 * (stiffness + stiffness.transpose())));
    vectors = linear.mass_factor.matrixU().solve(solver.eigenvectors());
    // The Rayleigh quotients phi^T K phi / phi^T M phi: quadratic in the shapes' error, where
    // the solver's eigenvalues are good to round-off of the largest one only.
    eigenvalues = (vectors.array() * (stiffness * vectors).array()).colwise().sum().transpose() /
                  (vectors.array() * (mass * vectors).array()).colwise().sum().transpose();
  } else {
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(linear.mass_factor.solve(stiffness));
    for (int j = 0; j < equations; ++j) {
      // A complex pair (Eigen puts Im > 0 first) gives the real plane of Re v and Im v at mu.
      const Complex value = solver.eigenvalues()[j];
      const Eigen::VectorXcd vector = solver.eigenvectors().col(value.imag() < 0.0 ? j - 1 : j);
      if (value.imag() < 0.0)
        vectors.col(j) = vector.imag();
      else
        vectors.col(j) = vector.real();
      eigenvalues[j] = value.real();
    }
  }

  std::vector<int> order(equations);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return eigenvalues[a] < eigenvalues[b]; });
  if (!result.symmetric) orthonormalise_clusters(eigenvalues, order, mass, vectors);

  const Eigen::MatrixXd magnitude = stiffness.cwiseAbs();
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(equations);
  for (int i = 0; i < count; ++i) {
    Eigen::VectorXd shape = vectors.col(order[i]);
    Eigen::Index largest = 0;
    shape.cwiseAbs().maxCoeff(&largest);
    if (shape[largest] < 0.0) shape = -shape;
    const double omega_squared = eigenvalues[order[i]];
    const bool rigid = barely_resisted(stiffness, magnitude, shape, none, settings.rigid_body_tolerance);
    result.eigenvalues.push_back(omega_squared);
    result.rigid_body.push_back(rigid);
    const double signed_omega = std::copysign(std::sqrt(std::abs(omega_squared)), omega_squared);
    result.frequencies_hz.push_back(rigid ? 0.0 : signed_omega / kTwoPi);
    result.shapes.col(i) = on_all_dofs(dofs, shape);
  }
  ForceProbe probe(assembler, linear.state);
  for (int i = 0; i < count; ++i)
    result.reactions.col(i) = prescribed_rows(dofs, probe.stiffness(result.shapes.col(i)));
  return result;
}

ModalResult modal_analysis(Analysis& analysis, int mode_count, const ModalSettings& settings) {
  return modal_analysis(analysis.model(), analysis.state(), mode_count, settings);
}

DampedModalResult damped_modal_analysis(Model& model, const State& state, int mode_count,
                                        const DampedModalSettings& settings) {
  Assembler assembler(model);
  const Linearisation linear(model, assembler, state, mode_count, settings.damping);
  const DofMap& dofs = model.dof_map();
  const int n = dofs.equation_count();
  const double spin = settings.spin_rate;

  // The turning frame's terms (header): G into the damping, the softening into K.
  Eigen::MatrixXd stiffness = linear.stiffness, damping = linear.damping;
  if (spin != 0.0) {
    const Eigen::SparseMatrix<double> turn = quarter_turn_matrix(model);
    const Eigen::MatrixXd inertia = translational_mass(model, linear.mass);
    const Eigen::MatrixXd inertia_turned = inertia * turn;  // M_t J
    damping += spin * (inertia_turned + turn * inertia);
    stiffness -= (spin * spin) * (Eigen::SparseMatrix<double>(turn.transpose()) * inertia_turned);
  }

  DampedModalResult result;
  result.spin_rate = spin;
  if (n == 0) return result;

  // Rigid-body modes: motions that the structure's K or the turning frame's stiffness
  // barely resists (the same test at rest; turning, the free translations, which turn at
  // Omega in this frame, and the free rotation, whose load stiffness the pre-stress
  // balances).
  const Eigen::MatrixXd magnitude = stiffness.cwiseAbs(), structure_magnitude = linear.stiffness.cwiseAbs();
  const auto rigid = [&](const Eigen::VectorXcd& shape) {
    const double tolerance = settings.rigid_body_tolerance;
    const Eigen::VectorXd a = shape.real(), b = shape.imag();
    return barely_resisted(stiffness, magnitude, a, b, tolerance) ||
           barely_resisted(linear.stiffness, structure_magnitude, a, b, tolerance);
  };
  std::vector<Root> roots;
  const bool try_krylov = settings.solver == DampedSolver::ShiftInvert ||
                          (settings.solver == DampedSolver::Automatic && 2 * n > kDenseLimit);
  if (try_krylov) {
    roots = shift_invert_roots(stiffness, damping, linear, mode_count);
    // A singular K (a rigid-body mode) is the dense solver's business.
    if (std::any_of(roots.begin(), roots.end(), [&](const Root& root) { return rigid(root.shape); })) roots.clear();
  }
  result.shift_invert = !roots.empty();
  if (roots.empty()) roots = dense_roots(linear, stiffness, damping);
  std::sort(roots.begin(), roots.end(),
            [](const Root& a, const Root& b) { return std::abs(a.value) < std::abs(b.value); });

  // The real and imaginary parts of rigid-body shapes that add to the span of the earlier
  // ones, M-orthonormalised, are reported once each: a double root split by round-off
  // gives its shape once, a circular translation both translations.
  struct Mode {
    Complex root;
    bool rigid;
    Eigen::VectorXcd shape;  // over the free equations
  };
  std::vector<Mode> modes;
  std::vector<Eigen::VectorXd> rigid_basis;  // M-orthonormal
  const Eigen::MatrixXd& mass = linear.mass;
  for (const Root& root : roots) {
    if (static_cast<int>(modes.size()) >= mode_count) break;
    if (!rigid(root.shape)) {
      modes.push_back({root.value, false, root.shape});
      continue;
    }
    Eigen::VectorXcd shape = root.shape;
    fix_phase(shape);
    for (const Eigen::VectorXd& part : {Eigen::VectorXd(shape.real()), Eigen::VectorXd(shape.imag())}) {
      Eigen::VectorXd added = part;
      for (const Eigen::VectorXd& earlier : rigid_basis) added -= earlier.dot(mass * added) * earlier;
      const double size = std::sqrt(added.dot(mass * added));
      if (size < 1e-3 || static_cast<int>(modes.size()) >= mode_count) continue;
      rigid_basis.push_back(added / size);
      modes.push_back({root.value, true, rigid_basis.back().cast<Complex>()});
    }
  }

  const int count = static_cast<int>(modes.size());
  result.shapes.setZero(dofs.dof_count(), count);
  result.reactions.setZero(dofs.dof_count(), count);
  ForceProbe probe(assembler, linear.state);
  for (int i = 0; i < count; ++i) {
    const Mode& mode = modes[i];
    Eigen::VectorXcd shape = on_all_dofs(dofs, mode.shape);
    fix_phase(shape);
    result.roots.push_back(mode.root);
    result.rigid_body.push_back(mode.rigid);
    result.frequencies_hz.push_back(mode.rigid ? 0.0 : mode.root.imag() / kTwoPi);
    result.natural_frequencies_hz.push_back(mode.rigid ? 0.0 : std::abs(mode.root) / kTwoPi);
    result.damping_ratios.push_back(mode.rigid ? 0.0 : -mode.root.real() / std::abs(mode.root));
    result.shapes.col(i) = shape;
    result.reactions.col(i) = prescribed_rows(dofs, support_reaction(probe, shape, mode.root, spin, settings.damping));
  }
  return result;
}

DampedModalResult damped_modal_analysis(Analysis& analysis, int mode_count, const DampedModalSettings& settings) {
  return damped_modal_analysis(analysis.model(), analysis.state(), mode_count, settings);
}

}  // namespace tirefe
