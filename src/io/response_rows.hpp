// ResponseRows: an element block's named responses (core/element_response.hpp) as rows of
// the result file: <group>time [s] and <group><name> for each response in its unit, one
// row per written step and one column per point of the block. The response rows are
// compressed (most contact points are open, most values zero); time is not.
#pragma once

#include <string>
#include <vector>

#include "core/element_response.hpp"
#include "io/hdf5_file.hpp"

namespace tirefe::io {

class ResponseRows {
 public:
  /// Creates the datasets under 'group' (ending in '/'); the responses must outlive the rows.
  ResponseRows(Hdf5File& file, const std::string& group, const ElementResponses& responses);
  /// Appends one row of every response at 'state' (and its time).
  void append(const State& state);

 private:
  const ElementResponses& responses_;
  ExtendibleDataset* time_;
  std::vector<ExtendibleDataset*> rows_;  // by response index
  std::vector<double> values_;
};

}  // namespace tirefe::io
