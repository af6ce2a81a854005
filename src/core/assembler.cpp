#include "core/assembler.hpp"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

namespace tirefe {

long Assembler::structure_signature() const {
  long signature = model_.structure_version();
  for (const auto& block : model_.blocks()) signature = signature * 31 + block->size() + 1;
  return signature * 31 + static_cast<long>(model_.blocks().size());
}

bool Assembler::update_pattern() {
  model_.finalize();
  const long signature = structure_signature();
  if (signature == signature_) return false;

  const DofMap& dofs = model_.dof_map();
  const int n = dofs.equation_count();
  std::vector<Eigen::Triplet<double, int>> entries;
  std::vector<int> equations;
  for (const auto& block : model_.blocks()) {
    for (int e = 0; e < block->size(); ++e) {
      equations.clear();
      for (int node : block->element_nodes(e))
        for (int c = 0; c < kDofsPerNode; ++c) equations.push_back(dofs.equation(dof_index(node, c)));
      for (int row : equations)
        for (int col : equations)
          if (row >= 0 && col >= 0) entries.emplace_back(row, col, 0.0);
    }
  }
  // Keep the diagonal in the pattern even for a DOF no element touches, so the
  // solver reports a singular matrix instead of a malformed one.
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 0.0);
  tangent_.resize(n, n);
  tangent_.setFromTriplets(entries.begin(), entries.end());
  tangent_.makeCompressed();

  auto slot_of = [this](int row, int col) {
    const int* rows = tangent_.innerIndexPtr();
    const int* begin = rows + tangent_.outerIndexPtr()[col];
    const int* end = rows + tangent_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - rows);
  };
  for (const auto& block : model_.blocks()) {
    std::vector<int> slots;
    slots.reserve(static_cast<size_t>(block->size()) * 9 * block->nodes_per_element() * block->nodes_per_element());
    for (int e = 0; e < block->size(); ++e) {
      equations.clear();
      for (int node : block->element_nodes(e))
        for (int c = 0; c < kDofsPerNode; ++c) equations.push_back(dofs.equation(dof_index(node, c)));
      for (int row : equations)
        for (int col : equations) slots.push_back(row >= 0 && col >= 0 ? slot_of(row, col) : -1);
    }
    block->bind_tangent_slots(std::move(slots));
  }
  signature_ = signature;
  ++pattern_version_;
  return true;
}

void Assembler::assemble(const EvaluationContext& context, const State& state, Eigen::VectorXd& residual) {
  residual.setZero(model_.mesh().dof_count());
  AssemblyTarget target{&residual, nullptr};
  if (context.want_tangent) {
    std::fill(tangent_.valuePtr(), tangent_.valuePtr() + tangent_.nonZeros(), 0.0);
    target.tangent_values = tangent_.valuePtr();
  }
  for (const auto& block : model_.blocks()) block->assemble(context, state, target);
}

void Assembler::bind_solver_layout(const std::vector<int>& destination) {
  if (destination.size() != static_cast<size_t>(tangent_.nonZeros()))
    throw std::logic_error("assembler: a solver layout of " + std::to_string(destination.size()) +
                           " entries for a pattern of " + std::to_string(tangent_.nonZeros()));
  // Stamps unique across assemblers (the tires of a vehicle bind theirs in threads of their own).
  static std::atomic<long> last_id{0};
  solver_stamp_ = ++last_id;
  for (const auto& block : model_.blocks()) block->bind_slot_layout(kSolverLayout, destination, solver_stamp_);
}

bool Assembler::solver_layout_bound() const {
  if (solver_stamp_ == 0) return false;
  for (const auto& block : model_.blocks())
    if (block->slot_layout_stamp(kSolverLayout) != solver_stamp_) return false;
  return true;
}

void Assembler::assemble_into_solver(const EvaluationContext& context, const State& state, Eigen::VectorXd& residual,
                                     double* storage) {
  if (solver_stamp_ == 0) throw std::logic_error("assembler: a tangent assembled in a solver's layout not bound");
  residual.setZero(model_.mesh().dof_count());
  AssemblyTarget target{&residual, storage, kSolverLayout, solver_stamp_};
  for (const auto& block : model_.blocks()) block->assemble(context, state, target);
}

bool Assembler::inertia_forces(const State& state, Eigen::VectorXd& forces) const {
  forces.setZero(model_.mesh().dof_count());
  for (const auto& block : model_.blocks())
    if (!block->add_inertia_forces(state, forces)) return false;
  return true;
}

void Assembler::query(const EvaluationContext& context, const State& state, Eigen::VectorXd& residual) {
  struct HistoryRestorer {
    Model& model;
    ~HistoryRestorer() { model.revert_history(); }
  } restorer{model_};
  assemble(context, state, residual);
}

}  // namespace tirefe
