#pragma once
/// A function of one variable on [a, b] held as Chebyshev interpolants on panels: once built,
/// it is evaluated, differentiated, integrated and inverted in O(degree) operations. The numeric
/// materials (numeric_material.hpp), and through them `tabulated`, keep W(ln s) and Ψ(ln s) so.
///
/// On each panel [a_k, b_k] the function is the polynomial of degree kDegree through its values
/// at the Chebyshev points of the second kind (ends included), held by its Chebyshev
/// coefficients; evaluation is Clenshaw's recurrence. For a function analytic on the panel the
/// coefficients fall geometrically, and `adapt` splits a panel until they have fallen to the
/// requested relative tolerance (the criterion of chebfun, Trefethen et al., simplified).
/// Derivatives and antiderivatives are exact operations on the coefficients (Mason & Handscomb
/// §2.4); a derivative loses about kDegree² ulps of the function's scale on the panel.

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "rigidity/status.hpp"

namespace rigidity {

class PiecewiseChebyshev {
 public:
  /// Degree of the interpolant on each panel of a sampled function.
  static constexpr int kDegree = 20;
  static constexpr int kNodes = kDegree + 1;

  /// How `adapt` refines.
  struct Refinement {
    double rel_tol = 1e-14;         ///< last coefficients <= rel_tol · max |f| on the panel
    double max_width = 1.0;         ///< no panel wider
    double min_width = 1e-9;        ///< a panel this narrow is kept even if not converged (a kink)
    std::size_t max_panels = 4096;  ///< more: not_converged
  };

  PiecewiseChebyshev() = default;

  /// The Chebyshev points of the second kind on [a, b], ascending, a and b included.
  [[nodiscard]] static std::array<double, kNodes> nodes(double a, double b);

  /// f interpolated on the panels between consecutive `breaks` (ascending, at least two).
  /// not_converged if f gives a non-finite value.
  [[nodiscard]] static Solved<PiecewiseChebyshev> sample(const std::vector<double>& breaks,
                                                         const std::function<double(double)>& f);

  /// f on [breaks.front(), breaks.back()], each panel between `breaks` split in halves until it
  /// meets `refinement`. not_converged if f gives a non-finite value or needs too many panels.
  [[nodiscard]] static Solved<PiecewiseChebyshev> adapt(const std::vector<double>& breaks,
                                                        const std::function<double(double)>& f,
                                                        const Refinement& refinement);

  [[nodiscard]] bool empty() const { return breaks_.size() < 2; }
  [[nodiscard]] double lower() const { return breaks_.front(); }
  [[nodiscard]] double upper() const { return breaks_.back(); }
  /// Panel ends, ascending.
  [[nodiscard]] const std::vector<double>& breaks() const { return breaks_; }
  [[nodiscard]] std::size_t panels() const { return breaks_.size() - 1; }

  /// The panel holding x: the last whose lower end is <= x (the first and last panels also
  /// take x beyond the ends, where the polynomial extrapolates). \pre !empty()
  [[nodiscard]] std::size_t panel_of(double x) const;
  /// The value at x of panel k's polynomial.
  [[nodiscard]] double on_panel(std::size_t k, double x) const;
  /// The value at x.
  [[nodiscard]] double operator()(double x) const { return on_panel(panel_of(x), x); }

  /// The derivative, panel by panel.
  [[nodiscard]] PiecewiseChebyshev derivative() const;
  /// The antiderivative that vanishes at x0, continuous across panel ends (each panel's
  /// integral is accumulated outwards from the panel holding x0).
  [[nodiscard]] PiecewiseChebyshev integral(double x0) const;
  /// scale · f + shift.
  [[nodiscard]] PiecewiseChebyshev affine(double scale, double shift) const;
  /// a x + b y, for x and y on the same panels.
  [[nodiscard]] static PiecewiseChebyshev combination(double a, const PiecewiseChebyshev& x, double b,
                                                      const PiecewiseChebyshev& y);

 private:
  PiecewiseChebyshev(std::vector<double> breaks, int degree);
  [[nodiscard]] double* coefficients(std::size_t k) { return coefficients_.data() + k * stride(); }
  [[nodiscard]] const double* coefficients(std::size_t k) const { return coefficients_.data() + k * stride(); }
  [[nodiscard]] std::size_t stride() const { return static_cast<std::size_t>(degree_) + 1; }
  /// Panel k's coefficients from f at its nodes.
  void fit(std::size_t k, const std::array<double, kNodes>& values);

  std::vector<double> breaks_;
  int degree_ = 0;
  std::vector<double> coefficients_;  ///< panel after panel, degree_ + 1 each
};

}  // namespace rigidity
