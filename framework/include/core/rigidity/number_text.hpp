#pragma once
/// Numbers in messages: the shortest decimal form that reads back to the same double, so
/// a stretch of 1e-9 reads "1e-09", never "0.000000", and no digit a user might need is lost.
#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string>

#include "rigidity/units.hpp"

namespace rigidity {

[[nodiscard]] inline std::string shortest(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  std::array<char, 32> digits{};
  const auto result = std::to_chars(digits.data(), digits.data() + digits.size(), value);
  return std::string(digits.data(), result.ptr);
}

/// `digits` significant digits, as a stream prints them.
[[nodiscard]] inline std::string significant(double value, int digits) {
  std::ostringstream os;
  os.precision(digits);
  os << value;
  return os.str();
}

/// Twelve significant digits: where a message names a stretch or a law's value that was found
/// by a search or a table, whose last digits say nothing.
[[nodiscard]] inline std::string twelve_digits(double value) { return significant(value, 12); }

/// A value given in natural units, written in the scene's units with its unit ("17.6 L/c",
/// "3e-08 s"); a speed of an SI scene also as a fraction of c ("6000 m/s (2.0e-05 c)").
[[nodiscard]] inline std::string in_units(double natural_value, Dimension d, UnitSystem u) {
  std::string text = shortest(from_natural(natural_value, d, u)) + " " + std::string(unit_symbol(d, u));
  if (d == Dimension::velocity && u == UnitSystem::si) text += " (" + shortest(natural_value) + " c)";
  return text;
}

}  // namespace rigidity
