#include "core/spelling.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace tirefe {

namespace {

double typo_distance(const std::string& a, const std::string& b) {
  std::vector<double> row(b.size() + 1), next(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<double>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    next[0] = static_cast<double>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int x = std::tolower(static_cast<unsigned char>(a[i - 1]));
      const int y = std::tolower(static_cast<unsigned char>(b[j - 1]));
      const double substitute = row[j - 1] + (x == y ? 0.0 : 1.0 + std::abs(x - y) / 1000.0);
      next[j] = std::min({row[j] + 1.0, next[j - 1] + 1.0, substitute});
    }
    std::swap(row, next);
  }
  return row[b.size()];
}

}  // namespace

std::string closest_name(const std::string& name, const std::vector<std::string>& known) {
  const std::string* best = nullptr;
  double best_distance = 0.0;
  for (const std::string& candidate : known) {
    const double distance = typo_distance(name, candidate);
    if (distance < 2.5 && distance < static_cast<double>(candidate.size()) && (!best || distance < best_distance)) {
      best = &candidate;
      best_distance = distance;
    }
  }
  return best ? *best : std::string();
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& known) {
  const std::string best = closest_name(name, known);
  return best.empty() ? best : "did you mean '" + best + "'?";
}

}  // namespace tirefe
