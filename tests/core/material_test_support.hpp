#pragma once
// Helpers shared by the material tests: building a registered material from parameter
// values (as the scene loader would), stretch grids, finite differences and an
// independent GSL quadrature of the Riemann invariant.

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/registry.hpp"

namespace rigidity::testing {

inline constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

/// The materials every build registers (SPEC §2).
inline const std::vector<std::string> kBuiltinMaterials = {"constant_sound_speed", "hooke", "rigid", "rigid_fluid"};
/// The materials only this test binary registers (numeric_material_test.cpp).
inline const std::vector<std::string> kTestOnlyMaterials = {"test_constant_sound_speed_strain_energy",
                                                            "test_rigid_pressure_law"};

/// Registered material `name`: declared defaults, then `values`, each checked against its
/// declared range as the scene loader does. \throws std::invalid_argument on a bad value.
inline std::shared_ptr<const Material> make_material(std::string_view name,
                                                     const std::map<std::string, double>& values = {}) {
  const MaterialInfo& info = MaterialRegistry::instance().at(name);
  ParameterValues parameters;
  for (const ParameterSpec& spec : info.parameters)
    if (spec.default_number) parameters.set(spec.name, *spec.default_number);
  for (const auto& [key, value] : values) {
    const auto spec = std::find_if(info.parameters.begin(), info.parameters.end(),
                                   [&key = key](const ParameterSpec& p) { return p.name == key; });
    if (spec == info.parameters.end())
      throw std::invalid_argument(std::string(name) + " has no parameter '" + key + "'");
    if (const std::string rule = spec->range_violation(value); !rule.empty())
      throw std::invalid_argument(std::string(name) + "." + key + " " + rule);
    parameters.set(key, value);
  }
  for (const ParameterSpec& spec : info.parameters)
    if (spec.required && !parameters.has(spec.name))
      throw std::invalid_argument(std::string(name) + " needs '" + spec.name + "'");
  return info.make(parameters);
}

/// Stretches from 1e-9 to 1e12 (ln-spaced), strains of ±1e-12, ±1e-6, ±1e-3 and s = 1, kept
/// where the material is admissible, plus the finite ends of its admissible range.
inline std::vector<Stretch> stretch_grid(const Material& material) {
  const StretchRange range = material.admissible();
  std::vector<Stretch> grid;
  const double log_lo = std::log(1e-9);
  const double log_hi = std::log(1e12);
  constexpr int kSteps = 42;
  for (int i = 0; i <= kSteps; ++i) grid.push_back(Stretch::from_log(log_lo + (log_hi - log_lo) * i / kSteps));
  for (double strain : {-1e-3, -1e-6, -1e-12, 0.0, 1e-12, 1e-6, 1e-3}) grid.push_back(Stretch::from_strain(strain));
  std::erase_if(grid, [&](Stretch s) { return !range.contains(s); });
  if (std::isfinite(range.log_min)) grid.push_back(Stretch::from_log(range.log_min));
  if (std::isfinite(range.log_max)) grid.push_back(Stretch::from_log(range.log_max));
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  return grid;
}

/// df/dt at t by the fourth-order central difference with step h.
template <class F>
double central_difference(F&& f, double t, double h) {
  return (f(t - 2.0 * h) - 8.0 * f(t - h) + 8.0 * f(t + h) - f(t + 2.0 * h)) / (12.0 * h);
}

/// Ψ(s) = ∫_{ln s}^0 c_s dτ by GSL QAG, independently of the material's own Ψ.
inline double reference_psi(const Material& material, Stretch s, double epsrel) {
  if (s.log() == 0.0) return 0.0;
  gsl_set_error_handler_off();
  auto integrand = [](double tau, void* params) {
    return static_cast<const Material*>(params)->sound_speed(Stretch::from_log(tau));
  };
  gsl_function f{integrand, const_cast<Material*>(&material)};
  constexpr std::size_t kLimit = 500;
  gsl_integration_workspace* workspace = gsl_integration_workspace_alloc(kLimit);
  double result = 0.0;
  double abserr = 0.0;
  const int status =
      gsl_integration_qag(&f, s.log(), 0.0, 0.0, epsrel, kLimit, GSL_INTEG_GAUSS41, workspace, &result, &abserr);
  gsl_integration_workspace_free(workspace);
  if (status != GSL_SUCCESS) throw std::runtime_error(std::string("reference quadrature: ") + gsl_strerror(status));
  return result;
}

}  // namespace rigidity::testing
