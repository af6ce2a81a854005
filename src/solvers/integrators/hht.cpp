#include "solvers/integrators/hht.hpp"

#include <sstream>

#include "core/mesh.hpp"

namespace tirefe {

std::shared_ptr<const Hht> Hht::make(double alpha) {
  if (!(alpha >= -1.0 / 3.0 && alpha <= 0.0)) {
    std::ostringstream message;
    message << "HHT needs alpha in [-1/3, 0] (unconditionally stable and second-order accurate); got " << alpha;
    throw ModelError(message.str());
  }
  return std::shared_ptr<const Hht>(new Hht(alpha));
}

std::string Hht::name() const {
  std::ostringstream text;
  text << "HHT(alpha=" << alpha_ << ")";
  return text.str();
}

}  // namespace tirefe
