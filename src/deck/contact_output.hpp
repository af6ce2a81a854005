// Contact results in the HDF5 result file (docs/output.md, docs/contact.md):
//   /history/<prefix>_fx, _fy            total contact force on the structure [N]
//   /history/<prefix>_patch_length       arc length spanned by the points in contact [m]
//   /history/<prefix>_nodes_in_contact   count of the points in contact (nodes, or a tread's samples)
//   /contact/<block>/nodes               a node contact's 0-based node indices (fixed), or
//   /contact/<block>/chord_start, chord_position   a tread contact's sample points: the
//                                        chord's first node and the point's place on it (0..1)
//   /contact/<block>/time                one row per written step [s]
//   /contact/<block>/gap, normal_force, tangential_force, state, coordinate, sliding_velocity
//                                        one row per written step, one column per point: the
//                                        block's named responses (contact_point_responses())
//   /surfaces/<name>/outline             the surface at every field frame (add_surface_output)
// state is 0 open, 1 stick, 2 slip.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contact/node_contact.hpp"
#include "contact/tread_contact.hpp"
#include "io/response_rows.hpp"
#include "io/result_file.hpp"
#include "solvers/analysis.hpp"

namespace tirefe::macros {

/// What the output reads of a contact block of either kind; the block must outlive the run.
struct ContactSource {
  std::string block;
  const RigidSurface* surface = nullptr;
  std::function<ContactSummary()> summarize;
  const ElementResponses* responses = nullptr;  // the per-point rows, by name
  std::function<void(io::Hdf5File&, const std::string& group)> write_points;
};
ContactSource contact_source(const ContactBlock& block);
ContactSource contact_source(const TreadContactBlock& block);

/// Adds the history channels (unless channel_prefix is empty) and, when every > 0, the
/// per-point rows written every 'every' accepted steps by an observer of the analysis. The
/// file and analysis must outlive the run.
void add_contact_output(io::ResultFile& file, Analysis& analysis, const ContactSource& source,
                        const std::string& channel_prefix, int every);

/// Draws the surface in the file's field frames (/surfaces/<name>, and the XDMF index): its
/// arcs within 1/4000 of the structure's size when first drawn, a road's rays out to a
/// structure's size beyond the structure.
void add_surface_output(io::ResultFile& file, const std::string& name, std::shared_ptr<const RigidSurface> surface);

}  // namespace tirefe::macros
