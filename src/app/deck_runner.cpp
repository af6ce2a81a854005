#include "app/deck_runner.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <vector>

#include "deck/checkpoint.hpp"
#include "deck/interrupt.hpp"
#include "deck/lua_module_dir.hpp"
#include "deck/lua_sandbox.hpp"
#include "io/frame_views.hpp"
#include "macros/macro_table.hpp"
#include "app/parameter_list.hpp"
#include "tirefe/source_paths.hpp"
#include "tirefe/version.hpp"

namespace tirefe::macros {

namespace {

constexpr const char* kUsage =
    "usage: tirefe DECK.lua [key=value ...] [--output-dir DIR] [--restart CHECKPOINT] [--quiet | --verbose]\n"
    "                       [--allow-read DIR] [--allow-write DIR] [--lua-memory MIB]\n"
    "       tirefe --list-parameters DECK.lua\n"
    "       tirefe --views RESULT.h5 ...\n"
    "       tirefe --help | --macros | --version\n";

constexpr const char* kHelp =
    "\n"
    "Runs an input deck, a Lua script that builds finite-element tire models and solves them.\n"
    "\n"
    "  key=value               set a parameter the deck declares with tirefe.parameters{...}\n"
    "  --output-dir DIR        folder for result files (default: results)\n"
    "  --restart CHECKPOINT    continue from a file written by model:checkpoint\n"
    "  --quiet                 no progress line, no step or modal reports\n"
    "  --verbose               one line per step on standard output instead of the progress\n"
    "                          line, and the Lua traceback of an error\n"
    "  --allow-read DIR        let the deck read files in DIR too (repeatable; docs/security.md)\n"
    "  --allow-write DIR       let the deck write files in DIR too (repeatable)\n"
    "  --lua-memory MIB        the most memory the deck's Lua may hold (default 1024 MiB)\n"
    "  --list-parameters DECK  the deck's parameters (name, default, unit, meaning); runs no model\n"
    "  --views RESULT.h5 ...   make the views of the field frames that the XDMF index beside each\n"
    "                          result file names, where the run left them out (model:output's views)\n"
    "  --macros                the macro reference (Markdown)\n"
    "  --version               version and git commit\n"
    "  -h, --help              this text\n"
    "\n"
    "Progress: when standard error is a terminal, one line rewritten in place at most four\n"
    "times a second: the model's time, steps, step cuts, wall time spent and, if the deck\n"
    "calls tirefe.progress{ end_time = T }, the wall time left. Nothing when it is not.\n"
    "\n"
    "Exit status: 0 success; 1 an error in the deck or the model (one line naming the deck\n"
    "file and line); 2 a usage error; 3 a self-check of the deck failed; 130 or 143 when\n"
    "SIGINT or SIGTERM stopped the run (after the step in progress, files closed).\n"
    "\n"
    "Documentation: README.md and docs/ (decks.md: decks and this command line; macros.md:\n"
    "every macro) in " TIREFE_SOURCE_DIR "\n";

struct CommandLine {
  std::string deck;
  std::map<std::string, std::string> overrides;
  std::string output_dir = "results";
  std::string restart;
  std::vector<std::string> read_folders, write_folders;
  size_t lua_memory_mib = kDefaultLuaMemoryMiB;
  bool quiet = false, verbose = false;
};

bool is_help(const std::string& argument) { return argument == "--help" || argument == "-h"; }

/// tirefe --list-parameters DECK (either order): the table, or a usage or deck error.
DeckOutcome list_parameters(int argc, char** argv) {
  const std::string first = argv[1], deck = argc == 3 ? argv[first == "--list-parameters" ? 2 : 1] : "";
  if (deck.empty() || deck.rfind("-", 0) == 0)
    return {2, std::string("tirefe: --list-parameters takes one deck and nothing else\n") + kUsage};
  try {
    std::cout << parameter_table(deck, declared_parameters(deck));
  } catch (const std::exception& error) {
    return {1, "tirefe: " + std::string(error.what()) + "\n"};
  }
  return {};
}

/// tirefe --views RESULT.h5 ...: the views each file lacks, or the first file's error.
DeckOutcome make_views(const std::vector<std::string>& files) {
  if (files.empty() ||
      std::any_of(files.begin(), files.end(), [](const std::string& f) { return f.rfind("-", 0) == 0; }))
    return {2, std::string("tirefe: --views takes one or more result files and nothing else\n") + kUsage};
  for (const std::string& file : files) {
    try {
      const size_t made = io::make_frame_views(file);
      std::cout << file << ": " << made << " views made\n";
    } catch (const std::exception& error) {
      return {1, "tirefe: " + std::string(error.what()) + "\n"};
    }
  }
  return {};
}

/// A --lua-memory value: a whole number of MiB from 1 to 1 TiB.
bool parse_mib(const std::string& text, size_t& mib) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 7) return false;
  mib = std::stoul(text);
  return mib >= 1 && mib <= (size_t{1} << 20);
}

/// Empty when the line is good, else what is wrong with it.
/// The options that take a value, and what it is (the usage's name for it).
const std::map<std::string, std::string> kValueOptions{{"--output-dir", "DIR"},
                                                       {"--restart", "CHECKPOINT"},
                                                       {"--allow-read", "DIR"},
                                                       {"--allow-write", "DIR"},
                                                       {"--lua-memory", "MIB"}};

std::string parse(int argc, char** argv, CommandLine& line) {
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (const auto option = kValueOptions.find(argument); option != kValueOptions.end()) {
      // Not the next option taken for a folder: "--output-dir --quiet" lacks its value.
      if (i + 1 >= argc || std::string(argv[i + 1]).rfind("--", 0) == 0)
        return "tirefe: option '" + argument + "' needs a value: " + argument + " " + option->second +
               (i + 1 < argc ? " (got the option '" + std::string(argv[i + 1]) + "')" : "") + "\n" + kUsage;
    }
    if (argument == "--output-dir" && i + 1 < argc) {
      line.output_dir = argv[++i];
    } else if (argument == "--restart" && i + 1 < argc) {
      line.restart = argv[++i];
    } else if (argument == "--allow-read" && i + 1 < argc) {
      line.read_folders.push_back(argv[++i]);
    } else if (argument == "--allow-write" && i + 1 < argc) {
      line.write_folders.push_back(argv[++i]);
    } else if (argument == "--lua-memory" && i + 1 < argc) {
      if (!parse_mib(argv[++i], line.lua_memory_mib))
        return "tirefe: --lua-memory takes a whole number of MiB from 1 to 1048576, got '" + std::string(argv[i]) +
               "'\n" + kUsage;
    } else if (argument == "--quiet") {
      line.quiet = true;
    } else if (argument == "--verbose") {
      line.verbose = true;
    } else if (argument.rfind("-", 0) == 0) {
      return "tirefe: unknown option '" + argument + "'\n" + kUsage;
    } else if (const auto equals = argument.find('='); equals != std::string::npos && equals > 0) {
      line.overrides[argument.substr(0, equals)] = argument.substr(equals + 1);
    } else if (line.deck.empty()) {
      line.deck = argument;
    } else {
      return "tirefe: more than one deck given ('" + line.deck + "', '" + argument + "')\n" + kUsage;
    }
  }
  return line.deck.empty() ? kUsage : "";
}

/// The deck's text; throws a std::runtime_error saying why a path is not a deck file to run.
std::string read_deck_text(const std::string& deck) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(deck, error);
  if (!std::filesystem::exists(status)) throw std::runtime_error("no deck file '" + deck + "'");
  if (std::filesystem::is_directory(status))
    throw std::runtime_error("'" + deck + "' is a folder; give a deck file in it (DECK.lua)");
  if (!std::filesystem::is_regular_file(status))  // a FIFO or a device would block or never end
    throw std::runtime_error("'" + deck + "' is not a regular file; give a deck file (DECK.lua)");
  std::ifstream in(deck, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the deck file '" + deck + "'");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

DeckOutcome run_deck_command(int argc, char** argv, const std::function<void(DeckSession&)>& configure) {
  const std::vector<std::string> arguments(argv + 1, argv + argc);
  if (std::any_of(arguments.begin(), arguments.end(), is_help)) {
    std::cout << kUsage << kHelp;
    return {};
  }
  if (std::count(arguments.begin(), arguments.end(), "--list-parameters")) return list_parameters(argc, argv);
  if (!arguments.empty() && arguments.front() == "--views") return make_views({arguments.begin() + 1, arguments.end()});
  if (argc == 2 && std::string(argv[1]) == "--macros") {
    std::cout << macro_reference();
    return {};
  }
  if (argc == 2 && std::string(argv[1]) == "--version") {
    std::cout << "tirefe " << kVersion << " (" << kGitCommit << ")\n";
    return {};
  }
  CommandLine line;
  if (std::string usage = parse(argc, argv, line); !usage.empty()) return {2, usage};

  DeckSession session;
  session.output_dir = line.output_dir;
  session.read_folders = line.read_folders;
  session.write_folders = line.write_folders;
  session.quiet = line.quiet;
  session.verbose = line.verbose && !line.quiet;
  if (!line.quiet && !line.verbose) session.progress.draw_on(ProgressLine::terminal(stderr));
  session.deck_path = line.deck;
  try {
    session.deck_text = read_deck_text(line.deck);  // kept in every output file
  } catch (const std::exception& error) {
    return {2, "tirefe: " + std::string(error.what()) + "\n"};
  }
  if (!line.restart.empty()) {
    try {
      session.restart = std::make_shared<Checkpoint>(read_checkpoint(line.restart));
    } catch (const std::exception& error) {
      return {1, "tirefe: " + line.deck + ": " + error.what() + "\n"};
    }
  }
  if (configure) configure(session);
  // Every outcome from here on names the files the run wrote.
  const auto ended = [&session](int status, std::string error) {
    DeckOutcome outcome{status, std::move(error), {}};
    for (const auto& file : session.output_purposes) outcome.files.push_back(file.first);
    return outcome;
  };
  // Erased before the run's last words (the error, the checks' summary).
  struct ClearProgress {
    ProgressLine& line;
    ~ClearProgress() { line.clear(); }
  } clear_progress{session.progress};
  std::string lua_dir;
  try {
    lua_dir = lua_module_dir();
  } catch (const std::exception& error) {
    return ended(1, "tirefe: " + std::string(error.what()) + "\n");
  }
  LuaSandbox sandbox(lua_dir);
  sandbox.set_memory_limit_mib(line.lua_memory_mib);
  const StopHandlers stop_handlers;
  try {
    install_macros(sandbox, session);
    sandbox.run_file(line.deck, line.overrides);
    if (session.restart)
      throw std::runtime_error("the deck ended before the time of the restart checkpoint '" + line.restart +
                               "' (t = " + std::to_string(session.restart->analysis.state.time) +
                               "): it is not the deck that wrote it");
  } catch (const DeckError& error) {
    std::string text = "tirefe: " + std::string(error.what()) + "\n";
    if (line.verbose && !sandbox.last_traceback().empty()) text += sandbox.last_traceback() + "\n";
    return ended(stop_signal().load() ? 128 + stop_signal().load() : 1, text);
  } catch (const std::exception& error) {
    return ended(1, "tirefe: " + line.deck + ": " + error.what() + "\n");
  }
  session.progress.clear();
  if (!session.checks.empty()) {
    const int failed = session.failed_checks();
    std::printf("%s: %d passed, %d failed\n", line.deck.c_str(), static_cast<int>(session.checks.size()) - failed,
                failed);
    if (failed > 0) return ended(3, "");
  }
  return ended(0, "");
}

}  // namespace tirefe::macros
