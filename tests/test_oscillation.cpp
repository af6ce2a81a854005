// Tests for the damped-oscillation fit used to read mode frequencies off spindle forces.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "post/oscillation.hpp"

using tirefe::post::dominant_oscillation;

namespace {

constexpr double kPi = 3.141592653589793;

struct Signal {
  std::vector<double> time, value;
};

/// trend + A e^{-sigma t} sin(2 pi f t + phase), unevenly sampled, with optional noise.
Signal damped_sine(double frequency, double decay_rate, double amplitude, double duration, double noise = 0.0) {
  Signal signal;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(0.6, 1.4);
  std::normal_distribution<double> gaussian(0.0, noise);
  const double mean_step = 2.5e-4;
  for (double t = 0.0; t <= duration; t += mean_step * jitter(random)) {
    const double trend = 3800.0 + 1500.0 * t;
    double y = trend + amplitude * std::exp(-decay_rate * t) * std::sin(2 * kPi * frequency * t + 0.7);
    if (noise > 0.0) y += gaussian(random);
    signal.time.push_back(t);
    signal.value.push_back(y);
  }
  return signal;
}

}  // namespace

TEST_CASE("a damped sine on a trend is recovered from four periods", "[post]") {
  // 88 Hz for 46 ms: the tire on top of a 660 mm cleat at 51.3 km/h. FFT bins would be 22 Hz.
  const Signal signal = damped_sine(88.0, 25.0, 400.0, 0.046);
  const auto found = dominant_oscillation(signal.time, signal.value, 0.0, 0.046);
  CHECK(found.frequency == Approx(88.0).epsilon(1e-6));
  CHECK(found.decay_rate == Approx(25.0).epsilon(1e-4));
  CHECK(found.amplitude == Approx(400.0).epsilon(1e-5));
  CHECK(found.rms_misfit < 1e-6);
}

TEST_CASE("noise of 5 percent of the amplitude moves the frequency by under 1 percent", "[post]") {
  const Signal signal = damped_sine(35.0, 10.0, 200.0, 0.15, 10.0);
  const auto found = dominant_oscillation(signal.time, signal.value, 0.0, 0.15);
  CHECK(found.frequency == Approx(35.0).epsilon(0.01));
  CHECK(found.rms_misfit == Approx(10.0).epsilon(0.15));  // what is left is the noise
}

TEST_CASE("a window with too few samples is refused with a message", "[post]") {
  const Signal signal = damped_sine(88.0, 0.0, 1.0, 0.01);
  CHECK_THROWS_AS(dominant_oscillation(signal.time, signal.value, 0.0, 0.001), std::invalid_argument);
  CHECK_THROWS_AS(dominant_oscillation(signal.time, signal.value, 0.0, 0.01, {5.0, 5000.0, 200.0}),
                  std::invalid_argument);
  CHECK_THROWS_AS(dominant_oscillation(signal.time, signal.value, 0.01, 0.0), std::invalid_argument);
}
