// Tests of the XDMF index written beside result files with field frames.
#include <catch2/catch.hpp>

#include <regex>
#include <string>

#include "io/xdmf.hpp"

using tirefe::io::XdmfFields;
using tirefe::io::xdmf_text;

namespace {

int count(const std::string& text, const std::string& pattern) {
  const std::regex expression(pattern);
  return static_cast<int>(std::distance(std::sregex_iterator(text.begin(), text.end(), expression),
                                        std::sregex_iterator()));
}

}  // namespace

TEST_CASE("XDMF index: one spatial collection per frame, one grid per distinct block", "[io][xdmf]") {
  XdmfFields fields;
  fields.hdf5_file_name = "run.h5";
  fields.nodes = 101;
  // A tire: tread beams and pressure share a shape (drawn once), wedges are triangles,
  // the rim is a point element, a 5-node block has no XDMF cell type and is left out.
  fields.blocks = {{"tire_tread", 100, 2}, {"tire_sidewall", 100, 3}, {"tire_pressure", 100, 2},
                   {"tire_rim", 1, 1}, {"odd", 3, 5}};
  fields.frame_times = {0.0, 0.005, 0.01};
  const std::string text = xdmf_text(fields);

  CHECK(count(text, "CollectionType=\"Temporal\"") == 1);
  CHECK(count(text, "<Time Value=") == 3);
  CHECK(count(text, "<Time Value=\"0.0050000000000000001\" />") == 1);
  CHECK(count(text, "TopologyType=\"Polyline\" NumberOfElements=\"100\" NodesPerElement=\"2\"") == 3);
  CHECK(count(text, "TopologyType=\"Triangle\" NumberOfElements=\"100\"") == 3);
  CHECK(count(text, "TopologyType=\"Polyvertex\" NumberOfElements=\"1\"") == 3);
  CHECK(count(text, "tire_pressure") == 0);
  CHECK(count(text, "odd") == 0);
  // Geometry = coordinates + the frame's (u_x, u_y) slab; frame 2 starts at row 2.
  CHECK(count(text, "run.h5:/mesh/coordinates") == 9);
  CHECK(count(text, ">2 0 0  1 1 1  1 101 2<") == 3);
  CHECK(count(text, "Dimensions=\"3 101 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">run.h5:/fields/displacement") ==
        3 * 3 * 4);
  CHECK(count(text, "<Attribute Name=\"theta_z\"") == 9);
}
