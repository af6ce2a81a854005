#include "io/xdmf.hpp"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "io/hdf5_file.hpp"

namespace tirefe::io {

namespace {

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

/// The shortest text that reads back as the same double.
std::string exact(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

std::string with_frame(const std::string& path, size_t frame) {
  const std::string token = "{frame}";
  const size_t at = path.find(token);
  if (at == std::string::npos) return path;
  return path.substr(0, at) + std::to_string(frame) + path.substr(at + token.size());
}

void data_item(std::string& out, const std::string& file, const XdmfData& data, size_t frame, const char* indent) {
  out += indent;
  out += "<DataItem Dimensions=\"";
  for (size_t i = 0; i < data.dimensions.size(); ++i) out += (i ? " " : "") + std::to_string(data.dimensions[i]);
  out += data.integer ? "\" DataType=\"Int\"" : "\" DataType=\"Float\"";
  out += " Precision=\"8\" Format=\"HDF\">" + file + ":" + escaped(with_frame(data.path, frame)) + "</DataItem>\n";
}

}  // namespace

XdmfIndex::XdmfIndex(std::string hdf5_file_name) : file_(escaped(hdf5_file_name)) {}

void XdmfIndex::add_grid(const XdmfGrid& grid) {
  Collection& collection = collections_.emplace_back(Collection{grid, {}});
  for (size_t frame = 0; frame < times_.size(); ++frame) append_frame(collection, frame);
}

void XdmfIndex::add_frame(double time) {
  times_.push_back(time);
  for (Collection& collection : collections_) append_frame(collection, times_.size() - 1);
}

void XdmfIndex::append_frame(Collection& collection, size_t frame) const {
  const XdmfGrid& grid = collection.grid;
  std::string& out = collection.frames;
  out += "      <Grid Name=\"" + escaped(grid.name) + "\" GridType=\"Uniform\">\n";
  out += "        <Time Value=\"" + exact(times_[frame]) + "\" />\n";
  out += "        <Topology TopologyType=\"" + grid.topology + "\" NumberOfElements=\"" + std::to_string(grid.cells) +
         "\"";
  if (grid.nodes_per_cell > 0) out += " NodesPerElement=\"" + std::to_string(grid.nodes_per_cell) + "\"";
  out += ">\n";
  data_item(out, file_, grid.connectivity, frame, "          ");
  out += "        </Topology>\n        <Geometry GeometryType=\"XY\">\n";
  data_item(out, file_, grid.geometry, frame, "          ");
  out += "        </Geometry>\n";
  for (const XdmfAttribute& attribute : grid.attributes) {
    out += "        <Attribute Name=\"" + escaped(attribute.name) + "\" AttributeType=\"" + attribute.type +
           "\" Center=\"" + attribute.centre + "\">\n";
    data_item(out, file_, attribute.data, frame, "          ");
    out += "        </Attribute>\n";
  }
  out += "      </Grid>\n";
}

template <class Out>
void XdmfIndex::write_to(Out& out) const {
  out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
  // The first grid last: the one meshio reads.
  for (size_t i = 1; i <= collections_.size(); ++i) {
    const Collection& collection = collections_[i % collections_.size()];
    out << "    <Grid Name=\"" << escaped(collection.grid.name)
        << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n"
        << collection.frames << "    </Grid>\n";
  }
  out << "  </Domain>\n</Xdmf>\n";
}

size_t XdmfIndex::size() const {
  size_t bytes = 0;
  for (const Collection& collection : collections_) bytes += collection.frames.size();
  return bytes;
}

std::string XdmfIndex::text() const {
  std::ostringstream out;
  write_to(out);
  return out.str();
}

void XdmfIndex::write(const std::string& path) const {
  const std::string partial = path + ".partial";
  {
    errno = 0;
    std::ofstream out(partial, std::ios::trunc);
    write_to(out);
    out.close();
    if (!out) {
      // The system's reason (a full disk) is the one that says what to do.
      const std::string reason = errno != 0 ? std::string(": ") + std::strerror(errno) : "";
      std::remove(partial.c_str());
      throw IoError("cannot write the XDMF index '" + partial + "'" + reason);
    }
  }
  if (std::rename(partial.c_str(), path.c_str()) != 0) {
    std::remove(partial.c_str());
    throw IoError("cannot rename the XDMF index '" + partial + "' to '" + path + "'");
  }
}

}  // namespace tirefe::io
