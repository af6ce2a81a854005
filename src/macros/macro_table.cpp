#include "macros/macro_table.hpp"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <type_traits>

#include "core/spelling.hpp"
#include "deck/checkpoint.hpp"
#include "deck/deck_model.hpp"

namespace tirefe::macros {

namespace {

constexpr const char* kModelMetatable = "tirefe.model";
constexpr const char* kSessionKey = "tirefe.session";

DeckSession& session_of(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kSessionKey);
  auto* session = static_cast<DeckSession*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return *session;
}

/// print() of a deck: clears the progress line first, so that the text starts on a clean line.
int print_clearing_progress(lua_State* L) {
  session_of(L).progress.clear();
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, 0);
  return 0;
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
    raise_deck_error(
        L, "model:" + macro.spec.name + " must be called with a colon on a model (model:" + macro.spec.name + "{...})");
  ensure_argument_table(L, 2);
  std::string failure;
  try {
    DeckModel& deck = check_model(L, 1);
    // Busy before anything reaches Lua again (a collection may run a finaliser on any allocation).
    const DeckModel::Busy busy(deck, "model:" + macro.spec.name);
    MacroArguments arguments(L, 2, macro.spec);
    const int results = macro.handler(L, deck, arguments);
    if (!deck.fits()) lua_gc(L, LUA_GCCOLLECT);  // the models the deck dropped count until collected
    deck.check_size();
    return results;
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
  const std::string hint = did_you_mean(name, known);
  raise_deck_error(L, std::string(on_model ? "models have no macro '" : "tirefe has no macro '") + name + "'" +
                          (hint.empty() ? "" : " (" + hint + ")"));
}

/// What a model userdata holds. Lua frees the userdata's memory itself; its finaliser only
/// closes the model, so the handle stays a valid (empty) object should a Lua finaliser
/// resurrect the userdata, and every later macro on it says the model was closed.
struct ModelHandle {
  std::unique_ptr<DeckModel> model;
};
static_assert(std::is_nothrow_default_constructible_v<ModelHandle>);

int collect_model(lua_State* L) {
  static_cast<ModelHandle*>(luaL_checkudata(L, 1, kModelMetatable))->model.reset();
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

const MacroSpec& model_macro_spec(const std::string& name) {
  for (const auto& macro : macro_table().model_macros)
    if (macro.spec.name == name) return macro.spec;
  throw std::logic_error("no model macro '" + name + "'");
}

DeckModel& check_model(lua_State* L, int index) {
  auto* handle = static_cast<ModelHandle*>(luaL_testudata(L, index, kModelMetatable));
  if (!handle) raise_deck_error(L, "expected a model made by tirefe.model{...}");
  if (!handle->model)
    raise_deck_error(L,
                     "this model was closed when Lua collected it (a finaliser kept it): "
                     "keep the model in a variable for as long as the deck uses it");
  DeckModel& deck = *handle->model;
  if (!deck.stale().empty()) raise_deck_error(L, deck.stale());
  if (!deck.busy_with().empty())
    raise_deck_error(L, "model '" + deck.title() + "' is busy in " + deck.busy_with() +
                            ": a Lua function called while it assembles or steps (a load function's 'fn') "
                            "may not use its macros");
  return deck;
}

DeckModel& push_new_model(lua_State* L, const std::string& title, DeckSession& session) {
  if (session.live_models.size() >= DeckModel::kMaxModels) lua_gc(L, LUA_GCCOLLECT);  // the dropped ones go first
  if (session.live_models.size() >= DeckModel::kMaxModels)
    throw ModelError("the deck holds " + std::to_string(session.live_models.size()) +
                     " models, the most at once (a model is freed once no variable holds it)");
  // The model is made before the userdata, so that a failure leaves no half-built handle.
  auto model = std::make_unique<DeckModel>(title, session);
  auto* handle = new (lua_newuserdatauv(L, sizeof(ModelHandle), 0)) ModelHandle{};
  luaL_setmetatable(L, kModelMetatable);
  handle->model = std::move(model);
  return *handle->model;
}

void install_macros(LuaSandbox& sandbox, DeckSession& session) {
  lua_State* L = sandbox.state();
  lua_pushlightuserdata(L, &session);
  lua_setfield(L, LUA_REGISTRYINDEX, kSessionKey);
  lua_getglobal(L, "print");
  lua_pushcclosure(L, print_clearing_progress, 1);
  lua_setglobal(L, "print");

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

  sandbox.set_parameters_observer([&session](const std::vector<std::pair<std::string, std::string>>& resolved) {
    session.parameters = resolved;
    if (session.restart) check_parameters(*session.restart, resolved);  // at the deck's parameters line
  });
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
