// Where the FMU finds its files: the resource location an importer hands to fmi2Instantiate
// (a file: URI, RFC 3986 / RFC 8089) as a folder, and the files its String parameters
// name, in that folder or on disk.
#pragma once

#include <string>

namespace tirefe::fmu {

/// The local path of a file URI: "file:///a/b%20c", "file://localhost/a/b" or "file:/a/b",
/// percent-decoded. Throws std::invalid_argument, saying why, for another scheme or host,
/// a relative path or a bad escape.
std::string path_of_file_uri(const std::string& uri);

/// The file a String parameter names: a file: URI or an absolute path on disk, or a path
/// relative to the FMU's resources folder 'resources' (which may be empty: none given).
/// Throws std::invalid_argument when it cannot be a file.
std::string resolve_file(const std::string& name, const std::string& resources);

}  // namespace tirefe::fmu
