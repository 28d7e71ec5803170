// The schema is self-consistent: every key documented, conditions and exclusive groups
// refer to declared keys, defaults satisfy their own rules.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <variant>

#include "rigidity/registry.hpp"
#include "rigidity/scene_schema.hpp"

namespace rigidity::schema {
namespace {

void check_key(const Key& key, const std::string& path) {
  SCOPED_TRACE(path);
  EXPECT_FALSE(key.doc.empty()) << "undocumented key";
  if (const auto* d = std::get_if<double>(&key.fallback)) {
    EXPECT_TRUE(key.kind == Kind::number || key.kind == Kind::integer);
    const bool above = !key.lower || (key.lower->inclusive ? *d >= key.lower->value : *d > key.lower->value);
    const bool below = !key.upper || (key.upper->inclusive ? *d <= key.upper->value : *d < key.upper->value);
    const bool allowed =
        key.allowed.empty() || std::find(key.allowed.begin(), key.allowed.end(), *d) != key.allowed.end();
    EXPECT_TRUE(above && below && allowed) << "default " << *d << " breaks its own rule";
  }
  if (const auto* w = std::get_if<std::string>(&key.fallback); w != nullptr && key.kind == Kind::choice) {
    EXPECT_NE(std::find(key.words.begin(), key.words.end(), *w), key.words.end());
  }
  EXPECT_FALSE(key.required && !std::holds_alternative<std::monostate>(key.fallback)) << "required with a default";

  if (key.kind == Kind::map) {
    for (std::size_t i = 0; i < key.fields.size(); ++i) {
      const Key& field = key.fields[i];
      EXPECT_FALSE(field.name.empty());
      if (field.only_if) {
        // A condition refers to a sibling declared earlier (the walker checks in order).
        const auto earlier = std::find_if(key.fields.begin(), key.fields.begin() + static_cast<std::ptrdiff_t>(i),
                                          [&](const Key& k) { return k.name == field.only_if->sibling; });
        EXPECT_NE(earlier, key.fields.begin() + static_cast<std::ptrdiff_t>(i))
            << field.name << " depends on " << field.only_if->sibling;
      }
    }
    for (const OneOf& group : key.one_of)
      for (const std::string& name : group.keys) EXPECT_NE(key.field(name), nullptr) << name;
    EXPECT_TRUE(!key.extension || key.field(key.extension->selector) != nullptr);
  }
  EXPECT_TRUE((key.kind != Kind::list && key.kind != Kind::dictionary) || key.fields.size() == 1u);
  for (const Key& field : key.fields) check_key(field, path + "." + (field.name.empty() ? "-" : field.name));
}

TEST(Schema, IsSelfConsistent) { check_key(scene_schema(), "scene"); }

TEST(Schema, DeclaresTheTopLevelKeysOfSpec3) {
  const Key scene = scene_schema();
  std::vector<std::string> names;
  for (const Key& k : scene.fields) names.push_back(k.name);
  EXPECT_EQ(names, (std::vector<std::string>{"name", "units", "plugins", "materials", "bodies", "boundaries", "solver",
                                             "time", "outputs"}));
}

TEST(Schema, MaterialModelsComeFromTheRegistry) {
  const Key scene = scene_schema();
  const Key& model = scene.field("materials")->fields.front().fields.front();
  EXPECT_EQ(model.name, "model");
  EXPECT_EQ(model.words, MaterialRegistry::instance().names());
  for (const char* builtin : {"rigid", "hooke", "rigid_fluid", "constant_sound_speed"})
    EXPECT_NE(std::find(model.words.begin(), model.words.end(), builtin), model.words.end()) << builtin;
}

TEST(Schema, ParameterKeysMirrorTheirDeclaration) {
  const ParameterSpec spec =
      ParameterSpec::number("wave_speed", "V").with_dimension(Dimension::velocity).require().above(0.0).at_most(1.0);
  const Key key = Key::parameter(spec);
  EXPECT_EQ(key.kind, Kind::number);
  EXPECT_EQ(key.dimension, Dimension::velocity);
  EXPECT_TRUE(key.required);
  EXPECT_EQ(key.range_text(UnitSystem::natural), "(0, 1]");
  EXPECT_EQ(key.range_text(UnitSystem::si), "(0, 299792458] m/s");
  EXPECT_EQ(key.range_text(UnitSystem::natural), spec.range_text());
}

TEST(Schema, DescribeListsKeysWithUnits) {
  const std::string natural = describe(scene_schema());
  const std::string si = describe(scene_schema(), UnitSystem::si);
  for (const char* key : {"name:", "velocity:", "gamma:", "segments:", "table:", "tolerance:", "probes:", "fronts:"})
    EXPECT_NE(natural.find(key), std::string::npos) << key;
  EXPECT_NE(natural.find("default 1e-12"), std::string::npos);
  EXPECT_NE(si.find("[m/s]"), std::string::npos);
  EXPECT_NE(si.find("(-299792458, 299792458) m/s"), std::string::npos);
}

}  // namespace
}  // namespace rigidity::schema
