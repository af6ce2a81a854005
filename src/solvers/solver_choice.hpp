// SolverChoice: the linear solver of an analysis' Newton iterations. KLU by default;
// use_ring() puts the structured RingSolver in its place, prefer_ring() lets every new
// tangent pattern choose (the RingSolver where it fits, KLU elsewhere). With driven DOFs
// (docs/spindle.md) Newton solves through a DrivenDofSolver wrapped around the chosen
// one. Both are (re)analysed when the tangent's pattern changes.
#pragma once

#include <memory>
#include <vector>

#include "solvers/driven_solver.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/ring_solver.hpp"

namespace tirefe {

class SolverChoice {
 public:
  /// Solves with 'ring' from now on: analyses 'tangent' (of pattern version 'pattern') at
  /// once, so a model that does not fit throws ModelError and keeps the current solver.
  void use_ring(std::unique_ptr<RingSolver> ring, const LinearSolver::Matrix& tangent, int pattern);
  /// Solves with 'ring' whenever the pattern fits it, with KLU otherwise (chosen at the next analyze()).
  void prefer_ring(std::unique_ptr<RingSolver> ring);

  /// True when the solver has analysed this pattern version.
  bool analyzed(int pattern) const { return pattern == analyzed_pattern_; }
  /// Chooses the solver for the tangent's pattern (version 'pattern') and analyses it.
  void analyze(const LinearSolver::Matrix& tangent, int pattern);
  /// The next analyze() starts afresh (no reused pivots), as after a restore.
  void forget_analysis() { analyzed_pattern_ = -1; }

  /// True when the driven solver wraps the current solver and pattern.
  bool driving() const { return driven_ && driven_pattern_ == analyzed_pattern_; }
  /// Wraps the current solver to hold these free equations (built and analysed for 'tangent').
  void drive(std::vector<int> equations, const LinearSolver::Matrix& tangent);
  void stop_driving() { driven_.reset(); }
  DrivenDofSolver* driven() { return driven_.get(); }

  /// The chosen solver (KLU or the RingSolver).
  LinearSolver& solver() { return *active_; }
  /// The solver of the Newton iterations: the chosen one, or the driven wrapper around it.
  LinearSolver& newton_solver() { return driven_ ? static_cast<LinearSolver&>(*driven_) : *active_; }
  /// The RingSolver in use; null while KLU solves.
  RingSolver* ring_solver() { return active_ == ring_.get() ? ring_.get() : nullptr; }

 private:
  enum class RingUse { Never, Always, WhereItFits };
  void select(LinearSolver& solver);

  KluSolver klu_;
  std::unique_ptr<RingSolver> ring_;
  RingUse ring_use_ = RingUse::Never;
  LinearSolver* active_ = &klu_;  // klu_ or ring_
  int analyzed_pattern_ = -1;     // the pattern version the solver last analysed
  std::unique_ptr<DrivenDofSolver> driven_;
  int driven_pattern_ = -1;  // the pattern driven_ was built for
};

}  // namespace tirefe
