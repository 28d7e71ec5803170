#pragma once
/// The material interface. A material is its strain energy W(s): the rest-frame
/// energy per unit natural length (per unit area), rest mass included (docs/physics.md):
///
///   p(s)   = -W'(s)                  pressure, compression positive
///   e(s)   = W(s)/s                  rest-frame energy density (the paper's ρ0 c²)
///   c_s²   = s W''(s) / (e + p)      sound speed, dp/de
///   Ψ(s)   = ∫_s^1 c_s(σ)/σ dσ       Riemann invariants J± = φ ± Ψ
///
/// Everything is in natural units (c = 1). Functions take the stretch as Stretch
/// (its logarithm) so that tiny strains and extreme stretches keep full precision.
///
/// Contract every material meets (tested over the whole registry):
///   - on the admissible range: W'' > 0 and 0 < c_s ≤ 1, p = -W' and e = W/s;
///   - stretch_at_pressure and stretch_at_psi invert pressure and riemann_psi, and
///     return a failed Status (never a guess) outside the reachable range;
///   - no function returns NaN for an admissible argument.

#include <limits>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/status.hpp"
#include "rigidity/stretch.hpp"

namespace rigidity {

/// Admissible stretches as an interval of ln s (bounds may be ±inf; inclusive).
struct StretchRange {
  double log_min = -std::numeric_limits<double>::infinity();
  double log_max = std::numeric_limits<double>::infinity();
  [[nodiscard]] constexpr bool contains(Stretch s) const { return s.log() >= log_min && s.log() <= log_max; }
};

/// What a flux, a face state or a jump condition asks of one stretch together.
struct LawValues {
  double pressure = 0.0;
  double enthalpy = 0.0;  ///< e + p
  double sound_speed = 0.0;
};

class Material {
 public:
  explicit Material(double rest_density) : rest_density_(rest_density) {}
  virtual ~Material() = default;
  Material(const Material&) = delete;
  Material& operator=(const Material&) = delete;

  /// The registry name of the model ("rigid", "hooke", ...).
  [[nodiscard]] virtual std::string_view model() const = 0;
  /// ρ00: mass density of the unstrained material at rest.
  [[nodiscard]] double rest_density() const { return rest_density_; }

  // ---- the law; \pre admissible().contains(s) ---------------------------------
  /// W(s) = e(s)·s, rest mass included.
  [[nodiscard]] virtual double strain_energy(Stretch s) const { return energy_density(s) * s.value(); }
  /// p(s) = -W'(s), compression positive.
  [[nodiscard]] virtual double pressure(Stretch s) const = 0;
  /// e(s) = W(s)/s.
  [[nodiscard]] virtual double energy_density(Stretch s) const = 0;
  /// ρ = e/c²: rest-frame density, equal to e in natural units.
  [[nodiscard]] double density(Stretch s) const { return energy_density(s); }
  /// e + p, the inertia of stress; override with a closed form where e + p is much
  /// smaller than e (far tension), so that it keeps relative precision.
  [[nodiscard]] virtual double enthalpy_density(Stretch s) const { return energy_density(s) + pressure(s); }
  /// c_s = sqrt(dp/de). \post 0 < c_s <= 1
  [[nodiscard]] virtual double sound_speed(Stretch s) const = 0;
  /// W''(s) = -dp/ds = c_s² (e + p)/s. \post > 0
  [[nodiscard]] virtual double stiffness(Stretch s) const;
  /// Ψ(s) = ∫_s^1 c_s(σ)/σ dσ: positive in compression, zero at s = 1.
  [[nodiscard]] virtual double riemann_psi(Stretch s) const = 0;
  /// p, e + p and c_s at s, each exactly as its own function gives it; override where the
  /// three share their work (the finite-volume face states ask for all three).
  [[nodiscard]] virtual LawValues laws_at(Stretch s) const {
    return {pressure(s), enthalpy_density(s), sound_speed(s)};
  }

  // ---- inverses ---------------------------------------------------------------
  /// The stretch at which the pressure is p; out_of_range outside (max_tension, max_pressure).
  [[nodiscard]] virtual Solved<Stretch> stretch_at_pressure(double p) const = 0;
  /// The stretch at which Ψ = psi; out_of_range outside (psi_min, psi_max).
  [[nodiscard]] virtual Solved<Stretch> stretch_at_psi(double psi) const = 0;

  // ---- range and limits ---------------------------------------------------------
  /// Stretches on which the material is defined, hyperbolic and causal.
  [[nodiscard]] virtual StretchRange admissible() const { return {}; }
  /// sup p over the admissible range (s → smallest stretch); +inf if unbounded.
  [[nodiscard]] virtual double max_pressure() const = 0;
  /// inf p over the admissible range (s → largest stretch): the maximum tension, <= 0.
  [[nodiscard]] virtual double max_tension() const = 0;
  /// Ψ at the smallest admissible stretch (+inf if the material cannot be crushed).
  [[nodiscard]] virtual double psi_max() const = 0;
  /// Ψ at the largest admissible stretch (-inf if it can be stretched without bound).
  [[nodiscard]] virtual double psi_min() const = 0;
  /// The pressure below which the material parts (cavitates or fractures);
  /// -inf for a solid that carries any tension it can reach.
  [[nodiscard]] virtual double cavitation_pressure() const { return -std::numeric_limits<double>::infinity(); }
  /// True if both wave families are linearly degenerate: every wave is a jump
  /// moving at the characteristic speed, and J∓ is continuous across a ± front.
  [[nodiscard]] virtual bool linearly_degenerate() const { return false; }
  /// True if sound travels at c at every admissible stretch: every wave is then a jump
  /// moving at ±c in the lab whatever the state, and waves of the two families cross
  /// without changing each other's path (the front tracker need not visit their crossings).
  /// \post implies linearly_degenerate() and sound_speed(s) == 1 everywhere.
  [[nodiscard]] virtual bool sound_at_light_speed() const { return false; }

  /// Empty if s is admissible, else a sentence saying why not.
  [[nodiscard]] std::string admissibility_violation(Stretch s) const;

  /// ln s of every stretch where the genuine nonlinearity changes sign (rigidity/convexity.hpp:
  /// find_inflections on the admissible range within [1/100, 100]), ascending; empty for a law
  /// that is convex there, or linearly degenerate. Between two of them a wave of either family is
  /// one shock or one fan; a wave across one may be composite. Found once, on first use.
  [[nodiscard]] const std::vector<double>& inflection_logs() const;

 private:
  double rest_density_;
  mutable std::once_flag inflections_found_;
  mutable std::vector<double> inflection_logs_;
};

}  // namespace rigidity
