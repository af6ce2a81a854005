// The macro reference in docs/ is generated from the macro specs: keep it current.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

#include "macros/macro_table.hpp"
#include "tirefe/test_paths.hpp"

TEST_CASE("docs/macros.md is the current macro reference (regenerate: tirefe --macros > docs/macros.md)",
          "[docs]") {
  std::ifstream in(std::string(TIREFE_SOURCE_DIR) + "/docs/macros.md");
  REQUIRE(in.good());
  const std::string documented((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(documented == tirefe::macros::macro_reference());
}
