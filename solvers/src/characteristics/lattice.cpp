// Lattice pieces: bodies of a linearly degenerate material whose sound is slower than light
// keep their fronts in two queues, each with the hodograph coordinates of its characteristic,
// and visit no crossing (see LightPiece in tracker.hpp).
#include <algorithm>
#include <cmath>
#include <vector>

#include "tracker.hpp"

namespace rigidity::characteristics {

namespace {

/// The coordinates of a front of one family at X at time t, from `prev`, a characteristic of
/// its own family with the strip between them crossed by the other family at speed
/// `adjacent`, and `met`, a characteristic of the other family whose vertex with it lies on
/// the line the front now moves on at speed `own`:
///   p − prev.p = adjacent (f − prev.f),   X = p + met.p + own (t − f − met.f).
Characteristic place(const Characteristic& prev, const Characteristic& met, double adjacent, double own, double X,
                     double t) {
  const double f = (X - met.p - prev.p + adjacent * prev.f - own * (t - met.f)) / (adjacent - own);
  return Characteristic{f, prev.p + adjacent * (f - prev.f)};
}

Characteristic of(const LightFront& f) { return Characteristic{f.f, f.p}; }

}  // namespace

void Tracker::note_invariants(LightPiece& lp, const Material& m, const State& s) const {
  const double j_plus = invariant(m, s, +1), j_minus = invariant(m, s, -1);
  lp.j_plus_min = std::min(lp.j_plus_min, j_plus);
  lp.j_plus_max = std::max(lp.j_plus_max, j_plus);
  lp.j_minus_min = std::min(lp.j_minus_min, j_minus);
  lp.j_minus_max = std::max(lp.j_minus_max, j_minus);
}

/// Every J+ the piece has held can meet every J− it has held: the states of those meetings,
/// Ψ = (J+ − J−)/2 from the most compressed to the most stretched, must be ones the
/// material takes (what a crossing on the node list asks of its star).
bool Tracker::lattice_safe(const LightPiece& lp, const Material& m) const {
  const double compressed = 0.5 * (lp.j_plus_max - lp.j_minus_min);
  const double stretched = 0.5 * (lp.j_plus_min - lp.j_minus_max);
  if (!(compressed < m.psi_max() && stretched > m.psi_min())) return false;
  for (const double psi : {compressed, stretched}) {
    const Solved<Stretch> s = memo_->stretch_at_psi(m, psi);
    if (!s.ok() || !representable(s.value)) return false;
  }
  return true;
}

/// Takes the fronts of `piece` (one linearly degenerate material, fronts only) into its
/// queues, with their coordinates: the lattice is anchored on a C+ and a C− characteristic
/// through the left end at time t, and each front, left to right, is placed from the last
/// characteristic of each family left of it. False (nothing changed) when the invariants
/// the piece holds could meet in a state the material cannot take.
bool Tracker::make_lattice(int piece, double t) {
  LightPiece& lp = light_[piece];
  const Piece& pc = pieces_[piece];
  const Node& left_end = nodes_[pc.left_end];
  const Material& m = *left_end.right.material;
  note_invariants(lp, m, left_end.right.state);
  long minus_total = 0;
  for (int n = left_end.next; n != pc.right_end; n = nodes_[n].next) {
    note_invariants(lp, m, nodes_[n].right.state);
    if (nodes_[n].family < 0) ++minus_total;
  }
  if (!lattice_safe(lp, m)) {
    lp = LightPiece{};
    return false;
  }
  lp.lattice = true;
  Characteristic last_plus{t, left_end.X_at(t)}, last_minus{0.0, 0.0};  // they meet at (t, X_left)
  long minus_seen = 0;
  for (int n = left_end.next; n != pc.right_end; n = nodes_[n].next) {
    const Node& f = nodes_[n];
    const Region& before = nodes_[f.prev].right;  // its strip and the adjacent one, both families' speeds
    const double X = f.X_at(t), x = f.x_at(t);
    const double plus_speed = speeds_of(before, +1).lagrangian, minus_speed = speeds_of(before, -1).lagrangian;
    if (f.family > 0) {
      last_plus = place(last_plus, last_minus, minus_speed, plus_speed, X, t);
      lp.plus.push_front(LightFront{X, invariant(m, f.right.state, +1), invariant(m, before.state, +1), t, x,
                                    last_plus.f, last_plus.p, minus_total - minus_seen, minus_speed});
      lp.plus.front().carried = f.carried;
      lp.plus.front().smooth = f.smooth;
    } else {
      last_minus = place(last_minus, last_plus, plus_speed, minus_speed, X, t);
      lp.minus.push_back(LightFront{X, invariant(m, before.state, -1), invariant(m, f.right.state, -1), t, x,
                                    last_minus.f, last_minus.p, 0, speeds_of(f.right, +1).lagrangian});
      enter_light(lp.minus, f, t, true);
      ++minus_seen;
    }
  }
  const Region& last = nodes_[nodes_[pc.right_end].prev].right;
  lp.ref_plus = place(last_plus, last_minus, speeds_of(last, -1).lagrangian, speeds_of(last, +1).lagrangian,
                      nodes_[pc.right_end].X_at(t), t);
  lp.ref_minus = Characteristic{0.0, 0.0};
  return true;
}

/// When the front nearest the end its family runs to gets there: after the last vertex of
/// the newest characteristic of the other family, on the line at its speed next to the end.
double Tracker::lattice_arrival(int piece, int family) const {
  const LightPiece& lp = light_[piece];
  const Piece& pc = pieces_[piece];
  if (family > 0) {
    const Characteristic f = of(lp.plus.front());
    const Characteristic met = lp.minus.empty() ? lp.ref_minus : of(lp.minus.back());
    const Node& end = nodes_[pc.right_end];
    const double speed = speeds_of(nodes_[lp.store].right, +1).lagrangian;
    return f.f + met.f + (end.X0 - f.p - met.p) / speed;
  }
  const Characteristic f = of(lp.minus.front());
  const Characteristic met = lp.plus.empty() ? lp.ref_plus : of(lp.plus.back());
  const Node& end = nodes_[pc.left_end];
  const double speed = speeds_of(end.right, -1).lagrangian;
  return met.f + f.f + (end.X0 - met.p - f.p) / speed;
}

/// A front an end has just emitted into a lattice piece (node `id`, next to that end) goes
/// into its queue: its own family's newest characteristic and the other family's last to
/// reach this end (or the piece's anchor) place it.
void Tracker::lattice_enter(int piece, int family, int id, double t) {
  LightPiece& lp = light_[piece];
  const Node& f = nodes_[id];
  const Region& left = nodes_[f.prev].right;
  const Region& right = f.right;
  const Material& m = *right.material;
  const double X = f.X_at(t), x = f.x_at(t);
  note_invariants(lp, m, left.state);
  note_invariants(lp, m, right.state);
  if (family > 0) {
    const Characteristic prev = lp.plus.empty() ? lp.ref_plus : of(lp.plus.back());
    const Characteristic c =
        place(prev, lp.ref_minus, speeds_of(right, -1).lagrangian, speeds_of(right, +1).lagrangian, X, t);
    lp.plus.push_back(LightFront{X, invariant(m, right.state, +1), invariant(m, left.state, +1), t, x, c.f, c.p,
                                 static_cast<long>(lp.minus.size()) - lp.minus_emitted,
                                 speeds_of(left, -1).lagrangian});
    enter_light(lp.plus, f, t, true);
  } else {
    const Characteristic prev = lp.minus.empty() ? lp.ref_minus : of(lp.minus.back());
    const Characteristic c =
        place(prev, lp.ref_plus, speeds_of(left, +1).lagrangian, speeds_of(left, -1).lagrangian, X, t);
    lp.minus.push_back(LightFront{X, invariant(m, left.state, -1), invariant(m, right.state, -1), t, x, c.f, c.p, 0,
                                  speeds_of(right, +1).lagrangian});
    enter_light(lp.minus, f, t, true);
  }
  if (family < 0) ++lp.minus_emitted;
}

/// Crossings the C+ fronts now in a light or lattice piece have passed there: those with the
/// fronts of the other family they found when they entered and those its right end emitted
/// since, less those still ahead of them.
long Tracker::lattice_crossings_done(int piece, double t) const {
  const LightPiece& lp = light_[piece];
  long done = 0;
  if (lp.lattice) {
    long minus_left = 0;
    walk_lattice_fronts(piece, t, [&](const LatticeFront& f, const State&) {
      if (f.family < 0) {
        ++minus_left;
      } else {
        done += f.front->meet_base + lp.minus_emitted - (static_cast<long>(lp.minus.size()) - minus_left);
      }
    });
    return done;
  }
  // C+ fronts from the rightmost, the C− fronts right of each counted from the right end.
  long ahead = 0;
  auto q = lp.minus.rbegin();
  for (const LightFront& p : lp.plus) {
    const double x = p.x_at(t, +1);
    for (; q != lp.minus.rend() && q->x_at(t, -1) > x; ++q) ++ahead;
    done += p.meet_base + lp.minus_emitted - ahead;
  }
  return done;
}

/// The piece's fronts go back on its node list at their places at time t, and its store goes.
void Tracker::dissolve_lattice(int piece, double t) {
  LightPiece& lp = light_[piece];
  const Piece& pc = pieces_[piece];
  const Material& m = *nodes_[pc.left_end].right.material;
  result_.stats.crossings_unvisited += lattice_crossings_done(piece, t);
  struct Placed {
    double X;
    int family;
    double strength;
    State left;
    double carried;
    bool smooth;
  };
  std::vector<Placed> placed;
  walk_lattice_fronts(piece, t, [&](const LatticeFront& f, const State& left) {
    placed.push_back(
        Placed{f.X, f.family, std::abs(f.front->j_ahead - f.front->j_behind), left, f.front->carried, f.front->smooth});
  });
  const State right_most = nodes_[lp.store].right.state;
  const Node& left_end = nodes_[pc.left_end];
  double X = left_end.X_at(t), x = left_end.x_at(t);
  int prev = pc.left_end;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const Placed& p = placed[i];
    x += (p.X - X) * label_density(p.left);
    X = p.X;
    const State& right = i + 1 < placed.size() ? placed[i + 1].left : right_most;
    const int id = new_node(NodeKind::front, piece);
    link(prev, id);
    set_front(id, p.family, FrontKind::contact, m, p.left, right, t, X, x, 0.0, t, p.strength);
    nodes_[id].right = Region{&m, right};
    nodes_[id].carried = p.carried;
    nodes_[id].smooth = p.smooth;
    prev = id;
  }
  link(prev, pc.right_end);
  kill_node(lp.store, t);
  light_fronts_ -= static_cast<long>(placed.size());
  light_bodies_ -= 1.0;
  const std::uint32_t version = lp.version + 1;
  lp = LightPiece{};
  lp.version = version;  // its arrival events are stale
  for (int n = pc.left_end; n != pc.right_end; n = nodes_[n].next) schedule_meet(n);
}

}  // namespace rigidity::characteristics
