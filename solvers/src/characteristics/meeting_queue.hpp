#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace rigidity::characteristics {

/// The next meeting of each node with its right neighbour: a binary min-heap invalidated
/// lazily, as event-driven codes do. Each node has a stamp; scheduling or cancelling its
/// meeting bumps the stamp, and an entry whose stamp no longer matches is dropped when it
/// reaches the top. Nothing is erased from the middle of the heap; when stale entries
/// outnumber the live ones the heap is rebuilt from the live ones, so its size stays within
/// a few times the number of live fronts.
class MeetingQueue {
 public:
  struct Entry {
    double t;
    std::uint64_t seq;
    int node;
    std::uint32_t stamp;
  };

  /// Drops stale entries from the top; call before empty() and top().
  void prune() {
    while (!heap_.empty() && !current(heap_.front())) pop_heap();
  }
  [[nodiscard]] bool empty() const { return heap_.empty(); }
  [[nodiscard]] const Entry& top() const { return heap_.front(); }

  void set(int node, double t, std::uint64_t seq) {
    grow(node);
    if (!scheduled_[node]) ++live_;
    scheduled_[node] = true;
    heap_.push_back(Entry{t, seq, node, ++stamp_[node]});
    std::push_heap(heap_.begin(), heap_.end(), later);
    if (heap_.size() > 4 * static_cast<std::size_t>(live_) + 1024) compact();
  }

  void erase(int node) {
    if (node >= static_cast<int>(stamp_.size()) || !scheduled_[node]) return;
    scheduled_[node] = false;
    --live_;
    ++stamp_[node];
  }

 private:
  static bool later(const Entry& a, const Entry& b) { return a.t != b.t ? a.t > b.t : a.seq > b.seq; }
  [[nodiscard]] bool current(const Entry& e) const { return scheduled_[e.node] && stamp_[e.node] == e.stamp; }
  void grow(int node) {
    if (node < static_cast<int>(stamp_.size())) return;
    stamp_.resize(static_cast<std::size_t>(node) + 1, 0);
    scheduled_.resize(static_cast<std::size_t>(node) + 1, false);
  }
  void pop_heap() {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    heap_.pop_back();
  }
  void compact() {
    heap_.erase(std::remove_if(heap_.begin(), heap_.end(), [this](const Entry& e) { return !current(e); }),
                heap_.end());
    std::make_heap(heap_.begin(), heap_.end(), later);
  }

  std::vector<Entry> heap_;
  std::vector<std::uint32_t> stamp_;
  std::vector<bool> scheduled_;
  long live_ = 0;
};

}  // namespace rigidity::characteristics
