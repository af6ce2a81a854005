// The fuzz corpus (tests/fuzz_corpus/<target>/) replayed through the fuzz targets' entry
// points (fuzz/fuzz_entries.hpp) in the normal suite: every input the fuzzers kept,
// including those that once crashed a parser, must be accepted or rejected cleanly.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "fuzz/fuzz_entries.hpp"
#include "tirefe/test_paths.hpp"

namespace fs = std::filesystem;

namespace {

int replay(const std::string& target, void (*entry)(const uint8_t*, size_t)) {
  int inputs = 0;
  for (const auto& file : fs::directory_iterator(fs::path(TIREFE_TEST_DATA_DIR) / "fuzz_corpus" / target)) {
    std::ifstream in(file.path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    INFO(file.path().string());
    CHECK_NOTHROW(entry(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
    ++inputs;
  }
  return inputs;
}

}  // namespace

TEST_CASE("the fuzz corpus replays cleanly through every parser", "[reliability][fuzz]") {
  CHECK(replay("deck_macro", tirefe::fuzz::deck_macro) >= 20);
  CHECK(replay("deck_sequence", tirefe::fuzz::deck_sequence) >= 8);
  CHECK(replay("road_profile", tirefe::fuzz::road_profile) >= 3);
  CHECK(replay("curve_data", tirefe::fuzz::curve_data) >= 3);
  CHECK(replay("property_file", tirefe::fuzz::property_file) >= 4);
  CHECK(replay("road_file", tirefe::fuzz::road_file) >= 4);
}

TEST_CASE("the fuzz corpus of a host's inputs replays cleanly: changed checkpoints and C API calls",
          "[reliability][fuzz][capi]") {
  CHECK(replay("checkpoint", tirefe::fuzz::checkpoint_file) >= 4);
  CHECK(replay("capi", tirefe::fuzz::capi_calls) >= 4);
}
