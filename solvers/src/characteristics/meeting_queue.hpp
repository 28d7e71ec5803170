#pragma once
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <vector>

namespace rigidity::characteristics {

/// The next meeting of each node with its right neighbour: a radix heap on the meeting
/// times, in hexadecimal digits. Time only moves forward (no meeting is scheduled before
/// the last one taken, save those a rare event handled first schedules, and round-off),
/// so the queue is monotone and a radix heap suits it: times ≥ 0 order as their bit
/// patterns, and an entry sits in the bucket of the highest hexadecimal digit in which
/// its time differs from the last time taken, and of its value there. A new entry costs
/// an append; taking the earliest deals the lowest non-empty bucket out into lower ones
/// from its earliest entry, each entry falling at least one digit each time, a couple of
/// times over its life (with binary digits, about log₂ of the entries). Bucket 0 (the
/// last time taken and anything scheduled before it) is a queue while its entries arrive
/// in order (the ties of one instant, by seq) and a binary heap once one does not.
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

  MeetingQueue() { std::fill(std::begin(earliest_), std::end(earliest_), kNever); }

  [[nodiscard]] bool empty() const { return live_ == 0; }
  [[nodiscard]] std::size_t size() const { return live_; }
  /// The earliest live meeting. \pre !empty()
  [[nodiscard]] const Entry& top() {
    if (!settled_) settle();
    return buckets_[0][head_];
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
  static constexpr int kDigits = 16;                  ///< hexadecimal digits of a 64-bit time
  static constexpr int kBuckets = 1 + kDigits * 16;   ///< bucket 0, then (digit, value) in time order
  static constexpr int kWords = (kBuckets - 1) / 64;  ///< of the bitmap of non-empty buckets above 0
  static constexpr double kNever = std::numeric_limits<double>::infinity();

  static bool earlier(const Entry& a, const Entry& b) { return a.t < b.t || (a.t == b.t && a.seq < b.seq); }
  /// The order of bucket 0, a binary heap: its entries share the last time taken, save
  /// meetings scheduled before it, and ties go by `seq`.
  static bool later(const Entry& a, const Entry& b) { return earlier(b, a); }
  [[nodiscard]] bool live(const Entry& e) const { return live_seq_[static_cast<std::size_t>(e.node)] == e.seq; }
  /// The bucket of a time: 0 at (or before) the last time taken, else 1 + 16 d + v for the
  /// highest hexadecimal digit d in which it differs from it and its value v there.
  [[nodiscard]] int bucket(double t) const {
    if (!(t > last_)) return 0;
    const std::uint64_t key = std::bit_cast<std::uint64_t>(t);
    const int digit = (63 - std::countl_zero(key ^ std::bit_cast<std::uint64_t>(last_))) / 4;
    return 1 + 16 * digit + static_cast<int>((key >> (4 * digit)) & 15U);
  }
  void mark(int b) { filled_[(b - 1) / 64] |= std::uint64_t{1} << ((b - 1) % 64); }
  void unmark(int b) { filled_[(b - 1) / 64] &= ~(std::uint64_t{1} << ((b - 1) % 64)); }
  /// The lowest non-empty bucket above 0, or 0 if there is none.
  [[nodiscard]] int lowest_filled() const {
    for (int w = 0; w < kWords; ++w)
      if (filled_[w] != 0) return 1 + 64 * w + std::countr_zero(filled_[w]);
    return 0;
  }
  void grow(int node) {
    if (node < static_cast<int>(live_seq_.size())) return;
    live_seq_.resize(static_cast<std::size_t>(node) + 1, kAbsent);
  }
  void place(const Entry& e) {
    const int b = bucket(e.t);
    buckets_[b].push_back(e);
    if (b > 0) {
      mark(b);
      if (e.t < earliest_[b]) earliest_[b] = e.t;
    } else {
      add_first(buckets_[0]);
    }
  }
  /// Bucket 0 has just received an entry at its back. Entries that come in order (ties of one
  /// instant arrive by seq) are a queue read from head_; the first that does not makes it a
  /// binary heap for the rest of its life (until it empties).
  void add_first(std::vector<Entry>& first) {
    if (in_order_) {
      const std::size_t n = first.size();
      if (n - 1 == head_ || !earlier(first[n - 1], first[n - 2])) return;
      first.erase(first.begin(), first.begin() + static_cast<std::ptrdiff_t>(head_));
      head_ = 0;
      in_order_ = false;
      std::make_heap(first.begin(), first.end(), later);
      return;
    }
    std::push_heap(first.begin(), first.end(), later);
  }
  void push(const Entry& e) {
    place(e);
    settled_ = false;
    if (++entries_ > 4 * live_ + 1024) drop_stale();
  }
  void drop_stale() {
    entries_ = 0;
    for (int b = 0; b < kBuckets; ++b) {
      std::vector<Entry>& bucket = buckets_[b];
      std::size_t kept = 0;
      earliest_[b] = kNever;
      for (std::size_t i = b == 0 ? head_ : 0; i < bucket.size(); ++i) {
        const Entry e = bucket[i];
        if (live(e)) {
          bucket[kept++] = e;
          if (e.t < earliest_[b]) earliest_[b] = e.t;
        }
      }
      bucket.resize(kept);
      entries_ += kept;
      if (b > 0 && kept == 0) unmark(b);
    }
    head_ = 0;  // an ordered queue stays in order, a heap is rebuilt
    if (!in_order_) std::make_heap(buckets_[0].begin(), buckets_[0].end(), later);
    settled_ = false;
  }
  /// Makes the top of bucket 0 its earliest live entry, refilling bucket 0 from the lowest
  /// non-empty bucket when it holds none.
  void settle() {
    for (;;) {
      std::vector<Entry>& first = buckets_[0];
      if (in_order_) {
        while (head_ < first.size() && !live(first[head_])) {
          ++head_;
          --entries_;
        }
      } else {
        while (!first.empty() && !live(first.front())) {
          std::pop_heap(first.begin(), first.end(), later);
          first.pop_back();
          --entries_;
        }
      }
      if (head_ < first.size()) {
        settled_ = true;
        return;
      }
      first.clear();  // empty: refilled below as an ordered queue
      head_ = 0;
      in_order_ = true;
      const int b = lowest_filled();
      if (b == 0) return;  // nothing live: the caller asked an empty queue
      unmark(b);
      std::vector<Entry>& from = buckets_[b];
      entries_ -= from.size();
      // The earliest entry of the bucket, stale or live, is no later than any live entry
      // anywhere (every later bucket is later than all of this one): the new origin. The
      // bucket's entries share its digits from d up, so each falls to a lower digit.
      last_ = earliest_[b];
      earliest_[b] = kNever;
      for (const Entry& e : from) {
        if (!live(e)) continue;
        place(e);
        ++entries_;
      }
      from.clear();
    }
  }

  std::vector<Entry> buckets_[kBuckets];
  double earliest_[kBuckets];            ///< of bucket b > 0: its earliest entry (stale ones too), kNever if empty
  std::uint64_t filled_[kWords] = {};    ///< bit b − 1 set: bucket b > 0 holds entries
  std::vector<std::uint64_t> live_seq_;  ///< seq of each node's live entry, or kAbsent
  std::size_t live_ = 0;                 ///< nodes with a live entry
  std::size_t entries_ = 0;              ///< entries in all buckets, live and stale
  double last_ = 0.0;                    ///< the last time taken from the top
  std::size_t head_ = 0;                 ///< bucket 0 in order: its first entry not yet taken
  bool in_order_ = true;                 ///< bucket 0 is an ordered queue (else a binary heap, head_ = 0)
  bool settled_ = false;
};

}  // namespace rigidity::characteristics
