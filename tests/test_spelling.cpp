// The one rule for "did you mean" suggestions (src/core/spelling.hpp): the closest known name
// by an edit distance ignoring case, neighbouring letters winning ties, nothing when no name
// is close enough to be a typo.
#include <catch2/catch.hpp>

#include "core/spelling.hpp"

using namespace tirefe;

TEST_CASE("closest_name: one or two edits away, case ignored, neighbouring letters win ties", "[spelling]") {
  const std::vector<std::string> beam_keys{"EA", "GA", "EI", "elements"};
  CHECK(closest_name("EJ", beam_keys) == "EI");  // J is next to I, far from A
  CHECK(closest_name("ej", beam_keys) == "EI");
  CHECK(closest_name("elemnts", beam_keys) == "elements");
  CHECK(closest_name("nodee", {"mode", "node", "nodes_of"}) == "node");
  CHECK(closest_name("modle", {"model", "mesh", "vehicle"}) == "model");  // a swap costs two edits
  CHECK(closest_name("milimeter", {"meter", "millimeter", "micrometer"}) == "millimeter");
}

TEST_CASE("closest_name: nothing when every name is three edits away or the typo would replace it whole",
          "[spelling]") {
  CHECK(closest_name("anything", {}).empty());
  CHECK(closest_name("xyz", {"node", "model"}).empty());
  CHECK(closest_name("beam", {"section"}).empty());
  CHECK(closest_name("Q", {"EA", "GA"}).empty());  // 2 edits on a 2-letter name: no typo of it
  CHECK(closest_name("EAX", {"EA"}) == "EA");
}

TEST_CASE("did_you_mean: the one wording of a suggestion, or nothing", "[spelling]") {
  CHECK(did_you_mean("HIEGHT", {"WIDTH", "HEIGHT"}) == "did you mean 'HEIGHT'?");
  CHECK(did_you_mean("TRED", {"TREAD", "UNITS"}) == "did you mean 'TREAD'?");
  CHECK(did_you_mean("pressure", {"WIDTH", "HEIGHT"}).empty());
}
