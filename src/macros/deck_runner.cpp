#include "macros/deck_runner.hpp"

#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>

#include "io/checkpoint.hpp"
#include "macros/interrupt.hpp"
#include "macros/lua_module_dir.hpp"
#include "macros/lua_sandbox.hpp"
#include "macros/macro_table.hpp"
#include "tirefe/version.hpp"

namespace tirefe::macros {

namespace {

constexpr const char* kUsage =
    "usage: tirefe DECK.lua [key=value ...] [--output-dir DIR] [--restart CHECKPOINT] [--quiet] [--verbose]\n"
    "       tirefe --macros | --version\n";

struct CommandLine {
  std::string deck;
  std::map<std::string, std::string> overrides;
  std::string output_dir = "results";
  std::string restart;
  bool quiet = false, verbose = false;
};

/// Empty when the line is good, else what is wrong with it.
std::string parse(int argc, char** argv, CommandLine& line) {
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--output-dir" && i + 1 < argc) {
      line.output_dir = argv[++i];
    } else if (argument == "--restart" && i + 1 < argc) {
      line.restart = argv[++i];
    } else if (argument == "--quiet") {
      line.quiet = true;
    } else if (argument == "--verbose") {
      line.verbose = true;
    } else if (argument.rfind("--", 0) == 0) {
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

}  // namespace

DeckOutcome run_deck_command(int argc, char** argv, const std::function<void(DeckSession&)>& configure) {
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
  session.quiet = line.quiet;
  session.deck_path = line.deck;
  {
    std::ifstream deck(line.deck, std::ios::binary);  // kept in every output file
    session.deck_text.assign(std::istreambuf_iterator<char>(deck), std::istreambuf_iterator<char>());
  }
  if (!line.restart.empty()) {
    try {
      session.restart = std::make_shared<io::Checkpoint>(io::read_checkpoint(line.restart));
    } catch (const std::exception& error) {
      return {1, "tirefe: " + line.deck + ": " + error.what() + "\n"};
    }
  }
  if (configure) configure(session);
  std::string lua_dir;
  try {
    lua_dir = lua_module_dir();
  } catch (const std::exception& error) {
    return {1, "tirefe: " + std::string(error.what()) + "\n"};
  }
  LuaSandbox sandbox(lua_dir);
  install_stop_handlers();
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
    return {stop_signal().load() ? 128 + stop_signal().load() : 1, text};
  } catch (const std::exception& error) {
    return {1, "tirefe: " + line.deck + ": " + error.what() + "\n"};
  }
  if (!session.checks.empty()) {
    const int failed = session.failed_checks();
    std::printf("%s: %d passed, %d failed\n", line.deck.c_str(), static_cast<int>(session.checks.size()) - failed,
                failed);
    if (failed > 0) return {3, ""};
  }
  return {};
}

}  // namespace tirefe::macros
