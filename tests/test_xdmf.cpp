// Tests of the XDMF index written beside result files with field frames: its text
// (io/xdmf.hpp), and what the result file puts in it and in the HDF5 file at each frame
// (the per-frame views, the deformation field, surfaces). tests/test_xdmf_readers.py
// reads the index back with meshio.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "elements/point_mass.hpp"
#include "elements/tread_beam.hpp"
#include "io/result_file.hpp"
#include "io/xdmf.hpp"
#include "solvers/analysis.hpp"
#include "test_support.hpp"

using tirefe::io::Hdf5File;
using tirefe::io::XdmfGrid;
using tirefe::io::XdmfIndex;

namespace {

int count(const std::string& text, const std::string& pattern) {
  const std::regex expression(pattern);
  return static_cast<int>(
      std::distance(std::sregex_iterator(text.begin(), text.end(), expression), std::sregex_iterator()));
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

XdmfGrid points_grid(const std::string& name) {
  // clang-format off
  return {name, "Polyvertex", 2, 1, {"/mesh/node_sets/" + name, {2}, true}, {"/mesh/coordinates", {5, 2}},
          {{"displacement", "Vector", "Node", {"/fields/frames/{frame}/displacement", {5, 3}}}}};
  // clang-format on
}

}  // namespace

TEST_CASE("XDMF index: a temporal collection per grid, whole datasets per frame, the first grid last", "[io][xdmf]") {
  XdmfIndex index("run&co.h5");
  XdmfGrid mesh{"mesh", "Mixed", 3, 0, {"/mesh/cells", {11}, true}, {"/mesh/coordinates", {5, 2}}, {}};
  mesh.attributes = {{"displacement", "Vector", "Node", {"/fields/frames/{frame}/displacement", {5, 3}}},
                     {"rotation", "Scalar", "Node", {"/fields/frames/{frame}/rotation", {5}}},
                     {"block", "Scalar", "Cell", {"/mesh/cell_block", {3}, true}}};
  index.add_grid(mesh);
  index.add_grid(points_grid("contact"));
  for (double time : {0.0, 0.005, 0.01}) index.add_frame(time);
  index.add_grid(points_grid("late"));  // added after three frames: shown in them too
  const std::string text = index.text();

  CHECK(count(text, "<Xdmf Version=\"3.0\">") == 1);
  CHECK(count(text, "GridType=\"Collection\" CollectionType=\"Temporal\"") == 3);
  CHECK(count(text, "GridType=\"Uniform\"") == 9);
  // The mesh, added first, is the last collection (the one meshio reads).
  CHECK(text.find("<Grid Name=\"contact\" GridType=\"Collection\"") <
        text.find("<Grid Name=\"late\" GridType=\"Collection\""));
  CHECK(text.find("<Grid Name=\"late\" GridType=\"Collection\"") <
        text.find("<Grid Name=\"mesh\" GridType=\"Collection\""));
  // Times read back exactly, in their shortest form.
  CHECK(count(text, "<Time Value=\"0.005\" />") == 3);
  CHECK(count(text, "<Time Value=") == 9);
  CHECK(count(text, "TopologyType=\"Mixed\" NumberOfElements=\"3\">") == 3);
  CHECK(count(text, "TopologyType=\"Polyvertex\" NumberOfElements=\"2\" NodesPerElement=\"1\">") == 6);
  // Every frame names its own whole dataset; the file name is escaped.
  CHECK(
      count(
          text,
          "Dimensions=\"5 3\" DataType=\"Float\" Precision=\"8\" Format=\"HDF\">run&amp;co.h5:/fields/frames/2/displacement<") ==
      3);
  CHECK(
      count(
          text,
          "Dimensions=\"5\" DataType=\"Float\" Precision=\"8\" Format=\"HDF\">run&amp;co.h5:/fields/frames/1/rotation<") ==
      1);
  CHECK(count(text, "<Attribute Name=\"block\" AttributeType=\"Scalar\" Center=\"Cell\">") == 3);
  CHECK(count(text, "DataType=\"Int\" Precision=\"8\" Format=\"HDF\">run&amp;co.h5:/mesh/cells<") == 3);
  CHECK(count(text, "\\{frame\\}") == 0);
  CHECK(count(text, "HyperSlab|Function") == 0);  // what ParaView 5.11's Xdmf3 readers fail on
  // size(): the frames' text exactly, all but the header and the collections' own lines.
  size_t frame_bytes = text.size() -
                       std::string("<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n").size() -
                       std::string("  </Domain>\n</Xdmf>\n").size();
  for (const char* name : {"mesh", "contact", "late"})
    frame_bytes -= ("    <Grid Name=\"" + std::string(name) +
                    "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n    </Grid>\n")
                       .size();
  CHECK(index.size() == frame_bytes);
}

TEST_CASE("XDMF index: written whole beside its name, then renamed, a failure is an IoError", "[io][xdmf]") {
  tirefe::testing::TempDir folder;
  XdmfIndex index("run.h5");
  index.add_grid(points_grid("contact"));
  index.add_frame(0.25);
  const std::string path = folder.path("run.xmf");
  std::ofstream(path) << "an older index";
  index.write(path);
  CHECK(read_text(path) == index.text());
  CHECK(!std::filesystem::exists(path + ".partial"));
  CHECK_THROWS_AS(index.write(folder.path("missing/run.xmf")), tirefe::io::IoError);
}

namespace {

using namespace tirefe;

/// A ring of beams around a spindle node, the rim a point on the spindle: node 0 is the spindle.
struct Ring {
  Model model;
  std::vector<int> ring;
  explicit Ring(int nodes = 6) {
    const int spindle = model.mesh().add_node(Eigen::Vector2d(0.1, 0.4));
    for (int i = 0; i < nodes; ++i) {
      const double angle = 2.0 * 3.14159265358979 * i / nodes;
      ring.push_back(
          model.mesh().add_node(Eigen::Vector2d(0.1, 0.4) + 0.3 * Eigen::Vector2d(std::cos(angle), std::sin(angle))));
    }
    model.mesh().add_node(Eigen::Vector2d(2.0, 0.0));  // a node of no tire
    model.mesh().define_node_set("ring", ring);
    BeamSection section;
    section.axial_stiffness = section.shear_stiffness = 1e5;
    section.bending_stiffness = 10;
    section.mass_per_length = 1;
    auto& beams = model.add_block<TreadBeam>("beams");
    for (int i = 0; i < nodes; ++i) {
      const int a = ring[i], b = ring[(i + 1) % nodes];
      beams.add({a, b}, TreadBeam(model.mesh().position(a), model.mesh().position(b), section));
    }
    auto& rim = model.add_block<NodalSpringMass>("rim");
    SpringMassProperties properties;
    properties.mass = 1.0;
    rim.add({spindle}, NodalSpringMass(properties));
  }
};

}  // namespace

TEST_CASE("result file: the deformation takes the rim's rigid motion out, in the fixed axes", "[io][xdmf]") {
  // A rigid turn by 2 rad about the spindle and a travel of the spindle, plus a known
  // deformation of one ring node: the deformation field must give back just that.
  tirefe::testing::TempDir folder;
  Ring ring;
  Analysis analysis(ring.model);
  const Eigen::Vector2d travel(0.05, -0.02), bulge(0.003, -0.001);
  const double spin = 2.0, twist = 0.01;
  {
    io::ResultFile file(folder.path("ring.h5"), io::RunMetadata{"ring", "", "", {}});
    file.add_rim(0, ring.ring);
    State& state = analysis.mutable_state();
    state.displacement = state.velocity = Eigen::VectorXd::Zero(kDofsPerNode * ring.model.mesh().node_count());
    const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(spin).toRotationMatrix();
    const Eigen::Vector2d spindle = ring.model.mesh().position(0);
    for (int node = 0; node < ring.model.mesh().node_count(); ++node) {
      const Eigen::Vector2d x = ring.model.mesh().position(node);
      const bool on_tire = node <= 6;
      const Eigen::Vector2d moved = on_tire ? Eigen::Vector2d(spindle + travel + rotation * (x - spindle)) : x;
      state.displacement.segment<2>(dof_index(node, kUx)) = moved - x;
      state.displacement[dof_index(node, kRz)] = on_tire ? spin : 0.0;
    }
    state.displacement.segment<2>(dof_index(3, kUx)) += bulge;
    state.displacement[dof_index(3, kRz)] += twist;
    state.displacement.segment<2>(dof_index(7, kUx)) = Eigen::Vector2d(0.5, 0.25);  // no tire's node
    file.write_fields(analysis.model(), analysis.state(), 1);
  }
  const Hdf5File file = Hdf5File::open_read_only(folder.path("ring.h5"));
  std::vector<hsize_t> shape;
  const std::vector<double> e = file.read_doubles("/fields/deformation", &shape);
  REQUIRE(shape == std::vector<hsize_t>{1, 8, 3});
  for (int node = 0; node <= 6; ++node) {
    INFO("node " << node);
    const bool bulged = node == 3;
    CHECK(e[3 * node] == Approx(bulged ? bulge.x() : 0.0).margin(1e-15));
    CHECK(e[3 * node + 1] == Approx(bulged ? bulge.y() : 0.0).margin(1e-15));
    CHECK(e[3 * node + 2] == Approx(bulged ? twist : 0.0).margin(1e-15));
  }
  CHECK(e[21] == 0.5);  // nodes of no tire keep their displacement
  CHECK(e[22] == 0.25);
  // The frame's views: (e_x, e_y, 0) and the rotation of every node.
  const std::vector<double> view = file.read_doubles("/fields/frames/0/deformation", &shape);
  REQUIRE(shape == std::vector<hsize_t>{8, 3});
  CHECK(view[9] == e[9]);
  CHECK(view[10] == e[10]);
  CHECK(view[11] == 0.0);
  const std::vector<double> rotation = file.read_doubles("/fields/frames/0/rotation", &shape);
  REQUIRE(shape == std::vector<hsize_t>{8});
  CHECK(rotation[3] == spin + twist);
}

TEST_CASE("result file: the index after every flush, a surface drawn in every frame, points as their own grids",
          "[io][xdmf]") {
  tirefe::testing::TempDir folder;
  Ring ring;
  Analysis analysis(ring.model);
  analysis.mutable_state().displacement = analysis.mutable_state().velocity =
      Eigen::VectorXd::Zero(kDofsPerNode * ring.model.mesh().node_count());
  const std::string index_path = folder.path("ring.xmf");
  // A square turning about the origin by 0.1 rad per second, drawn from the second frame on.
  const std::vector<Eigen::Vector2d> square{{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  auto turned = [&](double time, const Eigen::Vector2d&, double) {
    std::vector<Eigen::Vector2d> points;
    for (const Eigen::Vector2d& corner : square) points.push_back(Eigen::Rotation2Dd(0.1 * time) * corner);
    return points;
  };
  {
    io::ResultFile file(folder.path("ring.h5"), io::RunMetadata{"ring", "", "", {}});
    file.add_rim(0, ring.ring);
    file.show_node_set("ring");
    for (int frame = 0; frame < 3; ++frame) {
      analysis.mutable_state().time = 0.5 * frame;
      file.write_fields(analysis.model(), analysis.state(), frame);
      if (frame == 0) file.add_surface("square", true, turned);
      // Frames this close together (a flush's own time apart) wait for the next flush.
      file.flush();
      // On disk after each flush, while the run goes on.
      const std::string text = read_text(index_path);
      CHECK(count(text, "<Grid Name=\"mesh\" GridType=\"Uniform\">") == frame + 1);
      CHECK(count(text, "<Grid Name=\"square\" GridType=\"Uniform\">") == frame + 1);
      CHECK(count(text, "</Xdmf>") == 1);
    }
  }
  const std::string text = read_text(index_path);
  // Beams in the mixed topology; the rim (one node) and the shown node set as points.
  CHECK(count(text, "TopologyType=\"Mixed\" NumberOfElements=\"6\"") == 3);
  CHECK(count(text, "<Grid Name=\"rim\" GridType=\"Uniform\">") == 3);
  CHECK(count(text, "<Grid Name=\"ring\" GridType=\"Uniform\">") == 3);
  CHECK(count(text, "TopologyType=\"Polyline\" NumberOfElements=\"4\" NodesPerElement=\"2\"") == 3);
  const Hdf5File file = Hdf5File::open_read_only(folder.path("ring.h5"));
  CHECK(file.read_ints("/mesh/cells") ==
        std::vector<long long>{2, 2, 1, 2, 2, 2, 2, 3, 2, 2, 3, 4, 2, 2, 4, 5, 2, 2, 5, 6, 2, 2, 6, 1});
  CHECK(file.read_ints("/mesh/cell_block") == std::vector<long long>(6, 0));
  CHECK(file.read_ints("/surfaces/square/segments") == std::vector<long long>{0, 1, 1, 2, 2, 3, 3, 0});
  // The frame written before the surface existed shows it where it was then.
  std::vector<hsize_t> shape;
  const std::vector<double> outline = file.read_doubles("/surfaces/square/outline", &shape);
  REQUIRE(shape == std::vector<hsize_t>{3, 4, 2});
  for (int frame = 0; frame < 3; ++frame) {
    const Eigen::Vector2d first = Eigen::Rotation2Dd(0.05 * frame) * square[0];
    CHECK(outline[8 * frame] == Approx(first.x()).epsilon(1e-15));
    CHECK(outline[8 * frame + 1] == Approx(first.y()).epsilon(1e-15));
    CHECK(file.read_doubles("/surfaces/square/frames/" + std::to_string(frame)) ==
          std::vector<double>(outline.begin() + 8 * frame, outline.begin() + 8 * frame + 8));
  }
}

TEST_CASE("result file: the views of frames written between flushes are made at the flush and at the close",
          "[io][xdmf]") {
  tirefe::testing::TempDir folder;
  Ring ring;
  Analysis analysis(ring.model);
  const int dofs = kDofsPerNode * ring.model.mesh().node_count();
  const std::vector<Eigen::Vector2d> square{{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  auto moved = [&](double time, const Eigen::Vector2d&, double) {
    std::vector<Eigen::Vector2d> points;
    for (const Eigen::Vector2d& corner : square) points.push_back(corner + Eigen::Vector2d(time, 0.0));
    return points;
  };
  constexpr int kFrames = 6;
  {
    io::ResultFile file(folder.path("ring.h5"), io::RunMetadata{"ring", "", "", {}});
    for (int frame = 0; frame < kFrames; ++frame) {
      analysis.mutable_state().time = 0.5 * frame;
      analysis.mutable_state().displacement = Eigen::VectorXd::LinSpaced(dofs, frame, frame + 1.0);
      analysis.mutable_state().velocity = -analysis.state().displacement;
      file.write_fields(analysis.model(), analysis.state(), frame);
      if (frame == 1) file.flush();
      // Added with frames 0 and 1 flushed and frame 2 waiting for the flush.
      if (frame == 2) file.add_surface("square", true, moved);
    }
    // Frames 3 to 5 wait for the close.
  }
  const Hdf5File file = Hdf5File::open_read_only(folder.path("ring.h5"));
  const std::vector<double> displacement = file.read_doubles("/fields/displacement");
  const std::vector<double> velocity = file.read_doubles("/fields/velocity");
  const std::vector<double> outline = file.read_doubles("/surfaces/square/outline");
  REQUIRE(displacement.size() == static_cast<size_t>(kFrames * dofs));
  REQUIRE(outline.size() == static_cast<size_t>(kFrames * 8));
  for (int frame = 0; frame < kFrames; ++frame) {
    const std::string group = "/fields/frames/" + std::to_string(frame) + "/";
    std::vector<double> expected_displacement, expected_velocity, expected_rotation;
    for (int node = 0; node < dofs / kDofsPerNode; ++node) {
      const int row = frame * dofs + node * kDofsPerNode;
      expected_displacement.insert(expected_displacement.end(), {displacement[row], displacement[row + 1], 0.0});
      expected_velocity.insert(expected_velocity.end(), {velocity[row], velocity[row + 1], 0.0});
      expected_rotation.push_back(displacement[row + 2]);
    }
    CHECK(file.read_doubles(group + "displacement") == expected_displacement);
    CHECK(file.read_doubles(group + "velocity") == expected_velocity);
    CHECK(file.read_doubles(group + "rotation") == expected_rotation);
    CHECK(file.read_doubles("/surfaces/square/frames/" + std::to_string(frame)) ==
          std::vector<double>(outline.begin() + 8 * frame, outline.begin() + 8 * frame + 8));
    CHECK(outline[8 * frame] == 1.0 + 0.5 * frame);
  }
  const std::string text = read_text(folder.path("ring.xmf"));
  CHECK(count(text, "<Grid Name=\"square\" GridType=\"Uniform\">") == kFrames);
  CHECK(count(text, "<Grid Name=\"mesh\" GridType=\"Uniform\">") == kFrames);
  CHECK(count(text, "ring.h5:/fields/frames/5/displacement<") > 0);
}

// A ring model whose state changes with each frame: frame k sets every displacement and
// velocity to k at time k ms, and writes the frame.
struct RingFrames {
  explicit RingFrames(int nodes = 6) : ring(nodes) {}
  tirefe::testing::TempDir folder;
  Ring ring;
  Analysis analysis{ring.model};
  const int dofs = kDofsPerNode * ring.model.mesh().node_count();
  void write(io::ResultFile& file, int frame) {
    analysis.mutable_state().time = 0.001 * frame;
    analysis.mutable_state().displacement = analysis.mutable_state().velocity = Eigen::VectorXd::Constant(dofs, frame);
    file.write_fields(analysis.model(), analysis.state(), frame);
  }
};

TEST_CASE("result file: flushes written while the run goes on hold every frame, its views and the index",
          "[io][xdmf]") {
  RingFrames run;
  // Some 400 bytes a frame: the waiting rows reach kFlushBytes every ~650 frames.
  constexpr int kFrames = 3000;
  const std::string path = run.folder.path("ring.h5");
  {
    io::ResultFile file(path, io::RunMetadata{"ring", "", "", {}});
    for (int frame = 0; frame < kFrames; ++frame) {
      run.write(file, frame);
      if (frame == kFrames / 2) {
        file.file();  // waits for a flush being written: the file on disk then holds its frames
        const Hdf5File on_disk = Hdf5File::open_read_only(path);
        const size_t flushed = on_disk.read_doubles("/fields/time").size();
        CHECK(flushed >= io::ResultFile::kFlushBytes / (8 * (2 * run.dofs + 2)));
        CHECK(flushed <= static_cast<size_t>(frame + 1));
        // Views written ahead of the flushes: every flushed frame has its own, whole.
        const std::string last = std::to_string(flushed - 1);
        CHECK(on_disk.read_doubles("/fields/frames/" + last + "/rotation") ==
              std::vector<double>(run.dofs / kDofsPerNode, static_cast<double>(flushed - 1)));
      }
    }
  }
  const Hdf5File file = Hdf5File::open_read_only(path);
  const std::vector<double> time = file.read_doubles("/fields/time");
  REQUIRE(time.size() == kFrames);
  int wrong = 0;
  for (int frame = 0; frame < kFrames; frame += 7) {
    wrong += time[frame] != 0.001 * frame;
    const std::vector<double> rotation = file.read_doubles("/fields/frames/" + std::to_string(frame) + "/rotation");
    wrong += rotation != std::vector<double>(run.dofs / kDofsPerNode, frame);
  }
  CHECK(wrong == 0);
  const std::string text = read_text(run.folder.path("ring.xmf"));
  CHECK(count(text, "<Grid Name=\"mesh\" GridType=\"Uniform\">") == kFrames);
  CHECK(count(text, "ring.h5:/fields/frames/" + std::to_string(kFrames - 1) + "/displacement<") > 0);
}

TEST_CASE("result file: rows wait in memory for a batch at most, however large the file grows", "[io][xdmf]") {
  // 2 000 nodes: a frame's rows are 48 kB; the 200 frames, 9.6 MB. Flushes come when the
  // rows since the last reach half of the file (or a quarter second has passed): without
  // the batches between them, the rows waiting would grow to megabytes.
  RingFrames run(2000);
  constexpr int kFrames = 200;
  const std::string path = run.folder.path("ring.h5");
  size_t most_waiting = 0;
  {
    io::ResultFile file(path, io::RunMetadata{"ring", "", "", {}});
    for (int frame = 0; frame < kFrames; ++frame) {
      run.write(file, frame);
      size_t waiting = 0;
      for (const io::ExtendibleDataset& dataset : file.file().extendible_datasets()) waiting += dataset.pending_bytes();
      most_waiting = std::max(most_waiting, waiting);
    }
  }
  const size_t frame_bytes = sizeof(double) * (2 * run.dofs + 2);
  CHECK(most_waiting >= io::ResultFile::kRowBatchBytes - frame_bytes);
  CHECK(most_waiting < io::ResultFile::kRowBatchBytes);
  const Hdf5File file = Hdf5File::open_read_only(path);
  const std::vector<double> time = file.read_doubles("/fields/time");
  REQUIRE(time.size() == kFrames);
  CHECK(time.back() == 0.001 * (kFrames - 1));
  CHECK(file.read_doubles("/fields/frames/" + std::to_string(kFrames - 1) + "/rotation") ==
        std::vector<double>(run.dofs / kDofsPerNode, kFrames - 1));
}

TEST_CASE("result file: frames wait for their views a few hundred at most, so that a stopped run closes at once",
          "[io][xdmf][reliability]") {
  // Frames come far faster than the writer makes their views (a few per frame, each some
  // 0.1 ms): without the bound they pile up while a flush is written, and the close of a
  // run stopped by SIGINT, which writes them all, takes as long as the run took to make them.
  RingFrames run;
  constexpr int kFrames = 4000;
  size_t most_waiting = 0;
  io::ResultFile file(run.folder.path("ring.h5"), io::RunMetadata{"ring", "", "", {}});
  for (int frame = 0; frame < kFrames; ++frame) {
    run.write(file, frame);
    most_waiting = std::max(most_waiting, file.frames_awaiting_views());
  }
  CHECK(most_waiting >= io::ResultFile::kViewBatch);
  CHECK(most_waiting < io::ResultFile::kMaxUnviewedFrames);
}

TEST_CASE("result file: a flush that fails while the run goes on fails the next step, naming the file",
          "[io][xdmf][reliability]") {
  RingFrames run;
  const std::string path = run.folder.path("ring.h5");
  std::string error;
  int frames = 0;
  {
    io::ResultFile file(path, io::RunMetadata{"ring", "", "", {}});
    const tirefe::testing::FileSizeLimit limited(2 << 20);
    // The run goes on while the flush that fails is written: the failure comes at a later step.
    const auto start = std::chrono::steady_clock::now();
    try {
      for (; std::chrono::steady_clock::now() - start < std::chrono::seconds(60); ++frames) run.write(file, frames);
    } catch (const io::IoError& failure) {
      error = failure.what();
    }
    CHECK(file.file().failed());
  }
  INFO(error);
  CHECK_FALSE(error.empty());
  // The disk fills under the file or under its XDMF index, whichever is written first.
  CHECK_THAT(error, (Catch::Contains(path) || Catch::Contains(run.folder.path("ring.xmf"))) &&
                        Catch::EndsWith("File too large"));
  // The file on disk is the last flush, whole.
  const size_t flushed = Hdf5File::open_read_only(path).read_doubles("/fields/time").size();
  INFO(flushed << " of " << frames << " frames flushed");
  CHECK(flushed > 0);
  CHECK(flushed < static_cast<size_t>(frames));
}
