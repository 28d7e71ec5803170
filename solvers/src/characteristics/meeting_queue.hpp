#pragma once
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rigidity::characteristics {

/// The next meeting of each node with its right neighbour: a radix heap on the meeting
/// times. Time only moves forward (no meeting is scheduled before the last one taken,
/// save by round-off, which is taken at once), so the queue is monotone and a radix heap
/// suits it: entries sit in buckets by the highest bit in which their time differs from
/// the last time taken (times ≥ 0 order as their bit patterns), a new entry costs an
/// append, and taking the earliest scans the lowest non-empty bucket and deals its
/// entries into lower ones, each entry falling a few buckets at a time over its life.
/// Rescheduling a node appends a new entry and leaves the old one stale (it no longer
/// carries the node's live `seq`); stale entries are dropped when a scan meets them, and
/// all at once when they outnumber the live ones three to one, so memory stays bounded by
/// the nodes, not the run.
/// Ties in time go to the meeting scheduled first (`seq`), so runs are deterministic.
class MeetingQueue {
 public:
  struct Entry {
    double t;
    std::uint64_t seq;
    int node;
  };

  [[nodiscard]] bool empty() const { return live_ == 0; }
  [[nodiscard]] std::size_t size() const { return live_; }
  /// The earliest live meeting. \pre !empty()
  [[nodiscard]] const Entry& top() {
    if (!settled_) settle();
    return buckets_[0].front();
  }

  void set(int node, double t, std::uint64_t seq) {
    grow(node);
    std::uint64_t& live = live_seq_[static_cast<std::size_t>(node)];
    if (live == kAbsent) ++live_;
    live = seq;
    push(Entry{t, seq, node});
  }

  [[nodiscard]] bool contains(int node) const {
    return node < static_cast<int>(live_seq_.size()) && live_seq_[static_cast<std::size_t>(node)] != kAbsent;
  }

  /// Hands the entry of `from` (which has one) to `to` (which has none), at time t.
  void move(int from, int to, double t, std::uint64_t seq) {
    erase(from);
    set(to, t, seq);
  }

  void erase(int node) {
    if (!contains(node)) return;
    live_seq_[static_cast<std::size_t>(node)] = kAbsent;
    --live_;
    settled_ = false;
  }

 private:
  static constexpr std::uint64_t kAbsent = ~std::uint64_t{0};
  static constexpr int kBuckets = 65;

  static bool earlier(const Entry& a, const Entry& b) { return a.t < b.t || (a.t == b.t && a.seq < b.seq); }
  /// The order of bucket 0, a binary heap: its entries share the last time taken, save
  /// meetings a rare event (handled first) scheduled before it, and ties go by `seq`.
  static bool later(const Entry& a, const Entry& b) { return earlier(b, a); }
  [[nodiscard]] bool live(const Entry& e) const { return live_seq_[static_cast<std::size_t>(e.node)] == e.seq; }
  /// The bucket of a time: 0 at (or, by round-off, before) the last time taken, else one
  /// more than the highest bit in which it differs from it.
  [[nodiscard]] int bucket(double t) const {
    if (!(t > last_)) return 0;
    return 64 - std::countl_zero(std::bit_cast<std::uint64_t>(t) ^ std::bit_cast<std::uint64_t>(last_));
  }
  void grow(int node) {
    if (node < static_cast<int>(live_seq_.size())) return;
    live_seq_.resize(static_cast<std::size_t>(node) + 1, kAbsent);
  }
  void push(const Entry& e) {
    const int b = bucket(e.t);
    buckets_[b].push_back(e);
    if (b > 0) {
      filled_ |= std::uint64_t{1} << (b - 1);
    } else {
      std::push_heap(buckets_[0].begin(), buckets_[0].end(), later);
    }
    settled_ = false;
    if (++entries_ > 4 * live_ + 1024) drop_stale();
  }
  void drop_stale() {
    entries_ = 0;
    for (int b = 0; b < kBuckets; ++b) {
      std::vector<Entry>& bucket = buckets_[b];
      std::size_t kept = 0;
      for (const Entry& e : bucket)
        if (live(e)) bucket[kept++] = e;
      bucket.resize(kept);
      entries_ += kept;
      if (b > 0 && kept == 0) filled_ &= ~(std::uint64_t{1} << (b - 1));
    }
    std::make_heap(buckets_[0].begin(), buckets_[0].end(), later);
    settled_ = false;
  }
  /// Makes the top of bucket 0 its earliest live entry, refilling bucket 0 from the lowest
  /// non-empty bucket when it holds none.
  void settle() {
    for (;;) {
      std::vector<Entry>& first = buckets_[0];
      while (!first.empty() && !live(first.front())) {
        std::pop_heap(first.begin(), first.end(), later);
        first.pop_back();
        --entries_;
      }
      if (!first.empty()) {
        settled_ = true;
        return;
      }
      if (filled_ == 0) return;  // nothing live: the caller asked an empty queue
      const int b = std::countr_zero(filled_) + 1;
      filled_ &= ~(std::uint64_t{1} << (b - 1));
      std::vector<Entry>& from = buckets_[b];
      entries_ -= from.size();
      double earliest = 0.0;
      bool any = false;
      for (const Entry& e : from)
        if (live(e) && (!any || e.t < earliest)) {
          earliest = e.t;
          any = true;
        }
      if (any) {
        last_ = earliest;
        for (const Entry& e : from) {
          if (!live(e)) continue;
          const int to = bucket(e.t);
          buckets_[to].push_back(e);
          if (to > 0) {
            filled_ |= std::uint64_t{1} << (to - 1);
          } else {
            std::push_heap(buckets_[0].begin(), buckets_[0].end(), later);
          }
          ++entries_;
        }
      }
      from.clear();
    }
  }

  std::vector<Entry> buckets_[kBuckets];
  std::vector<std::uint64_t> live_seq_;  ///< seq of each node's live entry, or kAbsent
  std::size_t live_ = 0;                 ///< nodes with a live entry
  double last_ = 0.0;                    ///< the last time taken from the top
  std::uint64_t filled_ = 0;             ///< bit b − 1 set: bucket b > 0 holds entries
  std::size_t entries_ = 0;              ///< entries in all buckets, live and stale
  bool settled_ = false;
};

}  // namespace rigidity::characteristics
