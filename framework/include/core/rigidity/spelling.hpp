#pragma once
/// Suggestions for misspelt names (keys, materials, quantities).

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rigidity {

/// Levenshtein distance between a and b.
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `name`, or "" if none is close enough to be a misspelling
/// (more than a third of the name, and more than two characters, would have to change).
[[nodiscard]] std::string closest_match(std::string_view name, const std::vector<std::string>& candidates);

}  // namespace rigidity
