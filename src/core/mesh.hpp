// Mesh: reference node coordinates in the wheel plane and named node sets.
// Every node carries three degrees of freedom (u_x, u_y, theta_z); see dof_map.hpp.
#pragma once

#include <Eigen/Dense>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace tirefe {

/// Thrown for a model that cannot be built as described (bad node id, empty set, ...).
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr int kDofsPerNode = 3;
enum Component : int { kUx = 0, kUy = 1, kRz = 2 };

class Mesh {
 public:
  int add_node(const Eigen::Vector2d& reference_position) {
    positions_.push_back(reference_position);
    return static_cast<int>(positions_.size()) - 1;
  }
  int node_count() const { return static_cast<int>(positions_.size()); }
  int dof_count() const { return kDofsPerNode * node_count(); }
  const Eigen::Vector2d& position(int node) const { return positions_.at(checked(node)); }

  void define_node_set(const std::string& name, std::vector<int> nodes) {
    if (nodes.empty()) throw ModelError("node set '" + name + "' is empty");
    for (int node : nodes) checked(node);
    node_sets_[name] = std::move(nodes);
  }
  const std::vector<int>& node_set(const std::string& name) const {
    auto found = node_sets_.find(name);
    if (found == node_sets_.end()) throw ModelError("no node set named '" + name + "'");
    return found->second;
  }
  const std::map<std::string, std::vector<int>>& node_sets() const { return node_sets_; }

  int checked(int node) const {
    if (node < 0 || node >= node_count())
      throw ModelError("node " + std::to_string(node) + " does not exist (the mesh has " +
                       std::to_string(node_count()) + " nodes, numbered from 0)");
    return node;
  }

 private:
  std::vector<Eigen::Vector2d> positions_;
  std::map<std::string, std::vector<int>> node_sets_;
};

/// Global index of one nodal degree of freedom.
inline int dof_index(int node, int component) { return kDofsPerNode * node + component; }

}  // namespace tirefe
