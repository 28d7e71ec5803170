// Light pieces: bodies whose sound travels at light speed keep their fronts in two queues
// and visit no crossing (see LightPiece in tracker.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <vector>

#include "rigidity/errors.hpp"
#include "tracker.hpp"

namespace rigidity::characteristics {

/// Fronts a lone body needs at the start to be worth a light piece.
constexpr int kLightMinFronts = 8;
/// How many fronts of the other family a merge of two light fronts may reach across.
constexpr std::size_t kLightMergeReach = 16;

namespace {

/// Whether lab position x is at or past `limit`, going away from the end fronts of `family` leave.
bool beyond(int family, double x, double limit) { return family > 0 ? x >= limit : x <= limit; }

}  // namespace

State Tracker::light_state(const Material& m, double j_plus, double j_minus) const {
  const Solved<Stretch> s = memo_->stretch_at_psi(m, 0.5 * (j_plus - j_minus));
  if (!s.ok())
    throw NumericalError("a state between the fronts of a light or lattice piece could not be found (Ψ = " +
                         number(0.5 * (j_plus - j_minus)) + ")");
  return State{0.5 * (j_plus + j_minus), s.value};
}

/// Once the discontinuities of t = 0 are resolved, every piece of one material whose sound
/// travels at light speed and which carries any tension takes its fronts off the node list.
void Tracker::make_light(double t) {
  light_made_ = true;
  light_.resize(pieces_.size());
  for (std::size_t piece = 0; piece < pieces_.size(); ++piece) {
    const Piece& pc = pieces_[piece];
    if (pc.left_end == kNone) continue;
    const Material* m = nodes_[pc.left_end].right.material;
    if (m == nullptr || m->cavitation_pressure() > -kInf) continue;
    // Any other linearly degenerate material makes a lattice piece, unless fronts.csv would
    // need the vertices of its fronts' paths, or other bodies could send it the errors of
    // their merges: carried exactly, those grow past what the bound's stability factor
    // allows (on the three bars of ErrorBound.HoldsAgainstAnExactRunOfLinearlyDegenerateBodies,
    // error 3.2 times the booked sum, where the factor is 2; on the node list the Hooke bar's
    // own merges add what covers it).
    const bool lattice =
        !m->sound_at_light_speed() && m->linearly_degenerate() && !want_fronts_ && scene_.bodies.size() == 1;
    if (!m->sound_at_light_speed() && !lattice) continue;
    bool one_material = true;
    int fronts_in = 0;
    for (int n = nodes_[pc.left_end].next; n != pc.right_end; n = nodes_[n].next, ++fronts_in)
      one_material = one_material && nodes_[n].kind == NodeKind::front && nodes_[n].right.material == m;
    if (!one_material) continue;
    // A lone body with few fronts keeps them: they never multiply (walls and free ends
    // reflect a front as one front), and the queues would only cost it time.
    if (scene_.bodies.size() == 1 && fronts_in < kLightMinFronts) continue;
    if (lattice && static_cast<double>(fronts_in) > policy_.front_cap()) continue;  // it would dissolve at once
    LightPiece& lp = light_[piece];
    if (lattice && !make_lattice(static_cast<int>(piece), t)) continue;
    light_bodies_ += 1.0;
    // C+ fronts nearest the right end first: the list read from the right.
    long minus_right = 0;  // C− fronts right of the one read: the C+ fronts there will meet them
    for (int n = nodes_[pc.right_end].prev; !lattice && n != pc.left_end; n = nodes_[n].prev) {
      const Node& f = nodes_[n];
      const State& left = nodes_[f.prev].right.state;
      const State& right = f.right.state;
      const double x = f.x_at(t);
      if (f.family > 0) {
        lp.plus.push_back(
            LightFront{x - t, invariant(*m, right, +1), invariant(*m, left, +1), t, x, 0.0, 0.0, minus_right});
        enter_light(lp.plus, f, t, false);
      } else {
        lp.minus.push_front(LightFront{x + t, invariant(*m, left, -1), invariant(*m, right, -1), t, x});
        lp.minus.front().carried = f.carried;
        lp.minus.front().smooth = f.smooth;
        ++minus_right;
      }
    }
    const Region next_to_right = nodes_[nodes_[pc.right_end].prev].right;
    long fronts = 0;
    for (int n = nodes_[pc.left_end].next; n != pc.right_end;) {
      const int next = nodes_[n].next;
      nodes_[n].carried = 0.0;  // its front in the queues carries it
      kill_node(n, t);          // records its segment up to t
      ++fronts;
      n = next;
    }
    live_fronts_ += fronts;
    light_fronts_ += fronts;
    const int store = new_node(NodeKind::light_store, static_cast<int>(piece));
    Node& st = nodes_[store];
    st.front_kind = FrontKind::interface;
    st.X0 = 0.5 * (nodes_[pc.left_end].X0 + nodes_[pc.right_end].X0);
    st.t0 = t;
    st.right = next_to_right;
    link(pc.left_end, store);
    link(store, pc.right_end);
    lp.store = store;
    schedule_meet(pc.left_end);
    schedule_arrivals(static_cast<int>(piece));
  }
}

/// The next front to reach each end of a light piece: the oldest of each queue, on its lab
/// line, against the end's line.
void Tracker::schedule_arrivals(int piece) {
  LightPiece& lp = light_[piece];
  ++lp.version;
  // Not before the ends last moved, nor before now (round-off in a line's intercept).
  const double t_min =
      std::max({nodes_[pieces_[piece].left_end].t0, nodes_[pieces_[piece].right_end].t0, last_interaction_t_, 0.0});
  if (!lp.plus.empty()) {
    const Node& end = nodes_[pieces_[piece].right_end];
    // intercept + t = x0 + v (t − t0)
    const double t = lp.lattice ? lattice_arrival(piece, +1)
                                : (end.x0 - end.dxdt * end.t0 - lp.plus.front().intercept) / (1.0 - end.dxdt);
    const double at = std::max(t, t_min);
    if (at <= scene_.t_end) push(at, EventType::arrival, piece, +1, lp.version, 0);
  }
  if (!lp.minus.empty()) {
    const Node& end = nodes_[pieces_[piece].left_end];
    // intercept − t = x0 + v (t − t0)
    const double t = lp.lattice ? lattice_arrival(piece, -1)
                                : (lp.minus.front().intercept - end.x0 + end.dxdt * end.t0) / (1.0 + end.dxdt);
    const double at = std::max(t, t_min);
    if (at <= scene_.t_end) push(at, EventType::arrival, piece, -1, lp.version, 0);
  }
}

/// The oldest front of one family reaches its end: it goes back on the node list, next to
/// the end, and the end's Riemann problem is solved as for any piece.
void Tracker::arrive(int piece, int family, double t) {
  LightPiece& lp = light_[piece];
  const Piece& pc = pieces_[piece];
  const Material& m = *nodes_[lp.store].right.material;
  const int end = family > 0 ? pc.right_end : pc.left_end;
  const LightFront f = family > 0 ? lp.plus.front() : lp.minus.front();
  (family > 0 ? lp.plus : lp.minus).pop_front();
  --light_fronts_;  // a front on the node list again
  if (family > 0) result_.stats.crossings_unvisited += f.meet_base + lp.minus_emitted;
  const int id = new_node(NodeKind::front, piece);
  Node& n = nodes_[id];
  n.family = family;
  n.front_kind = FrontKind::contact;
  n.X0 = nodes_[end].X_at(t);
  if (lp.lattice) {
    // Its vertex with the end: the characteristic of its family the end has last met.
    (family > 0 ? lp.ref_plus : lp.ref_minus) = Characteristic{f.f, f.p};
    const State& ahead = family > 0 ? nodes_[lp.store].right.state : nodes_[pc.left_end].right.state;
    const FrontSpeeds speeds = memo_->speeds(m, ahead, family);
    n.t0 = t;
    n.x0 = nodes_[end].x_at(t);
    n.dxdt = speeds.lab;
    n.dXdt = speeds.lagrangian;
  } else {
    n.t0 = f.t0;  // its lab line from where it started: one segment in fronts.csv
    n.x0 = f.x0;
    n.dxdt = family;
  }
  n.born = f.t0;
  n.strength = std::abs(f.j_behind - f.j_ahead);
  n.carried = f.carried;
  n.smooth = f.smooth;
  if (family > 0) {
    // ahead of it: the state next to the right end; behind it: J+ it brings, J− there.
    const Region ahead = nodes_[lp.store].right;
    n.right = ahead;
    nodes_[lp.store].right = Region{&m, light_state(m, f.j_behind, invariant(m, ahead.state, -1))};
    link(lp.store, id);
    link(id, pc.right_end);
    resolve(id, pc.right_end, t);
  } else {
    const State& ahead = nodes_[pc.left_end].right.state;
    n.right = Region{&m, light_state(m, invariant(m, ahead, +1), f.j_behind)};
    link(pc.left_end, id);
    link(id, lp.store);
    resolve(pc.left_end, id, t);
  }
}

/// What an end's Riemann problem emitted into a light piece (fronts on its node list, next to
/// the end) goes into the queues; the store and the left end keep the states next to the ends.
void Tracker::absorb_light(int piece, double t) {
  LightPiece& lp = light_[piece];
  const Piece& pc = pieces_[piece];
  const Material& m = *nodes_[lp.store].right.material;
  // C+ fronts emitted at the left end: between it and the store, nearest the end last.
  std::vector<int> plus, minus;
  for (int n = nodes_[pc.left_end].next; n != lp.store; n = nodes_[n].next) plus.push_back(n);
  for (int n = nodes_[lp.store].next; n != pc.right_end; n = nodes_[n].next) minus.push_back(n);
  if (plus.empty() && minus.empty()) {
    schedule_arrivals(piece);
    return;
  }
  for (const int id : plus)
    if (nodes_[id].family < 0) throw NumericalError("a light piece's left end emitted a C− front");
  for (const int id : minus)
    if (nodes_[id].family > 0) throw NumericalError("a light piece's right end emitted a C+ front");
  if (lp.lattice) {
    // The C+ fronts from the one farthest from the left end, the C− from the one farthest from the right end.
    for (auto id = plus.rbegin(); id != plus.rend(); ++id) lattice_enter(piece, +1, *id, t);
    for (const int id : minus) lattice_enter(piece, -1, id, t);
  } else {
    for (const int id : plus) {
      const Node& f = nodes_[id];
      const double x = f.x_at(t);
      lp.plus.push_back(LightFront{x - t, invariant(m, f.right.state, +1), invariant(m, nodes_[f.prev].right.state, +1),
                                   t, x, 0.0, 0.0, static_cast<long>(lp.minus.size()) - lp.minus_emitted});
      enter_light(lp.plus, f, t, false);
    }
    for (const int id : minus) {
      const Node& f = nodes_[id];
      const double x = f.x_at(t);
      lp.minus.push_back(
          LightFront{x + t, invariant(m, nodes_[f.prev].right.state, -1), invariant(m, f.right.state, -1), t, x});
      enter_light(lp.minus, f, t, false);
      ++lp.minus_emitted;
    }
  }
  // The store holds the state next to the right end only once the C− fronts have read the
  // state ahead of the first of them from it.
  if (!minus.empty()) nodes_[lp.store].right = nodes_[minus.back()].right;
  for (const std::vector<int>* taken : {&plus, &minus}) {
    for (const int id : *taken) {
      nodes_[id].carried = 0.0;  // its front in the queues carries it
      kill_node(id, t);
    }
  }
  link(pc.left_end, lp.store);
  link(lp.store, pc.right_end);
  live_fronts_ += static_cast<long>(plus.size() + minus.size());
  light_fronts_ += static_cast<long>(plus.size() + minus.size());
  if (lp.lattice) {
    // A lattice piece has no merges: past its cap, or once its invariants could meet in a
    // state the material cannot take, its fronts go back on the node list.
    if (static_cast<double>(lp.plus.size() + lp.minus.size()) > policy_.front_cap() || !lattice_safe(lp, m)) {
      dissolve_lattice(piece, t);
      return;
    }
  } else {
    if (!plus.empty()) merge_light(piece, +1, t);
    if (!minus.empty()) merge_light(piece, -1, t);
  }
  schedule_arrivals(piece);
}

/// The newest front of one family, just emitted at its end, and the one emitted before it
/// (its neighbour in the queue) become one front when that costs no more than a merge may.
/// The merged front's place keeps the natural length of the piece, so that every end and
/// every other front keeps its lab path: regions between the new front and that place take
/// the invariant behind the new front, those beyond it the one ahead of the old front. For
/// two steps of one sign the place lies between them; for a bump (steps of opposite signs)
/// beyond the old front, as far as the next front of the family. Fronts of the other family
/// on the way keep their jumps.
bool Tracker::merge_light(int piece, int family, double t) {
  LightPiece& lp = light_[piece];
  std::deque<LightFront>& queue = family > 0 ? lp.plus : lp.minus;
  if (queue.size() < 2) return false;
  const LightFront& older = queue[queue.size() - 2];
  const LightFront& newer = queue.back();
  LightMerge g;
  g.family = family;
  g.j_between = older.j_behind;   // = newer.j_ahead
  g.j_near_old = older.j_ahead;   // ahead of the older front
  g.j_near_new = newer.j_behind;  // behind the newer one
  g.x_old = older.x_at(t, family);
  g.x_new = newer.x_at(t, family);
  // Most merges are refused here, before any state is built: the weaker front times half
  // the lab distance between the two (a merge costs about the weaker front times the natural
  // length between them, γ/s times the lab length) already costs more than a merge may.
  const double weaker = std::min(std::abs(g.j_between - g.j_near_old), std::abs(g.j_near_new - g.j_between));
  if (weaker * std::abs(g.x_old - g.x_new) * 0.5 > policy_.light_merge_limit()) return false;
  // How far the merged front may go: the next front of the family ahead, or the far end.
  g.x_limit = queue.size() >= 3 ? queue[queue.size() - 3].x_at(t, family)
                                : nodes_[family > 0 ? pieces_[piece].right_end : pieces_[piece].left_end].x_at(t);
  light_merge_parts(piece, t, g);
  if (!light_merge_place(piece, g)) return false;
  const double margin = 64.0 * kEps * (1.0 + std::abs(g.place));
  if (!(beyond(family, g.place, g.x_new + family * margin) && beyond(family, g.x_stop - family * margin, g.place)))
    return false;
  const double cost = light_merge_cost(g);
  if (cost > policy_.light_merge_limit()) return false;
  apply_merge_light(piece, g, cost, t);
  return true;
}

void Tracker::light_merge_parts(int piece, double t, LightMerge& g) const {
  const LightPiece& lp = light_[piece];
  const int family = g.family;
  const Material& m = *nodes_[lp.store].right.material;
  const std::deque<LightFront>& other = family > 0 ? lp.minus : lp.plus;
  const State& next_to_end = family > 0 ? nodes_[pieces_[piece].left_end].right.state : nodes_[lp.store].right.state;
  std::vector<LightMerge::Part>& parts = g.parts;
  double j_other = invariant(m, next_to_end, -family);
  double cursor = g.x_new;
  for (const LightFront& o : other) {  // the other family's fronts nearest the new front's end first
    const double xo = o.x_at(t, -family);
    if (!beyond(family, xo, cursor) || xo == cursor) continue;
    if (beyond(family, xo, g.x_limit)) break;
    if (parts.size() >= kLightMergeReach) break;
    // Up to xo, split at the older front.
    if (!beyond(family, cursor, g.x_old) && beyond(family, xo, g.x_old)) {
      parts.push_back(LightMerge::Part{cursor, g.x_old, j_other, g.j_between});
      cursor = g.x_old;
    }
    parts.push_back(
        LightMerge::Part{cursor, xo, j_other, beyond(family, cursor, g.x_old) ? g.j_near_old : g.j_between});
    j_other = o.j_behind;  // past it, away from this end: the side it comes from
    cursor = xo;
  }
  g.x_stop = parts.size() >= kLightMergeReach ? cursor : g.x_limit;
  if (!beyond(family, cursor, g.x_old)) {
    parts.push_back(LightMerge::Part{cursor, g.x_old, j_other, g.j_between});
    cursor = g.x_old;
  }
  if (beyond(family, g.x_stop, cursor) && g.x_stop != cursor)
    parts.push_back(LightMerge::Part{cursor, g.x_stop, j_other, g.j_near_old});
}

bool Tracker::light_merge_place(int piece, LightMerge& g) const {
  const Material& m = *nodes_[light_[piece].store].right.material;
  const int family = g.family;
  const std::vector<LightMerge::Part>& parts = g.parts;
  const auto label_per_lab = [&](double j_self, double j_o) {
    const State st = family > 0 ? light_state(m, j_self, j_o) : light_state(m, j_o, j_self);
    return 1.0 / label_density(st);
  };
  // Natural length now and as the merged front sweeps away from the new one: parts it has
  // passed take j_near_new, the others j_near_old; F = new length − old length, linear on
  // each part.
  const std::size_t n = parts.size();
  g.density_old.resize(n);
  g.density_new.resize(n);
  g.density_near_old.resize(n);
  double change = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double length = std::abs(parts[i].to - parts[i].from);
    g.density_old[i] = label_per_lab(parts[i].j_old, parts[i].j_other);
    g.density_new[i] = label_per_lab(g.j_near_new, parts[i].j_other);
    g.density_near_old[i] =
        parts[i].j_old == g.j_near_old ? g.density_old[i] : label_per_lab(g.j_near_old, parts[i].j_other);
    change += (g.density_near_old[i] - g.density_old[i]) * length;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double length = std::abs(parts[i].to - parts[i].from);
    const double rate = g.density_new[i] - g.density_near_old[i];
    const double next = change + rate * length;
    if ((change <= 0.0 && next >= 0.0) || (change >= 0.0 && next <= 0.0)) {
      g.swept_in_split = rate == 0.0 ? 0.0 : std::clamp(-change / rate, 0.0, length);
      g.place = parts[i].from + family * g.swept_in_split;
      g.split = i;
      break;
    }
    change = next;
  }
  return std::isfinite(g.place);
}

double Tracker::light_merge_cost(const LightMerge& g) const {
  // What it costs: |δJ| of this family times the natural length it changes over.
  double cost = 0.0;
  for (std::size_t i = 0; i < g.parts.size(); ++i) {
    const LightMerge::Part& part = g.parts[i];
    const double length = std::abs(part.to - part.from);
    const double swept = i < g.split ? length : i == g.split ? g.swept_in_split : 0.0;
    cost += g.density_old[i] *
            (std::abs(g.j_near_new - part.j_old) * swept + std::abs(g.j_near_old - part.j_old) * (length - swept));
  }
  return cost;
}

void Tracker::apply_merge_light(int piece, const LightMerge& g, double cost, double t) {
  const int family = g.family;
  const double place = g.place;
  std::deque<LightFront>& queue = family > 0 ? light_[piece].plus : light_[piece].minus;
  LightFront& older = queue[queue.size() - 2];
  const LightFront& newer = queue.back();
  ++merged_;
  older.carried += newer.carried + ledger_.book_merge(cost);
  older.smooth = older.smooth && newer.smooth;
  if (want_fronts_ && t > older.t0) {
    recorder_.front(FrontSegment{older.t0, older.x0, t, g.x_old, SegmentKind::contact, family});
  }
  older.j_behind = g.j_near_new;
  older.intercept = place - family * t;
  older.t0 = t;
  older.x0 = place;
  queue.pop_back();
  --live_fronts_;
  --light_fronts_;
}

void Tracker::record_light_segments(int piece, double t) {
  if (!want_fronts_) return;
  for (int family : {+1, -1}) {
    for (const LightFront& f : family > 0 ? light_[piece].plus : light_[piece].minus) {
      if (t > f.t0) recorder_.front(FrontSegment{f.t0, f.x0, t, f.x_at(t, family), SegmentKind::contact, family});
    }
  }
}

void Tracker::enter_light(std::deque<LightFront>& queue, const Node& f, double t, bool lattice) {
  LightFront& entered = queue.back();
  entered.carried = f.carried;
  entered.smooth = f.smooth;
  const std::size_t n = queue.size();
  if (!lattice || !f.smooth || n < 2 || !queue[n - 2].smooth) return;
  const double speed = std::abs(speeds_of(f.right, f.family).lagrangian);
  entered.carried += ledger_.book_fan(0.25 * f.strength * speed * (t - queue[n - 2].t0));  // the staircase's
}

double Tracker::light_alive_error(int piece) const {
  const LightPiece& lp = light_[piece];
  if (lp.lattice) return 0.0;
  double error = 0.0;
  for (const int family : {+1, -1}) {
    const std::deque<LightFront>& q = family > 0 ? lp.plus : lp.minus;
    // Label widths: the fronts run at light speed, so their lab distances stay as they were.
    const double speed = std::abs(speeds_of(nodes_[lp.store].right, family).lagrangian);
    const auto jump = [&](std::size_t k) { return q[k].j_ahead - q[k].j_behind; };
    const auto width = [&](std::size_t a, std::size_t b) { return speed * std::abs(q[a].intercept - q[b].intercept); };
    const auto train = [&](std::size_t a, std::size_t b) {
      return q[a].smooth && q[b].smooth && jump(a) * jump(b) > 0.0 && width(a, b) > 0.0;
    };
    const auto slope = [&](std::size_t a, std::size_t b) { return 0.5 * std::abs(jump(a) + jump(b)) / width(a, b); };
    // A line is drawn over a strip of a train only with another strip of it beside (see
    // line_through): two steps alone are sampled as their staircase.
    const auto drawn = [&](std::size_t a, std::size_t b) {
      return train(a, b) && ((a > 0 && train(a - 1, a)) || (b + 1 < q.size() && train(b, b + 1)));
    };
    for (std::size_t k = 0; k < q.size(); ++k) {
      if (!q[k].smooth) continue;
      const bool before = k > 0 && drawn(k - 1, k), after = k + 1 < q.size() && drawn(k, k + 1);
      if (before && after) {
        const double mean = 0.5 * (width(k - 1, k) + width(k, k + 1));
        error += std::abs(slope(k, k + 1) - slope(k - 1, k)) * mean * mean / 12.0;
      } else if (before || after) {
        const std::size_t a = before ? k - 1 : k, b = before ? k : k + 1;
        error += slope(a, b) * width(a, b) * width(a, b) / 12.0;
        // The strip beyond, to a step of the other sign no more than kPlateauRatio of the
        // wave's strips away, holds an extremum (see Tracker::reconstruction_error): half of
        // what it misses.
        const std::size_t c = before ? k + 1 : k - 1, d = before ? k + 2 : k - 2;
        if (c < q.size() && q[c].smooth && jump(c) * jump(k) < 0.0 && width(c, k) <= kPlateauRatio * width(a, b)) {
          const double other = d < q.size() && train(std::min(c, d), std::max(c, d)) ? slope(c, d) : 0.0;
          error += 0.5 * extremum_miss(width(c, k), jump(k), slope(a, b), jump(c), other);
        }
      } else {
        double room = piece_length(piece);
        if (k > 0) room = std::min(room, width(k - 1, k));
        if (k + 1 < q.size()) room = std::min(room, width(k, k + 1));
        error += 0.25 * std::abs(jump(k)) * room;
      }
    }
  }
  return error;
}

}  // namespace rigidity::characteristics
