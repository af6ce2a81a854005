// The tirefe command line (docs/decks.md, "The command line"): --help, --list-parameters
// and the documented form of a deck's parameters, the progress line on a terminal and
// its silence in a log, --verbose.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "app/parameter_list.hpp"
#include "deck/progress_line.hpp"
#include "solvers/analysis.hpp"
#include "test_support.hpp"
#include "tirefe/test_paths.hpp"

namespace fs = std::filesystem;
using tirefe::macros::ParameterDeclaration;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct Run {
  int status = -1;
  std::string out, err;
  double seconds = 0.0;
};

/// Runs a shell command in 'folder' with standard output and error caught in files there.
Run run_in(const std::string& folder, const std::string& command) {
  const std::string out = folder + "/.stdout", err = folder + "/.stderr";
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system(("cd '" + folder + "' && " + command + " >" + out + " 2>" + err).c_str());
  Run run;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = read_text(out);
  run.err = read_text(err);
  fs::remove(out);
  fs::remove(err);
  return run;
}

std::string tirefe_binary() { return TIREFE_BINARY; }
std::string source_path(const std::string& relative) { return std::string(TIREFE_SOURCE_DIR) + "/" + relative; }

/// The rows of a --list-parameters table by name: {default, unit, meaning}.
std::map<std::string, std::vector<std::string>> table_rows(const std::string& table) {
  std::map<std::string, std::vector<std::string>> rows;
  std::istringstream lines(table);
  std::string line;
  std::getline(lines, line);  // "DECK: N parameters, ..."
  std::getline(lines, line);  // the column titles
  const std::regex row(R"(^  (\S+) +(\S+) +(\S+) +(\S.*)$)");
  while (std::getline(lines, line)) {
    std::smatch match;
    if (std::regex_match(line, match, row)) rows[match[1]] = {match[2], match[3], match[4]};
  }
  return rows;
}

size_t count(const std::string& text, const std::string& piece) {
  size_t found = 0;
  for (size_t at = text.find(piece); at != std::string::npos; at = text.find(piece, at + 1)) ++found;
  return found;
}

}  // namespace

TEST_CASE("tirefe --help and -h print the usage, the options, the exit statuses and where the docs are; exit 0",
          "[cli]") {
  tirefe::testing::TempDir folder;
  const Run help = run_in(folder.path(), tirefe_binary() + " --help");
  CHECK(help.status == 0);
  CHECK(help.err.empty());
  for (const char* piece :
       {"usage: tirefe DECK.lua [key=value ...]", "--list-parameters DECK", "--output-dir DIR", "--restart CHECKPOINT",
        "--quiet", "--verbose", "-h, --help", "Progress:", "2 a usage error", "3 a self-check of the deck failed",
        "130 or 143", "docs/ (decks.md", TIREFE_SOURCE_DIR})
    CHECK(help.out.find(piece) != std::string::npos);
  const Run short_form = run_in(folder.path(), tirefe_binary() + " -h");
  CHECK(short_form.status == 0);
  CHECK(short_form.out == help.out);
  // An unknown option is a usage error that points at --help's usage lines.
  const Run unknown = run_in(folder.path(), tirefe_binary() + " --hepl");
  CHECK(unknown.status == 2);
  CHECK(unknown.err.rfind("tirefe: unknown option '--hepl'\nusage: tirefe DECK.lua", 0) == 0);
}

TEST_CASE(
    "tirefe --list-parameters lists every parameter of the drum-cleat deck with its default and unit, "
    "running no model",
    "[cli]") {
  tirefe::testing::TempDir folder;
  const Run list =
      run_in(folder.path(), tirefe_binary() + " --list-parameters " + source_path("inputs/drum_cleat.lua"));
  INFO(list.out << list.err);
  CHECK(list.status == 0);
  CHECK(list.err.empty());
  CHECK(list.out.rfind(
            source_path("inputs/drum_cleat.lua") + ": 29 parameters, set on the command line as name=value\n", 0) == 0);
  const auto rows = table_rows(list.out);
  CHECK(rows.size() == 29);
  using Row = std::vector<std::string>;
  CHECK(rows.at("speed_kmh") == Row{"51.3", "km/h", "final drum surface speed"});
  CHECK(rows.at("load") == Row{"3800", "N", "spindle load on the drum"});
  CHECK(rows.at("cleat_height") == Row{"0.025", "m", "cleat height"});
  CHECK(rows.at("cleat_start_deg") == Row{"-90", "deg", "where the cleat's middle is at rest, from +x (-90: bottom)"});
  CHECK(rows.at("integrator") == Row{"hht", "-", "hht or newmark"});
  CHECK(rows.at("check")[0] == "false");
  CHECK(rows.at("tire")[0] == "tires.145SR12_tread_layer");
  // Nothing ran: no results/ folder, no file at all where it ran.
  CHECK(fs::is_empty(folder.path()));
}

TEST_CASE("tirefe --list-parameters: a missing deck is a usage error (2), an unreadable one a deck error (1)",
          "[cli]") {
  tirefe::testing::TempDir folder;
  const Run missing = run_in(folder.path(), tirefe_binary() + " --list-parameters");
  CHECK(missing.status == 2);
  CHECK(missing.out.empty());
  CHECK(missing.err.rfind("tirefe: --list-parameters takes one deck and nothing else\nusage: tirefe", 0) == 0);
  const Run two = run_in(folder.path(), tirefe_binary() + " --list-parameters a.lua b.lua");
  CHECK(two.status == 2);
  const Run overrides = run_in(folder.path(), tirefe_binary() + " --list-parameters a.lua speed_kmh=30");
  CHECK(overrides.status == 2);
  const Run absent = run_in(folder.path(), tirefe_binary() + " --list-parameters no_such_deck.lua");
  CHECK(absent.status == 1);
  CHECK(absent.err == "tirefe: no_such_deck.lua: cannot open the deck file\n");
  CHECK(fs::is_empty(folder.path()));
}

TEST_CASE("tirefe --list-parameters stops a deck that builds a model before declaring parameters", "[cli]") {
  tirefe::testing::TempDir folder;
  folder.write("model_first.lua",
               "local model = tirefe.model{ title = 'not listed' }\n"
               "model:node{ x = 0, y = 0 }\n"
               "model:solve{ to = 1, dt = 0.5 }\n");
  const Run list = run_in(folder.path(), tirefe_binary() + " --list-parameters model_first.lua");
  CHECK(list.status == 0);
  CHECK(list.out == "model_first.lua declares no parameters (tirefe.parameters{...})\n");
  CHECK(!fs::exists(folder.path("results")));
}

TEST_CASE("a documented parameter gives the deck its plain default, and overrides convert to the default's type",
          "[cli][decks]") {
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write(
      "documented.lua",
      "local p = tirefe.parameters{\n"
      "  speed_kmh = { 51.3, 'final drum surface speed', unit = 'km/h' },\n"
      "  elements = { 100, 'wedges around the tire' },\n"
      "  label = { 'run', unit = '-' },\n"
      "  plain = 2.5,\n"
      "}\n"
      "assert(p.speed_kmh == 30.5, 'speed_kmh ' .. tostring(p.speed_kmh))\n"
      "assert(math.type(p.elements) == 'integer' and p.elements == 40, 'elements ' .. tostring(p.elements))\n"
      "assert(p.label == 'run' and p.plain == 2.5)\n");
  tirefe::macros::LuaSandbox sandbox(TIREFE_LUA_DIR);
  REQUIRE_NOTHROW(sandbox.run_file(deck, {{"speed_kmh", "30.5"}, {"elements", "40"}}));
  const std::vector<ParameterDeclaration>& declared = sandbox.declared_parameters();
  REQUIRE(declared.size() == 4);  // sorted by name
  CHECK(declared[0].name == "elements");
  CHECK(declared[0].default_text == "100");
  CHECK(declared[0].unit.empty());
  CHECK(declared[1].name == "label");
  CHECK(declared[1].meaning.empty());
  CHECK(declared[1].unit == "-");
  CHECK(declared[2].name == "plain");
  CHECK(declared[2].default_text == "2.5");
  CHECK(declared[3].name == "speed_kmh");
  CHECK(declared[3].default_text == "51.3");
  CHECK(declared[3].unit == "km/h");
  CHECK(declared[3].meaning == "final drum surface speed");
  try {
    sandbox.run_file(deck, {{"elements", "40.5"}});
    FAIL("a non-integer override of an integer default was accepted");
  } catch (const tirefe::macros::DeckError& error) {
    CHECK(std::string(error.what()) ==
          deck + ":1: command-line parameter 'elements=40.5' must be an integer like its default 100");
  }
}

TEST_CASE("every parameter of the shipped decks says what it means", "[cli][decks]") {
  int decks_with_parameters = 0;
  for (const auto& entry : fs::directory_iterator(source_path("inputs"))) {
    if (entry.path().extension() != ".lua") continue;
    const std::vector<ParameterDeclaration> declared = tirefe::macros::declared_parameters(entry.path().string());
    for (const auto& parameter : declared) {
      INFO(entry.path().string() << ": " << parameter.name);
      CHECK(!parameter.meaning.empty());
    }
    decks_with_parameters += declared.empty() ? 0 : 1;
  }
  CHECK(decks_with_parameters == 13);
}

TEST_CASE("docs/drum_cleat.md's table of deck parameters is the deck's own", "[cli][docs]") {
  const std::string doc = read_text(source_path("docs/drum_cleat.md"));
  const size_t section = doc.find("### Deck parameters");
  REQUIRE(section != std::string::npos);
  std::map<std::string, std::vector<std::string>> documented;  // name -> default, unit, meaning
  const std::regex row(R"(^\| `(\w+)` \| `?([^`|]*)`? \| ([^|]*) \| (.*) \|$)");
  std::istringstream lines(doc.substr(section, doc.find("\n## ", section) - section));
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (std::regex_match(line, match, row)) documented[match[1]] = {match[2], match[3], match[4]};
  }
  const std::vector<ParameterDeclaration> declared =
      tirefe::macros::declared_parameters(source_path("inputs/drum_cleat.lua"));
  CHECK(documented.size() == declared.size());
  for (const auto& parameter : declared) {
    INFO("parameter " << parameter.name);
    REQUIRE(documented.count(parameter.name));
    const std::vector<std::string>& doc_row = documented[parameter.name];
    char* end = nullptr;
    const double number = std::strtod(doc_row[0].c_str(), &end);
    if (*end == '\0' && !doc_row[0].empty())
      CHECK(number == Approx(std::stod(parameter.default_text)).epsilon(1e-12));
    else
      CHECK(doc_row[0] == parameter.default_text);
    CHECK(doc_row[1] == (parameter.unit.empty() ? "-" : parameter.unit));
    CHECK(doc_row[2] == parameter.meaning);
  }
}

TEST_CASE("the commands of the docs' 'sh run' blocks run, and print the lines of the 'text output' block after",
          "[cli][docs]") {
  int commands = 0;
  std::vector<std::string> docs{source_path("README.md")};
  for (const auto& entry : fs::directory_iterator(source_path("docs")))
    if (entry.path().extension() == ".md") docs.push_back(entry.path().string());
  for (const std::string& doc : docs) {
    std::istringstream lines(read_text(doc));
    std::string line, fence, output;  // fence: the info string of the open block
    bool inside = false;
    for (int number = 1; std::getline(lines, line); ++number) {
      if (line.rfind("```", 0) == 0) {
        inside = !inside;
        if (inside) fence = line.substr(3);
        continue;
      }
      if (!inside) continue;
      INFO(doc << ":" << number << ": " << line);
      if (fence == "sh run") {
        REQUIRE(line.rfind("build/tirefe ", 0) == 0);
        const Run run = run_in(TIREFE_SOURCE_DIR, tirefe_binary() + line.substr(12));
        CHECK(run.status == 0);
        output += run.out;
        ++commands;
      } else if (fence == "text output") {
        CHECK(output.find(line + "\n") != std::string::npos);
      }
    }
  }
  CHECK(commands >= 2);
}

TEST_CASE("ProgressLine: its text, one drawing per interval at most, erased before other output", "[cli]") {
  using tirefe::macros::ProgressLine;
  CHECK(ProgressLine::text(3.217, 8.0, 2894, 0, 4.2, 6.4) ==
        "t = 3.217 s of 8 s  step 2894  cuts 0  elapsed 0:04  left ~0:06");
  CHECK(ProgressLine::text(0.25, std::nullopt, 12, 3, 3725.0, std::nullopt) ==
        "t = 0.25 s  step 12  cuts 3  elapsed 1:02:05");

  std::FILE* stream = std::tmpfile();
  REQUIRE(stream != nullptr);
  ProgressLine line;
  line.clear();  // nothing drawn yet: nothing to erase
  tirefe::StepRecord record;
  record.step = 1;
  record.time = 0.5;
  line.record(record);  // not drawing yet
  line.draw_on(stream, std::chrono::hours(1));
  line.set_end_time(2.0);
  record.step = 2;
  record.time = 1.0;
  record.cuts = 2;
  line.record(record);  // drawn
  record.step = 3;
  record.time = 1.5;
  line.record(record);  // within the interval: not drawn
  line.clear();
  line.clear();  // erased once
  std::fflush(stream);
  std::rewind(stream);
  std::string written(256, '\0');
  written.resize(std::fread(written.data(), 1, written.size(), stream));
  std::fclose(stream);
  CHECK(written == "\rt = 1 s of 2 s  step 2  cuts 2  elapsed 0:00\x1b[K\r\r\x1b[K");
}

TEST_CASE(
    "the progress line: rewritten in place on a terminal, nothing per step in a log, one line a step with "
    "--verbose",
    "[cli]") {
  tirefe::testing::TempDir folder;
  const std::string deck = source_path("inputs/cantilever_elastica.lua");
  const std::string command = tirefe_binary() + " " + deck + " steps=40 --output-dir out";
  // A pseudo-terminal: script(1) runs the command with standard output and error on one.
  const Run terminal = run_in(folder.path(), "script -qec '" + command + "' /dev/null");
  INFO(terminal.out << terminal.err);
  REQUIRE(terminal.status == 0);
  const size_t drawings = count(terminal.out, "\rt = ");
  CHECK(drawings >= 1);
  CHECK(drawings <= 2 + static_cast<size_t>(4.0 * terminal.seconds));  // at most four a second
  CHECK(count(terminal.out, "\x1b[K\r") == drawings);
  CHECK(terminal.out.find("  step    40") == std::string::npos);
  // Erased before the deck's own output: the first check line starts on a clean line.
  CHECK(terminal.out.find("\r\x1b[Ktip deflection") != std::string::npos);

  const Run log = run_in(folder.path(), command);
  CHECK(log.status == 0);
  CHECK(log.err.empty());
  CHECK(log.out.find('\r') == std::string::npos);
  CHECK(log.out.find("step") == std::string::npos);
  CHECK(log.out.find("inputs/cantilever_elastica.lua: 3 passed, 0 failed\n") != std::string::npos);

  const Run verbose = run_in(folder.path(), command + " --verbose");
  CHECK(verbose.status == 0);
  CHECK(verbose.err.empty());
  CHECK(count(verbose.out, "  step ") == 40);
  CHECK(verbose.out.find("  step    40  t = 1 ") != std::string::npos);

  const Run quiet = run_in(folder.path(), "script -qec '" + command + " --quiet' /dev/null");
  CHECK(quiet.status == 0);
  CHECK(quiet.out.find("\rt = ") == std::string::npos);
}

TEST_CASE("an option that takes a value without one is a usage error naming the option, not an unknown option",
          "[cli]") {
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("deck.lua", "");
  for (const std::string option : {"--output-dir", "--restart", "--allow-read", "--allow-write", "--lua-memory"}) {
    INFO(option);
    const Run last = run_in(folder.path(), tirefe_binary() + " " + deck + " " + option);
    CHECK(last.status == 2);
    CHECK(last.err.rfind("tirefe: option '" + option + "' needs a value: " + option + " ", 0) == 0);
    // Nor is the next option taken for its value.
    const Run followed = run_in(folder.path(), tirefe_binary() + " " + deck + " " + option + " --quiet");
    CHECK(followed.status == 2);
    CHECK(followed.err.find("needs a value: " + option) != std::string::npos);
    CHECK(followed.err.find("(got the option '--quiet')") != std::string::npos);
  }
}
