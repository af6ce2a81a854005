// DrivenStepper: the steps of an analysis whose driven DOFs a host moves (a vehicle moving
// a tire's spindle, docs/spindle.md), in three verbs, as a co-simulation master calls a
// subsystem: solve() a step with the driven DOFs where the host puts them and read the
// forces that hold them there, then commit() or revert() it. Solves within one host step
// are trials from the committed state. Whether a trial starts from the predictor or from
// the last trial moved by its linear response, and whether commit() still computes or only
// tells the observers, are this class's own choices.
#pragma once

#include <iosfwd>

#include "solvers/step_problem.hpp"

namespace tirefe {

class DrivenStepper {
 public:
  /// Everything is the analysis's and outlives this object.
  DrivenStepper(StepProblem& problem, DrivenDofs& driven, NewtonSolver& newton, StepController& controller,
                EnergyBalance& energy, std::ostream* const& log)
      : problem_(problem), driven_(driven), newton_(newton), controller_(controller), energy_(energy), log_(log) {}
  DrivenStepper(const DrivenStepper&) = delete;
  DrivenStepper& operator=(const DrivenStepper&) = delete;

  /// Solves a trial step of size 'step' that ends with the driven DOFs at 'displacements'
  /// (drive order); throws StepFailure. 'near_last_trial': the host moved them little
  /// since the last trial of this step, which may then start from it.
  const StepRecord& solve(const Eigen::Ref<const Eigen::VectorXd>& displacements, double step,
                          bool near_last_trial = false);
  /// The forces that hold the driven DOFs at the trial (the reactions once committed).
  void forces(Eigen::Ref<Eigen::VectorXd> forces) const { problem_.driven_forces(forces); }
  /// Their Jacobian with respect to the driven displacements at the trial (ModelError without one).
  const DrivenDofSolver::SmallMatrix& jacobian();
  /// Accepts the trial: state, history and energies move on; the observers hear of the step.
  void commit();
  /// The computing part of commit(), which may run beside other analyses' in threads of
  /// their own; the commit() that follows only tells the observers.
  void prepare_commit();
  /// Forgets the trial.
  void revert();
  const State& trial() const { return problem_.trial(); }

 private:
  StepProblem& problem_;
  DrivenDofs& driven_;
  NewtonSolver& newton_;
  StepController& controller_;
  EnergyBalance& energy_;
  std::ostream* const& log_;
  StepRecord record_;
  double step_ = 0.0;
  bool pending_ = false;   // a solved trial awaits commit or revert
  bool prepared_ = false;  // prepare_commit() done, observers not yet told
};

}  // namespace tirefe
