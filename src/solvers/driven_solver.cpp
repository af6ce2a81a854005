#include "solvers/driven_solver.hpp"

#include <stdexcept>

namespace tirefe {

DrivenDofSolver::DrivenDofSolver(LinearSolver& inner, std::vector<int> driven)
    : inner_(inner), driven_(std::move(driven)) {
  if (driven_.empty() || driven_.size() > static_cast<size_t>(kMaxDriven))
    throw std::invalid_argument("DrivenDofSolver drives 1 to 3 equations");
  const int count = static_cast<int>(driven_.size());
  schur_.setZero(count, count);
  driven_part_.setZero(count);
}

void DrivenDofSolver::analyze(const Matrix& pattern) {
  inner_.analyze(pattern);
  columns_.setZero(pattern.rows(), static_cast<Eigen::Index>(driven_.size()));
  coupling_.setZero(pattern.rows(), static_cast<Eigen::Index>(driven_.size()));
}

void DrivenDofSolver::factorize(const Matrix& matrix) {
  inner_.factorize(matrix);
  const int count = static_cast<int>(driven_.size());
  columns_.setZero();
  for (int j = 0; j < count; ++j) columns_(driven_[j], j) = 1.0;
  inner_.solve(columns_);
  SmallMatrix inverse_schur(count, count);  // Z_s
  for (int i = 0; i < count; ++i) inverse_schur.row(i) = columns_.row(driven_[i]);
  schur_ = inverse_schur.inverse();
  coupling_.noalias() = columns_ * schur_;
  for (int i = 0; i < count; ++i) coupling_.row(driven_[i]).setZero();
  fresh_factorizations_ = inner_.factorization_count();
  refactorizations_ = inner_.refactorization_count();
}

void DrivenDofSolver::solve(Eigen::VectorXd& right_hand_side) const {
  for (int equation : driven_) right_hand_side[equation] = 0.0;
  inner_.solve(right_hand_side);
  for (size_t i = 0; i < driven_.size(); ++i) driven_part_[static_cast<Eigen::Index>(i)] = right_hand_side[driven_[i]];
  right_hand_side.noalias() -= coupling_ * driven_part_;
  for (int equation : driven_) right_hand_side[equation] = 0.0;
}

void DrivenDofSolver::solve(Eigen::MatrixXd& right_hand_sides) const {
  Eigen::VectorXd column;
  for (Eigen::Index j = 0; j < right_hand_sides.cols(); ++j) {
    column = right_hand_sides.col(j);
    solve(column);
    right_hand_sides.col(j) = column;
  }
}

}  // namespace tirefe
