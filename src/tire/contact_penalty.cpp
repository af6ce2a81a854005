#include "tire/contact_penalty.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/assembler.hpp"
#include "core/model.hpp"
#include "solvers/linear_solver.hpp"

namespace tirefe {

namespace {

/// The structure's static tangent dF_int/du at the analysis's current state, from the
/// analysis's own assembler (a second assembler would rebind the blocks' tangent slots).
const SparseMatrix& static_tangent(Analysis& analysis, State& state) {
  Model& model = analysis.model();
  Assembler& assembler = analysis.assembler();
  if (assembler.update_pattern()) analysis.linear_solver().analyze(assembler.tangent());
  state = analysis.state();
  if (state.displacement.size() != model.mesh().dof_count()) state.resize(model.mesh().dof_count());
  EvaluationContext context;  // static factors: dF_int/du alone
  context.time = state.time;
  Eigen::VectorXd residual;
  assembler.query(context, state, residual);
  return assembler.tangent();
}

}  // namespace

double structural_penalty(Analysis& analysis, const std::vector<int>& nodes, double factor) {
  if (!(factor > 0.0)) throw ModelError("contact: the penalty factor must be positive");
  State state;
  const SparseMatrix& tangent = static_tangent(analysis, state);
  const DofMap& dofs = analysis.model().dof_map();
  double largest = 0.0;
  for (int node : nodes)
    for (int component : {kUx, kUy}) {
      const int equation = dofs.equation(dof_index(node, component));
      if (equation >= 0) largest = std::max(largest, std::abs(tangent.coeff(equation, equation)));
    }
  if (!(largest > 0.0) || !std::isfinite(largest))
    throw ModelError(
        "contact: the contact nodes carry no stiffness, so the penalty cannot be scaled from the "
        "structure; give it explicitly");
  return factor * largest;
}

double structural_tangential_penalty(Analysis& analysis, const std::vector<int>& nodes, const RigidSurface& surface,
                                     double factor) {
  if (!(factor > 0.0)) throw ModelError("contact: the penalty factor must be positive");
  State state;
  const SparseMatrix& tangent = static_tangent(analysis, state);
  const Model& model = analysis.model();
  const DofMap& dofs = model.dof_map();
  // Unit loads along x and y at every node: the columns of the inverse at the nodes.
  Eigen::MatrixXd unit_loads =
      Eigen::MatrixXd::Zero(dofs.equation_count(), 2 * static_cast<Eigen::Index>(nodes.size()));
  for (size_t n = 0; n < nodes.size(); ++n)
    for (int component : {kUx, kUy}) {
      const int equation = dofs.equation(dof_index(nodes[n], component));
      if (equation >= 0) unit_loads(equation, 2 * n + component) = 1.0;
    }
  KluSolver solver;
  try {
    solver.analyze(tangent);
    solver.factorize(tangent);
  } catch (const SingularMatrix&) {
    throw ModelError(
        "contact: the structure is not supported without the contact, so the tangential penalty cannot be "
        "scaled from it; support it while defining the contact, or give the tangential penalty");
  }
  solver.solve(unit_loads);
  double smallest = std::numeric_limits<double>::infinity();
  bool unstable = false;
  for (size_t n = 0; n < nodes.size(); ++n) {
    Eigen::Matrix2d compliance = Eigen::Matrix2d::Zero();  // prescribed components: rigid
    for (int row : {kUx, kUy})
      for (int column : {kUx, kUy}) {
        const int equation = dofs.equation(dof_index(nodes[n], row));
        if (equation >= 0) compliance(row, column) = unit_loads(equation, 2 * n + column);
      }
    const Eigen::Vector2d position =
        model.mesh().position(nodes[n]) + state.displacement.segment<2>(dof_index(nodes[n], kUx));
    const Eigen::Vector2d tau = surface.project(position, state.time).tangent;
    const double flexibility = tau.dot(compliance * tau);
    if (flexibility > 0.0 && std::isfinite(flexibility)) smallest = std::min(smallest, 1.0 / flexibility);
    if (flexibility < 0.0) unstable = true;
  }
  // A negative compliance is a structure that is not stable in its current state (the
  // uninflated tire with the printed sign of k_sw): no stiffness to scale from.
  if (unstable)
    throw ModelError(
        "contact: the structure has a negative stiffness along the surface in its current state, so the "
        "tangential penalty cannot be scaled from it; define the contact after loading the structure into a "
        "stable state (after inflating a tire), or give tangential_penalty");
  if (!std::isfinite(smallest))
    throw ModelError("contact: the contact nodes cannot move along the surface; give the tangential penalty");
  return factor * smallest;
}

}  // namespace tirefe
