// Crash safety, for real: a long dynamic run is killed with SIGKILL, or stopped with
// SIGTERM, while it writes; its result file must still read, with consistent rows.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "io/hdf5_file.hpp"
#include "tirefe/test_paths.hpp"

namespace fs = std::filesystem;

namespace {

const char* kLongDeck = R"(
local model = tirefe.model{ title = "a long run" }
local chain = {}
for i = 0, 20 do chain[#chain + 1] = model:node{ x = i / 20, y = 0 } end
model:section{ name = "s", EA = 1e4, GA = 1e4, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = chain }
model:fix{ node = chain[1] }
model:load{ node = chain[#chain], fy = -1, load_function = "constant" }
model:integrator{ type = "newmark" }
model:output{ file = "long.h5", fields_every = 100 }
model:history{ name = "tip_uy", node = chain[#chain], dof = "uy" }
model:solve{ to = 1e4, dt = 1e-4 }
)";

/// Starts tirefe on the long deck, lets it run, sends 'signal', returns the exit status.
int run_and_signal(const fs::path& folder, int signal) {
  fs::create_directories(folder);
  const fs::path deck = folder / "long.lua";
  std::ofstream(deck) << kLongDeck;
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    execl(TIREFE_BINARY, TIREFE_BINARY, deck.c_str(), "--quiet", "--output-dir", folder.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  // Signal once the run has been going for 1.2 s and its file has had a few flushes (a
  // loaded machine starts it late); give up waiting after 20 s.
  const fs::path file = folder / "long.h5";
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const auto waited = std::chrono::steady_clock::now() - start;
    std::error_code missing;
    const bool written = fs::exists(file, missing) && fs::file_size(file, missing) > 40000;
    if ((written && waited > std::chrono::milliseconds(1200)) || waited > std::chrono::seconds(20)) break;
  }
  kill(child, signal);
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

/// Every history channel and field is readable, finite, and time increases.
size_t check_readable(const fs::path& file) {
  auto output = tirefe::io::Hdf5File::open_read_only(file.string());
  const std::vector<double> time = output.read_doubles("/history/time");
  const std::vector<double> tip = output.read_doubles("/history/tip_uy");
  const size_t rows = std::min(time.size(), tip.size());
  REQUIRE(rows > 10);
  size_t bad_rows = 0;
  for (size_t i = 0; i < rows; ++i)
    if (!std::isfinite(tip[i]) || (i > 0 && !(time[i] > time[i - 1]))) ++bad_rows;
  CHECK(bad_rows == 0);
  CHECK(output.read_string_attribute("/", "title") == "a long run");
  CHECK(std::system(("h5dump -H " + file.string() + " > /dev/null 2>&1").c_str()) == 0);
  return rows;
}

}  // namespace

TEST_CASE("a run killed with SIGKILL leaves a readable result file up to its last flush", "[reliability]") {
  const fs::path folder = fs::temp_directory_path() / "tirefe_sigkill";
  fs::remove_all(folder);
  const int status = run_and_signal(folder, SIGKILL);
  CHECK(WIFSIGNALED(status));
  const size_t rows = check_readable(folder / "long.h5");
  WARN("SIGKILL after at least 1.2 s left " << rows << " readable steps");
  fs::remove_all(folder);
}

TEST_CASE("SIGTERM stops a run after the current step, with every step in the file", "[reliability]") {
  const fs::path folder = fs::temp_directory_path() / "tirefe_sigterm";
  fs::remove_all(folder);
  const int status = run_and_signal(folder, SIGTERM);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 128 + SIGTERM);
  auto output = tirefe::io::Hdf5File::open_read_only((folder / "long.h5").string());
  const size_t time_rows = output.read_doubles("/history/time").size();
  CHECK(output.read_doubles("/history/tip_uy").size() == time_rows);
  CHECK(output.read_doubles("/history/newton_iterations").size() == time_rows);
  check_readable(folder / "long.h5");
  fs::remove_all(folder);
}
