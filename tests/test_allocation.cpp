// The Newton loop allocates nothing once a model is set up: assembly, factorisation and
// solves reuse their buffers. Checked by counting global operator new calls and the calls
// of malloc, calloc and realloc (Eigen's vectors take their memory there), wrapped around
// glibc's allocator.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <new>

#include "elements/tread_beam.hpp"
#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "solvers/ring_solver.hpp"
#include "tire/tire_builder.hpp"
#include "vehicle/tire_spindle.hpp"

namespace {
std::atomic<long> allocations{0};
}  // namespace

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* malloc(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* memory, std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(memory, size);
}
}

void* operator new(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* memory = std::malloc(size ? size : 1)) return memory;
  throw std::bad_alloc();
}
// Every form that the replaced delete may free comes from malloc too (Catch uses the
// nothrow form; a sanitizer's own would not pair with free).
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size ? size : 1);
}
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }

TEST_CASE("steps after the first allocate no memory in assembly, Newton and KLU refactorisation",
          "[kernel][allocation]") {
  using namespace tirefe;
  Model model;
  BeamSection section;
  section.axial_stiffness = 1e4;
  section.shear_stiffness = 1e4;
  section.bending_stiffness = 1.0;
  section.mass_per_length = 1.0;
  section.rotary_inertia_per_length = 1e-3;
  const int elements = 20;
  for (int i = 0; i <= elements; ++i) model.mesh().add_node({static_cast<double>(i) / elements, 0.0});
  auto& beams = model.add_block<TreadBeam>("beam");
  for (int i = 0; i < elements; ++i)
    beams.add({i, i + 1}, TreadBeam(model.mesh().position(i), model.mesh().position(i + 1), section));
  for (int c = 0; c < kDofsPerNode; ++c) model.fix(0, c);
  model.add_nodal_load(elements, kUy, -2.0, Model::kRampLoadFunction);

  Analysis analysis(model);
  analysis.set_integrator(Integrator::newmark());
  analysis.set_time_step(1e-3);
  analysis.advance(5e-3);  // warm-up: pattern, symbolic analysis, first factorisation, buffers

  const long before = allocations.load();
  const auto& records = analysis.advance(5e-3);
  const long during = allocations.load() - before;
  int iterations = 0;
  for (const auto& record : records) iterations += record.newton_iterations;
  INFO(records.size() << " steps, " << iterations << " Newton iterations, " << during << " allocations");
  CHECK(iterations >= 5);
  CHECK(during == 0);
}

TEST_CASE(
    "Newmark steps of the tire with the ring solver allocate no memory, nor do its factorisations, solves "
    "and condensations",
    "[kernel][allocation][ring_solver]") {
  using namespace tirefe;
  Model model;
  const Tire tire =
      build_tire(model, macros::load_tire_parameters("tires.145SR12"), LoadFunction::table({{0.0, 0.0}, {1e-3, 1.0}}));
  model.condense_node(tire.spindle);
  model.fix(tire.spindle, kUx);  // a dead axle: the spin is free, the border has one equation
  model.fix(tire.spindle, kUy);
  model.add_nodal_load(tire.spindle, kRz, 20.0, Model::kRampLoadFunction);
  Analysis analysis(model);
  analysis.use_ring_solver(tire.tread_nodes, {tire.spindle});
  analysis.set_integrator(Integrator::newmark());
  analysis.set_time_step(1e-4);
  analysis.advance(5e-4);  // warm-up

  long before = allocations.load();
  const auto& records = analysis.advance(5e-4);
  long during = allocations.load() - before;
  int iterations = 0;
  for (const auto& record : records) iterations += record.newton_iterations;
  INFO(records.size() << " steps, " << iterations << " Newton iterations, " << during << " allocations");
  CHECK(iterations >= 5);
  CHECK(during == 0);

  auto& ring = dynamic_cast<RingSolver&>(analysis.linear_solver());
  const SparseMatrix& tangent = analysis.assembler().tangent();
  Eigen::VectorXd rhs = Eigen::VectorXd::Ones(tangent.rows()), condensed(ring.border_size());
  Eigen::MatrixXd columns = Eigen::MatrixXd::Ones(tangent.rows(), 3);
  before = allocations.load();
  ring.factorize(tangent);
  ring.solve(rhs);
  ring.solve(columns);
  ring.factorize_interior(tangent);
  ring.condense(rhs, condensed);
  during = allocations.load() - before;
  CHECK(during == 0);
}

TEST_CASE("spindle steps of a driven tire allocate no memory: Newton, the driven solves and H_ss",
          "[kernel][allocation][spindle]") {
  using namespace tirefe;
  Model model;
  const Tire tire =
      build_tire(model, macros::load_tire_parameters("tires.145SR12"), LoadFunction::table({{0.0, 0.0}, {1e-3, 1.0}}));
  model.condense_node(tire.spindle);
  Analysis analysis(model);
  analysis.use_ring_solver(tire.tread_nodes, {tire.spindle});
  analysis.set_integrator(Integrator::newmark());
  TireSpindle spindle(analysis, tire.spindle, SpinMode::Free);
  auto step = [&](int i) {
    spindle.solve_step({1e-4, 1e-4 * i, -2e-4 * i, 0.0});  // the hub moves: Newton has work to do
    spindle.commit();
  };
  for (int i = 1; i <= 5; ++i) step(i);  // warm-up

  const long before = allocations.load();
  for (int i = 6; i <= 10; ++i) step(i);
  const long during = allocations.load() - before;
  CHECK(analysis.last_newton_report().iterations >= 1);
  CHECK(during == 0);
}
