#include "tire/tire_builder.hpp"

#include <cmath>
#include <cstdio>

#include "elements/point_mass.hpp"
#include "elements/tread_pressure.hpp"

namespace tirefe {

namespace {

constexpr double kPi = 3.14159265358979323846;

void require(bool valid, const std::string& parameter, const std::string& what, double value) {
  if (valid && std::isfinite(value)) return;
  char got[32];
  std::snprintf(got, sizeof got, "%g", value);
  throw ModelError("tire parameter '" + parameter + "' " + what + " (got " + got + ")");
}

}  // namespace

void TireParameters::check() const {
  require(elements >= 8, "elements", "must be at least 8 (100 resolves the contact patch)", elements);
  require(outer_diameter > 0, "outer_diameter", "must be positive", outer_diameter);
  require(rim_diameter > 0, "rim_diameter", "must be positive", rim_diameter);
  require(rim_diameter < outer_diameter, "rim_diameter", "must be smaller than outer_diameter", rim_diameter);
  require(tread_width > 0, "tread_width", "must be positive", tread_width);
  require(pressure >= 0, "pressure", "must be zero or positive", pressure);
  require(rim_mass > 0, "rim_mass", "must be positive (the spindle needs mass in dynamics)", rim_mass);
  require(rim_rotary_inertia > 0, "rim_rotary_inertia", "must be positive", rim_rotary_inertia);
  require(tread.axial_stiffness > 0, "tread_EA", "must be positive", tread.axial_stiffness);
  require(tread.shear_stiffness > 0, "tread_GA", "must be positive", tread.shear_stiffness);
  require(tread.bending_stiffness > 0, "tread_EI", "must be positive", tread.bending_stiffness);
  require(tread.mass_per_length > 0, "tread_mass_per_length", "must be positive", tread.mass_per_length);
  require(tread.rotary_inertia_per_length >= 0, "tread_rotary_inertia_per_length", "must not be negative",
          tread.rotary_inertia_per_length);
  require(tread.curvature_damping >= 0, "tread_curvature_damping", "must not be negative", tread.curvature_damping);
  require(sidewall.cord_length > 0, "sidewall_length", "must be positive", sidewall.cord_length);
  const double rim_to_tread = 0.5 * (outer_diameter - rim_diameter);
  // The reference cord must be a true arch: shorter than the cord by the straight-cord margin.
  const double alpha = sidewall.straight_cord_half_angle;
  require(rim_to_tread < sidewall.cord_length * std::sin(alpha) / alpha, "sidewall_length",
          "must exceed the rim-to-tread distance (outer_diameter - rim_diameter)/2 = " +
              std::to_string(rim_to_tread * 1e3).substr(0, 5) + " mm with some slack, or the sidewall has no arch",
          sidewall.cord_length);
  require(sidewall.bending_stiffness >= 0, "k_sw", "must not be negative", sidewall.bending_stiffness);
  require(sidewall.shear_stiffness >= 0, "k_gamma", "must not be negative", sidewall.shear_stiffness);
  require(std::abs(sidewall.bending_sign) == 1.0, "k_sw_sign", "must be +1 or -1", sidewall.bending_sign);
  require(sidewall.radial_damping >= 0, "sidewall_radial_damping", "must not be negative", sidewall.radial_damping);
  require(sidewall.circumferential_damping >= 0, "sidewall_circumferential_damping", "must not be negative",
          sidewall.circumferential_damping);
  if (tread_layer.enabled()) {
    require(tread_layer.radial_stiffness > 0, "tread_layer_radial_stiffness",
            "must be positive when the tread layer is on", tread_layer.radial_stiffness);
    require(tread_layer.circumferential_stiffness > 0, "tread_layer_circumferential_stiffness",
            "must be positive when the tread layer is on", tread_layer.circumferential_stiffness);
    require(tread_layer.mass_per_length >= 0, "tread_layer_mass_per_length", "must not be negative",
            tread_layer.mass_per_length);
  } else {
    require(tread_layer.mass_per_length == 0, "tread_layer_mass_per_length", "needs the tread layer's stiffnesses",
            tread_layer.mass_per_length);
    require(tread_layer.radial_damping == 0, "tread_layer_radial_damping", "needs the tread layer's stiffnesses",
            tread_layer.radial_damping);
    require(tread_layer.circumferential_damping == 0, "tread_layer_circumferential_damping",
            "needs the tread layer's stiffnesses", tread_layer.circumferential_damping);
  }
}

Tire build_tire(Model& model, const TireParameters& parameters, LoadFunction pressure_ramp, const std::string& name) {
  parameters.check();
  Tire tire;
  tire.name = name;
  tire.parameters = parameters;
  tire.pressure = std::make_shared<PressureSchedule>(parameters.pressure, std::move(pressure_ramp));

  Mesh& mesh = model.mesh();
  const int count = parameters.elements;
  const double radius = 0.5 * parameters.outer_diameter;
  tire.spindle = mesh.add_node(parameters.centre);
  for (int i = 0; i < count; ++i) {
    const double angle = 2.0 * kPi * i / count;
    tire.tread_nodes.push_back(
        mesh.add_node(parameters.centre + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle))));
  }
  mesh.define_node_set(name + "_spindle", {tire.spindle});
  mesh.define_node_set(name + "_tread", tire.tread_nodes);

  SidewallProperties sidewall = parameters.sidewall;
  sidewall.rim_radius = 0.5 * parameters.rim_diameter;
  // The tread rubber's mass moves with the belt: the layer's road side is massless
  // (contact/tread_contact.hpp), its mass redistributed to the belt nodes.
  BeamSection belt = parameters.tread;
  belt.mass_per_length += parameters.tread_layer.mass_per_length;
  auto& treads = model.add_block<TreadBeam>(name + "_tread");
  auto& sidewalls = model.add_block<SidewallWedge>(name + "_sidewall");
  auto& pressures = model.add_block<TreadPressure>(name + "_pressure");
  for (int i = 0; i < count; ++i) {
    const int a = tire.tread_nodes[i], b = tire.tread_nodes[(i + 1) % count];
    const Eigen::Vector2d& xa = mesh.position(a);
    const Eigen::Vector2d& xb = mesh.position(b);
    treads.add({a, b}, TreadBeam(xa, xb, belt));
    sidewalls.add({tire.spindle, a, b}, SidewallWedge(parameters.centre, xa, xb, sidewall, tire.pressure));
    pressures.add({a, b}, TreadPressure(xa, xb, parameters.tread_width, tire.pressure));
  }
  SpringMassProperties rim;
  rim.mass = parameters.rim_mass;
  rim.rotary_inertia = parameters.rim_rotary_inertia;
  model.add_block<NodalSpringMass>(name + "_rim").add({tire.spindle}, NodalSpringMass(rim));
  return tire;
}

}  // namespace tirefe

namespace tirefe {

TreadRubber tread_rubber(const TireParameters& parameters, double friction) {
  const TreadLayerParameters& layer = parameters.tread_layer;
  if (!layer.enabled())
    throw ModelError(
        "the tire touches the road through its tread rubber: give tread_layer_radial_stiffness and "
        "tread_layer_circumferential_stiffness (docs/tire.md)");
  TreadRubber rubber;
  rubber.normal_stiffness = layer.radial_stiffness;
  rubber.tangential_stiffness = layer.circumferential_stiffness;
  rubber.normal_damping = layer.radial_damping;
  rubber.tangential_damping = layer.circumferential_damping;
  rubber.friction = friction;
  return rubber;
}

}  // namespace tirefe
