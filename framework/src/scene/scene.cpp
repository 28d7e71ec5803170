#include "rigidity/scene.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rigidity {

double BodyDecl::natural_length() const {
  double length = 0.0;
  for (const Segment& segment : segments) length += segment.length;
  return length;
}

double ramp_rapidity(const std::vector<double>& times, const std::vector<double>& rapidities, double t) {
  if (times.empty()) return 0.0;
  if (!(t < times.back())) return rapidities.back();
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  const std::size_t row = i == 0 ? 0 : i - 1;
  const double v0 = std::tanh(rapidities[row]), v1 = std::tanh(rapidities[row + 1]);
  return std::atanh(v0 + (v1 - v0) * (t - times[row]) / (times[row + 1] - times[row]));
}

PistonMotion linear_piston(const std::vector<double>& times, const std::vector<double>& rapidities, double step) {
  constexpr double kMaxRampSteps = 1000.0;
  // The ramp as written: velocity linear in time between rows, constant after the last.
  const auto ramp = [&](double t) { return ramp_rapidity(times, rapidities, t); };
  // The staircase's values, each the ramp at the middle of its interval, with the first row's
  // and the last row's values at the ends: (anchor time, value).
  std::vector<double> anchors{times.front()}, values{rapidities.front()};
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    const double t0 = times[i], t1 = times[i + 1];
    const double span = std::abs(rapidities[i + 1] - rapidities[i]);
    const int steps = static_cast<int>(std::clamp(std::ceil(span / step), 1.0, kMaxRampSteps));
    for (int k = 0; k < steps; ++k) {
      anchors.push_back(t0 + (t1 - t0) * (k + 0.5) / steps);
      values.push_back(ramp(anchors.back()));
    }
  }
  anchors.push_back(times.back());
  values.push_back(rapidities.back());
  // Each step is taken when the ramp's velocity is the mean of its two sides' velocities: the
  // step then leaves on the characteristic of its mean value to second order, also where two
  // rows meet at a kink of the ramp (the steps on either side differ there) and at the first
  // and last rows, and the piston's position integrates a linear ramp exactly.
  PistonMotion out;
  out.times.push_back(times.front());
  out.rapidities.push_back(values.front());
  for (std::size_t k = 1; k < values.size(); ++k) {
    if (values[k] == values[k - 1]) continue;  // a row at constant speed: no step
    const double mean = 0.5 * (std::tanh(values[k - 1]) + std::tanh(values[k]));
    double lo = anchors[k - 1], hi = anchors[k];
    const bool rising = values[k] > values[k - 1];
    for (int it = 0; it < 200 && hi - lo > 1e-15 * (1.0 + std::abs(hi)); ++it) {
      const double mid = 0.5 * (lo + hi);
      ((std::tanh(ramp(mid)) < mean) == rising ? lo : hi) = mid;
    }
    const double at = std::max(0.5 * (lo + hi), out.times.back());
    if (at == out.times.back()) {
      out.rapidities.back() = values[k];  // the step leaves at the start: the piston starts on it
    } else {
      out.times.push_back(at);
      out.rapidities.push_back(values[k]);
    }
  }
  out.ramps = true;
  out.row_times = times;
  out.row_rapidities = rapidities;
  return out;
}

}  // namespace rigidity
