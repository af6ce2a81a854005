// Tests for the two ringing estimators (Hann spectrum peak, matrix pencil) and the
// reading that combines them.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "test_support.hpp"

#include "deck_support.hpp"
#include "post/matrix_pencil.hpp"
#include "post/ringing.hpp"
#include "post/spectrum.hpp"

using namespace tirefe::post;

namespace {

constexpr double kPi = 3.141592653589793;

struct Mode {
  double frequency, decay_rate, amplitude, phase;
};

struct Signal {
  std::vector<double> time, value;
};

/// 3800 + 1500 t + sum of damped sinusoids, every 'step' s (jittered by +-40 % if uneven).
Signal ringing(const std::vector<Mode>& modes, double duration, double step, bool uneven = false) {
  Signal signal;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jitter(0.6, 1.4);
  for (double t = 0.0; t <= duration + 1e-12; t += uneven ? step * jitter(random) : step) {
    double y = 3800.0 + 1500.0 * t;
    for (const Mode& m : modes)
      y += m.amplitude * std::exp(-m.decay_rate * t) * std::cos(2 * kPi * m.frequency * t + m.phase);
    signal.time.push_back(t);
    signal.value.push_back(y);
  }
  return signal;
}

}  // namespace

TEST_CASE("prepared window: uniform resampling and the straight line removed", "[post][ringing]") {
  const Signal line = ringing({}, 0.1, 2.5e-4, true);
  const SignalWindow window = prepare_window(line.time, line.value, 0.0, 0.1);
  for (double v : window.value) CHECK(std::abs(v) < 1e-9);
  CHECK(window.peak_to_peak == Approx(1500.0 * line.time.back()).epsilon(1e-12));
  CHECK(window.step > 0.6 * 2.5e-4);
  CHECK(window.step < 1.4 * 2.5e-4);
}

TEST_CASE("Hann spectrum: a sine of amplitude A reads A at its frequency, as a zero-padded DFT does",
          "[post][ringing]") {
  const Signal sine = ringing({{35.0, 0.0, 200.0, 0.3}}, 0.4, 2.5e-4);
  const SignalWindow window = prepare_window(sine.time, sine.value, 0.0, 0.4);
  const SpectralPeak peak = spectrum_peak(window, 10.0, 200.0);
  // 14 periods: the straight-line removal and the window leave a bias far below a bin (2.5 Hz).
  CHECK(peak.frequency == Approx(35.0).margin(0.02));
  CHECK(peak.amplitude == Approx(200.0).epsilon(0.01));
  // The spectrum at bin j of a DFT zero-padded to P N points is that DFT's magnitude.
  const size_t n = window.value.size(), padded = 8 * n;
  const int bin = 37;
  const double f = bin / (padded * window.step);
  double re = 0.0, im = 0.0, weights = 0.0;
  for (size_t k = 0; k < n; ++k) {
    const double w = std::pow(std::sin(kPi * k / (n - 1.0)), 2);
    re += w * window.value[k] * std::cos(2 * kPi * bin * k / padded);
    im -= w * window.value[k] * std::sin(2 * kPi * bin * k / padded);
    weights += w;
  }
  CHECK(hann_spectrum(window, {f})[0] == Approx(2 * std::hypot(re, im) / weights).epsilon(1e-10));
}

TEST_CASE("matrix pencil: two damped sinusoids closer than the window's resolution, each with its decay",
          "[post][ringing]") {
  // 35 and 41 Hz in 120 ms: an FFT bin is 8.3 Hz wide, the Hann main lobe twice that. The
  // detrended window has rank 6 (two pairs and the line the detrending leaves, which comes
  // back as a pair of frequency near 0): a threshold of 1e-6 keeps exactly those.
  const Signal signal = ringing({{35.0, 12.0, 900.0, 0.4}, {41.0, 30.0, 500.0, -1.1}}, 0.12, 2.5e-4);
  const SignalWindow window = prepare_window(signal.time, signal.value, 0.0, 0.12);
  std::vector<DampedComponent> components;
  for (const DampedComponent& c : matrix_pencil(window, {1e-6, 24}))
    if (c.frequency > 1.0) components.push_back(c);
  REQUIRE(components.size() >= 2);
  CHECK(components[0].frequency == Approx(35.0).epsilon(1e-6));
  CHECK(components[0].decay_rate == Approx(12.0).epsilon(1e-4));
  CHECK(components[0].damping_ratio == Approx(12.0 / std::hypot(12.0, 2 * kPi * 35.0)).epsilon(1e-4));
  CHECK(components[0].amplitude == Approx(900.0).epsilon(1e-5));
  CHECK(components[1].frequency == Approx(41.0).epsilon(1e-6));
  CHECK(components[1].decay_rate == Approx(30.0).epsilon(1e-4));
}

TEST_CASE("ringing reading: a fore-aft mode under a weaker vertical one, unevenly sampled", "[post][ringing]") {
  const Signal signal = ringing({{35.0, 15.0, 1500.0, 0.2}, {88.0, 35.0, 400.0, 1.0}}, 0.12, 2.5e-4, true);
  const RingingReading reading = read_ringing(signal.time, signal.value, 0.0, 0.12, {15.0, 200.0});
  // The spectrum's peak of a decaying sinusoid in a finite Hann window sits within a
  // fraction of a bin (8 Hz) of it; the pencil recovers it to the resampling's accuracy.
  CHECK(reading.spectrum.frequency == Approx(35.0).margin(0.5));
  CHECK(reading.pencil.frequency == Approx(35.0).margin(0.05));
  CHECK(reading.pencil.damping_ratio == Approx(15.0 / (2 * kPi * 35.0)).epsilon(0.02));
  CHECK(reading.frequency == Approx(35.0).margin(0.3));
  CHECK(reading.uncertainty < 0.3);
  CHECK(reading.samples == static_cast<int>(signal.time.size()));
  // Looking only above 60 Hz finds the vertical mode instead.
  const RingingReading vertical = read_ringing(signal.time, signal.value, 0.0, 0.12, {60.0, 200.0});
  CHECK(vertical.pencil.frequency == Approx(88.0).margin(0.1));
  CHECK(vertical.spectrum.frequency == Approx(88.0).margin(1.0));
}

TEST_CASE("ringing reading: bad windows and bands are refused with a message", "[post][ringing]") {
  const Signal signal = ringing({{35.0, 15.0, 1500.0, 0.2}}, 0.05, 1e-3);
  CHECK_THROWS_WITH(read_ringing(signal.time, signal.value, 0.0, 0.004), Catch::Contains("at least 8"));
  CHECK_THROWS_WITH(read_ringing(signal.time, signal.value, 0.0, 0.05, {10.0, 800.0}), Catch::Contains("Nyquist"));
  CHECK_THROWS_WITH(read_ringing(signal.time, signal.value, 0.0, 0.05, {100.0, 400.0}),
                    Catch::Contains("no damped sinusoid"));
  CHECK_THROWS_AS(read_ringing(signal.time, signal.value, 0.05, 0.0), std::invalid_argument);
}

TEST_CASE("cleat ringing summary: the measured column only for the test's own conditions", "[post][ringing][drum]") {
  // lua/cleat_ringing.lua, as inputs/drum_cleat.lua prints its summary, on made-up readings:
  // the measured frequencies hold for 51.3 km/h, 3800 N, 208 kPa and the 25 x 660 mm cleat only.
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("summary.lua", R"(
local ringing = require("cleat_ringing")
local readings = {}
for _, window in ipairs(ringing.windows) do
  readings[window.name] = { what = window.what, spectrum_frequency = 35.5, pencil_frequency = 35.7,
                            damping_ratio = 0.143, frequency = 35.6, uncertainty = 0.1 }
end
local test = { speed_kmh = 51.3, load = 3800, pressure_kpa = 208, cleat_height = 0.025, cleat_length = 0.66,
               drum_diameter = 1.7, tire = "tires.145SR12_tread_layer" }
local function changed(key, value)
  local conditions = {}
  for k, v in pairs(test) do conditions[k] = v end
  conditions[key] = value
  return conditions
end
local function table_text(conditions)
  return table.concat(ringing.table_lines(readings, ringing.measured(conditions)), "\n")
end
local function has(text, part) return text:find(part, 1, true) and 1 or 0 end

local own = table_text(test)
tirefe.check{ name = "test's conditions: a measured column", value = has(own, "reading        measured"), expected = 1 }
tirefe.check{ name = "test's conditions: Fz on top measured 88 Hz", value = has(own, "Hz   88 Hz"), expected = 1 }
tirefe.check{ name = "test's conditions: no note", value = has(own, "measured values are for"), expected = 0 }
for _, case in ipairs{ { "speed_kmh", 40 }, { "load", 3000 }, { "pressure_kpa", 250 }, { "cleat_height", 0.015 },
                       { "cleat_length", 0.5 }, { "drum_diameter", 2.0 } } do
  local other = table_text(changed(case[1], case[2]))
  local name = case[1] .. " = " .. case[2] .. ": "
  tirefe.check{ name = name .. "no measured column", value = has(other, "measured\n"), expected = 0 }
  tirefe.check{ name = name .. "no measured value", value = has(other, "Hz   88 Hz") + has(other, "Hz   35 Hz"),
                expected = 0 }
  tirefe.check{ name = name .. "the note", value = has(other, "(measured values are for 51.3 km/h, 3800 N, 208 kPa"),
                expected = 1 }
end
-- Within 0.1 % is the test's speed.
tirefe.check{ name = "51.30001 km/h is the test's", value = has(table_text(changed("speed_kmh", 51.30001)), "88 Hz"),
              expected = 1 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 3 + 6 * 3 + 1);
}
