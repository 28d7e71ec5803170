#include "rigidity/convexity.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "rigidity/number_text.hpp"

namespace rigidity {
namespace {

/// Half the step in ln s of the centred difference that gives dc_s/d(ln s).
constexpr double kStep = 1e-4;
/// |g| below this fraction of the largest c_s on the window counts as zero (linearly degenerate
/// there). g is the difference of two terms of the size of c_s, each from a numeric law's c_s:
/// on tabulated linearly degenerate laws (g = 0) it comes out at up to 6e-4 of c_s (a Hooke steel
/// table in Pa), on formulas at 2.2e-7 of c (the rigid law as a strain energy).
constexpr double kZero = 2e-3;
/// The scan leaves this fraction of the window's width in ln s at either end, where a numeric
/// law's c_s is fitted from one side only (a tabulated Murnaghan law's g changes sign 0.6 % from
/// the end of its table, a fit's end effect).
constexpr double kEdge = 0.02;
/// Samples of the window, and bisection steps that locate an inflection between two of them.
constexpr int kSamples = 400;
constexpr int kBisections = 60;

std::string behaviour(double g) {
  return g < 0.0 ? "compressions are shocks and expansions fans" : "expansions are shocks and compressions fans";
}

}  // namespace

double genuine_nonlinearity(const Material& material, double log_s, StretchRange window) {
  const double t = std::clamp(log_s, window.log_min + kStep, window.log_max - kStep);
  const double cs = material.sound_speed(Stretch::from_log(t));
  const double slope =
      (material.sound_speed(Stretch::from_log(t + kStep)) - material.sound_speed(Stretch::from_log(t - kStep))) /
      (2.0 * kStep);
  return slope - cs * (1.0 - cs * cs);
}

std::string Inflection::describe() const {
  return "at s = " + twelve_digits(stretch) +
         ": not convex: the genuine nonlinearity g = dc_s/d(ln s) - c_s (1 - c_s^2) changes sign there (g = " +
         twelve_digits(g_before) + " at s = " + twelve_digits(s_before) + ", where " + behaviour(g_before) +
         "; g = " + twelve_digits(g_after) + " at s = " + twelve_digits(s_after) + ", where " + behaviour(g_after) +
         ")";
}

std::optional<Inflection> find_inflection(const Material& material, StretchRange window) {
  if (!std::isfinite(window.log_min) || !std::isfinite(window.log_max) || !(window.log_max > window.log_min))
    return std::nullopt;
  std::vector<double> logs, g;
  double fastest = 0.0;
  const double width = window.log_max - window.log_min;
  const double from = window.log_min + kEdge * width, to = window.log_max - kEdge * width;
  for (int k = 0; k <= kSamples; ++k) {
    const double t = from + (to - from) * static_cast<double>(k) / kSamples;
    logs.push_back(t);
    fastest = std::max(fastest, material.sound_speed(Stretch::from_log(t)));
    g.push_back(genuine_nonlinearity(material, t, window));
  }
  const double zero = kZero * fastest;
  const auto sign = [&](double value) { return value > zero ? 1 : value < -zero ? -1 : 0; };
  // The changes of sign, each between the last sample of one sign and the next of the other;
  // the one nearest to s = 1.
  std::size_t last = logs.size(), best_a = 0, best_b = 0;
  bool found = false;
  for (std::size_t k = 0; k < logs.size(); ++k) {
    const int here = sign(g[k]);
    if (here == 0) continue;
    if (last < logs.size() && sign(g[last]) != here) {
      const double distance = std::min(std::abs(logs[last]), std::abs(logs[k]));
      if (!found || distance < std::min(std::abs(logs[best_a]), std::abs(logs[best_b]))) {
        best_a = last;
        best_b = k;
        found = true;
      }
    }
    last = k;
  }
  if (!found) return std::nullopt;
  double a = logs[best_a], b = logs[best_b];
  const bool negative_at_a = g[best_a] < 0.0;
  for (int step = 0; step < kBisections; ++step) {
    const double middle = 0.5 * (a + b);
    ((genuine_nonlinearity(material, middle, window) < 0.0) == negative_at_a ? a : b) = middle;
  }
  return Inflection{std::exp(0.5 * (a + b)), std::exp(logs[best_a]), g[best_a], std::exp(logs[best_b]), g[best_b]};
}

}  // namespace rigidity
