#include "io/response_rows.hpp"

namespace tirefe::io {

ResponseRows::ResponseRows(Hdf5File& file, const std::string& group, const ElementResponses& responses)
    : responses_(responses), time_(&file.create_extendible(group + "time", {}, "s")) {
  const std::vector<hsize_t> row{static_cast<hsize_t>(responses.response_points())};
  for (const ResponseName& response : responses.response_names())
    rows_.push_back(&file.create_compressed_extendible(group + response.name, row, response.unit));
}

void ResponseRows::append(const State& state) {
  time_->append(state.time);
  for (size_t index = 0; index < rows_.size(); ++index) {
    responses_.response_values(static_cast<int>(index), state, values_);
    rows_[index]->append(values_.data());
  }
}

}  // namespace tirefe::io
