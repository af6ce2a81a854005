// TireBuilder: the ring tire of docs/model.md section 1 from named physical parameters.
//
// One spindle node at the wheel centre and N tread nodes equally spaced on the circle
// of the unloaded outer diameter (the tread nodes carry the contact). Each wedge i joins
// the spindle to tread nodes i and i+1 (counter-clockwise) and is made of
//   - a tread beam between the two tread nodes (block <name>_tread),
//   - the sidewall arch-membrane element (block <name>_sidewall),
//   - the follower inflation pressure on the tread chord (block <name>_pressure);
// and the rigid rim + hub is a mass and rotary inertia on the spindle (block <name>_rim).
// The tread rubber between the belt and the road is a massless layer: its stiffness and
// damping make the tire's contact law (tread_rubber(), contact/tread_contact.hpp), its
// mass rides on the belt.
// Node sets: <name>_spindle, <name>_tread.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contact/tread_contact.hpp"
#include "core/model.hpp"
#include "elements/pressure_schedule.hpp"
#include "elements/sidewall.hpp"
#include "elements/tread_beam.hpp"

namespace tirefe {

/// The tread rubber between the belt and the road, per unit length of circumference: the
/// tire's contact law. A tire without it (both stiffnesses 0) cannot touch a road.
struct TreadLayerParameters {
  double radial_stiffness = 0.0;           // [N/m^2]: normal force per m of circumference per m of compression
  double circumferential_stiffness = 0.0;  // [N/m^2]: shear force per m of circumference per m of shift
  double mass_per_length = 0.0;            // the rubber's mass, carried by the belt [kg/m]
  double radial_damping = 0.0;             // [N s/m^2]: dashpot of the rubber's hysteresis, per m of circumference
  double circumferential_damping = 0.0;    // [N s/m^2]
  bool enabled() const { return radial_stiffness > 0.0 || circumferential_stiffness > 0.0; }
};

struct TireParameters {
  int elements = 100;
  double outer_diameter = 0.0;      // unloaded, uninflated, at the tread nodes [m]
  double rim_diameter = 0.0;        // effective rim diameter [m]
  double tread_width = 0.0;         // width the pressure acts on [m]
  BeamSection tread;                // tread (belt) beam section
  SidewallProperties sidewall;      // rim_radius is set from rim_diameter
  double rim_mass = 0.0;            // rim + hub mass [kg]
  double rim_rotary_inertia = 0.0;  // rim + hub rotary inertia [kg m^2]
  double pressure = 0.0;            // inflation pressure [Pa]
  TreadLayerParameters tread_layer;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // spindle position [m]

  /// Throws ModelError naming the first missing, non-physical or inconsistent parameter.
  void check() const;
};

struct Tire {
  std::string name;
  int spindle = -1;              // 0-based node index
  std::vector<int> tread_nodes;  // 0-based, counter-clockwise from the +x axis
  std::shared_ptr<PressureSchedule> pressure;
  TireParameters parameters;
};

/// Adds a tire to the model; the pressure follows parameters.pressure * pressure_ramp(t).
Tire build_tire(Model& model, const TireParameters& parameters, LoadFunction pressure_ramp,
                const std::string& name = "tire");

/// The tire's contact law with 'friction': its tread rubber. Throws ModelError for a tire
/// without one.
TreadRubber tread_rubber(const TireParameters& parameters, double friction);

}  // namespace tirefe
