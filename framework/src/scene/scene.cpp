#include "rigidity/scene.hpp"

namespace rigidity {

double BodyDecl::natural_length() const {
  double length = 0.0;
  for (const Segment& segment : segments) length += segment.length;
  return length;
}

}  // namespace rigidity
