#include "rigidity/chebyshev.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace rigidity {
namespace {

constexpr int kN = PiecewiseChebyshev::kDegree;

/// cos(m i π / N), m, i = 0..N: the matrix of the discrete cosine transform that turns values
/// at the Chebyshev points into coefficients.
const std::array<std::array<double, kN + 1>, kN + 1>& cosine_table() {
  static const auto table = [] {
    std::array<std::array<double, kN + 1>, kN + 1> t{};
    for (int m = 0; m <= kN; ++m)
      for (int i = 0; i <= kN; ++i) t[m][i] = std::cos(std::numbers::pi * (m * i % (2 * kN)) / kN);
    return t;
  }();
  return table;
}

/// Σ c_k T_k(u) by Clenshaw's recurrence.
double clenshaw(const double* c, int degree, double u) {
  double b1 = 0.0;
  double b2 = 0.0;
  for (int k = degree; k >= 1; --k) {
    const double b0 = c[k] + 2.0 * u * b1 - b2;
    b2 = b1;
    b1 = b0;
  }
  return c[0] + u * b1 - b2;
}

}  // namespace

PiecewiseChebyshev::PiecewiseChebyshev(std::vector<double> breaks, int degree)
    : breaks_(std::move(breaks)), degree_(degree), coefficients_((breaks_.size() - 1) * stride(), 0.0) {}

std::array<double, PiecewiseChebyshev::kNodes> PiecewiseChebyshev::nodes(double a, double b) {
  std::array<double, kNodes> t{};
  const double mid = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  for (int j = 0; j <= kN; ++j) t[j] = mid - half * std::cos(std::numbers::pi * j / kN);
  t[0] = a;
  t[kN] = b;
  return t;
}

void PiecewiseChebyshev::fit(std::size_t k, const std::array<double, kNodes>& values) {
  // values[j] is f at u_j = −cos(jπ/N) = cos((N − j)π/N): with i = N − j the usual
  // c_m = (2/N) Σ'' f(cos(iπ/N)) cos(m i π/N), the end terms (and then c_0, c_N) halved.
  const auto& cosines = cosine_table();
  double* c = coefficients(k);
  for (int m = 0; m <= kN; ++m) {
    double sum = 0.0;
    for (int i = 0; i <= kN; ++i) {
      const double weight = (i == 0 || i == kN) ? 0.5 : 1.0;
      sum += weight * values[kN - i] * cosines[m][i];
    }
    c[m] = (2.0 / kN) * sum;
  }
  c[0] *= 0.5;
  c[kN] *= 0.5;
}

Solved<PiecewiseChebyshev> PiecewiseChebyshev::sample(const std::vector<double>& breaks,
                                                      const std::function<double(double)>& f) {
  PiecewiseChebyshev out(breaks, kDegree);
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const std::array<double, kNodes> t = nodes(breaks[k], breaks[k + 1]);
    std::array<double, kNodes> values{};
    for (int j = 0; j <= kN; ++j) {
      values[j] = f(t[j]);
      if (!std::isfinite(values[j])) return Solved<PiecewiseChebyshev>::failure(Status::not_converged);
    }
    out.fit(k, values);
  }
  return {std::move(out)};
}

Solved<PiecewiseChebyshev> PiecewiseChebyshev::adapt(const std::vector<double>& breaks,
                                                     const std::function<double(double)>& f,
                                                     const Refinement& refinement) {
  // Panels no wider than max_width to start with, then halves until converged.
  std::vector<std::pair<double, double>> pending;  // a stack: the leftmost panel on top
  for (std::size_t k = breaks.size() - 1; k-- > 0;) {
    const double a = breaks[k];
    const double b = breaks[k + 1];
    const double count = std::max(1.0, std::ceil((b - a) / refinement.max_width));
    if (!(count <= static_cast<double>(refinement.max_panels)))
      return Solved<PiecewiseChebyshev>::failure(Status::not_converged);
    const auto pieces = static_cast<int>(count);
    for (int i = pieces; i-- > 0;)
      pending.emplace_back(i == 0 ? a : a + (b - a) * i / pieces, i + 1 == pieces ? b : a + (b - a) * (i + 1) / pieces);
  }
  std::vector<double> accepted_breaks{breaks.front()};
  std::vector<double> accepted_coefficients;
  PiecewiseChebyshev panel({0.0, 1.0}, kDegree);  // scratch for one panel's coefficients
  while (!pending.empty()) {
    const auto [a, b] = pending.back();
    pending.pop_back();
    const std::array<double, kNodes> t = nodes(a, b);
    std::array<double, kNodes> values{};
    double scale = 0.0;
    for (int j = 0; j <= kN; ++j) {
      values[j] = f(t[j]);
      if (!std::isfinite(values[j])) return Solved<PiecewiseChebyshev>::failure(Status::not_converged);
      scale = std::max(scale, std::abs(values[j]));
    }
    panel.fit(0, values);
    const double* c = panel.coefficients(0);
    const double tail = std::max({std::abs(c[kN - 2]), std::abs(c[kN - 1]), std::abs(c[kN])});
    if (tail <= refinement.rel_tol * scale || b - a <= refinement.min_width) {
      accepted_breaks.push_back(b);
      accepted_coefficients.insert(accepted_coefficients.end(), c, c + kNodes);
      if (accepted_breaks.size() - 1 > refinement.max_panels)
        return Solved<PiecewiseChebyshev>::failure(Status::not_converged);
      continue;
    }
    const double mid = 0.5 * (a + b);
    pending.emplace_back(mid, b);
    pending.emplace_back(a, mid);
  }
  PiecewiseChebyshev out(std::move(accepted_breaks), kDegree);
  out.coefficients_ = std::move(accepted_coefficients);
  return {std::move(out)};
}

std::size_t PiecewiseChebyshev::panel_of(double x) const {
  const auto it = std::upper_bound(breaks_.begin() + 1, breaks_.end() - 1, x);
  return static_cast<std::size_t>(it - breaks_.begin()) - 1;
}

double PiecewiseChebyshev::on_panel(std::size_t k, double x) const {
  const double a = breaks_[k];
  const double b = breaks_[k + 1];
  return clenshaw(coefficients(k), degree_, (2.0 * x - a - b) / (b - a));
}

PiecewiseChebyshev PiecewiseChebyshev::derivative() const {
  PiecewiseChebyshev out(breaks_, std::max(degree_ - 1, 0));
  for (std::size_t k = 0; k < panels(); ++k) {
    const double* c = coefficients(k);
    double* d = out.coefficients(k);
    // d_{m−1} = d_{m+1} + 2m c_m (m = n..1, d_n = d_{n+1} = 0), then d_0 halved; × du/dx.
    const double du_dx = 2.0 / (breaks_[k + 1] - breaks_[k]);
    std::vector<double> derived(stride() + 1, 0.0);
    for (int m = degree_; m >= 1; --m) derived[m - 1] = derived[m + 1] + 2.0 * m * c[m];
    derived[0] *= 0.5;
    for (int m = 0; m <= out.degree_; ++m) d[m] = derived[m];
    for (int m = 0; m <= out.degree_; ++m) d[m] *= du_dx;
  }
  return out;
}

PiecewiseChebyshev PiecewiseChebyshev::integral(double x0) const {
  const int n = degree_ + 1;
  PiecewiseChebyshev out(breaks_, n);
  std::vector<double> whole(panels());  // ∫ over each panel
  for (std::size_t k = 0; k < panels(); ++k) {
    const double* c = coefficients(k);
    double* integral_coefficients = out.coefficients(k);
    auto coefficient = [&](int m) { return m <= degree_ ? c[m] : 0.0; };
    const double dx_du = 0.5 * (breaks_[k + 1] - breaks_[k]);
    // ∫T_0 = T_1, ∫T_m = T_{m+1}/(2(m+1)) − T_{m−1}/(2(m−1)): C_1 = c_0 − c_2/2, C_m = (c_{m−1} − c_{m+1})/(2m).
    integral_coefficients[1] = (coefficient(0) - 0.5 * coefficient(2)) * dx_du;
    for (int m = 2; m <= n; ++m)
      integral_coefficients[m] = (coefficient(m - 1) - coefficient(m + 1)) / (2.0 * m) * dx_du;
    // Zero at the panel's lower end (T_m(−1) = (−1)^m); the panel's integral is the value at its upper end.
    double at_lower = 0.0;
    double at_upper = 0.0;
    for (int m = 1; m <= n; ++m) {
      at_lower += (m % 2 == 0 ? 1.0 : -1.0) * integral_coefficients[m];
      at_upper += integral_coefficients[m];
    }
    integral_coefficients[0] = -at_lower;
    whole[k] = at_upper - at_lower;
  }
  // The antiderivative at each panel's lower end, accumulated outwards from x0.
  const std::size_t home = panel_of(x0);
  std::vector<double> at_break(breaks_.size(), 0.0);
  at_break[home] = -out.on_panel(home, x0);
  for (std::size_t k = home; k < panels(); ++k) at_break[k + 1] = at_break[k] + whole[k];
  for (std::size_t k = home; k-- > 0;) at_break[k] = at_break[k + 1] - whole[k];
  for (std::size_t k = 0; k < panels(); ++k) out.coefficients(k)[0] += at_break[k];
  return out;
}

PiecewiseChebyshev PiecewiseChebyshev::affine(double scale, double shift) const {
  PiecewiseChebyshev out = *this;
  for (double& c : out.coefficients_) c *= scale;
  for (std::size_t k = 0; k < panels(); ++k) out.coefficients(k)[0] += shift;
  return out;
}

PiecewiseChebyshev PiecewiseChebyshev::combination(double a, const PiecewiseChebyshev& x, double b,
                                                   const PiecewiseChebyshev& y) {
  PiecewiseChebyshev out(x.breaks_, std::max(x.degree_, y.degree_));
  for (std::size_t k = 0; k < out.panels(); ++k) {
    double* c = out.coefficients(k);
    for (int m = 0; m <= x.degree_; ++m) c[m] += a * x.coefficients(k)[m];
    for (int m = 0; m <= y.degree_; ++m) c[m] += b * y.coefficients(k)[m];
  }
  return out;
}

}  // namespace rigidity
