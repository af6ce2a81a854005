// Validation of macro argument tables against their MacroSpec, typed accessors, and the
// generated Markdown reference. One checker per value type serves validation and accessors.
#include "macros/macro_spec.hpp"

#include "core/spelling.hpp"
#include "deck/lua_sandbox.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tirefe::macros {
namespace {

using Problem = std::optional<std::string>;  // a violation message, starting with "key '...'"

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

std::string format_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.14g", value);
  return buffer;
}

const char* type_name(ValueType type) {
  switch (type) {
    case ValueType::Number: return "number";
    case ValueType::Integer: return "integer";
    case ValueType::String: return "string";
    case ValueType::Boolean: return "boolean";
    case ValueType::NumberList: return "list of numbers";
    case ValueType::IntegerList: return "list of integers";
    case ValueType::NumberMatrix: return "list of equal-length number lists";
    case ValueType::StringList: return "list of strings";
    case ValueType::Function: return "function";
    case ValueType::Table: return "table";
    case ValueType::Any: return "any value";
  }
  return "?";
}

std::string with_article(ValueType type) {
  const std::string name = type_name(type);
  return (name.front() == 'i' ? "an " : "a ") + name;
}

// Short form for messages, e.g. string "abc" or number 2.5. Never converts numbers in place
// (lua_tostring would, which breaks lua_next traversals).
std::string describe_value(lua_State* L, int index) {
  switch (lua_type(L, index)) {
    case LUA_TSTRING: {
      std::string text = lua_tostring(L, index);
      if (text.size() > 40) text = text.substr(0, 37) + "...";
      return "string \"" + text + "\"";
    }
    case LUA_TNUMBER:
      return "number " + (lua_isinteger(L, index) ? std::to_string(lua_tointeger(L, index))
                                                  : format_number(lua_tonumber(L, index)));
    case LUA_TBOOLEAN: return lua_toboolean(L, index) ? "boolean true" : "boolean false";
    default: return luaL_typename(L, index);
  }
}

Problem type_problem(lua_State* L, int index, ValueType type, const std::string& what) {
  return what + " must be " + with_article(type) + ", got " + describe_value(L, index);
}

// An integer (an integral float such as 1e3 too) between the range's lower end and p.maximum:
// a value outside would wrap when the binding stores it in an int (2^32 + 24 as 24).
Problem integer_problem(lua_State* L, int index, const ParameterSpec& p, const std::string& what) {
  const lua_Integer value = lua_tointeger(L, index);
  const long long lowest = p.range == Range::Positive ? 1 : p.range == Range::Any ? -kIntegerLimit - 1 : 0;
  const long long highest = p.range == Range::Fraction01 ? std::min(1LL, p.maximum) : p.maximum;
  if (value >= lowest && value <= highest) return std::nullopt;
  return what + " must be an integer from " + std::to_string(lowest) + " to " + std::to_string(highest) + " (got " +
         describe_value(L, index) + ")";
}

// A list's entry and a matrix's row, named for a message.
std::string entry_name(const std::string& list, lua_Integer entry) { return list + " entry " + std::to_string(entry); }
std::string row_name(const std::string& matrix, lua_Integer row) { return matrix + " row " + std::to_string(row); }

Problem check_number(lua_State* L, int index, ValueType type, const ParameterSpec& p, const std::string& what) {
  if (lua_type(L, index) != LUA_TNUMBER) return type_problem(L, index, type, what);
  const double value = lua_tonumber(L, index);
  if (!std::isfinite(value)) return what + " is not a finite number";
  if (type == ValueType::Integer) {
    int exact = 0;
    lua_tointegerx(L, index, &exact);
    if (!exact) return type_problem(L, index, type, what);
  }
  if (const auto problem = range_problem(p, value)) return what + " " + *problem;
  if (type == ValueType::Integer) return integer_problem(L, index, p, what);
  return std::nullopt;
}

// A table whose keys are exactly 1..#t; 'index' must be absolute.
Problem check_sequence(lua_State* L, int index, ValueType type, const std::string& what) {
  if (!lua_istable(L, index)) return type_problem(L, index, type, what);
  const auto length = static_cast<lua_Integer>(lua_rawlen(L, index));
  lua_pushnil(L);
  while (lua_next(L, index)) {
    int is_integer = 0;
    const lua_Integer position = lua_tointegerx(L, -2, &is_integer);
    if (!is_integer || position < 1 || position > length) {
      Problem problem = what + " must be " + with_article(type) + " {a, b, ...}, found key " + describe_value(L, -2);
      lua_pop(L, 2);
      return problem;
    }
    lua_pop(L, 1);
  }
  return std::nullopt;
}

// A sequence of numbers (integers for IntegerList), each within p.range.
Problem check_list(lua_State* L, int index, ValueType type, const ParameterSpec& p, const std::string& what) {
  if (Problem problem = check_sequence(L, index, type, what)) return problem;
  const auto length = static_cast<lua_Integer>(lua_rawlen(L, index));
  const ValueType entry_type = type == ValueType::IntegerList ? ValueType::Integer : ValueType::Number;
  for (lua_Integer i = 1; i <= length; ++i) {
    lua_rawgeti(L, index, i);
    // An entry is named only when it has a problem: a history's list has thousands.
    Problem problem = check_number(L, lua_gettop(L), entry_type, p, what);
    if (problem) problem = check_number(L, lua_gettop(L), entry_type, p, entry_name(what, i));
    lua_pop(L, 1);
    if (problem) return problem;
  }
  return std::nullopt;
}

Problem check_matrix(lua_State* L, int index, const ParameterSpec& p, const std::string& what) {
  if (Problem problem = check_sequence(L, index, ValueType::NumberMatrix, what)) return problem;
  const auto rows = static_cast<lua_Integer>(lua_rawlen(L, index));
  size_t width = 0;
  for (lua_Integer r = 1; r <= rows; ++r) {
    lua_rawgeti(L, index, r);
    Problem problem = check_list(L, lua_gettop(L), ValueType::NumberList, p, what);
    if (problem) problem = check_list(L, lua_gettop(L), ValueType::NumberList, p, row_name(what, r));
    const size_t row_width = lua_rawlen(L, -1);
    lua_pop(L, 1);
    if (problem) return problem;
    if (r == 1) width = row_width;
    if (row_width != width)
      return row_name(what, r) + " has " + std::to_string(row_width) + " entries, expected " + std::to_string(width) +
             " like row 1";
  }
  return std::nullopt;
}

/// Text goes into result files as UTF-8 and into C strings: a NUL would cut it short
/// there, invalid UTF-8 would make the file unreadable to h5py.
Problem text_problem(const std::string& text, const std::string& what) {
  if (text.find('\0') != std::string::npos)
    return what + " holds a NUL character (\\0 at byte " + std::to_string(text.find('\0') + 1) +
           "); give text without one";
  for (size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    // The length of the sequence a leading byte starts, and the least value it may encode.
    const size_t length = byte < 0x80           ? 1
                          : (byte >> 5) == 0x6  ? 2
                          : (byte >> 4) == 0xE  ? 3
                          : (byte >> 3) == 0x1E ? 4
                                                : 0;
    bool valid = length > 0 && i + length <= text.size();
    unsigned long code = length == 1 ? byte : byte & (0x7F >> length);
    for (size_t k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      valid = (next & 0xC0) == 0x80;
      code = (code << 6) | (next & 0x3F);
    }
    const unsigned long least[] = {0, 0, 0x80, 0x800, 0x10000};
    valid = valid && code >= least[length] && code <= 0x10FFFF && (code < 0xD800 || code > 0xDFFF);
    if (!valid)
      return what + " is not UTF-8 text (byte " + std::to_string(i + 1) + " of " + std::to_string(text.size()) +
             "); save the deck as UTF-8";
    i += length;
  }
  return std::nullopt;
}

Problem check_value(lua_State* L, int index, ValueType type, const ParameterSpec& p, const std::string& what) {
  index = lua_absindex(L, index);
  switch (type) {
    case ValueType::Number:
    case ValueType::Integer: return check_number(L, index, type, p, what);
    case ValueType::NumberList:
    case ValueType::IntegerList: return check_list(L, index, type, p, what);
    case ValueType::NumberMatrix: return check_matrix(L, index, p, what);
    case ValueType::String: {
      if (lua_type(L, index) != LUA_TSTRING) return type_problem(L, index, type, what);
      size_t length = 0;
      const char* text = lua_tolstring(L, index, &length);
      if (Problem problem = text_problem(std::string(text, length), what)) return problem;
      const std::string value = text;
      if (p.choices.empty() || std::find(p.choices.begin(), p.choices.end(), value) != p.choices.end())
        return std::nullopt;
      return what + " must be one of " + join(p.choices) + " (got '" + value + "')";
    }
    case ValueType::StringList: {
      if (Problem problem = check_sequence(L, index, type, what)) return problem;
      const auto length = static_cast<lua_Integer>(lua_rawlen(L, index));
      for (lua_Integer i = 1; i <= length; ++i) {
        lua_rawgeti(L, index, i);
        Problem problem = check_value(L, -1, ValueType::String, p, what);
        if (problem) problem = check_value(L, -1, ValueType::String, p, entry_name(what, i));
        lua_pop(L, 1);
        if (problem) return problem;
      }
      return std::nullopt;
    }
    case ValueType::Boolean: return lua_isboolean(L, index) ? std::nullopt : type_problem(L, index, type, what);
    case ValueType::Function: return lua_isfunction(L, index) ? std::nullopt : type_problem(L, index, type, what);
    case ValueType::Table: return lua_istable(L, index) ? std::nullopt : type_problem(L, index, type, what);
    case ValueType::Any: return std::nullopt;
  }
  return std::nullopt;
}

std::string unknown_key_message(const MacroSpec& spec, const std::string& key) {
  std::vector<std::string> known;
  for (const auto& p : spec.parameters) known.push_back(p.key);
  const std::string hint = did_you_mean(key, known);
  return "macro '" + spec.name + "': unknown key '" + key + "' (" + (hint.empty() ? "" : hint + "; ") +
         "known keys: " + join(known) + ")";
}

int push_field(lua_State* L, int table, const std::string& key) {
  lua_pushlstring(L, key.data(), key.size());
  return lua_rawget(L, table);
}

std::vector<double> to_number_list(lua_State* L, int index) {
  index = lua_absindex(L, index);
  std::vector<double> values(lua_rawlen(L, index));
  for (size_t i = 0; i < values.size(); ++i) {
    lua_rawgeti(L, index, static_cast<lua_Integer>(i + 1));
    values[i] = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  return values;
}

}  // namespace

std::optional<std::string> range_problem(const ParameterSpec& p, double value) {
  const bool ok = p.range == Range::Positive      ? value > 0
                  : p.range == Range::NonNegative ? value >= 0
                  : p.range == Range::Fraction01  ? value >= 0 && value <= 1
                                                  : true;
  if (ok) return std::nullopt;
  const char* bound = p.range == Range::Positive      ? "positive"
                      : p.range == Range::NonNegative ? "non-negative"
                                                      : "between 0 and 1";
  return std::string("must be ") + bound + " (got " + format_number(value) + ")";
}

MacroArguments::MacroArguments(lua_State* L, int table_index, const MacroSpec& spec)
    : L_(L), table_(lua_absindex(L, table_index)), spec_(spec) {
  const std::string macro = "macro '" + spec.name + "'";
  if (!lua_istable(L, table_)) {
    const bool one_line_example = !spec.example.empty() && spec.example.find('\n') == std::string::npos;
    raise_deck_error(L, macro + " expects a table of named arguments, e.g. " +
                            (one_line_example ? spec.example : "tirefe." + spec.name + "{...}"));
  }
  std::vector<std::string> unknown;
  lua_pushnil(L);
  while (lua_next(L, table_)) {
    if (lua_type(L, -2) != LUA_TSTRING)
      raise_deck_error(L, macro + " takes named arguments only, got a positional " + describe_value(L, -1));
    std::string key = lua_tostring(L, -2);
    const bool known = std::any_of(spec.parameters.begin(), spec.parameters.end(),
                                   [&](const ParameterSpec& p) { return p.key == key; });
    if (!known) unknown.push_back(std::move(key));
    lua_pop(L, 1);
  }
  if (!unknown.empty())  // report the alphabetically first, so the message does not depend on hash order
    raise_deck_error(L, unknown_key_message(spec, *std::min_element(unknown.begin(), unknown.end())));

  for (const auto& p : spec.parameters) {
    if (push_field(L, table_, p.key) == LUA_TNIL) {
      lua_pop(L, 1);
      if (!p.required) continue;
      std::string meaning = p.doc;
      if (!p.unit.empty()) meaning += (meaning.empty() ? "" : ", ") + p.unit;
      raise_deck_error(
          L, macro + ": missing required key '" + p.key + "'" + (meaning.empty() ? "" : " (" + meaning + ")"));
    }
    const Problem problem = check_value(L, -1, p.type, p, "key '" + p.key + "'");
    lua_pop(L, 1);
    if (problem) raise_deck_error(L, macro + ": " + *problem);
  }
}

const ParameterSpec& MacroArguments::parameter(const std::string& key) const {
  for (const auto& p : spec_.parameters)
    if (p.key == key) return p;
  throw std::logic_error("macro '" + spec_.name + "': the binding reads key '" + key + "', which its spec lacks");
}

bool MacroArguments::has(const std::string& key) const {
  parameter(key);
  const bool present = push_field(L_, table_, key) != LUA_TNIL;
  lua_pop(L_, 1);
  return present;
}

void MacroArguments::push_value(const std::string& key) const {
  parameter(key);
  push_field(L_, table_, key);
}

// Absent key: the explicit fallback, else the spec default; then the same check as validation,
// which also catches a binding reading a key with the wrong accessor.
template <class T>
T MacroArguments::read(const std::string& key, ValueType as, const T* fallback, T (*convert)(lua_State*, int)) const {
  const ParameterSpec& p = parameter(key);
  const std::string macro = "macro '" + spec_.name + "': ";
  if (push_field(L_, table_, key) == LUA_TNIL) {
    lua_pop(L_, 1);
    if (fallback) return *fallback;
    const bool scalar =
        as == ValueType::Number || as == ValueType::Integer || as == ValueType::Boolean || as == ValueType::String;
    const int lua_type = as == ValueType::Boolean ? LUA_TBOOLEAN : as == ValueType::String ? LUA_TSTRING : LUA_TNUMBER;
    if (!scalar || !p.default_value || !push_parsed(L_, lua_type, as == ValueType::Integer, *p.default_value))
      throw std::logic_error(macro + "key '" + key + "' was not given and has no usable default");
  }
  if (const Problem problem = check_value(L_, -1, as, p, "key '" + key + "'")) {
    lua_pop(L_, 1);
    throw std::runtime_error(macro + *problem);
  }
  T value = convert(L_, lua_gettop(L_));
  lua_pop(L_, 1);
  return value;
}

double MacroArguments::number(const std::string& key) const {
  return read<double>(key, ValueType::Number, nullptr, [](lua_State* L, int i) { return lua_tonumber(L, i); });
}
double MacroArguments::number_or(const std::string& key, double fallback) const {
  return read<double>(key, ValueType::Number, &fallback, [](lua_State* L, int i) { return lua_tonumber(L, i); });
}
long long MacroArguments::integer(const std::string& key) const {
  return read<long long>(key, ValueType::Integer, nullptr,
                         [](lua_State* L, int i) { return static_cast<long long>(lua_tointeger(L, i)); });
}
long long MacroArguments::integer_or(const std::string& key, long long fallback) const {
  return read<long long>(key, ValueType::Integer, &fallback,
                         [](lua_State* L, int i) { return static_cast<long long>(lua_tointeger(L, i)); });
}
std::string MacroArguments::string(const std::string& key) const {
  return read<std::string>(key, ValueType::String, nullptr,
                           [](lua_State* L, int i) { return std::string(lua_tostring(L, i)); });
}
std::string MacroArguments::string_or(const std::string& key, const std::string& fallback) const {
  return read<std::string>(key, ValueType::String, &fallback,
                           [](lua_State* L, int i) { return std::string(lua_tostring(L, i)); });
}
bool MacroArguments::boolean(const std::string& key) const {
  return read<bool>(key, ValueType::Boolean, nullptr, [](lua_State* L, int i) { return lua_toboolean(L, i) != 0; });
}
std::vector<double> MacroArguments::number_list(const std::string& key) const {
  return read<std::vector<double>>(key, ValueType::NumberList, nullptr, to_number_list);
}
std::vector<long long> MacroArguments::integer_list(const std::string& key) const {
  return read<std::vector<long long>>(key, ValueType::IntegerList, nullptr, [](lua_State* L, int index) {
    std::vector<long long> values(lua_rawlen(L, index));
    for (size_t i = 0; i < values.size(); ++i) {
      lua_rawgeti(L, index, static_cast<lua_Integer>(i + 1));
      values[i] = static_cast<long long>(lua_tointeger(L, -1));
      lua_pop(L, 1);
    }
    return values;
  });
}
std::vector<std::string> MacroArguments::string_list(const std::string& key) const {
  return read<std::vector<std::string>>(key, ValueType::StringList, nullptr, [](lua_State* L, int index) {
    std::vector<std::string> values(lua_rawlen(L, index));
    for (size_t i = 0; i < values.size(); ++i) {
      lua_rawgeti(L, index, static_cast<lua_Integer>(i + 1));
      values[i] = lua_tostring(L, -1);
      lua_pop(L, 1);
    }
    return values;
  });
}
std::vector<std::vector<double>> MacroArguments::number_matrix(const std::string& key) const {
  return read<std::vector<std::vector<double>>>(key, ValueType::NumberMatrix, nullptr, [](lua_State* L, int index) {
    std::vector<std::vector<double>> rows(lua_rawlen(L, index));
    for (size_t r = 0; r < rows.size(); ++r) {
      lua_rawgeti(L, index, static_cast<lua_Integer>(r + 1));
      rows[r] = to_number_list(L, -1);
      lua_pop(L, 1);
    }
    return rows;
  });
}

std::string markdown_reference(const std::vector<MacroSpec>& specs) {
  const auto cell = [](std::string text) {  // '|' would split the table cell
    for (size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2)) text.replace(at, 1, "\\|");
    return text;
  };
  std::string out =
      "# tirefe macro reference\n\nGenerated by `tirefe --macros`. Every macro takes one table of named arguments: "
      "`tirefe.name{key = value, ...}` for the module's macros, `model:name{key = value, ...}` for the macros "
      "of a model made by `tirefe.model{...}`. Deck node numbers start at 1. See docs/decks.md for the deck "
      "language itself (`tirefe.parameters`, `require`, checks).\n";
  for (const auto& spec : specs) {
    out += "\n## " + spec.name + "\n\n" + spec.doc + "\n\n";
    out += "| key | type | unit | required / default | meaning |\n|---|---|---|---|---|\n";
    for (const auto& p : spec.parameters) {
      std::string type = type_name(p.type);
      if (p.range == Range::Positive) type += " > 0";
      if (p.range == Range::NonNegative) type += " >= 0";
      if (p.range == Range::Fraction01) type += " in [0, 1]";
      if ((p.type == ValueType::Integer || p.type == ValueType::IntegerList) && p.maximum != kIntegerLimit)
        type += ", at most " + std::to_string(p.maximum);
      const std::string need = p.required        ? "required"
                               : p.default_value ? "default `" + *p.default_value + "`"
                                                 : "optional";
      std::string meaning = p.doc;
      std::vector<std::string> choices;
      for (const auto& choice : p.choices) choices.push_back("`" + choice + "`");
      if (!choices.empty()) meaning += " One of: " + join(choices) + ".";
      out += "| `" + p.key + "` | " + cell(type) + " | " + cell(p.unit) + " | " + cell(need) + " | " + cell(meaning) +
             " |\n";
    }
    if (!spec.example.empty()) out += "\nExample:\n\n```lua\n" + spec.example + "\n```\n";
  }
  return out;
}

}  // namespace tirefe::macros
