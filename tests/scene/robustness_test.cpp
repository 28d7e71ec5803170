// No input crashes the loader: huge lists, deep nesting, alias bombs, binary garbage
// and random mutations of a valid scene all end in an InputError (or a valid Scene),
// never in another exception, an abort or exhausted memory.

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "rigidity/scene_loader.hpp"
#include "rigidity/scene_schema.hpp"

namespace rigidity {
namespace {

const std::string kHead = "name: n\nmaterials: {m: {model: rigid}}\n";

InputError refusal(const std::string& text) {
  try {
    (void)load_scene_string(text, "<generated>");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted";
  return InputError({}, "", "");
}

TEST(Limits, EnormousListOfSegments) {
  std::string text = kHead + "bodies:\n  - name: b\n    material: m\n    segments: [";
  for (std::size_t i = 0; i <= schema::kMaxListItems; ++i) text += "{length: 1},";
  text += "]\ntime: {end: 1}\n";
  const InputError e = refusal(text);
  EXPECT_EQ(e.key(), "bodies.0.segments");
  EXPECT_EQ(e.where().line, 6);
  EXPECT_NE(e.message().find("at most 100000"), std::string::npos) << e.what();
}

TEST(Limits, TooManyValuesAreRefusedBeforeBuildingATree) {
  std::string text = kHead + "outputs:\n  snapshots: [{quantities: [p], times: [";
  text.reserve(2 * schema::kMaxNodes + 200);
  for (std::size_t i = 0; i <= schema::kMaxNodes; ++i) text += "0,";
  text += "]}]\n";
  const InputError e = refusal(text);
  EXPECT_EQ(e.key(), "");
  EXPECT_NE(e.message().find("too many values"), std::string::npos) << e.what();
}

TEST(Limits, AliasBombIsRefusedWhileWalking) {
  // 2000 snapshots share one list of 1000 times through an alias: a small file, but
  // 2e6 values to check once the aliases are expanded.
  std::string bomb = kHead + "bodies: [{name: b, material: m, length: 1}]\ntime: {end: 1}\noutputs:\n  snapshots:\n";
  bomb += "    - {quantities: [p], times: &t [";
  for (int i = 0; i < 1000; ++i) bomb += "0,";
  bomb += "]}\n";
  for (int i = 0; i < 2000; ++i) bomb += "    - {quantities: [p], times: *t}\n";
  const InputError e = refusal(bomb);
  EXPECT_NE(e.message().find("aliases expanded"), std::string::npos) << e.what();
}

TEST(Limits, DeepNesting) {
  for (const char* open : {"[", "{a: ", "- "}) {
    std::string text = "name: ";
    for (int i = 0; i < 100000; ++i) text += open;
    const InputError e = refusal(text);
    EXPECT_EQ(e.where().line >= 1, true) << e.what();
  }
}

TEST(Limits, OversizedInput) {
  const std::string text(schema::kMaxInputBytes + 1, '#');
  const InputError e = refusal(text);
  EXPECT_NE(e.message().find("at most"), std::string::npos) << e.what();
}

TEST(Garbage, RandomBytes) {
  std::mt19937 random(12345);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(0, 400);
  for (int trial = 0; trial < 300; ++trial) {
    std::string text;
    const int n = length(random);
    for (int i = 0; i < n; ++i) text += static_cast<char>(byte(random));
    EXPECT_THROW((void)load_scene_string(text, "<garbage>"), InputError);
  }
}

TEST(Garbage, NulByteInTheMiddle) {
  std::string text(default_scene_text());
  text[text.size() / 2] = '\0';
  const InputError e = refusal(text);
  EXPECT_NE(e.message().find("not a text file"), std::string::npos) << e.what();
}

/// Mutations of the default scene, biased to YAML's syntax characters, must each load or
/// throw InputError: no other exception escapes.
TEST(Garbage, MutatedScenesNeverEscapeAsOtherErrors) {
  const std::string original(default_scene_text());
  const std::string alphabet = "[]{}:,-#&*!|>'\"%@?~ \n\t0123456789.eE+-abcxyz";
  std::mt19937 random(2024);
  std::uniform_int_distribution<std::size_t> where(0, original.size() - 1);
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);
  std::uniform_int_distribution<int> operation(0, 3);
  int accepted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string text = original;
    const int edits = 1 + trial % 4;
    for (int k = 0; k < edits && !text.empty(); ++k) {
      const std::size_t at = where(random) % text.size();
      switch (operation(random)) {
        case 0: text[at] = alphabet[pick(random)]; break;
        case 1: text.insert(at, 1, alphabet[pick(random)]); break;
        case 2: text.erase(at, 1); break;
        default: text.resize(at); break;
      }
    }
    try {
      (void)load_scene_string(text, "<mutated>");
      ++accepted;
    } catch (const InputError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << "escaped as " << typeid(e).name() << ": " << e.what() << "\n--- scene ---\n" << text;
    }
  }
  EXPECT_GT(accepted, 0);  // some mutations are harmless (in comments)
}

}  // namespace
}  // namespace rigidity
