#include "core/model.hpp"

#include <algorithm>

namespace tirefe {

Model::Model() { load_functions_.push_back(LoadFunction::linear()); }

int Model::add_load_function(LoadFunction function) {
  load_functions_.push_back(std::move(function));
  return static_cast<int>(load_functions_.size()) - 1;
}

const LoadFunction& Model::load_function(int id) const { return load_functions_[checked_load_function(id)]; }

int Model::checked_component(int component) const {
  if (component < 0 || component >= kDofsPerNode)
    throw ModelError("DOF component " + std::to_string(component) + " does not exist (ux = 0, uy = 1, rz = 2)");
  return component;
}

int Model::checked_load_function(int id) const {
  if (id < 0 || id >= load_function_count())
    throw ModelError("load function " + std::to_string(id) + " is not defined");
  return id;
}

void Model::prescribe(int node, int component, double value, int load_function) {
  const int dof = dof_index(mesh_.checked(node), checked_component(component));
  checked_load_function(load_function);
  release(node, component);
  prescribed_.push_back({dof, value, load_function});
  structure_changed_ = true;
}

void Model::release(int node, int component) {
  const int dof = dof_index(mesh_.checked(node), checked_component(component));
  auto removed = std::remove_if(prescribed_.begin(), prescribed_.end(),
                                [dof](const ScaledDofValue& constraint) { return constraint.dof == dof; });
  if (removed != prescribed_.end()) {
    prescribed_.erase(removed, prescribed_.end());
    structure_changed_ = true;
  }
}

void Model::add_nodal_load(int node, int component, double value, int load_function) {
  nodal_loads_.push_back(
      {dof_index(mesh_.checked(node), checked_component(component)), value, checked_load_function(load_function)});
}

void Model::condense_node(int node) {
  condensed_nodes_.push_back(mesh_.checked(node));
  structure_changed_ = true;
}

ElementBlock& Model::block(const std::string& name) const {
  for (const auto& block : blocks_)
    if (block->name() == name) return *block;
  throw ModelError("no element block named '" + name + "'");
}

bool Model::finalize() {
  if (!structure_changed_ && dof_map_.dof_count() == mesh_.dof_count()) return false;
  std::vector<bool> prescribed(mesh_.dof_count(), false), condensed(mesh_.dof_count(), false);
  for (const auto& constraint : prescribed_) prescribed[constraint.dof] = true;
  for (int node : condensed_nodes_)
    for (int c = 0; c < kDofsPerNode; ++c) condensed[dof_index(node, c)] = true;
  dof_map_.number(mesh_.dof_count(), prescribed, condensed);
  structure_changed_ = false;
  ++structure_version_;
  return true;
}

void Model::external_forces(double time, Eigen::VectorXd& forces) const {
  forces.setZero(mesh_.dof_count());
  for (const auto& load : nodal_loads_) forces[load.dof] += load.value * load_functions_[load.load_function](time);
}

void Model::apply_prescribed_displacements(double time, State& state) const {
  for (const auto& constraint : prescribed_)
    state.displacement[constraint.dof] = constraint.value * load_functions_[constraint.load_function](time);
}

void Model::commit_history() {
  for (auto& block : blocks_) block->commit();
}

void Model::revert_history() {
  for (auto& block : blocks_) block->revert();
}

bool Model::augment() {
  bool again = false;
  for (auto& block : blocks_) again = block->augment() || again;
  return again;
}

}  // namespace tirefe
