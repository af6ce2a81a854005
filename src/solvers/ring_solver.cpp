#include "solvers/ring_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <type_traits>

#include "core/mesh.hpp"

namespace tirefe {

namespace {

const char* const kComponentNames[kDofsPerNode] = {"ux", "uy", "rz"};

// LU factorization with partial pivoting in place, LAPACK style: step j swaps row j with
// the row p >= j holding the largest |a(p, j)| (pivots[j].row = p) and eliminates below
// the pivot; L (unit diagonal) is left below the diagonal, U on and above it, and the
// pivot's reciprocal in pivots[j].inverse: the solves multiply, a division costs several
// multiplications. The row scales travel with their rows so that each pivot is judged
// against its own row. Returns the position of the first pivot not above
// RingSolver::kPivotTolerance times its row's scale (NaN included), or -1.
template <class Factors>
[[gnu::always_inline]] inline int lu_factor(Factors&& a, RingSolver::Pivot* pivots, double* row_scale) {
  const Eigen::Index size = a.rows();
  for (Eigen::Index j = 0; j < size; ++j) {
    Eigen::Index pivot_row = j;
    for (Eigen::Index i = j + 1; i < size; ++i)
      if (std::abs(a(i, j)) > std::abs(a(pivot_row, j))) pivot_row = i;
    pivots[j].row = static_cast<int>(pivot_row);
    if (pivot_row != j) {
      a.row(j).swap(a.row(pivot_row));
      std::swap(row_scale[j], row_scale[pivot_row]);
    }
    const double pivot = a(j, j);
    if (!(std::abs(pivot) > RingSolver::kPivotTolerance * row_scale[j])) return static_cast<int>(j);
    pivots[j].inverse = 1.0 / pivot;
    for (Eigen::Index i = j + 1; i < size; ++i) {
      a(i, j) *= pivots[j].inverse;
      for (Eigen::Index c = j + 1; c < size; ++c) a(i, c) -= a(i, j) * a(j, c);
    }
  }
  return -1;
}

// B <- A^-1 B with the factors of lu_factor(), for any number of columns of B.
template <class Factors, class Columns>
[[gnu::always_inline]] inline void lu_solve(const Factors& lu, const RingSolver::Pivot* pivots, Columns&& b) {
  const Eigen::Index size = lu.rows();
  for (Eigen::Index j = 0; j < size; ++j)
    if (pivots[j].row != j) b.row(j).swap(b.row(pivots[j].row));
  for (Eigen::Index j = 0; j < size; ++j)
    for (Eigen::Index i = j + 1; i < size; ++i) b.row(i) -= lu(i, j) * b.row(j);
  for (Eigen::Index j = size - 1; j >= 0; --j) {
    b.row(j) *= pivots[j].inverse;
    for (Eigen::Index i = 0; i < j; ++i) b.row(i) -= lu(i, j) * b.row(j);
  }
}

using Block = Eigen::Map<Eigen::Matrix3d>;
using ConstBlock = Eigen::Map<const Eigen::Matrix3d>;
using Vector3 = Eigen::Map<Eigen::Vector3d>;
using ConstVector3 = Eigen::Map<const Eigen::Vector3d>;

}  // namespace

RingSolver::RingSolver(const DofMap& dofs, std::vector<int> ring_nodes, std::vector<int> border_nodes)
    : dofs_(dofs), ring_nodes_(std::move(ring_nodes)), border_nodes_(std::move(border_nodes)) {
  if (ring_nodes_.empty()) throw ModelError("ring solver: the ring needs at least one node");
  std::vector<int> all = ring_nodes_;
  all.insert(all.end(), border_nodes_.begin(), border_nodes_.end());
  std::sort(all.begin(), all.end());
  if (all.front() < 0) throw ModelError("ring solver: node " + std::to_string(all.front()) + " does not exist");
  const auto repeated = std::adjacent_find(all.begin(), all.end());
  if (repeated != all.end())
    throw ModelError("ring solver: node " + std::to_string(*repeated) +
                     " is listed twice (each node belongs to the ring or to the border, once)");
}

std::unique_ptr<RingSolver> RingSolver::holding(std::vector<int> held_equations) const {
  auto solver = std::make_unique<RingSolver>(dofs_, ring_nodes_, border_nodes_);
  std::sort(held_equations.begin(), held_equations.end());
  held_equations.erase(std::unique(held_equations.begin(), held_equations.end()), held_equations.end());
  solver->held_ = std::move(held_equations);
  return solver;
}

int RingSolver::entry_offset(int row, int column) const {
  // Blocks are stored column-major: D, U, L 3x3; W 3 x e; V e x 3; S e x e; a satellite's 3x3.
  if (row >= satellite_start_ || column >= satellite_start_) {
    const int within = row % 3 + 3 * (column % 3), row_block = row - row % 3, column_block = column - column % 3;
    const int row_satellite = (row - satellite_start_) / 3, column_satellite = (column - satellite_start_) / 3;
    if (row_block == column_block) return satellite_offset(row_satellite) + within;
    if (row >= satellite_start_ && satellite_hosts_[row_satellite] == column_block)
      return satellite_offset(row_satellite) + 9 + within;
    if (column >= satellite_start_ && satellite_hosts_[column_satellite] == row_block)
      return satellite_offset(column_satellite) + 18 + within;
    return -1;  // a satellite and a node other than its host
  }
  const int border_start = 3 * chain_;
  if (row < border_start && column < border_start) {
    const int row_node = row / 3, column_node = column / 3, within = row % 3 + 3 * (column % 3);
    if (row_node == column_node) return diagonal_offset(row_node) + within;
    if (column_node == row_node + 1) return upper_offset(row_node) + within;
    if (row_node == column_node + 1) return lower_offset(column_node) + within;
    return -1;  // chain nodes that are not ring neighbours
  }
  // r_0 (the first 3 columns/rows of E) neighbours c_0 = r_1 and c_{m-1} = r_{n-1} only.
  if (row < border_start) {
    const int node = row / 3, e = column - border_start;
    if (e < 3 && node != 0 && node != chain_ - 1) return -1;
    return border_column_offset(node) + row % 3 + 3 * e;
  }
  if (column < border_start) {
    const int node = column / 3, e = row - border_start;
    if (e < 3 && node != 0 && node != chain_ - 1) return -1;
    return border_row_offset(node) + e + width_ * (column % 3);
  }
  return border_block_offset() + (row - border_start) + width_ * (column - border_start);
}

std::string RingSolver::describe_node(int position) const {
  if (position >= satellite_start_) {
    const int i = (position - satellite_start_) / 3, host = satellite_hosts_[i];
    const std::string node = "node " + std::to_string(satellite_nodes_[i]);
    return host < 0 ? node + " (in neither the ring nor the border list)"
                    : "satellite " + node + " (of " + describe_node(host) + ")";
  }
  const int border_start = 3 * chain_;
  const int ring_size = static_cast<int>(ring_nodes_.size());
  if (position >= border_start + 3)
    return "border node " + std::to_string(dofs_.dof(border_equations_[position - border_start - 3]) / kDofsPerNode);
  const int ring_position = position < border_start ? position / 3 + 1 : 0;
  return "ring node " + std::to_string(ring_nodes_[ring_position]) + " (position " + std::to_string(ring_position) +
         " of " + std::to_string(ring_size) + " in the ring)";
}

void RingSolver::analyze(const Matrix& pattern) {
  interior_factored_ = border_factored_ = condensed_ = false;
  const int equations = dofs_.equation_count();
  if (!pattern.isCompressed() || pattern.rows() != equations || pattern.cols() != equations)
    throw ModelError("ring solver: the matrix is " + std::to_string(pattern.rows()) + " x " +
                     std::to_string(pattern.cols()) + " but the model numbers " + std::to_string(equations) +
                     " free equations (analyse the assembled, compressed tangent after Model::finalize)");
  chain_ = static_cast<int>(ring_nodes_.size()) - 1;

  // Equations -> padded positions; ring and satellite DOFs without an equation become
  // identity padding, the border's are left out.
  constexpr int kUnplaced = -1, kHeld = -2;
  position_of_equation_.assign(equations, kUnplaced);
  for (int equation : held_) {
    if (equation < 0 || equation >= equations)
      throw ModelError("ring solver: held equation " + std::to_string(equation) + " does not exist");
    position_of_equation_[equation] = kHeld;
  }
  padding_.clear();
  border_equations_.clear();
  auto check_node = [&](int node) {
    if (dof_index(node, 0) >= dofs_.dof_count())
      throw ModelError("ring solver: node " + std::to_string(node) + " does not exist (the model has " +
                       std::to_string(dofs_.dof_count() / kDofsPerNode) + " nodes)");
  };
  auto place = [&](int node, int first_position) {
    check_node(node);
    for (int c = 0; c < kDofsPerNode; ++c) {
      const int equation = dofs_.equation(dof_index(node, c)), position = first_position + c;
      if (equation == DofMap::kPrescribed)
        padding_.push_back(position);
      else if (position_of_equation_[equation] == kHeld)
        throw ModelError("ring solver: equation " + std::to_string(equation) + " of node " + std::to_string(node) +
                         " is held but is no border equation (only the border's equations can be held)");
      else
        position_of_equation_[equation] = position;
    }
  };
  for (int k = 0; k < chain_; ++k) place(ring_nodes_[k + 1], 3 * k);
  place(ring_nodes_[0], 3 * chain_);
  for (int node : border_nodes_) {
    check_node(node);
    for (int c = 0; c < kDofsPerNode; ++c) {
      const int equation = dofs_.equation(dof_index(node, c));
      if (equation == DofMap::kPrescribed || position_of_equation_[equation] == kHeld) continue;
      position_of_equation_[equation] = 3 * chain_ + 3 + static_cast<int>(border_equations_.size());
      border_equations_.push_back(equation);
    }
  }
  width_ = 3 + border_size();
  satellite_start_ = 3 * chain_ + 3 * ((width_ + 2) / 3);  // on a multiple of 3, as the node blocks are
  // The nodes of the remaining equations are satellites, if find_hosts() finds them a host.
  satellite_nodes_.clear();
  satellite_hosts_.clear();
  for (int equation = 0; equation < equations; ++equation)
    if (position_of_equation_[equation] == kUnplaced) {
      satellite_nodes_.push_back(dofs_.dof(equation) / kDofsPerNode);
      satellite_hosts_.push_back(-1);
      place(satellite_nodes_.back(), satellite_position(static_cast<int>(satellite_nodes_.size()) - 1));
    }
  const int satellites = static_cast<int>(satellite_nodes_.size());
  padded_size_ = satellite_start_ + 3 * satellites;
  planar_satellites_.assign(satellites, false);
  for (int i = 0; i < satellites; ++i) {
    auto prescribed = [&](int c) { return dofs_.equation(dof_index(satellite_nodes_[i], c)) == DofMap::kPrescribed; };
    planar_satellites_[i] = prescribed(kRz) && !prescribed(kUx) && !prescribed(kUy);
  }
  for (int equation : held_) position_of_equation_[equation] = padded_size_;  // out of the factors
  find_hosts(pattern);

  // Every stored entry must land in a block of the structure.
  destination_.resize(pattern.nonZeros());
  row_position_.resize(pattern.nonZeros());
  const int* starts = pattern.outerIndexPtr();
  const int* rows = pattern.innerIndexPtr();
  held_coupling_offset_ = satellite_offset(satellites);
  for (int column = 0; column < equations; ++column)
    for (int entry = starts[column]; entry < starts[column + 1]; ++entry) {
      const int row_position = position_of_equation_[rows[entry]];
      const int column_position = position_of_equation_[column];
      if (row_position == padded_size_ || column_position == padded_size_) {  // a held row or column
        destination_[entry] = column_position == padded_size_ ? held_column_offset(held_index(column)) + rows[entry]
                                                              : held_row_offset(held_index(rows[entry])) + column;
        row_position_[entry] = padded_size_;
        continue;
      }
      destination_[entry] = entry_offset(row_position, column_position);
      row_position_[entry] = row_position;
      if (destination_[entry] < 0)
        throw ModelError("ring solver: the tangent couples " + describe_node(row_position) + " (" +
                         kComponentNames[row_position % 3] + ") to " + describe_node(column_position) + " (" +
                         kComponentNames[column_position % 3] +
                         "), which are not ring neighbours; give the ring nodes in ring order, the nodes "
                         "coupled to everything as border nodes, or use the KLU solver");
    }
  // The same destinations row by row (held ones in row padded_size_), for
  // factorize_assembled()'s row scales.
  row_starts_.assign(padded_size_ + 3, 0);
  for (int row : row_position_) ++row_starts_[row + 2];
  for (int position = 0; position <= padded_size_ + 1; ++position) row_starts_[position + 1] += row_starts_[position];
  row_offsets_.resize(destination_.size());
  for (size_t entry = 0; entry < destination_.size(); ++entry)
    row_offsets_[row_starts_[row_position_[entry] + 1]++] = destination_[entry];
  padding_offsets_.clear();
  for (int position : padding_) padding_offsets_.push_back(entry_offset(position, position));
  pattern_starts_.assign(starts, starts + equations + 1);
  pattern_rows_.assign(rows, rows + pattern.nonZeros());

  blocks_.assign(held_row_offset(static_cast<int>(held_.size())), 0.0);
  row_scale_.assign(padded_size_ + 1, 0.0);
  pivots_.assign(padded_size_, Pivot{});
  border_schur_.setZero(border_size(), border_size());
  work_.setZero(padded_size_ + 1);
}

int RingSolver::held_index(int equation) const {
  const auto place = std::lower_bound(held_.begin(), held_.end(), equation);
  if (place == held_.end() || *place != equation)
    throw std::invalid_argument("ring solver: equation " + std::to_string(equation) + " is not held");
  return static_cast<int>(place - held_.begin());
}

const double* RingSolver::held_column(int equation) const {
  return blocks_.data() + held_column_offset(held_index(equation));
}

const double* RingSolver::held_row(int equation) const {
  return blocks_.data() + held_row_offset(held_index(equation));
}

void RingSolver::find_hosts(const Matrix& pattern) {
  const int ring_end = 3 * chain_ + 3;  // the ring's padded positions come first
  auto couple = [&](int satellite, int other) {
    const int i = (satellite - satellite_start_) / 3, other_block = other - other % 3;
    int& host = satellite_hosts_[i];
    if (other_block == satellite - satellite % 3 || other_block == host) return;
    if (other_block < ring_end && host < 0) {
      host = other_block;
      return;
    }
    throw ModelError("ring solver: node " + std::to_string(satellite_nodes_[i]) +
                     " belongs to neither a ring nor a border node and is coupled to " +
                     (host < 0 ? "" : describe_node(host) + " and to ") + describe_node(other_block) +
                     "; a node outside the lists may be coupled to one ring node only (a satellite, as a tread "
                     "layer's contact node): give it as a ring or border node, or use the KLU solver");
  };
  const int* starts = pattern.outerIndexPtr();
  const int* rows = pattern.innerIndexPtr();
  for (int column = 0; column < pattern.cols(); ++column)
    for (int entry = starts[column]; entry < starts[column + 1]; ++entry) {
      const int row_position = position_of_equation_[rows[entry]], column_position = position_of_equation_[column];
      if (row_position == padded_size_ || column_position == padded_size_) continue;  // held
      if (row_position >= satellite_start_) couple(row_position, column_position);
      if (column_position >= satellite_start_) couple(column_position, row_position);
    }
  for (size_t i = 0; i < satellite_hosts_.size(); ++i)
    if (satellite_hosts_[i] < 0)
      throw ModelError("ring solver: node " + std::to_string(satellite_nodes_[i]) +
                       " belongs to neither a ring nor a border node and is coupled to no ring node; give it as a "
                       "ring or border node, or use the KLU solver");
}

void RingSolver::check_same_pattern(const Matrix& matrix) const {
  const bool same = matrix.isCompressed() && matrix.rows() + 1 == static_cast<Eigen::Index>(pattern_starts_.size()) &&
                    matrix.cols() == matrix.rows() &&
                    std::equal(pattern_starts_.begin(), pattern_starts_.end(), matrix.outerIndexPtr()) &&
                    std::equal(pattern_rows_.begin(), pattern_rows_.end(), matrix.innerIndexPtr());
  if (!same)
    throw std::logic_error(
        "ring solver: the matrix's sparsity pattern is not the one analyze() saw "
        "(analyse again after the model's structure changes)");
}

template <class Work>
void RingSolver::with_width(Work&& work) const {
  // A spindle border (fixed, on a dead axle, free) gets fixed-size blocks; other widths
  // run the same code on dynamic-size blocks.
  if (width_ == 3)
    work(std::integral_constant<int, 3>{});
  else if (width_ == 4)
    work(std::integral_constant<int, 4>{});
  else if (width_ == 6)
    work(std::integral_constant<int, 6>{});
  else
    work(std::integral_constant<int, Eigen::Dynamic>{});
}

[[noreturn]] void RingSolver::throw_singular(int position, double pivot, double scale) const {
  char size[96];
  if (scale > 0.0 && std::isfinite(scale))
    std::snprintf(size, sizeof size, "a pivot %.1e times its row's largest entry", std::abs(pivot) / scale);
  else
    std::snprintf(size, sizeof size, "a %s row", scale == 0.0 ? "zero" : "non-finite");
  throw SingularMatrix(std::string("ring solver: ") + size + " at " + describe_node(position) +
                       ": the tangent matrix is singular (a mechanism, an unconstrained rigid-body motion, or a DOF "
                       "no element stiffens; check the boundary conditions)");
}

void RingSolver::factorize_interior(const Matrix& matrix) {
  if (pattern_starts_.empty()) analyze(matrix);
  check_same_pattern(matrix);
  clear_blocks();

  // Scatter the values into the padded blocks and note each row's largest entry.
  std::fill(row_scale_.begin(), row_scale_.end(), 0.0);
  const double* values = matrix.valuePtr();
  const int stored = static_cast<int>(matrix.nonZeros());
  for (int entry = 0; entry < stored; ++entry) {
    blocks_[destination_[entry]] = values[entry];
    double& scale = row_scale_[row_position_[entry]];
    scale = std::max(scale, std::abs(values[entry]));
  }
  eliminate_interior();
}

void RingSolver::clear_blocks() {
  interior_factored_ = border_factored_ = condensed_ = assembly_open_ = false;
  std::fill(blocks_.begin(), blocks_.end(), 0.0);
}

double* RingSolver::begin_assembly() {
  if (pattern_starts_.empty()) throw std::logic_error("ring solver: begin_assembly() needs analyze() first");
  clear_blocks();
  assembly_open_ = true;
  return blocks_.data();
}

void RingSolver::factorize_assembled() {
  if (!assembly_open_)
    throw std::logic_error("ring solver: factorize_assembled() needs begin_assembly() and an assembly first");
  assembly_open_ = false;  // the elimination works in place: one factorization per assembly
  // Each row's largest entry, as factorize_interior() notes it while it scatters.
  const double* base = blocks_.data();
  for (int position = 0; position < padded_size_; ++position) {
    double scale = 0.0;
    for (int k = row_starts_[position]; k < row_starts_[position + 1]; ++k)
      scale = std::max(scale, std::abs(base[row_offsets_[k]]));
    row_scale_[position] = scale;
  }
  eliminate_interior();
  factor_border();
}

void RingSolver::eliminate_interior() {
  for (size_t i = 0; i < padding_.size(); ++i) {
    blocks_[padding_offsets_[i]] = 1.0;
    row_scale_[padding_[i]] = 1.0;
  }
  eliminate_satellites();
  with_width([this](auto width) { eliminate_chain<decltype(width)::value>(); });
  eliminate_first_ring_node();
  Eigen::Map<const Eigen::MatrixXd> s(blocks_.data() + border_block_offset(), width_, width_);
  border_schur_ = s.bottomRightCorner(border_size(), border_size());
  interior_factored_ = true;
  ++fresh_factorizations_;
}

Eigen::Map<Eigen::Matrix3d, 0, Eigen::OuterStride<>> RingSolver::host_block(int i) {
  const int host = satellite_hosts_[i];
  return Eigen::Map<Eigen::Matrix3d, 0, Eigen::OuterStride<>>(blocks_.data() + entry_offset(host, host),
                                                              Eigen::OuterStride<>(host < 3 * chain_ ? 3 : width_));
}

void RingSolver::eliminate_satellites() {
  double* base = blocks_.data();
  for (int i = 0; i < static_cast<int>(satellite_nodes_.size()); ++i) {
    const int position = satellite_position(i);
    Block d(base + satellite_offset(i)), to_host(base + satellite_offset(i) + 9);
    const ConstBlock from_host(base + satellite_offset(i) + 18);
    if (planar_satellites_[i]) {  // the rotation's padding row and column: identity, no coupling
      auto translation = d.topLeftCorner<2, 2>();
      const int failed = lu_factor(translation, &pivots_[position], &row_scale_[position]);
      if (failed >= 0) throw_singular(position + failed, d(failed, failed), row_scale_[position + failed]);
      pivots_[position + 2] = Pivot{2, 1.0};  // the padding's, as the whole block's factorisation has it
      lu_solve(translation, &pivots_[position], to_host.topRows<2>());
      host_block(i) -= from_host.leftCols<2>().lazyProduct(to_host.topRows<2>());
      continue;
    }
    const int failed = lu_factor(d, &pivots_[position], &row_scale_[position]);
    if (failed >= 0) throw_singular(position + failed, d(failed, failed), row_scale_[position + failed]);
    lu_solve(d, &pivots_[position], to_host);
    host_block(i) -= from_host.lazyProduct(to_host);
  }
}

void RingSolver::forward_satellites(double* y) const {
  const double* base = blocks_.data();
  for (int i = 0; i < static_cast<int>(satellite_nodes_.size()); ++i) {
    Vector3 z(y + satellite_position(i));
    const ConstBlock d(base + satellite_offset(i)), from_host(base + satellite_offset(i) + 18);
    if (planar_satellites_[i]) {  // the padding's entry moves nothing
      auto translation = z.head<2>();
      lu_solve(d.topLeftCorner<2, 2>(), &pivots_[satellite_position(i)], translation);
      Vector3(y + satellite_hosts_[i]) -= from_host.leftCols<2>().lazyProduct(translation);
      continue;
    }
    lu_solve(d, &pivots_[satellite_position(i)], z);
    Vector3(y + satellite_hosts_[i]) -= from_host.lazyProduct(z);
  }
}

void RingSolver::back_satellites(double* x) const {
  const double* base = blocks_.data();
  for (int i = 0; i < static_cast<int>(satellite_nodes_.size()); ++i) {
    const ConstBlock to_host(base + satellite_offset(i) + 9);
    const ConstVector3 host(x + satellite_hosts_[i]);
    if (planar_satellites_[i])
      Vector3(x + satellite_position(i)).head<2>() -= to_host.topRows<2>().lazyProduct(host);
    else
      Vector3(x + satellite_position(i)) -= to_host.lazyProduct(host);
  }
}

template <int Width>
void RingSolver::eliminate_chain() {
  // Coefficient-based (lazy) products throughout: the blocks are far too small for
  // GEMM's packing, and they never allocate.
  using Columns = Eigen::Map<Eigen::Matrix<double, 3, Width>>;  // W_k, then Y_k
  using Rows = Eigen::Map<Eigen::Matrix<double, Width, 3>>;     // V_k
  double* base = blocks_.data();
  Eigen::Map<Eigen::Matrix<double, Width, Width>> s(base + border_block_offset(), width_, width_);
  for (int k = 0; k < chain_; ++k) {
    Block d(base + diagonal_offset(k));
    Columns w(base + border_column_offset(k), 3, width_);
    Rows v(base + border_row_offset(k), width_, 3);
    if (k > 0) {
      const ConstBlock lower(base + lower_offset(k - 1)), x(base + upper_offset(k - 1));
      d -= lower.lazyProduct(x);
      w -= lower.lazyProduct(Columns(base + border_column_offset(k - 1), 3, width_));
      v -= Rows(base + border_row_offset(k - 1), width_, 3).lazyProduct(x);
    }
    const int failed = lu_factor(d, &pivots_[3 * k], &row_scale_[3 * k]);
    if (failed >= 0) throw_singular(3 * k + failed, d(failed, failed), row_scale_[3 * k + failed]);
    lu_solve(d, &pivots_[3 * k], w);
    s -= v.lazyProduct(w);
    if (k + 1 < chain_) lu_solve(d, &pivots_[3 * k], Block(base + upper_offset(k)));
  }
}

void RingSolver::eliminate_first_ring_node() {
  Eigen::Map<Eigen::MatrixXd> s(blocks_.data() + border_block_offset(), width_, width_);
  const int first = 3 * chain_, border = width_ - 3;
  auto s00 = s.topLeftCorner<3, 3>();
  const int failed = lu_factor(s00, &pivots_[first], &row_scale_[first]);
  if (failed >= 0) throw_singular(first + failed, s00(failed, failed), row_scale_[first + failed]);
  auto s0b = s.topRightCorner(3, border);
  lu_solve(s00, &pivots_[first], s0b);
  s.bottomRightCorner(border, border) -= s.bottomLeftCorner(border, 3).lazyProduct(s0b);
}

void RingSolver::factorize(const Matrix& matrix) {
  factorize_interior(matrix);
  factor_border();
}

void RingSolver::factor_border() {
  const int first = 3 * chain_ + 3, border = width_ - 3;
  Eigen::Map<Eigen::MatrixXd> s(blocks_.data() + border_block_offset(), width_, width_);
  const int failed = lu_factor(s.bottomRightCorner(border, border), &pivots_[first], &row_scale_[first]);
  if (failed >= 0) throw_singular(first + failed, s(3 + failed, 3 + failed), row_scale_[first + failed]);
  border_factored_ = true;
}

void RingSolver::check_size(Eigen::Index size) const {
  if (size != static_cast<Eigen::Index>(position_of_equation_.size()))
    throw std::invalid_argument("ring solver: a right-hand side of " + std::to_string(size) + " entries for " +
                                std::to_string(position_of_equation_.size()) + " equations");
}

void RingSolver::gather(const double* values) const {
  work_.setZero();
  for (size_t equation = 0; equation < position_of_equation_.size(); ++equation)
    work_[position_of_equation_[equation]] = values[equation];
}

template <int Width>
void RingSolver::forward(double* y) const {
  using ConstRows = Eigen::Map<const Eigen::Matrix<double, Width, 3>>;
  const double* base = blocks_.data();
  Eigen::Map<Eigen::Matrix<double, Width, 1>> y_border(y + 3 * chain_, width_);
  forward_satellites(y);
  for (int k = 0; k < chain_; ++k) {
    Vector3 z(y + 3 * k);
    if (k > 0) z -= ConstBlock(base + lower_offset(k - 1)).lazyProduct(ConstVector3(y + 3 * k - 3));
    lu_solve(ConstBlock(base + diagonal_offset(k)), &pivots_[3 * k], z);
    y_border -= ConstRows(base + border_row_offset(k), width_, 3).lazyProduct(z);
  }
  Eigen::Map<const Eigen::MatrixXd> s(base + border_block_offset(), width_, width_);
  const int border = width_ - 3;
  Vector3 z0(y + 3 * chain_);
  lu_solve(s.topLeftCorner<3, 3>(), &pivots_[3 * chain_], z0);
  if (border > 0)
    Eigen::Map<Eigen::VectorXd>(y + 3 * chain_ + 3, border) -= s.bottomLeftCorner(border, 3).lazyProduct(z0);
}

template <int Width>
void RingSolver::back(double* x) const {
  using ConstColumns = Eigen::Map<const Eigen::Matrix<double, 3, Width>>;
  const double* base = blocks_.data();
  Eigen::Map<const Eigen::MatrixXd> s(base + border_block_offset(), width_, width_);
  const int border = width_ - 3;
  if (border > 0)
    Vector3(x + 3 * chain_) -=
        s.topRightCorner(3, border).lazyProduct(Eigen::Map<const Eigen::VectorXd>(x + 3 * chain_ + 3, border));
  const Eigen::Map<const Eigen::Matrix<double, Width, 1>> x_border(x + 3 * chain_, width_);
  for (int k = chain_ - 1; k >= 0; --k) {
    Vector3 xk(x + 3 * k);
    xk -= ConstColumns(base + border_column_offset(k), 3, width_).lazyProduct(x_border);
    if (k + 1 < chain_) xk -= ConstBlock(base + upper_offset(k)).lazyProduct(ConstVector3(x + 3 * k + 3));
  }
  back_satellites(x);
}

void RingSolver::solve_in_place(double* values) const {
  if (!border_factored_) throw std::logic_error("ring solver: solve() needs a successful factorize() first");
  condensed_ = false;
  gather(values);
  double* y = work_.data();
  with_width([this, y](auto width) { forward<decltype(width)::value>(y); });
  solve_border_and_back(values);
}

void RingSolver::solve_border_and_back(double* values) const {
  double* y = work_.data();
  const int first = 3 * chain_ + 3, border = width_ - 3;
  Eigen::Map<const Eigen::MatrixXd> s(blocks_.data() + border_block_offset(), width_, width_);
  lu_solve(s.bottomRightCorner(border, border), &pivots_[first], Eigen::Map<Eigen::VectorXd>(y + first, border));
  with_width([this, y](auto width) { back<decltype(width)::value>(y); });
  y[padded_size_] = 0.0;  // the held equations' solution
  for (size_t equation = 0; equation < position_of_equation_.size(); ++equation)
    values[equation] = y[position_of_equation_[equation]];
}

void RingSolver::solve(Eigen::VectorXd& right_hand_side) const {
  check_size(right_hand_side.size());
  solve_in_place(right_hand_side.data());
}

void RingSolver::solve(Eigen::MatrixXd& right_hand_sides) const {
  check_size(right_hand_sides.rows());
  for (Eigen::Index column = 0; column < right_hand_sides.cols(); ++column)
    solve_in_place(right_hand_sides.col(column).data());
}

void RingSolver::condense(const Eigen::VectorXd& right_hand_side, Eigen::VectorXd& condensed_border_rhs) const {
  if (!interior_factored_)
    throw std::logic_error("ring solver: condense() needs factorize() or factorize_interior() first");
  check_size(right_hand_side.size());
  gather(right_hand_side.data());
  double* y = work_.data();
  with_width([this, y](auto width) { forward<decltype(width)::value>(y); });
  condensed_border_rhs.resize(border_size());
  for (int i = 0; i < border_size(); ++i) condensed_border_rhs[i] = y[3 * chain_ + 3 + i];
  condensed_ = true;
}

void RingSolver::solve_condensed(const Eigen::VectorXd& condensed_border_rhs, Eigen::VectorXd& solution) const {
  if (!border_factored_ || !condensed_)
    throw std::logic_error("ring solver: solve_condensed() needs factorize() and then condense()");
  check_size(solution.size());
  if (condensed_border_rhs.size() != border_size())
    throw std::invalid_argument("ring solver: the condensed border right-hand side has " +
                                std::to_string(condensed_border_rhs.size()) + " entries, the border " +
                                std::to_string(border_size()));
  condensed_ = false;
  for (int i = 0; i < border_size(); ++i) work_[3 * chain_ + 3 + i] = condensed_border_rhs[i];
  solve_border_and_back(solution.data());
}

}  // namespace tirefe
