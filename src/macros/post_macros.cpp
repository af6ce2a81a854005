// Post-processing macros: tirefe.oscillation{...} finds the dominant damped oscillation in
// a window of a history the deck collected (the ringing of a spindle force after a cleat).
#include "macros/macro_table.hpp"
#include "post/oscillation.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;

int oscillation_macro(lua_State* L, DeckSession&, const MacroArguments& arguments) {
  post::OscillationSearch search;
  search.min_frequency = arguments.number("min_frequency");
  search.max_frequency = arguments.number("max_frequency");
  search.max_decay_rate = arguments.number("max_decay_rate");
  const post::Oscillation found =
      post::dominant_oscillation(arguments.number_list("time"), arguments.number_list("values"),
                                 arguments.number("from"), arguments.number("to"), search);
  lua_createtable(L, 0, 6);
  const std::pair<const char*, double> fields[] = {{"frequency", found.frequency},
                                                   {"amplitude", found.amplitude},
                                                   {"decay_rate", found.decay_rate},
                                                   {"peak_to_peak", found.peak_to_peak},
                                                   {"rms_misfit", found.rms_misfit},
                                                   {"samples", static_cast<double>(found.samples)}};
  for (const auto& [name, value] : fields) {
    lua_pushnumber(L, value);
    lua_setfield(L, -2, name);
  }
  return 1;
}

}  // namespace

void add_post_macros(MacroTable& table) {
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
         {"max_frequency", VT::Number, false, "Hz", "highest frequency searched", std::string("400"),
          Range::Positive},
         {"max_decay_rate", VT::Number, false, "1/s", "largest decay rate searched", std::string("200"),
          Range::Positive}},
        "local fz = tirefe.oscillation{ time = times, values = forces, from = 7.52, to = 7.56 }\n"
        "print(fz.frequency, fz.peak_to_peak)"},
       oscillation_macro});
}

}  // namespace tirefe::macros
