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

std::vector<Inflection> find_inflections(const Material& material, StretchRange window) {
  std::vector<Inflection> found;
  if (!std::isfinite(window.log_min) || !std::isfinite(window.log_max) || !(window.log_max > window.log_min))
    return found;
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
  // Each change of sign lies between the last sample of one sign and the next of the other.
  std::size_t last = logs.size();
  for (std::size_t k = 0; k < logs.size(); ++k) {
    const int here = sign(g[k]);
    if (here == 0) continue;
    if (last < logs.size() && sign(g[last]) != here) {
      double a = logs[last], b = logs[k];
      const bool negative_at_a = g[last] < 0.0;
      for (int step = 0; step < kBisections; ++step) {
        const double middle = 0.5 * (a + b);
        ((genuine_nonlinearity(material, middle, window) < 0.0) == negative_at_a ? a : b) = middle;
      }
      found.push_back(Inflection{std::exp(0.5 * (a + b)), std::exp(logs[last]), g[last], std::exp(logs[k]), g[k]});
    }
    last = k;
  }
  return found;
}

std::optional<Inflection> find_inflection(const Material& material, StretchRange window) {
  const std::vector<Inflection> all = find_inflections(material, window);
  if (all.empty()) return std::nullopt;
  const auto distance = [](const Inflection& i) {
    return std::min(std::abs(std::log(i.s_before)), std::abs(std::log(i.s_after)));
  };
  return *std::min_element(all.begin(), all.end(),
                           [&](const Inflection& a, const Inflection& b) { return distance(a) < distance(b); });
}

StretchRange inflection_window(const Material& material) {
  constexpr double kScan = 100.0;
  StretchRange window = material.admissible();
  window.log_min = std::max(window.log_min, -std::log(kScan));
  window.log_max = std::min(window.log_max, std::log(kScan));
  return window;
}

const std::vector<double>& Material::inflection_logs() const {
  std::call_once(inflections_found_, [this] {
    if (linearly_degenerate()) return;
    for (const Inflection& i : find_inflections(*this, inflection_window(*this)))
      inflection_logs_.push_back(std::log(i.stretch));
  });
  return inflection_logs_;
}

}  // namespace rigidity
