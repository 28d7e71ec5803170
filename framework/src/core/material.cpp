#include "rigidity/material.hpp"

#include <cmath>
#include <sstream>

#include "rigidity/number_text.hpp"

namespace rigidity {

double Material::stiffness(Stretch s) const {
  const double cs = sound_speed(s);
  return cs * cs * enthalpy_density(s) / s.value();
}

std::string Material::admissibility_violation(Stretch s) const {
  std::ostringstream os;
  os.precision(12);
  if (!std::isfinite(s.log())) {
    os << "stretch must be positive and finite";
    return os.str();
  }
  const StretchRange range = admissible();
  if (!range.contains(s)) {
    os << "stretch " << shortest(s.value()) << " is outside the admissible range [" << shortest(std::exp(range.log_min))
       << ", " << shortest(std::exp(range.log_max)) << "] of material '" << model() << "'";
    return os.str();
  }
  const double cs = sound_speed(s);
  if (!(cs > 0.0)) {
    os << "material '" << model() << "' is not hyperbolic at stretch " << shortest(s.value()) << " (sound speed "
       << shortest(cs) << ")";
    return os.str();
  }
  if (!(cs <= 1.0)) {
    os << "material '" << model() << "' is acausal at stretch " << shortest(s.value()) << " (sound speed "
       << shortest(cs) << " > c)";
    return os.str();
  }
  return "";
}

}  // namespace rigidity
