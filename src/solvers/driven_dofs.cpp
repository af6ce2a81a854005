#include "solvers/driven_dofs.hpp"

#include <string>

#include "core/mesh.hpp"
#include "solvers/driven_solver.hpp"

namespace tirefe {

DrivenDofs::DrivenDofs(std::vector<int> dofs, int dof_count) : dofs_(std::move(dofs)) {
  if (dofs_.size() > static_cast<size_t>(DrivenDofSolver::kMaxDriven))
    throw ModelError("at most " + std::to_string(DrivenDofSolver::kMaxDriven) + " DOFs (one node) can be driven");
  for (int dof : dofs_)
    if (dof < 0 || dof >= dof_count) throw ModelError("driven DOF " + std::to_string(dof) + " does not exist");
  displacements_.resize(static_cast<Eigen::Index>(dofs_.size()));
}

void DrivenDofs::start_at(const State& state) { gather(state.displacement, displacements_); }

void DrivenDofs::set_displacements(const Eigen::Ref<const Eigen::VectorXd>& values) {
  if (values.size() != displacements_.size())
    throw ModelError("got " + std::to_string(values.size()) + " driven displacements for " +
                     std::to_string(displacements_.size()) + " driven DOFs");
  if (!values.allFinite()) throw ModelError("driven displacements must be finite");
  displacements_ = values;
}

void DrivenDofs::impose(const Integrator& integrator, const State& committed, double step, State& trial) const {
  for (size_t i = 0; i < dofs_.size(); ++i) {
    trial.displacement[dofs_[i]] = displacements_[static_cast<Eigen::Index>(i)];
    integrator.update_rates(committed, step, dofs_[i], trial);
  }
}

void DrivenDofs::gather(const Eigen::VectorXd& field, Eigen::Ref<Eigen::VectorXd> values) const {
  for (size_t i = 0; i < dofs_.size(); ++i) values[static_cast<Eigen::Index>(i)] = field[dofs_[i]];
}

}  // namespace tirefe
