// The C API's step as a real-time host sees it: the 145 SR-12 on a fixed axle, pressed
// 15 mm, rolled freely from rest to 60 km/h on a flat run-up (3 s) and then over a rough
// road with cleats for 10 s of road, in host steps of 1 ms (tirefe_solve + tirefe_commit,
// HHT alpha -0.1). Every step of the road is timed; the bench prints the machine, the
// percentiles and the largest step time, the Newton iterations per step, the time per
// iteration, the steps cut (a step that fails is taken again in two halves, down to
// 1/16 ms) and the heap allocations during the road's steps (malloc, calloc, realloc and
// the aligned forms, counted by this program's own wrappers of glibc's allocator).
//
// The road (written to a CSV file the tire reads): a random profile of ISO 8608 class C,
// displacement PSD G(n) = 256e-6 m^3 (n / 0.1 m^-1)^-2, between 0.2 and 10 cycles per
// metre (wavelengths of 5 m down to 0.1 m: the longer ones a suspension follows, and a
// fixed axle must not), 2000 cosines of random phase (seeded), sampled every 2 cm and
// faded in over its first 2 m; on it three cleats 20 mm long, 10, 15 and 20 mm high, at a
// quarter, a half and three quarters of the road. Convex edges are rounded 5 mm.
//
// With --max-iterations N (and --budget-us T), a second tire with that step budget
// (tirefe_set_step_budget) runs on the same motion, its steps interleaved with the
// default's so that both see the same machine load: the bench then prints its figures,
// its budget report and how far its forces are from the default's.
//
//   bench_rough_road [--seconds 10] [--seed 1] [--max-iterations N] [--budget-us T]
//                    [--max-residual R] [--trace-allocations]
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <execinfo.h>
#include <malloc.h>
#include <unistd.h>

#include "tirefe.h"

// ---- Heap allocations: glibc's allocator behind counting wrappers ----------------------
extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* __libc_memalign(size_t, size_t);
void __libc_free(void*);
}

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
bool trace_allocations = false;
thread_local bool tracing = false;  // backtrace_symbols_fd running: its own calls are not traced

void count_allocation() {
  if (!counting.load(std::memory_order_relaxed)) return;
  const long n = allocations.fetch_add(1, std::memory_order_relaxed);
  if (trace_allocations && !tracing && n < 100) {  // where the first ones come from
    tracing = true;
    void* frames[24];
    const int depth = backtrace(frames, 24);
    std::fprintf(stderr, "allocation %ld during a step:\n", n + 1);
    backtrace_symbols_fd(frames, depth, 2);
    tracing = false;
  }
}
}  // namespace

extern "C" {
void* malloc(size_t size) {
  count_allocation();
  return __libc_malloc(size);
}
void* calloc(size_t count, size_t size) {
  count_allocation();
  return __libc_calloc(count, size);
}
void* realloc(void* memory, size_t size) {
  count_allocation();
  return __libc_realloc(memory, size);
}
void free(void* memory) { __libc_free(memory); }
void* memalign(size_t alignment, size_t size) {
  count_allocation();
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(size_t alignment, size_t size) { return memalign(alignment, size); }
int posix_memalign(void** memory, size_t alignment, size_t size) {
  *memory = memalign(alignment, size);
  return *memory ? 0 : ENOMEM;
}
}

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kSpeed = 60.0 / 3.6;                          // [m/s]
constexpr double kRampTime = 3.0;                              // [s] from rest to kSpeed
constexpr double kPress = 0.015;                               // [m] the axle below first touch
constexpr double kStep = 1e-3;                                 // [s] the host's step
constexpr double kRoadStart = kSpeed * kRampTime / 2.0 + 1.0;  // [m] where the rough road begins

/// x of the axle at time t: smootherstep speed from rest to kSpeed in kRampTime, then kSpeed.
double axle_x(double t) {
  if (t >= kRampTime) return kSpeed * (kRampTime / 2.0 + (t - kRampTime));
  const double s = t / kRampTime;
  return kSpeed * kRampTime * s * s * s * s * (2.5 + s * (-3.0 + s));  // the integral of 6s^5 - 15s^4 + 10s^3
}

/// The rough road's profile from kRoadStart over 'length' [m], in metres.
std::vector<std::pair<double, double>> rough_road(double length, unsigned seed) {
  const double psd_n0 = 256e-6, n0 = 0.1, n_low = 0.2, n_high = 10.0;  // ISO 8608 class C, waviness 2
  const int waves = 2000;
  const double dn = (n_high - n_low) / waves, spacing = 0.02, fade = 2.0;
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
  std::vector<double> amplitude(waves), frequency(waves), shift(waves);
  for (int i = 0; i < waves; ++i) {
    frequency[i] = n_low + (i + 0.5) * dn;
    amplitude[i] = std::sqrt(2.0 * psd_n0 * std::pow(frequency[i] / n0, -2.0) * dn);
    shift[i] = phase(random);
  }
  const int samples = static_cast<int>(std::ceil(length / spacing));
  std::vector<double> height(samples + 1, 0.0);
  for (int k = 0; k <= samples; ++k) {
    const double s = k * spacing;
    double z = 0.0;
    for (int i = 0; i < waves; ++i) z += amplitude[i] * std::cos(2.0 * M_PI * frequency[i] * s + shift[i]);
    const double taper = s < fade ? 0.5 - 0.5 * std::cos(M_PI * s / fade) : 1.0;
    height[k] = taper * z;
  }
  // The cleats: one sample interval (20 mm) long, standing on the profile at their foot.
  const double cleat_heights[] = {0.010, 0.015, 0.020};
  std::vector<std::pair<double, double>> points{{-1.0, 0.0}};
  int next_cleat = 0;
  for (int k = 0; k <= samples; ++k) {
    const double x = kRoadStart + k * spacing;
    points.emplace_back(x, height[k]);
    if (next_cleat < 3 && k < samples && k * spacing >= (next_cleat + 1) * length / 4.0) {
      const double top = height[k] + cleat_heights[next_cleat++];
      points.emplace_back(x, top);
      points.emplace_back(kRoadStart + (k + 1) * spacing, top);
    }
  }
  return points;
}

std::string write_road(const std::vector<std::pair<double, double>>& points) {
  const char* folder = std::getenv("TMPDIR");
  std::string path = std::string(folder && *folder ? folder : "/tmp") + "/tirefe_rough_road_XXXXXX.csv";
  const int fd = mkstemps(path.data(), 4);
  if (fd < 0) throw std::runtime_error("cannot create a temporary road file in " + path);
  close(fd);
  std::ofstream out(path);
  out << "# a rough road of ISO 8608 class C with three cleats (bench_rough_road)\nx [m], z [m]\n";
  out.precision(9);
  for (const auto& [x, z] : points) out << x << ", " << z << "\n";
  if (!out.flush()) throw std::runtime_error("cannot write the road file " + path);
  return path;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

/// One tire with its figures over the road.
struct RoadTire {
  tirefe_tire* tire = nullptr;
  std::vector<double> step_times;  // [us] of the road's steps
  std::vector<double> fx, fz;      // [N] at each road step
  long iterations = 0;
  int max_iterations = 0;
  int cuts = 0;
  double uncut_time = 0.0;  // [us] of the steps taken whole, and their iterations
  long uncut_iterations = 0;
  long allocations = 0;

  /// The step from the committed time by h to the axle at (x, z): in halves where it fails.
  /// Returns the force and the Newton iterations.
  void step(double h, double x_end, double x_start, double z, tirefe_spindle_force& out, int& iterations,
            int depth = 0) {
    const tirefe_spindle_motion motion{h, x_end, z, 0.0};
    const tirefe_status status = tirefe_solve(tire, &motion, &out);
    if (status == TIREFE_OK) {
      iterations += out.newton_iterations;
      if (tirefe_commit(tire) != TIREFE_OK) throw std::runtime_error(tirefe_message(tire));
      return;
    }
    if (status != TIREFE_STEP_FAILED || depth == 4) throw std::runtime_error(tirefe_message(tire));
    ++cuts;
    const double x_middle = 0.5 * (x_start + x_end);
    step(0.5 * h, x_middle, x_start, z, out, iterations, depth + 1);
    step(0.5 * h, x_end, x_middle, z, out, iterations, depth + 1);
  }

  /// One host step to time t, timed (and its allocations counted) when 'record'.
  void host_step(double t, bool record) {
    tirefe_spindle_force out;
    int step_iterations = 0;
    const int cuts_before = cuts;
    const long allocations_before = ::allocations.load();
    counting = record;
    const Clock::time_point start = Clock::now();
    step(kStep, axle_x(t), axle_x(t - kStep), -kPress, out, step_iterations);
    const double elapsed = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
    counting = false;
    if (!record) return;
    allocations += ::allocations.load() - allocations_before;
    step_times.push_back(elapsed);
    fx.push_back(out.force[0]);
    fz.push_back(out.force[1]);
    iterations += step_iterations;
    max_iterations = std::max(max_iterations, step_iterations);
    if (cuts == cuts_before) {
      uncut_time += elapsed;
      uncut_iterations += step_iterations;
    }
  }

  void print(const char* name) const {
    std::vector<double> sorted = step_times;
    std::sort(sorted.begin(), sorted.end());
    const size_t n = sorted.size();
    auto percentile = [&](double p) { return sorted[std::min(n - 1, static_cast<size_t>(std::ceil(p * n)) - 1)]; };
    double total = 0.0;
    for (double t : sorted) total += t;
    std::printf("%s\n", name);
    std::printf("  step time [ms]: median %.3f, 99th %.3f, 99.9th %.3f, max %.3f, mean %.3f\n", percentile(0.5) * 1e-3,
                percentile(0.99) * 1e-3, percentile(0.999) * 1e-3, sorted.back() * 1e-3, total / n * 1e-3);
    const long late = std::count_if(sorted.begin(), sorted.end(), [](double t) { return t > 1e3; });
    std::printf("  steps over 1 ms: %ld (%.2f %%)\n", late, 100.0 * late / n);
    std::printf("  Newton iterations per step: mean %.2f, max %d; time per iteration %.1f us (steps not cut)\n",
                static_cast<double>(iterations) / n, max_iterations, uncut_time / std::max(uncut_iterations, 1L));
    std::printf("  steps cut: %d; heap allocations during the steps: %ld\n", cuts, allocations);
    std::printf("  largest Fz %.0f N, largest |Fx| %.0f N\n", *std::max_element(fz.begin(), fz.end()),
                std::max(*std::max_element(fx.begin(), fx.end()), -*std::min_element(fx.begin(), fx.end())));
  }
};

tirefe_tire* open_tire(const std::string& road) {
  tirefe_options options;
  tirefe_default_options(&options);
  options.hht_alpha = -0.1;
  options.road = road.c_str();
  options.road_edge_radius = 0.005;
  options.start_z = -kPress;
  char error[512];
  tirefe_tire* tire = nullptr;
  if (tirefe_open("tires.145SR12", nullptr, 0, &options, &tire, error, sizeof error) != TIREFE_OK)
    throw std::runtime_error(error);
  return tire;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 10.0, budget_us = 0.0, max_residual = 0.0;
  unsigned seed = 1;
  int max_iterations = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    const bool has_value = i + 1 < argc;
    if (argument == "--seconds" && has_value)
      seconds = std::atof(argv[++i]);
    else if (argument == "--seed" && has_value)
      seed = static_cast<unsigned>(std::atol(argv[++i]));
    else if (argument == "--max-iterations" && has_value)
      max_iterations = std::atoi(argv[++i]);
    else if (argument == "--budget-us" && has_value)
      budget_us = std::atof(argv[++i]);
    else if (argument == "--max-residual" && has_value)
      max_residual = std::atof(argv[++i]);
    else if (argument == "--trace-allocations")
      trace_allocations = true;
    else {
      std::fprintf(stderr,
                   "usage: bench_rough_road [--seconds S] [--seed N] [--max-iterations N] [--budget-us T] "
                   "[--max-residual R] [--trace-allocations]\n(unknown or incomplete argument '%s')\n",
                   argument.c_str());
      return 2;
    }
  }
  if (!(seconds > 0.0) || max_iterations < 0 || budget_us < 0.0 || max_residual < 0.0) {
    std::fprintf(stderr,
                 "bench_rough_road: --seconds must be > 0, --max-iterations, --budget-us and --max-residual >= 0\n");
    return 2;
  }
  if (trace_allocations) {  // backtrace() loads its unwinder on its first call: before any counting
    void* frame[1];
    backtrace(frame, 1);
  }
  std::string road;
  try {
    road = write_road(rough_road(kSpeed * seconds, seed));
    std::vector<RoadTire> tires(max_iterations > 0 || budget_us > 0.0 ? 2 : 1);
    for (RoadTire& t : tires) t.tire = open_tire(road);
    // The budget from the start (the run-up too), its report from the road's start.
    auto set_budget = [&] {
      const tirefe_step_budget budget{max_iterations, budget_us * 1e-6, max_residual};
      if (tires.size() == 2 && tirefe_set_step_budget(tires[1].tire, &budget) != TIREFE_OK)
        throw std::runtime_error(tirefe_message(tires[1].tire));
    };
    set_budget();
    const int ramp_steps = static_cast<int>(std::lround(kRampTime / kStep));
    const int road_steps = static_cast<int>(std::lround(seconds / kStep));
    for (int k = 1; k <= ramp_steps + road_steps; ++k) {
      if (k == ramp_steps + 1) set_budget();
      for (size_t i = 0; i < tires.size(); ++i) {
        RoadTire& t = tires[(k + i) % tires.size()];  // each goes first in turn
        t.host_step(k * kStep, k > ramp_steps);
      }
    }

    std::printf("machine: %ld processors online, %s\n", sysconf(_SC_NPROCESSORS_ONLN), cpu_model().c_str());
    std::printf(
        "road: %.1f s at %.0f km/h (%.1f m) after a %.0f s run-up, ISO 8608 class C (0.2-10 /m, seed %u), cleats "
        "10, 15, 20 mm; axle 15 mm down, HHT alpha -0.1\n",
        seconds, kSpeed * 3.6, kSpeed * seconds, kRampTime, seed);
    std::printf("steps: %d of 1 ms (solve + commit)\n", road_steps);
    tires[0].print("default (Newton to convergence):");
    if (tires.size() == 2) {
      char name[128];
      std::snprintf(name, sizeof name,
                    "step budget (%d iterations, %.0f us, residual %g; 0: none or default):", max_iterations, budget_us,
                    max_residual);
      tires[1].print(name);
      tirefe_budget_report report;
      if (tirefe_step_budget_report(tires[1].tire, &report) != TIREFE_OK)
        throw std::runtime_error(tirefe_message(tires[1].tire));
      std::printf(
          "  budget report: %ld steps, %ld ended unconverged (worst relative residual %.2e), %ld overran the "
          "iterations, %ld the time (worst %.3f ms)\n",
          report.steps, report.unconverged, report.worst_residual, report.overruns, report.time_misses,
          report.worst_time * 1e3);
      double dfx = 0.0, dfz = 0.0;
      for (size_t k = 0; k < tires[0].fz.size(); ++k) {
        dfx = std::max(dfx, std::abs(tires[1].fx[k] - tires[0].fx[k]));
        dfz = std::max(dfz, std::abs(tires[1].fz[k] - tires[0].fz[k]));
      }
      const double peak0 = *std::max_element(tires[0].fz.begin(), tires[0].fz.end());
      const double peak1 = *std::max_element(tires[1].fz.begin(), tires[1].fz.end());
      std::printf("  against the default: largest |dFx| %.1f N, |dFz| %.1f N; peak Fz %+.2f %%\n", dfx, dfz,
                  100.0 * (peak1 - peak0) / peak0);
      double ratio = 0.0;
      std::vector<double> a = tires[0].step_times, b = tires[1].step_times;
      std::nth_element(a.begin(), a.begin() + a.size() / 2, a.end());
      std::nth_element(b.begin(), b.begin() + b.size() / 2, b.end());
      ratio = b[b.size() / 2] / a[a.size() / 2];
      std::printf("  median step time, budget over default: %.2f\n", ratio);
    }
    for (RoadTire& t : tires) tirefe_close(t.tire);
  } catch (const std::exception& failure) {
    std::fprintf(stderr, "bench_rough_road: %s\n", failure.what());
    if (!road.empty()) std::remove(road.c_str());
    return 1;
  }
  std::remove(road.c_str());
  return 0;
}
