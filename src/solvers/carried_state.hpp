// CarriedState: everything an Analysis carries from one accepted step to the next. With
// the element histories and the deck's settings it continues a run bit for bit, so it is
// what a snapshot copies, a restore puts back and a checkpoint writes (docs/restart.md).
// for_each_field() is its one field list: adding a field there is all a checkpoint needs.
#pragma once

#include <Eigen/Core>

#include "core/state.hpp"
#include "core/step_record.hpp"
#include "solvers/integrators/time_scheme.hpp"

namespace tirefe {

/// The sizes of the steps: the deck's, and the next one (smaller after cuts, growing back).
struct StepSizes {
  double nominal = 1.0;
  double current = 1.0;
};

struct CarriedState {
  State state;  // committed u, v, a and time
  StepSizes steps;
  Eigen::VectorXd external_old;         // F_n, the loads at the committed time
  Eigen::VectorXd old_internal_forces;  // g_n = f_int(u_n) + C v_n, HHT's weighting
  Eigen::VectorXd old_inertia_forces;   // M a_n, generalized-alpha's (alpha_m != 0)
  Eigen::VectorXd reactions;            // at prescribed and driven DOFs, zero elsewhere
  Eigen::VectorXd dashpot_forces;       // C v_n of the blocks with dashpots, for the energy balance
  Eigen::VectorXd unstored_forces;      // f_n of the blocks that store no energy, for the energy balance
  bool old_forces_valid = false;        // the old forces belong to the committed state
  bool acceleration_pending = false;    // the committed acceleration is to be put in equilibrium
  bool reactions_valid = false;         // reactions belong to the committed state
  bool energy_started = false;
  EnergyRecord energy;
  int accepted_steps = 0;
  // The scheme the state was carried with: a restore checks it against the deck's.
  SchemeRecord integrator;

  /// Calls visit(path, field) for every field, with the field's place in a checkpoint
  /// file: a dataset for a vector, an attribute "<object>/<name>" for a number or flag.
  template <class Self, class Visit>
  static void for_each_field(Self& self, Visit&& visit) {
    visit("/time", self.state.time);
    visit("/steps", self.accepted_steps);
    visit("/analysis/displacement", self.state.displacement);
    visit("/analysis/velocity", self.state.velocity);
    visit("/analysis/acceleration", self.state.acceleration);
    visit("/analysis/external_old", self.external_old);
    visit("/analysis/old_internal_forces", self.old_internal_forces);
    visit("/analysis/reactions", self.reactions);
    visit("/analysis/nominal_step", self.steps.nominal);
    visit("/analysis/current_step", self.steps.current);
    visit("/analysis/beta", self.integrator.beta);
    visit("/analysis/gamma", self.integrator.gamma);
    visit("/analysis/alpha", self.integrator.alpha);
    visit("/analysis/energy_kinetic", self.energy.kinetic);
    visit("/analysis/energy_strain", self.energy.strain);
    visit("/analysis/external_work", self.energy.external_work);
    visit("/analysis/energy_initial", self.energy.initial);
    visit("/analysis/energy_dissipated", self.energy.dissipated);
    visit("/analysis/dashpot_forces", self.dashpot_forces);
    visit("/analysis/unstored_forces", self.unstored_forces);
    visit("/analysis/surface_work", self.energy.surface_work);
    visit("/analysis/unstored_work", self.energy.unstored_work);
    visit("/analysis/energy_damping", self.energy.damping);
    visit("/analysis/contact_dissipated", self.energy.contact_dissipated);
    visit("/analysis/balance_error", self.energy.balance_error);
    visit("/analysis/supplied_at_start", self.energy.supplied_at_start);
    visit("/analysis/contact_dissipated_at_start", self.energy.contact_dissipated_at_start);
    visit("/analysis/old_forces_valid", self.old_forces_valid);
    visit("/analysis/acceleration_pending", self.acceleration_pending);
    visit("/analysis/reactions_valid", self.reactions_valid);
    visit("/analysis/energy_started", self.energy_started);
    visit("/analysis/integrator_kind", self.integrator.kind);
    visit("/analysis/alpha_m", self.integrator.alpha_m);
    visit("/analysis/old_inertia_forces", self.old_inertia_forces);
  }
};

}  // namespace tirefe
