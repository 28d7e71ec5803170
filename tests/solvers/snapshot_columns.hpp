#pragma once
// A run's snapshot samples of one body as columns by label, for the tests that write the exact
// solution as a function of the samples' own lab positions.
#include <map>

#include "rigidity/run_result.hpp"

namespace rigidity::test {

/// The samples of v, s and x of body `body` (any time), each by label X.
struct SnapshotColumns {
  std::map<double, double> v, s, x;
};
inline SnapshotColumns snapshot_columns(const RunResult& r, int body = 0) {
  SnapshotColumns c;
  for (const SnapshotSample& sample : r.snapshots)
    if (sample.body == body)
      (sample.quantity == Quantity::v ? c.v : sample.quantity == Quantity::s ? c.s : c.x)[sample.X] = sample.value;
  return c;
}

}  // namespace rigidity::test
