// Temporary files beside a result (FILE.partial, FILE.partial.copy): written, then renamed
// over the result, so that a run killed meanwhile keeps the previous file whole. A killed
// run leaves one behind, which the next run removes, but only if tirefe could have written
// it (docs/security.md): a symbolic link there is never written through nor removed, and a
// file of another kind is never deleted.
#pragma once

#include <string>

namespace tirefe::io {

/// True if 'path' is a regular file (not a link to one) that is empty or begins with 'signature'.
bool empty_or_begins_with(const std::string& path, const std::string& signature);

/// Clears 'path' for a temporary file whose kind begins with 'signature': removes what a
/// killed run left there. Throws IoError, naming the path, if anything else is there.
void clear_for_temporary(const std::string& path, const std::string& signature);

/// Opens 'path' for writing as a file that did not exist (never through a link); throws
/// IoError if anything is there. Returns the file descriptor.
int create_new_file(const std::string& path);

}  // namespace tirefe::io
