#pragma once
/// The stretch s = proper length / natural length, carried as its logarithm.
///
/// ln s keeps full relative precision for strains of 1e-12 (s - 1 = expm1(ln s)) as
/// well as for stretches of 1e-9 or 1e12, and it is the natural variable of the
/// Riemann invariants: for the `rigid` material s = exp(-rapidity) behind a wall impact.

#include <cmath>

namespace rigidity {

class Stretch {
 public:
  constexpr Stretch() = default;
  /// s = exp(log_stretch)
  [[nodiscard]] static constexpr Stretch from_log(double log_stretch) { return Stretch(log_stretch); }
  /// \pre s > 0
  [[nodiscard]] static Stretch from_value(double s) { return Stretch(std::log(s)); }
  /// s = 1 + strain, exact for tiny strains. \pre strain > -1
  [[nodiscard]] static Stretch from_strain(double strain) { return Stretch(std::log1p(strain)); }
  [[nodiscard]] static constexpr Stretch natural() { return Stretch(0.0); }

  [[nodiscard]] constexpr double log() const { return log_; }
  [[nodiscard]] double value() const { return std::exp(log_); }
  /// s - 1, to full relative precision near s = 1.
  [[nodiscard]] double strain() const { return std::expm1(log_); }

  friend constexpr bool operator==(Stretch a, Stretch b) = default;
  friend constexpr auto operator<=>(Stretch a, Stretch b) = default;

 private:
  constexpr explicit Stretch(double log_stretch) : log_(log_stretch) {}
  double log_ = 0.0;
};

}  // namespace rigidity
