// What a run records of an accepted step: its number, time, size, Newton iterations, cuts
// and energies. The solvers fill it; the result file's history channels and the progress
// line read it, so it lives below both.
#pragma once

namespace tirefe {

/// Energies at the end of an accepted step; initial + external_work = kinetic + strain + dissipated.
struct EnergyRecord {
  double kinetic = 0.0;        // v.M v / 2
  double strain = 0.0;         // sum of the element blocks' stored energy
  double external_work = 0.0;  // of nodal loads and support reactions since the start
  double initial = 0.0;        // kinetic + strain at the start of the analysis
  double dissipated = 0.0;     // initial + external_work - kinetic - strain
  // The balance closed term by term (energy_balance.hpp), since the start:
  double surface_work = 0.0;        // done on the structure by moving surfaces, through contacts
  double unstored_work = 0.0;       // done on it by element forces that store no energy
  double damping = 0.0;             // dissipated by the elements' dashpots
  double contact_dissipated = 0.0;  // dissipated by friction and the contacts' dashpots
  double balance_error = 0.0;       // kinetic + strain + damping + contact - initial - external - surface - unstored
  // The contacts' own accounts when the balance started (their histories carry them).
  double supplied_at_start = 0.0, contact_dissipated_at_start = 0.0;
};

struct StepRecord {
  int step = 0;       // accepted steps since the start
  double time = 0.0;  // at the end of the step
  double step_size = 0.0;
  int newton_iterations = 0;
  int cuts = 0;           // cuts taken before this step converged
  int augmentations = 0;  // augmented-Lagrangian multiplier updates
  double residual = 0.0;  // final |R|
  EnergyRecord energy;    // at the end of the step
};

}  // namespace tirefe
