// HDF5 output layer: a thin RAII wrapper over the HDF5 1.10 C API used for result files,
// restart data and post-processing helpers. Every failure is reported as IoError naming the
// file and the object (dataset/attribute) path.
#pragma once

#include <hdf5.h>

#include <Eigen/Dense>
#include <cstddef>
#include <deque>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace tirefe::io {

/// The first bytes of every HDF5 file (the superblock at offset 0).
extern const char* const kHdf5Signature;

class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// HDF5 prints its error stack unless told not to, once per thread: the errors it reports
// are IoErrors here. Every file opened silences the thread that opens it; a thread that
// writes to a file it did not open calls this first.
void silence_hdf5_errors();

// Owns one hid_t and closes it with the matching H5?close function.
class Hdf5Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Hdf5Handle() = default;
  Hdf5Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Hdf5Handle(Hdf5Handle&& other) noexcept;
  Hdf5Handle& operator=(Hdf5Handle&& other) noexcept;
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  ~Hdf5Handle() { reset(); }

  hid_t get() const { return id_; }
  void reset() noexcept;
  hid_t release() noexcept;  // the id, no longer owned
  herr_t close();            // reset(), with the closer's result (closing can write)

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// Whether an HDF5 call on one file failed; shared by the file and its datasets. A full disk
// surfaces in whichever call HDF5 writes in (its metadata cache writes at any call that
// evicts: a create, an extend, an attribute, a close, not only a flush) and leaves the
// file's state unknown: the first failure marks the file failed, and nothing more is
// written to it.
class FailureLatch {
 public:
  explicit FailureLatch(std::string file_path) : file_path_(std::move(file_path)) {}
  // 'rc', or (negative: a failed HDF5 call) the file marked failed and an IoError.
  template <class T, class Message>
  T check(T rc, Message&& message) {
    if (rc < 0) fail(message());
    return rc;
  }
  // Marks the file failed; throws 'message' with HDF5's reason.
  [[noreturn]] void fail(const std::string& message);
  // Before a write: an IoError once the file failed.
  template <class Message>
  void refuse_if_failed(Message&& message) const {
    if (failed_) refuse(message());
  }
  void mark() { failed_ = true; }
  bool failed() const { return failed_; }
  const std::string& file_path() const { return file_path_; }

 private:
  [[noreturn]] void refuse(const std::string& message) const;
  std::string file_path_;
  bool failed_ = false;
};

// An extendible, chunked dataset that grows by one "row" per append along its first
// dimension. A row has a fixed shape (empty shape = a scalar per row -> 1-D dataset of
// length rows(); shape {n,3} -> dataset rows() x n x 3). Doubles only. Appended rows
// wait in memory until the file is flushed or closed (Hdf5File::flush): one write of many
// rows costs about what one write of one row does. A flush may be written by another
// thread (Hdf5File::stage, then write_staged): appending touches only the rows waiting,
// never the rows staged for that flush, so the two threads share nothing.
class ExtendibleDataset {
 public:
  ExtendibleDataset(ExtendibleDataset&&) noexcept = default;
  ExtendibleDataset& operator=(ExtendibleDataset&&) noexcept = default;

  void append(const double* row_values);                 // row_size() doubles, row-major
  void append(double scalar);                            // only for scalar rows
  void append_rows(const double* values, hsize_t rows);  // rows * row_size() doubles (restarts)
  hsize_t rows() const { return rows_; }
  size_t row_size() const { return row_size_; }
  /// Bytes of the rows waiting in memory (not those staged for a flush being written).
  size_t pending_bytes() const { return pending_.size() * sizeof(double); }
  const std::string& path() const { return path_; }

 private:
  friend class Hdf5File;
  ExtendibleDataset(Hdf5Handle dataset, std::vector<hsize_t> dims, FailureLatch& latch, std::string path);

  /// The rows waiting become the rows of the next write (after those staged before).
  void stage();
  /// Writes the staged rows; the rows in the file and staged, for the views a flush makes.
  void write_staged();
  hsize_t staged_extent() const { return dims_[0] + static_cast<hsize_t>(staged_.size() / row_size_); }
  /// Writes 'rows' rows at the end of the dataset in the file.
  void write_rows(const double* values, hsize_t rows);
  /// Closes the dataset (HDF5 may write its header then).
  void close();

  Hdf5Handle dataset_;
  Hdf5Handle file_space_;  // reused across appends: resized in place, never re-created
  Hdf5Handle mem_space_;   // one row, flat
  std::vector<hsize_t> dims_, start_, count_;
  size_t row_size_ = 1;
  bool scalar_rows_ = false;     // a 1-D dataset (dims_ is the writing thread's while a flush is written)
  std::vector<double> pending_;  // appended rows not yet staged, row-major
  std::vector<double> staged_;   // rows for the flush being written
  hsize_t rows_ = 0;             // in the file, staged and waiting: the appending thread's count
  FailureLatch* latch_;          // the file's
  std::string path_;
};

class Hdf5File {
 public:
  // Create (truncate) a file. Parent folders must exist.
  static Hdf5File create(const std::string& path);
  // Create a file where nothing is (never through a symbolic link); IoError otherwise.
  static Hdf5File create_new(const std::string& path);
  // Create a file that is whole at every instant, even for a reader while it is written or
  // after the process is killed: it is written as '<path>.partial', copied whole to 'path'
  // (under a temporary name, then renamed) at every flush() and renamed to 'path' at close().
  // Leftovers of a killed run ('<path>.partial', '<path>.partial.copy') are removed here;
  // anything else in their place is refused (temporary_file.hpp).
  static Hdf5File create_published(const std::string& path);
  // A file held in memory only and dropped when closed ('name' for messages).
  static Hdf5File create_in_memory(const std::string& name);
  // Open an existing file read-only (tests, restart, post-processing).
  static Hdf5File open_read_only(const std::string& path);
  // Open an existing file to change it (tests and fuzzing alter checkpoints with it).
  static Hdf5File open_read_write(const std::string& path);
  // Open an existing file to add to it, whole at every instant: it is copied to
  // '<path>.partial', changed there and renamed over 'path' at close(); a process killed
  // meanwhile leaves 'path' as it was (and a leftover that the next open removes).
  static Hdf5File open_published(const std::string& path);

  Hdf5File(Hdf5File&& other) noexcept;
  Hdf5File& operator=(Hdf5File&& other) noexcept;
  ~Hdf5File();

  const std::string& path() const { return path_; }

  // Attributes on a group or dataset ("/" = root); a missing object is created as a group,
  // with intermediate groups. Strings are variable-length UTF-8 (h5py reads them as str).
  void write_attribute(const std::string& object_path, const std::string& name, const std::string& value);
  void write_attribute(const std::string& object_path, const std::string& name, double value);
  void write_attribute(const std::string& object_path, const std::string& name, long long value);
  // Other integer types (int, size_t, ...) would be ambiguous between double and long long.
  template <class Int, std::enable_if_t<std::is_integral_v<Int>, int> = 0>
  void write_attribute(const std::string& object_path, const std::string& name, Int value) {
    write_attribute(object_path, name, static_cast<long long>(value));
  }
  std::string read_string_attribute(const std::string& object_path, const std::string& name) const;
  double read_double_attribute(const std::string& object_path, const std::string& name) const;

  // Fixed datasets, row-major; groups along the path are created as needed.
  void write_matrix(const std::string& dataset_path, const Eigen::MatrixXd& values);  // rows x cols
  void write_vector(const std::string& dataset_path, const std::vector<double>& values);
  void write_int_vector(const std::string& dataset_path, const std::vector<long long>& values);
  void write_int_matrix(const std::string& dataset_path, hsize_t rows, hsize_t cols, const long long* data);
  void write_strings(const std::string& dataset_path, const std::vector<std::string>& values);  // 1-D, vlen UTF-8
  void write_string_dataset(const std::string& dataset_path, const std::string& text);  // scalar, for large text

  // Created empty, chunked, unlimited first dimension. The reference stays valid while this
  // object lives (also across moves of the Hdf5File). A non-empty unit becomes attribute "unit".
  ExtendibleDataset& create_extendible(const std::string& dataset_path, const std::vector<hsize_t>& row_shape,
                                       const std::string& unit = "");
  // The same with its rows compressed (byte shuffle, then deflate) in chunks of whole rows,
  // about 4 KiB or one row: for rows that compress (a contact's per-node rows, mostly
  // zeros), flushed one at a time (a flushed chunk is not rewritten).
  ExtendibleDataset& create_compressed_extendible(const std::string& dataset_path,
                                                  const std::vector<hsize_t>& row_shape, const std::string& unit = "");
  // A virtual dataset at 'view_path' that shows row 'row' of 'source' (rows x n x c) without
  // copying it: 'count' columns from 'first' of each of the n entries, padded with zeros
  // to 'width' columns (n x width); width 0 with count 1 gives n values. Readers that want
  // one whole dataset per frame (XDMF readers) read these.
  void write_row_view(const std::string& view_path, const ExtendibleDataset& source, hsize_t row, hsize_t first,
                      hsize_t count, hsize_t width);
  // The same of a dataset of 'source_shape' (rows x n x c) at 'source_path'.
  void write_row_view(const std::string& view_path, const std::string& source_path,
                      const std::vector<hsize_t>& source_shape, hsize_t row, hsize_t first, hsize_t count,
                      hsize_t width);

  // Whole dataset converted to double / long long, plus its shape (empty for scalars).
  std::vector<double> read_doubles(const std::string& dataset_path, std::vector<hsize_t>* shape = nullptr) const;
  std::vector<long long> read_ints(const std::string& dataset_path, std::vector<hsize_t>* shape = nullptr) const;
  // String dataset (1-D or scalar -> one element).
  std::vector<std::string> read_strings(const std::string& dataset_path) const;
  // Raw bytes, 1-D (checkpointed element histories).
  void write_bytes(const std::string& dataset_path, const std::vector<unsigned char>& bytes);
  std::vector<unsigned char> read_bytes(const std::string& dataset_path) const;
  // Every row of an extendible dataset appended so far, row-major: those in the file, those
  // staged and those waiting (no flush may be written meanwhile).
  std::vector<double> read_rows(const ExtendibleDataset& dataset) const;
  // The extendible datasets this object created, in creation order; null if none has the path.
  const std::deque<ExtendibleDataset>& extendible_datasets() const { return datasets_; }
  ExtendibleDataset* find_extendible(const std::string& dataset_path);
  bool exists(const std::string& object_path) const;
  // A dataset's dimensions (empty for a scalar).
  std::vector<hsize_t> shape(const std::string& dataset_path) const;
  // The names of a group's members, in the order of their names.
  std::vector<std::string> members(const std::string& group_path) const;
  // Removes the dataset or group at 'object_path' (to write it anew).
  void remove(const std::string& object_path);

  // Writes the appended rows and flushes everything, so that a process killed afterwards
  // leaves a file readable up to here (a published file: copies it to its path).
  void flush();
  // flush() in two parts, for a flush written by another thread: stage() takes the rows
  // appended so far (the appending thread calls it, between appends), flush_staged()
  // writes them and flushes (the writing thread: no other call on this file meanwhile,
  // appends aside). write_staged() writes them alone, for the next flush to flush.
  void stage();
  void write_staged();
  void flush_staged();
  // Writes the appended rows and closes the file (a published file: renames it to its path).
  // Throws IoError; afterwards the object holds no file. The destructor closes quietly.
  // After a failed HDF5 call the file is dropped instead (a published one keeps its last copy).
  void close();
  // An HDF5 call on the file failed (FailureLatch): it was reported, and nothing more is written.
  bool failed() const { return latch_ && latch_->failed(); }
  // Fails the file for a failure beside it (its index on the same full disk): reported by
  // the caller, and the close keeps the last flush, as after a failure of its own.
  void abandon() {
    if (latch_) latch_->mark();
  }

 private:
  Hdf5File(std::string path, Hdf5Handle file);
  void publish_copy() const;
  void write_dataset(const std::string& dataset_path, const std::vector<hsize_t>& dims, hid_t file_type, hid_t mem_type,
                     const void* data);
  ExtendibleDataset& create_chunked(const std::string& dataset_path, const std::vector<hsize_t>& row_shape,
                                    const std::string& unit, bool compressed);
  void write_scalar_attribute(const std::string& object_path, const std::string& name, hid_t file_type, hid_t mem_type,
                              const void* data);
  template <class T>
  std::vector<T> read_numeric(const std::string& dataset_path, hid_t mem_type, std::vector<hsize_t>* shape) const;

  std::string path_;
  std::string working_path_;  // where a published file is written; empty: written at path_
  Hdf5Handle file_;
  std::unique_ptr<FailureLatch> latch_;  // its address stays with the datasets across moves
  Hdf5Handle lcpl_;                      // link creation: intermediate groups on
  // Declared after file_ so the datasets are closed before the file.
  std::deque<ExtendibleDataset> datasets_;
};

}  // namespace tirefe::io
