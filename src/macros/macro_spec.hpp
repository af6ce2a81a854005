// Declarative specs for deck macros: every macro takes one table of named arguments, and
// its MacroSpec both validates a call (MacroArguments) and generates the reference docs.
#pragma once

#include <lua.hpp>

#include <optional>
#include <string>
#include <vector>

namespace tirefe::macros {

enum class ValueType {
  Number,
  Integer,
  String,
  Boolean,
  NumberList,
  IntegerList,
  NumberMatrix,  // list of equal-length number lists
  StringList,    // entries checked against the choices, if any
  Function,
  Table,  // free-form, checked by the binding
  Any
};

enum class Range { Any, Positive, NonNegative, Fraction01 /* [0,1] */ };

/// The largest value an Integer key takes unless its spec sets a smaller one: counts,
/// node numbers and intervals are C++ ints, and a larger Lua integer would wrap.
constexpr long long kIntegerLimit = 2147483647;

struct ParameterSpec {
  std::string key;
  ValueType type = ValueType::Number;
  bool required = false;
  std::string unit;
  std::string doc;
  // Shown in the docs; for scalar types also the value the plain accessors return when the key is absent.
  std::optional<std::string> default_value = std::nullopt;
  Range range = Range::Any;               // applies to numbers and to every entry of number lists/matrices
  std::vector<std::string> choices = {};  // allowed values of a String key (empty: any)
  long long maximum = kIntegerLimit;      // the largest value of an Integer key or IntegerList entry
};

struct MacroSpec {
  std::string name;  // called as tirefe.<name>{...}
  std::string doc;
  std::vector<ParameterSpec> parameters;
  std::string example;
};

/// Why a number is outside the parameter's range ("must be positive (got -1)"), or nothing.
std::optional<std::string> range_problem(const ParameterSpec& p, double value);

// The validated view of one macro call's argument table. The constructor raises a Lua error
// at the deck line (raise_deck_error) on any violation of the spec. Accessors on a key absent
// from the call return its spec default; with no default they throw (a binding bug, reported
// at the deck line by protected_call). The *_or variants return the given fallback instead.
// Holds a reference to 'spec' (specs are meant to be static) and reads the table lazily.
class MacroArguments {
 public:
  MacroArguments(lua_State* L, int table_index, const MacroSpec& spec);

  bool has(const std::string& key) const;
  double number(const std::string& key) const;
  double number_or(const std::string& key, double fallback) const;
  long long integer(const std::string& key) const;
  long long integer_or(const std::string& key, long long fallback) const;
  std::string string(const std::string& key) const;
  std::string string_or(const std::string& key, const std::string& fallback) const;
  bool boolean(const std::string& key) const;
  std::vector<double> number_list(const std::string& key) const;
  std::vector<long long> integer_list(const std::string& key) const;
  std::vector<std::vector<double>> number_matrix(const std::string& key) const;
  std::vector<std::string> string_list(const std::string& key) const;
  // Pushes the raw value (nil when absent), e.g. for Function and Table keys.
  void push_value(const std::string& key) const;

  const MacroSpec& spec() const { return spec_; }

 private:
  const ParameterSpec& parameter(const std::string& key) const;
  template <class T>
  T read(const std::string& key, ValueType as, const T* fallback, T (*convert)(lua_State*, int)) const;

  lua_State* L_;
  int table_;
  const MacroSpec& spec_;
};

// Markdown reference: one section per macro with its doc, a key table and the example.
std::string markdown_reference(const std::vector<MacroSpec>& specs);

}  // namespace tirefe::macros
