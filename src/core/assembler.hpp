// Assembler: gathers, evaluates and scatters every element block into the global
// residual (all DOFs, so prescribed rows carry the reactions) and the sparse tangent
// over the free equations. The sparsity pattern and each element entry's slot in the
// value array are computed once per model structure; assembly then only adds numbers.
#pragma once

#include <Eigen/Sparse>

#include "core/model.hpp"

namespace tirefe {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

class Assembler {
 public:
  explicit Assembler(Model& model) : model_(model) {}

  /// Rebuilds the pattern if the model's structure changed since the last call;
  /// returns true when it did (a linear solver must then redo its analysis).
  bool update_pattern();

  /// residual: element forces weighted by context.factors (external loads are the
  /// integrator's business); tangent: cK K + cC C + cM M over the free equations.
  /// The Newton step's evaluation, the one that writes the elements' trial history (which
  /// the step then commits or reverts).
  void assemble(const EvaluationContext& context, const State& state, Eigen::VectorXd& residual);
  /// The same evaluation for a query between steps (reactions, an initial acceleration,
  /// a penalty's scale, modal matrices): the elements' trial history is put back to the
  /// committed one afterwards, however the evaluation ends, so that no query changes the
  /// next step.
  void query(const EvaluationContext& context, const State& state, Eigen::VectorXd& residual);

  /// Binds the blocks' tangent entries to a linear solver's own storage too, as their slot
  /// layout 1: the stored entry s of the pattern (in tangent()'s value order) lands at
  /// destination[s] there (RingSolver::entry_destinations()). Valid until the pattern changes.
  void bind_solver_layout(const std::vector<int>& destination);
  /// True while every block holds the binding made last (another assembler of the same
  /// model binding its own slots, or a new pattern, takes it away).
  bool solver_layout_bound() const;
  /// assemble() with the tangent added into 'storage', in the bound solver layout and
  /// cleared by the caller, instead of into tangent(): the solver factors it where it
  /// lies, and tangent()'s values are left as they were.
  void assemble_into_solver(const EvaluationContext& context, const State& state, Eigen::VectorXd& residual,
                            double* storage);

  /// The inertia forces M a at 'state', one entry per DOF, from the kernels' constant
  /// masses without evaluating them; false when a block cannot give them.
  bool inertia_forces(const State& state, Eigen::VectorXd& forces) const;

  const SparseMatrix& tangent() const { return tangent_; }
  SparseMatrix& tangent() { return tangent_; }
  int pattern_version() const { return pattern_version_; }

 private:
  long structure_signature() const;

  Model& model_;
  SparseMatrix tangent_;
  long signature_ = -1;
  static constexpr int kSolverLayout = 1;  // the blocks' slot layout of a solver's storage
  long solver_stamp_ = 0;                  // the stamp of its binding made last, 0 for none
  int pattern_version_ = 0;
};

}  // namespace tirefe
