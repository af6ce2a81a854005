// Beam meshes built in C++: a straight line of TreadBeam elements (test cantilevers,
// the tread of a flat-track model) and a closed ring (the belt of a tire, the free ring
// whose modes have closed forms). Each call adds new nodes and one element block.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "elements/tread_beam.hpp"

namespace tirefe {

/// 'elements' beams from 'start' to 'end' through elements + 1 evenly spaced new
/// nodes; returns the node ids, start first.
std::vector<int> add_beam_line(Model& model, const std::string& block_name, const Eigen::Vector2d& start,
                               const Eigen::Vector2d& end, int elements, const BeamSection& section);

/// A closed ring of 'elements' beams: new node k sits at angle 2 pi k / elements
/// (counter-clockwise from +x) on the circle of 'radius' about 'center', and beam k
/// joins node k to node k + 1 (mod elements). Returns the node ids in that order.
std::vector<int> add_beam_ring(Model& model, const std::string& block_name, const Eigen::Vector2d& center,
                               double radius, int elements, const BeamSection& section);

}  // namespace tirefe
