// TreadPressure: the inflation pressure on the tread of one wedge, a follower load
// (docs/model.md section 1). Nodes: tread nodes a and b, counter-clockwise about the spindle.
//
// The pressure p(t) (the tire's shared PressureSchedule) over the tread width w acts
// normal to the DEFORMED chord c = x_b - x_a (x = X + u), outward: for counter-clockwise
// nodes the outward normal is c rotated by -90 degrees, (c_y, -c_x)/|c|. The total
// force p w |c| is split equally between the two nodes:
//   f_a = f_b = (p w / 2) (c_y, -c_x) = -(p w / 2) k x c.
// The residual is internal minus external force, so r_a = r_b = (p w / 2) k x c; with
// d(k x c) = k x (du_b - du_a) the load stiffness (unsymmetric) is
//   dr_a/du_a = dr_b/du_a = -(p w / 2) [k x],  dr_a/du_b = dr_b/du_b = +(p w / 2) [k x],
// [k x] = [[0, -1], [1, 0]]. Rotations carry nothing. The load has no per-element
// potential (the ring's p times enclosed area is one), so energy() returns zero.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <vector>

#include "core/element.hpp"
#include "elements/pressure_schedule.hpp"

namespace tirefe {

class TreadPressure : public KernelShape<2> {
 public:
  static constexpr KernelTraits traits() {
    KernelTraits traits;
    traits.reads_acceleration = false;
    traits.reads_velocity = false;  // no damping
    traits.stores_energy = false;   // energy() is zero (above)
    traits.idle_dofs = {2, 5};      // the rotations
    // [k x] couples x with y only: no component's load moves with the same component.
    traits.zero_tangent_entry = [](int row, int column) { return row % 3 == column % 3; };
    return traits;
  }

  /// Reference positions of the two tread nodes (counter-clockwise), tread width w [m].
  TreadPressure(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double width,
                std::shared_ptr<const PressureSchedule> pressure);

  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History& committed,
                History& trial, Vector& residual, Matrix* tangent) const;
  ElementEnergy energy(const LocalState<kDofs>& local, const History& history) const;
  /// The block's batch path (element.hpp): every load at once; evaluate() is its block of one.
  class Batch;

 private:
  Eigen::Vector2d reference_chord_;
  double width_;
  std::shared_ptr<const PressureSchedule> pressure_;
};

/// Loads over structure-of-arrays data: the pressure once per schedule, then one loop
/// vectorised across loads. Only the eight load-stiffness entries change; the other
/// tangent entries stay zero.
class TreadPressure::Batch {
 public:
  explicit Batch(const std::vector<TreadPressure>& loads);
  /// The batch of other loads (without allocating when their number is the same).
  void assign(const std::vector<TreadPressure>& loads);
  int size() const { return static_cast<int>(loads_.size()); }
  void evaluate(const BlockValues& values, const EvaluationContext& context, bool with_tangent);
  const double* residual() const { return residual_.data(); }
  const double* tangent() const { return tangent_.data(); }

 private:
  std::vector<TreadPressure> loads_;
  std::vector<double> chord_x_, chord_y_, half_load_;  // per load: reference chord, p w / 2
  std::vector<double> residual_, tangent_;             // [k * size + e]
};

}  // namespace tirefe
