// The result file's own cost in a run like inputs/drum_cleat.lua, without the model: 10 956
// steps of 20 history channels, 6 contact rows of 100 nodes every 20 steps, and a field frame
// every 9 steps (1 218 frames: displacement, velocity, deformation of 201 nodes, a drum
// outline of 139 points; uncompressed, the contact rows compressed, as io::ResultFile writes
// them), flushed every 1 370 steps as a run of some 2 s flushes every quarter second, and
// the XDMF views of the frames made 16 at a time, and their XDMF index (the deck's grids:
// the mesh, the rim, two node sets, the drum). Prints the CPU milliseconds of the rows, of
// the views, of the flushes, of the close and of the index, and the file's size.
// Timed alone, HDF5's code and data stay in the processor's caches: in a run, between the
// model's steps, the same calls cost up to twice as much. Usage: bench_result_file [FOLDER]
#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"
#include "io/xdmf.hpp"

using namespace tirefe::io;

namespace {

// Process CPU time: what the file costs the run, whatever else the machine runs.
struct Clock {
  using duration = std::chrono::nanoseconds;
  using time_point = std::chrono::time_point<Clock, duration>;
  static time_point now() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return time_point(duration(now.tv_sec * 1000000000LL + now.tv_nsec));
  }
};

double milliseconds(Clock::duration duration) { return std::chrono::duration<double, std::milli>(duration).count(); }

}  // namespace

int main(int argc, char** argv) {
  const std::string folder = argc > 1 ? argv[1] : std::filesystem::temp_directory_path().string();
  std::filesystem::create_directories(folder);  // a folder that is not there yet is made
  const std::string path = folder + "/bench_result_file.h5";
  constexpr int kSteps = 10956, kChannels = 20, kNodes = 201, kOutline = 139, kContactNodes = 100;
  constexpr int kFieldEvery = 9, kContactEvery = 20, kFlushEvery = 1370;
  constexpr size_t kViewBatch = 16;
  Clock::duration rows{}, views{}, flushes{}, closing{}, indexing{};
  XdmfIndex index("bench_result_file.h5");
  {
    // The deck's grids: attributes of every node, on the mesh and on point grids.
    auto node_grid = [&](const std::string& name, const std::string& topology, long long cells, int per_cell,
                         const XdmfData& connectivity) {
      XdmfGrid grid{name, topology, cells, per_cell, connectivity, {"/mesh/coordinates", {kNodes, 2}}, {}};
      for (const char* field : {"displacement", "velocity", "deformation"})
        grid.attributes.push_back(
            {field, "Vector", "Node", {std::string("/fields/frames/{frame}/") + field, {kNodes, 3}}});
      grid.attributes.push_back({"rotation", "Scalar", "Node", {"/fields/frames/{frame}/rotation", {kNodes}}});
      return grid;
    };
    XdmfGrid mesh = node_grid("mesh", "Mixed", 300, 0, {"/mesh/cells", {1200}, true});
    mesh.attributes.push_back({"block", "Scalar", "Cell", {"/mesh/cell_block", {300}, true}});
    index.add_grid(mesh);
    index.add_grid(node_grid("tire_rim", "Polyvertex", 1, 1, {"/mesh/blocks/tire_rim", {1, 1}, true}));
    for (const char* set : {"tire_contact", "tire_tread"})
      index.add_grid(node_grid(set, "Polyvertex", 100, 1, {std::string("/mesh/node_sets/") + set, {100}, true}));
    index.add_grid({"drum",
                    "Polyline",
                    kOutline - 1,
                    2,
                    {"/surfaces/drum/segments", {kOutline - 1, 2}, true},
                    {"/surfaces/drum/frames/{frame}", {kOutline, 2}},
                    {}});
  }
  size_t frames = 0;
  {
    auto start = Clock::now();
    Hdf5File file = Hdf5File::create_published(path);
    std::vector<ExtendibleDataset*> channels, contact;
    for (int c = 0; c < kChannels; ++c)
      channels.push_back(&file.create_extendible("/history/channel_" + std::to_string(c), {}, "N"));
    for (const char* name : {"gap", "normal_force", "tangential_force", "state", "coordinate", "sliding_velocity"})
      contact.push_back(&file.create_compressed_extendible(std::string("/contact/drum/") + name, {kContactNodes}));
    ExtendibleDataset& contact_time = file.create_extendible("/contact/drum/time", {}, "s");
    ExtendibleDataset& time = file.create_extendible("/fields/time", {}, "s");
    ExtendibleDataset& step = file.create_extendible("/fields/step", {});
    ExtendibleDataset& displacement = file.create_extendible("/fields/displacement", {kNodes, 3});
    ExtendibleDataset& velocity = file.create_extendible("/fields/velocity", {kNodes, 3});
    ExtendibleDataset& deformation = file.create_extendible("/fields/deformation", {kNodes, 3});
    ExtendibleDataset& outline = file.create_extendible("/surfaces/drum/outline", {kOutline, 2}, "m");
    std::vector<double> field(kNodes * 3), points(kOutline * 2), nodes(kContactNodes);
    size_t viewed = 0;
    rows += Clock::now() - start;
    for (int s = 1; s <= kSteps; ++s) {
      start = Clock::now();
      const double t = 1e-3 * s;
      for (int c = 0; c < kChannels; ++c) channels[c]->append(std::sin(t * (c + 1)));
      if (s % kContactEvery == 0) {
        for (int n = 0; n < kContactNodes; ++n) nodes[n] = std::cos(t + 0.01 * n);
        for (ExtendibleDataset* rows_of : contact) rows_of->append(nodes.data());
        contact_time.append(t);
      }
      if (s % kFieldEvery == 0) {
        // Smooth fields of a rolling tire: values that vary from node to node and frame to frame.
        for (int i = 0; i < kNodes * 3; ++i) field[i] = 0.1 * std::sin(0.031 * i + 7.0 * t) + 1e-4 * std::cos(i * t);
        time.append(t);
        step.append(static_cast<double>(s));
        displacement.append(field.data());
        velocity.append(field.data());
        deformation.append(field.data());
        for (int i = 0; i < kOutline; ++i) {
          points[2 * i] = 0.86 * std::cos(0.045 * i + t);
          points[2 * i + 1] = 0.86 * std::sin(0.045 * i + t);
        }
        outline.append(points.data());
        ++frames;
        rows += Clock::now() - start;
        start = Clock::now();
        index.add_frame(t);
        indexing += Clock::now() - start;
        start = Clock::now();
      }
      rows += Clock::now() - start;
      // The views of the frames waiting for them, 16 at a time between the flushes and the
      // rest at a flush, as io::ResultFile's writer makes them.
      const bool flush = s % kFlushEvery == 0 || s == kSteps;
      if (frames - viewed >= kViewBatch || (flush && viewed < frames)) {
        start = Clock::now();
        for (; viewed < frames; ++viewed) {
          const std::string prefix = "/fields/frames/" + std::to_string(viewed) + "/";
          file.write_row_view(prefix + "displacement", displacement, viewed, 0, 2, 3);
          file.write_row_view(prefix + "velocity", velocity, viewed, 0, 2, 3);
          file.write_row_view(prefix + "rotation", displacement, viewed, 2, 1, 0);
          file.write_row_view(prefix + "deformation", deformation, viewed, 0, 2, 3);
          file.write_row_view("/surfaces/drum/frames/" + std::to_string(viewed), outline, viewed, 0, 2, 2);
        }
        views += Clock::now() - start;
      }
      if (flush) {
        start = Clock::now();
        file.flush();
        flushes += Clock::now() - start;
      }
    }
    start = Clock::now();
    file.close();
    closing += Clock::now() - start;
    start = Clock::now();
    index.write(folder + "/bench_result_file.xmf");
    indexing += Clock::now() - start;
  }
  const double total = milliseconds(rows + views + flushes + closing + indexing);
  std::printf(
      "rows %.1f ms, views %.1f ms (%.0f us each), flushes %.1f ms, close %.1f ms, index %.1f ms: %.1f ms in all; "
      "%.1f MB\n",
      milliseconds(rows), milliseconds(views), 1e3 * milliseconds(views) / (5.0 * frames), milliseconds(flushes),
      milliseconds(closing), milliseconds(indexing), total, std::filesystem::file_size(path) / 1e6);
  std::filesystem::remove(path);
  std::filesystem::remove(folder + "/bench_result_file.xmf");
  return 0;
}
