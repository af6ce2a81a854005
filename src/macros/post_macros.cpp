// Post-processing macros on a history the deck collected (the ringing of a spindle force
// after a cleat): tirefe.ringing{...} reads its frequency by two estimators,
// tirefe.oscillation{...} fits one damped sinusoid on a trend.
#include <initializer_list>
#include <utility>

#include "macros/macro_table.hpp"
#include "post/oscillation.hpp"
#include "post/ringing.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;

void set_fields(lua_State* L, std::initializer_list<std::pair<const char*, double>> fields) {
  lua_createtable(L, 0, static_cast<int>(fields.size()));
  for (const auto& [name, value] : fields) {
    lua_pushnumber(L, value);
    lua_setfield(L, -2, name);
  }
}

int ringing_macro(lua_State* L, DeckSession&, const MacroArguments& arguments) {
  const post::RingingBand band{arguments.number("min_frequency"), arguments.number("max_frequency")};
  const post::RingingReading reading =
      post::read_ringing(arguments.number_list("time"), arguments.number_list("values"), arguments.number("from"),
                         arguments.number("to"), band);
  set_fields(L, {{"frequency", reading.frequency},
                 {"uncertainty", reading.uncertainty},
                 {"spectrum_frequency", reading.spectrum.frequency},
                 {"spectrum_amplitude", reading.spectrum.amplitude},
                 {"pencil_frequency", reading.pencil.frequency},
                 {"pencil_amplitude", reading.pencil.amplitude},
                 {"damping_ratio", reading.pencil.damping_ratio},
                 {"peak_to_peak", reading.peak_to_peak},
                 {"samples", static_cast<double>(reading.samples)}});
  return 1;
}

int oscillation_macro(lua_State* L, DeckSession&, const MacroArguments& arguments) {
  post::OscillationSearch search;
  search.min_frequency = arguments.number("min_frequency");
  search.max_frequency = arguments.number("max_frequency");
  search.max_decay_rate = arguments.number("max_decay_rate");
  const post::Oscillation found =
      post::dominant_oscillation(arguments.number_list("time"), arguments.number_list("values"),
                                 arguments.number("from"), arguments.number("to"), search);
  set_fields(L, {{"frequency", found.frequency},
                 {"amplitude", found.amplitude},
                 {"decay_rate", found.decay_rate},
                 {"peak_to_peak", found.peak_to_peak},
                 {"rms_misfit", found.rms_misfit},
                 {"samples", static_cast<double>(found.samples)}});
  return 1;
}

}  // namespace

void add_post_macros(MacroTable& table) {
  table.module_macros.push_back(
      {{"ringing",
        "Reads the frequency a sampled history rings at within [from, to] by two independent estimators of the "
        "same signal (resampled uniformly, its straight line removed): the peak of its Hann-windowed, "
        "zero-padded spectrum in the band, and the most energetic damped sinusoid in the band of a matrix-pencil "
        "decomposition. Returns {frequency (their mean) [Hz], uncertainty (half their difference) [Hz], "
        "spectrum_frequency, spectrum_amplitude, pencil_frequency, pencil_amplitude, damping_ratio (of the "
        "pencil's sinusoid), peak_to_peak, samples}.",
        {{"time", VT::NumberList, true, "s", "sample times (increasing)"},
         {"values", VT::NumberList, true, "", "sample values"},
         {"from", VT::Number, true, "s", "window start"},
         {"to", VT::Number, true, "s", "window end"},
         {"min_frequency", VT::Number, false, "Hz", "lowest frequency of the band", std::string("10"), Range::Positive},
         {"max_frequency", VT::Number, false, "Hz", "highest frequency of the band", std::string("200"),
          Range::Positive}},
        "local fx = tirefe.ringing{ time = times, values = forces, from = 7.59, to = 7.71, min_frequency = 15 }\n"
        "print(fx.frequency, fx.uncertainty, fx.damping_ratio)"},
       ringing_macro});
  table.module_macros.push_back(
      {{"oscillation",
        "Finds the dominant damped oscillation of a sampled history within [from, to] by a least-squares fit "
        "of a linear trend plus one damped sinusoid (resolves a frequency from a few periods, where an FFT "
        "cannot; samples may be unevenly spaced). Returns {frequency [Hz], amplitude, decay_rate [1/s], "
        "peak_to_peak, rms_misfit, samples}.",
        {{"time", VT::NumberList, true, "s", "sample times"},
         {"values", VT::NumberList, true, "", "sample values"},
         {"from", VT::Number, true, "s", "window start"},
         {"to", VT::Number, true, "s", "window end"},
         {"min_frequency", VT::Number, false, "Hz", "lowest frequency searched", std::string("5"), Range::Positive},
         {"max_frequency", VT::Number, false, "Hz", "highest frequency searched", std::string("400"), Range::Positive},
         {"max_decay_rate", VT::Number, false, "1/s", "largest decay rate searched", std::string("200"),
          Range::Positive}},
        "local fz = tirefe.oscillation{ time = times, values = forces, from = 7.52, to = 7.56 }\n"
        "print(fz.frequency, fz.peak_to_peak)"},
       oscillation_macro});
}

}  // namespace tirefe::macros
