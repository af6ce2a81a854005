// Helpers shared by the tests: finite-difference tangents of element kernels and
// small model builders.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <complex>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/element.hpp"

namespace tirefe::testing {

/// Central finite difference of a kernel's residual with respect to the displacement
/// (cK part), the velocity (cC part) and the acceleration (cM part), combined with the
/// given factors, to compare with the kernel's own tangent.
template <class Kernel>
typename ElementBlockOf<Kernel>::Matrix finite_difference_tangent(const Kernel& kernel,
                                                                  const LocalState<Kernel::kDofs>& local,
                                                                  const EvaluationContext& context,
                                                                  const typename Kernel::History& committed,
                                                                  double step = 1e-6) {
  using Vector = typename ElementBlockOf<Kernel>::Vector;
  typename ElementBlockOf<Kernel>::Matrix tangent;
  tangent.setZero();
  const IntegratorFactors& f = context.factors;
  // Each rate column differentiates only the force part that depends on that rate, so
  // the large factor (e.g. 1/(beta h^2)) does not amplify round-off of the other parts.
  auto residual_at = [&](const LocalState<Kernel::kDofs>& perturbed, const EvaluationContext& part) {
    Vector residual;
    typename Kernel::History trial = committed;
    kernel.evaluate(perturbed, part, committed, trial, residual, nullptr);
    return residual;
  };
  EvaluationContext damping_only = context, mass_only = context;
  damping_only.factors = {0.0, f.force_damping, 0.0, 0.0, 0.0, 0.0};
  mass_only.factors = {0.0, 0.0, f.force_mass, 0.0, 0.0, 0.0};
  damping_only.want_tangent = mass_only.want_tangent = false;
  for (int j = 0; j < Kernel::kDofs; ++j) {
    auto column = [&](auto field, const EvaluationContext& part, double factor) {
      if (factor == 0.0) return;
      LocalState<Kernel::kDofs> plus = local, minus = local;
      (plus.*field)[j] += step;
      (minus.*field)[j] -= step;
      tangent.col(j) += factor * (residual_at(plus, part) - residual_at(minus, part)) / (2.0 * step);
    };
    column(&LocalState<Kernel::kDofs>::displacement, context, f.tangent_stiffness / f.force_stiffness);
    if (f.force_damping != 0.0)
      column(&LocalState<Kernel::kDofs>::velocity, damping_only, f.tangent_damping / f.force_damping);
    if (f.force_mass != 0.0) column(&LocalState<Kernel::kDofs>::acceleration, mass_only, f.tangent_mass / f.force_mass);
  }
  return tangent;
}

inline EvaluationContext dynamic_context(double step = 1e-3, double beta = 0.25, double gamma = 0.5) {
  EvaluationContext context;
  context.time_step = step;
  context.factors = {1.0, 1.0, 1.0, 1.0, gamma / (beta * step), 1.0 / (beta * step * step)};
  return context;
}

template <int Dofs>
LocalState<Dofs> random_local_state(std::mt19937& random, double displacement_scale, double rotation_scale) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  LocalState<Dofs> local;
  for (int i = 0; i < Dofs; ++i) {
    const double scale = (i % 3 == 2) ? rotation_scale : displacement_scale;
    local.displacement[i] = scale * uniform(random);
    local.velocity[i] = uniform(random);
    local.acceleration[i] = uniform(random);
  }
  return local;
}

/// |K - K_fd| / |K| for a kernel without history at one state, K its tangent and K_fd
/// central differences of its residual; 'asymmetry' (if given) gets |K - K^T| / |K|.
template <class Kernel>
double relative_tangent_error(const Kernel& kernel, const LocalState<Kernel::kDofs>& local,
                              const EvaluationContext& context, double* asymmetry = nullptr) {
  typename Kernel::Vector residual;
  typename Kernel::Matrix tangent;
  NoHistory history;
  kernel.evaluate(local, context, history, history, residual, &tangent);
  const typename Kernel::Matrix numerical = finite_difference_tangent(kernel, local, context, history);
  if (asymmetry) *asymmetry = (tangent - tangent.transpose()).norm() / tangent.norm();
  return (tangent - numerical).norm() / tangent.norm();
}

/// The largest magnitude among what a kernel's traits (KernelTraits, element.hpp) say is
/// zero: the residual entries and tangent rows and columns of its idle_dofs, its
/// zero_tangent_entry entries, if it promises reads_acceleration = false or reads_velocity
/// = false, the change of its residual when the acceleration or the velocity is dropped,
/// and if it promises stores_energy = false, its energy. The block loop skips these, so
/// anything but 0 is a wrong promise.
template <class Kernel>
double declared_zero_magnitude(const Kernel& kernel, const LocalState<Kernel::kDofs>& local,
                               const EvaluationContext& context) {
  typename Kernel::Vector residual, dropped;
  typename Kernel::Matrix tangent;
  typename Kernel::History history{};
  kernel.evaluate(local, context, history, history, residual, &tangent);
  double largest = 0.0;
  constexpr auto idle = detail::IdleDofs<Kernel>::mask();
  for (int i = 0; i < Kernel::kDofs; ++i)
    if (idle[i])
      largest = std::max(
          {largest, std::abs(residual[i]), tangent.row(i).cwiseAbs().maxCoeff(), tangent.col(i).cwiseAbs().maxCoeff()});
  constexpr auto zero = detail::ZeroTangentEntries<Kernel>::mask();
  for (int k = 0; k < Kernel::kDofs * Kernel::kDofs; ++k)
    if (zero[k]) largest = std::max(largest, std::abs(tangent(k / Kernel::kDofs, k % Kernel::kDofs)));
  if constexpr (!detail::ReadsAcceleration<Kernel>::value) {
    LocalState<Kernel::kDofs> at_rest = local;
    at_rest.acceleration.setZero();
    kernel.evaluate(at_rest, context, history, history, dropped, nullptr);
    largest = std::max(largest, (residual - dropped).cwiseAbs().maxCoeff());
  }
  if constexpr (!detail::ReadsVelocity<Kernel>::value) {
    LocalState<Kernel::kDofs> still = local;
    still.velocity.setZero();
    kernel.evaluate(still, context, history, history, dropped, nullptr);
    largest = std::max(largest, (residual - dropped).cwiseAbs().maxCoeff());
  }
  if constexpr (!detail::StoresEnergy<Kernel>::value) {
    const ElementEnergy energy = kernel.energy(local, history);
    largest = std::max({largest, std::abs(energy.strain), std::abs(energy.kinetic)});
  }
  return largest;
}

/// |r - M a| / |M a| for a kernel with mass_times (element.hpp): r its residual with the
/// inertia weight alone, M a what mass_times says of the same acceleration. HHT finds the
/// end of a step's internal forces from mass_times, so it must be the kernel's inertia.
template <class Kernel>
double mass_times_deviation(const Kernel& kernel, const LocalState<Kernel::kDofs>& local) {
  EvaluationContext context;
  context.factors = IntegratorFactors::inertia_force();
  context.want_tangent = false;
  typename Kernel::Vector residual;
  typename Kernel::History history{};
  kernel.evaluate(local, context, history, history, residual, nullptr);
  const typename Kernel::Vector inertia = kernel.mass_times(local.acceleration);
  return (residual - inertia).norm() / inertia.norm();
}

/// The largest relative difference between a batch kernel's numbers (element.hpp) and
/// evaluate()'s over a block of elements at the given states: per element
/// |r_batch - r| / |r| and, with the tangent, |K_batch - K| / |K| (the tangent entries of
/// idle DOFs, never read, set to evaluate()'s zeros; the residual's are compared as they are).
/// Element states as a block's structure of arrays (element.hpp, BlockValues): 'values'
/// points into 'arrays', which must outlive it.
template <class Kernel>
struct BatchStates {
  std::vector<double> arrays;
  BlockValues values;

  explicit BatchStates(const std::vector<LocalState<Kernel::kDofs>>& locals) {
    constexpr int kDofs = Kernel::kDofs;
    const int count = static_cast<int>(locals.size());
    arrays.resize(3 * kDofs * count);
    double* displacement = arrays.data();
    double* velocity = displacement + kDofs * count;
    double* acceleration = velocity + kDofs * count;
    for (int e = 0; e < count; ++e)
      for (int k = 0; k < kDofs; ++k) {
        displacement[k * count + e] = locals[e].displacement[k];
        velocity[k * count + e] = locals[e].velocity[k];
        acceleration[k * count + e] = locals[e].acceleration[k];
      }
    values =
        BlockValues{count, displacement, velocity, detail::ReadsAcceleration<Kernel>::value ? acceleration : nullptr};
  }
};

template <class Kernel>
double batch_deviation(const std::vector<Kernel>& kernels, const std::vector<LocalState<Kernel::kDofs>>& locals,
                       const EvaluationContext& context, bool with_tangent) {
  constexpr int kDofs = Kernel::kDofs;
  const int count = static_cast<int>(kernels.size());
  const BatchStates<Kernel> states(locals);
  const BlockValues& values = states.values;
  typename Kernel::Batch batch(kernels);
  batch.evaluate(values, context, with_tangent);
  constexpr auto idle = detail::IdleDofs<Kernel>::mask();
  double worst = 0.0;
  for (int e = 0; e < count; ++e) {
    typename Kernel::Vector residual, batch_residual;
    typename Kernel::Matrix tangent, batch_tangent;
    typename Kernel::History history{};
    kernels[e].evaluate(locals[e], context, history, history, residual, with_tangent ? &tangent : nullptr);
    for (int k = 0; k < kDofs; ++k) batch_residual[k] = batch.residual()[k * count + e];
    worst = std::max(worst, (batch_residual - residual).norm() / residual.norm());
    if (!with_tangent) continue;
    for (int k = 0; k < kDofs * kDofs; ++k)
      batch_tangent.data()[k] = idle[k / kDofs] || idle[k % kDofs] ? tangent.data()[k] : batch.tangent()[k * count + e];
    worst = std::max(worst, (batch_tangent - tangent).norm() / tangent.norm());
  }
  return worst;
}

/// The largest relative difference between a batch kernel's summed strain and kinetic
/// energy and the sums of the elements' energy().
template <class Kernel>
double batch_energy_deviation(const std::vector<Kernel>& kernels,
                              const std::vector<LocalState<Kernel::kDofs>>& locals) {
  const BatchStates<Kernel> states(locals);
  const ElementEnergy batch = typename Kernel::Batch(kernels).energy(states.values);
  ElementEnergy sum;
  for (size_t e = 0; e < kernels.size(); ++e) sum += kernels[e].energy(locals[e], typename Kernel::History{});
  return std::max(std::abs(batch.strain - sum.strain) / std::abs(sum.strain),
                  std::abs(batch.kinetic - sum.kinetic) / std::abs(sum.kinetic));
}

/// The integrator factor combinations a batch kernel is checked under: static, Newmark
/// (damping and mass terms, h = 1e-4 s) and HHT-alpha (alpha = -0.1, forces weighted 0.9).
inline std::vector<EvaluationContext> batch_contexts() {
  EvaluationContext statics;
  statics.time = 0.5;
  EvaluationContext hht = dynamic_context(1e-4, 0.3025, 0.6);
  for (double* weight : {&hht.factors.force_stiffness, &hht.factors.force_damping, &hht.factors.tangent_stiffness})
    *weight *= 0.9;
  hht.factors.tangent_damping *= 0.9;
  hht.time = 0.75;
  EvaluationContext newmark = dynamic_context(1e-4);
  newmark.time = 0.25;
  return {statics, newmark, hht};
}

/// 'text' with the first 'from' replaced by 'to' ('from' must be there).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("the text holds no '" + from + "'");
  return text.replace(at, from.size(), to);
}

/// The same double to the last bit (and the sign of a zero).
inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// A shell command's exit status and its standard output (add 2>&1 for errors too).
struct CommandResult {
  int status;
  std::string output;
};
inline CommandResult run_command(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run '" + command + "'");
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), output};
}

/// Least-squares fit of u_{n+2} = p u_{n+1} - q u_n over samples [first, end): a free
/// response made of one complex pair lambda has p = 2 Re(lambda), q = |lambda|^2.
inline std::complex<double> fitted_root(const std::vector<double>& u, int first) {
  const int rows = static_cast<int>(u.size()) - 2 - first;
  Eigen::MatrixXd basis(rows, 2);
  Eigen::VectorXd target(rows);
  for (int r = 0; r < rows; ++r) {
    basis.row(r) << u[first + r + 1], -u[first + r];
    target[r] = u[first + r + 2];
  }
  const Eigen::Vector2d pq = basis.colPivHouseholderQr().solve(target);
  const double modulus = std::sqrt(pq[1]);
  return std::polar(modulus, std::acos(std::clamp(pq[0] / (2.0 * modulus), -1.0, 1.0)));
}

/// A fresh temporary folder, removed with its contents at scope exit.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("tirefe_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// Writes 'text' to the file 'name' (folders created as needed); returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path file = path_ / name;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
    return file.string();
  }
  std::string path(const std::string& name = "") const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// While it lives, no file this process writes grows past 'bytes': a write beyond fails
// (EFBIG, "File too large") as one on a full disk does, wherever HDF5 makes it.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) : ignored_(std::signal(SIGXFSZ, SIG_IGN)) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    const rlimit limit{bytes, saved_.rlim_max};
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, ignored_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*ignored_)(int);
};

}  // namespace tirefe::testing
