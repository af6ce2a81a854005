// Spelling suggestions for unknown names in inputs: "unknown key 'EJ' (did you mean 'EI'?)".
#pragma once

#include <string>
#include <vector>

namespace tirefe {

/// The known name closest to 'name', or "" when none is close enough to be a typo. The
/// distance is an edit distance ignoring case in which a substitution costs a little more
/// the further apart the letters are, so that neighbours (EJ -> EI rather than EA) win ties.
std::string closest_name(const std::string& name, const std::vector<std::string>& known);

/// "did you mean 'x'?" with x the closest_name, or "" when no known name is close: the one
/// wording of a suggestion, for every message that names an unknown key, macro, unit or section.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& known);

}  // namespace tirefe
