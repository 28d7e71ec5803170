#pragma once
// Shipped scene files as text, and edits of them, for the solver tests.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace rigidity::test {

/// The text of configs/`path` (e.g. "paper_wall_impact.yaml", "materials/rigid.yaml").
inline std::string config_text(const std::string& path) {
  std::ifstream in(std::string(RIGIDITY_SOURCE_DIR) + "/configs/" + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// `text` with `from` (which must occur) replaced by `to`.
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace rigidity::test
