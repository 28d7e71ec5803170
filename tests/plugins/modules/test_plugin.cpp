// Test plugins (tests/plugins/plugins_test.cpp), one per variant, selected by a definition:
//   RIGIDITY_TEST_PLUGIN_GOOD          a causal material, test_plugin_material
//   RIGIDITY_TEST_PLUGIN_ACAUSAL       c_s = 2 c: refused
//   RIGIDITY_TEST_PLUGIN_WRONG_ABI     says it was built for another plugin ABI: refused
//   RIGIDITY_TEST_PLUGIN_NOT_A_PLUGIN  registers a material but lacks RIGIDITY_PLUGIN(): refused
//   RIGIDITY_TEST_PLUGIN_DUPLICATE     registers a second `rigid`: refused
//   RIGIDITY_TEST_PLUGIN_REQUIRED      a material with a required parameter (a factor on its
//                                      stiffness: acausal above 4): loaded, with a note
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "rigidity/numeric_material.hpp"
#include "rigidity/plugins.hpp"

namespace {

#if defined(RIGIDITY_TEST_PLUGIN_GOOD)
constexpr std::string_view kMaterialName = "test_plugin_material";
constexpr double kStiffness = 0.25;  // the rigid law scaled: c_s(1) = 0.5
#elif defined(RIGIDITY_TEST_PLUGIN_ACAUSAL)
constexpr std::string_view kMaterialName = "test_plugin_acausal";
constexpr double kStiffness = 4.0;  // c_s = 2 > c
#elif defined(RIGIDITY_TEST_PLUGIN_WRONG_ABI)
constexpr std::string_view kMaterialName = "test_plugin_wrong_abi";
constexpr double kStiffness = 0.25;
#elif defined(RIGIDITY_TEST_PLUGIN_NOT_A_PLUGIN)
constexpr std::string_view kMaterialName = "test_plugin_not_a_plugin";
constexpr double kStiffness = 0.25;
#elif defined(RIGIDITY_TEST_PLUGIN_DUPLICATE)
constexpr std::string_view kMaterialName = "rigid";
constexpr double kStiffness = 1.0;
#elif defined(RIGIDITY_TEST_PLUGIN_REQUIRED)
constexpr std::string_view kMaterialName = "test_plugin_required";
constexpr double kStiffness = 0.25;
#endif

/// p = (k ρ00/2)(1/s² − 1) on s in [0.5, 2]: the rigid law scaled by k.
class TestMaterial final : public rigidity::PressureLawMaterial {
 public:
  static constexpr std::string_view kName = kMaterialName;
  static std::string doc() { return "Test only: the rigid law scaled, from a plugin."; }
  static std::vector<rigidity::ParameterSpec> parameters() {
    std::vector<rigidity::ParameterSpec> out{rigidity::rest_density_parameter()};
#if defined(RIGIDITY_TEST_PLUGIN_REQUIRED)
    out.push_back(rigidity::ParameterSpec::number("scale", "a required factor").require().above(0.0));
#endif
    return out;
  }
  explicit TestMaterial(const rigidity::ParameterValues& values)
      : PressureLawMaterial(values.number("rest_density"), {std::log(0.5), std::log(2.0)}) {
#if defined(RIGIDITY_TEST_PLUGIN_REQUIRED)
    scale_ = values.number("scale");
#endif
  }
  [[nodiscard]] std::string_view model() const override { return kName; }

 private:
  [[nodiscard]] double pressure_law(double s) const override {
    return 0.5 * kStiffness * scale_ * rest_density() * (1.0 / (s * s) - 1.0);
  }
  double scale_ = 1.0;
};

}  // namespace

RIGIDITY_REGISTER_MATERIAL(TestMaterial);

#if defined(RIGIDITY_TEST_PLUGIN_WRONG_ABI)
extern "C" __attribute__((visibility("default"))) int rigidity_plugin_abi_version() {
  return rigidity::kPluginAbiVersion + 1;
}
extern "C" __attribute__((visibility("default"))) const char* rigidity_plugin_built_against() { return "9.9.9"; }
#elif !defined(RIGIDITY_TEST_PLUGIN_NOT_A_PLUGIN)
RIGIDITY_PLUGIN();
#endif
