// The examples of the docs run as written. In a doc, a fenced block whose info string is
// "<language> file=NAME" is a data file the examples use; a block marked "lua deck" is a
// deck. Each doc's files are written to a fresh folder (next to copies of the shipped
// inputs/tires and inputs/roads), then each of its decks runs there and must end without
// an error and with every tirefe.check passed.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "deck_support.hpp"
#include "test_support.hpp"
#include "tirefe/test_paths.hpp"

namespace fs = std::filesystem;

namespace {

struct DocBlock {
  std::string info;  // the fence's info string, e.g. "lua deck"
  std::string text;
  int line = 0;      // of the opening fence
};

std::vector<DocBlock> fenced_blocks(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::vector<DocBlock> blocks;
  std::string line;
  bool inside = false;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.rfind("```", 0) == 0) {
      if (!inside) blocks.push_back({line.substr(3), "", number});
      inside = !inside;
    } else if (inside) {
      blocks.back().text += line + "\n";
    }
  }
  REQUIRE_FALSE(inside);
  return blocks;
}

/// Runs the examples of one doc; returns the number of decks run.
int run_examples(const std::string& doc) {
  tirefe::testing::TempDir folder;
  for (const char* shipped : {"tires", "roads"})
    fs::copy(fs::path(TIREFE_SOURCE_DIR) / "inputs" / shipped, folder.path(shipped), fs::copy_options::recursive);
  const std::vector<DocBlock> blocks = fenced_blocks(std::string(TIREFE_SOURCE_DIR) + "/" + doc);
  for (const DocBlock& block : blocks) {
    const size_t file = block.info.find("file=");
    if (file != std::string::npos) folder.write(block.info.substr(file + 5), block.text);
  }
  int decks = 0;
  for (const DocBlock& block : blocks) {
    if (block.info != "lua deck") continue;
    const std::string deck = folder.write("example_" + std::to_string(block.line) + ".lua", block.text);
    const tirefe::testing::InProcessRun run = tirefe::testing::run_deck_in_process(deck, folder.path("out"));
    INFO(doc << ", the deck at line " << block.line << ":\n" << block.text);
    CHECK(run.error == "");
    CHECK(run.failed_checks == 0);
    ++decks;
  }
  return decks;
}

}  // namespace

TEST_CASE("the examples of docs/tire.md and docs/contact.md run and pass their checks", "[docs]") {
  CHECK(run_examples("docs/tire.md") == 3);
  CHECK(run_examples("docs/contact.md") == 2);
}

TEST_CASE("the example of docs/security.md runs and passes its checks", "[docs][files]") {
  CHECK(run_examples("docs/security.md") == 1);
}
