// The front tracker's meeting queue against an ordered set: the same earliest meeting after
// every change, for the patterns a run makes (times advancing, many meetings at one instant,
// meetings far ahead, the queue growing and shrinking by orders of magnitude).
#include "meeting_queue.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <tuple>
#include <vector>

namespace {

using rigidity::characteristics::MeetingQueue;
using Key = std::tuple<double, std::uint64_t, int>;

/// Drives a MeetingQueue and an ordered set with the same operations and compares their
/// earliest meeting after each one.
class Twin {
 public:
  void set(int node, double t) {
    erase_reference(node);
    const std::uint64_t seq = seq_++;
    reference_.insert({t, seq, node});
    where_[node] = {t, seq};
    queue_.set(node, t, seq);
  }
  void erase(int node) {
    erase_reference(node);
    queue_.erase(node);
  }
  /// What a crossing does: `from`'s meeting goes, `to` (which has none) gets one at t.
  void move(int from, int to, double t) {
    ASSERT_TRUE(queue_.contains(from));
    ASSERT_FALSE(queue_.contains(to));
    erase_reference(from);
    const std::uint64_t seq = seq_++;
    reference_.insert({t, seq, to});
    where_[to] = {t, seq};
    queue_.move(from, to, t, seq);
  }
  [[nodiscard]] bool has(int node) const { return where_.count(node) != 0; }
  [[nodiscard]] int earliest_node() const { return std::get<2>(*reference_.begin()); }
  /// Pops the earliest meeting from both; false if the two disagree.
  bool pop_and_compare() {
    if (!same_top()) return false;
    if (reference_.empty()) return true;
    const int node = std::get<2>(*reference_.begin());
    erase(node);
    return true;
  }
  [[nodiscard]] bool same_top() {
    if (reference_.empty()) return queue_.empty();
    if (queue_.empty() || queue_.size() != reference_.size()) return false;
    const auto& [t, seq, node] = *reference_.begin();
    const MeetingQueue::Entry& e = queue_.top();
    return e.t == t && e.seq == seq && e.node == node;
  }
  [[nodiscard]] double earliest() const { return std::get<0>(*reference_.begin()); }
  [[nodiscard]] std::size_t size() const { return reference_.size(); }

 private:
  void erase_reference(int node) {
    const auto it = where_.find(node);
    if (it == where_.end()) return;
    reference_.erase({it->second.first, it->second.second, node});
    where_.erase(it);
  }
  MeetingQueue queue_;
  std::set<Key> reference_;
  std::map<int, std::pair<double, std::uint64_t>> where_;
  std::uint64_t seq_ = 0;
};

TEST(MeetingQueue, PopsInTimeOrderWithTiesToTheFirstScheduled) {
  Twin q;
  q.set(3, 2.0);
  q.set(1, 1.0);
  q.set(2, 1.0);  // a tie with node 1, scheduled later
  q.set(0, 5.0);
  for (int k = 0; k < 4; ++k) ASSERT_TRUE(q.pop_and_compare()) << "pop " << k;
  EXPECT_TRUE(q.same_top());
}

TEST(MeetingQueue, AgreesWithAnOrderedSetUnderTheChangesARunMakes) {
  std::mt19937_64 random(20261125);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const int nodes : {3, 40, 3000}) {
    Twin q;
    double now = 0.0;
    for (int step = 0; step < 40 * nodes + 2000; ++step) {
      const double r = unit(random);
      const int node = static_cast<int>(unit(random) * nodes);
      if (r < 0.45) {
        // A meeting ahead of now: mostly within a crossing time, sometimes at this very
        // instant (a crowd), sometimes far ahead.
        const double kind = unit(random);
        const double ahead = kind < 0.1 ? 0.0 : kind < 0.95 ? unit(random) : 1e6 * unit(random);
        q.set(node, now + ahead);
      } else if (r < 0.6) {
        q.erase(node);
      } else if (r < 0.75 && q.size() > 0 && !q.has(node)) {
        // The earliest meeting is a crossing: its entry goes to a node that meets nothing yet,
        // at a time ahead of it (or, rarely, the same instant).
        const double kind = unit(random);
        now = q.earliest();
        q.move(q.earliest_node(), node, now + (kind < 0.1 ? 0.0 : unit(random)));
      } else if (r < 0.8 && q.size() > 1 && !q.has(node)) {
        // Any meeting's entry moves, to an earlier or a later time.
        int from = (node + 1) % nodes;
        while (!q.has(from)) from = (from + 1) % nodes;
        q.move(from, node, now + unit(random));
      } else {
        if (q.size() > 0) now = q.earliest();
        ASSERT_TRUE(q.pop_and_compare()) << nodes << " nodes, step " << step;
      }
      ASSERT_TRUE(q.same_top()) << nodes << " nodes, step " << step;
    }
    while (q.size() > 0) ASSERT_TRUE(q.pop_and_compare());
  }
}

TEST(MeetingQueue, FollowsAQueueThatGrowsAndEmptiesByOrdersOfMagnitude) {
  Twin q;
  double now = 0.0;
  for (int round = 0; round < 3; ++round) {
    // Many meetings at few instants (a bar's segments all launching fronts at once), then
    // drained while each pop schedules a meeting further on for a few of them.
    for (int node = 0; node < 20000; ++node) q.set(node, now + 1e-3 * (node % 7));
    for (int k = 0; k < 30000 && q.size() > 0; ++k) {
      now = q.earliest();
      ASSERT_TRUE(q.pop_and_compare()) << "round " << round << ", pop " << k;
      if (k % 5 == 0) q.set(20000 + k % 100, now + 1e-9 * k);
    }
    while (q.size() > 0) ASSERT_TRUE(q.pop_and_compare());
  }
}

}  // namespace
