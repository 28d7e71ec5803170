#pragma once
// A material registered only in scene_tests ("scene_test_material"): the rigid law,
// with a pressure-dimensioned parameter and a text parameter that no built-in has,
// so the loader's SI conversion of pressures and its text parameters are tested too.
// Its constructor refuses `label: explode` with std::invalid_argument.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/parameters.hpp"
#include "rigidity/registry.hpp"

namespace rigidity::test {

class SceneTestMaterial final : public Material {
 public:
  static constexpr std::string_view kName = "scene_test_material";
  static std::string doc() { return "the rigid law, with extra parameters for the scene loader's tests"; }
  static std::vector<ParameterSpec> parameters() {
    return {rest_density_parameter(),
            ParameterSpec::number("yield_pressure", "a pressure, to test SI conversion")
                .with_dimension(Dimension::pressure)
                .defaults_to(0.3)
                .above(0.0),
            ParameterSpec::number("signal_speed", "a velocity, to test SI conversion")
                .with_dimension(Dimension::velocity)
                .defaults_to(0.7)
                .above(0.0)
                .at_most(1.0),
            ParameterSpec::text("label", "a word").defaults_to(std::string("plain"))};
  }
  explicit SceneTestMaterial(const ParameterValues& values)
      : Material(values.number("rest_density")),
        yield_pressure_(values.number("yield_pressure")),
        signal_speed_(values.number("signal_speed")),
        label_(values.text("label")) {
    if (label_ == "explode") throw std::invalid_argument("label 'explode' is refused by the constructor");
  }

  [[nodiscard]] double yield_pressure() const { return yield_pressure_; }
  [[nodiscard]] double signal_speed() const { return signal_speed_; }
  [[nodiscard]] const std::string& label() const { return label_; }

  [[nodiscard]] std::string_view model() const override { return kName; }
  [[nodiscard]] double pressure(Stretch s) const override { return 0.5 * rest_density() * std::expm1(-2.0 * s.log()); }
  [[nodiscard]] double energy_density(Stretch s) const override {
    return 0.5 * rest_density() * (std::exp(-2.0 * s.log()) + 1.0);
  }
  [[nodiscard]] double sound_speed(Stretch) const override { return 1.0; }
  [[nodiscard]] double riemann_psi(Stretch s) const override { return -s.log(); }
  [[nodiscard]] Solved<Stretch> stretch_at_pressure(double p) const override {
    if (!(p > max_tension())) return Solved<Stretch>::failure(Status::out_of_range);
    return {Stretch::from_log(-0.5 * std::log1p(2.0 * p / rest_density())), Status::ok};
  }
  [[nodiscard]] Solved<Stretch> stretch_at_psi(double psi) const override {
    return {Stretch::from_log(-psi), Status::ok};
  }
  [[nodiscard]] double max_pressure() const override { return std::numeric_limits<double>::infinity(); }
  [[nodiscard]] double max_tension() const override { return -0.5 * rest_density(); }
  [[nodiscard]] double psi_max() const override { return std::numeric_limits<double>::infinity(); }
  [[nodiscard]] double psi_min() const override { return -std::numeric_limits<double>::infinity(); }
  [[nodiscard]] bool linearly_degenerate() const override { return true; }

 private:
  double yield_pressure_;
  double signal_speed_;
  std::string label_;
};

}  // namespace rigidity::test
