#include "front_math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "rigidity/hyperbolic.hpp"
#include "rigidity/number_text.hpp"

namespace rigidity::characteristics {

namespace {
constexpr double kEps = std::numeric_limits<double>::epsilon();
}  // namespace

double wave_strength(const Material& m, const State& a, const State& b, int family) {
  return (b.rapidity - a.rapidity) + family * (m.riemann_psi(b.stretch) - m.riemann_psi(a.stretch));
}

FrontSpeeds label_jump_speeds(const Material& m, const State& a, const State& b, int family) {
  return label_jump_speeds(m, a, b, family, label_jump(a, b));
}

FrontSpeeds label_jump_speeds(const Material& m, const State& a, const State& b, int family, const LabelJump& jump) {
  const double speed = jump.speed();
  double lab = (jump.left.sinh + speed * jump.left_stretch) / jump.left.cosh;
  // dx/dt = v + m s/γ on either side. Where its two terms cancel on the left (that side
  // moving near light speed, the front slow in the lab), from the right if they cancel less.
  const double sinh_part = jump.left.sinh, label_part = speed * jump.left_stretch;
  if (std::abs(sinh_part + label_part) < 0.0625 * std::max(std::abs(sinh_part), std::abs(label_part))) {
    const Hyperbolic at_b = jump.right_known ? jump.right : hyperbolic(b.rapidity);
    const double b_label_part = speed * b.stretch.value();
    if (std::max(std::abs(at_b.sinh), std::abs(b_label_part)) / at_b.cosh <
        std::max(std::abs(sinh_part), std::abs(label_part)) / jump.left.cosh)
      lab = (at_b.sinh + b_label_part) / at_b.cosh;
  }
  // A coarse step (or a jump held off its curve) can give a speed against its family's
  // direction or beyond light: it then moves at the mean characteristic speed instead.
  if (!std::isfinite(speed) || jump.scaled_tau == 0.0 || !(family * speed > 0.0) || !(std::abs(lab) < 1.0)) {
    const FrontSpeeds sa = characteristic_speeds(m, a, family), sb = characteristic_speeds(m, b, family);
    return FrontSpeeds{0.5 * (sa.lagrangian + sb.lagrangian), 0.5 * (sa.lab + sb.lab)};
  }
  return FrontSpeeds{speed, lab};
}

Solved<double> curve_rapidity(const Material& m, CurveEnd& outer, TrialStretch& at, int family, bool* shock,
                              FrontSpeeds* fan_speeds) {
  const Stretch s = Stretch::from_log(at.z);
  // The state on the integral curve; the wave is a shock where the characteristics of its
  // family converge across it (as wave_is_shock decides, with the outer speed given).
  const double on_curve = outer.state.rapidity + family * (at.psi - outer.psi);
  bool converging = false;
  if (fan_speeds != nullptr) fan_speeds->lagrangian = std::numeric_limits<double>::quiet_NaN();
  if (!m.linearly_degenerate() && s != outer.state.stretch) {
    const FrontSpeeds star_speeds = characteristic_speeds(at.sound_speed, on_curve, at.stretch, family);
    const double star_speed = star_speeds.lagrangian;
    converging = family < 0 ? !(outer.speed < star_speed) : !(star_speed < outer.speed);
    if (!converging && fan_speeds != nullptr) *fan_speeds = star_speeds;
  }
  if (shock != nullptr) *shock = converging;
  if (converging) {
    return hugoniot_rapidity(outer.state, outer.laws.at(m, outer.state.stretch), s, at.laws.at(m, s), family);
  }
  return Solved<double>{on_curve, Status::ok};
}

Solved<SameMaterialStar> same_material_star(const Material& m, CrossingEnds& ends, const State& guess, double accept) {
  using Result = Solved<SameMaterialStar>;
  SameMaterialStar star;
  double sound_speed = 0.0;  // at the last stretch tried
  auto mismatch = [&](double z, double& g) {
    const Stretch s = Stretch::from_log(z);
    TrialStretch at{z, s.value(), m.riemann_psi(s), m.sound_speed(s), {}};
    sound_speed = at.sound_speed;
    const Solved<double> a = curve_rapidity(m, ends.left, at, -1, &star.shock[0], &star.speeds[0]);
    const Solved<double> b = curve_rapidity(m, ends.right, at, +1, &star.shock[1], &star.speeds[1]);
    if (!a.ok() || !b.ok()) return false;
    g = a.value - b.value;
    star.state = State{0.5 * (a.value + b.value), Stretch::from_log(z)};
    star.laws = at.laws;
    star.off[0] = star.off[1] = 0.5 * std::abs(g);
    return std::isfinite(g);
  };
  // Round-off in the rapidities the curves give: below it, another step changes nothing.
  const auto settled = [&](double g) {
    star.converged = std::abs(g) <= 4.0 * kEps * (1.0 + std::abs(star.state.rapidity));
    return star.converged || std::abs(g) <= accept;
  };
  double z0 = guess.stretch.log(), g0 = 0.0;
  if (!mismatch(z0, g0)) return Result::failure(Status::not_converged);
  if (settled(g0)) return Result{star, Status::ok};
  // dφ/d ln s is +c_s on the C− curve and −c_s on the C+ curve near the star: g' ≈ 2 c_s.
  double z1 = z0 - g0 / (2.0 * sound_speed), g1 = 0.0;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const StretchRange range = m.admissible();
    if (!(z1 > range.log_min && z1 < range.log_max)) return Result::failure(Status::out_of_range);
    if (!mismatch(z1, g1)) return Result::failure(Status::not_converged);
    if (settled(g1)) return Result{star, Status::ok};
    if (std::abs(z1 - z0) <= 2.0 * kEps * (1.0 + std::abs(z1))) {
      star.converged = true;  // the stretch cannot move: what is left of g is the curves' round-off
      return Result{star, Status::ok};
    }
    if (g1 == g0) return Result::failure(Status::not_converged);
    const double z2 = z1 - g1 * (z1 - z0) / (g1 - g0);
    z0 = z1;
    g0 = g1;
    z1 = z2;
  }
  return Result::failure(Status::not_converged);
}

bool same_state(const State& a, const State& b) {
  return std::abs(a.rapidity - b.rapidity) <= 4.0 * kEps * (1.0 + std::abs(a.rapidity)) &&
         std::abs(a.stretch.log() - b.stretch.log()) <= 4.0 * kEps * (1.0 + std::abs(a.stretch.log()));
}

bool touching(double x1, double x2) {
  return std::abs(x1 - x2) <= 64.0 * kEps * std::max({1.0, std::abs(x1), std::abs(x2)});
}

std::string number(double v) { return twelve_digits(v); }

}  // namespace rigidity::characteristics
