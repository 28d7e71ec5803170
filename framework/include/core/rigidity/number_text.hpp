#pragma once
/// Numbers in messages: the shortest decimal form that reads back to the same double, so
/// a stretch of 1e-9 reads "1e-09", never "0.000000", and no digit a user might need is lost.
#include <array>
#include <charconv>
#include <cmath>
#include <string>

namespace rigidity {

[[nodiscard]] inline std::string shortest(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  std::array<char, 32> digits{};
  const auto result = std::to_chars(digits.data(), digits.data() + digits.size(), value);
  return std::string(digits.data(), result.ptr);
}

}  // namespace rigidity
