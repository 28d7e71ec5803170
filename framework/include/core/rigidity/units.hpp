#pragma once
/// Units. Inside rigidity c = 1: lengths in the scene's length unit, times in
/// length/c, velocities in units of c, and mass density, energy density and pressure
/// all as mass densities (p/c², e/c²). SI scenes are converted at the boundary:
/// the loader on the way in, the writers on the way out.

#include <string_view>

namespace rigidity {

inline constexpr double kSpeedOfLightSI = 299792458.0;  // [m/s]

enum class UnitSystem { natural, si };

/// The physical dimension of a scene value or output quantity.
enum class Dimension {
  dimensionless,      ///< stretch, Lorentz factor, rapidity
  length,             ///< [m]
  time,               ///< [s]
  velocity,           ///< [m/s]  (natural: fraction of c)
  density,            ///< [kg/m³]  rest-mass or energy density / c²
  pressure,           ///< [Pa]  (natural: same unit as density, c = 1)
  energy_per_area,    ///< [J/m²]  per unit cross-section of the bar
  momentum_per_area,  ///< [kg/(m s)]  per unit cross-section of the bar
};

/// Factor f with  value_SI = f · value_natural  for the given dimension.
[[nodiscard]] constexpr double si_factor(Dimension d) {
  constexpr double c = kSpeedOfLightSI;
  switch (d) {
    case Dimension::dimensionless: return 1.0;
    case Dimension::length: return 1.0;
    case Dimension::time: return 1.0 / c;
    case Dimension::velocity: return c;
    case Dimension::density: return 1.0;
    case Dimension::pressure: return c * c;
    case Dimension::energy_per_area: return c * c;
    case Dimension::momentum_per_area: return c;
  }
  return 1.0;
}

[[nodiscard]] constexpr double to_natural(double value, Dimension d, UnitSystem u) {
  return u == UnitSystem::si ? value / si_factor(d) : value;
}
[[nodiscard]] constexpr double from_natural(double value, Dimension d, UnitSystem u) {
  return u == UnitSystem::si ? value * si_factor(d) : value;
}

/// The name of a dimension as scenes and `rigidity materials` write it: "pressure".
[[nodiscard]] constexpr std::string_view dimension_name(Dimension d) {
  switch (d) {
    case Dimension::dimensionless: return "dimensionless";
    case Dimension::length: return "length";
    case Dimension::time: return "time";
    case Dimension::velocity: return "velocity";
    case Dimension::density: return "density";
    case Dimension::pressure: return "pressure";
    case Dimension::energy_per_area: return "energy_per_area";
    case Dimension::momentum_per_area: return "momentum_per_area";
  }
  return "?";
}

/// The dimension named `name` (dimension_name's inverse); dimensionless for an unknown name.
[[nodiscard]] constexpr Dimension dimension_named(std::string_view name) {
  for (const Dimension d : {Dimension::length, Dimension::time, Dimension::velocity, Dimension::density,
                            Dimension::pressure, Dimension::energy_per_area, Dimension::momentum_per_area})
    if (dimension_name(d) == name) return d;
  return Dimension::dimensionless;
}

/// Unit symbol for documentation and headers, e.g. "m/s" or "c".
[[nodiscard]] constexpr std::string_view unit_symbol(Dimension d, UnitSystem u) {
  if (u == UnitSystem::si) {
    switch (d) {
      case Dimension::dimensionless: return "1";
      case Dimension::length: return "m";
      case Dimension::time: return "s";
      case Dimension::velocity: return "m/s";
      case Dimension::density: return "kg/m^3";
      case Dimension::pressure: return "Pa";
      case Dimension::energy_per_area: return "J/m^2";
      case Dimension::momentum_per_area: return "kg/(m s)";
    }
  } else {
    switch (d) {
      case Dimension::dimensionless: return "1";
      case Dimension::length: return "L";
      case Dimension::time: return "L/c";
      case Dimension::velocity: return "c";
      case Dimension::density: return "rho";
      case Dimension::pressure: return "rho c^2";
      case Dimension::energy_per_area: return "rho c^2 L";
      case Dimension::momentum_per_area: return "rho c L";
    }
  }
  return "?";
}

}  // namespace rigidity
