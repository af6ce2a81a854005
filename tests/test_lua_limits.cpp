// The limits that keep a deck (untrusted Lua) from hanging or exhausting the machine:
// the stop flag checked from Lua code, the bound on Lua memory, and the step budget of
// the step driver (docs/decks.md, Limits; docs/reliability.md).
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <thread>

#include "core/model.hpp"
#include "elements/beam_mesh.hpp"
#include "deck/lua_sandbox.hpp"
#include "solvers/analysis.hpp"
#include "test_support.hpp"
#include "tirefe/test_paths.hpp"

using namespace tirefe;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using tirefe::testing::TempDir;

namespace {

/// The exit status of a child, or -1 if it has not ended within 'limit' (it is then killed).
int wait_for(pid_t child, std::chrono::milliseconds limit) {
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  while (waitpid(child, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() - start > limit) {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("SIGTERM stops a deck looping in pure Lua, with its line and status 143", "[reliability][limits]") {
  TempDir dir;
  const std::string deck =
      GENERATE(as<std::string>{}, "local n = 0\nwhile true do\n  n = n + 1\nend\n",
               // catching the stop does not keep it going
               "while true do\n  pcall(function() while true do end end)\nend\n",
               // nor catching it in a coroutine, whose close returns it as a value
               "local co = coroutine.create(function()\n"
               "  local x <close> = setmetatable({}, { __close = function() while true do end end })\n"
               "  coroutine.yield()\nend)\ncoroutine.resume(co)\ncoroutine.close(co)\n");
  INFO(deck);
  const std::string path = dir.write("loop.lua", deck);
  const std::string errors = dir.path("errors.txt");
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    const int fd = open(errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDERR_FILENO);
    execl(TIREFE_BINARY, TIREFE_BINARY, path.c_str(), "--quiet", "--output-dir", dir.path("out").c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  kill(child, SIGTERM);
  const auto sent = std::chrono::steady_clock::now();
  // The hook looks at the stop flag every 10 000 Lua instructions (microseconds); 5 s
  // leaves room for a loaded machine, a hang never ends.
  const int status = wait_for(child, std::chrono::seconds(5));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  const std::string message = read_text(errors);
  INFO(message);
  CHECK(status == 128 + SIGTERM);
  CHECK(seconds < 5.0);
  CHECK_THAT(message,
             StartsWith("tirefe: " + path + ":") && Contains("stopped by SIGTERM while the deck ran Lua code"));
}

TEST_CASE("Lua memory beyond the bound is a deck error at its line, and the sandbox stays usable", "[lua][limits]") {
  TempDir dir;
  macros::LuaSandbox sandbox("");
  CHECK(sandbox.memory_limit_mib() == macros::kDefaultLuaMemoryMiB);
  CHECK(macros::kDefaultLuaMemoryMiB == 1024);
  sandbox.set_memory_limit_mib(16);
  SECTION("one allocation beyond it") {
    const std::string deck = dir.write("big.lua", "local a = 1\nlocal s = string.rep('x', 17 * 2^20)\n");
    CHECK_THROWS_WITH(sandbox.run_file(deck), deck +
                                                  ":2: the deck used more than 16 MiB of Lua memory (the limit; "
                                                  "--lua-memory MIB sets another)");
  }
  SECTION("a table growing into it") {
    const std::string deck = dir.write("grow.lua", "local rows = {}\nfor i = 1, 1e9 do\n  rows[i] = { i }\nend\n");
    CHECK_THROWS_WITH(sandbox.run_file(deck), StartsWith(deck + ":3: the deck used more than 16 MiB"));
  }
  SECTION("a deck may catch it with pcall and go on within the bound") {
    const std::string deck =
        dir.write("caught.lua",
                  "local ok, message = pcall(string.rep, 'x', 2^25)\nassert(not ok)\nsmall = string.rep('y', 2^20)\n");
    sandbox.run_file(deck);
    lua_getglobal(sandbox.state(), "small");
    CHECK(lua_rawlen(sandbox.state(), -1) == (1u << 20));
    lua_pop(sandbox.state(), 1);
  }
  // After the failure the same state runs a deck within the bound.
  const std::string fine = dir.write("fine.lua", "fine = #string.rep('z', 2^22)\n");
  sandbox.run_file(fine);
  lua_getglobal(sandbox.state(), "fine");
  CHECK(lua_tointeger(sandbox.state(), -1) == (1 << 22));
  lua_pop(sandbox.state(), 1);
}

TEST_CASE("the step budget stops an advance whose steps converge only far below dt", "[solver][limits]") {
  // A cantilever loaded through a load function that fails any step longer than 1 ms
  // (a stand-in for a model that converges only in small steps): every 10 ms step is cut
  // to 0.625 ms, grows back, fails, and is cut again: 16 steps per nominal step.
  Model model;
  BeamSection section;
  section.axial_stiffness = 1e6;
  section.shear_stiffness = 1e6;
  section.bending_stiffness = 10.0;
  const std::vector<int> nodes = add_beam_line(model, "beam", {0.0, 0.0}, {1.0, 0.0}, 4, section);
  model.fix(nodes.front(), kUx);
  model.fix(nodes.front(), kUy);
  model.fix(nodes.front(), kRz);
  Analysis analysis(model);
  const int refusing = model.add_load_function(LoadFunction([&analysis](double time) {
    // A NaN load fails the step's Newton solve, which is then cut.
    return time - analysis.state().time > 1e-3 * (1.0 + 1e-9) ? std::numeric_limits<double>::quiet_NaN() : time;
  }));
  model.add_nodal_load(nodes.back(), kUy, -1.0, refusing);
  analysis.set_time_step(0.01);

  SECTION("a budget of 10 steps per nominal step runs out") {
    analysis.step_control().step_budget = 10;
    try {
      analysis.advance(0.1);
      FAIL("the budget did not stop the advance");
    } catch (const StepFailure& failure) {
      const std::string message = failure.what();
      INFO(message);
      CHECK_THAT(message, StartsWith("the step budget ran out at t = 0.06875: 110 steps where dt = 0.01 asks for 10 "
                                     "(the last dt = 0.000625)"));
      CHECK_THAT(message, Contains("model:step_control{ step_budget = 10 }"));
    }
    // 10 x (10 + 1) steps of 0.625 ms were taken and kept.
    CHECK(analysis.accepted_steps() == 110);
    CHECK(analysis.state().time == Approx(0.06875).epsilon(1e-12));
  }
  SECTION("the default budget lets it finish") {
    CHECK(analysis.step_control().step_budget == 100);
    const auto& records = analysis.advance(0.1);
    CHECK(records.size() == 160);
    CHECK(analysis.state().time == Approx(0.1).epsilon(1e-12));
  }
  SECTION("no budget") {
    analysis.step_control().step_budget = 0;
    analysis.advance(0.1);
    CHECK(analysis.accepted_steps() == 160);
  }
}
