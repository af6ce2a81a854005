#include "fmu/fmu_files.hpp"

#include <cctype>
#include <stdexcept>

namespace tirefe::fmu {

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower >= 'a' && lower <= 'f' ? lower - 'a' + 10 : -1;
}

std::string lower_case(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string percent_decoded(const std::string& text, const std::string& uri) {
  std::string decoded;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      decoded += text[i];
      continue;
    }
    const int high = i + 2 < text.size() ? hex_value(text[i + 1]) : -1;
    const int low = high >= 0 ? hex_value(text[i + 2]) : -1;
    if (low < 0 || (high == 0 && low == 0))
      throw std::invalid_argument("'" + uri + "' has a bad escape at '" + text.substr(i, 3) + "' (%XX, not %00)");
    decoded += static_cast<char>(16 * high + low);
    i += 2;
  }
  return decoded;
}

}  // namespace

std::string path_of_file_uri(const std::string& uri) {
  const std::string scheme = "file:";  // schemes are case-insensitive
  if (uri.size() < scheme.size() || lower_case(uri.substr(0, scheme.size())) != scheme)
    throw std::invalid_argument("'" + uri + "' is not a file: URI");
  std::string rest = uri.substr(scheme.size());
  if (rest.rfind("//", 0) == 0) {  // an authority: empty or localhost, the host's own files
    const size_t path_start = rest.find('/', 2);
    const std::string host = rest.substr(2, path_start == std::string::npos ? std::string::npos : path_start - 2);
    if (!host.empty() && lower_case(host) != "localhost")
      throw std::invalid_argument("'" + uri + "' names files on the host '" + host + "', not on this machine");
    rest = path_start == std::string::npos ? "" : rest.substr(path_start);
  }
  if (rest.empty() || rest[0] != '/') throw std::invalid_argument("'" + uri + "' has no absolute path");
  std::string path = percent_decoded(rest, uri);
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return path;
}

std::string resolve_file(const std::string& name, const std::string& resources) {
  if (name.empty()) throw std::invalid_argument("an empty file name");
  if (lower_case(name.substr(0, 5)) == "file:") return path_of_file_uri(name);
  if (name[0] == '/') return name;
  if (resources.empty())
    throw std::invalid_argument("'" + name + "' is relative to the FMU's resources, but the importer gave none");
  return resources + "/" + name;
}

}  // namespace tirefe::fmu
