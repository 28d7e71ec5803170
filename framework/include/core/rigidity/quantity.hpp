#pragma once
/// Output quantities (docs/cli.md, "What a run writes"): X label, x lab position, v, s, p, e, rho, gamma, cs.

#include <optional>
#include <string_view>

#include "rigidity/units.hpp"

namespace rigidity {

enum class Quantity { X, x, v, s, p, e, rho, gamma, cs };

inline constexpr Quantity kAllQuantities[] = {Quantity::X, Quantity::x,   Quantity::v,     Quantity::s, Quantity::p,
                                              Quantity::e, Quantity::rho, Quantity::gamma, Quantity::cs};

[[nodiscard]] constexpr std::string_view to_string(Quantity q) {
  switch (q) {
    case Quantity::X: return "X";
    case Quantity::x: return "x";
    case Quantity::v: return "v";
    case Quantity::s: return "s";
    case Quantity::p: return "p";
    case Quantity::e: return "e";
    case Quantity::rho: return "rho";
    case Quantity::gamma: return "gamma";
    case Quantity::cs: return "cs";
  }
  return "?";
}

[[nodiscard]] constexpr std::optional<Quantity> quantity_from_string(std::string_view name) {
  for (Quantity q : kAllQuantities)
    if (to_string(q) == name) return q;
  return std::nullopt;
}

[[nodiscard]] constexpr Dimension dimension_of(Quantity q) {
  switch (q) {
    case Quantity::X:
    case Quantity::x: return Dimension::length;
    case Quantity::v:
    case Quantity::cs: return Dimension::velocity;
    case Quantity::p:
    case Quantity::e: return Dimension::pressure;
    case Quantity::rho: return Dimension::density;
    case Quantity::s:
    case Quantity::gamma: return Dimension::dimensionless;
  }
  return Dimension::dimensionless;
}

}  // namespace rigidity
