// HDF5 output layer implementation (HDF5 1.10 C API). Negative HDF5 return codes become
// IoError carrying the innermost HDF5 error description; automatic stack printing is off.
#include "io/hdf5_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <numeric>
#include <utility>

#include "io/temporary_file.hpp"

namespace tirefe::io {

const char* const kHdf5Signature = "\x89HDF\r\n\x1a\n";

namespace {

// The innermost entry of the HDF5 error stack is the most specific one, reduced to one
// line: a failed read or write describes itself over lines (a time stamp, buffers,
// offsets) around the system's message, and that message alone says what to do.
std::string hdf5_error_detail() {
  std::string detail;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* error, void* out) -> herr_t {
        if (n == 0 && error->desc != nullptr) *static_cast<std::string*>(out) = error->desc;
        return 0;
      },
      &detail);
  H5Eclear2(H5E_DEFAULT);
  const std::string system_marker = "error message = '";
  const size_t system_message = detail.find(system_marker);
  if (system_message != std::string::npos) {
    const size_t start = system_message + system_marker.size();
    detail = detail.substr(start, detail.find('\'', start) - start);
  }
  std::replace_if(
      detail.begin(), detail.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return detail.empty() ? "HDF5 error" : detail;
}

std::string system_error(const std::string& action) { return action + ": " + std::strerror(errno); }

// Copies the file 'from' to the new file 'to' whole, in the kernel where it can (no pass
// through this process; a reflink on file systems that share blocks). A failed copy is removed.
void copy_file(const std::string& from, const std::string& to) {
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) throw IoError(system_error("cannot read '" + from + "'"));
  int out = -1;
  try {
    out = create_new_file(to);
  } catch (const IoError&) {
    ::close(in);
    throw;
  }
  struct stat status {};
  bool copied = ::fstat(in, &status) == 0;
  for (off_t left = status.st_size; copied && left > 0;) {
    ssize_t moved = ::copy_file_range(in, nullptr, out, nullptr, static_cast<size_t>(left), 0);
    if (moved < 0 && (errno == EXDEV || errno == ENOSYS || errno == EINVAL || errno == EOPNOTSUPP)) {
      char buffer[1 << 16];  // no kernel copy between these files: through a buffer
      moved = ::read(in, buffer, sizeof buffer);
      for (ssize_t written = 0; moved > 0 && written < moved;) {
        const ssize_t n = ::write(out, buffer + written, static_cast<size_t>(moved - written));
        if (n < 0) moved = -1;
        written += n;
      }
    }
    copied = moved > 0;
    left -= moved;
  }
  std::string failure = copied ? "" : system_error("cannot write '" + to + "'");
  ::close(in);
  if (::close(out) != 0 && failure.empty()) failure = system_error("cannot write '" + to + "'");
  if (failure.empty()) return;
  ::unlink(to.c_str());
  throw IoError(failure);
}

std::string describe(const std::string& action, const std::string& object, const std::string& file) {
  return "cannot " + action + " '" + object + "' in '" + file + "'";
}

// `message` is only evaluated on failure, so hot paths build no strings.
template <class T, class Message>
T check(T rc, Message&& message) {
  if (rc < 0) throw IoError(message() + ": " + hdf5_error_detail());
  return rc;
}

// HDF5 closes what is still open when the process exits, and crashes on a file whose
// flush failed (HDF5 1.10.8, a full disk): every file here is closed by its owner, so the
// library is left to the exit. Set before the library starts (static initialization).
[[maybe_unused]] const bool kNoCloseAtExit = H5dont_atexit() >= 0;

constexpr size_t kMetadataCacheBytes = 128 * 1024;

Hdf5Handle make_fapl(const std::string& path) {
  auto message = [&] { return "cannot set up file access for '" + path + "'"; };
  Hdf5Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), message), H5Pclose);
  // V18 superblock/object format: readable by h5py 3.7 / HDF5 1.10, and it has no
  // "file open for write" flag, so h5dump can read a flushed file while we still write it.
  check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V110), message);
  check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), message);
  // A small metadata cache of fixed size. HDF5's own grows with the objects a file holds
  // (a long run's thousands of frame views: some 90 MB) and costs time as it grows. A cache
  // this small writes metadata whenever it evicts, in any call: a full disk can fail any
  // call (FailureLatch).
  H5AC_cache_config_t cache{};
  cache.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  check(H5Pget_mdc_config(fapl.get(), &cache), message);
  cache.set_initial_size = true;
  cache.initial_size = cache.min_size = cache.max_size = kMetadataCacheBytes;
  cache.incr_mode = H5C_incr__off;
  cache.flash_incr_mode = H5C_flash_incr__off;
  cache.decr_mode = H5C_decr__off;
  check(H5Pset_mdc_config(fapl.get(), &cache), message);
#if (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 10 && H5_VERS_RELEASE >= 7) || H5_VERSION_GE(1, 12, 1)
  // No flock(): live monitoring (h5dump/h5py on a running job) must not be locked out.
  check(H5Pset_file_locking(fapl.get(), false, true), message);
#endif
  return fapl;
}

// Variable-length UTF-8: h5py 3 reads such attributes as str (fixed-length ones as bytes).
Hdf5Handle make_string_type() {
  auto message = [] { return std::string("cannot create string type"); };
  Hdf5Handle type(check(H5Tcopy(H5T_C_S1), message), H5Tclose);
  check(H5Tset_size(type.get(), H5T_VARIABLE), message);
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), message);
  return type;
}

Hdf5Handle dataspace_of(const std::vector<hsize_t>& dims) {
  const hid_t id =
      dims.empty() ? H5Screate(H5S_SCALAR) : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  return Hdf5Handle(check(id, [] { return std::string("cannot create dataspace"); }), H5Sclose);
}

hsize_t element_count(const std::vector<hsize_t>& dims) {
  return std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
}

// Reads `count` strings of attribute or dataset `object` with file type `file_type`; `read`
// performs H5Aread/H5Dread into a buffer for the given memory type and checks it. Handles
// both variable-length and fixed-length strings (files written by other tools).
template <class Read, class Message>
std::vector<std::string> read_string_elements(hid_t file_type, hsize_t count, Read&& read, Message&& message) {
  if (check(H5Tget_class(file_type), message) != H5T_STRING) throw IoError(message() + ": not a string");
  std::vector<std::string> result;
  result.reserve(count);
  if (check(H5Tis_variable_str(file_type), message) > 0) {
    Hdf5Handle mem_type = make_string_type();
    std::vector<char*> buffer(count, nullptr);
    read(mem_type.get(), buffer.data());
    for (char* s : buffer) {
      result.emplace_back(s != nullptr ? s : "");
      H5free_memory(s);
    }
    return result;
  }
  const size_t size = H5Tget_size(file_type);
  Hdf5Handle mem_type(check(H5Tcopy(file_type), message), H5Tclose);
  std::vector<char> buffer(count * size);
  read(mem_type.get(), buffer.data());
  const bool space_padded = H5Tget_strpad(file_type) == H5T_STR_SPACEPAD;
  for (hsize_t i = 0; i < count; ++i) {
    const char* s = buffer.data() + i * size;
    std::string value(s, strnlen(s, size));
    if (space_padded) value.erase(value.find_last_not_of(' ') + 1);
    result.push_back(std::move(value));
  }
  return result;
}

template <class Message>
Hdf5Handle open_single_value_attribute(hid_t file, const std::string& object_path, const std::string& name,
                                       FailureLatch& latch, Message&& message) {
  Hdf5Handle attribute(
      latch.check(H5Aopen_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), message),
      H5Aclose);
  Hdf5Handle space(latch.check(H5Aget_space(attribute.get()), message), H5Sclose);
  if (latch.check(H5Sget_simple_extent_npoints(space.get()), message) != 1)
    throw IoError(message() + ": not a single value");
  return attribute;
}

}  // namespace

// --- Hdf5Handle -------------------------------------------------------------------------

Hdf5Handle::Hdf5Handle(Hdf5Handle&& other) noexcept
    : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}

Hdf5Handle& Hdf5Handle::operator=(Hdf5Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = std::exchange(other.id_, H5I_INVALID_HID);
    closer_ = other.closer_;
  }
  return *this;
}

hid_t Hdf5Handle::release() noexcept { return std::exchange(id_, H5I_INVALID_HID); }

herr_t Hdf5Handle::close() {
  const hid_t id = release();
  return id >= 0 && closer_ != nullptr ? closer_(id) : 0;
}

void Hdf5Handle::reset() noexcept {
  if (id_ >= 0 && closer_ != nullptr) closer_(id_);  // failure is ignored: destructors must not throw
  id_ = H5I_INVALID_HID;
}

// --- FailureLatch ------------------------------------------------------------------------

void FailureLatch::fail(const std::string& message) {
  failed_ = true;
  throw IoError(message + ": " + hdf5_error_detail());
}

void FailureLatch::refuse(const std::string& message) const {
  throw IoError(message + ": an earlier write to '" + file_path_ + "' failed");
}

// --- ExtendibleDataset --------------------------------------------------------------------

ExtendibleDataset::ExtendibleDataset(Hdf5Handle dataset, std::vector<hsize_t> dims, FailureLatch& latch,
                                     std::string path)
    : dataset_(std::move(dataset)),
      dims_(std::move(dims)),
      start_(dims_.size(), 0),
      count_(dims_),
      rows_(dims_[0]),
      latch_(&latch),
      path_(std::move(path)) {
  count_[0] = 1;
  row_size_ = static_cast<size_t>(element_count(count_));
  scalar_rows_ = dims_.size() == 1;
  file_space_ = Hdf5Handle(
      latch.check(H5Dget_space(dataset_.get()), [&] { return describe("open dataset", path_, latch.file_path()); }),
      H5Sclose);
  mem_space_ = dataspace_of({static_cast<hsize_t>(row_size_)});
}

void ExtendibleDataset::close() {
  file_space_.reset();
  mem_space_.reset();
  latch_->check(dataset_.close(), [&] { return describe("close dataset", path_, latch_->file_path()); });
}

void ExtendibleDataset::append(const double* row_values) {
  pending_.insert(pending_.end(), row_values, row_values + row_size_);
  ++rows_;
}

void ExtendibleDataset::append(double scalar) {
  if (!scalar_rows_) {
    throw IoError(describe("append a scalar to dataset", path_, latch_->file_path()) + ": rows are not scalars");
  }
  append(&scalar);
}

void ExtendibleDataset::stage() {
  if (staged_.empty()) {
    staged_.swap(pending_);  // the buffers trade places: neither is reallocated
  } else {
    staged_.insert(staged_.end(), pending_.begin(), pending_.end());
  }
  pending_.clear();
}

void ExtendibleDataset::write_staged() {
  if (staged_.empty()) return;
  std::vector<double> rows;
  rows.swap(staged_);  // written or not, they are not written twice
  write_rows(rows.data(), static_cast<hsize_t>(rows.size() / row_size_));
  rows.clear();
  staged_.swap(rows);  // its capacity, for the next flush
}

void ExtendibleDataset::append_rows(const double* values, hsize_t rows) {
  if (rows == 0) return;
  stage();  // in order
  write_staged();
  write_rows(values, rows);
  rows_ += rows;
}

void ExtendibleDataset::write_rows(const double* values, hsize_t rows) {
  auto message = [&] { return describe("append rows to dataset", path_, latch_->file_path()); };
  latch_->refuse_if_failed(message);
  std::vector<hsize_t> dims = dims_, start(dims_.size(), 0), count = count_;
  start[0] = dims_[0];
  dims[0] += rows;
  count[0] = rows;
  // The memory the shape of the file's selection: HDF5 maps a selection of the same shape
  // onto the chunks whole, one of another shape value by value.
  Hdf5Handle memory = dataspace_of(count);
  const int rank = static_cast<int>(dims.size());
  latch_->check(H5Dset_extent(dataset_.get(), dims.data()), message);
  dims_ = dims;
  latch_->check(H5Sset_extent_simple(file_space_.get(), rank, dims_.data(), nullptr), message);
  latch_->check(H5Sselect_hyperslab(file_space_.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
                message);
  latch_->check(H5Dwrite(dataset_.get(), H5T_NATIVE_DOUBLE, memory.get(), file_space_.get(), H5P_DEFAULT, values),
                message);
}

void silence_hdf5_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {
// The new file 'path' (H5Fcreate with 'flags'); 'failure' says what could not be done.
Hdf5Handle create_file(const std::string& path, unsigned flags, const std::string& failure) {
  silence_hdf5_errors();
  Hdf5Handle fapl = make_fapl(path);
  const hid_t id = H5Fcreate(path.c_str(), flags, H5P_DEFAULT, fapl.get());
  check(id, [&] { return failure; });
  return Hdf5Handle(id, H5Fclose);
}
}  // namespace

// --- Hdf5File ------------------------------------------------------------------------------

Hdf5File::Hdf5File(std::string path, Hdf5Handle file)
    : path_(std::move(path)), file_(std::move(file)), latch_(std::make_unique<FailureLatch>(path_)) {
  auto message = [&] { return "cannot set up link creation for '" + path_ + "'"; };
  lcpl_ = Hdf5Handle(check(H5Pcreate(H5P_LINK_CREATE), message), H5Pclose);
  check(H5Pset_create_intermediate_group(lcpl_.get(), 1), message);
}

Hdf5File Hdf5File::create(const std::string& path) {
  return Hdf5File(path, create_file(path, H5F_ACC_TRUNC, "cannot create output file '" + path + "'"));
}

Hdf5File Hdf5File::create_new(const std::string& path) {
  // O_EXCL: the creation fails on anything there, a symbolic link included.
  return Hdf5File(path, create_file(path, H5F_ACC_EXCL, "cannot create '" + path + "'"));
}

Hdf5File Hdf5File::create_published(const std::string& path) {
  const std::string working = path + ".partial";
  for (const std::string& leftover : {working, working + ".copy"}) clear_for_temporary(leftover, kHdf5Signature);
  Hdf5File file(path, create_file(working, H5F_ACC_EXCL,
                                  "cannot create output file '" + path + "' (written as '" + working + "')"));
  file.working_path_ = working;
  return file;
}

Hdf5File Hdf5File::create_in_memory(const std::string& name) {
  silence_hdf5_errors();
  Hdf5Handle fapl = make_fapl(name);
  // The core driver without a backing store: the file lives in memory and is never written.
  check(H5Pset_fapl_core(fapl.get(), 64 * 1024, false), [&] { return "cannot keep '" + name + "' in memory"; });
  const hid_t id = H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  check(id, [&] { return "cannot create the in-memory file '" + name + "'"; });
  return Hdf5File(name, Hdf5Handle(id, H5Fclose));
}

namespace {
Hdf5Handle open_file(const std::string& path, unsigned flags) {
  silence_hdf5_errors();
  Hdf5Handle fapl = make_fapl(path);
  const hid_t id = H5Fopen(path.c_str(), flags, fapl.get());
  check(id, [&] { return "cannot open file '" + path + "'"; });
  return Hdf5Handle(id, H5Fclose);
}
}  // namespace

Hdf5File Hdf5File::open_read_only(const std::string& path) { return Hdf5File(path, open_file(path, H5F_ACC_RDONLY)); }

Hdf5File Hdf5File::open_read_write(const std::string& path) { return Hdf5File(path, open_file(path, H5F_ACC_RDWR)); }

Hdf5File Hdf5File::open_published(const std::string& path) {
  const std::string working = path + ".partial";
  for (const std::string& leftover : {working, working + ".copy"}) clear_for_temporary(leftover, kHdf5Signature);
  open_file(path, H5F_ACC_RDONLY);  // an HDF5 file, named as such, before it is copied
  copy_file(path, working);
  try {
    Hdf5File file(path, open_file(working, H5F_ACC_RDWR));
    file.working_path_ = working;
    return file;
  } catch (const IoError&) {
    std::remove(working.c_str());
    throw;
  }
}

Hdf5File::Hdf5File(Hdf5File&& other) noexcept
    : path_(std::move(other.path_)),
      working_path_(std::move(other.working_path_)),
      file_(std::move(other.file_)),
      latch_(std::move(other.latch_)),
      lcpl_(std::move(other.lcpl_)),
      datasets_(std::move(other.datasets_)) {}

Hdf5File& Hdf5File::operator=(Hdf5File&& other) noexcept {
  // Swap, so our old datasets and file are closed (datasets first) when `other` dies.
  std::swap(path_, other.path_);
  std::swap(working_path_, other.working_path_);
  std::swap(file_, other.file_);
  std::swap(latch_, other.latch_);
  std::swap(lcpl_, other.lcpl_);
  std::swap(datasets_, other.datasets_);
  return *this;
}

Hdf5File::~Hdf5File() {
  try {
    close();
  } catch (const std::exception&) {  // a full disk: the rows already written stay readable
  }
}

void Hdf5File::close() {
  if (file_.get() < 0) return;
  const bool reported = failed();  // by the call that failed
  std::string failure;
  try {
    if (!reported) {
      for (ExtendibleDataset& dataset : datasets_) {
        dataset.stage();
        dataset.write_staged();
      }
      for (ExtendibleDataset& dataset : datasets_) dataset.close();
    }
  } catch (const IoError& error) {
    failure = error.what();
  }
  datasets_.clear();
  lcpl_.reset();
  if (H5Fclose(file_.release()) < 0 && failure.empty()) {
    latch_->mark();
    failure = "cannot close '" + path_ + "': " + hdf5_error_detail();
  }
  if (reported) {
    H5Eclear2(H5E_DEFAULT);
    if (!working_path_.empty()) std::remove(working_path_.c_str());
    return;
  }
  if (working_path_.empty()) {
    if (!failure.empty()) throw IoError(failure);
    return;
  }
  // A published file that could not be completed keeps its last whole copy.
  if (failure.empty() && std::rename(working_path_.c_str(), path_.c_str()) != 0)
    failure = system_error("cannot rename '" + working_path_ + "' to '" + path_ + "'");
  if (!failure.empty()) {
    std::remove(working_path_.c_str());
    throw IoError(failure);
  }
}

void Hdf5File::write_scalar_attribute(const std::string& object_path, const std::string& name, hid_t file_type,
                                      hid_t mem_type, const void* data) {
  auto message = [&] { return describe("write attribute '" + name + "' of", object_path, path_); };
  latch_->refuse_if_failed(message);
  const hid_t file = file_.get();
  const hid_t id = exists(object_path) ? H5Oopen(file, object_path.c_str(), H5P_DEFAULT)
                                       : H5Gcreate2(file, object_path.c_str(), lcpl_.get(), H5P_DEFAULT, H5P_DEFAULT);
  FailureLatch& latch = *latch_;
  Hdf5Handle object(latch.check(id, message), H5Oclose);
  if (latch.check(H5Aexists(object.get(), name.c_str()), message) > 0)
    latch.check(H5Adelete(object.get(), name.c_str()), message);
  Hdf5Handle space = dataspace_of({});
  Hdf5Handle attribute(
      latch.check(H5Acreate2(object.get(), name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), message),
      H5Aclose);
  latch.check(H5Awrite(attribute.get(), mem_type, data), message);
  latch.check(attribute.close(), message);
  latch.check(object.close(), message);
}

void Hdf5File::write_attribute(const std::string& object_path, const std::string& name, const std::string& value) {
  Hdf5Handle type = make_string_type();
  const char* text = value.c_str();
  write_scalar_attribute(object_path, name, type.get(), type.get(), &text);
}

void Hdf5File::write_attribute(const std::string& object_path, const std::string& name, double value) {
  write_scalar_attribute(object_path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void Hdf5File::write_attribute(const std::string& object_path, const std::string& name, long long value) {
  write_scalar_attribute(object_path, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, &value);
}

std::string Hdf5File::read_string_attribute(const std::string& object_path, const std::string& name) const {
  auto message = [&] { return describe("read attribute '" + name + "' of", object_path, path_); };
  Hdf5Handle attribute = open_single_value_attribute(file_.get(), object_path, name, *latch_, message);
  Hdf5Handle type(latch_->check(H5Aget_type(attribute.get()), message), H5Tclose);
  auto read = [&](hid_t mem_type, void* buffer) { latch_->check(H5Aread(attribute.get(), mem_type, buffer), message); };
  return read_string_elements(type.get(), 1, read, message).front();
}

double Hdf5File::read_double_attribute(const std::string& object_path, const std::string& name) const {
  auto message = [&] { return describe("read attribute '" + name + "' of", object_path, path_); };
  Hdf5Handle attribute = open_single_value_attribute(file_.get(), object_path, name, *latch_, message);
  double value = 0.0;
  latch_->check(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value), message);  // converts integer attributes too
  return value;
}

void Hdf5File::write_dataset(const std::string& dataset_path, const std::vector<hsize_t>& dims, hid_t file_type,
                             hid_t mem_type, const void* data) {
  auto message = [&] { return describe("write dataset", dataset_path, path_); };
  latch_->refuse_if_failed(message);
  Hdf5Handle space = dataspace_of(dims);
  Hdf5Handle dataset(latch_->check(H5Dcreate2(file_.get(), dataset_path.c_str(), file_type, space.get(), lcpl_.get(),
                                              H5P_DEFAULT, H5P_DEFAULT),
                                   message),
                     H5Dclose);
  if (element_count(dims) > 0)
    latch_->check(H5Dwrite(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), message);
  latch_->check(dataset.close(), message);
}

void Hdf5File::write_matrix(const std::string& dataset_path, const Eigen::MatrixXd& values) {
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major = values;
  write_dataset(dataset_path, {static_cast<hsize_t>(values.rows()), static_cast<hsize_t>(values.cols())},
                H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, row_major.data());
}

void Hdf5File::write_vector(const std::string& dataset_path, const std::vector<double>& values) {
  write_dataset(dataset_path, {values.size()}, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, values.data());
}

void Hdf5File::write_int_vector(const std::string& dataset_path, const std::vector<long long>& values) {
  write_dataset(dataset_path, {values.size()}, H5T_STD_I64LE, H5T_NATIVE_LLONG, values.data());
}

void Hdf5File::write_int_matrix(const std::string& dataset_path, hsize_t rows, hsize_t cols, const long long* data) {
  write_dataset(dataset_path, {rows, cols}, H5T_STD_I64LE, H5T_NATIVE_LLONG, data);
}

void Hdf5File::write_strings(const std::string& dataset_path, const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const std::string& value : values) pointers.push_back(value.c_str());
  Hdf5Handle type = make_string_type();
  write_dataset(dataset_path, {values.size()}, type.get(), type.get(), pointers.data());
}

void Hdf5File::write_string_dataset(const std::string& dataset_path, const std::string& text) {
  const char* pointer = text.c_str();
  Hdf5Handle type = make_string_type();
  write_dataset(dataset_path, {}, type.get(), type.get(), &pointer);
}

ExtendibleDataset& Hdf5File::create_extendible(const std::string& dataset_path, const std::vector<hsize_t>& row_shape,
                                               const std::string& unit) {
  return create_chunked(dataset_path, row_shape, unit, false);
}

ExtendibleDataset& Hdf5File::create_compressed_extendible(const std::string& dataset_path,
                                                          const std::vector<hsize_t>& row_shape,
                                                          const std::string& unit) {
  return create_chunked(dataset_path, row_shape, unit, true);
}

ExtendibleDataset& Hdf5File::create_chunked(const std::string& dataset_path, const std::vector<hsize_t>& row_shape,
                                            const std::string& unit, bool compressed) {
  auto message = [&] { return describe("create extendible dataset", dataset_path, path_); };
  latch_->refuse_if_failed(message);
  const hsize_t row_size = element_count(row_shape);
  if (row_size == 0) throw IoError(message() + ": row shape has a zero extent");
  std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk;
  dims.insert(dims.end(), row_shape.begin(), row_shape.end());
  max_dims.insert(max_dims.end(), row_shape.begin(), row_shape.end());
  chunk = dims;
  // ~2 KiB chunks for scalar series, up to ~64 KiB for small vector rows, one row for big
  // ones; compressed: ~4 KiB, or one row.
  chunk[0] =
      compressed ? std::max<hsize_t>(1, 512 / row_size) : std::max<hsize_t>(1, std::min<hsize_t>(256, 8192 / row_size));

  const int rank = static_cast<int>(dims.size());
  Hdf5Handle space(latch_->check(H5Screate_simple(rank, dims.data(), max_dims.data()), message), H5Sclose);
  Hdf5Handle dcpl(latch_->check(H5Pcreate(H5P_DATASET_CREATE), message), H5Pclose);
  latch_->check(H5Pset_chunk(dcpl.get(), rank, chunk.data()), message);
  if (compressed) {
    // Shuffling groups the bytes of equal significance, which deflate then finds alike.
    latch_->check(H5Pset_shuffle(dcpl.get()), message);
    // Deflate's fastest level: the rows are mostly zeros, which it packs as well as level 6
    // does (the drum-cleat file 18.73 MB against 18.67 MB) for 0.91 of the deck's CPU time.
    latch_->check(H5Pset_deflate(dcpl.get(), 1), message);
  }
  Hdf5Handle dataset(latch_->check(H5Dcreate2(file_.get(), dataset_path.c_str(), H5T_IEEE_F64LE, space.get(),
                                              lcpl_.get(), dcpl.get(), H5P_DEFAULT),
                                   message),
                     H5Dclose);
  ExtendibleDataset created(std::move(dataset), std::move(dims), *latch_, dataset_path);
  if (!unit.empty()) write_attribute(dataset_path, "unit", unit);
  return datasets_.emplace_back(std::move(created));
}

void Hdf5File::write_row_view(const std::string& view_path, const ExtendibleDataset& source, hsize_t row, hsize_t first,
                              hsize_t count, hsize_t width) {
  std::vector<hsize_t> dims = source.dims_;
  // The source as it will be once 'row' is written (appended rows may still wait in memory).
  if (!dims.empty()) dims[0] = std::max(source.staged_extent(), row + 1);
  write_row_view(view_path, source.path(), dims, row, first, count, width);
}

void Hdf5File::write_row_view(const std::string& view_path, const std::string& source_path,
                              const std::vector<hsize_t>& source_dims, hsize_t row, hsize_t first, hsize_t count,
                              hsize_t width) {
  auto message = [&] { return describe("write view", view_path, path_); };
  latch_->refuse_if_failed(message);
  const std::vector<hsize_t>& dims = source_dims;
  if (dims.size() != 3 || row >= dims[0] || first + count > dims[2] || count == 0 ||
      (width == 0 ? count != 1 : count > width))
    throw IoError(message() + ": no such row or columns of '" + source_path + "'");
  const hsize_t entries = dims[1];
  const std::vector<hsize_t> source_start{row, 0, first}, source_count{1, entries, count};
  Hdf5Handle source_space = dataspace_of(source_dims);
  latch_->check(H5Sselect_hyperslab(source_space.get(), H5S_SELECT_SET, source_start.data(), nullptr,
                                    source_count.data(), nullptr),
                message);
  const std::vector<hsize_t> view_dims =
      width == 0 ? std::vector<hsize_t>{entries} : std::vector<hsize_t>{entries, width};
  Hdf5Handle view_space = dataspace_of(view_dims);
  if (width > 0) {
    const std::vector<hsize_t> start{0, 0}, columns{entries, count};
    latch_->check(H5Sselect_hyperslab(view_space.get(), H5S_SELECT_SET, start.data(), nullptr, columns.data(), nullptr),
                  message);
  }
  Hdf5Handle dcpl(latch_->check(H5Pcreate(H5P_DATASET_CREATE), message), H5Pclose);
  const double zero = 0.0;
  latch_->check(H5Pset_fill_value(dcpl.get(), H5T_NATIVE_DOUBLE, &zero), message);
#if (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 10 && H5_VERS_RELEASE >= 5) || H5_VERSION_GE(1, 12, 0)
  // Views carry no attributes: a minimal object header (a few hundred bytes per view less).
  latch_->check(H5Pset_dset_no_attrs_hint(dcpl.get(), true), message);
#endif
  // "." is this file.
  latch_->check(H5Pset_virtual(dcpl.get(), view_space.get(), ".", source_path.c_str(), source_space.get()), message);
  latch_->check(H5Sselect_all(view_space.get()), message);
  Hdf5Handle view(latch_->check(H5Dcreate2(file_.get(), view_path.c_str(), H5T_IEEE_F64LE, view_space.get(),
                                           lcpl_.get(), dcpl.get(), H5P_DEFAULT),
                                message),
                  H5Dclose);
  latch_->check(view.close(), message);
}

template <class T>
std::vector<T> Hdf5File::read_numeric(const std::string& dataset_path, hid_t mem_type,
                                      std::vector<hsize_t>* shape) const {
  auto message = [&] { return describe("read dataset", dataset_path, path_); };
  FailureLatch& latch = *latch_;
  Hdf5Handle dataset(latch.check(H5Dopen2(file_.get(), dataset_path.c_str(), H5P_DEFAULT), message), H5Dclose);
  Hdf5Handle space(latch.check(H5Dget_space(dataset.get()), message), H5Sclose);
  std::vector<hsize_t> dims(static_cast<size_t>(latch.check(H5Sget_simple_extent_ndims(space.get()), message)));
  latch.check(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), message);
  std::vector<T> values(static_cast<size_t>(element_count(dims)));
  if (!values.empty())
    latch.check(H5Dread(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), message);
  if (shape != nullptr) *shape = std::move(dims);
  return values;
}

std::vector<double> Hdf5File::read_doubles(const std::string& dataset_path, std::vector<hsize_t>* shape) const {
  return read_numeric<double>(dataset_path, H5T_NATIVE_DOUBLE, shape);
}

std::vector<long long> Hdf5File::read_ints(const std::string& dataset_path, std::vector<hsize_t>* shape) const {
  return read_numeric<long long>(dataset_path, H5T_NATIVE_LLONG, shape);
}

std::vector<std::string> Hdf5File::read_strings(const std::string& dataset_path) const {
  auto message = [&] { return describe("read dataset", dataset_path, path_); };
  FailureLatch& latch = *latch_;
  Hdf5Handle dataset(latch.check(H5Dopen2(file_.get(), dataset_path.c_str(), H5P_DEFAULT), message), H5Dclose);
  Hdf5Handle space(latch.check(H5Dget_space(dataset.get()), message), H5Sclose);
  const auto count = static_cast<hsize_t>(latch.check(H5Sget_simple_extent_npoints(space.get()), message));
  Hdf5Handle type(latch.check(H5Dget_type(dataset.get()), message), H5Tclose);
  auto read = [&](hid_t mem_type, void* buffer) {
    latch.check(H5Dread(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer), message);
  };
  return read_string_elements(type.get(), count, read, message);
}

void Hdf5File::write_bytes(const std::string& dataset_path, const std::vector<unsigned char>& bytes) {
  write_dataset(dataset_path, {bytes.size()}, H5T_STD_U8LE, H5T_NATIVE_UCHAR, bytes.data());
}

std::vector<unsigned char> Hdf5File::read_bytes(const std::string& dataset_path) const {
  return read_numeric<unsigned char>(dataset_path, H5T_NATIVE_UCHAR, nullptr);
}

std::vector<double> Hdf5File::read_rows(const ExtendibleDataset& dataset) const {
  std::vector<double> rows = read_doubles(dataset.path());
  rows.insert(rows.end(), dataset.staged_.begin(), dataset.staged_.end());
  rows.insert(rows.end(), dataset.pending_.begin(), dataset.pending_.end());
  return rows;
}

ExtendibleDataset* Hdf5File::find_extendible(const std::string& dataset_path) {
  for (ExtendibleDataset& dataset : datasets_)
    if (dataset.path() == dataset_path) return &dataset;
  return nullptr;
}

void Hdf5File::remove(const std::string& object_path) {
  latch_->check(H5Ldelete(file_.get(), object_path.c_str(), H5P_DEFAULT),
                [&] { return describe("remove", object_path, path_); });
}

bool Hdf5File::exists(const std::string& object_path) const {
  // H5Lexists fails (rather than returning false) when an intermediate group is missing,
  // so walk the path one component at a time.
  if (object_path.empty()) return false;
  size_t end = 0;
  while (end != std::string::npos) {
    end = object_path.find('/', end + 1);
    const std::string prefix = object_path.substr(0, end);
    if (prefix.empty() || prefix == "/") continue;
    const htri_t found = H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT);
    if (found < 0) H5Eclear2(H5E_DEFAULT);
    if (found <= 0) return false;
  }
  return true;
}

std::vector<hsize_t> Hdf5File::shape(const std::string& dataset_path) const {
  auto message = [&] { return describe("read the shape of", dataset_path, path_); };
  Hdf5Handle dataset(latch_->check(H5Dopen2(file_.get(), dataset_path.c_str(), H5P_DEFAULT), message), H5Dclose);
  Hdf5Handle space(latch_->check(H5Dget_space(dataset.get()), message), H5Sclose);
  std::vector<hsize_t> dims(static_cast<size_t>(latch_->check(H5Sget_simple_extent_ndims(space.get()), message)));
  latch_->check(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), message);
  return dims;
}

std::vector<std::string> Hdf5File::members(const std::string& group_path) const {
  auto message = [&] { return describe("list the members of", group_path, path_); };
  std::vector<std::string> names;
  const auto add = [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  latch_->check(H5Literate_by_name(file_.get(), group_path.c_str(), H5_INDEX_NAME, H5_ITER_INC, nullptr, add, &names,
                                   H5P_DEFAULT),
                message);
  return names;
}

void Hdf5File::flush() {
  stage();
  flush_staged();
}

void Hdf5File::stage() {
  for (ExtendibleDataset& dataset : datasets_) dataset.stage();
}

void Hdf5File::write_staged() {
  for (ExtendibleDataset& dataset : datasets_) dataset.write_staged();
}

void Hdf5File::flush_staged() {
  auto message = [&] { return "cannot flush '" + path_ + "'"; };
  latch_->refuse_if_failed(message);
  write_staged();
  latch_->check(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), message);
  if (working_path_.empty()) return;
  try {
    publish_copy();
  } catch (const IoError&) {  // the system's reason is in the message
    latch_->mark();
    throw;
  }
}

void Hdf5File::publish_copy() const {
  // Renamed into place: a reader, or a run killed meanwhile, finds the previous copy whole.
  const std::string copy = working_path_ + ".copy";
  copy_file(working_path_, copy);
  if (std::rename(copy.c_str(), path_.c_str()) != 0) {
    const IoError error(system_error("cannot rename '" + copy + "' to '" + path_ + "'"));
    std::remove(copy.c_str());
    throw error;
  }
}

}  // namespace tirefe::io
