// The version string, set by CMake for every part of the library (it sits with the
// output writers, the first part that needed it outside the CLI).
#include "rigidity/version.hpp"

namespace rigidity {

const char* version() { return RIGIDITY_VERSION; }

}  // namespace rigidity
