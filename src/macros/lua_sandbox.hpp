// The Lua state an input deck runs in: safe standard libraries only, a text-only
// require() over the deck folder and the shipped lua/ folder, command-line parameters,
// and helpers that turn every error into a one-line "deck.lua:LINE: message".
#pragma once

// Debian's liblua5.4-c++ is compiled as C++ (errors are C++ exceptions, so destructors
// run when a Lua error unwinds through our code) but its luaconf.h still declares the API
// extern "C" (nm -D shows unmangled symbols). <lua.hpp> therefore matches the library.
#include <lua.hpp>

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tirefe::macros {

// An error in an input deck; what() already starts with "deck.lua:LINE: ".
class DeckError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class LuaSandbox {
 public:
  // lua_dir: the project's lua/ folder (modules shipped with tirefe).
  explicit LuaSandbox(std::string lua_dir);
  LuaSandbox(const LuaSandbox&) = delete;  // the Lua registry points back at this object
  LuaSandbox& operator=(const LuaSandbox&) = delete;

  lua_State* state() { return state_.get(); }

  // Runs a deck file (Lua source text only). 'overrides' are command-line key=value pairs
  // consumed by tirefe.parameters{...}. Every failure is thrown as DeckError.
  void run_file(const std::string& deck_path, const std::map<std::string, std::string>& overrides = {});

  // Sets tirefe[name] = f (creating the global 'tirefe' table if needed).
  void register_function(const char* name, lua_CFunction f);

  // Called by tirefe.parameters{...} with the resolved parameters (name, value as text),
  // sorted by name: the result file records which case a run is.
  using ParametersObserver = std::function<void(const std::vector<std::pair<std::string, std::string>>&)>;
  void set_parameters_observer(ParametersObserver observer) { parameters_observer_ = std::move(observer); }

  const std::string& deck_path() const { return deck_path_; }
  const std::string& deck_text() const { return deck_text_; }
  const std::string& lua_dir() const { return lua_dir_; }
  const std::map<std::string, std::string>& overrides() const { return overrides_; }
  // Full Lua traceback of the last runtime error, for --verbose.
  const std::string& last_traceback() const { return last_traceback_; }

  // The sandbox owning L, or nullptr for a plain Lua state.
  static LuaSandbox* from(lua_State* L);

 private:
  static int message_handler(lua_State* L);
  void open_safe_libraries();
  void ensure_tirefe_table();

  std::string lua_dir_;
  std::unique_ptr<lua_State, void (*)(lua_State*)> state_;
  std::string deck_path_;
  std::string deck_text_;
  std::map<std::string, std::string> overrides_;
  std::string last_traceback_;
  bool parameters_called_ = false;
  ParametersObserver parameters_observer_;

  friend int lua_parameters(lua_State* L);
};

// "deck.lua:LINE: " for the innermost stack level running the deck itself (so errors raised
// inside helper modules still point at the deck line), else the innermost Lua level; "" if none.
std::string deck_location(lua_State* L);

// The text of an error value: a string or number as is, else its __tostring, else what
// it is ("error called with a table value instead of a message ...").
std::string error_text(lua_State* L, int index);

// Raises a Lua error carrying deck_location(L) + message. Never returns.
[[noreturn]] void raise_deck_error(lua_State* L, const std::string& message);

// Pushes 'text' parsed as a Lua value of lua_type (LUA_TNUMBER, an integer if 'integer',
// LUA_TBOOLEAN from true/false, LUA_TSTRING); false, nothing pushed, if it does not parse.
bool push_parsed(lua_State* L, int lua_type, bool integer, const std::string& text);

// tirefe.parameters(defaults): a new table holding the defaults with the command-line
// overrides applied, each converted to its default's type.
int lua_parameters(lua_State* L);

// Wraps a C++ binding so that a std::exception it throws becomes a Lua error at the deck
// line. Lua's own errors (a pointer type in the C++ build) pass through untouched.
template <int (*F)(lua_State*)>
int protected_call(lua_State* L) {
  std::string message;
  try {
    return F(L);
  } catch (const std::exception& e) {
    message = e.what();
  }
  // Raised outside the handler: the caught exception is already destroyed.
  raise_deck_error(L, message);
}

}  // namespace tirefe::macros
