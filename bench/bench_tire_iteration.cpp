// Cost of one Newton iteration on the 100-element 145 SR-12 tire (303 DOFs), split into
// assembly (all element kernels), KLU refactorisation and triangular solves, at the
// inflated state with a free-spinning hub, Newmark factors of a 1e-4 s step.
//   build/bench_tire_iteration [repetitions]
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "core/assembler.hpp"
#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "tire/tire_builder.hpp"

using namespace tirefe;
using Clock = std::chrono::steady_clock;

namespace {

template <class Work>
double microseconds_per_call(int repetitions, Work&& work) {
  const auto start = Clock::now();
  for (int i = 0; i < repetitions; ++i) work();
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count() / repetitions;
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::atoi(argv[1]) : 2000;
  Model model;
  const Tire tire = build_tire(model, macros::load_tire_parameters("tires.145SR12"), LoadFunction::linear());
  model.fix(tire.spindle, kUx);
  model.fix(tire.spindle, kUy);
  Analysis analysis(model);
  analysis.set_time_step(0.5);
  analysis.advance(1.0);  // inflate quasi-statically
  std::printf("tire: %d nodes, %d equations, inflated in %d steps\n", model.mesh().node_count(),
              model.dof_map().equation_count(), analysis.accepted_steps());

  Assembler& assembler = analysis.assembler();
  KluSolver& solver = analysis.linear_solver();
  EvaluationContext context;
  context.time = 1.0;
  const double h = 1e-4;
  context.factors = {1.0, 1.0, 1.0, 1.0, 0.5 / (0.25 * h), 1.0 / (0.25 * h * h)};
  Eigen::VectorXd residual;
  const State& state = analysis.state();
  assembler.assemble(context, state, residual);
  solver.factorize(assembler.tangent());
  Eigen::VectorXd rhs = Eigen::VectorXd::Ones(model.dof_map().equation_count());

  context.want_tangent = true;
  const double assembly = microseconds_per_call(repetitions, [&] { assembler.assemble(context, state, residual); });
  context.want_tangent = false;
  const double residual_only = microseconds_per_call(repetitions, [&] { assembler.assemble(context, state, residual); });
  const double refactor = microseconds_per_call(repetitions, [&] { solver.factorize(assembler.tangent()); });
  const double solve = microseconds_per_call(repetitions, [&] { solver.solve(rhs); });

  std::printf("nonzeros %ld, repetitions %d\n", static_cast<long>(assembler.tangent().nonZeros()), repetitions);
  std::printf("%-36s %10s\n", "per Newton iteration", "us");
  std::printf("%-36s %10.1f\n", "assembly (residual + tangent)", assembly);
  std::printf("%-36s %10.1f\n", "assembly (residual only)", residual_only);
  std::printf("%-36s %10.1f\n", "KLU refactorisation", refactor);
  std::printf("%-36s %10.1f\n", "triangular solve", solve);
  std::printf("%-36s %10.1f\n", "total", assembly + refactor + solve);
  return 0;
}
