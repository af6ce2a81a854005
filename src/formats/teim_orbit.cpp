#include "formats/teim_orbit.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/spelling.hpp"

namespace tirefe::formats {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool is_name(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(),
                                      [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

bool is_quote(char c) { return c == '\'' || c == '"'; }

/// Position of the first 'wanted' character outside quoted strings.
size_t find_unquoted(const std::string& line, char wanted) {
  char quote = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    if (quote) {
      if (line[i] == quote) quote = 0;
    } else if (is_quote(line[i])) {
      quote = line[i];
    } else if (line[i] == wanted) {
      return i;
    }
  }
  return std::string::npos;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

/// Whitespace- or comma-separated tokens; a quoted string is one token (without its quotes).
std::optional<std::vector<std::string>> split_tokens(const std::string& text) {
  std::vector<std::string> tokens;
  size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == ',') {
      ++i;
    } else if (is_quote(c)) {
      const size_t close = text.find(c, i + 1);
      if (close == std::string::npos) return std::nullopt;
      tokens.push_back(text.substr(i + 1, close - i - 1));
      i = close + 1;
    } else {
      const size_t end = text.find_first_of(" \t,", i);
      tokens.push_back(text.substr(i, end == std::string::npos ? std::string::npos : end - i));
      i = end == std::string::npos ? text.size() : end;
    }
  }
  return tokens;
}

/// A finite number filling the whole text (a subnormal one too: strtod flags it ERANGE).
std::optional<double> parse_number(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

bool is_number_row(const std::vector<std::string>& tokens) {
  return !tokens.empty() && std::all_of(tokens.begin(), tokens.end(),
                                        [](const std::string& token) { return parse_number(token).has_value(); });
}

/// The first control byte of a line other than tab and carriage return: a NUL cuts a value
/// short in every C string routine, so a file holding one is refused rather than misread.
std::optional<unsigned char> control_byte(const std::string& line) {
  for (const char c : line) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && byte != '\t' && byte != '\r') || byte == 0x7f) return byte;
  }
  return std::nullopt;
}

// ---- units -------------------------------------------------------------------------

struct KnownUnit {
  const char* quantity;
  std::vector<const char*> names;  // the first is the one listed in messages
  double numerator, denominator;   // SI value of one unit = numerator / denominator
};

// Names as ADAMS/Tire and MF-Tyre files write them, and the usual abbreviations
// (case-insensitive). Exact ratios where the definition is exact (an inch is 0.0254 m).
const std::vector<KnownUnit>& known_units() {
  static const std::vector<KnownUnit> units{{"LENGTH", {"meter", "metre", "m"}, 1.0, 1.0},
                                            {"LENGTH", {"mm", "millimeter", "millimetre"}, 1.0, 1000.0},
                                            {"LENGTH", {"cm", "centimeter", "centimetre"}, 1.0, 100.0},
                                            {"LENGTH", {"km", "kilometer", "kilometre"}, 1000.0, 1.0},
                                            {"LENGTH", {"inch", "in"}, 127.0, 5000.0},
                                            {"LENGTH", {"foot", "ft"}, 381.0, 1250.0},
                                            {"LENGTH", {"mile"}, 201168.0, 125.0},
                                            {"FORCE", {"newton", "n"}, 1.0, 1.0},
                                            {"FORCE", {"kN", "kilo_newton", "kilonewton"}, 1000.0, 1.0},
                                            {"FORCE", {"lbf", "pound_force"}, 4.4482216152605, 1.0},
                                            {"FORCE", {"kpound_force", "kip"}, 4448.2216152605, 1.0},
                                            {"FORCE", {"dyne"}, 1.0, 100000.0},
                                            {"FORCE", {"ounce_force", "ozf"}, 0.27801385095378125, 1.0},
                                            {"MASS", {"kg", "kilogram"}, 1.0, 1.0},
                                            {"MASS", {"gram", "g"}, 1.0, 1000.0},
                                            {"MASS", {"tonne"}, 1000.0, 1.0},
                                            {"MASS", {"lbm", "pound_mass"}, 0.45359237, 1.0},
                                            {"MASS", {"kpound_mass"}, 453.59237, 1.0},
                                            {"MASS", {"slug"}, 4.4482216152605, 0.3048},
                                            {"MASS", {"ounce_mass"}, 0.028349523125, 1.0},
                                            {"TIME", {"second", "sec", "s"}, 1.0, 1.0},
                                            {"TIME", {"millisecond", "ms"}, 1.0, 1000.0},
                                            {"TIME", {"minute", "min"}, 60.0, 1.0},
                                            {"TIME", {"hour"}, 3600.0, 1.0},
                                            {"ANGLE", {"radians", "radian", "rad"}, 1.0, 1.0},
                                            {"ANGLE", {"degrees", "degree", "deg"}, kPi, 180.0},
                                            {"PRESSURE", {"pascal", "pa"}, 1.0, 1.0},
                                            {"PRESSURE", {"kPa", "kilopascal"}, 1000.0, 1.0},
                                            {"PRESSURE", {"MPa", "megapascal"}, 1e6, 1.0},
                                            {"PRESSURE", {"bar"}, 1e5, 1.0},
                                            {"PRESSURE", {"psi"}, 4.4482216152605, 0.00064516}};
  return units;
}

struct BaseQuantity {
  const char* word;
  const char* si;
  int Dimension::*exponent;
};
const BaseQuantity kBases[] = {{"force", "N", &Dimension::force},   {"mass", "kg", &Dimension::mass},
                               {"length", "m", &Dimension::length}, {"time", "s", &Dimension::time},
                               {"angle", "rad", &Dimension::angle}, {"pressure", "Pa", &Dimension::pressure}};

/// "a b^2/(c d)" from the bases' names; 'one' when dimensionless.
std::string format_dimension(const Dimension& dimension, bool si, const char* one) {
  std::vector<std::string> above, below;
  for (const BaseQuantity& base : kBases) {
    const int exponent = dimension.*base.exponent;
    if (exponent == 0) continue;
    std::string factor = si ? base.si : base.word;
    if (std::abs(exponent) > 1) factor += "^" + std::to_string(std::abs(exponent));
    (exponent > 0 ? above : below).push_back(factor);
  }
  auto spaced = [](const std::vector<std::string>& factors) {
    std::string out;
    for (const auto& factor : factors) out += (out.empty() ? "" : " ") + factor;
    return out;
  };
  if (above.empty() && below.empty()) return one;
  std::string text = above.empty() ? "1" : spaced(above);
  if (below.size() == 1) text += "/" + below.front();
  if (below.size() > 1) text += "/(" + spaced(below) + ")";
  return text;
}

}  // namespace

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

bool same_name(const std::string& a, const std::string& b) { return upper(a) == upper(b); }

std::string si_unit(const Dimension& dimension) { return format_dimension(dimension, true, ""); }
std::string dimension_name(const Dimension& dimension) { return format_dimension(dimension, false, "-"); }

UnitSystem::UnitSystem() = default;

const std::vector<std::pair<std::string, std::string>>& UnitSystem::si_units() {
  static const std::vector<std::pair<std::string, std::string>> units{
      {"LENGTH", "meter"}, {"FORCE", "newton"}, {"ANGLE", "radians"}, {"MASS", "kg"}, {"TIME", "second"}};
  return units;
}

std::optional<std::string> UnitSystem::set(const std::string& quantity, const std::string& unit) {
  const std::string key = upper(quantity);
  Scale* target = key == "LENGTH"  ? &length_
                  : key == "FORCE" ? &force_
                  : key == "MASS"  ? &mass_
                  : key == "TIME"  ? &time_
                  : key == "ANGLE" ? &angle_
                                   : nullptr;
  if (!target && key != "PRESSURE")
    return "unknown quantity '" + quantity + "' (known: LENGTH, FORCE, ANGLE, MASS, TIME, PRESSURE)";
  std::vector<std::string> names;
  for (const KnownUnit& known : known_units()) {
    if (known.quantity != key) continue;
    names.push_back(known.names.front());
    for (const char* name : known.names)
      if (same_name(name, unit)) {
        const Scale scale{known.numerator, known.denominator};
        if (target)
          *target = scale;
        else
          pressure_ = scale;
        return std::nullopt;
      }
  }
  std::vector<std::string> every;
  for (const KnownUnit& known : known_units())
    if (known.quantity == key) every.insert(every.end(), known.names.begin(), known.names.end());
  const std::string hint = did_you_mean(unit, every);
  std::string word = quantity;
  std::transform(word.begin(), word.end(), word.begin(), [](unsigned char c) { return std::tolower(c); });
  return quantity + " = '" + unit + "' is not a known " + word + " unit (" + (hint.empty() ? "" : hint + "; ") +
         "known: " + join(names) + ")";
}

double UnitSystem::to_si(double value, const Dimension& dimension) const {
  double numerator = 1.0, denominator = 1.0;
  auto apply = [&](const Scale& scale, int exponent) {
    for (int i = 0; i < std::abs(exponent); ++i) {
      numerator *= exponent > 0 ? scale.numerator : scale.denominator;
      denominator *= exponent > 0 ? scale.denominator : scale.numerator;
    }
  };
  apply(length_, dimension.length + (pressure_ ? 0 : -2 * dimension.pressure));
  apply(force_, dimension.force + (pressure_ ? 0 : dimension.pressure));
  apply(mass_, dimension.mass);
  apply(time_, dimension.time);
  apply(angle_, dimension.angle);
  if (pressure_) apply(*pressure_, dimension.pressure);
  // One rounding when either is 1 (a value in mm reads as the same double as in m).
  if (numerator == 1.0) return value / denominator;
  if (denominator == 1.0) return value * numerator;
  return value * numerator / denominator;
}

// ---- parsing -----------------------------------------------------------------------

std::string TeimOrbitFile::where(int line) const {
  return path_ + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": ";
}

TeimOrbitFile TeimOrbitFile::read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw TeimOrbitError(path + ": cannot open the file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse(text, path);
}

const TeimOrbitSection* TeimOrbitFile::section(const std::string& name) const {
  for (const auto& section : sections_)
    if (same_name(section.name, name)) return &section;
  return nullptr;
}

const TeimOrbitTable* TeimOrbitSection::own_table() const {
  for (const auto& table : tables)
    if (table.name.empty()) return &table;
  return nullptr;
}

TeimOrbitFile TeimOrbitFile::parse(const std::string& text, const std::string& path) {
  TeimOrbitFile file;
  file.path_ = path;
  std::istringstream in(text);
  std::string raw;
  TeimOrbitSection* section = nullptr;
  TeimOrbitTable* table = nullptr;
  bool columns_allowed = false;  // right after a table's (NAME) line or a section's header
  for (int number = 1; std::getline(in, raw); ++number) {
    const auto fail = [&](const std::string& message) { throw TeimOrbitError(file.where(number) + message); };
    if (const auto byte = control_byte(raw)) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", *byte);
      fail(std::string(*byte == 0 ? "a NUL byte" : "a control byte (" + std::string(hex) + ")") +
           " in the line: the file is damaged or not text (write it again as plain text)");
    }
    const size_t comment = find_unquoted(raw, '$');
    const std::string line = trimmed(comment == std::string::npos ? raw : raw.substr(0, comment));
    if (line.empty() || line.front() == '!') continue;
    const bool was_columns_allowed = columns_allowed;
    columns_allowed = false;

    if (line.front() == '[' || line.front() == '(') {
      const char close = line.front() == '[' ? ']' : ')';
      const std::string name = trimmed(line.substr(1, line.size() - 2));
      if (line.back() != close || !is_name(name))
        fail(std::string("expected ") + (close == ']' ? "a section header [NAME]" : "a table header (NAME)") +
             ", got '" + line + "'");
      if (close == ']') {
        for (const auto& existing : file.sections_)
          if (same_name(existing.name, name))
            fail("section [" + name + "] appears twice (first at line " + std::to_string(existing.line) + ")");
        file.sections_.push_back({name, number, {}, {}});
        section = &file.sections_.back();
        table = nullptr;
        columns_allowed = true;  // the column names of the section's own table
      } else {
        if (!section) fail("table (" + name + ") outside a section (start one with [NAME])");
        for (const auto& existing : section->tables)
          if (same_name(existing.name, name))
            fail("[" + section->name + "] has two tables (" + name + ") (first at line " +
                 std::to_string(existing.line) + ")");
        section->tables.push_back({name, number, {}, {}, {}});
        table = &section->tables.back();
        columns_allowed = true;
      }
      continue;
    }
    if (line.front() == '{') {
      if (!was_columns_allowed)
        fail("column names { ... } belong on the line after a table's (NAME) or a section's [NAME]");
      if (line.back() != '}') fail("column names are written { name name ... }");
      const auto columns = split_tokens(line.substr(1, line.size() - 2));
      if (!columns) fail("unterminated string in the column names");
      if (!table) {  // the section's own table
        section->tables.push_back({"", number, {}, {}, {}});
        table = &section->tables.back();
      }
      table->columns = *columns;
      continue;
    }
    const size_t equals = find_unquoted(line, '=');
    if (equals != std::string::npos) {
      if (!section) fail("'" + line + "' outside a section (start one with [NAME])");
      const std::string key = trimmed(line.substr(0, equals)), value = trimmed(line.substr(equals + 1));
      if (!is_name(key)) fail("'" + key + "' is not a key name (letters, digits and _)");
      TeimOrbitValue entry{key, value, false, number, 0};
      if (!value.empty() && is_quote(value.front())) {
        const size_t close = value.find(value.front(), 1);
        if (close == std::string::npos) fail("[" + section->name + "] " + key + ": unterminated string " + value);
        if (close != value.size() - 1)
          fail("[" + section->name + "] " + key + ": text after the string: " + value.substr(close + 1));
        entry.text = value.substr(1, close - 1);
        entry.quoted = true;
      } else if (value.find_first_of(" \t") != std::string::npos) {
        fail("[" + section->name + "] " + key + " = " + value + ": one value expected (quote a string: '...')");
      }
      for (const auto& existing : section->values)
        if (same_name(existing.key, key) && !existing.first_line) entry.first_line = existing.line;
      section->values.push_back(entry);
      table = nullptr;
      continue;
    }
    const auto row = split_tokens(line);
    if (!row) fail("unterminated string in the row '" + line + "'");
    if (!table && section && was_columns_allowed && is_number_row(*row)) {  // the section's own table, no names
      section->tables.push_back({"", number, {}, {}, {}});
      table = &section->tables.back();
    }
    if (!table) fail("expected [SECTION], (TABLE), KEY = value or a table row, got '" + line + "'");
    table->rows.push_back(*row);
    table->row_lines.push_back(number);
    // A section's own table continues while its rows are numbers.
    if (table->name.empty() && !is_number_row(*row))
      fail("[" + section->name + "] row '" + line + "': the rows of a section's table are numbers");
  }
  return file;
}

// ---- reading by schema ---------------------------------------------------------------

TeimOrbitReader::TeimOrbitReader(const TeimOrbitFile& file, const std::string& file_type) : file_(file) {
  // The header is optional (many tire files start at [UNITS]); what it says must fit.
  if (const auto type = string("MDI_HEADER", "FILE_TYPE"); type && !same_name(*type, file_type))
    fail(line("MDI_HEADER", "FILE_TYPE"), "FILE_TYPE = '" + *type + "': this reader takes '" + file_type + "' files");
  number("MDI_HEADER", "FILE_VERSION");
  if (const auto format = string("MDI_HEADER", "FILE_FORMAT"); format && !same_name(*format, "ASCII"))
    fail(line("MDI_HEADER", "FILE_FORMAT"),
         "[MDI_HEADER] FILE_FORMAT = '" + *format + "': tirefe reads text files (FILE_FORMAT = 'ASCII')");
  table("MDI_HEADER", "COMMENTS");

  const TeimOrbitSection* units = file.section("UNITS");
  if (!units) fail(0, "no [UNITS] section (LENGTH, FORCE, ANGLE, MASS and TIME, e.g. LENGTH = 'meter')");
  for (const auto& [quantity, si] : UnitSystem::si_units()) {
    const auto unit = string("UNITS", quantity);
    if (!unit) fail(units->line, "[UNITS] has no " + quantity + " (e.g. " + quantity + " = '" + si + "')");
    if (const auto problem = units_.set(quantity, *unit)) fail(line("UNITS", quantity), "[UNITS] " + *problem);
  }
  if (const auto pressure = string("UNITS", "PRESSURE"))
    if (const auto problem = units_.set("PRESSURE", *pressure)) fail(line("UNITS", "PRESSURE"), "[UNITS] " + *problem);
}

void TeimOrbitReader::fail(int line, const std::string& message) const {
  throw TeimOrbitError(file_.where(line) + message);
}

namespace {

std::string repeat_message(const TeimOrbitSection& section, const TeimOrbitValue& value) {
  return "[" + section.name + "] " + value.key + " is given twice (first at line " + std::to_string(value.first_line) +
         ")";
}

}  // namespace

const TeimOrbitValue* TeimOrbitReader::find(const std::string& section, const std::string& key) const {
  const TeimOrbitSection* found = file_.section(section);
  if (!found) return nullptr;
  const TeimOrbitValue* first = nullptr;
  for (const auto& value : found->values) {
    if (!same_name(value.key, key)) continue;
    if (value.first_line) fail(value.line, repeat_message(*found, value));
    first = &value;
  }
  return first;
}

int TeimOrbitReader::line(const std::string& section, const std::string& key) const {
  const TeimOrbitValue* value = find(section, key);
  return value ? value->line : 0;
}

double TeimOrbitReader::to_number(const std::string& section, const TeimOrbitValue& value,
                                  const Dimension& dimension) const {
  const std::string what = "[" + section + "] " + value.key + " = ";
  if (value.quoted) fail(value.line, what + "'" + value.text + "' is a string, not a number");
  const auto number = parse_number(value.text);
  if (!number) fail(value.line, what + value.text + " is not a finite number");
  return units_.to_si(*number, dimension);
}

std::optional<double> TeimOrbitReader::number(const std::string& section, const std::string& key,
                                              const Dimension& dimension) {
  known_.insert({upper(section), upper(key)});
  const TeimOrbitValue* value = find(section, key);
  if (!value || (value->text.empty() && !value->quoted)) return std::nullopt;  // absent or blank
  return to_number(section, *value, dimension);
}

double TeimOrbitReader::required_number(const std::string& section, const std::string& key, const Dimension& dimension,
                                        const std::string& meaning) {
  if (const auto value = number(section, key, dimension)) return *value;
  const TeimOrbitSection* found = file_.section(section);
  const std::string unit = dimension_name(dimension);
  const TeimOrbitValue* blank = find(section, key);
  fail(blank   ? blank->line
       : found ? found->line
               : 0,
       (blank ? "[" + section + "] " + key + " has no value" : "missing [" + section + "] " + key) + " (" + meaning +
           (dimension.dimensionless() ? "" : ", a " + unit) + ")");
}

std::optional<std::string> TeimOrbitReader::string(const std::string& section, const std::string& key) {
  known_.insert({upper(section), upper(key)});
  const TeimOrbitValue* value = find(section, key);
  if (!value || (value->text.empty() && !value->quoted)) return std::nullopt;  // absent or blank
  return value->text;
}

const TeimOrbitTable* TeimOrbitReader::table(const std::string& section, const std::string& name) {
  known_.insert({upper(section), "(" + upper(name) + ")"});
  const TeimOrbitSection* found = file_.section(section);
  if (!found) return nullptr;
  for (const auto& table : found->tables)
    if (same_name(table.name, name)) return &table;
  return nullptr;
}

std::vector<double> TeimOrbitReader::row_numbers(const TeimOrbitTable& table, size_t row,
                                                 const Dimension& dimension) const {
  std::vector<double> values;
  for (const std::string& token : table.rows[row]) {
    const auto number = parse_number(token);
    if (!number) fail(table.row_lines[row], "(" + table.name + ") row: '" + token + "' is not a finite number");
    values.push_back(units_.to_si(*number, dimension));
  }
  return values;
}

void TeimOrbitReader::finish() const {
  // The known names of a section (or the known sections, for "") in sorted order.
  auto known_in = [&](const std::string& section, bool tables) {
    std::vector<std::string> names;
    for (const auto& [known_section, name] : known_) {
      if (section.empty()) {
        if (names.empty() || names.back() != known_section) names.push_back(known_section);
      } else if (known_section == section && (name.front() == '(') == tables) {
        names.push_back(tables ? name.substr(1, name.size() - 2) : name);
      }
    }
    return names;
  };
  auto hint = [](const std::string& name, const std::vector<std::string>& known, const char* kind) {
    const std::string suggestion = did_you_mean(name, known);
    return " (" + (suggestion.empty() ? suggestion : suggestion + "; ") + "known " + kind + ": " +
           (known.empty() ? std::string("none") : join(known)) + ")";
  };
  int first_line = 0;
  std::string first_message;
  auto report = [&](int line, const std::string& message) {
    if (first_message.empty() || line < first_line) first_line = line, first_message = message;
  };
  const std::vector<std::string> sections = known_in("", false);
  for (const TeimOrbitSection& section : file_.sections()) {
    const std::string name = upper(section.name);
    if (std::find(sections.begin(), sections.end(), name) == sections.end()) {
      std::vector<std::string> bracketed;
      for (const auto& known : sections) bracketed.push_back("[" + known + "]");
      report(section.line, "unknown section [" + section.name + "]" + hint("[" + name + "]", bracketed, "sections"));
      continue;
    }
    for (const TeimOrbitValue& value : section.values) {
      if (!known_.count({name, upper(value.key)}))
        report(value.line, "[" + section.name + "] unknown key '" + value.key + "'" +
                               hint(upper(value.key), known_in(name, false), "keys"));
      else if (value.first_line)
        report(value.line, repeat_message(section, value));
    }
    for (const TeimOrbitTable& table : section.tables)
      if (!known_.count({name, "(" + upper(table.name) + ")"}))
        report(table.line, table.name.empty() ? "[" + section.name + "] holds rows of values, which it does not take"
                                              : "[" + section.name + "] unknown table (" + table.name + ")" +
                                                    hint(upper(table.name), known_in(name, true), "tables"));
  }
  if (!first_message.empty()) fail(first_line, first_message);
}

void TeimOrbitReader::finish_foreign(const std::map<std::string, std::vector<std::string>>& checked) const {
  for (const auto& [checked_section, listed] : checked) {
    const TeimOrbitSection* section = file_.section(checked_section);
    if (!section) continue;
    const std::string name = upper(section->name);
    std::vector<std::string> used;
    for (const auto& [known_section, key] : known_)
      if (known_section == name && key.front() != '(') used.push_back(key);
    for (const TeimOrbitValue& value : section->values) {
      const std::string key = upper(value.key);
      if (known_.count({name, key}) || std::find(listed.begin(), listed.end(), key) != listed.end()) continue;
      const std::string suggestion = did_you_mean(key, used);
      if (!suggestion.empty())
        fail(value.line, "[" + section->name + "] unknown key '" + value.key + "' (" + suggestion +
                             " tirefe reads that one; a key tirefe does not read is passed over)");
    }
  }
}

// ---- writing -----------------------------------------------------------------------

std::string round_trip_number(double value) {
  // The fewest significant digits that read back as the same bits, written without an
  // exponent where that stays short (3000000 rather than 3e+06).
  char buffer[64];
  int digits = 1;
  for (; digits < 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*e", digits - 1, value);
    const double back = std::strtod(buffer, nullptr);
    if (std::memcmp(&back, &value, sizeof value) == 0) break;
  }
  std::snprintf(buffer, sizeof buffer, "%.*e", digits - 1, value);
  const int exponent = std::atoi(std::strchr(buffer, 'e') + 1);
  if (std::isfinite(value) && exponent >= -5 && exponent < 16)
    std::snprintf(buffer, sizeof buffer, "%.*f", std::max(0, digits - 1 - exponent), value);
  return buffer;
}

TeimOrbitWriter::TeimOrbitWriter(const std::string& file_type, const std::vector<std::string>& comments) {
  section("MDI_HEADER");
  string("FILE_TYPE", file_type);
  line("FILE_VERSION", "1.0", "");
  string("FILE_FORMAT", "ASCII");
  text_ += "(COMMENTS)\n{comment_string}\n";
  for (const std::string& comment : comments) {
    const char quote = comment.find('\'') == std::string::npos ? '\'' : '"';
    if (comment.find(quote) != std::string::npos || comment.find('\n') != std::string::npos)
      throw TeimOrbitError("a comment line may not hold both quotes (' and \") or a line break: " + comment);
    text_ += quote + comment + quote + "\n";
  }
  section("UNITS");
  for (const auto& [quantity, unit] : UnitSystem::si_units()) string(quantity, unit);
}

void TeimOrbitWriter::section(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  text_ += "$" + std::string(std::max<size_t>(3, 71 - lower.size()), '-') + lower + "\n[" + name + "]\n";
}

void TeimOrbitWriter::line(const std::string& key, const std::string& value, const std::string& comment) {
  std::string text = key;
  text.resize(std::max<size_t>(text.size(), 34), ' ');
  text += "= " + value;
  if (!comment.empty()) {
    text.resize(std::max<size_t>(text.size() + 1, 58), ' ');
    text += "$ " + comment;
  }
  text_ += text + "\n";
}

void TeimOrbitWriter::number(const std::string& key, double value, const std::string& comment) {
  line(key, round_trip_number(value), comment);
}

void TeimOrbitWriter::string(const std::string& key, const std::string& value, const std::string& comment) {
  if (value.find('\'') != std::string::npos) throw TeimOrbitError(key + ": a string may not hold a quote (')");
  line(key, "'" + value + "'", comment);
}

void TeimOrbitWriter::save(const std::string& path) const {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text_;
  out.close();
  if (!out) throw TeimOrbitError(path + ": cannot write the file");
}

}  // namespace tirefe::formats
