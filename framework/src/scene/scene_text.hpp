#pragma once
// Scalars of scene files: strict number and boolean literals, and their text in
// messages and in resolved_scene.yaml. Internal to the scene loader.

#include <string>
#include <string_view>
#include <vector>

namespace rigidity::detail {

/// The shortest text that reads back as exactly v ("0.6", "1e-12", "299792458").
[[nodiscard]] std::string format_number(double v);

enum class NumberSyntax { finite, non_finite, invalid };

struct NumberLiteral {
  NumberSyntax syntax = NumberSyntax::invalid;
  double value = 0.0;
};

/// Reads a decimal number, YAML 1.2 core syntax ([-+]? digits [. digits] [e[-+]digits]).
/// `.nan`, `.inf`, `inf`, `1e999` are non_finite; anything else (hex, "1_000", "fast") is invalid.
[[nodiscard]] NumberLiteral parse_number(std::string_view text);

/// YAML 1.2 core booleans: 1 for true|True|TRUE, 0 for false|False|FALSE, -1 for anything else.
[[nodiscard]] int parse_boolean(std::string_view text);

/// True if a plain scalar with this text would not read back as this string
/// (null, a boolean or number look-alike, leading/trailing space, empty).
[[nodiscard]] bool needs_quotes(std::string_view text);

/// 'text' for a message, shortened if long.
[[nodiscard]] std::string quoted(std::string_view text);

/// "a, b, c"
[[nodiscard]] std::string join(const std::vector<std::string>& words, std::string_view separator = ", ");

}  // namespace rigidity::detail
