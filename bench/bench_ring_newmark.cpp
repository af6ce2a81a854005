// Benchmark: Newmark free vibration of a free tire-like ring of 100 tread beams, started
// with an n = 2 velocity field; then the cost of one Newton iteration split into
// assembly, KLU factorization and triangular solve, each timed on the final tangent.
//
// Inextensible n = 2 shape on the ring of radius R: v_r = V cos 2t, v_t = -(V/2) sin 2t,
// cross-section spin (v_t - dv_r/dt) / R = 1.5 V sin 2t / R (t the polar angle).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "elements/beam_mesh.hpp"
#include "solvers/analysis.hpp"

using namespace tirefe;

namespace {

constexpr double kPi = 3.14159265358979323846;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// Mean wall time of one call of 'work' in microseconds over 'repetitions' calls.
template <class Work>
double microseconds_per_call(int repetitions, Work&& work) {
  work();  // warm-up
  const Clock::time_point start = Clock::now();
  for (int i = 0; i < repetitions; ++i) work();
  return 1e6 * seconds_since(start) / repetitions;
}

}  // namespace

int main() {
  const int elements = 100, steps = 3000, repetitions = 2000;
  const double radius = 0.27, time_step = 1e-4, speed = 1.0;  // V [m/s]
  BeamSection section;
  section.axial_stiffness = 3e5;
  section.shear_stiffness = 8e4;
  section.bending_stiffness = 20.0;
  section.mass_per_length = 1.5;
  // rho I = rho A * EI / EA: the rotary inertia of a solid section with these stiffnesses.
  section.rotary_inertia_per_length = section.mass_per_length * section.bending_stiffness / section.axial_stiffness;

  Model model;
  const std::vector<int> nodes = add_beam_ring(model, "tread", {0.0, 0.0}, radius, elements, section);
  Analysis analysis(model);
  analysis.set_integrator(Integrator::newmark());
  analysis.set_time_step(time_step);
  Eigen::VectorXd velocity = Eigen::VectorXd::Zero(model.mesh().dof_count());
  for (int k = 0; k < elements; ++k) {
    const double angle = 2.0 * kPi * k / elements;
    const double radial = speed * std::cos(2.0 * angle), tangential = -0.5 * speed * std::sin(2.0 * angle);
    velocity[dof_index(nodes[k], kUx)] = radial * std::cos(angle) - tangential * std::sin(angle);
    velocity[dof_index(nodes[k], kUy)] = radial * std::sin(angle) + tangential * std::cos(angle);
    velocity[dof_index(nodes[k], kRz)] = 1.5 * speed * std::sin(2.0 * angle) / radius;
  }
  analysis.set_initial_velocity(velocity);

  const Clock::time_point run_start = Clock::now();
  const std::vector<StepRecord>& records = analysis.advance(steps * time_step);
  const double run_seconds = seconds_since(run_start);
  long iterations = 0;
  int cuts = 0;
  for (const StepRecord& record : records) {
    iterations += record.newton_iterations;
    cuts += record.cuts;
  }
  const EnergyRecord& energy = analysis.energy();

  // One Newton iteration = assemble residual and effective tangent, factorize, solve.
  EvaluationContext context;
  context.time = analysis.state().time;
  context.time_step = time_step;
  context.factors = analysis.integrator().factors(time_step);
  Assembler& assembler = analysis.assembler();
  LinearSolver& solver = analysis.linear_solver();
  Eigen::VectorXd residual, right_hand_side(model.dof_map().equation_count());
  const double assembly =
      microseconds_per_call(repetitions, [&] { assembler.assemble(context, analysis.state(), residual); });
  const double factorization = microseconds_per_call(repetitions, [&] { solver.factorize(assembler.tangent()); });
  const double solve = microseconds_per_call(repetitions, [&] {
    right_hand_side.setOnes();
    solver.solve(right_hand_side);
  });

  std::printf("Free ring, Newmark average acceleration: %d tread beams, %d equations, R = %.2f m, dt = %.0e s\n",
              elements, model.dof_map().equation_count(), radius, time_step);
  std::printf("  %-38s %12d\n", "steps", static_cast<int>(records.size()));
  std::printf("  %-38s %12ld\n", "Newton iterations", iterations);
  std::printf("  %-38s %12.2f\n", "iterations per step", static_cast<double>(iterations) / records.size());
  std::printf("  %-38s %12d\n", "step cuts", cuts);
  std::printf("  %-38s %12.3f\n", "wall time [s]", run_seconds);
  std::printf("  %-38s %12.2f\n", "wall time per Newton iteration [us]", 1e6 * run_seconds / iterations);
  std::printf("  %-38s %12.2e\n", "energy dissipated / initial", energy.dissipated / energy.initial);
  std::printf("  per call, %d repetitions on the final effective tangent [us]:\n", repetitions);
  std::printf("  %-38s %12.2f\n", "assembly (residual + tangent)", assembly);
  std::printf("  %-38s %12.2f\n", "factorization (KLU refactor)", factorization);
  std::printf("  %-38s %12.2f\n", "solve", solve);
  std::printf("  %-38s %12.2f\n", "sum", assembly + factorization + solve);
  return 0;
}
