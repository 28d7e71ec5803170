/// `hooke`: the relativistic Hooke material (Brotas 1980). Shocks from the natural
/// state run at the constant speed V relative to the unstrained material, for every
/// impact speed: the argument of physics/0307019 §3 with V_b = V < c instead of c.
///
/// With b = V, a² = 1 − b² and R(s) = sqrt(b² + a²/s²) (docs/materials.md):
///
///   e = ρ00 (R − b²)/a²,   p = e/R − ρ00,   c_s = b/R,   c_s² = b²s²/(b²s² + a²).
///
/// The code uses forms free of 1/a² so that V = 1 is exactly the `rigid` law, and free
/// of cancellation at s = 1 (σ = s − 1/s = 2 sinh ln s, q = s R = sqrt(b²s² + a²)):
///
///   p   = −ρ00 b² σ / (R (q + s))          [p = e/R − ρ00 = ρ00 b² (1/s² − 1)/(R (R + 1)), since
///                                           (R − b²)/a² − R = (R² − 1)(1 − a²)/(a²(R + 1)), R² − 1 = a²(1/s² − 1)]
///       = −ρ00 b/(1 + b) + ρ00 b/(s² R (R + b))      (in far tension: never below the maximum tension)
///   e   = ρ00 (1 − σ/(q + s))              [(R − b²)/a² − 1 = (R² − 1)/(a²(R + 1))]
///       = (e + p) − p,  e + p = ρ00/(s q)  [(R − b²)(R + 1) − a² R = a²/s²]  (in tension: e + p ≥ 0)
///   W'' = ρ00 b² / q³                      [d²(e s)/ds²]
///   Ψ   = asinh(b/a) − asinh(b s/a) = asinh(−b σ/(R + 1))     [asinh x − asinh y = asinh(x√(1+y²) − y√(1+x²))]
///
/// Inverses: s = cosh Ψ − sinh(Ψ)/b; with P = p/ρ00 and d = b² − a² P (from p = e/R − ρ00):
/// R = b²/d and 1/s² − 1 = P (R + 1)/d.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/hyperbolic.hpp"
#include "rigidity/material.hpp"
#include "rigidity/parameters.hpp"
#include "rigidity/registry.hpp"

namespace rigidity {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// e^−½ − 1: the strain below which s(Ψ) is taken from its form for small s.
constexpr double kStrainAtHalf = -0.39346934028736658;

class Hooke final : public Material {
 public:
  static constexpr std::string_view kName = "hooke";

  static std::string doc() {
    return "Relativistic Hooke material (Brotas 1980): shocks from the natural state run at the constant speed V "
           "relative to the unstrained material. With b = V, R = sqrt(b^2 + (1 - b^2)/s^2): "
           "e = rho00 (R - b^2)/(1 - b^2), p = e/R - rho00, c_s^2 = b^2 s^2/(b^2 s^2 + 1 - b^2). "
           "Newtonian limit p = rho00 V^2 (1 - s) (Young's modulus rho00 V^2); V = 1 is `rigid`; "
           "both wave families linearly degenerate; p < rho00 V^2/(1 - V^2), so an impact at v >= V "
           "crushes the bar to zero length.";
  }
  static std::vector<ParameterSpec> parameters() {
    return {rest_density_parameter(),
            ParameterSpec::number("wave_speed", "V: speed of shocks from the natural state, relative to the material")
                .with_dimension(Dimension::velocity)
                .require()
                .above(0.0)
                .at_most(1.0)};
  }

  explicit Hooke(const ParameterValues& values)
      : Material(values.number("rest_density")),
        b_(values.number("wave_speed")),
        a_(std::sqrt((1.0 - b_) * (1.0 + b_))),
        psi_max_(a_ > 0.0 ? std::atanh(b_) : kInfinity) {
    if (!(b_ > 0.0 && b_ <= 1.0)) throw std::invalid_argument("hooke: wave_speed must be in (0, 1]");
  }

  [[nodiscard]] std::string_view model() const override { return kName; }

  /// p = e/R − ρ00 (docs/materials.md): as −ρ00 b² σ/(R (q + s)) near s = 1, and in far tension as the
  /// maximum tension plus a positive remainder, so that it never rounds below that limit.
  [[nodiscard]] double pressure(Stretch s) const override { return pressure_of(terms(s.log()), s.log()); }

  /// e = ρ00 (R − b²)/(1 − b²) (docs/materials.md): as ρ00 (1 − σ/(q + s)) in compression, and in
  /// tension as (e + p) − p, so that e + p never rounds below 0.
  [[nodiscard]] double energy_density(Stretch s) const override {
    if (s.log() >= 0.0) return enthalpy_density(s) - pressure(s);
    const Terms k = terms(s.log());
    return rest_density() * (1.0 - k.two_sinh / (k.q + k.s));
  }

  /// e + p = ρ00/(s² R): from e(1 + 1/R) − ρ00 with R² − b² = a²/s².
  [[nodiscard]] double enthalpy_density(Stretch s) const override { return enthalpy_of(terms(s.log())); }

  /// c_s = b/R = b s/sqrt(b²s² + a²) (docs/materials.md).
  [[nodiscard]] double sound_speed(Stretch s) const override { return b_ / terms(s.log()).r; }

  /// p, e + p and c_s from one evaluation of the terms.
  [[nodiscard]] LawValues laws_at(Stretch s) const override {
    const Terms k = terms(s.log());
    return {pressure_of(k, s.log()), enthalpy_of(k), b_ / k.r};
  }

  /// W'' = ρ00 b²/(b²s² + a²)^{3/2}.
  [[nodiscard]] double stiffness(Stretch s) const override {
    const double q = terms(s.log()).q;
    return rest_density() * b_ * b_ / (q * q * q);
  }

  /// Ψ = asinh(b/a) − asinh(b s/a), as asinh(−b σ/(R + 1)).
  [[nodiscard]] double riemann_psi(Stretch s) const override {
    const Terms k = terms(s.log());
    return std::asinh(-b_ * k.two_sinh / (k.r + 1.0));
  }

  /// Inverse of p(s); reachable for −ρ00 b/(1 + b) < p < ρ00 b²/a².
  [[nodiscard]] Solved<Stretch> stretch_at_pressure(double p) const override {
    if (!(p > max_tension() && p < max_pressure())) return Solved<Stretch>::failure(Status::out_of_range);
    const double reduced = p / rest_density();
    const double d = b_ * b_ - a_ * a_ * reduced;  // b² − a² p/ρ00 > 0 below the maximum pressure
    const double r = b_ * b_ / d;                  // R at that pressure
    const double inverse_square_minus_one = reduced * (r + 1.0) / d;  // 1/s² − 1
    double log_s = -0.5 * std::log1p(inverse_square_minus_one);
    if (inverse_square_minus_one < -0.5) {
      // Far tension: 1/s² = b² (b + (1 + b) P)(b + d)/((1 + b) d²), whose factor
      // b + (1 + b) P = (1 + b)(P − P_min) carries all the precision p has left.
      const double above_limit = b_ + (1.0 + b_) * reduced;
      log_s = -0.5 * std::log(b_ * b_ * above_limit * (b_ + d) / ((1.0 + b_) * d * d));
    }
    if (!std::isfinite(log_s)) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(log_s)};
  }

  /// s = cosh Ψ − sinh(Ψ)/b (from b s/a = sinh(asinh(b/a) − Ψ)); reachable for Ψ < atanh(b).
  [[nodiscard]] Solved<Stretch> stretch_at_psi(double psi) const override {
    if (!(psi < psi_max() && psi > psi_min())) return Solved<Stretch>::failure(Status::out_of_range);
    double log_s = 0.0;
    if (std::abs(psi) < 1.0) {
      // Near s = 1 (s > e^−½, as below): s − 1 = (cosh Ψ − 1) − sinh(Ψ)/b = 2h² − 2h sqrt(1 + h²)/b
      // with h = sinh(Ψ/2), free of cancellation there (its two terms could cancel only for
      // h > 1/b ≥ 1): one sinh and one log1p.
      const double h = std::sinh(0.5 * psi);
      const double strain = 2.0 * h * h - 2.0 * h * std::sqrt(1.0 + h * h) / b_;
      if (strain > kStrainAtHalf) return {Stretch::from_log(std::log1p(strain))};
    }
    if (psi <= -1.0) {
      // s = e^{−Ψ} [(1 + e^{2Ψ})/2 + (1 − e^{2Ψ})/(2b)]: both terms positive, no overflow.
      const double e2 = std::exp(2.0 * psi);
      log_s = -psi + std::log(0.5 * (1.0 + e2) + 0.5 * (1.0 - e2) / b_);
    } else {
      // s = e^{−Ψ} [(1 + b) − (1 − b) e^{2Ψ}]/(2b): exact at b = 1, and all the precision
      // there is as s → 0 (Ψ → artanh b), but only absolute precision near s = 1.
      const double shrink = b_ < 1.0 ? (1.0 - b_) * std::exp(2.0 * psi) : 0.0;
      const double bracket = (1.0 + b_) - shrink;
      if (!(bracket > 0.0)) return Solved<Stretch>::failure(Status::out_of_range);
      log_s = -psi + std::log(bracket / (2.0 * b_));
      if (log_s > -0.5) {  // near s = 1: s − 1 = (cosh Ψ − 1) − sinh(Ψ)/b, no cancellation here
        const double h = std::sinh(0.5 * psi);
        log_s = std::log1p(2.0 * h * h - std::sinh(psi) / b_);
      }
    }
    if (!std::isfinite(log_s)) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(log_s)};
  }

  /// lim_{s→0} p = ρ00 b²/a² (+inf for V = 1).
  [[nodiscard]] double max_pressure() const override {
    return a_ > 0.0 ? rest_density() * b_ * b_ / (a_ * a_) : kInfinity;
  }
  /// lim_{s→∞} p = −ρ00 b/(1 + b) (R → b).
  [[nodiscard]] double max_tension() const override { return -rest_density() * b_ / (1.0 + b_); }
  /// lim_{s→0} Ψ = asinh(b/a) = artanh(b) (+inf for V = 1).
  [[nodiscard]] double psi_max() const override { return psi_max_; }
  [[nodiscard]] double psi_min() const override { return -kInfinity; }
  /// Ψ + artanh(c_s) = artanh(b) is constant: the lab speed of each family is constant
  /// along its own waves (docs/materials.md).
  [[nodiscard]] bool linearly_degenerate() const override { return true; }

 private:
  /// What the laws are written in, at t = ln s: s, 1/s, σ = s − 1/s = 2 sinh t (exact near
  /// s = 1), R = sqrt(b² + a²/s²) and q = s R = sqrt(b² s² + a²). From one exponential
  /// (rigidity::hyperbolic) and one square root; beyond |t| = 300, where a square could
  /// overflow, each on its own with hypot.
  struct Terms {
    double s, inv_s, two_sinh, r, q;
  };
  [[nodiscard]] Terms terms(double t) const {
    if (std::abs(t) < 300.0) {
      // R² = 1 + a² (1/s² − 1) = 1 − a² σ/s: exactly 1 at s = 1 (c_s = V there), free of
      // cancellation below s = e (far tension: b² + (a/s)², two positive terms).
      const Hyperbolic h = hyperbolic(t);
      const double a_over_s = a_ * h.em;
      const double r = std::sqrt(t < 1.0 ? 1.0 - a_ * a_ * (2.0 * h.sinh) * h.em : b_ * b_ + a_over_s * a_over_s);
      return {h.ep, h.em, 2.0 * h.sinh, r, h.ep * r};
    }
    return {std::exp(t), std::exp(-t), 2.0 * std::sinh(t), std::hypot(b_, a_ * std::exp(-t)),
            std::hypot(b_ * std::exp(t), a_)};
  }

  [[nodiscard]] double pressure_of(const Terms& k, double t) const {
    if (t >= 1.0) return rest_density() * b_ * k.inv_s * k.inv_s / (k.r * (k.r + b_)) + max_tension();
    return -rest_density() * b_ * b_ * k.two_sinh / (k.r * (k.q + k.s));
  }
  /// e + p = ρ00/(s² R).
  [[nodiscard]] double enthalpy_of(const Terms& k) const { return rest_density() * k.inv_s * k.inv_s / k.r; }

  double b_;        ///< V: shock speed relative to the unstrained material
  double a_;        ///< sqrt(1 − V²)
  double psi_max_;  ///< artanh(V), asked for by every crossing
};

RIGIDITY_REGISTER_MATERIAL(Hooke);

}  // namespace
}  // namespace rigidity
