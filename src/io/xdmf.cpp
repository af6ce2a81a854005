#include "io/xdmf.hpp"

#include <fstream>
#include <set>
#include <sstream>

#include "io/hdf5_file.hpp"

namespace tirefe::io {

namespace {

const char* topology_of(int nodes_per_element) {
  switch (nodes_per_element) {
    case 1: return "Polyvertex";
    case 2: return "Polyline";
    case 3: return "Triangle";
    case 4: return "Quadrilateral";
    default: return nullptr;
  }
}

/// One frame's slab of /fields/displacement: 'components' columns from 'first'.
void write_slab(std::ostream& out, const XdmfFields& fields, size_t frame, int first, int components,
                const std::string& indent) {
  const size_t frames = fields.frame_times.size();
  out << indent << "<DataItem ItemType=\"HyperSlab\" Dimensions=\"" << fields.nodes << " " << components
      << "\" Type=\"HyperSlab\">\n"
      << indent << "  <DataItem Dimensions=\"3 3\" Format=\"XML\">" << frame << " 0 " << first << "  1 1 1  1 "
      << fields.nodes << " " << components << "</DataItem>\n"
      << indent << "  <DataItem Dimensions=\"" << frames << " " << fields.nodes
      << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << fields.hdf5_file_name
      << ":/fields/displacement</DataItem>\n"
      << indent << "</DataItem>\n";
}

}  // namespace

std::string xdmf_text(const XdmfFields& fields) {
  std::ostringstream out;
  out.precision(17);
  out << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n  <Domain>\n"
      << "    <Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const std::string& file = fields.hdf5_file_name;
  for (size_t frame = 0; frame < fields.frame_times.size(); ++frame) {
    out << "      <Grid Name=\"frame " << frame << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
        << "        <Time Value=\"" << fields.frame_times[frame] << "\" />\n";
    std::set<std::pair<int, int>> drawn;  // blocks repeating another's shape (the pressure on the tread) are skipped
    for (const XdmfBlock& block : fields.blocks) {
      const char* topology = topology_of(block.nodes_per_element);
      if (!topology || block.elements == 0) continue;
      if (!drawn.insert({block.elements, block.nodes_per_element}).second) continue;
      out << "        <Grid Name=\"" << block.name << "\" GridType=\"Uniform\">\n"
          << "          <Topology TopologyType=\"" << topology << "\" NumberOfElements=\"" << block.elements << "\""
          << (block.nodes_per_element <= 2 ? " NodesPerElement=\"" + std::to_string(block.nodes_per_element) + "\""
                                           : std::string())
          << ">\n"
          << "            <DataItem Dimensions=\"" << block.elements << " " << block.nodes_per_element
          << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << file << ":/mesh/blocks/" << block.name
          << "</DataItem>\n          </Topology>\n"
          << "          <Geometry GeometryType=\"XY\">\n"
          << "            <DataItem ItemType=\"Function\" Function=\"$0 + $1\" Dimensions=\"" << fields.nodes
          << " 2\">\n"
          << "              <DataItem Dimensions=\"" << fields.nodes
          << " 2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file << ":/mesh/coordinates</DataItem>\n";
      write_slab(out, fields, frame, 0, 2, "              ");
      out << "            </DataItem>\n          </Geometry>\n";
      const char* names[] = {"u_x", "u_y", "theta_z"};
      for (int component = 0; component < 3; ++component) {
        out << "          <Attribute Name=\"" << names[component] << "\" AttributeType=\"Scalar\" Center=\"Node\">\n";
        write_slab(out, fields, frame, component, 1, "            ");
        out << "          </Attribute>\n";
      }
      out << "        </Grid>\n";
    }
    out << "      </Grid>\n";
  }
  out << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return out.str();
}

void write_xdmf(const std::string& path, const XdmfFields& fields) {
  std::ofstream out(path, std::ios::trunc);
  out << xdmf_text(fields);
  if (!out) throw IoError("cannot write the XDMF index '" + path + "'");
}

}  // namespace tirefe::io
