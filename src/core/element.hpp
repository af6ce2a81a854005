// The element contract shared by every element, load and contact kernel.
//
// An element never knows which integrator drives it (docs/kernel.md). It returns
//     residual = wK * f_int(u) + wC * C v + wM * M a
//     tangent  = cK * dF_int/du + cC * C + cM * M
// where the integrator alone chooses the weights w and the tangent factors c
// (static: w = (1,0,0), c = (1,0,0); Newmark: w = (1,1,1), c = (1, gamma/(beta h), 1/(beta h^2))).
//
// Kernels are small value types with fixed-size Eigen blocks; ElementBlockOf<Kernel>
// loops over one block of them, gathers, evaluates and scatters without allocating,
// and keeps their history as committed + trial copies (commit on an accepted step,
// revert on a cut step).
//
// Augmented-Lagrangian kernels (contact) also get a per-step base history: evaluations
// start from it, and between Newton solves of one step augment() may update it (Uzawa
// multiplier updates) from the converged trial history. It starts each step equal to the
// committed history, so a cut step reverts the multipliers too. A kernel opts in with
//     bool augment(History& base, const History& trial) const;   // true: solve again
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "core/element_response.hpp"
#include "core/mesh.hpp"
#include "core/state.hpp"

namespace tirefe {

struct IntegratorFactors {
  double force_stiffness = 1.0;    // wK
  double force_damping = 0.0;      // wC
  double force_mass = 0.0;         // wM
  double tangent_stiffness = 1.0;  // cK
  double tangent_damping = 0.0;    // cC
  double tangent_mass = 0.0;       // cM

  // One term alone, for queries between steps: its force (residual, no tangent wanted)
  // or its matrix (tangent).
  static IntegratorFactors stiffness_force() { return only(&IntegratorFactors::force_stiffness); }
  static IntegratorFactors damping_force() { return only(&IntegratorFactors::force_damping); }
  static IntegratorFactors inertia_force() { return only(&IntegratorFactors::force_mass); }
  static IntegratorFactors stiffness_matrix() { return {}; }  // with its force f_int
  static IntegratorFactors damping_matrix() { return only(&IntegratorFactors::tangent_damping); }
  static IntegratorFactors mass_matrix() { return only(&IntegratorFactors::tangent_mass); }

 private:
  static IntegratorFactors only(double IntegratorFactors::*factor) {
    IntegratorFactors factors{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    factors.*factor = 1.0;
    return factors;
  }
};

struct EvaluationContext {
  double time = 0.0;  // time at the end of the step being solved
  double time_step = 0.0;
  IntegratorFactors factors;
  bool want_tangent = true;
  // The first evaluation of a Newton solve, at the predicted state: a contact block that
  // holds its contacts there linearises about the state the step began with (node_contact.hpp).
  bool first_evaluation = false;
};

struct ElementEnergy {
  double strain = 0.0;
  double kinetic = 0.0;
  // Booked by an element that keeps its own account (a contact on a moving surface), since
  // its history began: the work a prescribed motion did through it on the structure, and
  // what it dissipated (friction, its dashpots).
  double supplied = 0.0;
  double dissipated = 0.0;
  ElementEnergy& operator+=(const ElementEnergy& other) {
    strain += other.strain;
    kinetic += other.kinetic;
    supplied += other.supplied;
    dissipated += other.dissipated;
    return *this;
  }
};

/// Thrown when an element produces NaN or infinity: names the block, the element and the
/// node and DOF of the first non-finite entry. The Newton solve stops at once; the step is cut.
class NonFiniteResult : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Global equation numbers and where each element-matrix entry lands in the sparse
/// tangent's value array; built by the Assembler (assembler.hpp).
class TangentSlots;

/// Global buffers one assembly pass writes into.
struct AssemblyTarget {
  Eigen::VectorXd* residual = nullptr;  // one entry per DOF (prescribed DOFs give reactions)
  double* tangent_values = nullptr;     // sparse values of the free-equation tangent, or null
  int layout = 0;                       // the numbered slot layout tangent_values is laid out in
  long stamp = 0;                       // for a layout other than 0: the binding it expects
};

/// The nodal values of a whole block, gathered as structure of arrays for a kernel's batch
/// path: local DOF k of element e at [k * count + e] (velocity and acceleration null unless
/// the kernel reads them; an idle DOF's values zero).
struct BlockValues {
  int count = 0;
  const double* displacement = nullptr;
  const double* velocity = nullptr;
  const double* acceleration = nullptr;
};

/// The stored energy of a batch's elements, summed: 'element(e)' gives element e's, and
/// the loop over them vectorises (a batch's energy(), element.hpp's batch path).
template <class ElementEnergyOf>
ElementEnergy sum_energies(int count, ElementEnergyOf element) {
  double strain = 0.0, kinetic = 0.0;
#pragma omp simd reduction(+ : strain, kinetic)
  for (int e = 0; e < count; ++e) {
    const ElementEnergy one = element(e);
    strain += one.strain;
    kinetic += one.kinetic;
  }
  ElementEnergy total;
  total.strain = strain;
  total.kinetic = kinetic;
  return total;
}

/// Whether every value is finite, in one vectorised pass without a branch per value:
/// x * 0 is 0 for a finite x and NaN for an infinite or NaN one, and a NaN survives the sum.
inline bool all_finite(const double* values, int count) {
  double probe = 0.0;
#pragma omp simd reduction(+ : probe)
  for (int k = 0; k < count; ++k) probe += values[k] * 0.0;
  return probe == 0.0;
}

template <int Dofs>
struct LocalState {
  Eigen::Matrix<double, Dofs, 1> displacement, velocity, acceleration;
};

class ElementBlock {
 public:
  virtual ~ElementBlock() = default;
  virtual const std::string& name() const = 0;
  virtual int nodes_per_element() const = 0;
  virtual int size() const = 0;
  virtual std::vector<int> element_nodes(int element) const = 0;

  /// Slot layout 0: the positions of element-matrix entries in the sparse value array,
  /// row-major per element, -1 where a row or column is a prescribed DOF. Binding it anew
  /// forgets the other layouts.
  virtual void bind_tangent_slots(std::vector<int> slots) = 0;
  /// Slot layout 'layout' (1, 2, ...): the entry at slot s of layout 0 lands at place[s];
  /// 'stamp' (not 0) names this binding for AssemblyTarget::stamp.
  virtual void bind_slot_layout(int layout, const std::vector<int>& place, long stamp) = 0;
  /// The stamp of that layout's binding, 0 for none.
  virtual long slot_layout_stamp(int layout) const = 0;

  virtual void assemble(const EvaluationContext& context, const State& state, AssemblyTarget& target) = 0;
  virtual ElementEnergy energy(const State& state) const = 0;
  /// How the energy balance books the block's work (energy_balance.hpp): its forces derive
  /// from the energy() it stores, or they do work it does not store (a follower load); it
  /// may have dashpots, whose forces the damping factors give; it may keep its own account
  /// of dissipation and of the work of a moving surface (ElementEnergy::supplied, dissipated).
  virtual bool stores_energy() const = 0;
  virtual bool has_dashpots() const = 0;
  /// Whether an evaluation leaves the block's state alone (it keeps no history).
  virtual bool history_free() const = 0;
  /// Adds the block's inertia forces M a at 'state' to 'global' (one entry per DOF) and
  /// returns true; false, adding nothing, when the kernel cannot say (it reads the
  /// acceleration but has no mass_times).
  virtual bool add_inertia_forces(const State& state, Eigen::VectorXd& global) const = 0;
  virtual void commit() = 0;
  virtual void revert() = 0;
  /// Uzawa update after a converged Newton solve; true if the block wants another solve.
  virtual bool augment() { return false; }

  // Checkpoints: the committed history of every element as plain bytes. The kernel's
  // type name and the history's size let a restart refuse a block of another kind.
  virtual std::string kernel_type() const = 0;
  virtual size_t history_bytes_per_element() const = 0;
  virtual std::vector<unsigned char> committed_history_bytes() const = 0;
  /// Sets the committed (and trial) history of every element from such bytes.
  virtual void set_history_bytes(const std::vector<unsigned char>& bytes) = 0;
};

struct NoHistory {};

/// A set of a kernel's local DOFs, written as a list: {5, 8}.
class LocalDofSet {
 public:
  constexpr LocalDofSet() = default;
  constexpr LocalDofSet(std::initializer_list<int> dofs) {
    for (int dof : dofs) bits_ |= 1ull << dof;
  }
  constexpr bool contains(int dof) const { return (bits_ >> dof) & 1ull; }

 private:
  unsigned long long bits_ = 0;
};

/// What a kernel promises so that the block loop may skip work. Every member starts as the
/// promise of a kernel that makes none; a kernel changes the ones it makes in
///     static constexpr KernelTraits traits() {
///       KernelTraits traits;
///       traits.reads_acceleration = false;
///       traits.idle_dofs = {5, 8};
///       return traits;
///     }
/// so that a misspelt member does not compile (tests/compile_fail/). The element tests
/// check every promise (tests/test_support.hpp, declared_zero_magnitude).
struct KernelTraits {
  bool reads_acceleration = true;  // false: the gather leaves a = 0
  bool reads_velocity = true;      // false: the batch path gathers no velocities (values.velocity null)
  // false: energy() is always zero (a follower load's): the block's energy() neither
  // gathers nor loops, and the energy balance books the work of its forces instead.
  bool stores_energy = true;
  // true: the kernel keeps its own account of what it dissipates, its velocity-dependent
  // forces included (a contact's): the energy balance does not evaluate its dashpots.
  bool books_energy = false;
  // true: 'trial' arrives holding what the element's last evaluation left (the previous
  // Newton iterate's history) rather than a copy of 'base'; the kernel then writes every field.
  bool reads_last_trial = false;
  // Local DOFs whose residual row and tangent row and column are always zero (neither
  // read nor loaded).
  LocalDofSet idle_dofs;
  // True for local tangent entries that are always zero (not scattered): a follower load's.
  bool (*zero_tangent_entry)(int row, int column) = nullptr;
};

/// The fixed sizes and block types of a kernel with `Nodes` nodes; kernels derive from it.
template <int Nodes, class HistoryType = NoHistory>
struct KernelShape {
  static_assert(kDofsPerNode * Nodes <= 64, "LocalDofSet holds 64 DOFs");
  static constexpr int kNodes = Nodes;
  static constexpr int kDofs = kDofsPerNode * Nodes;
  using History = HistoryType;
  using Vector = Eigen::Matrix<double, kDofs, 1>;
  using Matrix = Eigen::Matrix<double, kDofs, kDofs, Eigen::RowMajor>;
  /// No promises; a kernel that makes some declares its own (KernelTraits).
  static constexpr KernelTraits traits() { return {}; }
};

namespace detail {
template <class Kernel, class = void>
struct HasAugment : std::false_type {};
template <class Kernel>
struct HasAugment<Kernel,
                  std::void_t<decltype(std::declval<const Kernel&>().augment(
                      std::declval<typename Kernel::History&>(), std::declval<const typename Kernel::History&>()))>>
    : std::true_type {};

// Optional kernel members besides traits() (KernelTraits):
//   Vector mass_times(const Vector& x) const;  // M x: the inertia forces M a of a kernel
//       that reads the acceleration, without evaluating the rest (its mass is constant,
//       as the contract's tangent cM M has it)
// Optional batch path: a history-free kernel may evaluate its whole block in one call,
//   class Kernel::Batch {
//     explicit Batch(const std::vector<Kernel>& kernels);
//     void evaluate(const BlockValues& values, const EvaluationContext& context, bool with_tangent);
//     const double* residual() const;  // local DOF k of element e at [k * count + e]
//     const double* tangent() const;   // row-major entry k of element e at [k * count + e]
//   };
// over structure-of-arrays data, so that the compiler vectorises across elements. It gives
// the numbers of evaluate() (to round-off); the entries of idle DOFs are never read. It may
// also sum the block's stored energy, the energies of energy() to round-off, from values
// without accelerations:
//     ElementEnergy energy(const BlockValues& values) const;
template <class Kernel, class = void>
struct BatchOf : std::false_type {
  struct type {};
};
template <class Kernel>
struct BatchOf<Kernel, std::void_t<typename Kernel::Batch>> : std::true_type {
  using type = typename Kernel::Batch;
};

template <class Batch, class = void>
struct HasBatchEnergy : std::false_type {};
template <class Batch>
struct HasBatchEnergy<Batch,
                      std::void_t<decltype(std::declval<const Batch&>().energy(std::declval<const BlockValues&>()))>>
    : std::true_type {};

// The kernel's traits one by one. The flags of an earlier convention, detected by name,
// are refused: a kernel states its promises in traits() alone.
template <class Kernel>
struct ReadsAcceleration : std::bool_constant<Kernel::traits().reads_acceleration> {};
template <class Kernel>
struct ReadsVelocity : std::bool_constant<Kernel::traits().reads_velocity> {};
template <class Kernel>
struct StoresEnergy : std::bool_constant<Kernel::traits().stores_energy> {};
template <class Kernel>
struct ReadsLastTrial : std::bool_constant<Kernel::traits().reads_last_trial> {};
template <class Kernel>
struct BooksEnergy : std::bool_constant<Kernel::traits().books_energy> {};

#define TIREFE_REFUSED_KERNEL_FLAG(Flag)       \
  template <class Kernel, class = void>        \
  struct Declares_##Flag : std::false_type {}; \
  template <class Kernel>                      \
  struct Declares_##Flag<Kernel, std::void_t<decltype(Kernel::Flag)>> : std::true_type {};
TIREFE_REFUSED_KERNEL_FLAG(kReadsAcceleration)
TIREFE_REFUSED_KERNEL_FLAG(kReadsVelocity)
TIREFE_REFUSED_KERNEL_FLAG(kStoresEnergy)
TIREFE_REFUSED_KERNEL_FLAG(kBooksEnergy)
TIREFE_REFUSED_KERNEL_FLAG(kReadsLastTrial)
TIREFE_REFUSED_KERNEL_FLAG(kIdleDofs)
#undef TIREFE_REFUSED_KERNEL_FLAG
template <class Kernel>
constexpr bool kDeclaresLooseFlags =
    Declares_kReadsAcceleration<Kernel>::value || Declares_kReadsVelocity<Kernel>::value ||
    Declares_kStoresEnergy<Kernel>::value || Declares_kBooksEnergy<Kernel>::value ||
    Declares_kReadsLastTrial<Kernel>::value || Declares_kIdleDofs<Kernel>::value;

template <class Kernel, class = void>
struct HasMassTimes : std::false_type {};
template <class Kernel>
struct HasMassTimes<Kernel, std::void_t<decltype(std::declval<const Kernel&>().mass_times(
                                std::declval<const typename Kernel::Vector&>()))>> : std::true_type {};

/// Which local DOFs a kernel declares idle (traits().idle_dofs).
template <class Kernel>
struct IdleDofs {
  static constexpr std::array<bool, Kernel::kDofs> mask() {
    std::array<bool, Kernel::kDofs> idle{};
    for (int dof = 0; dof < Kernel::kDofs; ++dof) idle[dof] = Kernel::traits().idle_dofs.contains(dof);
    return idle;
  }
};

/// Which local tangent entries a kernel declares always zero, row-major (traits().zero_tangent_entry).
template <class Kernel>
struct ZeroTangentEntries {
  static constexpr std::array<bool, Kernel::kDofs * Kernel::kDofs> mask() {
    return of(Kernel::traits().zero_tangent_entry);
  }

 private:
  static constexpr std::array<bool, Kernel::kDofs * Kernel::kDofs> of(bool (*zero_entry)(int row, int column)) {
    std::array<bool, Kernel::kDofs * Kernel::kDofs> zero{};
    if (zero_entry != nullptr)
      for (int k = 0; k < Kernel::kDofs * Kernel::kDofs; ++k)
        zero[k] = zero_entry(k / Kernel::kDofs, k % Kernel::kDofs);
    return zero;
  }
};
}  // namespace detail

template <class Kernel>
class ElementBlockOf final : public ElementBlock, public BlockResponses<ElementBlockOf<Kernel>, Kernel> {
  static_assert(!detail::kDeclaresLooseFlags<Kernel>, "a kernel states its promises in traits() (KernelTraits)");

 public:
  static constexpr int kNodes = Kernel::kNodes;
  static constexpr int kDofs = kDofsPerNode * kNodes;
  using History = typename Kernel::History;
  using Vector = Eigen::Matrix<double, kDofs, 1>;
  using Matrix = Eigen::Matrix<double, kDofs, kDofs, Eigen::RowMajor>;

  explicit ElementBlockOf(std::string name) : name_(std::move(name)) {}

  int add(const std::array<int, kNodes>& nodes, Kernel kernel) {
    nodes_.push_back(nodes);
    kernels_.push_back(std::move(kernel));
    committed_.emplace_back();
    base_.emplace_back();
    trial_.emplace_back();
    batch_.reset();
    return size() - 1;
  }

  const std::string& name() const override { return name_; }
  int nodes_per_element() const override { return kNodes; }
  int size() const override { return static_cast<int>(kernels_.size()); }
  std::vector<int> element_nodes(int element) const override {
    return {nodes_[element].begin(), nodes_[element].end()};
  }
  const Kernel& kernel(int element) const { return kernels_[element]; }
  Kernel& kernel(int element) {
    batch_.reset();  // the batch copies the kernels' constants
    return kernels_[element];
  }
  const History& trial_history(int element) const { return trial_[element]; }
  const History& committed_history(int element) const { return committed_[element]; }
  /// Element e's nodal values at 'state', as its kernel reads them (accelerations only if it reads them).
  void gather(int e, const State& state, LocalState<kDofs>& local) const {
    for (int n = 0; n < kNodes; ++n) {
      const int first = dof_index(nodes_[e][n], 0);
      local.displacement.template segment<kDofsPerNode>(kDofsPerNode * n) =
          state.displacement.template segment<kDofsPerNode>(first);
      local.velocity.template segment<kDofsPerNode>(kDofsPerNode * n) =
          state.velocity.template segment<kDofsPerNode>(first);
      if constexpr (detail::ReadsAcceleration<Kernel>::value)
        local.acceleration.template segment<kDofsPerNode>(kDofsPerNode * n) =
            state.acceleration.template segment<kDofsPerNode>(first);
    }
  }
  /// Sets an element's history (initial contact state, restart) as committed.
  void set_history(int element, const History& history) {
    committed_[element] = base_[element] = trial_[element] = history;
  }

  /// Keeps, per element, the entries that land in the sparse values: neither a prescribed
  /// DOF's (slot -1), nor an idle DOF's row or column, nor a declared zero, so the scatter
  /// has no branch.
  void bind_tangent_slots(std::vector<int> slots) override {
    constexpr std::array<bool, kDofs> idle = detail::IdleDofs<Kernel>::mask();
    constexpr std::array<bool, kDofs* kDofs> zero = detail::ZeroTangentEntries<Kernel>::mask();
    tangent_entries_.clear();
    element_entries_.assign(1, 0);
    for (int e = 0; e < size(); ++e) {
      const int* slot = slots.data() + static_cast<size_t>(e) * kDofs * kDofs;
      for (int k = 0; k < kDofs * kDofs; ++k)
        if (slot[k] >= 0 && !idle[k / kDofs] && !idle[k % kDofs] && !zero[k]) tangent_entries_.push_back({k, slot[k]});
      element_entries_.push_back(static_cast<int>(tangent_entries_.size()));
    }
    layouts_.clear();  // a new pattern: the other layouts are bound anew
    if constexpr (kBatched) prepare_batch();
  }

  void bind_slot_layout(int layout, const std::vector<int>& place, long stamp) override {
    if (layout < 1) throw std::logic_error("block '" + name_ + "': slot layout 0 is bound by bind_tangent_slots");
    if (layouts_.size() < static_cast<size_t>(layout)) layouts_.resize(layout);
    SlotLayout& bound = layouts_[layout - 1];
    bound.stamp = stamp;
    bound.place = place;
    bound.entries = placed(tangent_entries_, place);
    if constexpr (kBatched) bound.batch_entries = placed(batch_entries_, place);
  }
  long slot_layout_stamp(int layout) const override {
    return layout >= 1 && static_cast<size_t>(layout) <= layouts_.size() ? layouts_[layout - 1].stamp : 0;
  }

  void assemble(const EvaluationContext& context, const State& state, AssemblyTarget& target) override {
    if constexpr (kBatched) {
      assemble_batch(context, state, target);
      return;
    }
    LocalState<kDofs> local;
    local.acceleration.setZero();  // stays zero for kernels that never read it
    Vector residual;
    Matrix tangent;
    const bool with_tangent = context.want_tangent && target.tangent_values != nullptr;
    const TangentEntry* entries = tangent_entries(target);
    for (int e = 0; e < size(); ++e) {
      gather(e, state, local);
      if constexpr (!detail::ReadsLastTrial<Kernel>::value) trial_[e] = base_[e];
      kernels_[e].evaluate(local, context, base_[e], trial_[e], residual, with_tangent ? &tangent : nullptr);
      if (!residual.allFinite()) throw_non_finite(e, "residual", residual);
      scatter_residual(e, residual, *target.residual);
      if (with_tangent) scatter_tangent(e, tangent, entries, target.tangent_values);
    }
  }

  ElementEnergy energy(const State& state) const override {
    if constexpr (!detail::StoresEnergy<Kernel>::value) return {};
    if constexpr (detail::HasBatchEnergy<Batch>::value)
      if (batch_) return batch_->energy(gather_batch(state, false));
    ElementEnergy total;
    LocalState<kDofs> local;
    local.acceleration.setZero();
    for (int e = 0; e < size(); ++e) {
      gather(e, state, local);
      total += kernels_[e].energy(local, trial_[e]);
    }
    return total;
  }

  bool stores_energy() const override { return detail::StoresEnergy<Kernel>::value; }
  bool history_free() const override { return std::is_empty_v<History>; }
  bool has_dashpots() const override {
    return detail::ReadsVelocity<Kernel>::value && !detail::BooksEnergy<Kernel>::value;
  }

  bool add_inertia_forces(const State& state, Eigen::VectorXd& global) const override {
    if constexpr (!detail::ReadsAcceleration<Kernel>::value) {
      return true;  // no mass
    } else if constexpr (detail::HasMassTimes<Kernel>::value) {
      LocalState<kDofs> local;
      for (int e = 0; e < size(); ++e) {
        gather(e, state, local);
        scatter_residual(e, kernels_[e].mass_times(local.acceleration), global);
      }
      return true;
    } else {
      return false;
    }
  }

  void commit() override {
    committed_ = trial_;
    base_ = trial_;
  }
  void revert() override {
    trial_ = committed_;
    base_ = committed_;
  }
  std::string kernel_type() const override { return typeid(Kernel).name(); }
  size_t history_bytes_per_element() const override { return sizeof(History); }
  std::vector<unsigned char> committed_history_bytes() const override {
    // Plain data owns nothing: numbers and fixed-size Eigen vectors (bitwise copyable,
    // though Eigen does not declare them trivially copyable); no pointers, no containers.
    static_assert(std::is_trivially_destructible_v<History>,
                  "element history must be plain data (checkpoints copy bytes)");
    std::vector<unsigned char> bytes(committed_.size() * sizeof(History), 0);
    // An empty history's one byte is padding, never written: leave it 0 so that two
    // checkpoints of one state are the same bytes (histories with data have no padding).
    if constexpr (!std::is_empty_v<History>)
      if (!bytes.empty()) std::memcpy(bytes.data(), static_cast<const void*>(committed_.data()), bytes.size());
    return bytes;
  }
  void set_history_bytes(const std::vector<unsigned char>& bytes) override {
    if (bytes.size() != committed_.size() * sizeof(History))
      throw std::invalid_argument("block '" + name_ + "': " + std::to_string(bytes.size()) + " bytes of history for " +
                                  std::to_string(size()) + " elements of " + std::to_string(sizeof(History)) +
                                  " bytes");
    if (!bytes.empty()) std::memcpy(static_cast<void*>(committed_.data()), bytes.data(), bytes.size());
    base_ = trial_ = committed_;
  }

  bool augment() override {
    if constexpr (detail::HasAugment<Kernel>::value) {
      bool again = false;
      for (int e = 0; e < size(); ++e) again = kernels_[e].augment(base_[e], trial_[e]) || again;
      return again;
    } else {
      return false;
    }
  }

 private:
  static constexpr bool kBatched = detail::BatchOf<Kernel>::value;
  static constexpr std::array<bool, kDofs> kIdle = detail::IdleDofs<Kernel>::mask();
  using Batch = typename detail::BatchOf<Kernel>::type;
  struct TangentEntry {
    int entry;  // row-major index into the element matrix
    int slot;   // position in the sparse values
  };
  /// A numbered slot layout: where each sparse slot lands, and the entries moved there.
  struct SlotLayout {
    long stamp = 0;
    std::vector<int> place;
    std::vector<TangentEntry> entries, batch_entries;
  };

  /// (Re)builds the batch and its gather buffers: once per structure, outside the Newton loop.
  void prepare_batch() {
    static_assert(std::is_empty_v<History>, "a batch kernel keeps no history");
    batch_ = std::make_unique<Batch>(kernels_);
    gathered_.assign(static_cast<size_t>(3) * kDofs * size(), 0.0);
    // Where each of the batch's values comes from and goes: [k * size + e], local DOF k.
    batch_dofs_.resize(static_cast<size_t>(kDofs) * size());
    for (int e = 0; e < size(); ++e)
      for (int k = 0; k < kDofs; ++k)
        batch_dofs_[k * size() + e] = dof_index(nodes_[e][k / kDofsPerNode], k % kDofsPerNode);
    // The entries again with their place in the batch's tangent, [entry * size + e]: the
    // scatter reads them in the same order and multiplies nothing.
    batch_entries_.clear();
    if (element_entries_.size() != static_cast<size_t>(size()) + 1) return;  // no slots bound yet
    for (int e = 0; e < size(); ++e)
      for (int t = element_entries_[e]; t < element_entries_[e + 1]; ++t)
        batch_entries_.push_back({tangent_entries_[t].entry * size() + e, tangent_entries_[t].slot});
    for (SlotLayout& bound : layouts_) bound.batch_entries = placed(batch_entries_, bound.place);
  }

  /// The batch path: gather every element's nodal values as structure of arrays, evaluate
  /// the block in one call, scatter from the batch's arrays.
  void assemble_batch(const EvaluationContext& context, const State& state, AssemblyTarget& target) {
    if (!batch_) prepare_batch();
    const BlockValues values = gather_batch(state);
    const int count = size();
    const int* dofs = batch_dofs_.data();
    const bool with_tangent = context.want_tangent && target.tangent_values != nullptr;
    batch_->evaluate(values, context, with_tangent);

    const double* residual = batch_->residual();
    if (!all_finite(residual, kDofs * count)) throw_non_finite_batch();
    Eigen::VectorXd& global = *target.residual;
    for (int e = 0; e < count; ++e)  // element by element, as one at a time would add them
      for (int k = 0; k < kDofs; ++k)
        if (!kIdle[k]) global[dofs[k * count + e]] += residual[k * count + e];
    if (!with_tangent) return;
    const double* tangent = batch_->tangent();
    const std::vector<TangentEntry>& entries = target.layout == 0 ? batch_entries_ : bound_layout(target).batch_entries;
    for (const TangentEntry& t : entries) target.tangent_values[t.slot] += tangent[t.entry];
  }

  /// Every element's nodal values as structure of arrays, in the batch's buffers: of its
  /// DOFs that are not idle (those of the idle ones stay zero); the velocities only for a
  /// kernel that reads them, the accelerations only for one that reads them and
  /// 'with_acceleration' (the stored energy reads none).
  BlockValues gather_batch(const State& state, bool with_acceleration = true) const {
    const int count = size();
    double* displacement = gathered_.data();
    double* velocity = displacement + kDofs * count;
    double* acceleration = velocity + kDofs * count;
    constexpr bool reads_velocity = detail::ReadsVelocity<Kernel>::value;
    const bool reads_acceleration = detail::ReadsAcceleration<Kernel>::value && with_acceleration;
    // One pass per DOF reads each index once for all the fields it gathers.
    const double *u = state.displacement.data(), *v = state.velocity.data(), *a = state.acceleration.data();
    for (int k = 0; k < kDofs; ++k) {
      if (kIdle[k]) continue;
      const int* dofs = batch_dofs_.data() + k * count;
      const int first = k * count;
      for (int e = 0; e < count; ++e) {  // the compiler takes reads_acceleration out of the loop
        const int dof = dofs[e];
        displacement[first + e] = u[dof];
        if constexpr (reads_velocity) velocity[first + e] = v[dof];
        if (reads_acceleration) acceleration[first + e] = a[dof];
      }
    }
    return BlockValues{count, displacement, reads_velocity ? velocity : nullptr,
                       reads_acceleration ? acceleration : nullptr};
  }

  void scatter_residual(int e, const Vector& residual, Eigen::VectorXd& global) const {
    for (int n = 0; n < kNodes; ++n)
      global.template segment<kDofsPerNode>(dof_index(nodes_[e][n], 0)) +=
          residual.template segment<kDofsPerNode>(kDofsPerNode * n);
  }
  void scatter_tangent(int e, const Matrix& tangent, const TangentEntry* entries, double* values) const {
    const double* entry = tangent.data();
    const TangentEntry* end = entries + element_entries_[e + 1];
    for (const TangentEntry* t = entries + element_entries_[e]; t != end; ++t) values[t->slot] += entry[t->entry];
  }
  /// The element entries of the layout the target asks for, slot by slot.
  const TangentEntry* tangent_entries(const AssemblyTarget& target) const {
    return target.layout == 0 ? tangent_entries_.data() : bound_layout(target).entries.data();
  }
  /// The numbered layout the target asks for, bound with the target's stamp.
  const SlotLayout& bound_layout(const AssemblyTarget& target) const {
    if (slot_layout_stamp(target.layout) == 0 || slot_layout_stamp(target.layout) != target.stamp)
      throw std::logic_error("block '" + name_ + "': a tangent assembled in slot layout " +
                             std::to_string(target.layout) + ", which is not bound to it");
    return layouts_[target.layout - 1];
  }
  /// Entries with their slots moved to 'place'.
  static std::vector<TangentEntry> placed(std::vector<TangentEntry> entries, const std::vector<int>& place) {
    for (TangentEntry& t : entries) t.slot = place[t.slot];
    return entries;
  }
  /// The batch's first element with a non-finite residual entry, named.
  [[noreturn]] void throw_non_finite_batch() const {
    const double* residual = batch_->residual();
    const int count = size();
    for (int e = 0; e < count; ++e) {
      Vector element;
      for (int k = 0; k < kDofs; ++k) element[k] = residual[k * count + e];
      if (!element.allFinite()) throw_non_finite(e, "residual", element);
    }
    throw std::logic_error("block '" + name_ + "': a non-finite residual entry went missing");
  }
  /// Names the element, its nodes and the first node and DOF whose entry is NaN or infinite
  /// (nodes and elements numbered from 1, as in decks).
  [[noreturn]] void throw_non_finite(int e, const char* what, const Vector& values) const {
    static const char* const kDofNames[kDofsPerNode] = {"ux", "uy", "rz"};
    std::string nodes;
    for (int n : nodes_[e]) nodes += (nodes.empty() ? "" : ", ") + std::to_string(n + 1);
    int first = 0;
    while (first < kDofs - 1 && std::isfinite(values[first])) ++first;
    throw NonFiniteResult("element " + std::to_string(e + 1) + " of block '" + name_ + "' (nodes " + nodes +
                          ") produced a non-finite " + what + " at node " +
                          std::to_string(nodes_[e][first / kDofsPerNode] + 1) + ", " + kDofNames[first % kDofsPerNode] +
                          " (" + std::to_string(values[first]) + ")");
  }

  std::string name_;
  std::vector<std::array<int, kNodes>> nodes_;
  std::vector<Kernel> kernels_;
  std::vector<History> committed_, base_, trial_;
  std::vector<TangentEntry> tangent_entries_;
  std::vector<int> element_entries_;         // element e's entries: [element_entries_[e], element_entries_[e + 1])
  std::vector<TangentEntry> batch_entries_;  // entry: the place in the batch's tangent
  std::vector<SlotLayout> layouts_;          // the numbered slot layouts 1, 2, ... at [layout - 1]
  std::vector<int> batch_dofs_;              // the global DOF of the batch's value [k * size + e]
  std::unique_ptr<Batch> batch_;             // kernels with a batch path only
  mutable std::vector<double> gathered_;     // the batch's displacement, velocity and acceleration
};

}  // namespace tirefe
