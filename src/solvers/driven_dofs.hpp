// DrivenDofs: free DOFs whose displacement at the end of each step a host gives (a
// vehicle moving a tire's spindle, docs/spindle.md), and those displacements. Newton
// solves the other equations; the driven DOFs' residuals are the forces that hold them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/state.hpp"
#include "solvers/integrator.hpp"

namespace tirefe {

class DrivenDofs {
 public:
  DrivenDofs() = default;
  /// 'dofs' (at most one node's, DrivenDofSolver::kMaxDriven) of a mesh with dof_count
  /// DOFs; ModelError for more or for one that does not exist.
  DrivenDofs(std::vector<int> dofs, int dof_count);

  const std::vector<int>& dofs() const { return dofs_; }
  /// Where the host wants them at the end of the next step, in dofs() order.
  const Eigen::VectorXd& displacements() const { return displacements_; }
  bool empty() const { return dofs_.empty(); }
  /// Holds the driven DOFs where 'state' has them until the host says otherwise.
  void start_at(const State& state);
  /// Displacements at the end of the next step, in dofs() order (ModelError for a wrong
  /// count or a value that is not finite).
  void set_displacements(const Eigen::Ref<const Eigen::VectorXd>& values);
  /// Puts the driven DOFs of the trial state where the host wants them, with the rates
  /// the integrator gives that displacement.
  void impose(const Integrator& integrator, const State& committed, double step, State& trial) const;
  /// The driven entries of 'field', in dofs() order.
  void gather(const Eigen::VectorXd& field, Eigen::Ref<Eigen::VectorXd> values) const;

 private:
  std::vector<int> dofs_;
  Eigen::VectorXd displacements_;
};

}  // namespace tirefe
