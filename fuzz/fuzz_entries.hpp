// The parsers' fuzz entry points (docs/reliability.md), shared by the libFuzzer targets in
// fuzz/ and by the corpus replay in the test suite. Each feeds arbitrary bytes to one
// parser and returns normally whether the input was accepted or rejected with the
// parser's documented error; anything else (a crash, an undocumented exception, a
// rejection without the file's name, a non-finite value accepted) is a failure: it aborts
// under the fuzzer and fails the replay test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace tirefe::fuzz {

/// Broken invariants of a parser (never thrown for merely bad input).
class FuzzFailure : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// The first byte picks a deck macro; the rest is its argument table, called on a small
/// model through the Lua sandbox and the macro layer (argument validation).
void deck_macro(const uint8_t* data, size_t size);
/// A short sequence of macro calls on a small beam model, solving ones included (bounded
/// steps and step counts), with Lua load functions that call back into macros while the
/// model assembles: each byte pair picks a call and its argument (fuzz_entries.cpp).
void deck_sequence(const uint8_t* data, size_t size);
/// The deck deck_sequence() runs for these bytes (to read a finding as a deck).
std::string sequence_deck(const uint8_t* data, size_t size);
/// A road-profile text file (two columns x y), then the profile built from it and a few projections.
void road_profile(const uint8_t* data, size_t size);
/// A CSV data file (header with unit suffixes, rows of numbers).
void curve_data(const uint8_t* data, size_t size);
/// A TeimOrbit file read as a tire property file (.tir: tirefe's own or a standard MF-Tyre
/// file) and as a road data file (.rdf).
void property_file(const uint8_t* data, size_t size);
/// A road profile file read by name as CSV (.csv, each track), OpenCRG (.crg, three lateral
/// positions) and 'x y' text (src/formats/road_file.hpp).
void road_file(const uint8_t* data, size_t size);
/// A checkpoint of a small beam run with its numbers changed (fuzz_entries.cpp), read back
/// and restarted from: refused with an error naming the file or the deck, or restarted to
/// a result file whose times are finite.
void checkpoint_file(const uint8_t* data, size_t size);
/// The changes checkpoint_file() makes for these bytes: "<place> = <value>" per line.
std::string checkpoint_changes(const uint8_t* data, size_t size);
/// A sequence of C API calls (include/tirefe.h) on a small tire, with arguments from the
/// bytes: every call answers with a known status, a one-line message when it fails,
/// finite numbers when it succeeds, and a failed step leaves the committed state as it was.
void capi_calls(const uint8_t* data, size_t size);

}  // namespace tirefe::fuzz
