// Where the Lua modules shipped with tirefe are (lua/ of the sources, share/tirefe/lua
// of an installed copy): the folder require() searches after the deck's own.
#pragma once

#include <string>

namespace tirefe::macros {

/// TIREFE_LUA_PATH if set; else the installed folder next to the library or executable
/// holding this code (found from where it was loaded, so a moved installation works), or
/// the resources/lua of the FMU whose binary it is; else, for a binary of the build tree
/// only, the source tree's lua/. Throws ModelError when none holds the modules.
std::string lua_module_dir();

}  // namespace tirefe::macros
