// TireOnRoad: a tire model ready to be driven through its spindle. Builds the ring tire
// with its spindle at the origin and held, inflates it quasi-statically (1 s, the hub
// held: a free hub has rigid-body modes quasi-statically), puts the road under the
// inflated tire, touching its lowest tread node, and adds the tread contact with Coulomb
// friction on the tire's own tread rubber (contact/tread_contact.hpp). The spindle is
// condensed and the RingSolver solves.
// press() then loads it quasi-statically, and drive() makes it dynamic and hands the
// spindle to a TireSpindle for a host.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "contact/tread_contact.hpp"
#include "contact/rigid_surface.hpp"
#include "solvers/analysis.hpp"
#include "tire/tire_builder.hpp"
#include "vehicle/tire_spindle.hpp"

namespace tirefe {

struct RoadContact {
  double friction = 0.0;
};

class TireOnRoad {
 public:
  /// The road at the height 'level' of the inflated tire's lowest point (the spindle is
  /// at y = 0), in the frame where the tire stands still.
  using RoadMaker = std::function<std::shared_ptr<const RigidSurface>(double level)>;

  TireOnRoad(const TireParameters& parameters, const RoadMaker& road, const RoadContact& contact);
  TireOnRoad(const TireOnRoad&) = delete;
  TireOnRoad& operator=(const TireOnRoad&) = delete;

  /// Moves the held spindle quasi-statically (in 1 s of model time) to 'deflection'
  /// below its design position [m]; returns the vertical spindle force then [N] (the
  /// force on the tire: negative when pressed).
  double press(double deflection);
  /// Switches the tire to 'integrator' (dynamic) and hands its spindle to a TireSpindle, at
  /// rest: the spindle's acceleration is zero, the tire's others in equilibrium with it.
  TireSpindle& drive(const Integrator& integrator, SpinMode spin = SpinMode::Free);
  TireSpindle& spindle() { return *spindle_; }

  Model& model() { return model_; }
  Analysis& analysis() { return *analysis_; }
  const Tire& tire() const { return tire_; }
  /// Height of the road below the spindle at the end of inflation (negative) [m].
  double road_level() const { return road_level_; }
  const TreadContactBlock& contact() const { return *contact_; }

 private:
  Model model_;
  Tire tire_;
  std::unique_ptr<Analysis> analysis_;
  double road_level_ = 0.0;
  const TreadContactBlock* contact_ = nullptr;
  std::unique_ptr<TireSpindle> spindle_;
};

/// The static vertical force-deflection curve of the tire of 'parameters' on a flat
/// frictionless road: inflated on its held hub, its spindle pressed quasi-statically to each
/// of the 'deflections' [m] below first touch in turn; returns the vertical force the tire
/// exerts on the wheel at each [N] (positive: it carries the wheel). 'between_presses' (may
/// be empty) runs before every press: a host that is asked to stop throws from it.
std::vector<double> static_vertical_forces(const TireParameters& parameters, const std::vector<double>& deflections,
                                           const std::function<void()>& between_presses = {});

}  // namespace tirefe
