// Model: the mesh, element blocks, loads and constraints of one structure, with its
// DOF numbering. Building is free-form; finalize() numbers the equations and must be
// called again after the structure changes (the Assembler rebuilds its pattern then).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/dof_map.hpp"
#include "core/element.hpp"
#include "core/load_function.hpp"
#include "core/mesh.hpp"
#include "core/state.hpp"

namespace tirefe {

/// A nodal force or a prescribed displacement: value * load_function(t) on one DOF.
struct ScaledDofValue {
  int dof;
  double value;
  int load_function;
};

class Model {
 public:
  static constexpr int kRampLoadFunction = 0;  // f(t) = t, always defined

  Model();

  Mesh& mesh() { return mesh_; }
  const Mesh& mesh() const { return mesh_; }
  const DofMap& dof_map() const { return dof_map_; }

  int add_load_function(LoadFunction function);
  const LoadFunction& load_function(int id) const;
  int load_function_count() const { return static_cast<int>(load_functions_.size()); }

  void fix(int node, int component) { prescribe(node, component, 0.0, kRampLoadFunction); }
  /// u = value * f(t) on one DOF (replaces an earlier constraint on it).
  void prescribe(int node, int component, double value, int load_function);
  /// Removes a constraint (the DOF becomes free again).
  void release(int node, int component);
  void add_nodal_load(int node, int component, double value, int load_function);
  /// Numbers the node's DOFs last (their own partition, for the spindle force).
  void condense_node(int node);

  template <class Kernel>
  ElementBlockOf<Kernel>& add_block(const std::string& name) {
    auto block = std::make_unique<ElementBlockOf<Kernel>>(name);
    auto& reference = *block;
    blocks_.push_back(std::move(block));
    structure_changed_ = true;
    return reference;
  }
  const std::vector<std::unique_ptr<ElementBlock>>& blocks() const { return blocks_; }
  ElementBlock& block(const std::string& name) const;

  /// Numbers the equations; returns true if the numbering changed.
  bool finalize();
  int structure_version() const { return structure_version_; }

  /// Sum of nodal loads at time t, one entry per DOF.
  void external_forces(double time, Eigen::VectorXd& forces) const;
  /// Sets the prescribed DOFs of 'state' to their values at time t.
  void apply_prescribed_displacements(double time, State& state) const;
  const std::vector<ScaledDofValue>& prescribed_dofs() const { return prescribed_; }

  void commit_history();
  void revert_history();
  /// Augmented-Lagrangian update of every block; true if one wants another solve.
  bool augment();

 private:
  int checked_component(int component) const;
  int checked_load_function(int id) const;

  Mesh mesh_;
  DofMap dof_map_;
  std::vector<LoadFunction> load_functions_;
  std::vector<ScaledDofValue> prescribed_;
  std::vector<ScaledDofValue> nodal_loads_;
  std::vector<int> condensed_nodes_;
  std::vector<std::unique_ptr<ElementBlock>> blocks_;
  bool structure_changed_ = true;
  int structure_version_ = 0;
};

}  // namespace tirefe
