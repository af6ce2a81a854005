// Measured curves read from CSV files (a force-deflection curve, say), for fits and decks.
//
//   # 145 SR-12, flat road           <- '#' starts a comment, on its own line or after values
//   deflection_mm, force_N, pressure_kPa
//   5.0, 960, 208
//
// The first line that is not blank or a comment is the header: column names separated by
// commas, semicolons or tabs (the header's separator is the file's; with a semicolon or a
// tab a comma in a number is the decimal mark, as spreadsheets write it), each usually
// ending in a unit suffix (_mm, _N, _kPa, ...; unit_suffixes()) or followed by the unit in
// brackets or parentheses ("x [mm]", "Distance (m)"). Every value is converted to SI on reading
// and the column is known by its name without the unit (deflection_mm -> "deflection" in
// m); a header without a known suffix is taken as is, without conversion, while a unit in
// brackets must be a known one. A row with the wrong number of values or a value that is
// not a finite decimal number (hex, inf, nan, a NUL byte in it, an overflow like 1e400)
// is an error naming the file and the line; a value too small for a double (1e-400)
// underflows to 0 (or the nearest subnormal) like any rounding. A UTF-8 byte order mark
// at the start of the file (spreadsheets write one) is skipped.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace tirefe::fitting {

class CurveDataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct UnitSuffix {
  const char* suffix;  // as written after the last '_' of a header, e.g. "kPa"
  double to_si;        // SI value of one unit
  const char* si_unit;
};

/// The recognised unit suffixes (case-sensitive).
const std::vector<UnitSuffix>& unit_suffixes();

struct DataColumn {
  std::string header;          // as written, e.g. deflection_mm
  std::string name;            // without the unit suffix, e.g. deflection
  std::string unit;            // the suffix ("" if none)
  std::string si_unit;         // the unit of 'values' ("" if none)
  std::vector<double> values;  // SI
};

class CurveData {
 public:
  /// Reads a CSV file (CurveDataError with "file:LINE: ..." on a malformed row).
  static CurveData read_csv(const std::string& path);

  const std::string& path() const { return path_; }
  const std::vector<DataColumn>& columns() const { return columns_; }
  size_t rows() const { return columns_.empty() ? 0 : columns_.front().values.size(); }
  /// The file line of a data row (0-based), for messages about its values.
  int line(size_t row) const { return row_lines_.at(row); }
  /// A column by its name or its full header; CurveDataError listing the columns otherwise.
  const DataColumn& column(const std::string& name) const;

 private:
  std::string path_;
  std::vector<DataColumn> columns_;
  std::vector<int> row_lines_;
};

}  // namespace tirefe::fitting
