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
  static PressureSchedule constant(double pressure) {
    return PressureSchedule(pressure, LoadFunction::constant(1.0));
  }

  double at(double time) const { return pressure_ * ramp_(time); }

 private:
  double pressure_;
  LoadFunction ramp_;
};

}  // namespace tirefe
