#include "app/parameter_list.hpp"

#include <algorithm>

#include "deck/lua_module_dir.hpp"

namespace tirefe::macros {

std::vector<ParameterDeclaration> declared_parameters(const std::string& deck_path) {
  LuaSandbox sandbox(lua_module_dir());
  sandbox.stop_at_parameters();
  sandbox.run_file(deck_path);
  return sandbox.declared_parameters();
}

std::string parameter_table(const std::string& deck_path, const std::vector<ParameterDeclaration>& parameters) {
  if (parameters.empty()) return deck_path + " declares no parameters (tirefe.parameters{...})\n";
  std::vector<std::vector<std::string>> rows{{"name", "default", "unit", "meaning"}};
  for (const auto& parameter : parameters)
    rows.push_back(
        {parameter.name, parameter.default_text, parameter.unit.empty() ? "-" : parameter.unit, parameter.meaning});
  size_t widths[3] = {0, 0, 0};
  for (const auto& row : rows)
    for (size_t column = 0; column < 3; ++column) widths[column] = std::max(widths[column], row[column].size());
  std::string table =
      deck_path + ": " + std::to_string(parameters.size()) + " parameters, set on the command line as name=value\n";
  for (const auto& row : rows) {
    std::string line = "  ";
    for (size_t column = 0; column < 3; ++column)
      line += row[column] + std::string(widths[column] - row[column].size() + 2, ' ');
    line += row[3];
    line.erase(line.find_last_not_of(' ') + 1);
    table += line + "\n";
  }
  return table;
}

}  // namespace tirefe::macros
