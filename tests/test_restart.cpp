// Checkpoint and restart, for real: tests/restart_deck.lua (a ring on a road moving under
// it, with friction, HHT-alpha) runs uninterrupted, then again from its checkpoints: one
// written between two solves, one written automatically in the middle of a solve. Every
// row of the restarted result files and the final state must equal the uninterrupted
// run's bit for bit.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "elements/beam_mesh.hpp"
#include "io/hdf5_file.hpp"
#include "deck/checkpoint.hpp"
#include "test_support.hpp"
#include "tirefe/test_paths.hpp"

namespace fs = std::filesystem;
using tirefe::io::Hdf5File;

namespace {

const std::string kDeck = std::string(TIREFE_TEST_DATA_DIR) + "/restart_deck.lua";

struct Run {
  int status;
  std::string output;  // standard output and error
};

Run run_deck(const fs::path& folder, const std::string& arguments, const std::string& deck = kDeck) {
  fs::remove_all(folder);
  const std::string command =
      std::string(TIREFE_BINARY) + " " + deck + " --output-dir " + folder.string() + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string output;
  std::array<char, 512> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

/// A copy of the restart deck in 'folder' that sets 'change' right after its parameters
/// (on the same line, so that line numbers stay): another model with the same parameters.
std::string edited_deck(const fs::path& folder, const std::string& change) {
  std::ifstream in(kDeck);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string end_of_parameters = "with_contact = 1 }";
  text.replace(text.find(end_of_parameters), end_of_parameters.size(), end_of_parameters + " " + change);
  fs::create_directories(folder);
  std::ofstream(folder / "restart_deck.lua") << text;
  return (folder / "restart_deck.lua").string();
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

}  // namespace

TEST_CASE("a run restarted from a checkpoint continues bit for bit", "[reliability][restart]") {
  const fs::path root = fs::temp_directory_path() / "tirefe_restart";
  const fs::path whole = root / "whole";
  const Run uninterrupted = run_deck(whole, "--quiet");
  REQUIRE(uninterrupted.status == 0);
  const auto reference_end = tirefe::macros::read_checkpoint((whole / "end.ckpt.h5").string());
  const Hdf5File reference = Hdf5File::open_read_only((whole / "restart.h5").string());
  REQUIRE(reference_end.analysis.accepted_steps == 150);
  // The case is not trivial: the ring slides in contact and the road drags it.
  const std::vector<double> patch_fx = reference.read_doubles("/history/patch_fx");
  REQUIRE(patch_fx.size() == 150);
  CHECK(std::abs(patch_fx.back()) > 50.0);

  for (const char* checkpoint : {"mid.ckpt.h5", "auto.ckpt.h5"}) {
    DYNAMIC_SECTION("restarted from " << checkpoint) {
      const auto saved = tirefe::macros::read_checkpoint((whole / checkpoint).string());
      const int start_step = saved.analysis.accepted_steps;
      CHECK(start_step == (std::string(checkpoint) == "mid.ckpt.h5" ? 60 : 120));
      const fs::path folder = root / fs::path(checkpoint).stem().stem();
      fs::create_directories(root);
      fs::copy_file(whole / checkpoint, root / checkpoint, fs::copy_options::overwrite_existing);
      const Run restarted = run_deck(folder, "--restart " + (root / checkpoint).string());
      INFO(restarted.output.substr(0, 2000));
      REQUIRE(restarted.status == 0);
      CHECK(restarted.output.find("restarted at step " + std::to_string(start_step)) != std::string::npos);
      CHECK(restarted.output.find("step     1 ") == std::string::npos);  // nothing before it was recomputed

      // Every row dataset of the result file (history, fields, contact rows).
      const Hdf5File result = Hdf5File::open_read_only((folder / "restart.h5").string());
      int compared = 0;
      for (const auto& rows : reference_end.rows) {
        INFO(rows.path);
        CHECK(same_bits(result.read_doubles(rows.path), reference.read_doubles(rows.path)));
        ++compared;
      }
      CHECK(compared >= 20);
      // The XDMF index names the frames the checkpoint brought back too, as the uninterrupted run's does.
      auto text_of = [](const fs::path& path) {
        std::ifstream in(path);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      };
      CHECK(text_of(folder / "restart.xmf").find("/surfaces/road/frames/0<") != std::string::npos);
      CHECK(text_of(folder / "restart.xmf") == text_of(whole / "restart.xmf"));

      // The final state, element and contact history included.
      const auto end = tirefe::macros::read_checkpoint((folder / "end.ckpt.h5").string());
      const auto& a = end.analysis;
      const auto& b = reference_end.analysis;
      CHECK(a.state.time == b.state.time);
      CHECK(a.accepted_steps == b.accepted_steps);
      CHECK(a.state.displacement == b.state.displacement);
      CHECK(a.state.velocity == b.state.velocity);
      CHECK(a.state.acceleration == b.state.acceleration);
      CHECK(a.reactions == b.reactions);
      CHECK(a.energy.dissipated == b.energy.dissipated);
      REQUIRE(end.blocks.size() == reference_end.blocks.size());
      for (size_t k = 0; k < end.blocks.size(); ++k) CHECK(end.blocks[k].history == reference_end.blocks[k].history);
    }
  }
}

TEST_CASE("a restart refuses a checkpoint of another model", "[reliability][restart]") {
  const fs::path root = fs::temp_directory_path() / "tirefe_restart_other";
  REQUIRE(run_deck(root / "whole", "--quiet t_mid=0.02 t_end=0.04").status == 0);
  const std::string checkpoint = (root / "whole" / "mid.ckpt.h5").string();
  const std::string same_parameters = "--quiet t_mid=0.02 t_end=0.04 --restart " + checkpoint;
  // The deck edited after its parameters: the parameters match, the model does not.
  const fs::path decks = root / "edited";
  SECTION("another node count") {
    const Run other = run_deck(root / "other", same_parameters, edited_deck(decks, "p.elements = 20"));
    CHECK(other.status == 1);
    CHECK(other.output.find("restart_deck.lua:33:") != std::string::npos);
    CHECK(other.output.find("the checkpoint is of another model: it has 24 nodes, the deck's model 20") !=
          std::string::npos);
  }
  SECTION("another integrator") {
    // Same mesh and blocks; only the deck's integrator differs.
    const Run other = run_deck(root / "other", same_parameters, edited_deck(decks, "p.alpha = -0.2"));
    CHECK(other.status == 1);
    CHECK(other.output.find("the checkpoint was taken with another integrator than the deck's") != std::string::npos);
  }
  SECTION("another set of element blocks") {
    const Run other = run_deck(root / "other", same_parameters, edited_deck(decks, "p.with_contact = 0"));
    CHECK(other.status == 1);
    CHECK(other.output.find("it has 2 element blocks, the deck's model 1") != std::string::npos);
  }
}

TEST_CASE("a restart refuses parameters other than the checkpoint's", "[reliability][restart]") {
  // The restarted file's /parameters would say t_end = 0.05 of rows computed for 0.04.
  const fs::path root = fs::temp_directory_path() / "tirefe_restart_parameters";
  REQUIRE(run_deck(root / "whole", "--quiet t_mid=0.02 t_end=0.04").status == 0);
  const std::string checkpoint = (root / "whole" / "mid.ckpt.h5").string();
  CHECK(tirefe::macros::read_checkpoint(checkpoint).parameters.size() == 7);
  const Run changed = run_deck(root / "changed", "--quiet t_mid=0.02 t_end=0.05 dt=0.001 --restart " + checkpoint);
  CHECK(changed.status == 1);
  CHECK(changed.output == "tirefe: " + kDeck +
                              ":4: the restart changes the parameters the checkpoint was written with: dt = 0.001 "
                              "(the checkpoint's: 0.002), t_end = 0.05 (the checkpoint's: 0.04); a restart continues "
                              "the same case (give the checkpoint's values, or run without --restart)\n");
  CHECK_FALSE(fs::exists(root / "changed" / "restart.h5"));  // refused before any file is written
  CHECK(run_deck(root / "same", "--quiet t_end=0.04 t_mid=0.02 --restart " + checkpoint).status == 0);
}

TEST_CASE("two checkpoints of the same state are the same bytes, element histories included",
          "[reliability][restart]") {
  // Two processes, so that bytes left uninitialised (an empty history's padding byte, the
  // gaps of a struct) would differ: the tread beams and the contact nodes' histories.
  const fs::path root = fs::temp_directory_path() / "tirefe_restart_identical";
  std::vector<tirefe::macros::Checkpoint> ends;
  for (const char* run : {"first", "second"}) {
    REQUIRE(run_deck(root / run, "--quiet t_mid=0.02 t_end=0.04").status == 0);
    ends.push_back(tirefe::macros::read_checkpoint((root / run / "end.ckpt.h5").string()));
  }
  REQUIRE(ends[0].blocks.size() == 2);  // tread beams and contact
  REQUIRE(ends[1].blocks.size() == 2);
  for (size_t b = 0; b < 2; ++b) {
    const auto& first = ends[0].blocks[b];
    const auto& second = ends[1].blocks[b];
    INFO("block " << first.name);
    CHECK(first.history.size() == static_cast<size_t>(first.bytes_per_element * first.elements));
    CHECK(first.elements == 24);
    CHECK(first.history == second.history);
  }
  // An empty history is written as zeros, not as whatever its padding byte held.
  const auto& beams = ends[0].blocks[0].bytes_per_element == 1 ? ends[0].blocks[0] : ends[0].blocks[1];
  REQUIRE(beams.bytes_per_element == 1);
  CHECK(std::count(beams.history.begin(), beams.history.end(), 0) == 24);
  CHECK(ends[0].analysis.state.displacement == ends[1].analysis.state.displacement);
}

namespace {

/// A cantilever of four beams with a tip load, two static steps taken.
struct SmallRun {
  tirefe::Model model;
  tirefe::Analysis analysis{model};
  SmallRun() {
    tirefe::BeamSection section;
    section.axial_stiffness = section.shear_stiffness = 1e6;
    section.bending_stiffness = 10.0;
    const std::vector<int> nodes = tirefe::add_beam_line(model, "beam", {0.0, 0.0}, {1.0, 0.0}, 4, section);
    for (int dof : {tirefe::kUx, tirefe::kUy, tirefe::kRz}) model.fix(nodes.front(), dof);
    model.add_nodal_load(nodes.back(), tirefe::kUy, -1.0, tirefe::Model::kRampLoadFunction);
    analysis.set_time_step(0.1);
    analysis.advance(0.2);
  }
};

std::string refusal_of(const std::string& checkpoint) {
  try {
    tirefe::macros::read_checkpoint(checkpoint);
  } catch (const tirefe::io::IoError& error) {
    return error.what();
  }
  return "(accepted)";
}

}  // namespace

TEST_CASE("a checkpoint holding a count out of range or a non-finite number is refused, never wrapped",
          "[reliability][restart]") {
  tirefe::testing::TempDir dir;
  SmallRun run;
  tirefe::macros::Checkpoint checkpoint = tirefe::macros::capture_checkpoint(run.analysis, nullptr, 1, "small");
  const std::string path = dir.path("small.ckpt.h5");
  tirefe::macros::write_checkpoint(path, checkpoint);
  REQUIRE(tirefe::macros::read_checkpoint(path).analysis.accepted_steps == 2);

  SECTION("an attribute changed in the file") {
    struct Tampering {
      const char* object;
      const char* name;
      double value;
      const char* refusal;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Tampering tampering = GENERATE_COPY(values<Tampering>(
        {{"/", "steps", -2147483649.0, "'/steps' = -2147483649 is not an integer from 0 to 2147483647"},
         {"/", "steps", 2.5, "'/steps' = 2.5 is not an integer from 0 to 2147483647"},
         {"/", "model_index", 0.0, "'/model_index' = 0 is not an integer from 1 to 2147483647"},
         {"/rows", "steps_recorded", 1e300, "'/rows/steps_recorded' = 1e+300 is not an integer"},
         {"/blocks/0", "elements", nan, "'/blocks/0/elements' = nan is not an integer"},
         {"/analysis", "reactions_valid", 2.0, "'/analysis/reactions_valid' = 2 is not an integer from 0 to 1"},
         {"/", "time", nan, "'/time' holds nan, not a finite number"},
         {"/analysis", "current_step", -INFINITY, "'/analysis/current_step' holds -inf"},
         {"/analysis", "current_step", -1.0, "'/analysis/current_step' = -1 is no step size > 0"}}));
    INFO(tampering.object << " " << tampering.name);
    tirefe::io::Hdf5File::open_read_write(path).write_attribute(tampering.object, tampering.name, tampering.value);
    CHECK_THAT(refusal_of(path), Catch::Contains("restart file '" + path + "' is not a readable checkpoint (") &&
                                     Catch::Contains(tampering.refusal));
  }
  SECTION("a state vector with a NaN") {
    {
      tirefe::io::Hdf5File file = tirefe::io::Hdf5File::open_read_write(path);
      std::vector<double> velocity = file.read_doubles("/analysis/velocity");
      velocity.back() = std::numeric_limits<double>::quiet_NaN();
      file.remove("/analysis/velocity");
      file.write_vector("/analysis/velocity", velocity);
    }
    CHECK_THAT(refusal_of(path), Catch::Contains("'/analysis/velocity' holds nan, not a finite number"));
  }
  SECTION("rows whose shape overflows, and a time row that is not a number") {
    checkpoint.has_output = true;
    checkpoint.rows.push_back({"/fields/displacement", {1LL << 40, 1LL << 40}, 0, {}});
    tirefe::macros::write_checkpoint(path, checkpoint);
    CHECK_THAT(refusal_of(path), Catch::Contains("rows of '/fields/displacement' are incomplete"));
    checkpoint.rows = {{"/history/time", {}, 2, {0.1, std::numeric_limits<double>::quiet_NaN()}}};
    tirefe::macros::write_checkpoint(path, checkpoint);
    CHECK_THAT(refusal_of(path), Catch::Contains("'/rows/0/values' holds nan, not a finite number"));
  }
}

TEST_CASE("an analysis stops counting steps at the largest int instead of wrapping", "[reliability][restart]") {
  SmallRun run;
  tirefe::CarriedState state = run.analysis.snapshot();
  state.accepted_steps = std::numeric_limits<int>::max();
  run.analysis.restore(state);
  CHECK_THROWS_WITH(run.analysis.advance(0.1),
                    "the analysis has taken 2147483647 steps, the most it counts; continue in another run");
  CHECK(run.analysis.accepted_steps() == std::numeric_limits<int>::max());
}
