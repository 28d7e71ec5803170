// The material registry: exactly the expected materials, each registered from its own
// file with its parameters declared; duplicates and unknown names reported usefully.

#include "rigidity/registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "material_test_support.hpp"
#include "rigidity/numeric_material.hpp"

namespace rigidity::testing {
namespace {

/// A second material called "rigid", to provoke a duplicate registration.
class AnotherRigid final : public PressureLawMaterial {
 public:
  static constexpr std::string_view kName = "rigid";
  static std::string doc() { return "Test only: a duplicate of `rigid`."; }
  static std::vector<ParameterSpec> parameters() { return {rest_density_parameter()}; }
  explicit AnotherRigid(const ParameterValues& values) : PressureLawMaterial(values.number("rest_density")) {}
  [[nodiscard]] std::string_view model() const override { return kName; }

 private:
  [[nodiscard]] double pressure_law(double s) const override { return 0.5 * rest_density() * (1.0 / (s * s) - 1.0); }
};

std::vector<std::string> expected_names() {
  std::vector<std::string> names = kBuiltinMaterials;
  names.insert(names.end(), kTestOnlyMaterials.begin(), kTestOnlyMaterials.end());
  std::sort(names.begin(), names.end());
  return names;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(MaterialRegistry, ListsExactlyTheBuiltinsAndTheTestMaterials) {
  EXPECT_EQ(MaterialRegistry::instance().names(), expected_names());
  EXPECT_NO_THROW(MaterialRegistry::instance().check());
}

TEST(MaterialRegistry, BuiltinsRegisterFromTheirOwnFiles) {
  for (const std::string& name : kBuiltinMaterials) {
    const MaterialInfo& info = MaterialRegistry::instance().at(name);
    EXPECT_TRUE(info.file.ends_with("materials/" + name + ".cpp")) << name << " registered at " << info.file;
    EXPECT_GT(info.line, 0) << name;
  }
}

TEST(MaterialRegistry, EveryMaterialDeclaresItsParametersAndNamesItself) {
  for (const std::string& name : MaterialRegistry::instance().names()) {
    SCOPED_TRACE(name);
    const MaterialInfo& info = MaterialRegistry::instance().at(name);
    EXPECT_FALSE(info.doc.empty());
    const auto rho = std::find_if(info.parameters.begin(), info.parameters.end(),
                                  [](const ParameterSpec& p) { return p.name == "rest_density"; });
    ASSERT_NE(rho, info.parameters.end()) << "every material takes rest_density (docs/materials.md)";
    EXPECT_EQ(rho->default_number, 1.0);
    EXPECT_EQ(rho->dimension, Dimension::density);
    EXPECT_NE(rho->range_violation(0.0), "");
    for (const ParameterSpec& p : info.parameters) {
      EXPECT_FALSE(p.doc.empty()) << p.name;
      EXPECT_TRUE(p.required || p.default_number || p.default_text || p.type == ParameterType::numbers)
          << p.name << ": neither required nor defaulted (a map of numbers is empty by default)";
    }
    std::map<std::string, double> required;
    for (const ParameterSpec& p : info.parameters)
      if (p.required && p.type == ParameterType::number)  // required texts: make_material's samples
        required[p.name] = p.upper ? p.upper->value : (p.lower ? p.lower->value + 1.0 : 1.0);
    EXPECT_EQ(make_material(name, required)->model(), name);
  }
  // docs/materials.md: wave_speed and sound_speed are required velocities in (0, 1].
  for (const auto& [model, key] :
       {std::pair{"hooke", "wave_speed"}, std::pair{"constant_sound_speed", "sound_speed"}}) {
    const MaterialInfo& info = MaterialRegistry::instance().at(model);
    const auto p = std::find_if(info.parameters.begin(), info.parameters.end(),
                                [&key = key](const ParameterSpec& spec) { return spec.name == key; });
    ASSERT_NE(p, info.parameters.end()) << model;
    EXPECT_TRUE(p->required);
    EXPECT_EQ(p->dimension, Dimension::velocity);
    EXPECT_EQ(p->range_text(), "(0, 1]");
    EXPECT_THROW(make_material(model), std::invalid_argument) << model << " without " << key;
  }
}

TEST(MaterialRegistry, UnknownNameListsTheRegisteredOnesAndTheClosest) {
  const MaterialRegistry& registry = MaterialRegistry::instance();
  EXPECT_EQ(registry.find("steel"), nullptr);
  try {
    static_cast<void>(registry.at("rigdi"));
    FAIL() << "an unknown name was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "'rigdi'")) << what;
    EXPECT_TRUE(contains(what, "did you mean 'rigid'")) << what;
    for (const std::string& name : registry.names()) EXPECT_TRUE(contains(what, name)) << what;
  }
  EXPECT_EQ(registry.closest("hook"), "hooke");
  EXPECT_EQ(registry.closest("rigid_fluids"), "rigid_fluid");
  EXPECT_EQ(registry.closest("constant_soundspeed"), "constant_sound_speed");
  EXPECT_EQ(registry.closest("unobtainium"), "");
}

TEST(MaterialRegistryDeathTest, DuplicateDuringStartupIsReportedByCheckNamingBothPlaces) {
  // In a fresh process (the registry is process-wide): a duplicate added during static
  // initialisation is recorded, and check() reports it.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        MaterialRegistry& registry = MaterialRegistry::instance();
        const bool added = registry.add(describe_material<AnotherRigid>(__FILE__, 4242));
        try {
          registry.check();
        } catch (const std::runtime_error& e) {
          std::fprintf(stderr, "%s\n", e.what());
          std::exit(added ? 1 : 0);
        }
        std::exit(2);
      },
      ::testing::ExitedWithCode(0),
      "material 'rigid' is registered twice: at .*materials/rigid\\.cpp:[0-9]+ and at .*registry_test\\.cpp:4242");
}

TEST(MaterialRegistry, DuplicateAfterStartupThrowsNamingBothPlaces) {
  MaterialRegistry& registry = MaterialRegistry::instance();
  registry.seal();  // as main() does once static initialisation is over
  const MaterialInfo& original = registry.at("rigid");
  const int line = __LINE__ + 2;
  try {
    registry.add(describe_material<AnotherRigid>(__FILE__, line));
    FAIL() << "a duplicate name was accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "'rigid'")) << what;
    EXPECT_TRUE(contains(what, original.file + ":" + std::to_string(original.line))) << what;
    EXPECT_TRUE(contains(what, std::string(__FILE__) + ":" + std::to_string(line))) << what;
  }
  EXPECT_EQ(registry.names(), expected_names());
  EXPECT_EQ(registry.at("rigid").file, original.file);
}

/// A material a plugin would bring, added and withdrawn again in a batch.
class BatchMaterial final : public PressureLawMaterial {
 public:
  static constexpr std::string_view kName = "batch_material";
  static std::string doc() { return "Test only: a material of a plugin that is refused."; }
  static std::vector<ParameterSpec> parameters() { return {rest_density_parameter()}; }
  explicit BatchMaterial(const ParameterValues& values) : PressureLawMaterial(values.number("rest_density")) {}
  [[nodiscard]] std::string_view model() const override { return kName; }

 private:
  [[nodiscard]] double pressure_law(double s) const override { return 0.5 * rest_density() * (1.0 / (s * s) - 1.0); }
};

TEST(MaterialRegistry, LookupsOnOtherThreadsSeeThePluginsAddedAndWithdrawnWhole) {
  // A sweep case may load a plugin while others look materials up: the registry is shared.
  MaterialRegistry& registry = MaterialRegistry::instance();
  const std::vector<std::string> before = registry.names();
  std::vector<std::string> with = before;
  with.push_back("batch_material");
  std::sort(with.begin(), with.end());
  std::atomic<bool> done{false};
  std::atomic<long> lookups{0}, torn{0};
  const auto look = [&] {
    while (!done.load()) {
      if (registry.find("rigid") == nullptr) ++torn;
      const std::vector<std::string> names = registry.names();
      if (names != before && names != with) ++torn;
      ++lookups;
    }
  };
  std::thread a(look), b(look);
  for (int i = 0; i < 2000 || lookups.load() < 200; ++i) {  // while both look
    registry.begin_batch();
    registry.add(describe_material<BatchMaterial>(__FILE__, __LINE__));
    registry.end_batch(false);
  }
  done = true;
  a.join();
  b.join();
  EXPECT_GT(lookups.load(), 0);
  EXPECT_EQ(torn.load(), 0);
  EXPECT_EQ(registry.names(), before);
}

}  // namespace
}  // namespace rigidity::testing
