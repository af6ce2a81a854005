// TeimOrbit property files: the text format of tire data (.tir) and road data (.rdf) that
// ADAMS/Tire, MF-Tyre, FTire and Chrono read, and that tirefe reads and writes for its own
// tire parameters (docs/tire.md) and 2D roads (docs/roads.md).
//
//   $------------------------------------------------ units   <- '$' starts a comment
//   [UNITS]                                                    <- a section
//   LENGTH = 'mm'                                              <- KEY = value, strings quoted
//   [PARAMETERS]
//   HEIGHT = 10.0          $ of the plank
//   (XZ_DATA)                                                  <- a table in the section
//   { x  z_l  z_r }                                            <- optional column names
//   0  0  0                                                    <- rows of values
//   [SHAPE]
//   { radial width }                                           <- a section's own table:
//   1.0  0.0                                                      rows right after its header
//
// Section, table and key names are case-insensitive (messages show them as written); a
// line starting with '!' is a comment too. A key without a value (KEY =) counts as absent,
// as the Magic Formula files that leave a parameter blank mean it. Numbers are converted
// to SI on reading by the dimension the reader states for each key and the units of the
// file's [UNITS] section (UnitSystem): one parser and one units table for every file type.
// A NUL or other control byte (other than tab) anywhere is an error: such a file is damaged
// or not text, and a NUL would cut a value short.
//
// TeimOrbitReader reads a file the way its caller's schema asks and refuses the rest:
// every key and table the caller asked for (present or not) is known; once the caller has
// read everything it knows, finish() reports the first section, key or table of the file
// that nobody asked for, with the closest known name. A file of another program's schema
// (a Magic Formula tire) is read with finish_foreign() instead, which passes over what the
// caller lists as not used. A key given twice is an error where it is read. Every error
// names the file and line.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tirefe::formats {

class TeimOrbitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Exponents of the base quantities a value is measured in (force/length^2 is {-2, 1}).
/// 'pressure' is its own base: [UNITS] PRESSURE, or FORCE/LENGTH^2 without it.
struct Dimension {
  int length = 0, force = 0, mass = 0, time = 0, angle = 0, pressure = 0;
  bool dimensionless() const { return !length && !force && !mass && !time && !angle && !pressure; }
};

/// The unit of a dimension in SI, e.g. "N s/m^2" ("" when dimensionless).
std::string si_unit(const Dimension& dimension);
/// The dimension in words, e.g. "force time/length^2" ("-" when dimensionless).
std::string dimension_name(const Dimension& dimension);

/// The units of [UNITS]; to_si converts a value of a dimension to SI.
class UnitSystem {
 public:
  UnitSystem();  // SI
  /// Sets a base quantity's unit by its [UNITS] key and value (LENGTH, 'mm'); the message
  /// of a failure says what is wrong (unknown quantity or unit, with the known ones).
  std::optional<std::string> set(const std::string& quantity, const std::string& unit);
  double to_si(double value, const Dimension& dimension) const;
  /// The [UNITS] keys and the SI unit name of each, in the order files write them.
  static const std::vector<std::pair<std::string, std::string>>& si_units();

 private:
  struct Scale {
    double numerator = 1.0, denominator = 1.0;  // SI value of one unit = numerator / denominator
  };
  Scale length_, force_, mass_, time_, angle_;
  std::optional<Scale> pressure_;
};

struct TeimOrbitValue {
  std::string key;   // as written
  std::string text;  // without the quotes of a string; empty after a bare 'KEY ='
  bool quoted = false;
  int line = 0;
  int first_line = 0;  // a repeat of the key: the line of its first value (0: none)
};

struct TeimOrbitTable {
  std::string name;  // as written, without the parentheses; "" for the section's own table
  int line = 0;
  std::vector<std::string> columns;  // from the optional { ... } line
  std::vector<std::vector<std::string>> rows;
  std::vector<int> row_lines;
};

struct TeimOrbitSection {
  std::string name;  // as written, without the brackets
  int line = 0;
  std::vector<TeimOrbitValue> values;  // repeats of a key included (first_line set)
  std::vector<TeimOrbitTable> tables;
  /// The section's own table (rows right after its header, as [SHAPE] holds), or nullptr.
  const TeimOrbitTable* own_table() const;
};

/// A parsed file: its sections in file order.
class TeimOrbitFile {
 public:
  static TeimOrbitFile read(const std::string& path);
  static TeimOrbitFile parse(const std::string& text, const std::string& path);

  const std::string& path() const { return path_; }
  const std::vector<TeimOrbitSection>& sections() const { return sections_; }
  const TeimOrbitSection* section(const std::string& name) const;
  /// "path:LINE: " (or "path: " for line 0), the prefix of every message about the file.
  std::string where(int line) const;

 private:
  std::string path_;
  std::vector<TeimOrbitSection> sections_;
};

class TeimOrbitReader {
 public:
  /// Checks the optional [MDI_HEADER] (FILE_TYPE = file_type, FILE_VERSION a number,
  /// FILE_FORMAT = 'ASCII', a (COMMENTS) table; each optional, a wrong one an error) and
  /// reads [UNITS] (LENGTH, FORCE, ANGLE, MASS, TIME, optional PRESSURE).
  TeimOrbitReader(const TeimOrbitFile& file, const std::string& file_type);

  /// The number at [section] key in SI, or nothing when the key is absent or blank.
  std::optional<double> number(const std::string& section, const std::string& key, const Dimension& dimension = {});
  /// As number(), with 'meaning' in the message when the key is missing.
  double required_number(const std::string& section, const std::string& key, const Dimension& dimension,
                         const std::string& meaning);
  /// A string value (quoted, or a bare word), or nothing when the key is absent or blank.
  std::optional<std::string> string(const std::string& section, const std::string& key);
  /// The line of a key (0 when absent), for messages about its value.
  int line(const std::string& section, const std::string& key) const;
  /// A table, or nullptr when absent; name "" is the section's own table.
  const TeimOrbitTable* table(const std::string& section, const std::string& name);
  /// A table's row converted to numbers in SI (every entry of 'dimension').
  std::vector<double> row_numbers(const TeimOrbitTable& table, size_t row, const Dimension& dimension) const;

  /// Throws for the first section, key or table of the file that was never asked for,
  /// or for a repeated key anywhere.
  void finish() const;
  /// For a file of another program's schema: throws only for a key of a section of
  /// 'checked' that is neither read nor listed there, and that is spelt like a key read (a
  /// misspelling of a key tirefe uses, with the closest name). Everything else is that
  /// program's and passed over.
  void finish_foreign(const std::map<std::string, std::vector<std::string>>& checked) const;

  const TeimOrbitFile& file() const { return file_; }
  const UnitSystem& units() const { return units_; }
  [[noreturn]] void fail(int line, const std::string& message) const;

 private:
  /// The key's value; a key given twice is an error naming both lines.
  const TeimOrbitValue* find(const std::string& section, const std::string& key) const;
  double to_number(const std::string& section, const TeimOrbitValue& value, const Dimension& dimension) const;

  const TeimOrbitFile& file_;
  UnitSystem units_;
  std::set<std::pair<std::string, std::string>> known_;  // (SECTION, KEY) and (SECTION, (TABLE)), upper case
};

/// Writes a file section by section: "KEY = value  $ comment" lines, numbers in the
/// shortest form that reads back to the same double.
class TeimOrbitWriter {
 public:
  /// [MDI_HEADER] and [UNITS] (SI), with 'comments' as its (COMMENTS) lines.
  TeimOrbitWriter(const std::string& file_type, const std::vector<std::string>& comments);
  void section(const std::string& name);
  void number(const std::string& key, double value, const std::string& comment = "");
  void string(const std::string& key, const std::string& value, const std::string& comment = "");
  const std::string& text() const { return text_; }
  /// Writes the text to 'path' (TeimOrbitError when it cannot).
  void save(const std::string& path) const;

 private:
  void line(const std::string& key, const std::string& value, const std::string& comment);
  std::string text_;
};

/// Names and keywords of TeimOrbit files compare without case ('ASCII', 'ascii').
bool same_name(const std::string& a, const std::string& b);
/// The text in upper case (ASCII letters), as names compare.
std::string upper(std::string text);
/// The text without the blanks around it (spaces, tabs, a carriage return).
std::string trimmed(const std::string& text);

/// The shortest decimal text that reads back as exactly 'value'.
std::string round_trip_number(double value);

}  // namespace tirefe::formats
