#include "macros/macro_table.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "macros/deck_model.hpp"

namespace tirefe::macros {

namespace {

/// " (did you mean 'x'?)" for the closest known name, or "".
std::string suggestion(const std::string& name, const std::vector<std::string>& known) {
  std::string best;
  size_t best_distance = 3;  // suggest only close names
  for (const auto& candidate : known) {
    std::vector<size_t> row(candidate.size() + 1), next(candidate.size() + 1);
    for (size_t j = 0; j <= candidate.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= name.size(); ++i) {
      next[0] = i;
      for (size_t j = 1; j <= candidate.size(); ++j)
        next[j] = std::min({row[j] + 1, next[j - 1] + 1, row[j - 1] + (name[i - 1] == candidate[j - 1] ? 0 : 1)});
      std::swap(row, next);
    }
    if (row.back() < best_distance) {
      best_distance = row.back();
      best = candidate;
    }
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

constexpr const char* kModelMetatable = "tirefe.model";
constexpr const char* kSessionKey = "tirefe.session";

DeckSession& session_of(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kSessionKey);
  auto* session = static_cast<DeckSession*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return *session;
}

/// Calls without arguments (model:step()) get an empty argument table.
void ensure_argument_table(lua_State* L, int index) {
  if (lua_isnoneornil(L, index)) {
    lua_settop(L, index - 1);
    lua_newtable(L);
  }
}

int call_module_macro(lua_State* L) {
  const auto& macro = macro_table().module_macros[lua_tointeger(L, lua_upvalueindex(1))];
  ensure_argument_table(L, 1);
  std::string failure;
  try {
    MacroArguments arguments(L, 1, macro.spec);
    return macro.handler(L, session_of(L), arguments);
  } catch (const std::exception& error) {
    failure = "macro '" + macro.spec.name + "': " + error.what();
  }
  raise_deck_error(L, failure);
}

int call_model_macro(lua_State* L) {
  const auto& macro = macro_table().model_macros[lua_tointeger(L, lua_upvalueindex(1))];
  if (!luaL_testudata(L, 1, kModelMetatable))
    raise_deck_error(L, "model:" + macro.spec.name + " must be called with a colon on a model (model:" +
                            macro.spec.name + "{...})");
  ensure_argument_table(L, 2);
  std::string failure;
  try {
    MacroArguments arguments(L, 2, macro.spec);
    return macro.handler(L, check_model(L, 1), arguments);
  } catch (const std::exception& error) {
    failure = "macro '" + macro.spec.name + "': " + error.what();
  }
  raise_deck_error(L, failure);
}

/// __index of models and of the tirefe table: an unknown name is a deck error with a suggestion.
int unknown_macro(lua_State* L) {
  const char* name = lua_tostring(L, 2);
  if (!name) return 0;
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
  const bool on_model = lua_toboolean(L, lua_upvalueindex(2));
  std::vector<std::string> known;
  lua_pushnil(L);
  while (lua_next(L, lua_upvalueindex(1))) {
    if (lua_type(L, -2) == LUA_TSTRING) known.push_back(lua_tostring(L, -2));
    lua_pop(L, 1);
  }
  raise_deck_error(L, std::string(on_model ? "models have no macro '" : "tirefe has no macro '") + name + "'" +
                          suggestion(name, known));
}

int collect_model(lua_State* L) {
  auto* owner = static_cast<std::unique_ptr<DeckModel>*>(luaL_checkudata(L, 1, kModelMetatable));
  owner->~unique_ptr();
  return 0;
}

}  // namespace

const MacroTable& macro_table() {
  static const MacroTable table = [] {
    MacroTable built;
    add_model_macros(built);
    add_dynamics_macros(built);
    add_tire_macros(built);
    add_tire_file_macros(built);
    add_contact_macros(built);
    add_fitting_macros(built);
    add_post_macros(built);
    add_vehicle_macros(built);
    add_checkpoint_macros(built);
    return built;
  }();
  return table;
}

std::string deck_relative(const DeckSession& session, const std::string& file) {
  std::filesystem::path path(file);
  if (path.is_relative() && !session.deck_path.empty())
    path = std::filesystem::path(session.deck_path).parent_path() / path;
  return path.string();
}

namespace {

// Creates the folder of the output 'file' with its missing parents, naming the one that
// cannot be made and why (a read-only parent, a file in the way) rather than leaving the
// file's creation to fail with "No such file or directory".
void create_output_folder(const std::filesystem::path& file) {
  auto failure = [&](const std::filesystem::path& folder, const std::string& reason) {
    return std::runtime_error("cannot create the output folder '" + folder.string() + "' for '" + file.string() +
                              "': " + reason);
  };
  std::filesystem::path made;
  for (const std::filesystem::path& part : file.parent_path()) {
    made /= part;
    std::error_code error;
    if (std::filesystem::is_directory(made, error)) continue;
    if (std::filesystem::exists(made, error)) throw failure(made, "a file of that name is in the way");
    if (!std::filesystem::create_directory(made, error) && error) throw failure(made, error.message());
  }
}

}  // namespace

std::string deck_output_path(const DeckSession& session, const std::string& file) {
  std::filesystem::path path(file);
  if (path.is_relative()) path = std::filesystem::path(session.output_dir) / path;
  if (path.has_parent_path()) create_output_folder(path);
  return path.string();
}

const MacroSpec& model_macro_spec(const std::string& name) {
  for (const auto& macro : macro_table().model_macros)
    if (macro.spec.name == name) return macro.spec;
  throw std::logic_error("no model macro '" + name + "'");
}

DeckModel& check_model(lua_State* L, int index) {
  auto* owner = static_cast<std::unique_ptr<DeckModel>*>(luaL_testudata(L, index, kModelMetatable));
  if (!owner || !*owner) raise_deck_error(L, "expected a model made by tirefe.model{...}");
  if (!(*owner)->stale().empty()) raise_deck_error(L, (*owner)->stale());
  return **owner;
}

DeckModel& push_new_model(lua_State* L, const std::string& title, DeckSession& session) {
  void* memory = lua_newuserdatauv(L, sizeof(std::unique_ptr<DeckModel>), 0);
  auto* owner = new (memory) std::unique_ptr<DeckModel>(std::make_unique<DeckModel>(title, session));
  luaL_setmetatable(L, kModelMetatable);
  return **owner;
}

void install_macros(LuaSandbox& sandbox, DeckSession& session) {
  lua_State* L = sandbox.state();
  lua_pushlightuserdata(L, &session);
  lua_setfield(L, LUA_REGISTRYINDEX, kSessionKey);

  const MacroTable& table = macro_table();
  luaL_newmetatable(L, kModelMetatable);
  lua_newtable(L);  // methods
  for (size_t i = 0; i < table.model_macros.size(); ++i) {
    lua_pushinteger(L, static_cast<lua_Integer>(i));
    lua_pushcclosure(L, call_model_macro, 1);
    lua_setfield(L, -2, table.model_macros[i].spec.name.c_str());
  }
  lua_pushboolean(L, true);
  lua_pushcclosure(L, unknown_macro, 2);
  lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, collect_model);
  lua_setfield(L, -2, "__gc");
  lua_pushliteral(L, "locked");
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 1);

  sandbox.set_parameters_observer(
      [&session](const std::vector<std::pair<std::string, std::string>>& resolved) { session.parameters = resolved; });
  lua_getglobal(L, "tirefe");
  for (size_t i = 0; i < table.module_macros.size(); ++i) {
    lua_pushinteger(L, static_cast<lua_Integer>(i));
    lua_pushcclosure(L, call_module_macro, 1);
    lua_setfield(L, -2, table.module_macros[i].spec.name.c_str());
  }
  // Reads of unknown names (tirefe.modle) are errors; the macros live in a shadow table.
  lua_newtable(L);  // metatable
  lua_newtable(L);  // shadow holding the macros
  lua_pushnil(L);
  while (lua_next(L, -4)) {
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_rawset(L, -4);
  }
  lua_pushboolean(L, false);
  lua_pushcclosure(L, unknown_macro, 2);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, -2);
  lua_pop(L, 1);
}

std::string macro_reference() {
  std::vector<MacroSpec> specs;
  for (const auto& macro : macro_table().module_macros) {
    specs.push_back(macro.spec);
    specs.back().name = "tirefe." + macro.spec.name;
  }
  for (const auto& macro : macro_table().model_macros) {
    specs.push_back(macro.spec);
    specs.back().name = "model:" + macro.spec.name;
  }
  return markdown_reference(specs);
}

}  // namespace tirefe::macros
