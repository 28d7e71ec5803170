// The tracker's invariants, checked after every interaction while check_tracker_invariants is on.
#include <atomic>
#include <cmath>
#include <deque>
#include <string>

#include "rigidity/errors.hpp"
#include "rigidity/solvers/characteristics.hpp"
#include "tracker.hpp"

namespace rigidity {
namespace {
std::atomic<bool> checking{false};
}  // namespace

void check_tracker_invariants(bool on) { checking.store(on, std::memory_order_relaxed); }

namespace characteristics {

bool validating() { return checking.load(std::memory_order_relaxed); }

void Tracker::validate(double t) const {
  const auto fail = [&](const std::string& what) {
    throw NumericalError("tracker invariant broken at t = " + number(t) + ": " + what);
  };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  long fronts = 0;
  for (std::size_t p = 0; p < pieces_.size(); ++p) {
    const Piece& piece = pieces_[p];
    if (piece.left_end == kNone) continue;  // rejoined into another piece
    const int index = static_cast<int>(p);
    if (nodes_[piece.left_end].kind != NodeKind::left_end || nodes_[piece.right_end].kind != NodeKind::right_end)
      fail("piece " + std::to_string(p) + " does not start and end with its ends");
    for (int n = piece.left_end;; n = nodes_[n].next) {
      const Node& node = nodes_[n];
      if (!node.alive || node.piece != index) fail("node " + std::to_string(n) + " is dead or in another piece");
      if (node.kind == NodeKind::front) {
        ++fronts;
        if (!non_negative(node.strength) || !non_negative(node.carried))
          fail("front " + std::to_string(n) + " has strength " + number(node.strength) + " and carries " +
               number(node.carried));
      } else if (node.smooth) {
        fail("node " + std::to_string(n) + " is smooth but no front");
      }
      if (n == piece.right_end) break;
      const int next = node.next;
      if (next == kNone || nodes_[next].prev != n)
        fail("nodes " + std::to_string(n) + " and " + std::to_string(next) + " are not linked both ways");
      // (An unsplit fan's neighbours stay outside its wedge: they are split before entering.)
      const double X = facing(n, true).X_at(t), X_next = facing(next, false).X_at(t);
      if (node.kind != NodeKind::light_store && nodes_[next].kind != NodeKind::light_store &&
          X_next < X - 1e-9 * (1.0 + std::abs(X)))
        fail("node " + std::to_string(next) + " at label " + number(X_next) + " is left of node " + std::to_string(n) +
             " at " + number(X));
    }
    if (!is_light(index)) {
      // Every meeting due before the end is scheduled: a node whose next meeting is missing
      // from the queue would pass through its neighbour.
      for (int n = piece.left_end; n != piece.right_end; n = nodes_[n].next)
        if (meeting_time(n) < kInf && !meetings_.contains(n))
          fail("node " + std::to_string(n) + " meets node " + std::to_string(nodes_[n].next) +
               " at t = " + number(meeting_time(n)) + " with no meeting scheduled");
      continue;
    }
    const LightPiece& lp = light_[p];
    for (const int family : {+1, -1}) {
      const std::deque<LightFront>& queue = family > 0 ? lp.plus : lp.minus;
      fronts += static_cast<long>(queue.size());
      for (std::size_t i = 0; i < queue.size(); ++i) {
        if (!non_negative(queue[i].carried)) fail("a light front carries " + number(queue[i].carried));
        // A light piece's C+ fronts stand right to left in their queue, its C− fronts left to right.
        if (lp.lattice || i == 0) continue;
        const double here = queue[i].x_at(t, family), before = queue[i - 1].x_at(t, family);
        if (family > 0 ? here > before + 1e-9 * (1.0 + std::abs(here)) : here < before - 1e-9 * (1.0 + std::abs(here)))
          fail("the fronts of a light piece are out of the order they run in");
      }
    }
  }
  if (fronts != live_fronts_)
    fail(std::to_string(fronts) + " fronts on the lists and queues, " + std::to_string(live_fronts_) + " counted live");
  if (!ledger_.sound()) fail("an error book of the ledger is negative or not finite");
  // What the waves carry is what the ledger handed them: no error is dropped or made twice
  // where a front ends, merges, splits or enters a light piece.
  double carried = 0.0;
  for (const Node& node : nodes_)
    if (node.alive && node.kind == NodeKind::front) carried += node.carried;
  for (const LightPiece& lp : light_)
    for (const std::deque<LightFront>* queue : {&lp.plus, &lp.minus})
      for (const LightFront& f : *queue) carried += f.carried;
  if (std::abs(carried - ledger_.carried()) > 1e-9 * ledger_.flow())
    fail("the waves carry " + number(carried) + " of error, the ledger says " + number(ledger_.carried()));
}

}  // namespace characteristics
}  // namespace rigidity
