// MacroTable: every macro a deck can call, each a documented spec plus a handler.
// Module macros are called as tirefe.name{...}; model macros as model:name{...} on a
// model made by tirefe.model{...}. One generic Lua entry point validates the argument
// table against the spec and turns C++ exceptions into deck errors at the calling line.
#pragma once

#include <string>
#include <vector>

#include "deck/deck_files.hpp"
#include "deck/lua_sandbox.hpp"
#include "macros/macro_spec.hpp"

namespace tirefe {
struct TireParameters;
}

namespace tirefe::macros {

class DeckModel;
struct DeckSession;

/// Handlers return the number of Lua results they pushed.
using ModuleHandler = int (*)(lua_State* L, DeckSession& session, const MacroArguments& arguments);
using ModelHandler = int (*)(lua_State* L, DeckModel& model, const MacroArguments& arguments);

struct ModuleMacro {
  MacroSpec spec;
  ModuleHandler handler;
};
struct ModelMacro {
  MacroSpec spec;
  ModelHandler handler;
};

struct MacroTable {
  std::vector<ModuleMacro> module_macros;
  std::vector<ModelMacro> model_macros;
};

/// All macros of tirefe (each group of macros adds itself in its own file).
const MacroTable& macro_table();
void add_model_macros(MacroTable& table);
void add_dynamics_macros(MacroTable& table);
void add_tire_macros(MacroTable& table);
void add_tire_file_macros(MacroTable& table);
void add_contact_macros(MacroTable& table);
void add_fitting_macros(MacroTable& table);
void add_post_macros(MacroTable& table);
void add_vehicle_macros(MacroTable& table);
void add_checkpoint_macros(MacroTable& table);

// Argument pieces shared by the macro groups.
const std::vector<std::string>& dof_names();  // ux, uy, rz
int dof_component(const std::string& name);
ParameterSpec node_key();
ParameterSpec set_key();
/// The kernel's 0-based index of a deck node number (from 1).
int deck_node(DeckModel& deck, long long number);
/// 0-based nodes named by the 'node' or 'set' argument (exactly one of them).
std::vector<int> target_nodes(DeckModel& deck, const MacroArguments& arguments);

/// The spec of a model macro by name (model:tire's is "tire").
const MacroSpec& model_macro_spec(const std::string& name);

/// The tire parameters of a Lua module in lua/ (e.g. "tires.145SR12") or of a tire property
/// file (a path ending in .tir), read with the tire macro's own spec: one source of truth for
/// decks, tests and benchmarks.
/// 'overrides' replace parameters by model:tire key (a misspelt key is refused as in a deck).
using ParameterValue = std::pair<std::string, double>;
TireParameters load_tire_parameters(const std::string& source, const std::vector<ParameterValue>& overrides = {});
/// Pushes the model:tire parameter table of a tire property file (docs/tire.md); throws a
/// std::exception naming the file, line and key for a bad file.
int push_tire_property_file(lua_State* L, const std::string& path);
/// Markdown table of the property file's keys (docs/tire.md holds it).
std::string tire_property_file_reference();

/// Installs tirefe.* and the model methods into the sandbox's Lua state.
void install_macros(LuaSandbox& sandbox, DeckSession& session);
/// Markdown reference of every macro (docs/macros.md is generated from it).
std::string macro_reference();

/// The DeckModel behind a model userdata at 'index' (raises a deck error otherwise).
DeckModel& check_model(lua_State* L, int index);
/// Pushes a new model userdata owning a DeckModel.
DeckModel& push_new_model(lua_State* L, const std::string& title, DeckSession& session);

}  // namespace tirefe::macros
