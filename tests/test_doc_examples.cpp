// The examples of the docs run as written. In a doc, a fenced block whose info string is
// "<language> file=NAME" is a data file the examples use; a block marked "lua deck" is a
// deck. Each doc's files are written to a fresh folder (next to copies of the shipped
// inputs/tires and inputs/roads), then each of its decks runs there and must end without
// an error and with every tirefe.check passed.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "deck_support.hpp"
#include "io/hdf5_file.hpp"
#include "deck/checkpoint.hpp"
#include "test_support.hpp"
#include "tirefe/test_paths.hpp"

namespace fs = std::filesystem;

namespace {

struct DocBlock {
  std::string info;  // the fence's info string, e.g. "lua deck"
  std::string text;
  int line = 0;  // of the opening fence
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

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// Runs the `build/tirefe ...` lines of a doc's sh blocks, in order, in 'folder' (which
/// sees the shipped inputs/ as its own); each must exit with status 0. Returns their number.
int run_commands(const std::string& doc, const tirefe::testing::TempDir& folder) {
  fs::create_directory_symlink(fs::path(TIREFE_SOURCE_DIR) / "inputs", folder.path("inputs"));
  const std::string program = "build/tirefe ";
  int commands = 0;
  for (const DocBlock& block : fenced_blocks(std::string(TIREFE_SOURCE_DIR) + "/" + doc)) {
    if (block.info != "sh") continue;
    std::istringstream lines(block.text);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind(program, 0) != 0) continue;
      const std::string command =
          "cd " + folder.path() + " && " + TIREFE_BINARY + " " + line.substr(program.size()) + " > /dev/null 2>&1";
      INFO(doc << ", the block at line " << block.line << ": " << line);
      const int status = std::system(command.c_str());
      REQUIRE(WIFEXITED(status));
      CHECK(WEXITSTATUS(status) == 0);
      ++commands;
    }
  }
  return commands;
}

}  // namespace

TEST_CASE("the commands of docs/restart.md run, and the restarted run's file equals the whole run's",
          "[docs][restart]") {
  tirefe::testing::TempDir folder;
  REQUIRE(run_commands("docs/restart.md", folder) == 2);
  const fs::path whole = folder.path("results"), restarted = whole / "restarted";
  const auto checkpoint = tirefe::macros::read_checkpoint((whole / "rolling.ckpt.h5").string());
  CHECK(checkpoint.analysis.state.time == Approx(2.3).epsilon(1e-12));
  const auto reference = tirefe::io::Hdf5File::open_read_only((whole / "tire_restart.h5").string());
  const auto result = tirefe::io::Hdf5File::open_read_only((restarted / "tire_restart.h5").string());
  // Every row dataset, history, fields and contact rows, over the whole run.
  int compared = 0;
  for (const auto& rows : checkpoint.rows) {
    INFO(rows.path);
    const std::vector<double> a = result.read_doubles(rows.path), b = reference.read_doubles(rows.path);
    REQUIRE(a.size() == b.size());
    CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
    ++compared;
  }
  CHECK(compared >= 20);
  CHECK(reference.read_doubles("/history/time").back() == Approx(2.6).epsilon(1e-12));
  // The run is a rolling tire: loaded, turning at the road's speed over its rolling radius.
  CHECK(reference.read_doubles("/history/spindle_fz").back() == Approx(3590).epsilon(0.02));
  CHECK(reference.read_doubles("/history/spin_rate").back() == Approx(8.0 / 0.2717).epsilon(0.01));
  CHECK(text_of(restarted / "tire_restart.xmf") == text_of(whole / "tire_restart.xmf"));
}

TEST_CASE(
    "the examples of docs/tire.md, docs/mf_tire_files.md, docs/roads.md and docs/output.md run and pass their "
    "checks",
    "[docs]") {
  CHECK(run_examples("docs/tire.md") == 3);
  CHECK(run_examples("docs/mf_tire_files.md") == 1);
  CHECK(run_examples("docs/roads.md") == 4);
  CHECK(run_examples("docs/output.md") == 1);
}

TEST_CASE("the example of docs/security.md runs and passes its checks", "[docs][files]") {
  CHECK(run_examples("docs/security.md") == 1);
}

TEST_CASE("the example of docs/decks.md's library modules runs and passes its checks", "[docs][modules]") {
  CHECK(run_examples("docs/decks.md") == 1);
}
