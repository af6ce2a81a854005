#include "solvers/driven_solver.hpp"

#include <algorithm>
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
  ring_ = dynamic_cast<RingSolver*>(&inner_);
  held_.reset();
  held_factors_ = schur_current_ = false;
  driven_in_border_.clear();
  free_in_border_.clear();
  if (!ring_ || !analyze_ring_route()) {  // the general route: the columns Z
    ring_ = nullptr;
    columns_.setZero(pattern.rows(), static_cast<Eigen::Index>(driven_.size()));
    coupling_.setZero(pattern.rows(), static_cast<Eigen::Index>(driven_.size()));
    return;
  }
  held_ = ring_->holding(driven_);
  held_->analyze(pattern);
  columns_.setZero(pattern.rows(), static_cast<Eigen::Index>(driven_.size()));
}

bool DrivenDofSolver::analyze_ring_route() {
  const std::vector<int>& border = ring_->border_equations();
  if (border.size() > static_cast<size_t>(kMaxDriven)) return false;  // H_b of several border nodes
  for (int equation : driven_) {
    const auto place = std::find(border.begin(), border.end(), equation);
    if (place == border.end()) return false;  // a driven equation in the ring
    driven_in_border_.push_back(static_cast<int>(place - border.begin()));
  }
  for (int i = 0; i < static_cast<int>(border.size()); ++i)
    if (std::find(driven_in_border_.begin(), driven_in_border_.end(), i) == driven_in_border_.end())
      free_in_border_.push_back(i);
  border_rhs_.setZero(static_cast<Eigen::Index>(border.size()));
  free_rhs_.setZero(static_cast<Eigen::Index>(free_in_border_.size()));
  return true;
}

void DrivenDofSolver::factorize(const Matrix& matrix) {
  if (!held_) {
    factorize_with_schur(matrix);
    return;
  }
  schur_current_ = held_factors_ = false;
  held_->factorize(matrix);
  held_factors_ = true;
  fresh_factorizations_ = inner_.factorization_count() + held_->factorization_count();
}

double* DrivenDofSolver::begin_assembly() {
  if (!held_) throw std::logic_error("DrivenDofSolver: an assembly into the solver needs the ring route");
  schur_current_ = held_factors_ = false;
  return held_->begin_assembly();
}

void DrivenDofSolver::factorize_assembled() {
  schur_current_ = held_factors_ = false;
  held_->factorize_assembled();
  held_factors_ = true;
  fresh_factorizations_ = inner_.factorization_count() + held_->factorization_count();
}

void DrivenDofSolver::factorize_with_schur_assembled() {
  if (schur_current_) return;
  if (!held_factors_) factorize_assembled();
  // Z_u = A_uu^-1 A_us, column by column (the held solve leaves the driven rows at zero).
  const int count = static_cast<int>(driven_.size());
  for (int j = 0; j < count; ++j) {
    const double* column = held_->held_column(driven_[j]);
    std::copy(column, column + columns_.rows(), columns_.col(j).data());
  }
  held_->solve(columns_);
  for (int i = 0; i < count; ++i) {
    const Eigen::Map<const Eigen::VectorXd> row(held_->held_row(driven_[i]), columns_.rows());
    for (int j = 0; j < count; ++j)
      schur_(i, j) = held_->held_column(driven_[j])[driven_[i]] - row.dot(columns_.col(j));
  }
  schur_current_ = true;
}

void DrivenDofSolver::multiply_driven_columns(const Eigen::VectorXd& x, Eigen::VectorXd& product) const {
  product.setZero(x.size());
  for (int equation : driven_)
    product += x[equation] * Eigen::Map<const Eigen::VectorXd>(held_->held_column(equation), x.size());
}

const DrivenDofSolver::SmallMatrix& DrivenDofSolver::schur_complement() const {
  if (!schur_current_)
    throw std::logic_error("DrivenDofSolver: schur_complement() needs factorize_with_schur() of the matrix first");
  return schur_;
}

void DrivenDofSolver::factorize_with_schur(const Matrix& matrix) {
  schur_current_ = held_factors_ = false;
  if (ring_) {
    factorize_on_ring(matrix);
    schur_current_ = true;
    return;
  }
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
  schur_current_ = true;
}

void DrivenDofSolver::factorize_on_ring(const Matrix& matrix) {
  ring_->factorize(matrix);
  const Eigen::MatrixXd& border = ring_->border_schur_complement();
  const int driven = static_cast<int>(driven_in_border_.size()), free = static_cast<int>(free_in_border_.size());
  SmallMatrix free_block(free, free), driven_free(driven, free), free_driven(free, driven);
  for (int i = 0; i < free; ++i) {
    for (int j = 0; j < free; ++j) free_block(i, j) = border(free_in_border_[i], free_in_border_[j]);
    for (int j = 0; j < driven; ++j) free_driven(i, j) = border(free_in_border_[i], driven_in_border_[j]);
  }
  for (int i = 0; i < driven; ++i) {
    for (int j = 0; j < driven; ++j) schur_(i, j) = border(driven_in_border_[i], driven_in_border_[j]);
    for (int j = 0; j < free; ++j) driven_free(i, j) = border(driven_in_border_[i], free_in_border_[j]);
  }
  free_inverse_ = free ? SmallMatrix(free_block.inverse()) : SmallMatrix(0, 0);  // the spindle's free rz, if any
  driven_from_free_ = driven_free * free_inverse_;
  if (free) schur_ -= driven_from_free_ * free_driven;
  fresh_factorizations_ = inner_.factorization_count() + held_->factorization_count();
  refactorizations_ = inner_.refactorization_count();
}

void DrivenDofSolver::solve_on_ring(Eigen::VectorXd& right_hand_side) const {
  ring_->condense(right_hand_side, border_rhs_);
  for (size_t i = 0; i < free_in_border_.size(); ++i)
    free_rhs_[static_cast<Eigen::Index>(i)] = border_rhs_[free_in_border_[i]];
  for (size_t i = 0; i < driven_.size(); ++i)  // y_s + delta
    border_rhs_[driven_in_border_[i]] = driven_from_free_.row(static_cast<Eigen::Index>(i)).dot(free_rhs_);
  ring_->solve_condensed(border_rhs_, right_hand_side);
}

void DrivenDofSolver::solve(Eigen::VectorXd& right_hand_side) const {
  if (held_factors_) {
    held_->solve(right_hand_side);  // x_s = 0 by the hold
    return;
  }
  if (ring_) {  // the driven rows' right-hand side is replaced in the condensed border
    solve_on_ring(right_hand_side);
    for (int equation : driven_) right_hand_side[equation] = 0.0;  // round-off of the border solve
    return;
  }
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
