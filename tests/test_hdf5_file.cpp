// Tests for the HDF5 output layer (src/io/hdf5_file.*): round trips, extendible datasets,
// readability of flushed files by h5dump and by a reader after the writer was killed, errors,
// and a write that fails anywhere (a full disk) failing the whole file.
#include <catch2/catch.hpp>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>
#include <sys/resource.h>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

#include "io/hdf5_file.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using tirefe::io::Hdf5File;
using tirefe::io::IoError;

namespace {

// Unique file name in the temp folder, removed when the test ends.
class TempPath {
 public:
  TempPath() {
    static std::mt19937_64 random{std::random_device{}()};
    path_ = (fs::temp_directory_path() /
             ("tirefe_hdf5_" + std::to_string(getpid()) + "_" + std::to_string(random()) + ".h5"))
                .string();
  }
  ~TempPath() {
    std::error_code ignored;
    fs::remove(path_, ignored);
  }
  const std::string& str() const { return path_; }

 private:
  std::string path_;
};

// Appends the stdout of a shell command to `output`; true when the command succeeded.
bool run_capture(const std::string& command, std::string& output) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return false;
  char buffer[4096];
  size_t n = 0;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
  return pclose(pipe) == 0;
}

}  // namespace

TEST_CASE("Hdf5File round-trips attributes and fixed datasets", "[io][hdf5]") {
  TempPath temp;
  Eigen::MatrixXd matrix(3, 4);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) matrix(i, j) = 10.0 * i + j + 0.125;
  const std::vector<double> vector{1.5, -2.25, 1e-300, 6.02214076e23};
  const std::vector<long long> ints{0, -1, 9007199254740993LL, 42};
  const long long connectivity[2][3] = {{0, 1, 2}, {2, 3, 0}};
  const std::vector<std::string> names{"tread", "", "Schulter ü", std::string(300, 'x')};
  const std::string deck(100000, 'd');  // larger than an attribute's 64 KiB object-header limit

  {
    Hdf5File file = Hdf5File::create(temp.str());
    CHECK(file.path() == temp.str());
    file.write_attribute("/", "code", std::string("tirefe"));
    file.write_attribute("/", "code", std::string("tirefe ü"));  // overwrite
    file.write_attribute("/", "empty", std::string());
    file.write_attribute("/", "dt", 1e-4);
    file.write_attribute("/", "steps", 123456789012LL);
    file.write_attribute("/", "nodes", 7);            // int goes to the long long overload
    file.write_attribute("/run/info", "deck", deck);  // creates /run and /run/info
    file.write_matrix("/mesh/matrix", matrix);
    file.write_vector("/mesh/vector", vector);
    file.write_vector("/mesh/empty", {});
    file.write_int_vector("/mesh/ints", ints);
    file.write_int_matrix("/mesh/connectivity", 2, 3, &connectivity[0][0]);
    file.write_strings("/mesh/names", names);
    file.write_string_dataset("/run/deck", deck);
    file.write_attribute("/mesh/matrix", "unit", std::string("mm"));
  }

  const Hdf5File file = Hdf5File::open_read_only(temp.str());
  CHECK(file.read_string_attribute("/", "code") == "tirefe ü");
  CHECK(file.read_string_attribute("/", "empty").empty());
  CHECK(file.read_double_attribute("/", "dt") == 1e-4);
  CHECK(file.read_double_attribute("/", "steps") == 123456789012.0);
  CHECK(file.read_double_attribute("/", "nodes") == 7.0);
  CHECK(file.read_string_attribute("/run/info", "deck") == deck);
  CHECK(file.read_string_attribute("/mesh/matrix", "unit") == "mm");

  std::vector<hsize_t> shape;
  const std::vector<double> matrix_values = file.read_doubles("/mesh/matrix", &shape);
  CHECK(shape == std::vector<hsize_t>{3, 4});
  REQUIRE(matrix_values.size() == 12);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) CHECK(matrix_values[4 * i + j] == matrix(i, j));  // row-major

  CHECK(file.read_doubles("/mesh/vector", &shape) == vector);
  CHECK(shape == std::vector<hsize_t>{4});
  CHECK(file.read_doubles("/mesh/empty", &shape).empty());
  CHECK(shape == std::vector<hsize_t>{0});
  CHECK(file.read_ints("/mesh/ints", &shape) == ints);  // exact beyond 2^53
  CHECK(shape == std::vector<hsize_t>{4});
  CHECK(file.read_ints("/mesh/connectivity", &shape) == std::vector<long long>{0, 1, 2, 2, 3, 0});
  CHECK(shape == std::vector<hsize_t>{2, 3});
  CHECK(file.read_strings("/mesh/names") == names);
  CHECK(file.read_strings("/run/deck") == std::vector<std::string>{deck});

  CHECK(file.exists("/"));
  CHECK(file.exists("/mesh"));
  CHECK(file.exists("/mesh/names"));
  CHECK(file.exists("run/info"));
  CHECK_FALSE(file.exists("/mesh/missing"));
  CHECK_FALSE(file.exists("/nowhere/deeper/still"));
}

TEST_CASE("ExtendibleDataset appends scalar and shaped rows", "[io][hdf5]") {
  TempPath temp;
  constexpr int kRows = 1000;
  const auto scalar_value = [](int i) { return 0.001 * i - 3.0; };
  const auto field_value = [](int i, int k) { return i * 100.0 + k + 0.5; };
  {
    Hdf5File file = Hdf5File::create(temp.str());
    auto& time = file.create_extendible("/series/time", {}, "s");
    auto& field = file.create_extendible("/series/displacement", {4, 3}, "mm");
    CHECK(time.row_size() == 1);
    CHECK(field.row_size() == 12);
    CHECK(time.path() == "/series/time");
    CHECK_THROWS_AS(field.append(1.0), IoError);

    Hdf5File moved = std::move(file);  // references into the file must survive a move
    double row[12];
    for (int i = 0; i < kRows; ++i) {
      time.append(scalar_value(i));
      for (int k = 0; k < 12; ++k) row[k] = field_value(i, k);
      field.append(row);
    }
    CHECK(time.rows() == kRows);
    CHECK(field.rows() == kRows);
  }

  const Hdf5File file = Hdf5File::open_read_only(temp.str());
  CHECK(file.read_string_attribute("/series/time", "unit") == "s");
  CHECK(file.read_string_attribute("/series/displacement", "unit") == "mm");
  std::vector<hsize_t> shape;
  const std::vector<double> time = file.read_doubles("/series/time", &shape);
  CHECK(shape == std::vector<hsize_t>{kRows});
  REQUIRE(time.size() == kRows);
  int mismatches = 0;
  for (int i = 0; i < kRows; ++i) mismatches += time[i] != scalar_value(i);
  CHECK(mismatches == 0);

  const std::vector<double> field = file.read_doubles("/series/displacement", &shape);
  CHECK(shape == std::vector<hsize_t>{kRows, 4, 3});
  REQUIRE(field.size() == kRows * 12);
  for (int i = 0; i < kRows; ++i)
    for (int k = 0; k < 12; ++k) mismatches += field[12 * i + k] != field_value(i, k);
  CHECK(mismatches == 0);
}

TEST_CASE("A flushed file is readable by h5dump while still open for writing", "[io][hdf5]") {
  if (!fs::exists("/usr/bin/h5dump")) {
    WARN("h5dump not found; skipping");
    return;
  }
  TempPath temp;
  Hdf5File file = Hdf5File::create(temp.str());
  file.write_attribute("/", "code", std::string("tirefe"));
  auto& series = file.create_extendible("/series/force", {3});
  const double row[3] = {1.0, 2.0, 3.0};
  for (int i = 0; i < 10; ++i) series.append(row);
  file.flush();

  std::string output;
  CHECK(run_capture("/usr/bin/h5dump -H '" + temp.str() + "' 2>&1", output));
  INFO(output);
  CHECK(output.find("DATASET \"force\"") != std::string::npos);
  CHECK(output.find("( 10, 3 ) / ( H5S_UNLIMITED, 3 )") != std::string::npos);

  output.clear();  // and the data itself, not only the header
  CHECK(run_capture("/usr/bin/h5dump -d /series/force -s 9,0 -c 1,3 '" + temp.str() + "' 2>&1", output));
  CHECK(output.find("(9,0): 1, 2, 3") != std::string::npos);
}

TEST_CASE("A writer killed after flush leaves a readable file", "[io][hdf5]") {
  TempPath temp;
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {  // the writer; no Catch assertions here
    try {
      Hdf5File file = Hdf5File::create(temp.str());
      auto& series = file.create_extendible("/series/time", {});
      for (int i = 0; i < 500; ++i) series.append(static_cast<double>(i));
      file.flush();
      for (int i = 500; i < 600; ++i) series.append(static_cast<double>(i));  // unflushed
      raise(SIGKILL);
    } catch (...) {
    }
    _exit(1);
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGKILL);

  const Hdf5File file = Hdf5File::open_read_only(temp.str());
  const std::vector<double> time = file.read_doubles("/series/time");
  REQUIRE(time.size() >= 500);
  int mismatches = 0;
  for (int i = 0; i < 500; ++i) mismatches += time[i] != i;
  CHECK(mismatches == 0);
}

TEST_CASE("Hdf5File errors name the file and the object", "[io][hdf5]") {
  const std::string missing_folder = (fs::temp_directory_path() / "tirefe_no_such_folder_4711" / "out.h5").string();
  REQUIRE_FALSE(fs::exists(fs::path(missing_folder).parent_path()));
  // On one line, the system's reason last (not HDF5's description of its call).
  CHECK_THROWS_WITH(Hdf5File::create(missing_folder),
                    "cannot create output file '" + missing_folder + "': No such file or directory");
  CHECK_THROWS_WITH(Hdf5File::create_published(missing_folder), "cannot create output file '" + missing_folder +
                                                                    "' (written as '" + missing_folder +
                                                                    ".partial'): No such file or directory");
  CHECK_THROWS_WITH(Hdf5File::open_read_only(missing_folder), Catch::Contains(missing_folder));

  TempPath temp;
  Hdf5File file = Hdf5File::create(temp.str());
  file.write_vector("/a/b", {1.0});
  CHECK_THROWS_AS(file.read_doubles("/a/missing"), IoError);
  CHECK_THROWS_WITH(file.read_doubles("/a/missing"), Catch::Contains("'/a/missing'") && Catch::Contains(temp.str()));
  CHECK_THROWS_WITH(file.read_strings("/a/b"), Catch::Contains("'/a/b'") && Catch::Contains("not a string"));
  CHECK_THROWS_WITH(file.read_double_attribute("/a/b", "nope"), Catch::Contains("nope") && Catch::Contains("'/a/b'"));
  CHECK_THROWS_WITH(file.write_vector("/a/b", {2.0}), Catch::Contains("'/a/b'"));  // no silent overwrite
  CHECK_THROWS_AS(file.create_extendible("/a/zero", {0}), IoError);
}

TEST_CASE("a published file holds its last flush, whole, until the close renames it into place", "[io][hdf5]") {
  TempPath temp;
  const std::string working = temp.str() + ".partial";
  std::ofstream(working + ".copy") << tirefe::io::kHdf5Signature << "a killed run's unfinished copy";
  {
    Hdf5File file = Hdf5File::create_published(temp.str());
    CHECK_FALSE(fs::exists(working + ".copy"));  // removed: no result
    CHECK_FALSE(fs::exists(temp.str()));         // nothing flushed yet
    tirefe::io::ExtendibleDataset& time = file.create_extendible("/history/time", {});
    for (int row = 0; row < 10; ++row) time.append(row);
    file.flush();
    for (int row = 10; row < 25; ++row) time.append(row);
    // A reader (or a kill) now finds the ten flushed rows, not the fifteen in memory.
    CHECK(Hdf5File::open_read_only(temp.str()).read_doubles("/history/time").size() == 10);
    CHECK(fs::exists(working));
    file.close();
  }
  CHECK(Hdf5File::open_read_only(temp.str()).read_doubles("/history/time").size() == 25);
  CHECK_FALSE(fs::exists(working));
  CHECK_FALSE(fs::exists(working + ".copy"));
}

TEST_CASE("a file opened published changes only at its close; abandoned, it stays as it was", "[io][hdf5]") {
  TempPath temp;
  const std::string working = temp.str() + ".partial";
  Hdf5File::create(temp.str()).write_vector("/a", {1.0, 2.0});
  {
    Hdf5File file = Hdf5File::open_published(temp.str());
    file.write_vector("/b", {3.0});
    CHECK(fs::exists(working));
    CHECK_FALSE(Hdf5File::open_read_only(temp.str()).exists("/b"));  // a kill now leaves the file as it was
    file.abandon();
  }
  CHECK_FALSE(fs::exists(working));
  CHECK_FALSE(Hdf5File::open_read_only(temp.str()).exists("/b"));
  {
    Hdf5File file = Hdf5File::open_published(temp.str());
    CHECK(file.shape("/a") == std::vector<hsize_t>{2});
    CHECK(file.members("/") == std::vector<std::string>{"a"});
    file.write_vector("/b", {3.0});
    file.close();
  }
  CHECK(Hdf5File::open_read_only(temp.str()).read_doubles("/b") == std::vector<double>{3.0});
  CHECK(Hdf5File::open_read_only(temp.str()).members("/") == std::vector<std::string>{"a", "b"});
  CHECK_FALSE(fs::exists(working));
  // Not an HDF5 file: refused before anything is copied.
  std::ofstream(temp.str(), std::ios::trunc) << "not a result";
  CHECK_THROWS_WITH(Hdf5File::open_published(temp.str()),
                    Catch::Contains("cannot open file") && Catch::Contains(temp.str()));
  CHECK_FALSE(fs::exists(working));
}

TEST_CASE("a flush written by another thread: rows appended meanwhile wait for the next, in order", "[io][hdf5]") {
  TempPath temp;
  constexpr int kStaged = 200, kMeanwhile = 5000;
  {
    Hdf5File file = Hdf5File::create_published(temp.str());
    tirefe::io::ExtendibleDataset& time = file.create_extendible("/history/time", {});
    tirefe::io::ExtendibleDataset& field = file.create_compressed_extendible("/fields/u", {40, 3});
    std::vector<double> row(120);
    auto append = [&](int i) {
      time.append(i);
      for (size_t k = 0; k < row.size(); ++k) row[k] = 1000.0 * i + static_cast<double>(k);
      field.append(row.data());
    };
    for (int i = 0; i < kStaged; ++i) append(i);
    file.stage();
    std::thread writer([&] { file.flush_staged(); });
    for (int i = kStaged; i < kStaged + kMeanwhile; ++i) append(i);  // while the flush is written
    writer.join();
    CHECK(time.rows() == kStaged + kMeanwhile);
    CHECK(time.pending_bytes() == kMeanwhile * sizeof(double));
    // A reader (or a kill) finds the staged rows, exactly.
    const Hdf5File published = Hdf5File::open_read_only(temp.str());
    const std::vector<double> flushed = published.read_doubles("/history/time");
    REQUIRE(flushed.size() == kStaged);
    CHECK(flushed.back() == kStaged - 1);
    file.flush();
  }
  const Hdf5File file = Hdf5File::open_read_only(temp.str());
  const std::vector<double> time = file.read_doubles("/history/time");
  const std::vector<double> field = file.read_doubles("/fields/u");
  REQUIRE(time.size() == kStaged + kMeanwhile);
  REQUIRE(field.size() == 120 * time.size());
  int out_of_place = 0;
  for (size_t i = 0; i < time.size(); ++i) {
    out_of_place += time[i] != static_cast<double>(i);
    for (size_t k = 0; k < 120; ++k) out_of_place += field[120 * i + k] != 1000.0 * i + static_cast<double>(k);
  }
  CHECK(out_of_place == 0);
}

namespace {

using tirefe::testing::FileSizeLimit;

constexpr int kFrames = 300, kNodes = 50;

double field_value(int frame, int node, int column) { return 1000.0 * frame + 10.0 * node + column; }

// A result file in small: attributes, fixed datasets, a history, field rows and their views,
// flushed every fifth frame. Counts the frames each flush completed.
void write_frames(Hdf5File& file, int& flushed_frames) {
  file.write_attribute("/", "title", std::string("a run that fills its disk"));
  file.write_string_dataset("/deck", std::string(2000, 'x'));
  auto& time = file.create_extendible("/history/time", {}, "s");
  auto& field = file.create_compressed_extendible("/fields/displacement", {kNodes, 3}, "m, m, rad");
  std::vector<double> row(kNodes * 3);
  for (int frame = 0; frame < kFrames; ++frame) {
    for (int node = 0; node < kNodes; ++node)
      for (int column = 0; column < 3; ++column) row[3 * node + column] = field_value(frame, node, column);
    time.append(0.01 * frame);
    field.append(row.data());
    const std::string prefix = "/fields/frames/" + std::to_string(frame) + "/";
    file.write_row_view(prefix + "displacement", field, frame, 0, 2, 3);
    file.write_row_view(prefix + "rotation", field, frame, 2, 1, 0);
    file.write_row_view(prefix + "x", field, frame, 0, 1, 0);
    file.write_row_view(prefix + "y", field, frame, 1, 1, 0);
    file.write_attribute(prefix, "time", 0.01 * frame);
    if (frame % 10 == 0) file.write_vector("/modes/" + std::to_string(frame) + "/frequency", {1.0 * frame});
    if (frame % 100 == 99) {
      file.flush();
      flushed_frames = frame + 1;
    }
  }
  file.close();
}

// The action of an IoError "cannot <action> '<object>' ...".
std::string failed_call(const std::string& message) { return message.substr(0, message.find(" '")); }

}  // namespace

TEST_CASE("a write that fails in any HDF5 call fails the file: one message naming it, nothing written after",
          "[io][hdf5][reliability]") {
  TempPath temp;
  const std::string working = temp.str() + ".partial";
  int flushed_frames = 0;
  {
    Hdf5File file = Hdf5File::create_published(temp.str());
    write_frames(file, flushed_frames);
  }
  const auto whole = static_cast<rlim_t>(fs::file_size(temp.str()));
  std::set<std::string> failed_calls;
  constexpr int kLimits = 30;
  for (int step = 1; step < kLimits; ++step) {
    const rlim_t limit = whole * step / kLimits;
    INFO("files limited to " << limit << " of " << whole << " bytes");
    Hdf5File file = Hdf5File::create_published(temp.str());
    flushed_frames = 0;
    std::string error;
    {
      const FileSizeLimit limited(limit);
      try {
        write_frames(file, flushed_frames);
      } catch (const IoError& failure) {
        error = failure.what();
      }
      INFO(error);
      REQUIRE_FALSE(error.empty());
      failed_calls.insert(failed_call(error));
      CHECK_THAT(error, Catch::Contains(temp.str()) && Catch::EndsWith("File too large"));
      CHECK(error.find('\n') == std::string::npos);
      CHECK(file.failed());
      // Nothing more is written: each further write is refused, naming the file.
      const std::uintmax_t size = fs::exists(working) ? fs::file_size(working) : 0;
      const std::string refused = "an earlier write to '" + temp.str() + "' failed";
      CHECK_THROWS_WITH(file.write_attribute("/", "after", 1.0), Catch::EndsWith(refused));
      CHECK_THROWS_WITH(file.write_vector("/after", {1.0}), Catch::EndsWith(refused));
      CHECK_THROWS_WITH(file.create_extendible("/after_rows", {}), Catch::EndsWith(refused));
      CHECK_THROWS_WITH(file.flush(), Catch::EndsWith(refused));
      if (fs::exists(working)) CHECK(fs::file_size(working) == size);
      CHECK_NOTHROW(file.close());  // reported already: the file is dropped quietly
    }
    CHECK_FALSE(fs::exists(working));
    CHECK_FALSE(fs::exists(working + ".copy"));
    // The published file is the last flush, whole.
    if (flushed_frames == 0) continue;
    const Hdf5File published = Hdf5File::open_read_only(temp.str());
    CHECK(published.read_doubles("/history/time").size() == static_cast<size_t>(flushed_frames));
    const int frame = flushed_frames - 1;
    const std::vector<double> rotation =
        published.read_doubles("/fields/frames/" + std::to_string(frame) + "/rotation");
    REQUIRE(rotation.size() == kNodes);
    for (int node = 0; node < kNodes; ++node) CHECK(rotation[node] == field_value(frame, node, 2));
    CHECK(published.read_double_attribute("/fields/frames/" + std::to_string(frame), "time") == 0.01 * frame);
  }
  // The failures come in creates, writes and attributes, not only in flushes.
  INFO(Catch::Detail::stringify(failed_calls));
  CHECK(failed_calls.size() >= 3);
}
