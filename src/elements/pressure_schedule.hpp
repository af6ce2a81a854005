// PressureSchedule: the inflation pressure as a function of time, p(t) = p_0 f(t),
// shared (through a std::shared_ptr) by every sidewall wedge and tread pressure load
// of one tire, so that the membrane term of the sidewalls (docs/model.md eq. 9) and the
// pressure on the tread always see the same value. f is a LoadFunction (FEAP's PROP):
// LoadFunction::linear() ramps the pressure up with the quasi-static load level.
#pragma once

#include <cmath>
#include <string>
#include <utility>

#include "core/load_function.hpp"
#include "core/mesh.hpp"

namespace tirefe {

class PressureSchedule {
 public:
  /// pressure: p_0 [Pa]; ramp: f(t), so that p(t) = p_0 f(t).
  PressureSchedule(double pressure, LoadFunction ramp) : pressure_(pressure), ramp_(std::move(ramp)) {
    if (!std::isfinite(pressure))
      throw ModelError("inflation pressure must be finite (got " + std::to_string(pressure) + ")");
  }
  /// A pressure held at p_0 for all times.
  static PressureSchedule constant(double pressure) { return PressureSchedule(pressure, LoadFunction::constant(1.0)); }

  /// Every wedge and tread load of the tire asks for the same time in one assembly: the
  /// ramp (a std::function, a table search) runs once per time, the rest read the memo.
  double at(double time) const {
    if (time != memo_time_) {
      memo_pressure_ = pressure_ * ramp_(time);
      memo_time_ = time;
    }
    return memo_pressure_;
  }

 private:
  double pressure_;
  LoadFunction ramp_;
  mutable double memo_time_ = std::nan(""), memo_pressure_ = 0.0;
};

}  // namespace tirefe
