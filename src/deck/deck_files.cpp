#include "deck/deck_files.hpp"

#include <iterator>
#include <vector>

#include "core/mesh.hpp"
#include "io/hdf5_file.hpp"
#include "io/temporary_file.hpp"
#include "io/xdmf.hpp"
#include "deck/deck_session.hpp"
#include "deck/lua_module_dir.hpp"

namespace tirefe::macros {

namespace fs = std::filesystem;

OutputFile OutputFile::hdf5(std::string purpose) { return {std::move(purpose), "an HDF5 file", io::kHdf5Signature}; }
OutputFile OutputFile::xdmf(std::string purpose) { return {std::move(purpose), "an XDMF index", io::kXdmfSignature}; }

namespace {

std::vector<fs::path> write_folders(const DeckSession& session) {
  std::vector<fs::path> folders{session.output_dir};
  folders.insert(folders.end(), session.write_folders.begin(), session.write_folders.end());
  return folders;
}

/// A deck reads its own folder, the shipped Lua modules and data, what it may write, and
/// what the command line allows.
std::vector<fs::path> read_folders(const DeckSession& session) {
  const fs::path deck_folder = fs::path(session.deck_path).parent_path();
  // The shipped data sits beside the Lua modules: inputs/ in the sources, tires/ installed.
  const fs::path lua = lua_module_dir();
  std::vector<fs::path> folders{deck_folder.empty() ? fs::path(".") : deck_folder, lua, lua.parent_path() / "inputs",
                                lua.parent_path() / "tires"};
  folders.insert(folders.end(), session.read_folders.begin(), session.read_folders.end());
  for (const fs::path& folder : write_folders(session)) folders.push_back(folder);
  return folders;
}

bool inside_any(const fs::path& real, const std::vector<fs::path>& folders) {
  for (const fs::path& folder : folders)
    if (lies_within(real, resolved_path(folder))) return true;
  return false;
}

/// An existing file is replaced only if it holds nothing or is of the kind written: a
/// deck never truncates a file tirefe did not write.
void refuse_foreign_file(const fs::path& real, const std::string& shown, const OutputFile& kind) {
  std::error_code error;
  const fs::file_status status = fs::status(real, error);
  if (!fs::exists(status)) return;
  if (fs::is_directory(status)) throw ModelError("'" + shown + "' is a folder; give a file name");
  if (!fs::is_regular_file(status)) throw ModelError("'" + shown + "' is not a regular file; tirefe writes only files");
  if (!io::empty_or_begins_with(real.string(), kind.signature))
    throw ModelError("'" + shown + "' exists and is not " + kind.format +
                     "; tirefe replaces only files of the kind it writes: remove it or choose another name");
}

// Creates the folder of the output 'file' with its missing parents, naming the one that
// cannot be made and why (a read-only parent, a file in the way) rather than leaving the
// file's creation to fail with "No such file or directory".
void create_output_folder(const fs::path& file) {
  auto failure = [&](const fs::path& folder, const std::string& reason) {
    return ModelError("cannot create the output folder '" + folder.string() + "' for '" + file.string() +
                      "': " + reason);
  };
  // Another process (an MPI rank writing its own corner) may make the same folder at the
  // same time: try to make it first, and judge what is there only when that fails.
  fs::path made;
  for (const fs::path& part : file.parent_path()) {
    made /= part;
    std::error_code error, ignored;
    if (fs::create_directory(made, error) || fs::is_directory(made, ignored)) continue;
    if (fs::exists(made, ignored)) throw failure(made, "a file of that name is in the way");
    throw failure(made, error.message());
  }
}

}  // namespace

fs::path resolved_path(const fs::path& path) {
  std::error_code error;
  fs::path real = fs::weakly_canonical(fs::absolute(path, error), error);
  return error ? fs::absolute(path).lexically_normal() : real;
}

bool lies_within(const fs::path& path, const fs::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
    if (f->empty()) continue;  // a trailing separator
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

void require_regular_file(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status) || fs::is_regular_file(status)) return;  // a missing file is its reader's to report
  if (fs::is_directory(status)) throw ModelError("'" + path + "' is a folder; give a file");
  throw ModelError("'" + path +
                   "' is no regular file (a FIFO or a device would block the read or never end it); "
                   "give a file");
}

std::string deck_relative(const DeckSession& session, const std::string& file) {
  fs::path path(file);
  if (path.is_relative() && !session.deck_path.empty()) path = fs::path(session.deck_path).parent_path() / path;
  if (!inside_any(resolved_path(path), read_folders(session)))
    throw ModelError("'" + file +
                     "' lies outside the folders a deck may read (its own folder, the project's lua/ and inputs/, "
                     "the output folder); give another with --allow-read DIR (docs/security.md)");
  require_regular_file(path.string());
  return path.string();
}

std::string deck_output_path(DeckSession& session, const std::string& file, const OutputFile& kind) {
  fs::path path(file);
  if (!path.has_filename())  // "" or "sub/": the file's own name is missing
    throw ModelError("'" + file + "' names no file, only a folder; give a file name (e.g. 'run.h5')");
  if (path.is_relative()) path = fs::path(session.output_dir) / path;
  const fs::path real = resolved_path(path);
  if (!inside_any(real, write_folders(session)))
    throw ModelError("'" + file + "' lies outside the output folder '" + session.output_dir +
                     "' (a relative path lands there); a deck writes nowhere else unless the command line adds a "
                     "folder with --allow-write DIR (docs/security.md)");
  refuse_foreign_file(real, path.string(), kind);
  const auto [claimed, added] = session.output_purposes.emplace(real.string(), kind.purpose);
  if (!added && claimed->second != kind.purpose)
    throw ModelError("'" + path.string() + "' is already " + claimed->second + " in this run; give " + kind.purpose +
                     " another name");
  if (path.has_parent_path()) create_output_folder(path);
  return path.string();
}

void release_outputs(DeckSession& session, const std::string& purpose) {
  for (auto entry = session.output_purposes.begin(); entry != session.output_purposes.end();)
    entry = entry->second == purpose ? session.output_purposes.erase(entry) : std::next(entry);
}

}  // namespace tirefe::macros
