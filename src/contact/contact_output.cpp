#include "contact/contact_output.hpp"

#include <memory>
#include <utility>
#include <vector>

namespace tirefe {

void add_contact_output(io::ResultFile& file, Analysis& analysis, const ContactBlock& block,
                        const std::string& channel_prefix, int every) {
  if (!channel_prefix.empty()) {
    const ContactBlock* source = &block;
    file.add_channel(channel_prefix + "_fx", "N",
                     [source](const Analysis&, const StepRecord&) { return summarize_contact(*source).force.x(); });
    file.add_channel(channel_prefix + "_fy", "N",
                     [source](const Analysis&, const StepRecord&) { return summarize_contact(*source).force.y(); });
    file.add_channel(channel_prefix + "_patch_length", "m",
                     [source](const Analysis&, const StepRecord&) { return summarize_contact(*source).patch_length; });
    file.add_channel(channel_prefix + "_nodes_in_contact", "", [source](const Analysis&, const StepRecord&) {
      return static_cast<double>(summarize_contact(*source).nodes_in_contact);
    });
    // The surface's prescribed motion (a drum's angle, a road's travel), to place events
    // such as a cleat passage on the time axis.
    if (block.size() > 0) {
      const RigidMotion* motion = &block.kernel(0).surface().motion();
      file.add_channel(channel_prefix + "_surface_angle", "rad",
                       [motion](const Analysis& run, const StepRecord&) { return motion->angle_at(run.state().time); });
      file.add_channel(channel_prefix + "_surface_x", "m", [motion](const Analysis& run, const StepRecord&) {
        return motion->translation_at(run.state().time).x();
      });
    }
  }
  if (every <= 0) return;

  const std::string group = "/contact/" + block.name() + "/";
  std::vector<long long> nodes;
  for (int e = 0; e < block.size(); ++e) nodes.push_back(block.element_nodes(e)[0]);
  io::Hdf5File& hdf5 = file.file();
  hdf5.write_int_vector(group + "nodes", nodes);
  const std::vector<hsize_t> row{static_cast<hsize_t>(block.size())};
  struct Datasets {
    io::ExtendibleDataset *time, *gap, *normal_force, *tangential_force, *state, *coordinate, *sliding_velocity;
    ContactNodeResults results;
  };
  // Per-node rows are fields: compressed (most nodes are open, most values zero).
  auto field = [&](const char* name, const char* unit) -> io::ExtendibleDataset* {
    return &hdf5.create_compressed_extendible(group + name, row, unit);
  };
  auto datasets = std::make_shared<Datasets>(Datasets{&hdf5.create_extendible(group + "time", {}, "s"),
                                                      field("gap", "m"),
                                                      field("normal_force", "N"),
                                                      field("tangential_force", "N"),
                                                      field("state", "0 open, 1 stick, 2 slip"),
                                                      field("coordinate", "m"),
                                                      field("sliding_velocity", "m/s"),
                                                      {}});
  const ContactBlock* source = &block;
  analysis.add_step_observer([datasets, source, every](const Analysis& run, const StepRecord& record) {
    if (record.step % every != 0) return;
    Datasets& d = *datasets;
    fill_contact_results(*source, d.results);
    d.time->append(run.state().time);
    d.gap->append(d.results.gap.data());
    d.normal_force->append(d.results.normal_force.data());
    d.tangential_force->append(d.results.tangential_force.data());
    d.state->append(d.results.state.data());
    d.coordinate->append(d.results.coordinate.data());
    d.sliding_velocity->append(d.results.sliding_velocity.data());
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

}  // namespace tirefe
