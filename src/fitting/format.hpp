// One number as text with a printf pattern, for the fit's log lines and messages.
#pragma once

#include <cstdio>
#include <string>

namespace tirefe::fitting {

inline std::string formatted(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

}  // namespace tirefe::fitting
