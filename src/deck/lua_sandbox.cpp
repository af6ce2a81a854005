// LuaSandbox: safe library set, text-only loading, require(), tirefe.parameters and the
// error plumbing that reports every deck problem as "deck.lua:LINE: message".
#include "deck/lua_sandbox.hpp"

#include "deck/deck_files.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <utility>
#include <vector>

#include "deck/deck_files.hpp"
#include "deck/interrupt.hpp"

namespace tirefe::macros {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSandboxKey = "tirefe.sandbox";  // registry: light userdata -> LuaSandbox
constexpr const char* kLoadedKey = "tirefe.loaded";    // registry: require() cache

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out.empty() ? "none" : out;
}

// Full path for file chunks (short_src truncates long paths to 60 characters).
std::string display_name(const lua_Debug& ar) {
  return ar.source[0] == '@' ? std::string(ar.source + 1) : std::string(ar.short_src);
}

struct Location {
  std::string file, line, body;
};

// Splits the "where:LINE: " prefix that luaL_where and the parser put on messages.
std::optional<Location> split_location(const std::string& message) {
  for (auto colon = message.find(':'); colon != std::string::npos; colon = message.find(':', colon + 1)) {
    auto end = colon + 1;
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) ++end;
    if (end > colon + 1 && message.compare(end, 2, ": ") == 0)
      return Location{message.substr(0, colon), message.substr(colon + 1, end - colon - 1), message.substr(end + 2)};
  }
  return std::nullopt;
}

// The chunk on the current stack that a message prefix names (display name, is it the deck?).
// A prefix naming no running chunk is ordinary message text and is left alone.
std::optional<std::pair<std::string, bool>> chunk_on_stack(lua_State* L, const std::string& file,
                                                           const std::string& deck_path) {
  if (!deck_path.empty() && file == deck_path) return std::make_pair(deck_path, true);
  lua_Debug ar;
  for (int level = 0; lua_getstack(L, level, &ar); ++level) {
    lua_getinfo(L, "S", &ar);
    if (file == ar.short_src || file == display_name(ar))
      return std::make_pair(display_name(ar), !deck_path.empty() && ar.source == "@" + deck_path);
  }
  return std::nullopt;
}

// load() with the mode forced to text: precompiled chunks bypass the parser's checks.
int text_only_load(lua_State* L) {
  if (lua_gettop(L) < 3) lua_settop(L, 3);  // pads chunkname/mode; an absent 'env' must stay absent
  lua_pushliteral(L, "t");
  lua_replace(L, 3);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// setmetatable without finalisers: Lua turns hooks off while a __gc metamethod runs, so a
// finaliser that loops would be deaf to the stop hook (SIGINT, SIGTERM). A __gc added to a
// metatable afterwards marks nothing for finalisation (Lua 5.4, section 2.5.3).
int setmetatable_without_gc(lua_State* L) {
  lua_settop(L, 2);
  if (lua_type(L, 2) == LUA_TTABLE && (lua_pushliteral(L, "__gc"), lua_rawget(L, 2) != LUA_TNIL))
    raise_deck_error(L,
                     "setmetatable: a deck may not set a __gc finaliser (Lua runs finalisers where SIGINT and "
                     "SIGTERM cannot stop them); release what the table holds explicitly");
  lua_settop(L, 2);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, 2, 1);
  return 1;
}

// Is the table at 'index' plain data (numbers, strings, booleans and such tables, no
// metatable)? 'seen' (absolute index) holds the tables already visited, for cycles.
bool is_data_table(lua_State* L, int index, int seen) {
  index = lua_absindex(L, index);
  if (lua_getmetatable(L, index)) {
    lua_pop(L, 1);
    return false;
  }
  lua_pushvalue(L, index);
  const bool visited = lua_rawget(L, seen) != LUA_TNIL;
  lua_pop(L, 1);
  if (visited) return true;
  lua_pushvalue(L, index);
  lua_pushboolean(L, 1);
  lua_rawset(L, seen);
  luaL_checkstack(L, 4, "parameter table nested too deep");
  lua_pushnil(L);
  while (lua_next(L, index)) {
    const int type = lua_type(L, -1);
    const bool data = type == LUA_TTABLE ? is_data_table(L, -1, seen)
                                         : type != LUA_TFUNCTION && type != LUA_TUSERDATA && type != LUA_TTHREAD &&
                                               type != LUA_TLIGHTUSERDATA;
    lua_pop(L, 1);
    if (!data) {
      lua_pop(L, 1);
      return false;
    }
  }
  return true;
}

// Pushes a deep copy of the data table at 'index'; 'copies' (absolute index) maps each
// original table to its copy, so shared and cyclic parts keep their shape.
void push_deep_copy(lua_State* L, int index, int copies) {
  index = lua_absindex(L, index);
  lua_pushvalue(L, index);
  if (lua_rawget(L, copies) != LUA_TNIL) return;
  lua_pop(L, 1);
  lua_newtable(L);
  const int copy = lua_gettop(L);
  lua_pushvalue(L, index);
  lua_pushvalue(L, copy);
  lua_rawset(L, copies);
  luaL_checkstack(L, 4, "parameter table nested too deep");
  lua_pushnil(L);
  while (lua_next(L, index)) {
    if (lua_istable(L, -1)) {
      push_deep_copy(L, -1, copies);
      lua_replace(L, -2);
    }
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_rawset(L, copy);
  }
}

// Replaces the module value on top of the stack by what require hands out: a parameter
// table (plain data) as a fresh deep copy, so that one deck's 'set.y = ...' cannot reach
// the next require; a library (a table holding functions) or any other value as it is.
void hand_out_module(lua_State* L) {
  if (!lua_istable(L, -1)) return;
  lua_newtable(L);
  const bool data = is_data_table(L, -2, lua_gettop(L));
  lua_pop(L, 1);
  if (!data) return;
  lua_newtable(L);
  push_deep_copy(L, -2, lua_gettop(L));
  lua_replace(L, -3);
  lua_pop(L, 1);
}

// require(name): <deck dir>/name.lua, <deck dir>/name/init.lua, then the same under lua_dir.
// The loaded value is cached; parameter tables are handed out as copies (hand_out_module).
int lua_require(lua_State* L) {
  const std::string name = luaL_checkstring(L, 1);
  lua_settop(L, 1);
  lua_getfield(L, LUA_REGISTRYINDEX, kLoadedKey);  // 2
  if (lua_getfield(L, 2, name.c_str()) != LUA_TNIL) {
    hand_out_module(L);
    return 1;
  }
  lua_pop(L, 1);
  if (name.empty() || name.front() == '.' || name.find_first_of("/\\") != std::string::npos ||
      name.find("..") != std::string::npos)
    raise_deck_error(L, "require: invalid module name '" + name + "' (use dots for folders, e.g. 'tire.profiles')");

  std::string relative = name;
  std::replace(relative.begin(), relative.end(), '.', '/');
  const LuaSandbox* self = LuaSandbox::from(L);
  std::vector<fs::path> dirs;
  if (self) {
    const fs::path deck_dir = fs::path(self->deck_path()).parent_path();
    dirs.push_back(deck_dir.empty() ? fs::path(".") : deck_dir);
    if (!self->lua_dir().empty()) dirs.emplace_back(self->lua_dir());
  }
  std::vector<std::string> tried;
  for (const auto& dir : dirs) {
    for (const auto& candidate : {dir / (relative + ".lua"), dir / relative / "init.lua"}) {
      tried.push_back(candidate.string());
      std::error_code ec;
      if (!fs::is_regular_file(candidate, ec)) continue;
      if (!lies_within(resolved_path(candidate), resolved_path(dir)))  // a symlink out of the folder
        raise_deck_error(L, "module '" + name + "': '" + tried.back() +
                                "' is a symbolic link out of its folder; modules are read from the deck's folder "
                                "and lua/ only (docs/security.md)");
      if (luaL_loadfilex(L, tried.back().c_str(), "t") != LUA_OK)
        raise_deck_error(L, "cannot load module '" + name + "': " + error_text(L, -1));
      lua_pushstring(L, name.c_str());
      lua_pushstring(L, tried.back().c_str());
      lua_call(L, 2, 1);
      if (lua_isnil(L, -1)) {  // modules returning nothing are cached as 'true', as in standard Lua
        lua_pop(L, 1);
        lua_pushboolean(L, 1);
      }
      lua_pushvalue(L, -1);
      lua_setfield(L, 2, name.c_str());
      hand_out_module(L);
      return 1;
    }
  }
  raise_deck_error(L, "module '" + name + "' not found; searched: " + join(tried));
}

// The string on top of the stack, popped: a documented parameter's meaning or unit ("" if nil).
std::string optional_text(lua_State* L, const std::string& form, const char* what) {
  std::string text;
  if (lua_type(L, -1) == LUA_TSTRING)
    text = lua_tostring(L, -1);
  else if (!lua_isnil(L, -1))
    raise_deck_error(L, form + ": the " + what + " must be a string, not a " + luaL_typename(L, -1));
  lua_pop(L, 1);
  return text;
}

// The declaration of parameter 'name' whose value is on top of the stack. A documented
// one, { default, "meaning", unit = "..." }, is replaced there by its default (left on the stack).
ParameterDeclaration read_declaration(lua_State* L, const std::string& name) {
  ParameterDeclaration declaration{name, "", "", ""};
  if (lua_istable(L, -1)) {
    const int table = lua_gettop(L);
    const std::string form = "tirefe.parameters: " + name + " = { default, \"meaning\", unit = \"...\" }";
    lua_pushnil(L);
    while (lua_next(L, table)) {
      lua_pop(L, 1);
      const bool known = lua_isinteger(L, -1)
                             ? lua_tointeger(L, -1) == 1 || lua_tointeger(L, -1) == 2
                             : lua_type(L, -1) == LUA_TSTRING && std::string(lua_tostring(L, -1)) == "unit";
      if (!known) raise_deck_error(L, form + " takes no key '" + luaL_tolstring(L, -1, nullptr) + "'");
    }
    lua_rawgeti(L, table, 2);
    declaration.meaning = optional_text(L, form, "meaning");
    lua_getfield(L, table, "unit");
    declaration.unit = optional_text(L, form, "unit");
    lua_rawgeti(L, table, 1);
    const int type = lua_type(L, -1);
    if (type != LUA_TNUMBER && type != LUA_TBOOLEAN && type != LUA_TSTRING)
      raise_deck_error(L, form + ": the default comes first, a number, boolean or string");
    lua_replace(L, table);
  }
  if (lua_type(L, -1) == LUA_TNUMBER && !lua_isinteger(L, -1)) {
    char text[32];  // 2e7 reads better as 20000000 than as Lua's 20000000.0
    std::snprintf(text, sizeof text, "%.14g", lua_tonumber(L, -1));
    declaration.default_text = text;
  } else {
    declaration.default_text = luaL_tolstring(L, -1, nullptr);
    lua_pop(L, 1);
  }
  return declaration;
}

}  // namespace

std::string error_text(lua_State* L, int index) {
  if (lua_type(L, index) == LUA_TSTRING || lua_type(L, index) == LUA_TNUMBER) return lua_tostring(L, index);
  if (luaL_callmeta(L, index, "__tostring")) {
    const bool is_text = lua_type(L, -1) == LUA_TSTRING;
    std::string text = is_text ? lua_tostring(L, -1) : "";
    lua_pop(L, 1);
    if (is_text) return text;
  }
  // error({...}) or error(nil): nothing to print but the kind, and what a deck should do.
  return std::string("error called with a ") + luaL_typename(L, index) +
         " value instead of a message (write error(\"what is wrong\"), or give the value a __tostring)";
}

// Instructions between two looks at the stop flag: a few microseconds of Lua.
constexpr int kStopHookInstructions = 10000;

LuaSandbox::LuaSandbox(std::string lua_dir) : lua_dir_(std::move(lua_dir)) {
  memory_.sandbox = this;
  state_ = lua_newstate(allocate, &memory_);
  if (!state_) throw std::runtime_error("cannot create a Lua state (out of memory)");
  lua_State* L = state();
  // An error outside any protected call (a load function called by a host's step through
  // the C API) becomes an exception with the error's own text, which names its deck line.
  lua_atpanic(L, [](lua_State* P) -> int { throw std::runtime_error(error_text(P, -1)); });
  // A deck looping in pure Lua still stops on SIGINT / SIGTERM (coroutines inherit the hook).
  lua_sethook(L, stop_hook, LUA_MASKCOUNT, kStopHookInstructions);
  lua_pushlightuserdata(L, this);
  lua_setfield(L, LUA_REGISTRYINDEX, kSandboxKey);
  lua_newtable(L);
  lua_setfield(L, LUA_REGISTRYINDEX, kLoadedKey);
  open_safe_libraries();
  register_function("parameters", protected_call<lua_parameters>);
}

LuaSandbox::~LuaSandbox() { lua_close(state_); }

void* LuaSandbox::allocate(void* account, void* block, size_t old_size, size_t new_size) {
  auto& memory = *static_cast<MemoryAccount*>(account);
  if (!block) old_size = 0;  // then old_size is the kind of object, not a size
  if (new_size == 0) {
    std::free(block);
    memory.used -= old_size;
    return nullptr;
  }
  if (new_size > old_size && new_size - old_size > memory.limit - std::min(memory.used, memory.limit)) {
    if (!memory.refused && memory.sandbox && memory.sandbox->state_)
      memory.refused_at = deck_location(memory.sandbox->state_, memory.sandbox->deck_path_);
    memory.refused = true;
    return nullptr;  // Lua raises its memory error
  }
  void* moved = std::realloc(block, new_size);
  if (!moved) return nullptr;
  memory.used = memory.used - old_size + new_size;
  if (new_size > old_size) memory.refused = false;  // Lua's retry after an emergency collection worked
  return moved;
}

std::string LuaSandbox::memory_message() const {
  return "the deck used more than " + std::to_string(memory_limit_mib()) +
         " MiB of Lua memory (the limit; --lua-memory MIB sets another)";
}

void LuaSandbox::stop_hook(lua_State* L, lua_Debug*) {
  const int signal = stop_signal().load();
  if (!signal) {
    // A host's cancel that was answered leaves a state looking every instruction: back to the pace.
    if (lua_gethookcount(L) != kStopHookInstructions) lua_sethook(L, stop_hook, LUA_MASKCOUNT, kStopHookInstructions);
    return;
  }
  // From now on every instruction raises again: a deck catching the error with pcall
  // cannot go on, the error climbs to the top; in the main thread too, where a coroutine's
  // error ends as a value of coroutine.resume or coroutine.close.
  lua_sethook(L, stop_hook, LUA_MASKCOUNT, 1);
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
  lua_sethook(lua_tothread(L, -1), stop_hook, LUA_MASKCOUNT, 1);
  lua_pop(L, 1);
  raise_deck_error(L, std::string("stopped by ") + stop_cause(signal) + " while the deck ran Lua code");
}

LuaSandbox* LuaSandbox::from(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kSandboxKey);
  auto* self = static_cast<LuaSandbox*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return self;
}

void LuaSandbox::open_safe_libraries() {
  lua_State* L = state();
  static const luaL_Reg libraries[] = {{LUA_GNAME, luaopen_base},        {LUA_TABLIBNAME, luaopen_table},
                                       {LUA_STRLIBNAME, luaopen_string}, {LUA_MATHLIBNAME, luaopen_math},
                                       {LUA_UTF8LIBNAME, luaopen_utf8},  {LUA_COLIBNAME, luaopen_coroutine}};
  for (const auto& library : libraries) {
    luaL_requiref(L, library.name, library.func, 1);
    lua_pop(L, 1);
  }
  // os: clocks, dates and environment only; the rest reaches files and processes.
  luaL_requiref(L, LUA_OSLIBNAME, luaopen_os, 0);
  lua_newtable(L);
  for (const char* name : {"clock", "time", "date", "getenv"}) {
    lua_getfield(L, -2, name);
    lua_setfield(L, -2, name);
  }
  lua_setglobal(L, LUA_OSLIBNAME);
  lua_pop(L, 1);

  for (const char* name : {"dofile", "loadfile"}) {  // file access goes through require() only
    lua_pushnil(L);
    lua_setglobal(L, name);
  }
  lua_getglobal(L, "load");
  lua_pushcclosure(L, text_only_load, 1);
  lua_setglobal(L, "load");
  lua_getglobal(L, "setmetatable");
  lua_pushcclosure(L, setmetatable_without_gc, 1);
  lua_setglobal(L, "setmetatable");
  lua_pushcfunction(L, lua_require);
  lua_setglobal(L, "require");
}

void LuaSandbox::register_function(const char* name, lua_CFunction f) {
  lua_State* L = state();
  if (lua_getglobal(L, "tirefe") != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setglobal(L, "tirefe");
  }
  lua_pushcfunction(L, f);
  lua_setfield(L, -2, name);
  lua_pop(L, 1);
}

int LuaSandbox::message_handler(lua_State* L) {
  LuaSandbox* self = from(L);
  const std::string deck = self ? self->deck_path_ : std::string();
  std::string where = deck_location(L);
  std::string text = error_text(L, 1);
  // Re-anchor Lua's own "file:LINE: " prefix on the deck line; keep the inner origin as a hint.
  if (const auto location = split_location(text)) {
    if (const auto chunk = chunk_on_stack(L, location->file, deck)) {
      const std::string origin = chunk->first + ":" + location->line;
      text = location->body;
      if (chunk->second)
        where = origin + ": ";  // may be a caller's line, via error(msg, 2)
      else if (origin + ": " != where)
        text += " (raised at " + origin + ")";
    }
  }
  if (where.empty() && !deck.empty()) where = deck + ": ";
  text = where + text;
  luaL_traceback(L, L, text.c_str(), 1);
  if (self) self->last_traceback_ = lua_tostring(L, -1);
  lua_pushstring(L, text.c_str());
  return 1;
}

void LuaSandbox::run_file(const std::string& deck_path, const std::map<std::string, std::string>& overrides) {
  deck_path_ = deck_path;
  overrides_ = overrides;
  parameters_called_ = false;
  last_traceback_.clear();
  try {
    require_regular_file(deck_path);
  } catch (const std::runtime_error& error) {  // ModelError
    throw DeckError(deck_path + ": " + error.what());
  }
  std::ifstream in(deck_path, std::ios::binary);
  if (!in) throw DeckError(deck_path + ": cannot open the deck file");
  deck_text_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (deck_text_.rfind(LUA_SIGNATURE, 0) == 0)
    throw DeckError(deck_path + ": is a precompiled (binary) Lua chunk; decks must be Lua source text");
  register_function("parameters", protected_call<lua_parameters>);  // the bindings may have replaced 'tirefe'

  lua_State* L = state();
  stopped_ = false;
  declared_.clear();
  if (stop_at_parameters_) {
    lua_getglobal(L, "tirefe");
    lua_newtable(L);
    lua_pushcfunction(L, stop_before_macro);
    lua_setfield(L, -2, "__index");
    lua_setmetatable(L, -2);
    lua_pop(L, 1);
  }
  const int base = lua_gettop(L);
  lua_pushcfunction(L, message_handler);
  int status = luaL_loadfilex(L, deck_path.c_str(), "t");
  const bool loaded = status == LUA_OK;
  if (loaded) status = lua_pcall(L, 0, 0, base + 1);
  if (status != LUA_OK && stopped_) status = LUA_OK;
  if (status != LUA_OK) {
    std::string message = error_text(L, -1);
    lua_settop(L, base);
    if (status == LUA_ERRMEM) message = (memory_.refused ? memory_.refused_at : std::string()) + memory_message();
    memory_.refused = false;
    if (!loaded) {  // the parser names the deck by its (possibly truncated) short_src
      if (const auto location = split_location(message))
        message = deck_path + ":" + location->line + ": " + location->body;
    }
    if (message.rfind(deck_path + ":", 0) != 0) message = deck_path + ": " + message;
    throw DeckError(message);
  }
  lua_settop(L, base);
  if (!parameters_called_ && !overrides_.empty() && !stop_at_parameters_)
    throw DeckError(deck_path + ": command-line parameter '" + overrides_.begin()->first +
                    "' is not declared by the deck (declare it with tirefe.parameters{...})");
}

std::string deck_location(lua_State* L) {
  const LuaSandbox* self = LuaSandbox::from(L);
  return deck_location(L, self ? self->deck_path() : std::string());
}

std::string deck_location(lua_State* L, const std::string& deck_path) {
  const std::string deck_source = deck_path.empty() ? std::string() : "@" + deck_path;
  std::string innermost;
  lua_Debug ar;
  for (int level = 0; lua_getstack(L, level, &ar); ++level) {
    lua_getinfo(L, "Sl", &ar);
    if (ar.currentline <= 0) continue;  // C functions carry no line
    std::string where = display_name(ar) + ":" + std::to_string(ar.currentline) + ": ";
    if (!deck_source.empty() && deck_source == ar.source) return where;
    if (innermost.empty()) innermost = std::move(where);
  }
  return innermost;
}

void raise_deck_error(lua_State* L, const std::string& message) {
  const std::string text = deck_location(L) + message;
  lua_pushlstring(L, text.data(), text.size());
  lua_error(L);  // C++ build: throws, so 'text' and the callers' locals are destroyed properly
  std::abort();  // unreachable; lua_error is not declared [[noreturn]]
}

bool push_parsed(lua_State* L, int lua_type, bool integer, const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  if (lua_type == LUA_TNUMBER && integer) {
    const long long value = std::strtoll(begin, &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE) return false;
    lua_pushinteger(L, static_cast<lua_Integer>(value));
  } else if (lua_type == LUA_TNUMBER) {
    const double value = std::strtod(begin, &end);
    if (text.empty() || *end != '\0' || !std::isfinite(value)) return false;
    lua_pushnumber(L, value);
  } else if (lua_type == LUA_TBOOLEAN) {
    if (text != "true" && text != "false") return false;
    lua_pushboolean(L, text == "true");
  } else if (lua_type == LUA_TSTRING) {
    lua_pushlstring(L, text.data(), text.size());
  } else {
    return false;
  }
  return true;
}

int lua_parameters(lua_State* L) {
  if (!lua_istable(L, 1))
    raise_deck_error(L, "tirefe.parameters expects a table of defaults, e.g. tirefe.parameters{ speed_kmh = 50 }");
  lua_settop(L, 1);
  lua_newtable(L);  // 2: the result; the deck's defaults table stays untouched
  std::vector<ParameterDeclaration> declarations;
  lua_pushnil(L);
  while (lua_next(L, 1)) {
    if (lua_type(L, -2) != LUA_TSTRING) raise_deck_error(L, "tirefe.parameters: parameter names must be strings");
    declarations.push_back(read_declaration(L, lua_tostring(L, -2)));
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_rawset(L, 2);
  }
  std::sort(declarations.begin(), declarations.end(),
            [](const ParameterDeclaration& a, const ParameterDeclaration& b) { return a.name < b.name; });
  std::vector<std::string> declared;
  for (const auto& declaration : declarations) declared.push_back(declaration.name);

  LuaSandbox* self = LuaSandbox::from(L);
  if (!self) return 1;
  self->parameters_called_ = true;
  self->declared_ = declarations;
  if (self->stop_at_parameters_) {
    self->stopped_ = true;
    raise_deck_error(L, "stopped after tirefe.parameters (--list-parameters)");
  }
  for (const auto& [key, text] : self->overrides_) {
    lua_getfield(L, 2, key.c_str());
    const int type = lua_type(L, -1);
    const bool is_integer = lua_isinteger(L, -1);
    const std::string default_text = luaL_tolstring(L, -1, nullptr);
    lua_pop(L, 2);
    if (type == LUA_TNIL)
      raise_deck_error(
          L, "command-line parameter '" + key + "' is not declared by the deck (declared: " + join(declared) + ")");
    if (type != LUA_TNUMBER && type != LUA_TBOOLEAN && type != LUA_TSTRING)
      raise_deck_error(L,
                       "command-line parameter '" + key + "' cannot override a " + lua_typename(L, type) + " default");
    if (!push_parsed(L, type, is_integer, text)) {
      const char* expected = type == LUA_TBOOLEAN ? "true or false" : is_integer ? "an integer" : "a number";
      raise_deck_error(L, "command-line parameter '" + key + "=" + text + "' must be " + expected +
                              " like its default " + default_text);
    }
    lua_setfield(L, 2, key.c_str());
  }
  if (self->parameters_observer_) {
    std::vector<std::pair<std::string, std::string>> resolved;
    for (const std::string& name : declared) {
      lua_getfield(L, 2, name.c_str());
      resolved.emplace_back(name, luaL_tolstring(L, -1, nullptr));
      lua_pop(L, 2);
    }
    self->parameters_observer_(resolved);
  }
  return 1;
}

int stop_before_macro(lua_State* L) {
  if (LuaSandbox* self = LuaSandbox::from(L)) self->stopped_ = true;
  raise_deck_error(L, "stopped before tirefe." + std::string(luaL_tolstring(L, 2, nullptr)) + " (--list-parameters)");
}

}  // namespace tirefe::macros
