// The suite's own test names: CTest learns them by listing them (catch_discover_tests) and
// keeps them in CMake lists, where a square bracket that does not close swallows the
// names after it: one such name silently drops tests from `ctest`. Brackets in a name
// must pair up.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

TEST_CASE("test names pair their square brackets, or CTest would not see the tests after them", "[suite]") {
  const std::vector<Catch::TestCase>& tests = Catch::getRegistryHub().getTestCaseRegistry().getAllTests();
  CHECK(tests.size() > 200);
  for (const Catch::TestCase& test : tests) {
    int open = 0;
    bool paired = true;
    for (char c : test.name) {
      open += c == '[' ? 1 : c == ']' ? -1 : 0;
      paired = paired && open >= 0;
    }
    INFO(test.name);
    CHECK((paired && open == 0));
  }
}
