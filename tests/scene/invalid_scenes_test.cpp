// Every file in tests/scenes/invalid/ is a scene the loader must refuse. Each carries
// its expectation in header comments:
//
//   # expect-line: 7                       the line of the error (1-based)
//   # expect-key: bodies.0.velocity        the dotted key (empty: the file as a whole)
//   # expect-message: |v| < c              text the message must contain (any number of these)

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/scene_loader.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kInvalidDir = fs::path(RIGIDITY_TEST_DATA_DIR) / "scenes" / "invalid";

struct Expectation {
  std::optional<int> line;
  std::optional<std::string> key;
  std::vector<std::string> messages;
};

std::string trim(std::string s) {
  const auto first = s.find_first_not_of(" \t\r");
  const auto last = s.find_last_not_of(" \t\r");
  return first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
}

Expectation read_expectation(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  Expectation e;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind('#', 0) != 0) continue;
    const auto field = [&](const std::string& name) -> std::optional<std::string> {
      const std::string tag = "# expect-" + name + ":";
      if (line.rfind(tag, 0) != 0) return std::nullopt;
      return trim(line.substr(tag.size()));
    };
    if (auto v = field("line")) e.line = std::stoi(*v);
    if (auto v = field("key")) e.key = *v;
    if (auto v = field("message")) e.messages.push_back(*v);
  }
  return e;
}

std::vector<std::string> invalid_scene_names() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kInvalidDir))
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

class InvalidScene : public testing::TestWithParam<std::string> {};

TEST_P(InvalidScene, IsRefusedAtTheDeclaredLineAndKey) {
  const fs::path file = kInvalidDir / (GetParam() + ".yaml");
  const Expectation expected = read_expectation(file);
  ASSERT_TRUE(expected.line.has_value()) << file << " has no '# expect-line:' header";
  ASSERT_TRUE(expected.key.has_value()) << file << " has no '# expect-key:' header";

  try {
    const rigidity::Scene scene = rigidity::load_scene_file(file.string());
    FAIL() << file << " was accepted";
  } catch (const rigidity::InputError& error) {
    const std::string what = error.what();
    EXPECT_EQ(error.where().line, *expected.line) << what;
    EXPECT_EQ(error.key(), *expected.key) << what;
    EXPECT_EQ(error.where().file, file.string()) << what;
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_EQ(what.rfind(error.where().str() + ": error: ", 0), 0u) << what;
    EXPECT_GE(error.where().column, 1) << what;
    for (const std::string& m : expected.messages) EXPECT_NE(error.message().find(m), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, InvalidScene, testing::ValuesIn(invalid_scene_names()),
                         [](const testing::TestParamInfo<std::string>& param) { return param.param; });

TEST(InvalidSceneCorpus, HasAtLeastFortyFiles) { EXPECT_GE(invalid_scene_names().size(), 40u); }

}  // namespace
