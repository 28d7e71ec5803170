// Kernels of the finite-volume baseline: conserved variables and their fluxes,
// the recovery of (φ, s) from U, the HLL flux and the slope limiter.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rigidity/hyperbolic.hpp"
#include "rigidity/solvers/finite_volume.hpp"

namespace rigidity::finite_volume {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Largest rapidity the recovery considers: sinh and cosh stay finite (γ ≈ 5e303).
constexpr double kMaxRapidity = 700.0;
constexpr int kMaxIterations = 200;
/// A Newton step of the recovery this small (relative, see recover_state) ends it.
constexpr double kNewtonSettled = 1e-8;

/// ln cosh φ from |φ| and e^−|φ|, without overflow and exact for small φ.
double log_cosh(double a, double e_minus_a) { return a + std::log1p(e_minus_a * e_minus_a) - std::log(2.0); }
double log_cosh(double phi) {
  const double a = std::abs(phi);
  return log_cosh(a, std::exp(-a));
}

/// acosh(e^d) for d ≥ 0: the rapidity at which cosh φ = e^d.
double acosh_of_exp(double d) {
  if (d <= 0.0) return 0.0;
  // acosh y = ln(y + sqrt(y² − 1)) = d + ln(1 + sqrt(1 − e^{−2d})); for small d, sqrt(2 d) leads.
  if (d < 1e-8) return std::sqrt(2.0 * d);
  return d + std::log1p(std::sqrt(-std::expm1(-2.0 * d)));
}

/// The momentum per unit label G(φ) = (e+p) s sinh φ along s = L cosh φ, and dG/dφ.
struct MomentumCurve {
  const Material* material;
  double labels;      ///< L = s/γ
  double log_labels;  ///< ln L

  [[nodiscard]] Stretch stretch(double phi) const { return Stretch::from_log(log_labels + log_cosh(phi)); }

  /// (e+p) s at the stretch of rapidity φ.
  [[nodiscard]] double enthalpy_per_label(double phi) const {
    const Stretch s = stretch(phi);
    return material->enthalpy_density(s) * s.value();
  }

  [[nodiscard]] double value(double phi) const { return enthalpy_per_label(phi) * std::sinh(phi); }

  /// G and G' = (e+p) s (1 + (1 − c_s²) sinh² φ)/cosh φ at φ ≥ 0, from one exponential
  /// of φ (this is the inner loop of every finite-volume step): cosh, sinh and ln cosh
  /// from it, and s = L cosh φ.
  struct Point {
    double phi, g, dg;
    double log_s;         ///< ln s = ln L + ln cosh φ
    double sinh, cosh;    ///< of φ
    double h;             ///< (e+p) s
    double sound_speed2;  ///< c_s²
  };
  [[nodiscard]] Point evaluate(double phi) const {
    const Hyperbolic hy = hyperbolic(phi);
    Point p{};
    p.phi = phi;
    p.sinh = hy.sinh;
    p.cosh = hy.cosh;
    p.log_s = log_labels + log_cosh(phi, hy.em);
    const Stretch s = Stretch::from_log(p.log_s);
    const double c = material->sound_speed(s);
    p.h = material->enthalpy_density(s) * labels * hy.cosh;
    p.sound_speed2 = c * c;
    p.g = p.h * hy.sinh;
    p.dg = p.h * (1.0 + (1.0 - p.sound_speed2) * hy.sinh * hy.sinh) / hy.cosh;
    return p;
  }
};

/// The state at φ = sign × next, near the last point evaluated: ln s moves by
/// tanh φ (next − φ) (the step is at round-off or below 1e-8: its square is not seen),
/// with the sensitivity of φ to U there for the next recovery.
Recovered settle(const MomentumCurve::Point& at, double next, double sign, const Conserved& u) {
  Recovered r;
  r.state = State{sign * next, Stretch::from_log(at.log_s + at.sinh / at.cosh * (next - at.phi))};
  r.u = u;
  // δU₁ = h (cosh φ δφ − c² sinh φ δz) and δz = δ ln L + tanh φ δφ (z = ln s, d ln h/dz = −c²).
  const double d = 1.0 + (1.0 - at.sound_speed2) * at.sinh * at.sinh;
  r.dphi_dmomentum = at.cosh / (at.h * d);
  r.dphi_dloglabels = sign * at.sound_speed2 * at.sinh * at.cosh / d;
  r.enthalpy_per_label = at.h;
  return r;
}

Recovered failed(Status status) {
  Recovered r;
  r.status = status;
  return r;
}

}  // namespace

Conserved conserved(const Material& m, const State& st) {
  return Conserved{label_density(st), momentum_density(m, st)};
}

Flux flux(const Material& m, const State& st) { return Flux{-std::tanh(st.rapidity), m.pressure(st.stretch)}; }

RecoveryBounds recovery_bounds(const Material& m) {
  RecoveryBounds b;
  const StretchRange range = m.admissible();
  b.log_min = range.log_min;
  b.log_cap = range.log_max;
  b.parts = m.cavitation_pressure() > -kInf;
  if (b.parts) {
    const Solved<Stretch> parting = m.stretch_at_pressure(m.cavitation_pressure());
    if (parting.ok()) b.log_cap = std::min(b.log_cap, parting.value.log());
  }
  return b;
}

Recovered recover_state(const Material& m, const Conserved& u, double rapidity_guess) {
  return recover_state(m, recovery_bounds(m), u, rapidity_guess);
}

Recovered recover_state(const Material& m, const RecoveryBounds& bounds, const Conserved& u, double rapidity_guess) {
  Recovered none;
  none.state.rapidity = rapidity_guess;
  return recover_state(m, bounds, u, none);
}

Recovered recover_state(const Material& m, const RecoveryBounds& bounds, const Conserved& u,
                        const Recovered& previous) {
  const double labels = u[0], momentum = u[1];
  if (!(labels > 0.0) || !std::isfinite(labels) || !std::isfinite(momentum)) return failed(Status::out_of_range);
  const double log_labels = std::log(labels);
  const double target = std::abs(momentum);
  const double sign = momentum < 0.0 ? -1.0 : 1.0;
  const MomentumCurve curve{&m, labels, log_labels};
  const double log_cap = bounds.log_cap;
  const bool parts = bounds.parts;
  const auto clamped = [&]() {
    // At the parting stretch, with the momentum kept: (e+p) s sinh φ = U₁.
    Recovered r;
    const Stretch s = Stretch::from_log(log_cap);
    const double h = m.enthalpy_density(s) * s.value();
    r.state = State{sign * std::asinh(target / h), s};
    r.cavitated = true;
    if (!std::isfinite(r.state.rapidity)) r.status = Status::out_of_range;
    return r;
  };

  // The bracket in |φ|: s = L cosh φ between the bounds of the range.
  double lo = 0.0, hi = kMaxRapidity;
  if (std::isfinite(bounds.log_min) && log_labels < bounds.log_min) lo = acosh_of_exp(bounds.log_min - log_labels);
  if (std::isfinite(log_cap)) {
    if (log_labels > log_cap) {
      if (parts) return clamped();
      return failed(Status::out_of_range);
    }
    hi = std::min(hi, acosh_of_exp(log_cap - log_labels));
  }
  if (lo > hi) return failed(Status::out_of_range);
  if (target == 0.0 && lo == 0.0) return Recovered{State{0.0, curve.stretch(0.0)}, Status::ok, false};
  if (lo > 0.0 && curve.value(lo) > target) return failed(Status::out_of_range);

  // A tiny momentum (down to subnormal numbers): G(φ) = h(φ) sinh φ with h(φ) = h(0)(1 + O(φ²)),
  // so φ = asinh(|U₁|/h(0)) is exact to round-off below 1e-8 and needs no iteration. Asked
  // only where the cell's last (e+p) s (which moves little in a step) does not rule it out.
  if (lo == 0.0 && !(target >= 1e-6 * previous.enthalpy_per_label)) {
    const double h0 = curve.enthalpy_per_label(0.0);
    if (target < 1e-8 * h0) {
      const double phi = std::asinh(target / h0);
      return Recovered{State{sign * phi, curve.stretch(phi)}, Status::ok, false};
    }
  }

  // Newton on G(φ) = |U₁| from the guess, safeguarded: a step that leaves the
  // bracket [lo, hi] bisects it, or, while no point above the root is known, doubles
  // φ outwards (G may underflow far beyond the root, so the cap is a poor first try).
  bool hi_known = false;  // G(hi) ≥ |U₁| established
  double phi = previous.state.rapidity;
  if (std::isfinite(previous.dphi_dmomentum)) {
    phi += previous.dphi_dmomentum * (momentum - previous.u[1]) +
           previous.dphi_dloglabels * (labels - previous.u[0]) / previous.u[0];
  }
  phi = std::abs(phi);
  if (!(phi > lo && phi <= hi)) {  // a guess at the cap (a cell clamped there) settles in one evaluation
    phi = std::min(lo + target / curve.enthalpy_per_label(lo), 0.5 * (lo + hi));  // G ≈ h φ for small φ
    if (!(phi > lo)) phi = 0.5 * (lo + hi);
  }
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const MomentumCurve::Point at = curve.evaluate(phi);
    const double residual = at.g - target;
    if (residual == 0.0) return settle(at, phi, sign, u);
    if (residual < 0.0) {
      lo = phi;
      if (phi >= hi) {
        // Even the fastest admissible state at this label density has less momentum.
        if (parts && hi < kMaxRapidity) return clamped();
        return failed(Status::out_of_range);
      }
    } else {
      hi = phi;
      hi_known = true;
    }
    double next = phi - residual / at.dg;
    const bool newton = next > lo && next < hi;
    if (!newton) next = hi_known ? 0.5 * (lo + hi) : std::min(2.0 * std::max(phi, 0.5), hi);
    // A Newton step leaves an error of about (g''/2g') × step², with g''/g' at most of order
    // min(φ, 1)/φ-scale: below 1e-8 × min(φ, 1) the next iterate is exact to round-off, and
    // confirming it would cost another evaluation of the material.
    const bool converged = std::abs(next - phi) <= 2.0 * kEps * std::abs(next) + std::numeric_limits<double>::min() ||
                           (newton && std::abs(next - phi) <= kNewtonSettled * std::min(std::abs(next), 1.0)) ||
                           (hi_known && hi - lo <= 2.0 * kEps * hi);
    if (converged) return settle(at, next, sign, u);
    phi = next;
  }
  return failed(Status::not_converged);
}

namespace {
/// What the HLL flux needs of one state, from one exponential of φ and one of ln s.
struct FaceState {
  double slowest = 0.0, fastest = 0.0;  ///< Lagrangian characteristic speeds of C− and C+
  Conserved u;
  Flux f;
};

/// dX/dt of C∓ and C+ at stretch s, sound speed c and e^±φ: cosh φ ± c sinh φ =
/// ((1 ± c) e^φ + (1 ∓ c) e^−φ)/2, free of cancellation for c → 1 and large |φ|
/// (as characteristic_speeds).
LagrangianSpeeds speeds_at(double s, double c, double ep, double em) {
  return LagrangianSpeeds{-c / (s * 0.5 * ((1.0 - c) * ep + (1.0 + c) * em)),
                          c / (s * 0.5 * ((1.0 + c) * ep + (1.0 - c) * em))};
}

FaceState face_state(const Material& m, const State& st) {
  const double s = st.stretch.value();
  const Hyperbolic hy = hyperbolic(st.rapidity);
  const LawValues laws = m.laws_at(st.stretch);
  const LagrangianSpeeds speeds = speeds_at(s, laws.sound_speed, hy.ep, hy.em);
  FaceState out;
  out.fastest = speeds.plus;
  out.slowest = speeds.minus;
  out.u = Conserved{s / hy.cosh, laws.enthalpy * s * hy.sinh};
  out.f = Flux{-velocity_of(st.rapidity, hy), laws.pressure};
  return out;
}
}  // namespace

FaceFlux hll_flux(const Material& mL, const State& left, const Material& mR, const State& right) {
  const FaceState l = face_state(mL, left), r = face_state(mR, right);
  const double slowest = std::min(l.slowest, r.slowest);
  const double fastest = std::max(l.fastest, r.fastest);
  // In label coordinates S− < 0 < S+ always: the HLL flux at X/t = 0 is the
  // flux of the intermediate state (Toro eq. 10.21).
  const Flux f = (fastest * l.f - slowest * r.f + slowest * fastest * (r.u - l.u)) / (fastest - slowest);
  FaceFlux out;
  out.velocity_left = out.velocity_right = -f[0];
  out.pressure = f[1];
  return out;
}

LagrangianSpeeds lagrangian_speeds(const Material& m, const State& st) {
  const double ep = std::exp(st.rapidity);
  return speeds_at(st.stretch.value(), m.sound_speed(st.stretch), ep, 1.0 / ep);
}

double mc_limited_slope(double a, double b) {
  if (!(a * b > 0.0)) return 0.0;
  const double magnitude = std::min({2.0 * std::abs(a), 2.0 * std::abs(b), 0.5 * std::abs(a + b)});
  return a > 0.0 ? magnitude : -magnitude;
}

}  // namespace rigidity::finite_volume
