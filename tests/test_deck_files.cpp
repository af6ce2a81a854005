// The files a deck may read and write (docs/security.md): the path rules of
// deck/deck_files.hpp, the command-line options that widen them, and decks given as
// something that is not a deck file.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "io/hdf5_file.hpp"
#include "deck/deck_files.hpp"
#include "deck/deck_session.hpp"
#include "macros/macro_table.hpp"
#include "tire/tire_builder.hpp"
#include "test_support.hpp"
#include "tirefe/test_paths.hpp"

namespace fs = std::filesystem;
using tirefe::macros::deck_output_path;
using tirefe::macros::deck_relative;
using tirefe::macros::OutputFile;
using tirefe::testing::TempDir;
using Catch::Matchers::Contains;

namespace {

/// Places a session's deck at <dir>/deck/deck.lua and its output folder at <dir>/out.
void place_in(tirefe::macros::DeckSession& session, const TempDir& dir) {
  session.deck_path = dir.write("deck/deck.lua", "");
  session.output_dir = dir.path("out");
}

std::string refusal(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& error) {
    return error.what();
  }
  return "";
}

tirefe::testing::CommandResult run_tirefe(const std::string& arguments) {
  return tirefe::testing::run_command(std::string(TIREFE_BINARY) + " " + arguments + " 2>&1");
}

}  // namespace

TEST_CASE("a deck reads from its folder, lua/, inputs/ and the folders the command line allows", "[files]") {
  TempDir dir;
  tirefe::macros::DeckSession session;
  place_in(session, dir);
  const std::string data = dir.write("deck/data/road.csv", "x,y\n0,0\n");
  dir.write("other/secret.csv", "x,y\n1,1\n");

  CHECK(deck_relative(session, "data/road.csv") == data);
  CHECK(deck_relative(session, data) == data);
  CHECK(deck_relative(session, std::string(TIREFE_SOURCE_DIR) + "/inputs/roads/chuckhole.rdf") ==
        std::string(TIREFE_SOURCE_DIR) + "/inputs/roads/chuckhole.rdf");
  CHECK(deck_relative(session, std::string(TIREFE_LUA_DIR) + "/tires/145SR12.lua").size() > 0);
  CHECK(deck_relative(session, dir.path("out/written.tir")) == dir.path("out/written.tir"));
  // A missing file inside the folders passes: its reader says it is missing.
  CHECK(deck_relative(session, "no_such.csv") == dir.path("deck/no_such.csv"));

  for (const std::string& outside :
       {std::string("../other/secret.csv"), dir.path("other/secret.csv"), std::string("/etc/passwd"),
        std::string("/proc/self/maps"), std::string("data/../../other/secret.csv")}) {
    INFO(outside);
    CHECK_THAT(refusal([&] { deck_relative(session, outside); }),
               Contains("'" + outside + "' lies outside the folders a deck may read") && Contains("--allow-read DIR"));
  }
  SECTION("a symbolic link out of the deck's folder is resolved before the check") {
    fs::create_directory_symlink(dir.path("other"), dir.path("deck/link"));
    CHECK_THAT(refusal([&] { deck_relative(session, "link/secret.csv"); }), Contains("lies outside"));
  }
  SECTION("--allow-read adds a folder") {
    session.read_folders.push_back(dir.path("other"));
    CHECK(deck_relative(session, "../other/secret.csv") == dir.path("deck/../other/secret.csv"));
    // Not a folder whose name merely starts alike.
    dir.write("other2/x.csv", "");
    CHECK_THAT(refusal([&] { deck_relative(session, "../other2/x.csv"); }), Contains("lies outside"));
  }
}

TEST_CASE("a deck writes only in the output folder, never over a file of another kind", "[files]") {
  TempDir dir;
  tirefe::macros::DeckSession session;
  place_in(session, dir);
  const OutputFile result = OutputFile::hdf5("the result file of model 1 ('a')");

  CHECK(deck_output_path(session, "sub/r.h5", result) == dir.path("out/sub/r.h5"));
  CHECK(fs::is_directory(dir.path("out/sub")));  // created for the writer
  CHECK(deck_output_path(session, dir.path("out/sub/r.h5"), result) == dir.path("out/sub/r.h5"));  // same purpose again

  for (const std::string& outside :
       {std::string("../r.h5"), dir.path("deck/r.h5"), std::string("/tmp/r.h5"), std::string("sub/../../r.h5")}) {
    INFO(outside);
    CHECK_THAT(refusal([&] { deck_output_path(session, outside, OutputFile::hdf5("a fit result file")); }),
               Contains("'" + outside + "' lies outside the output folder") && Contains("--allow-write DIR"));
  }
  CHECK_FALSE(fs::exists(dir.path("r.h5")));

  SECTION("a symbolic link out of the output folder is resolved before the check") {
    fs::create_directories(dir.path("elsewhere"));
    fs::create_directory_symlink(dir.path("elsewhere"), dir.path("out/link"));
    CHECK_THAT(refusal([&] { deck_output_path(session, "link/r.h5", result); }), Contains("lies outside"));
  }
  SECTION("--allow-write adds a folder") {
    session.write_folders.push_back(dir.path("elsewhere"));
    CHECK(deck_output_path(session, dir.path("elsewhere/r.h5"), result) == dir.path("elsewhere/r.h5"));
  }
  SECTION("an existing file is replaced only if it is empty or of the kind written") {
    const std::string notes = dir.write("out/notes.h5", "my notes\n");
    CHECK_THAT(refusal([&] { deck_output_path(session, "notes.h5", result); }),
               Contains("notes.h5' exists and is not an HDF5 file") && !Contains("my notes"));
    std::ifstream in(notes);
    std::string kept;
    std::getline(in, kept);
    CHECK(kept == "my notes");  // untouched
    dir.write("out/empty.h5", "");
    CHECK(deck_output_path(session, "empty.h5", result) == dir.path("out/empty.h5"));
    tirefe::io::Hdf5File::create(dir.path("out/old.h5"));
    CHECK(deck_output_path(session, "old.h5", result) == dir.path("out/old.h5"));
    CHECK_THAT(refusal([&] { deck_output_path(session, "sub", result); }), Contains("is a folder"));
  }
  SECTION("one file, one purpose in a run") {
    CHECK_THAT(
        refusal([&] { deck_output_path(session, "sub/r.h5", OutputFile::hdf5("the checkpoint of model 1 ('a')")); }),
        Contains("sub/r.h5' is already the result file of model 1 ('a') in this run; give the checkpoint of "
                 "model 1 ('a') another name"));
    // Through another spelling of the same file.
    CHECK_THAT(refusal([&] { deck_output_path(session, "./sub/../sub/r.h5", OutputFile::hdf5("a fit result file")); }),
               Contains("is already the result file"));
    tirefe::macros::release_outputs(session, "the result file of model 1 ('a')");
    CHECK(deck_output_path(session, "sub/r.h5", OutputFile::hdf5("a fit result file")) == dir.path("out/sub/r.h5"));
  }
}

TEST_CASE("runs that make the same output folder at once all get it", "[files]") {
  // MPI ranks of one vehicle each write their corner's file into one new folder.
  TempDir dir;
  constexpr int kRuns = 8, kRounds = 100;
  std::atomic<int> ready{0}, refused{0};
  std::vector<std::thread> runs;
  for (int r = 0; r < kRuns; ++r)
    runs.emplace_back([&, r] {
      for (int round = 0; round < kRounds; ++round) {
        tirefe::macros::DeckSession session;
        place_in(session, dir);
        ready.fetch_add(1);
        while (ready.load() < (round + 1) * kRuns) std::this_thread::yield();  // start each round together
        const std::string file = "round" + std::to_string(round) + "/a/b/r" + std::to_string(r) + ".h5";
        try {
          deck_output_path(session, file, OutputFile::hdf5("corner " + std::to_string(r)));
        } catch (const std::exception&) {
          refused.fetch_add(1);
        }
      }
    });
  for (std::thread& run : runs) run.join();
  CHECK(refused.load() == 0);
  CHECK(fs::is_directory(dir.path("out/round" + std::to_string(kRounds - 1) + "/a/b")));
}

TEST_CASE("a folder, a missing file or a FIFO as the deck: one line and exit status 2", "[files][decks]") {
  TempDir dir;
  const std::string fifo = dir.path("deck.lua");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const std::string inputs = std::string(TIREFE_SOURCE_DIR) + "/inputs/";
  const std::pair<std::string, std::string> cases[] = {
      {inputs, "tirefe: '" + inputs + "' is a folder; give a deck file in it (DECK.lua)\n"},
      {dir.path("no_such.lua"), "tirefe: no deck file '" + dir.path("no_such.lua") + "'\n"},
      {fifo, "tirefe: '" + fifo + "' is not a regular file; give a deck file (DECK.lua)\n"}};
  for (const auto& [deck, message] : cases) {
    INFO(deck);
    const auto run = tirefe::testing::run_command("timeout 20 " + std::string(TIREFE_BINARY) + " " + deck +
                                                  " --output-dir " + dir.path("out") + " 2>&1");
    CHECK(run.status == 2);
    CHECK(run.output == message);
  }
}

TEST_CASE("a FIFO, a device or a folder in place of a file a deck or a host reads is refused, not read",
          "[files][decks]") {
  // A FIFO would block the read for ever, /dev/zero would never end it.
  TempDir dir;
  tirefe::macros::DeckSession session;
  place_in(session, dir);
  REQUIRE(::mkfifo(dir.path("deck/fifo.csv").c_str(), 0600) == 0);
  fs::create_symlink("/dev/zero", dir.path("deck/zero.tir"));
  fs::create_directories(dir.path("deck/folder.csv"));
  CHECK_THAT(refusal([&] { deck_relative(session, "fifo.csv"); }),
             Contains("fifo.csv' is no regular file (a FIFO or a device would block the read or never end it); give "
                      "a file"));
  session.read_folders.push_back("/dev");
  CHECK_THAT(refusal([&] { deck_relative(session, "zero.tir"); }), Contains("zero.tir' is no regular file"));
  CHECK_THAT(refusal([&] { deck_relative(session, "folder.csv"); }), Contains("folder.csv' is a folder; give a file"));
  // A host's tire property file (tirefe_open), outside any deck.
  CHECK_THAT(refusal([&] { tirefe::macros::load_tire_parameters(dir.path("deck/zero.tir")); }),
             Contains("zero.tir' is no regular file"));
}

TEST_CASE("a deck's read of a foreign file names it without a line of its content", "[files][decks]") {
  TempDir dir;
  const std::string deck = dir.write("deck.lua", "local rows = tirefe.read_csv{ file = '/etc/passwd' }\n");
  const auto run = run_tirefe(deck + " --output-dir " + dir.path("out"));
  CHECK(run.status == 1);
  CHECK(run.output == "tirefe: " + deck +
                          ":1: macro 'read_csv': '/etc/passwd' lies outside the folders a deck may "
                          "read (its own folder, the project's lua/ and inputs/, the output folder); give another with "
                          "--allow-read DIR (docs/security.md)\n");
}

TEST_CASE("the options --allow-read and --allow-write widen what a deck may read and write", "[files][decks]") {
  TempDir dir;
  dir.write("data/curve.csv", "deflection [m],force [N]\n0,0\n0.01,1500\n");
  const std::string deck = dir.write(
      "deck/deck.lua", "local curve = tirefe.read_csv{ file = '" + dir.path("data/curve.csv") +
                           "' }\n"
                           "tirefe.check{ name = 'force', value = curve.force[2], expected = 1500, tolerance = 0 }\n"
                           "tirefe.write_tire{ file = '" +
                           dir.path("tires/a.tir") + "', parameters = require('tires.145SR12') }\n");
  const auto refused = run_tirefe(deck + " --quiet --output-dir " + dir.path("out"));
  CHECK(refused.status == 1);
  CHECK_THAT(refused.output, Contains("curve.csv' lies outside the folders a deck may read"));
  const auto allowed = run_tirefe(deck + " --quiet --output-dir " + dir.path("out") + " --allow-read " +
                                  dir.path("data") + " --allow-write " + dir.path("tires"));
  INFO(allowed.output);
  CHECK(allowed.status == 0);
  CHECK(fs::file_size(dir.path("tires/a.tir")) > 1000);
}
