#include "deck/checkpoint.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <map>

#include "io/temporary_file.hpp"

namespace tirefe::macros {

namespace {

constexpr const char* kFormat = "tirefe checkpoint 1";

std::vector<double> to_std(const Eigen::VectorXd& vector) { return {vector.data(), vector.data() + vector.size()}; }
Eigen::VectorXd to_eigen(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

/// A tampered value for a message, to 15 digits.
std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

/// The attribute 'name' of 'object' as CarriedState::for_each_field names it ("/analysis/beta").
std::string field_path(const std::string& object, const std::string& name) {
  return (object == "/" ? "" : object) + "/" + name;
}

/// An integer attribute from 'low' to 'high': a tampered file's 1e300 or -2^31 - 1 is
/// refused, never wrapped (the counts are ints in the model).
long long integer_attribute(const io::Hdf5File& file, const std::string& object, const char* name, long long low = 0,
                            long long high = std::numeric_limits<int>::max()) {
  const double value = file.read_double_attribute(object, name);
  if (!(value >= static_cast<double>(low) && value <= static_cast<double>(high)) || value != std::floor(value))
    throw io::IoError("'" + field_path(object, name) + "' = " + number_text(value) + " is not an integer from " +
                      std::to_string(low) + " to " + std::to_string(high));
  return static_cast<long long>(value);
}

/// The number of values in a row of 'shape', or -1 if an extent is below 1 or the row
/// would hold more than INT_MAX values.
long long row_size_of(const std::vector<long long>& shape) {
  constexpr long long kMost = std::numeric_limits<int>::max();
  long long size = 1;
  for (long long extent : shape) {
    if (extent < 1 || extent > kMost / size) return -1;
    size *= extent;
  }
  return size;
}

/// Refuses a state value that is not a finite number (NaN, infinity).
template <class Values>
void require_finite(const Values& values, const std::string& path) {
  for (double value : values)
    if (!std::isfinite(value))
      throw io::IoError("'" + path + "' holds " + number_text(value) + ", not a finite number");
}

/// A field's place in the file, "/analysis/beta": the object "/analysis" and the name "beta".
std::pair<std::string, std::string> attribute_place(const std::string& path) {
  const size_t slash = path.rfind('/');
  return {slash == 0 ? "/" : path.substr(0, slash), path.substr(slash + 1)};
}

/// Writes each of the carried state's fields where CarriedState::for_each_field puts it.
struct FieldWriter {
  io::Hdf5File& file;
  void operator()(const char* path, const Eigen::VectorXd& field) const { file.write_vector(path, to_std(field)); }
  void operator()(const char* path, double field) const {
    const auto [object, name] = attribute_place(path);
    file.write_attribute(object, name, field);
  }
  void operator()(const char* path, int field) const { write_integer(path, field); }
  void operator()(const char* path, bool field) const { write_integer(path, field ? 1 : 0); }
  void write_integer(const char* path, long long field) const {
    const auto [object, name] = attribute_place(path);
    file.write_attribute(object, name, field);
  }
};

/// Reads them back.
struct FieldReader {
  const io::Hdf5File& file;
  void operator()(const char* path, Eigen::VectorXd& field) const {
    const std::vector<double> values = file.read_doubles(path);
    require_finite(values, path);
    field = to_eigen(values);
  }
  void operator()(const char* path, double& field) const {
    const auto [object, name] = attribute_place(path);
    field = file.read_double_attribute(object, name);
    require_finite(std::initializer_list<double>{field}, path);
  }
  void operator()(const char* path, int& field) const { field = static_cast<int>(read_integer(path, 0)); }
  void operator()(const char* path, bool& field) const { field = read_integer(path, 1) != 0; }
  long long read_integer(const char* path, long long high) const {
    const auto [object, name] = attribute_place(path);
    return high > 0 ? integer_attribute(file, object, name.c_str(), 0, high)
                    : integer_attribute(file, object, name.c_str());
  }
};

}  // namespace

Checkpoint capture_checkpoint(Analysis& analysis, io::ResultFile* output, int model_index, const std::string& title) {
  Checkpoint checkpoint;
  checkpoint.title = title;
  checkpoint.model_index = model_index;
  checkpoint.node_count = analysis.model().mesh().node_count();
  checkpoint.analysis = analysis.snapshot();
  for (const auto& block : analysis.model().blocks())
    checkpoint.blocks.push_back({block->name(), block->kernel_type(),
                                 static_cast<long long>(block->history_bytes_per_element()), block->size(),
                                 block->committed_history_bytes()});
  if (output) {
    checkpoint.has_output = true;
    checkpoint.steps_recorded = output->steps_recorded();
    output->flush();  // the rows still in memory
    io::Hdf5File& file = output->file();
    for (const io::ExtendibleDataset& dataset : file.extendible_datasets()) {
      SavedRows rows;
      rows.path = dataset.path();
      std::vector<hsize_t> shape;
      rows.values = file.read_doubles(dataset.path(), &shape);
      rows.rows = static_cast<long long>(shape.front());
      rows.row_shape.assign(shape.begin() + 1, shape.end());
      checkpoint.rows.push_back(std::move(rows));
    }
  }
  return checkpoint;
}

void restore_checkpoint(const Checkpoint& checkpoint, Analysis& analysis, io::ResultFile* output) {
  const Model& model = analysis.model();
  auto differs = [](const std::string& what) { return ModelError("the checkpoint is of another model: " + what); };
  if (checkpoint.node_count != model.mesh().node_count())
    throw differs("it has " + std::to_string(checkpoint.node_count) + " nodes, the deck's model " +
                  std::to_string(model.mesh().node_count()));
  if (checkpoint.blocks.size() != model.blocks().size())
    throw differs("it has " + std::to_string(checkpoint.blocks.size()) + " element blocks, the deck's model " +
                  std::to_string(model.blocks().size()));
  for (size_t b = 0; b < checkpoint.blocks.size(); ++b) {
    const SavedBlock& saved = checkpoint.blocks[b];
    const ElementBlock& block = *model.blocks()[b];
    if (saved.name != block.name() || saved.kernel_type != block.kernel_type() ||
        saved.bytes_per_element != static_cast<long long>(block.history_bytes_per_element()) ||
        saved.elements != block.size())
      throw differs("its block " + std::to_string(b + 1) + " is '" + saved.name + "' with " +
                    std::to_string(saved.elements) + " elements, the deck's is '" + block.name() + "' with " +
                    std::to_string(block.size()));
  }
  if (checkpoint.has_output != (output != nullptr))
    throw differs(checkpoint.has_output ? "it wrote a result file, the deck's model writes none"
                                        : "it wrote no result file, the deck's model does");
  analysis.model().finalize();
  analysis.restore(checkpoint.analysis);
  for (size_t b = 0; b < checkpoint.blocks.size(); ++b)
    model.blocks()[b]->set_history_bytes(checkpoint.blocks[b].history);
  if (!output) return;
  output->start(analysis.model());
  io::Hdf5File& file = output->file();
  if (file.extendible_datasets().size() != checkpoint.rows.size())
    throw differs("its result file had " + std::to_string(checkpoint.rows.size()) + " row datasets, the deck's " +
                  std::to_string(file.extendible_datasets().size()));
  for (const SavedRows& rows : checkpoint.rows) {
    io::ExtendibleDataset* dataset = file.find_extendible(rows.path);
    const long long row_size = row_size_of(rows.row_shape);
    if (!dataset || dataset->rows() != 0 || static_cast<long long>(dataset->row_size()) != row_size)
      throw differs("its result file has '" + rows.path + "' which the deck's does not write alike");
    dataset->append_rows(rows.values.data(), static_cast<hsize_t>(rows.rows));
  }
  output->set_steps_recorded(checkpoint.steps_recorded);
  output->flush();
  output->index_restored_frames();
}

namespace {
const char* const kUnfinished = ".partial";  // a checkpoint being written
}  // namespace

void remove_unfinished_checkpoint(const std::string& path) {
  io::clear_for_temporary(path + kUnfinished, io::kHdf5Signature);
}

void check_parameters(const Checkpoint& checkpoint,
                      const std::vector<std::pair<std::string, std::string>>& parameters) {
  std::map<std::string, std::string> saved(checkpoint.parameters.begin(), checkpoint.parameters.end());
  std::string differences;
  auto add = [&differences](const std::string& text) { differences += (differences.empty() ? "" : ", ") + text; };
  for (const auto& [name, value] : parameters) {
    const auto found = saved.find(name);
    if (found == saved.end())
      add(name + " = " + value + " (not in the checkpoint)");
    else if (found->second != value)
      add(name + " = " + value + " (the checkpoint's: " + found->second + ")");
    if (found != saved.end()) saved.erase(found);
  }
  for (const auto& [name, value] : saved) add(name + " missing (the checkpoint's: " + value + ")");
  if (!differences.empty())
    throw ModelError("the restart changes the parameters the checkpoint was written with: " + differences +
                     "; a restart continues the same case (give the checkpoint's values, or run without --restart)");
}

void write_checkpoint(const std::string& path, const Checkpoint& checkpoint) {
  const std::string partial = path + kUnfinished;
  io::clear_for_temporary(partial, io::kHdf5Signature);
  {
    io::Hdf5File file = io::Hdf5File::create_new(partial);
    file.write_attribute("/", "title", checkpoint.title);
    file.write_attribute("/", "model_index", checkpoint.model_index);
    file.write_attribute("/", "node_count", checkpoint.node_count);
    CarriedState::for_each_field(checkpoint.analysis, FieldWriter{file});
    file.write_attribute("/blocks", "count", static_cast<long long>(checkpoint.blocks.size()));
    for (size_t b = 0; b < checkpoint.blocks.size(); ++b) {
      const SavedBlock& block = checkpoint.blocks[b];
      const std::string group = "/blocks/" + std::to_string(b);
      file.write_bytes(group + "/history", block.history);
      file.write_attribute(group, "name", block.name);
      file.write_attribute(group, "kernel_type", block.kernel_type);
      file.write_attribute(group, "bytes_per_element", block.bytes_per_element);
      file.write_attribute(group, "elements", block.elements);
    }
    file.write_attribute("/rows", "has_output", static_cast<long long>(checkpoint.has_output));
    file.write_attribute("/rows", "steps_recorded", checkpoint.steps_recorded);
    file.write_attribute("/rows", "count", static_cast<long long>(checkpoint.rows.size()));
    for (size_t r = 0; r < checkpoint.rows.size(); ++r) {
      const SavedRows& rows = checkpoint.rows[r];
      const std::string group = "/rows/" + std::to_string(r);
      file.write_vector(group + "/values", rows.values);
      file.write_int_vector(group + "/row_shape", rows.row_shape);
      file.write_attribute(group, "path", rows.path);
      file.write_attribute(group, "rows", rows.rows);
    }
    if (!checkpoint.parameters.empty()) {
      std::vector<std::string> names, values;
      for (const auto& [name, value] : checkpoint.parameters) {
        names.push_back(name);
        values.push_back(value);
      }
      file.write_strings("/parameters/names", names);
      file.write_strings("/parameters/values", values);
    }
    // Written last: a file without it is incomplete.
    file.write_attribute("/", "format", std::string(kFormat));
    file.close();  // a close that fails (a full disk) leaves the checkpoint unfinished
  }
  std::error_code error;
  std::filesystem::rename(partial, path, error);
  if (error) throw io::IoError("cannot write checkpoint '" + path + "': " + error.message());
}

Checkpoint read_checkpoint(const std::string& path) {
  const std::string unfinished = kUnfinished;
  if (path.size() > unfinished.size() &&
      path.compare(path.size() - unfinished.size(), unfinished.size(), unfinished) == 0)
    throw io::IoError("restart file '" + path + "' is a checkpoint a run did not finish writing; restart from '" +
                      path.substr(0, path.size() - unfinished.size()) + "'");
  if (!std::filesystem::exists(path)) throw io::IoError("restart file '" + path + "' does not exist");
  try {
    const io::Hdf5File file = io::Hdf5File::open_read_only(path);
    if (!file.exists("/analysis") || file.read_string_attribute("/", "format") != kFormat)
      throw io::IoError("no checkpoint written by this tirefe");
    Checkpoint checkpoint;
    checkpoint.title = file.read_string_attribute("/", "title");
    checkpoint.model_index = static_cast<int>(integer_attribute(file, "/", "model_index", 1));
    checkpoint.node_count = static_cast<int>(integer_attribute(file, "/", "node_count"));
    CarriedState::for_each_field(checkpoint.analysis, FieldReader{file});
    for (const auto& [path, step] : {std::pair{"/analysis/nominal_step", checkpoint.analysis.steps.nominal},
                                     std::pair{"/analysis/current_step", checkpoint.analysis.steps.current}})
      if (!(step > 0.0))
        throw io::IoError(std::string("'") + path + "' = " + number_text(step) + " is no step size > 0");
    const long long blocks = integer_attribute(file, "/blocks", "count");
    for (long long b = 0; b < blocks; ++b) {
      const std::string group = "/blocks/" + std::to_string(b);
      checkpoint.blocks.push_back({file.read_string_attribute(group, "name"),
                                   file.read_string_attribute(group, "kernel_type"),
                                   integer_attribute(file, group, "bytes_per_element"),
                                   integer_attribute(file, group, "elements"), file.read_bytes(group + "/history")});
    }
    checkpoint.has_output = integer_attribute(file, "/rows", "has_output", 0, 1) != 0;
    checkpoint.steps_recorded = static_cast<int>(integer_attribute(file, "/rows", "steps_recorded"));
    const long long row_sets = integer_attribute(file, "/rows", "count");
    for (long long r = 0; r < row_sets; ++r) {
      const std::string group = "/rows/" + std::to_string(r);
      SavedRows rows;
      rows.path = file.read_string_attribute(group, "path");
      rows.rows = integer_attribute(file, group, "rows");
      rows.row_shape = file.read_ints(group + "/row_shape");
      rows.values = file.read_doubles(group + "/values");
      const long long values = static_cast<long long>(rows.values.size());
      const long long row_size = row_size_of(rows.row_shape);
      if (row_size < 0 || values % row_size != 0 || values / row_size != rows.rows)
        throw io::IoError("rows of '" + rows.path + "' are incomplete");
      // Every row of a result file has its time: the rows of a run nobody tampered with.
      if (rows.path == "/history/time") require_finite(rows.values, "/rows/" + std::to_string(r) + "/values");
      checkpoint.rows.push_back(std::move(rows));
    }
    if (file.exists("/parameters/names")) {
      const std::vector<std::string> names = file.read_strings("/parameters/names");
      const std::vector<std::string> values = file.read_strings("/parameters/values");
      if (names.size() != values.size()) throw io::IoError("its parameters are incomplete");
      for (size_t i = 0; i < names.size(); ++i) checkpoint.parameters.emplace_back(names[i], values[i]);
    }
    return checkpoint;
  } catch (const io::IoError& error) {
    throw io::IoError("restart file '" + path + "' is not a readable checkpoint (" + error.what() + ")");
  }
}

}  // namespace tirefe::macros
