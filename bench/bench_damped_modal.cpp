// Wall time of the damped modal analysis (12 modes) of the 145 SR-12 models inflated on a
// held hub, by the dense first-order solver and by shift-invert block Krylov, and the
// largest difference of their roots. The tread-layer model has 500 free equations: a
// 1000 x 1000 first-order form.
#include <algorithm>
#include <chrono>
#include <complex>
#include <cstdio>
#include <string>

#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "solvers/modal.hpp"
#include "tire/tire_builder.hpp"

using namespace tirefe;

int main() {
  for (const std::string module : {"tires.145SR12", "tires.145SR12_tread_layer"}) {
    Model model;
    const Tire tire = build_tire(model, macros::load_tire_parameters(module), LoadFunction::linear());
    for (int c = 0; c < kDofsPerNode; ++c) model.fix(tire.spindle, c);
    Analysis analysis(model);
    analysis.set_time_step(0.25);
    analysis.advance(1.0);
    DampedModalResult results[2];
    double seconds[2];
    for (int route = 0; route < 2; ++route) {
      DampedModalSettings settings;
      settings.solver = route == 0 ? DampedSolver::Dense : DampedSolver::ShiftInvert;
      const auto start = std::chrono::steady_clock::now();
      results[route] = damped_modal_analysis(analysis, 12, settings);
      seconds[route] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    double difference = 0.0;
    for (size_t i = 0; i < results[0].roots.size(); ++i)
      difference =
          std::max(difference, std::abs(results[0].roots[i] - results[1].roots[i]) / std::abs(results[0].roots[i]));
    std::printf("%-28s %4d equations: dense %6.2f s, shift-invert %5.2f s (%s), roots agree to %.1e\n", module.c_str(),
                model.dof_map().equation_count(), seconds[0], seconds[1],
                results[1].shift_invert ? "converged" : "fell back to dense", difference);
  }
}
