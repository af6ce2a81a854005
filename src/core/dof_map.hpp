// DofMap: equation numbers of the free degrees of freedom.
//
// Prescribed DOFs (fixed or driven by a load function) get no equation; their values
// live in the Model's constraint list. DOFs of "condensed" nodes (the spindle, for the
// spindle-force macro) are numbered after every other free DOF, so the tangent splits
// into the blocks [K_uu K_us; K_su K_ss] of docs/model.md eq. (25) by a single index.
#pragma once

#include <vector>

namespace tirefe {

class DofMap {
 public:
  static constexpr int kPrescribed = -1;

  void number(int dof_count, const std::vector<bool>& prescribed, const std::vector<bool>& condensed) {
    equation_of_dof_.assign(dof_count, kPrescribed);
    dof_of_equation_.clear();
    for (int pass = 0; pass < 2; ++pass) {
      for (int dof = 0; dof < dof_count; ++dof) {
        if (prescribed[dof] || condensed[dof] != (pass == 1)) continue;
        equation_of_dof_[dof] = static_cast<int>(dof_of_equation_.size());
        dof_of_equation_.push_back(dof);
      }
    }
  }

  int equation(int dof) const { return equation_of_dof_[dof]; }
  int dof(int equation) const { return dof_of_equation_[equation]; }
  int equation_count() const { return static_cast<int>(dof_of_equation_.size()); }
  int dof_count() const { return static_cast<int>(equation_of_dof_.size()); }
  bool is_prescribed(int dof) const { return equation_of_dof_[dof] == kPrescribed; }

 private:
  std::vector<int> equation_of_dof_;
  std::vector<int> dof_of_equation_;
};

}  // namespace tirefe
