#pragma once
/// The paper's experiment for any material: an unstrained bar strikes a fixed wall. What
/// `rigidity compare` tabulates, and what a sweep or a script asks of a material without
/// running a scene: the state behind the reflected front, the front's speed, and the impact
/// speed that crushes the bar.
#include <optional>

#include "rigidity/material.hpp"
#include "rigidity/status.hpp"

namespace rigidity {

struct Impact {
  double v = 0.0;            ///< the bar's speed towards the wall
  double s = 1.0;            ///< stretch behind the reflected front
  double p = 0.0;            ///< pressure behind it
  double front_speed = 0.0;  ///< the front's speed relative to the unstrained bar (in its rest frame)
};

/// An impact, or the status of the Riemann solver: out_of_range if the bar is crushed
/// (no classical solution), anything else a numerical failure.
struct ImpactOutcome {
  Impact impact;
  Status status = Status::ok;
};

/// An unstrained bar at speed v (0 < v < 1) strikes a fixed (push-only) wall on its right:
/// the state behind the reflected front from the exact Riemann solver, and the front's speed
/// relative to the unstrained bar.
[[nodiscard]] ImpactOutcome wall_impact(const Material& material, double v);

/// The impact speed from which on the bar is crushed (the state behind the front leaves the
/// admissible range), if any.
[[nodiscard]] std::optional<double> crush_speed(const Material& material);

/// A compression of the unstrained bar at rest to stretch s < 1: the speed the material
/// behind takes through a shock (the Hugoniot from rest), none where the jump conditions
/// have no solution; and through a smooth compression wave (the isentrope: J− = φ − Ψ
/// constant across a C+ wave, φ = Ψ(s) − Ψ(1)). The two agree for linearly degenerate laws.
[[nodiscard]] std::optional<double> hugoniot_speed(const Material& material, Stretch s);
[[nodiscard]] double isentrope_speed(const Material& material, Stretch s);

}  // namespace rigidity
