#include "solvers/modal.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/assembler.hpp"
#include "solvers/analysis.hpp"

namespace tirefe {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;

/// Assembles the free-equation tangent for one set of tangent factors, densely.
Eigen::MatrixXd dense_tangent(Assembler& assembler, const State& state, const IntegratorFactors& factors,
                              Eigen::VectorXd& residual) {
  EvaluationContext context;
  context.time = state.time;
  context.factors = factors;
  context.want_tangent = true;
  assembler.assemble(context, state, residual);
  // The assembler keeps one sparse matrix: copy it out before the next pass.
  return Eigen::MatrixXd(assembler.tangent());
}

/// Restores trial = committed history however the assembly ends.
struct HistoryRevert {
  Model& model;
  ~HistoryRevert() { model.revert_history(); }
};

/// K_pf phi for every mode: central difference of the residual along the shape.
void support_reactions(Model& model, Assembler& assembler, const State& state, ModalResult& result) {
  HistoryRevert revert{model};
  const DofMap& dofs = model.dof_map();
  EvaluationContext context;
  context.time = state.time;
  context.want_tangent = false;
  State shifted = state;
  Eigen::VectorXd plus, minus;
  for (Eigen::Index mode = 0; mode < result.shapes.cols(); ++mode) {
    const double step = 1e-7 / result.shapes.col(mode).lpNorm<Eigen::Infinity>();
    shifted.displacement = state.displacement + step * result.shapes.col(mode);
    assembler.assemble(context, shifted, plus);
    shifted.displacement = state.displacement - step * result.shapes.col(mode);
    assembler.assemble(context, shifted, minus);
    for (int dof = 0; dof < dofs.dof_count(); ++dof)
      if (dofs.is_prescribed(dof)) result.reactions(dof, mode) = (plus[dof] - minus[dof]) / (2.0 * step);
  }
}

}  // namespace

ModalResult modal_analysis(Model& model, const State& state, int mode_count, const ModalSettings& settings) {
  if (mode_count < 1)
    throw ModelError("modal analysis: ask for at least one mode (got " + std::to_string(mode_count) + ")");
  Assembler assembler(model);  // its own pattern, so an Analysis' solver is never left out of date
  assembler.update_pattern();
  const DofMap& dofs = model.dof_map();
  const int equations = dofs.equation_count();

  State linearisation = state;
  for (Eigen::VectorXd* field :
       {&linearisation.displacement, &linearisation.velocity, &linearisation.acceleration}) {
    const Eigen::Index old_size = std::min<Eigen::Index>(field->size(), dofs.dof_count());
    field->conservativeResize(dofs.dof_count());
    field->tail(dofs.dof_count() - old_size).setZero();
  }

  Eigen::MatrixXd stiffness, mass;
  {
    HistoryRevert revert{model};
    Eigen::VectorXd residual;
    stiffness = dense_tangent(assembler, linearisation, {1.0, 0.0, 0.0, 1.0, 0.0, 0.0}, residual);
    mass = dense_tangent(assembler, linearisation, {0.0, 0.0, 0.0, 0.0, 0.0, 1.0}, residual);
  }

  ModalResult result;
  const int count = std::min(mode_count, equations);
  result.shapes.setZero(dofs.dof_count(), count);
  result.reactions.setZero(dofs.dof_count(), count);
  if (count == 0) return result;

  const Eigen::MatrixXd symmetric_mass = 0.5 * (mass + mass.transpose());
  const Eigen::LLT<Eigen::MatrixXd> cholesky(symmetric_mass);
  if (cholesky.info() != Eigen::Success)
    throw ModelError("modal analysis: the mass matrix is not positive definite; every free DOF needs mass "
                     "(give beams a rotary inertia rhoI > 0 and point masses a rotary inertia J > 0)");

  const double largest_entry = stiffness.cwiseAbs().maxCoeff();
  result.symmetric =
      (stiffness - stiffness.transpose()).cwiseAbs().maxCoeff() <= settings.symmetry_tolerance * largest_entry;
  Eigen::VectorXd eigenvalues;
  Eigen::MatrixXd vectors;
  if (result.symmetric) {
    // L^-1 K L^-T y = omega^2 y with phi = L^-T y: mass-orthonormal shapes. This is what
    // Eigen's GeneralizedSelfAdjointEigenSolver does, but it ignores a failed Cholesky.
    const auto lower = cholesky.matrixL();
    Eigen::MatrixXd reduced = lower.solve(0.5 * (stiffness + stiffness.transpose()));
    reduced = lower.solve(reduced.transpose()).eval();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(reduced);
    eigenvalues = solver.eigenvalues();
    vectors = cholesky.matrixU().solve(solver.eigenvectors());
  } else {
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(cholesky.solve(stiffness));
    eigenvalues = solver.eigenvalues().real();
    vectors = solver.eigenvectors().real();
    for (int j = 0; j < vectors.cols(); ++j) {
      const double modal_mass = vectors.col(j).dot(symmetric_mass * vectors.col(j));
      if (modal_mass > 0.0) vectors.col(j) /= std::sqrt(modal_mass);
    }
  }

  std::vector<int> order(equations);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return eigenvalues[a] < eigenvalues[b]; });

  const double stiffness_norm = stiffness.cwiseAbs().rowwise().sum().maxCoeff();
  for (int i = 0; i < count; ++i) {
    Eigen::VectorXd shape = vectors.col(order[i]);
    Eigen::Index largest = 0;
    shape.cwiseAbs().maxCoeff(&largest);
    if (shape[largest] < 0.0) shape = -shape;
    const double omega_squared = eigenvalues[order[i]];
    const bool rigid = (stiffness * shape).lpNorm<Eigen::Infinity>() <=
                       settings.rigid_body_tolerance * stiffness_norm * shape.lpNorm<Eigen::Infinity>();
    result.eigenvalues.push_back(omega_squared);
    result.rigid_body.push_back(rigid);
    const double signed_omega = std::copysign(std::sqrt(std::abs(omega_squared)), omega_squared);
    result.frequencies_hz.push_back(rigid ? 0.0 : signed_omega / kTwoPi);
    for (int equation = 0; equation < equations; ++equation) result.shapes(dofs.dof(equation), i) = shape[equation];
  }
  support_reactions(model, assembler, linearisation, result);
  return result;
}

ModalResult modal_analysis(Analysis& analysis, int mode_count, const ModalSettings& settings) {
  return modal_analysis(analysis.model(), analysis.state(), mode_count, settings);
}

}  // namespace tirefe
