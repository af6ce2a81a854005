// The inflated 145 SR-12 on a road: quasi-static force-deflection on a flat road and on the
// 1.7 m drum (stiffness, convergence, penetration, patch), loading with and without
// friction, steady free rolling on a moving road, rolling over a bump's edges, and a clear
// failure for a tread node jammed against a cleat wall.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "contact/node_contact.hpp"
#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "tire/contact_penalty.hpp"
#include "tire/tire_builder.hpp"

using namespace tirefe;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTolerance = 5e-4;  // the contact's penetration tolerance [m]

/// One accepted step of a loading run.
struct LoadPoint {
  double deflection = 0.0;  // spindle travel since first touch [m]
  double load = 0.0;        // vertical spindle force, upwards on the road [N]
  ContactSummary contact;
  int newton_iterations = 0;
  int cuts = 0;
  std::vector<std::pair<double, double>> forces;  // per tread node: x - x_spindle [m], t_N [N]
};

/// The 145 SR-12 inflated to 208 kPa on a held hub (t in [0, 1]); a surface touching its
/// lowest tread node is added with contact() and the spindle pressed down by press().
struct TireOnRoad {
  Model model;
  Tire tire;
  std::unique_ptr<Analysis> analysis;
  ContactBlock* contact = nullptr;
  int press_function = -1;
  double lowest = 0.0;  // y of the lowest tread point after inflation [m]
  double inflated_radius = 0.0;

  explicit TireOnRoad(int elements = 100) {
    TireParameters parameters = macros::load_tire_parameters("tires.145SR12");
    parameters.elements = elements;
    tire = build_tire(model, parameters, LoadFunction::table({{0.0, 0.0}, {1.0, 1.0}}));
    for (int c = 0; c < kDofsPerNode; ++c) model.fix(tire.spindle, c);
    press_function = model.add_load_function(LoadFunction::table({{1.0, 0.0}, {2.0, 1.0}}));
    analysis = std::make_unique<Analysis>(model);
    analysis->set_time_step(0.25);
    analysis->advance(1.0);
    lowest = 1e9;
    for (int node : tire.tread_nodes) lowest = std::min(lowest, position(node).y());
    inflated_radius = -lowest;
  }

  Eigen::Vector2d position(int node) const {
    return model.mesh().position(node) + analysis->state().displacement.segment<2>(dof_index(node, 0));
  }

  /// Contact with penalties scaled from the inflated tire (docs/contact.md).
  void add_contact(std::shared_ptr<const RigidSurface> surface, double friction) {
    ContactParameters parameters;
    parameters.friction = friction;
    parameters.normal_penalty = structural_penalty(*analysis, tire.tread_nodes);
    parameters.tangential_penalty = structural_tangential_penalty(*analysis, tire.tread_nodes, *surface);
    contact =
        &add_contact_block(model, "contact", std::move(surface), tire.tread_nodes, parameters, analysis->state().time);
  }

  /// Presses the spindle down to 'deepest' in 'steps' quasi-static steps (t from 1 to 2).
  std::vector<LoadPoint> press(double deepest, int steps) {
    model.prescribe(tire.spindle, kUy, -deepest, press_function);
    std::vector<LoadPoint> points;
    analysis->set_time_step(1.0 / steps);
    for (int i = 1; i <= steps; ++i) {
      const StepRecord record = analysis->advance().back();
      points.push_back(load_point(record));
    }
    return points;
  }

  LoadPoint load_point(const StepRecord& record) const {
    LoadPoint point;
    point.deflection = -analysis->state().displacement[dof_index(tire.spindle, kUy)];
    point.load = -analysis->reactions()[dof_index(tire.spindle, kUy)];
    point.contact = summarize_contact(*contact);
    point.newton_iterations = record.newton_iterations;
    point.cuts = record.cuts;
    point.forces = contact_forces();
    return point;
  }

  /// Horizontal offset of each tread node from the spindle and its normal force.
  std::vector<std::pair<double, double>> contact_forces() const {
    std::vector<std::pair<double, double>> forces;
    const double spindle_x = position(tire.spindle).x();
    for (int i = 0; i < contact->size(); ++i)
      forces.emplace_back(position(tire.tread_nodes[i]).x() - spindle_x, contact->committed_history(i).normal_force);
    return forces;
  }
};

std::shared_ptr<FlatRoad> flat_road_at(double y, RigidMotion motion = {}) {
  return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, y), Eigen::Vector2d::UnitX(), std::move(motion));
}

}  // namespace

TEST_CASE("145 SR-12 on a flat road: force-deflection to 30 mm, stiffness near 3800 N, patch growth",
          "[road][contact][tire]") {
  // Displacement-controlled spindle, frictionless road, 2 mm steps.
  TireOnRoad coarse(100), fine(200);
  std::vector<LoadPoint> curves[2];
  TireOnRoad* tires[2] = {&coarse, &fine};
  for (int m = 0; m < 2; ++m) {
    tires[m]->add_contact(flat_road_at(tires[m]->lowest), 0.0);
    curves[m] = tires[m]->press(0.030, 15);
  }
  const std::vector<LoadPoint>& curve = curves[0];
  for (int m = 0; m < 2; ++m) {
    double previous = 0.0;
    for (const LoadPoint& point : curves[m]) {
      INFO("elements " << tires[m]->tire.tread_nodes.size() << ", deflection " << point.deflection);
      CHECK(point.load > previous);  // monotone
      previous = point.load;
      CHECK(point.cuts == 0);  // converged at once
      CHECK(point.newton_iterations <= 6);
      CHECK(point.contact.max_penetration <= kTolerance);
      // The road carries the spindle load, straight up.
      CHECK(point.contact.force.y() == Approx(point.load).epsilon(1e-8));
      CHECK(std::abs(point.contact.force.x()) <= 1e-8 * point.load);
    }
  }
  // Mesh convergence of the load: 100 against 200 elements.
  WARN("load at 20 mm: " << curves[0][9].load << " N (100 elements), " << curves[1][9].load
                         << " N (200); at 30 mm: " << curves[0][14].load << " N, " << curves[1][14].load << " N");
  CHECK(curves[0][9].load == Approx(curves[1][9].load).epsilon(0.01));
  CHECK(curves[0][14].load == Approx(curves[1][14].load).epsilon(0.01));

  // Vertical stiffness at 3800 N: the secant through the neighbouring steps.
  size_t i = 1;
  while (curve[i].load < 3800.0) ++i;
  const double tangent = (curve[i].load - curve[i - 1].load) / (curve[i].deflection - curve[i - 1].deflection);
  const double deflection_3800 = curve[i - 1].deflection + (3800.0 - curve[i - 1].load) / tangent;
  WARN("145 SR-12, flat road, 208 kPa: 3800 N at " << deflection_3800 * 1e3 << " mm, secant " << 3.8 / deflection_3800
                                                   << " N/mm, tangent " << tangent / 1e3 << " N/mm (Rhyne: 194 N/mm)");
  CHECK(tangent / 1e3 >= 150.0);
  CHECK(tangent / 1e3 <= 250.0);
  CHECK(3.8 / deflection_3800 >= 150.0);
  CHECK(3.8 / deflection_3800 <= 250.0);

  // Patch (200 elements: nodes 8.5 mm apart): grows with the deflection, symmetric about
  // the spindle, and shorter than the chord 2 sqrt(2 R delta) of the undeformed circle cut
  // by the road: the tread ring flattens over a part of the chord only (docs/tire.md).
  const std::vector<LoadPoint>& patch_curve = curves[1];
  for (size_t k = 1; k < patch_curve.size(); ++k) {
    const LoadPoint& point = patch_curve[k];
    // More nodes touch as the load grows; a patch of given nodes shortens only by the
    // belt's compression (micrometres).
    CHECK(point.contact.nodes_in_contact >= patch_curve[k - 1].contact.nodes_in_contact);
    CHECK(point.contact.patch_length >= patch_curve[k - 1].contact.patch_length - 1e-5);
    const double chord = 2.0 * std::sqrt(2.0 * fine.inflated_radius * point.deflection);
    CHECK(point.contact.patch_length < 0.5 * chord);
  }
  for (int step : {9, 14}) {  // 20 and 30 mm
    const double chord = 2.0 * std::sqrt(2.0 * fine.inflated_radius * patch_curve[step].deflection);
    WARN("deflection " << patch_curve[step].deflection * 1e3 << " mm: patch "
                       << patch_curve[step].contact.patch_length * 1e3 << " mm, chord " << chord * 1e3 << " mm");
    CHECK(patch_curve[step].contact.patch_length > 0.2 * chord);
  }
  const auto forces = fine.contact_forces();
  for (const auto& [x, normal] : forces) {
    if (normal == 0.0) continue;
    // Every contact node has its mirror image across the spindle with the same force.
    bool mirrored = false;
    for (const auto& [x2, normal2] : forces)
      mirrored = mirrored || (std::abs(x + x2) < 1e-9 && std::abs(normal - normal2) <= 1e-6 * normal);
    CHECK(mirrored);
  }
}

namespace {

/// Largest difference between the assembled static tangent of 'loaded' at its current
/// displacements and central differences of the assembled residual, relative to the
/// tangent's largest entry; evaluated 'later' after the current time (the road moving on).
double tangent_error(TireOnRoad& loaded, double later = 0.0) {
  Analysis& analysis = *loaded.analysis;
  Assembler& assembler = analysis.assembler();
  const DofMap& dofs = loaded.model.dof_map();
  EvaluationContext context;  // quasi-static: K alone
  context.time = analysis.state().time + later;
  State state = analysis.state();
  Eigen::VectorXd residual, plus, minus;
  assembler.assemble(context, state, residual);
  const Eigen::MatrixXd tangent = Eigen::MatrixXd(assembler.tangent());
  const int equations = dofs.equation_count();
  Eigen::MatrixXd numerical(equations, equations);
  const double step = 1e-8;  // m and rad: the deflections are of order 1e-2
  for (int column = 0; column < equations; ++column) {
    const int dof = dofs.dof(column);
    state.displacement[dof] += step;
    assembler.assemble(context, state, plus);
    state.displacement[dof] -= 2.0 * step;
    assembler.assemble(context, state, minus);
    state.displacement[dof] += step;
    for (int row = 0; row < equations; ++row)
      numerical(row, column) = (plus[dofs.dof(row)] - minus[dofs.dof(row)]) / (2.0 * step);
  }
  loaded.model.revert_history();  // the evaluations leave no trial history behind
  return (tangent - numerical).cwiseAbs().maxCoeff() / tangent.cwiseAbs().maxCoeff();
}

int nodes_in_state(const ContactBlock& contact, ContactState state) {
  int count = 0;
  for (int i = 0; i < contact.size(); ++i) count += contact.committed_history(i).state == state ? 1 : 0;
  return count;
}

}  // namespace

TEST_CASE("tire in contact: the assembled tangent equals finite differences, sticking and slipping",
          "[road][contact][tire][tangent]") {
  // Pressed 20 mm with friction 0.3: the patch sticks. Then the road slides 10 mm under the
  // held tire (quasi-static, t from 2 to 3): the patch slips. The tangent is unsymmetric
  // (follower pressure, sidewall shear, friction); its largest entries are about 1e8 N/m.
  // At an accepted state a slipping node sits exactly on the friction cone (its stick
  // point has just been moved there), where a difference quotient straddles stick and slip;
  // so the slipping patch is differentiated 0.1 mm of road travel later, well inside slip,
  // as within a step's Newton iterations.
  TireOnRoad loaded(60);
  const int slide = loaded.model.add_load_function(LoadFunction::table({{2.0, 0.0}, {3.0, 1.0}, {4.0, 2.0}}));
  loaded.add_contact(flat_road_at(loaded.lowest, RigidMotion::translation(MotionFunction::from_load_function(
                                                     loaded.model.load_function(slide), 0.01))),
                     0.3);
  loaded.press(0.020, 5);
  REQUIRE(nodes_in_state(*loaded.contact, ContactState::Stick) >= 3);
  CHECK(tangent_error(loaded) < 1e-6);

  loaded.analysis->set_time_step(0.25);
  loaded.analysis->advance(1.0);
  REQUIRE(nodes_in_state(*loaded.contact, ContactState::Slip) >= 3);
  CHECK(tangent_error(loaded, 0.01) < 1e-6);
}

TEST_CASE("145 SR-12 on the 1.7 m drum is slightly softer than on a flat road", "[road][contact][tire]") {
  // Same tire, same spindle travel from first touch. The drum's surface falls away from
  // the flat road's by h = x^2 / (2 R_d) under a contact node at x, which unloads the tire.
  // Two first-order estimates of the loss bracket it:
  //  - the patch as a rigid punch: the load-weighted mean drop, times the tangent stiffness,
  //    K sum(N_i h_i) / sum(N_i) (too small: the edge nodes, which the drum lowers most,
  //    carry more of each load increment than of the load);
  //  - by reciprocity, the load increment per unit spindle travel that each node takes,
  //    sum(dN_i/d delta h_i), with dN_i/d delta by central differences of the flat road's
  //    steps (too large: it counts in full the nodes about to touch down, which the drum
  //    reaches later or not at all).
  const double drum_radius = 0.85;
  TireOnRoad flat, drum;
  flat.add_contact(flat_road_at(flat.lowest), 0.0);
  drum.add_contact(std::make_shared<Drum>(2.0 * drum_radius, Eigen::Vector2d(0.0, drum.lowest - drum_radius),
                                          MotionFunction::constant(0.0)),
                   0.0);
  const std::vector<LoadPoint> on_flat = flat.press(0.030, 15), on_drum = drum.press(0.030, 15);
  for (size_t step = 0; step < on_flat.size(); ++step) {
    CHECK(on_drum[step].load <= on_flat[step].load * (1.0 + 1e-9));
    CHECK(on_drum[step].load >= 0.94 * on_flat[step].load);
    CHECK(on_drum[step].contact.max_penetration <= kTolerance);
  }
  for (int step : {9, 13}) {  // 20 and 28 mm
    const LoadPoint &before = on_flat[step - 1], &point = on_flat[step], &after = on_flat[step + 1];
    const double stiffness = (after.load - before.load) / (after.deflection - before.deflection);
    double punch = 0.0, increments = 0.0;
    for (size_t i = 0; i < point.forces.size(); ++i) {
      const double drop = point.forces[i].first * point.forces[i].first / (2.0 * drum_radius);
      punch += stiffness * point.forces[i].second * drop / point.load;
      increments += (after.forces[i].second - before.forces[i].second) / (after.deflection - before.deflection) * drop;
    }
    const double softening = point.load - on_drum[step].load;
    WARN("deflection " << point.deflection * 1e3 << " mm: flat " << point.load << " N, drum " << on_drum[step].load
                       << " N, softer by " << softening << " N (estimates " << punch << " to " << increments << " N)");
    CHECK(softening > 0.9 * punch);
    CHECK(softening < 1.1 * increments);
  }
}

TEST_CASE("145 SR-12 pressed with friction: slightly stiffer, symmetric, within the friction cone",
          "[road][contact][tire][friction]") {
  // Touching nodes stick where they land and are held against the sideways spread of the
  // flattening tread: a constraint added to the frictionless problem, so the loads can only
  // rise, and by little (the tread barely slides).
  const double mu = 0.3;
  TireOnRoad smooth, rough;
  smooth.add_contact(flat_road_at(smooth.lowest), 0.0);
  rough.add_contact(flat_road_at(rough.lowest), mu);
  const std::vector<LoadPoint> frictionless = smooth.press(0.030, 15), frictional = rough.press(0.030, 15);
  for (size_t k = 0; k < frictional.size(); ++k) {
    INFO("deflection " << frictional[k].deflection);
    CHECK(frictional[k].load >= frictionless[k].load * (1.0 - 1e-9));
    CHECK(frictional[k].load <= frictionless[k].load * 1.001);
    CHECK(frictional[k].contact.max_penetration <= kTolerance);
    CHECK(std::abs(frictional[k].contact.force.x()) <= 1e-6 * frictional[k].load);
  }
  WARN("30 mm: " << frictionless.back().load << " N frictionless, " << frictional.back().load << " N with mu = " << mu);
  double largest_ratio = 0.0;
  for (int i = 0; i < rough.contact->size(); ++i) {
    const ContactHistory& h = rough.contact->committed_history(i);
    if (h.state == ContactState::Open) continue;
    CHECK(std::abs(h.tangential_force) <= mu * h.normal_force * (1.0 + 1e-9));
    largest_ratio = std::max(largest_ratio, std::abs(h.tangential_force) / h.normal_force);
  }
  WARN("largest |t_T| / t_N at 30 mm: " << largest_ratio);
  CHECK(largest_ratio > 1e-3);  // friction is at work
}

TEST_CASE("145 SR-12 rolling freely on a moving road: spin rate = speed / effective rolling radius",
          "[road][contact][tire][dynamics]") {
  // Pressed 20 mm on a road that then accelerates to 5 m/s in 0.15 s and holds; the spindle
  // is held in x and y, its spin free; HHT-alpha. In steady rolling the tread nodes stick
  // in the patch and move with the road, so one turn passes all N nodes at their spacing l
  // in the patch: the effective rolling radius is v / omega = N l / (2 pi), kinematically.
  const double speed = 5.0, ramp = 0.15, hold = 0.15, deflection = 0.020;
  TireOnRoad rolling;
  rolling.add_contact(
      flat_road_at(rolling.lowest, RigidMotion::translation(MotionFunction::ramped_rate(-speed, ramp, 2.0))), 0.3);
  const double static_load = rolling.press(deflection, 10).back().load;
  rolling.model.release(rolling.tire.spindle, kRz);
  rolling.analysis->set_integrator(Integrator::hht(-0.1));
  rolling.analysis->set_time_step(5e-4);
  const int spin = dof_index(rolling.tire.spindle, kRz);
  double spin_sum = 0.0, load_sum = 0.0, drag_sum = 0.0;
  int samples = 0;
  rolling.analysis->add_step_observer([&](const Analysis& run, const StepRecord& record) {
    CHECK(summarize_contact(*rolling.contact).max_penetration <= kTolerance);
    if (record.time > 2.0 + ramp + 0.05) {  // after the start-up transient
      spin_sum += run.state().velocity[spin];
      load_sum += -run.reactions()[dof_index(rolling.tire.spindle, kUy)];
      drag_sum += run.reactions()[dof_index(rolling.tire.spindle, kUx)];
      ++samples;
    }
  });
  rolling.analysis->advance(ramp + hold);
  const double spin_rate = -spin_sum / samples;  // the road moves to -x: the tire turns clockwise
  const double rolling_radius = speed / spin_rate;

  // Node spacing in the patch: the sticking nodes, in order along the road.
  std::vector<double> xs;
  for (int i = 0; i < rolling.contact->size(); ++i)
    if (rolling.contact->committed_history(i).state == ContactState::Stick)
      xs.push_back(rolling.position(rolling.tire.tread_nodes[i]).x());
  REQUIRE(xs.size() >= 3);
  std::sort(xs.begin(), xs.end());
  const double spacing = (xs.back() - xs.front()) / (xs.size() - 1);
  const double kinematic_radius = rolling.tire.tread_nodes.size() * spacing / (2.0 * kPi);
  const double loaded_radius = rolling.inflated_radius - deflection;
  WARN("rolling at " << speed << " m/s, " << load_sum / samples << " N: spin " << spin_rate
                     << " rad/s, effective radius " << rolling_radius * 1e3 << " mm (N l / 2 pi "
                     << kinematic_radius * 1e3 << " mm; loaded " << loaded_radius * 1e3 << " mm, unloaded "
                     << rolling.inflated_radius * 1e3 << " mm); drag " << drag_sum / samples << " N");
  CHECK(rolling_radius > loaded_radius);
  CHECK(rolling_radius < rolling.inflated_radius);
  CHECK(rolling_radius == Approx(kinematic_radius).epsilon(2e-3));
  // The load of the static press: rolling at 5 m/s adds little (centrifugal hoop tension).
  CHECK(load_sum / samples == Approx(static_load).epsilon(0.01));
}

TEST_CASE("a tread node jammed against a vertical cleat wall ends the run with a StepFailure",
          "[road][contact][failure]") {
  // The spindle is held and the road frictionless: a pressed tread node cannot climb a
  // vertical wall quasi-statically. Steps that scrape through at tiny sizes must not let the
  // step dwindle without end: the run stops below the nominal step / 4^max_cuts.
  TireOnRoad tire;
  tire.add_contact(std::make_shared<RoadProfile>(RoadProfile::cleat_points(0.15, 0.2, 0.01, tire.lowest), 0.0,
                                                 RigidMotion::translation(MotionFunction::ramped_rate(-0.5, 0.0, 2.0))),
                   0.0);
  tire.press(0.020, 10);
  tire.analysis->step_control().max_cuts = 6;
  tire.analysis->set_time_step(0.004);
  int accepted = 0;
  double smallest = 1.0;
  tire.analysis->add_step_observer([&](const Analysis&, const StepRecord& record) {
    ++accepted;
    smallest = std::min(smallest, record.step_size);
  });
  CHECK_THROWS_AS(tire.analysis->advance(1.0), StepFailure);
  CHECK(smallest >= 0.004 / 4096 * (1.0 - 1e-9));
  CHECK(accepted < 1000);
  CHECK(tire.analysis->state().displacement.allFinite());
}

TEST_CASE("145 SR-12 rolling over a bump: tread nodes pass its rounded and sharp edges converged, outside the road",
          "[road][contact][tire][vertex][dynamics]") {
  // Pressed 20 mm on a road that accelerates to 5 m/s in 0.1 s and carries a 10 mm bump
  // (45 degree ramps, sharp feet, a 100 mm top whose edges are sharp or rounded) under the
  // freely spinning tire (spindle held in x and y; HHT, mu = 0.3). Every step converges,
  // no node penetrates beyond the tolerance, the load peaks near the flat road's at 30 mm
  // (the top is as long as the patch there) without spikes, and returns to the static load.
  const double height = 0.010, top = 0.100, start = 0.35, deflection = 0.020;
  TireOnRoad reference;
  reference.add_contact(flat_road_at(reference.lowest), 0.0);
  const double load_30 = reference.press(0.030, 15).back().load;
  for (double edge_radius : {0.005, 0.0}) {
    INFO("edge radius " << edge_radius);
    TireOnRoad tire;
    const double y = tire.lowest;
    const std::vector<Eigen::Vector2d> bump = {{-1.0, y},
                                               {start, y},
                                               {start + height, y + height},
                                               {start + height + top, y + height},
                                               {start + 2 * height + top, y},
                                               {3.0, y}};
    tire.add_contact(std::make_shared<RoadProfile>(
                         bump, edge_radius, RigidMotion::translation(MotionFunction::ramped_rate(-5.0, 0.1, 2.0))),
                     0.3);
    const double static_load = tire.press(deflection, 10).back().load;
    tire.model.release(tire.tire.spindle, kRz);
    tire.analysis->set_integrator(Integrator::hht(-0.1));
    tire.analysis->set_time_step(5e-4);
    double largest = 0.0, smallest = 1e9;
    int cuts = 0;
    tire.analysis->add_step_observer([&](const Analysis& run, const StepRecord& record) {
      const double load = -run.reactions()[dof_index(tire.tire.spindle, kUy)];
      CHECK(std::isfinite(load));
      CHECK(summarize_contact(*tire.contact).max_penetration <= kTolerance);
      largest = std::max(largest, load);
      smallest = std::min(smallest, load);
      cuts += record.cuts;
    });
    tire.analysis->advance(0.25);  // the road travels 1 m: the bump passes
    const double final_load = -tire.analysis->reactions()[dof_index(tire.tire.spindle, kUy)];
    WARN("edge radius " << edge_radius * 1e3 << " mm: static " << static_load << " N, over the bump " << smallest
                        << " to " << largest << " N (flat road at 30 mm " << load_30 << " N), after " << final_load
                        << " N, cuts " << cuts);
    CHECK(largest > 0.95 * load_30);
    CHECK(largest < 1.1 * load_30);
    CHECK(smallest > 0.85 * static_load);
    CHECK(final_load == Approx(static_load).epsilon(0.02));
  }
}
