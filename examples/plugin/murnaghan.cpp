// A material plugin: Murnaghan's equation of state for solids (1944), p = (K/n)(s^-n - 1), with
// K = rho00 c0^2 and n = 4. Only p(s) is given; rigidity derives W, c_s and the Riemann invariant.
#include <cmath>
#include <rigidity/numeric_material.hpp>
#include <rigidity/plugins.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace {

class Murnaghan final : public rigidity::PressureLawMaterial {
 public:
  static constexpr std::string_view kName = "murnaghan";
  static std::string doc() {
    return "Murnaghan's solid, p = (K/n)(s^-n - 1), K = rho00 c0^2, n = 4: it stiffens in compression, and "
           "turns acausal near s = 0.2 at c0 = 0.1 c, so its range is s in [0.3, 3].";
  }
  static std::vector<rigidity::ParameterSpec> parameters() {
    return {rigidity::rest_density_parameter(),
            rigidity::ParameterSpec::number("sound_speed", "c0: the sound speed of the unstrained solid")
                .with_dimension(rigidity::Dimension::velocity)
                .defaults_to(0.1)
                .above(0.0)
                .at_most(0.1)};
  }
  explicit Murnaghan(const rigidity::ParameterValues& values)
      : PressureLawMaterial(values.number("rest_density"), {std::log(0.3), std::log(3.0)}),
        bulk_modulus_(values.number("rest_density") * std::pow(values.number("sound_speed"), 2)) {}
  [[nodiscard]] std::string_view model() const override { return kName; }

 private:
  [[nodiscard]] double pressure_law(double s) const override { return bulk_modulus_ / 4.0 * (std::pow(s, -4.0) - 1.0); }
  double bulk_modulus_;  ///< K = rho00 c0^2
};

}  // namespace

RIGIDITY_REGISTER_MATERIAL(Murnaghan);
RIGIDITY_PLUGIN();
