// Contact results in the HDF5 result file (docs/output.md, docs/contact.md):
//   /history/<prefix>_fx, _fy            total contact force on the structure [N]
//   /history/<prefix>_patch_length       arc length spanned by the nodes in contact [m]
//   /history/<prefix>_nodes_in_contact   count
//   /contact/<block>/nodes               0-based node indices (fixed)
//   /contact/<block>/time                one row per written step [s]
//   /contact/<block>/gap, normal_force, tangential_force, state, coordinate, sliding_velocity
//                                        one row per written step, one column per node
//   /surfaces/<name>/outline             the surface at every field frame (add_surface_output)
// state is 0 open, 1 stick, 2 slip.
#pragma once

#include <memory>
#include <string>

#include "contact/node_contact.hpp"
#include "io/result_file.hpp"

namespace tirefe {

/// Adds the history channels (unless channel_prefix is empty) and, when every > 0, the
/// per-node rows written every 'every' accepted steps by an observer of the analysis. The
/// block, file and analysis must outlive the run.
void add_contact_output(io::ResultFile& file, Analysis& analysis, const ContactBlock& block,
                        const std::string& channel_prefix, int every);

/// Draws the surface in the file's field frames (/surfaces/<name>, and the XDMF index): its
/// arcs within 1/4000 of the structure's size when first drawn, a road's rays out to a
/// structure's size beyond the structure.
void add_surface_output(io::ResultFile& file, const std::string& name, std::shared_ptr<const RigidSurface> surface);

}  // namespace tirefe
