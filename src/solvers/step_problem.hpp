// StepProblem: the equations of one time step, as Newton sees them. It holds the trial
// state from the integrator's predictor, evaluates the step's residual and tangent there,
// and decides where the tangent lies: in the sparse matrix, or straight in the storage of
// the RingSolver that factors it (docs/kernel.md). It chooses how a solve starts: from the
// predictor, or, for a host that moves its driven DOFs a little between trials, from the
// last trial moved by its linear response. On success it commits the trial: reactions,
// energy, element history and the carried state move on.
#pragma once

#include <iosfwd>
#include <string>

#include "core/assembler.hpp"
#include "core/model.hpp"
#include "solvers/carried_state.hpp"
#include "solvers/driven_dofs.hpp"
#include "solvers/driven_solver.hpp"
#include "solvers/energy_balance.hpp"
#include "solvers/integrator.hpp"
#include "solvers/newton.hpp"
#include "solvers/solver_choice.hpp"
#include "solvers/step_controller.hpp"

namespace tirefe {

class StepProblem : private StepEquations {
 public:
  /// Everything is the caller's and outlives this object.
  StepProblem(Model& model, Assembler& assembler, SolverChoice& solvers, const Integrator& integrator,
              CarriedState& carried, const DrivenDofs& driven);
  StepProblem(const StepProblem&) = delete;
  StepProblem& operator=(const StepProblem&) = delete;

  /// Sizes the carried fields to the mesh (nodes added since the last step start at rest).
  void size_state();
  /// Sizes the state, analyses a new tangent pattern and wraps the solver for driven DOFs.
  void prepare();
  /// The trial at end_time from the predictor, prescribed and driven DOFs in place, with
  /// the committed forces the integrator weighs.
  void predict(double step, double end_time);
  /// Moves the last trial by its linear response to the driven DOFs' new places
  /// (A_uu du_u = -A_us du_s with the factors of driven_tangent()), so that the next
  /// solve() starts expecting convergence: its first evaluation assembles the residual
  /// alone. False, nothing moved, when those factors are not the current pattern's (the
  /// caller knows the last trial was of this step's size).
  bool start_from_driven_move(double step);
  /// Newton and the augmentations from the trial as it is; false (history reverted, the
  /// reason in failure()) when it does not converge.
  bool solve(NewtonSolver& newton, int max_augmentations, StepRecord& record, std::ostream* log);
  /// Forgets the trial: the element history is the committed one again.
  void revert() { model_.revert_history(); }
  /// The converged trial becomes the committed state (record: step number, time, energy).
  void commit(double step, EnergyBalance& energy, StepRecord& record);

  const State& trial() const { return trial_; }
  double committed_time() const { return carried_.state.time; }
  const std::string& failure() const { return failure_; }
  /// The driven DOFs' residuals at the converged trial, HHT-weighted like the equations.
  void driven_forces(Eigen::Ref<Eigen::VectorXd> forces) const { driven_.gather(residual_all_, forces); }
  /// H = K_ss - K_su K_uu^-1 K_us of the converged trial's effective tangent (docs/model.md
  /// eq. 27); its factors serve start_from_driven_move().
  const DrivenDofSolver::SmallMatrix& driven_tangent();

 private:
  void require_equations() const;
  /// M a at 'state' (generalized-alpha's old inertia force).
  void query_inertia_forces(const State& state, Eigen::VectorXd& inertia);
  /// The RingSolver the tangent is assembled into (bound to the assembler for this pattern),
  /// or null: the RingSolver solving alone, or the held one of a DrivenDofSolver on the ring route.
  RingSolver* solver_taking_tangent();
  // StepEquations
  void evaluate(bool with_tangent, Eigen::VectorXd& free_residual, double& force_level) override;
  const SparseMatrix& tangent() const override { return assembler_.tangent(); }
  void factorize_tangent(LinearSolver& solver) override;
  double apply_increment(const Eigen::VectorXd& increment) override;
  bool wants_converged_tangent() const override { return !driven_.empty(); }
  bool start_expected_converged() const override { return start_expected_converged_; }

  Model& model_;
  Assembler& assembler_;
  SolverChoice& solvers_;
  const Integrator& integrator_;
  CarriedState& carried_;
  const DrivenDofs& driven_;
  std::string failure_;

  State trial_;
  Eigen::VectorXd residual_all_, external_new_;
  Eigen::VectorXd inertia_forces_;  // M a of the step being committed
  // How a solve starts.
  double trial_reference_ = 0.0;           // Newton's reference force of the step's trial from the predictor
  double resolve_reference_ = 0.0;         // that force, a floor of the force level while starting from a move
  bool first_evaluation_ = false;          // the next evaluate() is the first of a Newton solve
  bool start_expected_converged_ = false;  // the next solve starts from a trial's linear response
  bool start_without_tangent_ = false;     // the last evaluation was such a start's, of the residual alone
  Eigen::VectorXd start_residual_;         // the free residual of that start made again with its tangent
  Eigen::VectorXd driven_move_, response_;
  int response_pattern_ = -1;  // pattern of the factors from driven_tangent(); -1: none
  // Where the tangent lies.
  RingSolver* layout_solver_ = nullptr;  // the solver whose layout the assembler holds bound,
  int layout_pattern_ = -1;              // for this pattern version
  bool tangent_in_solver_ = false;       // the last evaluation's tangent lies in layout_solver_
};

}  // namespace tirefe
