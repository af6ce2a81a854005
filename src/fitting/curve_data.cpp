#include "fitting/curve_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <fstream>
#include <unordered_map>

namespace tirefe::fitting {

namespace {

// Spreadsheet programs start a CSV file saved as UTF-8 with it; it is no part of the first name.
const std::string kUtf8ByteOrderMark = "\xEF\xBB\xBF";

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> split_fields(const std::string& line, char separator) {
  std::vector<std::string> fields;
  size_t start = 0;
  for (size_t at = line.find(separator);; at = line.find(separator, start)) {
    fields.push_back(trimmed(line.substr(start, at == std::string::npos ? std::string::npos : at - start)));
    if (at == std::string::npos) return fields;
    start = at + 1;
  }
}

/// The separator of a file, from its header: a tab or a semicolon when the header holds
/// one (as spreadsheets write where the comma is the decimal mark), else the comma.
char separator_of(const std::string& header) {
  if (header.find('\t') != std::string::npos) return '\t';
  if (header.find(';') != std::string::npos) return ';';
  return ',';
}

const UnitSuffix* known_unit(const std::string& unit) {
  for (const UnitSuffix& known : unit_suffixes())
    if (unit == known.suffix) return &known;
  return nullptr;
}

/// "name [unit]" or "name (unit)" (the unit must be known), "name_unit" (a known suffix)
/// or a bare name.
DataColumn column_from_header(const std::string& header, const std::string& where) {
  DataColumn column{header, header, "", "", {}};
  const auto bracket = header.find_first_of("[(");
  if (bracket != std::string::npos) {
    const char close = header[bracket] == '[' ? ']' : ')';
    const std::string unit = trimmed(header.substr(bracket + 1, header.size() - bracket - 2));
    column.name = trimmed(header.substr(0, bracket));
    const UnitSuffix* known = known_unit(unit);
    if (header.back() != close || column.name.empty() || !known) {
      std::string units;
      for (const UnitSuffix& suffix : unit_suffixes()) units += (units.empty() ? "" : " ") + std::string(suffix.suffix);
      throw CurveDataError(where + "column '" + header + "': write the unit as 'name [unit]' or 'name (unit)' with a " +
                           "known unit (" + units + ")");
    }
    column.unit = unit;
    column.si_unit = known->si_unit;
    return column;
  }
  const auto underscore = header.rfind('_');
  if (underscore == std::string::npos || underscore == 0) return column;
  const std::string suffix = header.substr(underscore + 1);
  for (const UnitSuffix& unit : unit_suffixes())
    if (suffix == unit.suffix) {
      column.name = header.substr(0, underscore);
      column.unit = suffix;
      column.si_unit = unit.si_unit;
    }
  return column;
}

/// A decimal number filling the whole field: digits, sign, point and exponent only (no hex,
/// inf, nan, and no NUL cutting the field short). A value too small for a double
/// (1e-400) underflows to the nearest double, 0 or subnormal; one too large is refused.
std::optional<double> decimal_number(const std::string& field) {
  if (field.empty() || field.find_first_not_of("0123456789+-.eE") != std::string::npos) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(field.c_str(), &end);
  if (end != field.c_str() + field.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

/// Printable text of a field for a message (a NUL or a control byte shown as '?').
std::string shown(std::string field) {
  for (char& c : field)
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  return field;
}

double to_si(const std::string& unit) {
  const UnitSuffix* known = known_unit(unit);
  return known ? known->to_si : 1.0;
}

std::string header_list(const std::vector<DataColumn>& columns) {
  std::string out;
  for (const auto& column : columns) out += (out.empty() ? "" : ", ") + column.header;
  return out;
}

}  // namespace

const std::vector<UnitSuffix>& unit_suffixes() {
  // clang-format off
  static const std::vector<UnitSuffix> units{
      {"m", 1.0, "m"},      {"mm", 1e-3, "m"},      {"cm", 1e-2, "m"},
      {"N", 1.0, "N"},      {"kN", 1e3, "N"},       {"N/m", 1.0, "N/m"},
      {"in", 0.0254, "m"},  {"ft", 0.3048, "m"},    {"N/mm", 1e3, "N/m"},
      {"Pa", 1.0, "Pa"},    {"kPa", 1e3, "Pa"},
      {"MPa", 1e6, "Pa"},   {"bar", 1e5, "Pa"},     {"psi", 6894.757293168, "Pa"},
      {"s", 1.0, "s"},      {"ms", 1e-3, "s"},      {"Hz", 1.0, "Hz"},
      {"rad", 1.0, "rad"},  {"deg", 3.14159265358979323846 / 180.0, "rad"},
      {"kg", 1.0, "kg"},    {"m/s", 1.0, "m/s"},    {"km/h", 1.0 / 3.6, "m/s"}};
  // clang-format on
  return units;
}

CurveData CurveData::read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CurveDataError("cannot open '" + path + "'");
  CurveData data;
  data.path_ = path;
  std::string line;
  char separator = ',';
  for (int number = 1; std::getline(in, line); ++number) {
    if (number == 1 && line.rfind(kUtf8ByteOrderMark, 0) == 0) line.erase(0, kUtf8ByteOrderMark.size());
    const std::string content = trimmed(line.substr(0, line.find('#')));
    if (content.empty()) continue;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    if (data.columns_.empty()) separator = separator_of(content);
    const std::vector<std::string> fields = split_fields(content, separator);
    if (data.columns_.empty()) {                                  // the header
      std::unordered_map<std::string, const std::string*> names;  // name -> header: linear in the columns
      for (const std::string& header : fields) {
        if (header.empty()) throw CurveDataError(where + "empty column name in the header");
        if (shown(header) != header)
          throw CurveDataError(where + "column name '" + shown(header) + "' holds a control character or NUL byte");
        DataColumn column = column_from_header(header, where);
        const auto [named, added] = names.emplace(column.name, &header);
        if (!added)
          throw CurveDataError(where + "two columns named '" + column.name + "' ('" + *named->second + "', '" + header +
                               "')");
        data.columns_.push_back(column);
      }
      continue;
    }
    if (fields.size() != data.columns_.size())
      throw CurveDataError(where + "expected " + std::to_string(data.columns_.size()) + " values (" +
                           header_list(data.columns_) + "), found " + std::to_string(fields.size()));
    for (size_t c = 0; c < fields.size(); ++c) {
      DataColumn& column = data.columns_[c];
      // With ';' or tab between the fields a comma is the decimal mark (1,5 is 1.5).
      std::string field = fields[c];
      if (separator != ',') std::replace(field.begin(), field.end(), ',', '.');
      const std::optional<double> value = decimal_number(field);
      if (!value)
        throw CurveDataError(where + "column '" + column.header + "': '" + shown(fields[c]) +
                             "' is not a finite number (write decimals like 12.5 or -3e-4)");
      column.values.push_back(*value * to_si(column.unit));
    }
    data.row_lines_.push_back(number);
  }
  if (data.columns_.empty()) throw CurveDataError(path + ": no header line (column names) found");
  if (data.rows() == 0) throw CurveDataError(path + ": no data rows after the header");
  return data;
}

const DataColumn& CurveData::column(const std::string& name) const {
  for (const auto& column : columns_)
    if (column.name == name || column.header == name) return column;
  throw CurveDataError(path_ + ": no column '" + name + "' (columns: " + header_list(columns_) + ")");
}

}  // namespace tirefe::fitting
