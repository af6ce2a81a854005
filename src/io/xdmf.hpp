// XDMF index of a result file's displacement fields, so ParaView (File > Open, "Xdmf3
// Reader S" or "XDMF Reader") animates the deforming structure. The .xmf file holds no
// numbers: it points at /mesh and /fields in the HDF5 file beside it. Each frame is one
// grid per element block: tread beams as polylines, sidewall wedges as triangles (the
// tire's side view), point elements as vertices. Node positions are reference
// coordinates plus the frame's (u_x, u_y); u_x, u_y and theta_z are point attributes.
#pragma once

#include <string>
#include <vector>

namespace tirefe::io {

struct XdmfBlock {
  std::string name;  // /mesh/blocks/<name>
  int elements = 0;
  int nodes_per_element = 0;
};

struct XdmfFields {
  std::string hdf5_file_name;  // relative to the .xmf file's folder
  int nodes = 0;
  std::vector<XdmfBlock> blocks;
  std::vector<double> frame_times;  // /fields/time
};

/// The XDMF text for these fields.
std::string xdmf_text(const XdmfFields& fields);
/// Writes xdmf_text() to 'path' (replacing it); throws IoError when it cannot.
void write_xdmf(const std::string& path, const XdmfFields& fields);

}  // namespace tirefe::io
