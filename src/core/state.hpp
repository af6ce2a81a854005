// State: nodal displacements, velocities and accelerations of every DOF (free and
// prescribed alike, indexed by dof_index(node, component)) at one time.
#pragma once

#include <Eigen/Dense>

namespace tirefe {

struct State {
  Eigen::VectorXd displacement;
  Eigen::VectorXd velocity;
  Eigen::VectorXd acceleration;
  double time = 0.0;

  void resize(int dof_count) {
    displacement.setZero(dof_count);
    velocity.setZero(dof_count);
    acceleration.setZero(dof_count);
  }
};

}  // namespace tirefe
