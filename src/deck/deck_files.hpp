// The files a deck may read and write (docs/security.md). A deck reads from its own folder,
// the project's lua/ and inputs/ folders, the folders it may write to and folders given
// with --allow-read; it writes only in the output folder (--output-dir) and folders given
// with --allow-write. Paths are resolved (symlinks, "..") before the check. An existing
// file is replaced only if it is of the kind tirefe writes there, and one file serves one
// purpose in a run (a checkpoint cannot replace the result file).
#pragma once

#include <filesystem>
#include <string>
#include <utility>

namespace tirefe::macros {

struct DeckSession;

/// What a deck writes to a file: 'purpose' names it in messages ("the result file of
/// model 1 ('drum')"); an existing file may be replaced only if it is empty or begins
/// with 'signature', the mark of 'format' ("an HDF5 file").
struct OutputFile {
  std::string purpose;
  std::string format;
  std::string signature;

  static OutputFile hdf5(std::string purpose);
  static OutputFile xdmf(std::string purpose);
};

/// 'path' made absolute with symlinks and ".." resolved (as far as it exists).
std::filesystem::path resolved_path(const std::filesystem::path& path);
/// True if the resolved 'path' is 'folder' or lies below it (both resolved by the caller).
bool lies_within(const std::filesystem::path& path, const std::filesystem::path& folder);

/// Throws a ModelError naming 'path' if it is there but no regular file: a FIFO would
/// block its read, a device such as /dev/zero would never end it, a folder is no file.
void require_regular_file(const std::string& path);
/// A file a deck reads: a relative path is taken from the deck's folder. Throws a
/// ModelError if the file lies outside the folders the deck may read or is no regular file.
std::string deck_relative(const DeckSession& session, const std::string& file);
/// A file a deck writes: a relative path goes in the output folder, created as needed.
/// Throws a ModelError if it lies outside the folders the deck may write, if an existing
/// file there is not of this kind, or if the run already writes it for another purpose.
std::string deck_output_path(DeckSession& session, const std::string& file, const OutputFile& kind);
/// Frees the names claimed for 'purpose' (a model that is gone no longer writes them).
void release_outputs(DeckSession& session, const std::string& purpose);

}  // namespace tirefe::macros
