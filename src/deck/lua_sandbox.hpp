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

/// One parameter a deck declares: tirefe.parameters{ name = default } or, documented,
/// tirefe.parameters{ name = { default, "meaning", unit = "unit" } } (meaning, unit optional).
struct ParameterDeclaration {
  std::string name, default_text, unit, meaning;
};

// The bytes the Lua state of a deck may hold (string.rep(1e9) or a table of millions of
// entries is refused there, not by the machine running out of memory).
constexpr size_t kDefaultLuaMemoryMiB = 1024;

class LuaSandbox {
 public:
  // lua_dir: the project's lua/ folder (modules shipped with tirefe).
  explicit LuaSandbox(std::string lua_dir);
  ~LuaSandbox();
  LuaSandbox(const LuaSandbox&) = delete;  // the Lua registry points back at this object
  LuaSandbox& operator=(const LuaSandbox&) = delete;

  lua_State* state() { return state_; }

  // Runs a deck file (Lua source text only). 'overrides' are command-line key=value pairs
  // consumed by tirefe.parameters{...}. Every failure is thrown as DeckError.
  void run_file(const std::string& deck_path, const std::map<std::string, std::string>& overrides = {});

  // Sets tirefe[name] = f (creating the global 'tirefe' table if needed).
  void register_function(const char* name, lua_CFunction f);

  // Called by tirefe.parameters{...} with the resolved parameters (name, value as text),
  // sorted by name: the result file records which case a run is.
  using ParametersObserver = std::function<void(const std::vector<std::pair<std::string, std::string>>&)>;
  void set_parameters_observer(ParametersObserver observer) { parameters_observer_ = std::move(observer); }

  // --list-parameters: run_file ends the deck at its tirefe.parameters{...} call, or at
  // its first use of another tirefe function (no macros are installed then).
  void stop_at_parameters() { stop_at_parameters_ = true; }
  // What the deck's tirefe.parameters{...} declared, sorted by name.
  const std::vector<ParameterDeclaration>& declared_parameters() const { return declared_; }

  const std::string& deck_path() const { return deck_path_; }
  const std::string& deck_text() const { return deck_text_; }
  const std::string& lua_dir() const { return lua_dir_; }
  const std::map<std::string, std::string>& overrides() const { return overrides_; }
  // Full Lua traceback of the last runtime error, for --verbose.
  const std::string& last_traceback() const { return last_traceback_; }

  // The sandbox owning L, or nullptr for a plain Lua state.
  static LuaSandbox* from(lua_State* L);

  // At most this many MiB of Lua memory (kDefaultLuaMemoryMiB unless set); an allocation
  // beyond it fails as Lua's "not enough memory", reported as the deck using too much.
  void set_memory_limit_mib(size_t mib) { memory_.limit = mib << 20; }
  size_t memory_limit_mib() const { return memory_.limit >> 20; }
  // True once an allocation was refused for the limit: the run's memory error is the deck's.
  bool memory_exceeded() const { return memory_.refused; }
  // "the deck used more than N MiB of Lua memory ..." (the message of such a failure).
  std::string memory_message() const;

 private:
  // The Lua allocator's account: bytes in use and the bound, and where the deck was
  // when an allocation was refused (a memory error carries no location of its own).
  struct MemoryAccount {
    size_t used = 0;
    size_t limit = kDefaultLuaMemoryMiB << 20;
    bool refused = false;
    std::string refused_at;  // "deck.lua:LINE: ", or "" if unknown
    LuaSandbox* sandbox = nullptr;
  };
  static void* allocate(void* account, void* block, size_t old_size, size_t new_size);
  static void stop_hook(lua_State* L, lua_Debug* ar);
  static int message_handler(lua_State* L);
  void open_safe_libraries();

  MemoryAccount memory_;
  std::string lua_dir_;
  lua_State* state_ = nullptr;
  std::string deck_path_;
  std::string deck_text_;
  std::map<std::string, std::string> overrides_;
  std::string last_traceback_;
  bool parameters_called_ = false;
  bool stop_at_parameters_ = false;
  bool stopped_ = false;  // by stop_at_parameters
  std::vector<ParameterDeclaration> declared_;
  ParametersObserver parameters_observer_;

  friend int lua_parameters(lua_State* L);
  friend int stop_before_macro(lua_State* L);
};

// "deck.lua:LINE: " for the innermost stack level running the deck itself (so errors raised
// inside helper modules still point at the deck line), else the innermost Lua level; "" if none.
std::string deck_location(lua_State* L);
// The same for a known deck path; reads the call stack only (pushes nothing, allocates no
// Lua memory), so the allocator may call it.
std::string deck_location(lua_State* L, const std::string& deck_path);

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
// The tirefe table's __index under stop_at_parameters: the deck is past its parameters.
int stop_before_macro(lua_State* L);

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
