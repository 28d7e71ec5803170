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

PistonMotion linear_piston(const std::vector<double>& times, const std::vector<double>& rapidities, double step) {
  constexpr double kMaxRampSteps = 1000.0;
  PistonMotion out;
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    const double t0 = times[i], t1 = times[i + 1];
    const double v0 = std::tanh(rapidities[i]), v1 = std::tanh(rapidities[i + 1]);
    const double span = std::abs(rapidities[i + 1] - rapidities[i]);
    const int steps = static_cast<int>(std::clamp(std::ceil(span / step), 1.0, kMaxRampSteps));
    for (int k = 0; k < steps; ++k) {
      const double a = (k + 0.5) / steps;  // the middle of the step
      out.times.push_back(t0 + (t1 - t0) * k / steps);
      out.rapidities.push_back(std::atanh(v0 + (v1 - v0) * a));
    }
  }
  out.times.push_back(times.back());
  out.rapidities.push_back(rapidities.back());
  out.ramps = true;
  out.row_times = times;
  out.row_rapidities = rapidities;
  return out;
}

}  // namespace rigidity
