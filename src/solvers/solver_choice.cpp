#include "solvers/solver_choice.hpp"

#include "core/mesh.hpp"  // ModelError

namespace tirefe {

void SolverChoice::use_ring(std::unique_ptr<RingSolver> ring, const LinearSolver::Matrix& tangent, int pattern) {
  ring->analyze(tangent);  // throws for a model that does not fit, before anything changes
  ring_ = std::move(ring);
  ring_use_ = RingUse::Always;
  select(*ring_);
  analyzed_pattern_ = pattern;
}

void SolverChoice::prefer_ring(std::unique_ptr<RingSolver> ring) {
  ring_ = std::move(ring);
  ring_use_ = RingUse::WhereItFits;
  analyzed_pattern_ = -1;  // chosen at the next analyze()
}

void SolverChoice::select(LinearSolver& solver) {
  if (active_ != &solver) driven_.reset();  // it wrapped the other one
  active_ = &solver;
}

void SolverChoice::analyze(const LinearSolver::Matrix& tangent, int pattern) {
  if (ring_use_ == RingUse::WhereItFits) {
    try {
      ring_->analyze(tangent);
      select(*ring_);
      analyzed_pattern_ = pattern;
      return;
    } catch (const ModelError&) {  // not a lone ring and its border: the general solver
      select(klu_);
    }
  }
  active_->analyze(tangent);
  analyzed_pattern_ = pattern;
}

void SolverChoice::drive(std::vector<int> equations, const LinearSolver::Matrix& tangent) {
  driven_ = std::make_unique<DrivenDofSolver>(*active_, std::move(equations));
  driven_->analyze(tangent);
  driven_pattern_ = analyzed_pattern_;
}

}  // namespace tirefe
