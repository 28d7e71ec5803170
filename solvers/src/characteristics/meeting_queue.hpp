#pragma once
#include <cstdint>
#include <vector>

namespace rigidity::characteristics {

/// The next meeting of each node with its right neighbour: an indexed 4-ary min-heap.
/// A node has at most one entry, and the heap knows where it is, so rescheduling a
/// node moves its entry up or down in place and cancelling removes it: the heap holds
/// only live meetings (no stale entries to pop), and four children per level make it
/// half as deep as a binary heap, with the children of a slot side by side in memory.
/// Ties in time go to the meeting scheduled first (`seq`), so runs are deterministic.
class MeetingQueue {
 public:
  struct Entry {
    double t;
    std::uint64_t seq;
    int node;
  };

  [[nodiscard]] bool empty() const { return heap_.empty(); }
  [[nodiscard]] std::size_t size() const { return heap_.size(); }
  [[nodiscard]] const Entry& top() const { return heap_.front(); }

  void set(int node, double t, std::uint64_t seq) {
    grow(node);
    const Entry e{t, seq, node};
    const int at = position_[static_cast<std::size_t>(node)];
    if (at == kAbsent) {
      heap_.push_back(e);
      sift_up(heap_.size() - 1, e);
      return;
    }
    const std::size_t i = static_cast<std::size_t>(at);
    if (earlier(e, heap_[i])) {
      sift_up(i, e);
    } else {
      sift_down(i, e);
    }
  }

  [[nodiscard]] bool contains(int node) const {
    return node < static_cast<int>(position_.size()) && position_[static_cast<std::size_t>(node)] != kAbsent;
  }

  /// Hands the entry of `from` (which has one) to `to` (which has none), at time t.
  void move(int from, int to, double t, std::uint64_t seq) {
    grow(to);
    const std::size_t i = static_cast<std::size_t>(position_[static_cast<std::size_t>(from)]);
    position_[static_cast<std::size_t>(from)] = kAbsent;
    const Entry e{t, seq, to};
    if (i > 0 && earlier(e, heap_[(i - 1) / kArity])) {
      sift_up(i, e);
    } else {
      sift_down(i, e);
    }
  }

  void erase(int node) {
    if (node >= static_cast<int>(position_.size())) return;
    const int at = position_[static_cast<std::size_t>(node)];
    if (at == kAbsent) return;
    position_[static_cast<std::size_t>(node)] = kAbsent;
    const Entry last = heap_.back();
    heap_.pop_back();
    const std::size_t i = static_cast<std::size_t>(at);
    if (i == heap_.size()) return;  // it was the last entry
    if (i == 0) {
      pop_root(last);
      return;
    }
    if (earlier(last, heap_[i])) {
      sift_up(i, last);
    } else {
      sift_down(i, last);
    }
  }

 private:
  static constexpr int kAbsent = -1;
  static constexpr std::size_t kArity = 4;

  /// Without branches: which of four children is earliest is a coin toss the branch
  /// predictor cannot learn.
  static bool earlier(const Entry& a, const Entry& b) {
    return static_cast<bool>(static_cast<int>(a.t < b.t) |
                             (static_cast<int>(a.t == b.t) & static_cast<int>(a.seq < b.seq)));
  }
  void grow(int node) {
    if (node < static_cast<int>(position_.size())) return;
    position_.resize(static_cast<std::size_t>(node) + 1, kAbsent);
  }
  void place(std::size_t i, const Entry& e) {
    heap_[i] = e;
    position_[static_cast<std::size_t>(e.node)] = static_cast<int>(i);
  }
  /// Puts e at slot i or above it, moving later parents down.
  void sift_up(std::size_t i, const Entry& e) {
    while (i > 0) {
      const std::size_t parent = (i - 1) / kArity;
      if (!earlier(e, heap_[parent])) break;
      place(i, heap_[parent]);
      i = parent;
    }
    place(i, e);
  }
  /// The earliest child of slot i, or the heap's size if it has none.
  [[nodiscard]] std::size_t earliest_child(std::size_t i) const {
    const std::size_t n = heap_.size();
    const std::size_t first = kArity * i + 1;
    if (first >= n) return n;
    std::size_t best = first;
    const std::size_t end = first + kArity < n ? first + kArity : n;
    for (std::size_t c = first + 1; c < end; ++c) best = earlier(heap_[c], heap_[best]) ? c : best;
    return best;
  }
  /// Puts e at slot i or below it, moving earlier children up.
  void sift_down(std::size_t i, const Entry& e) {
    for (;;) {
      const std::size_t best = earliest_child(i);
      if (best == heap_.size() || !earlier(heap_[best], e)) break;
      place(i, heap_[best]);
      i = best;
    }
    place(i, e);
  }

  /// Removing the earliest meeting (what every crossing does): the entry that refills the
  /// root is one of the latest, so instead of comparing it on the way down, the hole walks
  /// down to a leaf along the earliest children and the entry rises from there (Floyd),
  /// usually not at all.
  void pop_root(const Entry& last) {
    std::size_t i = 0;
    for (;;) {
      const std::size_t best = earliest_child(i);
      if (best == heap_.size()) break;
      place(i, heap_[best]);
      i = best;
    }
    sift_up(i, last);
  }

  std::vector<Entry> heap_;
  std::vector<int> position_;  ///< slot of each node's entry, or kAbsent
};

}  // namespace rigidity::characteristics
