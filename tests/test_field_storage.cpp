// Tests of how result files store field rows (src/io/hdf5_file.*): compressed extendible
// datasets (shuffle + deflate, one flushed row never rewritten) and the virtual row views
// that give XDMF readers one whole dataset per frame without copying it.
#include <catch2/catch.hpp>

#include <hdf5.h>

#include <cmath>
#include <vector>

#include "io/hdf5_file.hpp"
#include "test_support.hpp"

using tirefe::io::Hdf5File;
using tirefe::io::IoError;

namespace {

/// The filters of a dataset, in order, and its chunk shape and bytes on disk.
struct Storage {
  std::vector<H5Z_filter_t> filters;
  std::vector<hsize_t> chunk;
  H5D_layout_t layout;
  hsize_t bytes;
};

Storage storage_of(const std::string& file_path, const std::string& dataset_path) {
  Storage storage;
  const hid_t file = H5Fopen(file_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dataset = H5Dopen2(file, dataset_path.c_str(), H5P_DEFAULT);
  const hid_t plist = H5Dget_create_plist(dataset);
  storage.layout = H5Pget_layout(plist);
  for (int i = 0; i < H5Pget_nfilters(plist); ++i) {
    unsigned flags = 0;
    size_t values = 0;
    storage.filters.push_back(H5Pget_filter2(plist, i, &flags, &values, nullptr, 0, nullptr, nullptr));
  }
  if (storage.layout == H5D_CHUNKED) {
    storage.chunk.resize(8);
    storage.chunk.resize(H5Pget_chunk(plist, 8, storage.chunk.data()));
  }
  storage.bytes = H5Dget_storage_size(dataset);
  H5Pclose(plist);
  H5Dclose(dataset);
  H5Fclose(file);
  return storage;
}

}  // namespace

TEST_CASE("field rows: compressed with shuffle and deflate, one row per chunk, read back exactly", "[io][hdf5]") {
  tirefe::testing::TempDir folder;
  const std::string path = folder.path("fields.h5");
  constexpr int kRows = 200, kNodes = 201;
  // Values with few significant bits (as 2D fields with a zero column are): compressible.
  auto value = [](int row, int entry) { return 0.25 * row - 0.5 * (entry % 7) + (entry % 3 == 2 ? 0.0 : 1.0); };
  {
    Hdf5File file = Hdf5File::create(path);
    auto& field = file.create_compressed_extendible("/fields/displacement", {kNodes, 3}, "m, m, rad");
    auto& history = file.create_extendible("/history/time", {}, "s");
    std::vector<double> row(kNodes * 3);
    for (int r = 0; r < kRows; ++r) {
      for (int k = 0; k < kNodes * 3; ++k) row[k] = value(r, k);
      field.append(row.data());
      history.append(0.1 * r);
      if (r % 10 == 0) file.flush();  // rows arrive a frame at a time
    }
  }
  {
    const Hdf5File file = Hdf5File::open_read_only(path);
    std::vector<hsize_t> shape;
    const std::vector<double> values = file.read_doubles("/fields/displacement", &shape);
    REQUIRE(shape == std::vector<hsize_t>{kRows, kNodes, 3});
    int mismatches = 0;
    for (int r = 0; r < kRows; ++r)
      for (int k = 0; k < kNodes * 3; ++k) mismatches += values[r * kNodes * 3 + k] != value(r, k);
    CHECK(mismatches == 0);
    CHECK(file.read_string_attribute("/fields/displacement", "unit") == "m, m, rad");
  }

  const Storage field = storage_of(path, "/fields/displacement");
  CHECK(field.filters == std::vector<H5Z_filter_t>{H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE});
  CHECK(field.chunk == std::vector<hsize_t>{1, kNodes, 3});  // a row of 4.8 KiB: one per chunk
  CHECK(field.bytes < kRows * kNodes * 3 * sizeof(double) / 10);
  // History rows stay as they were: uncompressed.
  CHECK(storage_of(path, "/history/time").filters.empty());
}

TEST_CASE("field rows: small rows are compressed some 4 KiB to a chunk", "[io][hdf5]") {
  tirefe::testing::TempDir folder;
  const std::string path = folder.path("contact.h5");
  {
    Hdf5File file = Hdf5File::create(path);
    auto& rows = file.create_compressed_extendible("/contact/drum/state", {100});
    const std::vector<double> row(100, 1.0);
    rows.append(row.data());
  }
  CHECK(storage_of(path, "/contact/drum/state").chunk == std::vector<hsize_t>{5, 100});
}

TEST_CASE("row views: one row's columns as a whole dataset, zero padded, without a copy", "[io][hdf5]") {
  tirefe::testing::TempDir folder;
  const std::string path = folder.path("views.h5");
  constexpr int kNodes = 4;
  auto value = [](int row, int node, int column) { return 100.0 * row + 10.0 * node + column + 0.5; };
  {
    Hdf5File file = Hdf5File::create(path);
    auto& field = file.create_compressed_extendible("/fields/displacement", {kNodes, 3});
    std::vector<double> row(kNodes * 3);
    for (int r = 0; r < 3; ++r) {
      for (int n = 0; n < kNodes; ++n)
        for (int c = 0; c < 3; ++c) row[3 * n + c] = value(r, n, c);
      field.append(row.data());
      // Made before the row leaves memory; the view shows it once the file holds it.
      file.write_row_view("/fields/frames/" + std::to_string(r) + "/displacement", field, r, 0, 2, 3);
      file.write_row_view("/fields/frames/" + std::to_string(r) + "/rotation", field, r, 2, 1, 0);
    }
    CHECK_THROWS_AS(file.write_row_view("/bad", field, 0, 2, 2, 3), IoError);  // columns 2 and 3 of 3
    CHECK_THROWS_AS(file.write_row_view("/bad", field, 0, 0, 2, 1), IoError);  // wider than the view
    CHECK_THROWS_AS(file.write_row_view("/bad", field, 0, 0, 2, 0), IoError);  // two columns as values
    CHECK_THROWS_AS(file.write_row_view("/bad", field, 0, 0, 0, 3), IoError);  // no column
  }
  {
    const Hdf5File file = Hdf5File::open_read_only(path);
    std::vector<hsize_t> shape;
    const std::vector<double> vector = file.read_doubles("/fields/frames/1/displacement", &shape);
    CHECK(shape == std::vector<hsize_t>{kNodes, 3});
    CHECK(vector == std::vector<double>{value(1, 0, 0), value(1, 0, 1), 0.0, value(1, 1, 0), value(1, 1, 1), 0.0,
                                        value(1, 2, 0), value(1, 2, 1), 0.0, value(1, 3, 0), value(1, 3, 1), 0.0});
    const std::vector<double> scalar = file.read_doubles("/fields/frames/2/rotation", &shape);
    CHECK(shape == std::vector<hsize_t>{kNodes});
    CHECK(scalar == std::vector<double>{value(2, 0, 2), value(2, 1, 2), value(2, 2, 2), value(2, 3, 2)});
  }
  const Storage view = storage_of(path, "/fields/frames/1/displacement");
  CHECK(view.layout == H5D_VIRTUAL);
  CHECK(view.bytes == 0);
}
