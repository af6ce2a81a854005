// tirefe --list-parameters DECK: the parameters a deck declares, read by running the deck
// only up to its tirefe.parameters{...} call (no model is built, no file written).
#pragma once

#include <string>
#include <vector>

#include "deck/lua_sandbox.hpp"

namespace tirefe::macros {

/// The deck's declared parameters, sorted by name (none if it builds a model first);
/// DeckError if the deck fails before.
std::vector<ParameterDeclaration> declared_parameters(const std::string& deck_path);

/// The table printed for them: a header, then name, default, unit ("-" if none) and
/// meaning, one parameter a line, in aligned columns.
std::string parameter_table(const std::string& deck_path, const std::vector<ParameterDeclaration>& parameters);

}  // namespace tirefe::macros
