#pragma once
/// The version of rigidity (the CMake project version).

namespace rigidity {

/// "MAJOR.MINOR.PATCH"
[[nodiscard]] const char* version();

}  // namespace rigidity
