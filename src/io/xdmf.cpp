#include "io/xdmf.hpp"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <ostream>
#include <sstream>

#include <ext/stdio_filebuf.h>

#include "io/hdf5_file.hpp"
#include "io/temporary_file.hpp"

namespace tirefe::io {

const char* const kXdmfSignature = "<?xml";

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

/// A path's text with "{frame}" (its first) left as a hole of 'text'.
void path_with_frame(FrameText& text, const std::string& path) {
  const std::string token = "{frame}";
  const size_t at = path.find(token);
  if (at == std::string::npos) {
    text.literal(escaped(path));
    return;
  }
  text.literal(escaped(path.substr(0, at)));  // digits need no escaping: the parts escape alone
  text.hole(FrameText::Hole::frame);
  text.literal(escaped(path.substr(at + token.size())));
}

void data_item(FrameText& text, const std::string& file, const XdmfData& data, const char* indent) {
  std::string head = indent;
  head += "<DataItem Dimensions=\"";
  for (size_t i = 0; i < data.dimensions.size(); ++i) head += (i ? " " : "") + std::to_string(data.dimensions[i]);
  head += data.integer ? "\" DataType=\"Int\"" : "\" DataType=\"Float\"";
  text.literal(head + " Precision=\"8\" Format=\"HDF\">" + file + ":");
  path_with_frame(text, data.path);
  text.literal("</DataItem>\n");
}

}  // namespace

void FrameText::literal(const std::string& text) { pieces_.back() += text; }

void FrameText::hole(Hole hole) {
  holes_.push_back(hole);
  pieces_.emplace_back();
}

void FrameText::append(std::string& out, const std::string& time, const std::string& frame) const {
  out += pieces_[0];
  for (size_t i = 0; i < holes_.size(); ++i) {
    out += holes_[i] == Hole::time ? time : frame;
    out += pieces_[i + 1];
  }
}

size_t FrameText::length(size_t time, size_t frame) const {
  size_t bytes = 0;
  for (const std::string& piece : pieces_) bytes += piece.size();
  for (Hole hole : holes_) bytes += hole == Hole::time ? time : frame;
  return bytes;
}

XdmfIndex::XdmfIndex(std::string hdf5_file_name) : file_(escaped(hdf5_file_name)) {}

void XdmfIndex::add_grid(const XdmfGrid& grid) {
  const Collection& collection = collections_.emplace_back(Collection{grid, frame_text(grid)});
  for (size_t frame = 0; frame < times_.size(); ++frame) bytes_ += frame_length(collection, frame);
}

void XdmfIndex::add_frame(double time) {
  times_.push_back(time);
  for (const Collection& collection : collections_) bytes_ += frame_length(collection, times_.size() - 1);
}

FrameText XdmfIndex::frame_text(const XdmfGrid& grid) const {
  FrameText text;
  text.literal("      <Grid Name=\"" + escaped(grid.name) + "\" GridType=\"Uniform\">\n        <Time Value=\"");
  text.hole(FrameText::Hole::time);
  text.literal("\" />\n        <Topology TopologyType=\"" + grid.topology + "\" NumberOfElements=\"" +
               std::to_string(grid.cells) + "\"");
  if (grid.nodes_per_cell > 0) text.literal(" NodesPerElement=\"" + std::to_string(grid.nodes_per_cell) + "\"");
  text.literal(">\n");
  data_item(text, file_, grid.connectivity, "          ");
  text.literal("        </Topology>\n        <Geometry GeometryType=\"XY\">\n");
  data_item(text, file_, grid.geometry, "          ");
  text.literal("        </Geometry>\n");
  for (const XdmfAttribute& attribute : grid.attributes) {
    text.literal("        <Attribute Name=\"" + escaped(attribute.name) + "\" AttributeType=\"" + attribute.type +
                 "\" Center=\"" + attribute.centre + "\">\n");
    data_item(text, file_, attribute.data, "          ");
    text.literal("        </Attribute>\n");
  }
  text.literal("      </Grid>\n");
  return text;
}

size_t XdmfIndex::frame_length(const Collection& collection, size_t frame) const {
  return collection.text.length(exact(times_[frame]).size(), std::to_string(frame).size());
}

template <class Out>
void XdmfIndex::write_to(Out& out) const {
  out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
  // The frames' text is made as it is written, a block at a time: the index keeps only the
  // times, and a long run's megabytes of text are never held.
  constexpr size_t kBlock = 1 << 16;
  std::string block;
  block.reserve(2 * kBlock);
  // The first grid last: the one meshio reads.
  for (size_t i = 1; i <= collections_.size(); ++i) {
    const Collection& collection = collections_[i % collections_.size()];
    out << "    <Grid Name=\"" << escaped(collection.grid.name)
        << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t frame = 0; frame < times_.size(); ++frame) {
      collection.text.append(block, exact(times_[frame]), std::to_string(frame));
      if (block.size() < kBlock && frame + 1 < times_.size()) continue;
      out << block;
      block.clear();
    }
    out << "    </Grid>\n";
  }
  out << "  </Domain>\n</Xdmf>\n";
}

std::string XdmfIndex::text() const {
  std::ostringstream out;
  write_to(out);
  return out.str();
}

void XdmfIndex::write(const std::string& path) const {
  const std::string partial = path + ".partial";
  clear_for_temporary(partial, kXdmfSignature);
  {
    __gnu_cxx::stdio_filebuf<char> file(create_new_file(partial), std::ios::out);  // closes it
    std::ostream out(&file);
    errno = 0;
    write_to(out);
    out.flush();
    if (!out || file.close() == nullptr) {
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
