// TireSpindle: a tire seen from a vehicle through its spindle (docs/model.md section 6).
//
// The host (a multibody code, the Vehicle of this module, a co-simulation master) puts
// the spindle somewhere at the end of a time step; solve_step() solves the tire's
// nonlinear dynamic step with the spindle held there and returns the spindle force and
// its consistent Jacobian H_ss = K_ss - K_su K_uu^-1 K_us of the Newmark/HHT effective
// tangent (eq. 27). Calls within one host step are trials: the tire advances only on
// commit(); revert() forgets the trial. Everything crosses the interface as the plain
// values of SpindleRequest and SpindleReply (spindle_exchange.hpp), so the same calls
// can be made in this thread, another thread or another process (docs/spindle.md).
//
// The tire's Analysis must be dynamic; its spindle node is driven (Analysis::drive_dofs)
// in ux, uy and, unless the spin is free, rz. The tire keeps its own integrator (the
// host's scheme should match it: see docs/spindle.md).
#pragma once

#include "solvers/analysis.hpp"
#include "vehicle/spindle_exchange.hpp"

namespace tirefe {

class TireSpindle {
 public:
  /// Drives 'spindle' of the analysed model in ux, uy and, unless the spin is free, rz
  /// (any prescription of them is released). The analysis must outlive this object.
  TireSpindle(Analysis& analysis, int spindle, SpinMode spin);

  /// Solves the trial step to the requested spindle position; throws StepFailure.
  const SpindleReply& solve_step(const SpindleInput& input);
  /// The last solve_step()'s reply with the Jacobian of its trial, computed now if that
  /// solve left it out; throws ModelError when no trial is pending.
  const SpindleReply& jacobian();
  /// Accepts the last trial step: the tire's state and history advance.
  void commit();
  /// The computing part of commit() (DrivenStepper::prepare_commit), which may run in a
  /// thread of its own; commit() then only writes the output. Never throws: a failure
  /// is kept and reported by the commit() that follows.
  void prepare_commit();
  /// Forgets the last trial step.
  void revert();
  /// Dispatches one request (solve, Jacobian, commit or revert); never throws: failures come
  /// back as status Failed with the message. Commit and Revert answer with the committed
  /// time and spindle force (committed_force()).
  SpindleReply serve(const SpindleRequest& request);

  /// Where the spindle is at the committed time: x, y [m] and spin angle [rad].
  Eigen::Vector3d committed_position() const;
  /// Spindle force at the committed time (the physical reaction).
  Eigen::Vector3d committed_force() const;
  double time() const { return analysis_.state().time; }
  SpinMode spin() const { return spin_; }
  Analysis& analysis() { return analysis_; }

 private:
  Analysis& analysis_;
  int spindle_;
  SpinMode spin_;
  int driven_count_;  // 2 with free spin, else 3
  SpindleReply reply_;
  bool reply_has_jacobian_ = false;
  std::string commit_failure_;  // of prepare_commit()
};

}  // namespace tirefe
