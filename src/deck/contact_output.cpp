#include "deck/contact_output.hpp"

#include <memory>
#include <utility>
#include <vector>

namespace tirefe::macros {

namespace {

// What either kind of contact block gives alike: its name, surface, totals and per-point rows.
template <class Block>
ContactSource common_source(const Block& block) {
  ContactSource source;
  source.block = block.name();
  if (block.size() > 0) source.surface = &block.kernel(0).surface();
  source.summarize = [&block] { return summarize_contact(block); };
  source.responses = responses_of(block);
  return source;
}

}  // namespace

ContactSource contact_source(const ContactBlock& block) {
  ContactSource source = common_source(block);
  source.write_points = [&block](io::Hdf5File& file, const std::string& group) {
    std::vector<long long> nodes;
    for (int e = 0; e < block.size(); ++e) nodes.push_back(block.element_nodes(e)[0]);
    file.write_int_vector(group + "nodes", nodes);
  };
  return source;
}

ContactSource contact_source(const TreadContactBlock& block) {
  ContactSource source = common_source(block);
  source.write_points = [&block](io::Hdf5File& file, const std::string& group) {
    std::vector<long long> starts;
    std::vector<double> positions;
    for (int e = 0; e < block.size(); ++e)
      for (int q = 0; q < TreadContact::kSamples; ++q) {
        starts.push_back(block.element_nodes(e)[0]);
        positions.push_back(TreadContact::sample_weight(q));
      }
    file.write_int_vector(group + "chord_start", starts);
    file.write_vector(group + "chord_position", positions);
  };
  return source;
}

void add_contact_output(io::ResultFile& file, Analysis& analysis, const ContactSource& source,
                        const std::string& channel_prefix, int every) {
  if (!channel_prefix.empty()) {
    // The four totals of a step from one pass over the points, the first channel's.
    struct StepSummary {
      int step = -1;
      double time = 0.0;
      ContactSummary summary;
    };
    const auto cache = std::make_shared<StepSummary>();
    const auto at = [summarize = source.summarize, cache](const State& state,
                                                          const StepRecord& record) -> const ContactSummary& {
      if (cache->step != record.step || cache->time != state.time) *cache = {record.step, state.time, summarize()};
      return cache->summary;
    };
    file.add_channel(channel_prefix + "_fx", "N",
                     [at](const State& state, const StepRecord& record) { return at(state, record).force.x(); });
    file.add_channel(channel_prefix + "_fy", "N",
                     [at](const State& state, const StepRecord& record) { return at(state, record).force.y(); });
    file.add_channel(channel_prefix + "_patch_length", "m",
                     [at](const State& state, const StepRecord& record) { return at(state, record).patch_length; });
    file.add_channel(channel_prefix + "_nodes_in_contact", "", [at](const State& state, const StepRecord& record) {
      return static_cast<double>(at(state, record).nodes_in_contact);
    });
    // The surface's prescribed motion (a drum's angle, a road's travel), to place events
    // such as a cleat passage on the time axis.
    if (source.surface) {
      const RigidMotion* motion = &source.surface->motion();
      file.add_channel(channel_prefix + "_surface_angle", "rad",
                       [motion](const State& state, const StepRecord&) { return motion->angle_at(state.time); });
      file.add_channel(channel_prefix + "_surface_x", "m", [motion](const State& state, const StepRecord&) {
        return motion->translation_at(state.time).x();
      });
    }
  }
  if (every <= 0) return;

  const std::string group = "/contact/" + source.block + "/";
  io::Hdf5File& hdf5 = file.file();
  source.write_points(hdf5, group);
  // The block's responses every 'every' accepted steps.
  auto rows = std::make_shared<io::ResponseRows>(hdf5, group, *source.responses);
  analysis.add_step_observer([rows, every](const Analysis& run, const StepRecord& record) {
    if (record.step % every == 0) rows->append(run.state());
  });
}

void add_surface_output(io::ResultFile& file, const std::string& name, std::shared_ptr<const RigidSurface> surface) {
  // The chords are chosen once (the first outline's reach), so every frame has as many points.
  const bool closed = surface->curve().closed();
  file.add_surface(name, closed,
                   [surface, tolerance = 0.0](double time, const Eigen::Vector2d& centre, double reach) mutable {
                     if (tolerance == 0.0) tolerance = reach / 4000.0;
                     return surface->outline(time, centre, reach, tolerance);
                   });
}

}  // namespace tirefe::macros
