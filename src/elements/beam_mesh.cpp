#include "elements/beam_mesh.hpp"

#include <cmath>

namespace tirefe {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;

/// Joins consecutive nodes (and the last to the first when closed) with beams.
void add_beams(Model& model, const std::string& block_name, const std::vector<int>& nodes, bool closed,
               const BeamSection& section) {
  auto& beams = model.add_block<TreadBeam>(block_name);
  const int count = static_cast<int>(nodes.size());
  for (int k = 0; k + 1 < count + (closed ? 1 : 0); ++k) {
    const int a = nodes[k], b = nodes[(k + 1) % count];
    beams.add({a, b}, TreadBeam(model.mesh().position(a), model.mesh().position(b), section));
  }
}

void require_elements(int elements, int minimum, const char* what) {
  if (elements < minimum)
    throw ModelError(std::string(what) + " needs at least " + std::to_string(minimum) + " elements (got " +
                     std::to_string(elements) + ")");
}

}  // namespace

std::vector<int> add_beam_line(Model& model, const std::string& block_name, const Eigen::Vector2d& start,
                               const Eigen::Vector2d& end, int elements, const BeamSection& section) {
  require_elements(elements, 1, "a beam line");
  std::vector<int> nodes;
  for (int k = 0; k <= elements; ++k)
    nodes.push_back(model.mesh().add_node(start + (end - start) * (static_cast<double>(k) / elements)));
  add_beams(model, block_name, nodes, false, section);
  return nodes;
}

std::vector<int> add_beam_ring(Model& model, const std::string& block_name, const Eigen::Vector2d& center,
                               double radius, int elements, const BeamSection& section) {
  require_elements(elements, 3, "a beam ring");
  if (!(radius > 0.0)) throw ModelError("a beam ring needs a positive radius (got " + std::to_string(radius) + ")");
  std::vector<int> nodes;
  for (int k = 0; k < elements; ++k) {
    const double angle = kTwoPi * k / elements;
    nodes.push_back(model.mesh().add_node(center + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle))));
  }
  add_beams(model, block_name, nodes, true, section);
  return nodes;
}

}  // namespace tirefe
