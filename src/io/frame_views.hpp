// The views of a field frame: the whole datasets the XDMF index names for frame k, each a
// virtual dataset showing row k of the frames' datasets (docs/output.md, XDMF index).
//   /fields/frames/<k>/displacement, velocity, deformation   u_x, u_y (z = 0), nodes x 3
//   /fields/frames/<k>/rotation                              theta_z, nodes
//   /surfaces/<name>/frames/<k>                              the surface's outline, points x 2
// A run makes them as it writes its frames, or leaves them to make_frame_views (the
// command `tirefe --views FILE`), which makes those a file lacks.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"

namespace tirefe::io {

struct RowView {
  std::string path;
  std::string source;           // the dataset of frames x entries x columns it shows row k of
  hsize_t first, count, width;  // Hdf5File::write_row_view
};

/// Frame 'frame' of a surface's outline.
RowView surface_view(const std::string& surface, size_t frame);

/// The views of frame 'frame', of the datasets 'has' finds (velocity and deformation are
/// not in every file) and of the surfaces 'surfaces'.
std::vector<RowView> frame_views(size_t frame, const std::function<bool(const std::string&)>& has,
                                 const std::vector<std::string>& surfaces);

/// Makes, in the result file at 'path', the views of its frames (/fields/time) that it
/// lacks; the file is whole at every instant (Hdf5File::open_published). Returns the views made.
size_t make_frame_views(const std::string& path);

}  // namespace tirefe::io
