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

// A fenced block whose info string says "source=PATH" quotes a file of the repository
// that the suite builds and runs (examples/): the quote must be that file, verbatim.
TEST_CASE("code quoted in docs/coupling.md is the built and tested file", "[docs]") {
  std::ifstream in(std::string(TIREFE_SOURCE_DIR) + "/docs/coupling.md");
  REQUIRE(in.good());
  int quoted = 0;
  std::string line, source, text;
  bool inside = false;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.rfind("```", 0) != 0) {
      if (inside) text += line + "\n";
      continue;
    }
    inside = !inside;
    if (inside) {
      const size_t at = line.find("source=");
      source = at == std::string::npos ? "" : line.substr(at + 7);
      text.clear();
    } else if (!source.empty()) {
      std::ifstream file(std::string(TIREFE_SOURCE_DIR) + "/" + source);
      INFO("docs/coupling.md quotes " << source << " (block ending at line " << number << ")");
      REQUIRE(file.good());
      CHECK(text == std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>()));
      ++quoted;
    }
  }
  CHECK(quoted == 4);  // the consumer project, the C and Python quarter cars, the k_sw fit
}
