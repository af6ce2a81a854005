// StepController: advances a stepped system (a model's Analysis, a vehicle) to a target
// time. It cuts a step that fails in half and tries again, grows the step back toward the
// nominal one after an easy convergence, lets the last step land on the target (no sliver
// of a step is left over), stops at the smallest step, the most cuts or the step budget,
// takes the steps of a window's own size while the time is inside it, and tells the
// observers of every accepted step.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/step_record.hpp"
#include "solvers/carried_state.hpp"

namespace tirefe {

/// Raised when a step cannot be completed even after the allowed cuts.
class StepFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StepControl {
  double min_step = 0.0;       // 0: no lower bound beyond max_cuts
  double max_step = 0.0;       // 0: the nominal step
  int max_cuts = 10;           // halvings of one step
  int depth = 0;               // no step below the nominal one halved this often (0: 2 max_cuts)
  int easy_iterations = 4;     // grow the step after converging in this many iterations or fewer
  double growth = 2.0;         // growth factor back toward the nominal step
  int max_augmentations = 20;  // augmented-Lagrangian updates per step
  // One advance may take at most step_budget steps per nominal step it spans (plus
  // step_budget): a step that keeps converging only at a small fraction of the nominal one
  // (an out-of-balance start, a tiny rotary inertia) stops the run instead of filling the
  // disk with steps. 0: no budget.
  int step_budget = 100;
};

/// Steps of their own size between two times (absolute, e.g. around an obstacle's impacts).
struct StepWindow {
  double from = 0.0, to = 0.0, step = 0.0;  // [s]
};

/// What a StepController advances.
class SteppedSystem {
 public:
  virtual ~SteppedSystem() = default;
  /// The committed time.
  virtual double time() const = 0;
  /// Solves a step of size 'step' ending at end_time from the committed state, as a trial
  /// (record: iterations, residual); false, with the trial forgotten, when it fails.
  virtual bool try_step(double step, double end_time, StepRecord& record) = 0;
  /// Commits the trial step (record: step number, time, energy).
  virtual void commit_step(double step, StepRecord& record) = 0;
  /// Why the step from the committed time fails even after 'cuts' cuts, the last of size 'step'.
  virtual std::string failure_message(int cuts, double step) const = 0;
  /// Where the committed time lies, for a message: "at t = ..." on the system's own clock.
  virtual std::string where() const;
};

class StepController {
 public:
  using Observer = std::function<void(const StepRecord&)>;

  /// Steps of sizes.nominal, the next of sizes.current (the caller's carried state).
  explicit StepController(StepSizes& sizes) : sizes_(sizes) {}

  StepControl& settings() { return control_; }
  const StepControl& settings() const { return control_; }
  /// Windows of their own step size for the next advances (ModelError for an empty or
  /// backward window).
  void set_windows(std::vector<StepWindow> windows);

  /// Advances 'system' to the time 'target' (the last step lands on it exactly); returns
  /// the records of the accepted steps. Throws StepFailure.
  const std::vector<StepRecord>& advance_to(SteppedSystem& system, double target);

  void add_observer(Observer observer) { observers_.push_back(std::move(observer)); }
  /// Runs after every observer of an accepted step (a checkpoint: the step's output is complete then).
  void set_closing_observer(Observer observer) { closing_observer_ = std::move(observer); }
  /// Tells the observers of an accepted step.
  void notify(const StepRecord& record) const;

 private:
  void advance_span(SteppedSystem& system, double target);
  void check_step_budget(const SteppedSystem& system, int steps_taken, double nominal_steps, double step) const;

  StepSizes& sizes_;
  StepControl control_;
  std::vector<StepWindow> windows_;
  std::vector<StepRecord> records_;
  std::vector<Observer> observers_;
  Observer closing_observer_;
};

}  // namespace tirefe
