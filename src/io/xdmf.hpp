// XDMF 3 index of a result file's field frames (<stem>.xmf beside <stem>.h5), read by
// ParaView ("Xdmf3 Reader (S)" and "(T)") and by meshio (meshio.xdmf.TimeSeriesReader).
// The index holds no numbers: every DataItem names one whole dataset of the HDF5 file, by
// the file's name (relative to the index's folder) and the dataset's path.
//
// Layout: one temporal collection per grid, holding one uniform grid per frame with its
// Time, Topology, Geometry (XY) and Attributes. The first grid added (the model's mesh) is
// written last, because meshio's TimeSeriesReader reads the last collection only and takes
// its first frame's topology and geometry as the mesh. What the readers accept, and so
// what is written:
//   - ParaView 5.11 drops grids outside a temporal collection when others have times, and
//     fails on HyperSlab and Function DataItems: hence whole datasets, a collection each;
//   - meshio reads HDF DataItems whole (no slabs), one Topology per grid, and in a Mixed
//     topology a vertex as "1 node" where XDMF wants "1 count nodes": point-like blocks
//     are grids of their own (Polyvertex), never part of a Mixed topology.
#pragma once

#include <string>
#include <vector>

namespace tirefe::io {

/// The first bytes of every XDMF index tirefe writes.
extern const char* const kXdmfSignature;

/// A dataset of the HDF5 file. In a path, "{frame}" stands for the frame's number.
struct XdmfData {
  std::string path;
  std::vector<long long> dimensions;
  bool integer = false;  // 8-byte integers, else 8-byte floats
};

struct XdmfAttribute {
  std::string name;
  std::string type;    // "Scalar" or "Vector"
  std::string centre;  // "Node" or "Cell"
  XdmfData data;
};

struct XdmfGrid {
  std::string name;
  std::string topology;  // XDMF TopologyType: "Mixed", "Polyvertex", "Polyline", ...
  long long cells = 0;
  int nodes_per_cell = 0;  // written for Polyvertex and Polyline
  XdmfData connectivity;
  XdmfData geometry;  // points x 2
  std::vector<XdmfAttribute> attributes;
};

/// A grid's frame as text with holes: the frame's time and its number (in dataset paths),
/// so that each frame costs a few appends, not a formatting.
class FrameText {
 public:
  enum class Hole { time, frame };
  void literal(const std::string& text);
  void hole(Hole hole);
  /// The text with 'time' and 'frame' in its holes, appended to 'out'.
  void append(std::string& out, const std::string& time, const std::string& frame) const;
  /// Its length with a time and a frame number of these lengths in the holes.
  size_t length(size_t time, size_t frame) const;

 private:
  std::vector<std::string> pieces_{1};  // one more than the holes: the text around them
  std::vector<Hole> holes_;
};

class XdmfIndex {
 public:
  /// 'hdf5_file_name': the HDF5 file as the index names it (beside the index).
  explicit XdmfIndex(std::string hdf5_file_name);

  /// Adds a grid shown at every frame, the frames so far included.
  void add_grid(const XdmfGrid& grid);
  /// Adds a frame at 'time' to every grid.
  void add_frame(double time);
  size_t frames() const { return times_.size(); }
  const std::vector<double>& times() const { return times_; }
  bool empty() const { return collections_.empty() || times_.empty(); }
  /// The bytes of the frames' text: nearly all of text().
  size_t size() const { return bytes_; }

  std::string text() const;
  /// Writes text() beside 'path' and renames it to 'path', so the index there is always
  /// whole (a run killed while writing keeps the previous one). Throws IoError.
  void write(const std::string& path) const;

 private:
  struct Collection {
    XdmfGrid grid;
    FrameText text;  // one frame's XML
  };
  FrameText frame_text(const XdmfGrid& grid) const;
  size_t frame_length(const Collection& collection, size_t frame) const;
  template <class Out>
  void write_to(Out& out) const;

  std::string file_;
  std::vector<Collection> collections_;
  std::vector<double> times_;
  size_t bytes_ = 0;  // of the frames' text
};

}  // namespace tirefe::io
