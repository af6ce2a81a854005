// Cost of one Newton iteration on the 100-element 145 SR-12 tire, the paper's (303 DOFs)
// and the calibrated one with a tread layer (503: a contact node on each belt node, a
// satellite of it for the RingSolver), split into assembly (all element kernels),
// factorisation and triangular solves, for the general KLU solver and the structured
// RingSolver side by side, plus the RingSolver's spindle condensation (Schur complement
// H and condensed right-hand side f_b). The tire is inflated quasi-statically, then the
// effective tangent of a Newmark step of 1e-4 s is timed, for the spindle free (3 border
// equations), a dead axle (ux, uy fixed: 1) and a fixed spindle (0). The spindle is
// condensed (numbered last).
// Then the same tire on a dead axle pressed 25 mm onto the drum-cleat deck's 1.7 m drum at
// rest, with its contact block (the deck's penalties and friction): the contact pass, the
// assembly with it, and a whole Newton iteration as the deck takes it (the tangent assembled
// into the RingSolver's blocks, the factorisation, the solve).
// Times are the CPU time of the thread per call, the least over ten blocks of a tenth of
// the repetitions each: on a machine shared with other work, time slices lost to it and
// disturbed blocks do not count.
//   build/bench_tire_iteration [repetitions]
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "contact/tread_contact.hpp"
#include "core/assembler.hpp"
#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "solvers/ring_solver.hpp"
#include "tire/tire_builder.hpp"

using namespace tirefe;

namespace {

template <class Work>
double microseconds_per_call(int repetitions, Work&& work) {
  auto thread_microseconds = [] {
    timespec now;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return 1e6 * static_cast<double>(now.tv_sec) + 1e-3 * static_cast<double>(now.tv_nsec);
  };
  work();  // warm the caches and any first-call set-up
  constexpr int kBlocks = 10;
  const int per_block = std::max(1, repetitions / kBlocks);
  double least = 0.0;
  for (int block = 0; block < kBlocks; ++block) {
    const double start = thread_microseconds();
    for (int i = 0; i < per_block; ++i) work();
    const double time = (thread_microseconds() - start) / per_block;
    least = block == 0 ? time : std::min(least, time);
  }
  return least;
}

struct Timings {
  int equations = 0, border = 0;
  long nonzeros = 0;
  double assembly = 0, residual_only = 0;
  double klu_factorize = 0, klu_solve = 0, klu_schur = 0;
  double ring_factorize = 0, ring_solve = 0, ring_interior = 0, ring_condense = 0;
  double assemble_and_factorize = 0, assemble_into_ring = 0;  // tangent assembly + ring factorisation
  double difference = 0;                                      // |x_ring - x_klu| / |x_klu|
};

/// The tire built into 'model', its spindle condensed and fixed in its first
/// 'fixed_components'.
Tire condensed_tire(Model& model, const char* tire_set, int fixed_components) {
  const Tire tire = build_tire(model, macros::load_tire_parameters(tire_set), LoadFunction::linear());
  for (int c = 0; c < fixed_components; ++c) model.fix(tire.spindle, c);
  model.condense_node(tire.spindle);
  return tire;
}

/// Inflated quasi-statically to t = 1 on a held hub (so the static tangent is regular),
/// the hub's other components released after.
void inflate(Model& model, Analysis& analysis, int spindle, int fixed_components) {
  analysis.set_time_step(0.5);
  for (int c = fixed_components; c < kDofsPerNode; ++c) model.fix(spindle, c);
  analysis.advance(1.0);
  for (int c = fixed_components; c < kDofsPerNode; ++c) model.release(spindle, c);
}

/// A Newmark step's effective tangent (h = 1e-4 s) at 'time'.
EvaluationContext newmark_context(double time) {
  EvaluationContext context;
  context.time = time;
  const double h = 1e-4;
  context.factors = {1.0, 1.0, 1.0, 1.0, 0.5 / (0.25 * h), 1.0 / (0.25 * h * h)};
  context.want_tangent = true;
  return context;
}

Timings time_tire(const char* tire_set, int fixed_components, int repetitions) {
  Model model;
  const Tire tire = condensed_tire(model, tire_set, fixed_components);
  Analysis analysis(model);
  inflate(model, analysis, tire.spindle, fixed_components);

  Timings timings;
  Assembler& assembler = analysis.assembler();
  assembler.update_pattern();
  EvaluationContext context = newmark_context(1.0);
  Eigen::VectorXd residual;
  const State& state = analysis.state();
  timings.assembly = microseconds_per_call(repetitions, [&] { assembler.assemble(context, state, residual); });
  context.want_tangent = false;
  timings.residual_only = microseconds_per_call(repetitions, [&] { assembler.assemble(context, state, residual); });
  model.revert_history();
  const SparseMatrix& tangent = assembler.tangent();
  const int n = static_cast<int>(tangent.rows());
  timings.equations = n;
  timings.nonzeros = static_cast<long>(tangent.nonZeros());
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);

  KluSolver klu;
  klu.analyze(tangent);
  Eigen::VectorXd x_klu = rhs;
  timings.klu_factorize = microseconds_per_call(repetitions, [&] { klu.factorize(tangent); });
  timings.klu_solve = microseconds_per_call(repetitions, [&] {
    x_klu = rhs;
    klu.solve(x_klu);
  });

  RingSolver ring(model.dof_map(), tire.tread_nodes, {tire.spindle});
  ring.analyze(tangent);
  const int border = ring.border_size();
  timings.border = border;
  Eigen::VectorXd x_ring = rhs, condensed;
  timings.ring_factorize = microseconds_per_call(repetitions, [&] { ring.factorize(tangent); });
  timings.ring_solve = microseconds_per_call(repetitions, [&] {
    x_ring = rhs;
    ring.solve(x_ring);
  });
  timings.ring_interior = microseconds_per_call(repetitions, [&] { ring.factorize_interior(tangent); });
  timings.ring_condense = microseconds_per_call(repetitions, [&] { ring.condense(rhs, condensed); });
  timings.difference = (x_ring - x_klu).norm() / x_klu.norm();

  // A Newton iteration's tangent and its factors: through the sparse values, or assembled
  // straight into the RingSolver's blocks (Assembler::bind_solver_layout).
  context.want_tangent = true;
  timings.assemble_and_factorize = microseconds_per_call(repetitions, [&] {
    assembler.assemble(context, state, residual);
    ring.factorize(tangent);
  });
  assembler.bind_solver_layout(ring.entry_destinations());
  timings.assemble_into_ring = microseconds_per_call(repetitions, [&] {
    assembler.assemble_into_solver(context, state, residual, ring.begin_assembly());
    ring.factorize_assembled();
  });
  model.revert_history();

  // The KLU route to H: factor K, solve for the border's unit columns, H = ((K^-1)_bb)^-1.
  if (border > 0) {
    Eigen::MatrixXd columns(n, border);
    Eigen::MatrixXd schur(border, border);
    timings.klu_schur = microseconds_per_call(repetitions, [&] {
      klu.factorize(tangent);
      columns.setZero();
      for (int i = 0; i < border; ++i) columns(n - border + i, i) = 1.0;
      klu.solve(columns);
      schur = columns.bottomRows(border).inverse();
    });
  }
  return timings;
}

struct DrumTimings {
  int in_contact = 0;
  double contact = 0, assembly = 0, residual_only = 0, ring_factorize = 0, ring_solve = 0, iteration = 0;
};

/// The tire on a dead axle pressed onto the deck's drum at rest (hub 25 mm down).
DrumTimings time_on_drum(const char* tire_set, int repetitions) {
  Model model;
  const Tire tire = condensed_tire(model, tire_set, kDofsPerNode);  // held while pressed
  Analysis analysis(model);
  inflate(model, analysis, tire.spindle, kDofsPerNode);

  // The drum's top under the hub, touching the lowest tread node.
  double lowest = 0.0;
  for (int node : tire.tread_nodes)
    lowest = std::min(lowest, model.mesh().position(node).y() + analysis.state().displacement[dof_index(node, 1)]);
  const double drum_radius = 0.85;
  Cleat cleat;  // the deck's, on the far side of the drum
  cleat.height = 0.025;
  cleat.arc_length = 0.66;
  cleat.edge_radius = 0.005;
  cleat.angle = -0.5 * 3.14159265358979323846;
  auto drum = std::make_shared<Drum>(2.0 * drum_radius, Eigen::Vector2d(0.0, lowest - drum_radius),
                                     MotionFunction::constant(), cleat);
  TreadContactBlock& contact =
      add_tread_contact_block(model, "drum", drum, tire.tread_nodes, tread_rubber(tire.parameters, 0.3));
  const int press = model.add_load_function(LoadFunction::table({{1.0, 0.0}, {2.0, 1.0}}));
  model.prescribe(tire.spindle, 1, -0.025, press);
  analysis.set_time_step(0.05);
  analysis.advance(1.0);
  model.release(tire.spindle, 2);  // a dead axle: the hub turns

  DrumTimings timings;
  timings.in_contact = summarize_contact(contact).nodes_in_contact;
  Assembler& assembler = analysis.assembler();
  assembler.update_pattern();
  EvaluationContext context = newmark_context(2.0);
  const State& state = analysis.state();
  Eigen::VectorXd residual;
  timings.assembly = microseconds_per_call(repetitions, [&] { assembler.assemble(context, state, residual); });
  context.want_tangent = false;
  timings.residual_only = microseconds_per_call(repetitions, [&] { assembler.assemble(context, state, residual); });
  context.want_tangent = true;
  const SparseMatrix& tangent = assembler.tangent();
  Eigen::VectorXd forces = Eigen::VectorXd::Zero(model.dof_map().dof_count());
  std::vector<double> values(static_cast<size_t>(tangent.nonZeros()));
  AssemblyTarget target{&forces, values.data(), 0};
  timings.contact = microseconds_per_call(repetitions, [&] { contact.assemble(context, state, target); });

  RingSolver ring(model.dof_map(), tire.tread_nodes, {tire.spindle});
  ring.analyze(tangent);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(tangent.rows(), 1.0, 2.0);
  Eigen::VectorXd x = rhs;
  timings.ring_factorize = microseconds_per_call(repetitions, [&] { ring.factorize(tangent); });
  timings.ring_solve = microseconds_per_call(repetitions, [&] {
    x = rhs;
    ring.solve(x);
  });
  assembler.bind_solver_layout(ring.entry_destinations());
  timings.iteration = microseconds_per_call(repetitions, [&] {
    assembler.assemble_into_solver(context, state, residual, ring.begin_assembly());
    ring.factorize_assembled();
    x = rhs;
    ring.solve(x);
  });
  model.revert_history();
  return timings;
}

void print_drum_table(const DrumTimings (&all)[2], int repetitions) {
  std::printf(
      "on the drum: dead axle, hub 25 mm down on the 1.7 m drum at rest, contact block of 100 nodes,\n"
      "Newmark effective tangent (h = 1e-4 s), %d repetitions, times in us\n",
      repetitions);
  std::printf("%-56s %14s %14s\n", "", "paper's", "calibrated");
  std::printf("%-56s %14d %14d\n", "nodes in contact", all[0].in_contact, all[1].in_contact);
  auto row = [&](const char* label, double DrumTimings::*field) {
    std::printf("%-56s %14.1f %14.1f\n", label, all[0].*field, all[1].*field);
  };
  row("contact pass (residual + tangent)", &DrumTimings::contact);
  row("assembly with contact (residual + tangent)", &DrumTimings::assembly);
  row("assembly with contact (residual only)", &DrumTimings::residual_only);
  row("ring factorisation", &DrumTimings::ring_factorize);
  row("ring solve", &DrumTimings::ring_solve);
  row("Newton iteration: assembly into the ring, factor, solve", &DrumTimings::iteration);
}

void print_table(const char* title, const Timings (&all)[3], int repetitions) {
  const char* cases[] = {"spindle free", "dead axle", "spindle fixed"};
  std::printf("%s, 100 elements, Newmark effective tangent (h = 1e-4 s), %d repetitions, times in us\n", title,
              repetitions);
  std::printf("%-40s %14s %14s %14s\n", "", cases[0], cases[1], cases[2]);
  auto row = [&](const char* label, double Timings::*field, const char* format = "%14.1f") {
    std::printf("%-40s", label);
    for (const Timings& t : all) std::printf(format, t.*field);
    std::printf("\n");
  };
  auto count_row = [&](const char* label, int Timings::*field) {
    std::printf("%-40s", label);
    for (const Timings& t : all) std::printf("%14d", t.*field);
    std::printf("\n");
  };
  count_row("equations", &Timings::equations);
  count_row("border (spindle) equations", &Timings::border);
  row("assembly (residual + tangent)", &Timings::assembly);
  row("assembly (residual only)", &Timings::residual_only);
  row("KLU refactorisation", &Timings::klu_factorize);
  row("KLU solve", &Timings::klu_solve);
  row("ring factorisation", &Timings::ring_factorize);
  row("assembly with tangent + ring factorisation", &Timings::assemble_and_factorize);
  row("the same assembled into the ring's blocks", &Timings::assemble_into_ring);
  row("ring solve", &Timings::ring_solve);
  row("ring partial factorisation -> H", &Timings::ring_interior);
  row("ring condensed rhs f_b", &Timings::ring_condense);
  row("KLU route to H (factor, b solves, inv)", &Timings::klu_schur);
  std::printf("%-40s", "KLU factor + solve");
  for (const Timings& t : all) std::printf("%14.1f", t.klu_factorize + t.klu_solve);
  std::printf("\n%-40s", "ring factor + solve");
  for (const Timings& t : all) std::printf("%14.1f", t.ring_factorize + t.ring_solve);
  std::printf("\n");
  row("|x_ring - x_KLU| / |x_KLU|", &Timings::difference, "%14.1e");
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::atoi(argv[1]) : 2000;
  const char* tires[][2] = {{"tires.145SR12", "145 SR-12 (the paper's)"},
                            {"tires.145SR12_tread_layer", "145 SR-12 calibrated (tread layer)"}};
  const int fixed[] = {0, 2, 3};
  for (const auto& tire : tires) {
    Timings all[3];
    for (int i = 0; i < 3; ++i) all[i] = time_tire(tire[0], fixed[i], repetitions);
    print_table(tire[1], all, repetitions);
    std::printf("\n");
  }
  DrumTimings on_drum[2];
  for (int i = 0; i < 2; ++i) on_drum[i] = time_on_drum(tires[i][0], repetitions);
  print_drum_table(on_drum, repetitions);
  return 0;
}
