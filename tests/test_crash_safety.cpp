// Crash safety, for real: a long dynamic run is killed with SIGKILL, or stopped with
// SIGTERM, while it writes; its result file must still read, with consistent rows. Runs
// killed at random instants, a full disk and an output folder that cannot be made.
// scripts/kill-test.sh runs the kill loop long (TIREFE_KILLS kills).
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "io/hdf5_file.hpp"
#include "deck/checkpoint.hpp"
#include "test_support.hpp"
#include "tirefe/test_paths.hpp"

namespace fs = std::filesystem;

namespace {

// A cantilever chain under a tip load, by Newmark, writing 'outputs' (Lua lines) until 'to'.
std::string chain_deck(const std::string& title, const std::string& outputs, const std::string& to) {
  return "local model = tirefe.model{ title = \"" + title + "\" }\n" + R"(local chain = {}
for i = 0, 20 do chain[#chain + 1] = model:node{ x = i / 20, y = 0 } end
model:section{ name = "s", EA = 1e4, GA = 1e4, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = chain }
model:fix{ node = chain[1] }
model:load{ node = chain[#chain], fy = -1, load_function = "constant" }
model:integrator{ type = "newmark" }
)" + outputs +
         "model:solve{ to = " + to + ", dt = 1e-4 }\n";
}

const std::string kLongDeck = chain_deck("a long run", R"(model:output{ file = "long.h5", fields_every = 100 }
model:history{ name = "tip_uy", node = chain[#chain], dof = "uy" }
)",
                                         "1e4");

/// Starts 'binary' with 'arguments' (output and error to 'log' if given); returns its pid.
pid_t start(const std::string& binary, std::vector<std::string> arguments, const fs::path& log = {}) {
  arguments.insert(arguments.begin(), binary);
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    if (!log.empty() && std::freopen(log.c_str(), "w", stderr) != nullptr) dup2(fileno(stderr), fileno(stdout));
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  return child;
}

int wait_for(pid_t child) {
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

/// Starts tirefe on the long deck, lets it run, sends 'signal', returns the exit status.
int run_and_signal(const fs::path& folder, int signal) {
  fs::create_directories(folder);
  const fs::path deck = folder / "long.lua";
  std::ofstream(deck) << kLongDeck;
  const pid_t child = start(TIREFE_BINARY, {deck.string(), "--quiet", "--output-dir", folder.string()});
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
  return wait_for(child);
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

namespace {

using tirefe::io::Hdf5File;
using tirefe::io::kHdf5Signature;

struct DatasetEntry {
  std::string path;
  bool extendible = false;  // chunked: rows appended as the run goes
  bool text = false;
  std::vector<hsize_t> dims;
};

/// Every dataset of 'file' (at any depth), by HDF5's own walk of the links.
std::vector<DatasetEntry> list_datasets(const fs::path& file) {
  std::vector<DatasetEntry> entries;
  const hid_t id = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) throw std::runtime_error("does not open");
  auto visit = [](hid_t group, const char* name, const H5L_info_t*, void* data) -> herr_t {
    const hid_t object = H5Oopen(group, name, H5P_DEFAULT);
    if (object < 0) return -1;
    if (H5Iget_type(object) == H5I_DATASET) {
      DatasetEntry entry;
      entry.path = std::string("/") + name;
      const hid_t plist = H5Dget_create_plist(object), type = H5Dget_type(object), space = H5Dget_space(object);
      entry.extendible = H5Pget_layout(plist) == H5D_CHUNKED;
      entry.text = H5Tget_class(type) == H5T_STRING;
      entry.dims.resize(static_cast<size_t>(std::max(0, H5Sget_simple_extent_ndims(space))));
      H5Sget_simple_extent_dims(space, entry.dims.data(), nullptr);
      H5Sclose(space);
      H5Tclose(type);
      H5Pclose(plist);
      static_cast<std::vector<DatasetEntry>*>(data)->push_back(std::move(entry));
    }
    H5Oclose(object);
    return 0;
  };
  const herr_t walked = H5Lvisit(id, H5_INDEX_NAME, H5_ITER_NATIVE, visit, &entries);
  H5Fclose(id);
  if (walked < 0) throw std::runtime_error("its objects cannot all be walked");
  return entries;
}

bool increasing(const std::vector<double>& values) {
  for (size_t i = 1; i < values.size(); ++i)
    if (!(values[i] > values[i - 1])) return false;
  return true;
}

/// What is wrong with a result file ("" for nothing): every dataset must read; the
/// appended datasets of a group with a 'time' have as many rows as it, and its times
/// increase; every history row has a positive step size (no row of zeros); a surface has
/// an outline per field frame; the XDMF index beside it is whole and names only datasets
/// the file holds.
std::string inconsistency(const fs::path& path) {
  try {
    const std::vector<DatasetEntry> datasets = list_datasets(path);
    const Hdf5File file = Hdf5File::open_read_only(path.string());
    std::map<std::string, hsize_t> group_rows;  // group -> rows of its time
    for (const DatasetEntry& dataset : datasets) {
      if (dataset.text) {
        file.read_strings(dataset.path);
        continue;
      }
      const std::vector<double> values = file.read_doubles(dataset.path);
      const fs::path name(dataset.path);
      if (!dataset.extendible || name.filename() != "time") continue;
      group_rows[name.parent_path().string()] = dataset.dims.front();
      if (!increasing(values)) return dataset.path + " does not increase";
    }
    for (const DatasetEntry& dataset : datasets) {
      const fs::path name(dataset.path);
      const auto group = group_rows.find(name.parent_path().string());
      if (dataset.extendible && group != group_rows.end() && dataset.dims.front() != group->second)
        return dataset.path + " has " + std::to_string(dataset.dims.front()) + " rows, " + group->first + "/time " +
               std::to_string(group->second);
      if (name.filename() == "outline" && dataset.dims.front() != group_rows["/fields"])
        return dataset.path + " has not one row per field frame";
    }
    if (group_rows.count("/history") != 0)
      for (const double step_size : file.read_doubles("/history/step_size"))
        if (!(step_size > 0.0)) return "/history has a row of step size " + std::to_string(step_size);
    fs::path index_path = path;
    index_path.replace_extension(".xmf");
    if (fs::exists(index_path)) {
      std::ifstream in(index_path);
      const std::string index((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (index.find("</Xdmf>") == std::string::npos) return index_path.string() + " is not whole";
      const std::regex named(path.filename().string() + ":(/[^<]*)<");
      std::set<std::string> paths;
      for (auto match = std::sregex_iterator(index.begin(), index.end(), named); match != std::sregex_iterator();
           ++match)
        paths.insert((*match)[1]);
      for (const std::string& named_path : paths)
        if (!file.exists(named_path)) return index_path.string() + " names " + named_path + " which the file lacks";
    }
  } catch (const std::exception& error) {
    return error.what();
  }
  return "";
}

int kills_to_try() {
  const char* text = std::getenv("TIREFE_KILLS");
  return text != nullptr ? std::max(1, std::atoi(text)) : 24;
}

/// Everything the run printed (it was started with this file as its log).
std::string text_of(const fs::path& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("runs killed at random instants leave whole, consistent result files and checkpoints",
          "[reliability][kill]") {
  // The restart deck: a ring in frictional contact with a moving road, fields every 25
  // steps, contact rows every 5, a checkpoint every 40; 300 to 3500 steps a second on a
  // loaded or an idle machine, so 50 000 steps outlast the longest delay before the kill.
  const char* binary_override = std::getenv("TIREFE_KILL_BINARY");  // another build, for comparisons
  const std::string binary = binary_override != nullptr ? binary_override : TIREFE_BINARY;
  const int kills = kills_to_try();
  tirefe::testing::TempDir folder;
  const fs::path result = folder.path("restart.h5"), checkpoint = folder.path("auto.ckpt.h5");
  const unsigned seed = std::random_device{}();
  INFO("random seed " << seed);
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> delay_ms(20, 1500);
  int with_file = 0;
  std::vector<std::string> failures;
  for (int kill_number = 0; kill_number < kills; ++kill_number) {
    // A killed run's leftovers stay (the next run must cope); its whole files go, so that
    // each check sees this run's.
    for (const fs::path& file : {result, fs::path(result).replace_extension(".xmf"), checkpoint}) fs::remove(file);
    const int delay = delay_ms(random);
    const pid_t child = start(binary, {std::string(TIREFE_TEST_DATA_DIR) + "/restart_deck.lua", "t_end=100", "--quiet",
                                       "--output-dir", folder.path()});
    std::this_thread::sleep_for(std::chrono::milliseconds(delay));
    kill(child, SIGKILL);
    const int status = wait_for(child);
    REQUIRE(WIFSIGNALED(status));
    std::string problem;
    if (fs::exists(result)) {
      ++with_file;
      problem = inconsistency(result);
    }
    if (problem.empty() && fs::exists(checkpoint)) {
      try {
        tirefe::macros::read_checkpoint(checkpoint.string());
      } catch (const std::exception& error) {
        problem = error.what();
      }
    }
    if (!problem.empty()) failures.push_back("kill after " + std::to_string(delay) + " ms: " + problem);
  }
  std::ostringstream report;
  report << kills << " kills, " << with_file << " with a result file, " << kills - failures.size()
         << " left every file whole and consistent";
  for (const std::string& failure : failures) report << "\n  " << failure;
  WARN(report.str());
  CHECK(with_file >= kills / 2);  // most kills hit a run that was writing
  CHECK(failures.empty());
}

namespace {

const std::string kShortDeck = chain_deck("a short run", R"(model:output{ file = "short.h5", fields_every = 10 }
model:checkpoint{ file = "short.ckpt.h5", every_steps = 20 }
)",
                                          "5e-3");

}  // namespace

TEST_CASE("the next run removes what a killed run left unfinished, and an unfinished checkpoint is refused",
          "[reliability]") {
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("short.lua", kShortDeck);
  const std::vector<std::string> leftovers{"short.h5.partial", "short.h5.partial.copy", "short.ckpt.h5.partial"};
  // Cut off anywhere: an HDF5 file's first bytes, or none.
  for (const std::string& leftover : leftovers)
    folder.write(leftover, leftover == "short.h5.partial.copy" ? "" : kHdf5Signature + std::string("unfinished"));
  const fs::path log = folder.path("log.txt");
  REQUIRE(wait_for(start(TIREFE_BINARY, {deck, "--quiet", "--output-dir", folder.path()}, log)) == 0);
  for (const std::string& leftover : leftovers) CHECK_FALSE(fs::exists(folder.path(leftover)));
  CHECK(inconsistency(folder.path("short.h5")).empty());
  CHECK(Hdf5File::open_read_only(folder.path("short.h5")).read_doubles("/history/time").size() == 50);

  folder.write("short.ckpt.h5.partial", "a killed run's unfinished checkpoint");
  const int status = wait_for(
      start(TIREFE_BINARY,
            {deck, "--quiet", "--output-dir", folder.path(), "--restart", folder.path("short.ckpt.h5.partial")}, log));
  CHECK(WEXITSTATUS(status) == 1);
  CHECK_THAT(text_of(log), Catch::Contains("is a checkpoint a run did not finish writing; restart from '" +
                                           folder.path("short.ckpt.h5") + "'"));

  // A file that no run of tirefe wrote is never deleted: the deck stops at the macro.
  folder.write("short.h5.partial", "my notes");
  CHECK(WEXITSTATUS(wait_for(start(TIREFE_BINARY, {deck, "--quiet", "--output-dir", folder.path()}, log))) == 1);
  CHECK_THAT(text_of(log), Catch::Contains("short.h5.partial' is in the way of the temporary file tirefe writes there: "
                                           "it is a file tirefe did not write; remove it"));
  CHECK(text_of(folder.path("short.h5.partial")) == "my notes");
}

TEST_CASE("a full disk stops the run with one line naming the file, which keeps its last flush", "[reliability]") {
  tirefe::testing::TempDir folder;
  const fs::path disk = folder.path("disk");
  fs::create_directories(disk);
  if (mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=4m") != 0) {
    WARN("skipped: a small file system cannot be mounted here (" << std::strerror(errno) << "; needs root)");
    return;
  }
  struct Unmount {
    std::string path;
    ~Unmount() { umount2(path.c_str(), MNT_DETACH); }
  } unmount{disk.string()};
  // Frequent frames: the XDMF index is rewritten near the full disk too.
  const std::string deck =
      folder.write("long.lua", tirefe::testing::replaced(kLongDeck, "fields_every = 100", "fields_every = 10"));
  const fs::path log = folder.path("log.txt");
  const pid_t child = start(TIREFE_BINARY, {deck, "--quiet", "--output-dir", disk.string()}, log);
  int status = 0;
  for (int waited = 0; waited < 600 && waitpid(child, &status, WNOHANG) == 0; ++waited)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  if (kill(child, 0) == 0) {  // still running after a minute: fail, but do not leave it behind
    kill(child, SIGKILL);
    status = wait_for(child);
    FAIL("the run went on with its disk full");
  }
  const std::string printed = text_of(log);
  INFO(printed);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 1);
  // Rows are flushed on wall time, so the disk may fill under the result file or under its
  // XDMF index, whichever is written first: either is named.
  CHECK_THAT(printed, (Catch::Contains((disk / "long.h5").string()) || Catch::Contains((disk / "long.xmf").string())) &&
                          Catch::Contains("No space left on device"));
  CHECK(std::count(printed.begin(), printed.end(), '\n') == 1);  // the message, on one line
  CHECK(inconsistency(disk / "long.h5").empty());
  CHECK(Hdf5File::open_read_only((disk / "long.h5").string()).read_doubles("/history/time").size() > 100);
  CHECK_FALSE(fs::exists(disk / "long.h5.partial"));
  CHECK_FALSE(fs::exists(disk / "long.h5.partial.copy"));
  const fs::path index = disk / "long.xmf";
  if (fs::exists(index)) CHECK(fs::file_size(index) > 0);
}

TEST_CASE("an output folder that cannot be made is named, with the reason", "[reliability]") {
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("short.lua", kShortDeck);
  const fs::path log = folder.path("log.txt");
  SECTION("a file in the way") {
    folder.write("taken", "a file, not a folder");
    const std::string output = folder.path("taken/results");
    CHECK(WEXITSTATUS(wait_for(start(TIREFE_BINARY, {deck, "--quiet", "--output-dir", output}, log))) == 1);
    CHECK_THAT(text_of(log), Catch::Contains("cannot create the output folder '" + folder.path("taken") + "' for '" +
                                             output + "/short.h5': a file of that name is in the way"));
  }
  SECTION("a read-only parent") {
    const fs::path locked = folder.path("locked");
    fs::create_directories(locked);
    // Root writes through permissions: a read-only file system stands in for them.
    const bool root = geteuid() == 0;
    if (root && mount("tmpfs", locked.c_str(), "tmpfs", MS_RDONLY, "size=16k") != 0) {
      WARN("skipped: a read-only file system cannot be mounted here (" << std::strerror(errno) << ")");
      return;
    }
    if (!root) fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    const int status =
        wait_for(start(TIREFE_BINARY, {deck, "--quiet", "--output-dir", (locked / "results").string()}, log));
    if (root) umount2(locked.c_str(), MNT_DETACH);
    fs::permissions(locked, fs::perms::owner_all);
    CHECK(WEXITSTATUS(status) == 1);
    CHECK_THAT(text_of(log), Catch::Contains("cannot create the output folder '" + (locked / "results").string() +
                                             "' for '" + (locked / "results" / "short.h5").string() +
                                             "': " + (root ? "Read-only file system" : "Permission denied")));
  }
}
