// The temporary files written beside result files, indexes and checkpoints (FILE.partial,
// FILE.partial.copy): never written through a symbolic link, and what is in their place
// is removed only if tirefe could have left it there (docs/security.md).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "io/hdf5_file.hpp"
#include "io/xdmf.hpp"
#include "deck/checkpoint.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using tirefe::io::Hdf5File;
using tirefe::testing::TempDir;

namespace {

std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <class Write>
std::string refusal(Write&& write) {
  try {
    write();
  } catch (const tirefe::io::IoError& error) {
    return error.what();
  }
  return "(accepted)";
}

/// The smallest index there is: one grid, one frame.
tirefe::io::XdmfIndex small_index() {
  tirefe::io::XdmfIndex index("run.h5");
  tirefe::io::XdmfGrid grid;
  grid.name = "mesh";
  grid.topology = "Polyvertex";
  grid.cells = 1;
  grid.nodes_per_cell = 1;
  grid.connectivity = {"/mesh/cells", {1, 1}, true};
  grid.geometry = {"/mesh/coordinates", {1, 2}};
  index.add_grid(grid);
  index.add_frame(0.0);
  return index;
}

}  // namespace

TEST_CASE("a symbolic link in the place of a temporary file is never written through", "[io][files]") {
  TempDir dir;
  const std::string victim = dir.write("elsewhere/victim.txt", "kept\n");
  const std::string temporary =
      GENERATE(as<std::string>{}, "run.h5.partial", "run.h5.partial.copy", "run.xmf.partial", "ck.h5.partial");
  INFO(temporary);
  fs::create_symlink(victim, dir.path(temporary));
  std::string message;
  if (temporary == "run.xmf.partial") {
    message = refusal([&] { small_index().write(dir.path("run.xmf")); });
  } else if (temporary == "ck.h5.partial") {
    message = refusal([&] { tirefe::macros::write_checkpoint(dir.path("ck.h5"), tirefe::macros::Checkpoint{}); });
  } else {
    message = refusal([&] { Hdf5File::create_published(dir.path("run.h5")).flush(); });
  }
  CHECK_THAT(message, Contains("'" + dir.path(temporary) +
                               "' is in the way of the temporary file tirefe writes there: "
                               "it is a symbolic link, which tirefe never writes through; "
                               "remove it"));
  CHECK(text_of(victim) == "kept\n");
  CHECK(fs::is_symlink(dir.path(temporary)));
}

TEST_CASE("a file in the place of a temporary is removed only if a killed run of tirefe left it", "[io][files]") {
  TempDir dir;
  SECTION("a user's file is kept, and the write refused") {
    dir.write("ck.h5.partial", "my notes\n");
    CHECK_THAT(refusal([&] { tirefe::macros::remove_unfinished_checkpoint(dir.path("ck.h5")); }),
               Contains("ck.h5.partial' is in the way of the temporary file tirefe writes there: it is a file tirefe "
                        "did not write; remove it"));
    CHECK_THAT(refusal([&] { tirefe::macros::write_checkpoint(dir.path("ck.h5"), tirefe::macros::Checkpoint{}); }),
               Contains("it is a file tirefe did not write"));
    dir.write("run.h5.partial", "my notes\n");
    CHECK_THAT(refusal([&] { Hdf5File::create_published(dir.path("run.h5")); }),
               Contains("it is a file tirefe did not write"));
    dir.write("run.xmf.partial", "my notes\n");
    CHECK_THAT(refusal([&] { small_index().write(dir.path("run.xmf")); }),
               Contains("it is a file tirefe did not write"));
    for (const char* kept : {"ck.h5.partial", "run.h5.partial", "run.xmf.partial"})
      CHECK(text_of(dir.path(kept)) == "my notes\n");
  }
  SECTION("what a killed run left (its own kind of file, or an empty one) is replaced") {
    Hdf5File::create(dir.path("run.h5.partial")).close();
    dir.write("run.h5.partial.copy", "");
    dir.write("run.xmf.partial", "<?xml version=\"1.0\"?>\n<Xdmf");
    Hdf5File file = Hdf5File::create_published(dir.path("run.h5"));
    file.write_attribute("/", "title", std::string("new"));
    file.close();
    CHECK(Hdf5File::open_read_only(dir.path("run.h5")).read_string_attribute("/", "title") == "new");
    CHECK_FALSE(fs::exists(dir.path("run.h5.partial.copy")));
    small_index().write(dir.path("run.xmf"));
    CHECK_THAT(text_of(dir.path("run.xmf")), Contains("/mesh/coordinates"));
    CHECK_FALSE(fs::exists(dir.path("run.xmf.partial")));
  }
}
