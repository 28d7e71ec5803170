// What keeps the number of fronts bounded, and what it costs: merging fronts of one family, and the error of fan steps.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "tracker.hpp"

namespace rigidity::characteristics {

/// Two neighbouring fronts of one family in one material whose weaker one is within what a
/// merge may cost (ResolutionPolicy::merge_limit: strength times distance, the L1 error of
/// moving it) of the other are one front: the weaker one moves onto the stronger, which then
/// joins the outer states. For a linearly degenerate material that front is exact (the other
/// invariant is the same on all three states); a shock of a genuinely nonlinear one must stay
/// near its Hugoniot and a fan step within two fan steps. Keeps the fronts of long multi-body
/// runs from growing without bound; returns the surviving front.
/// The L1 error of replacing neighbouring fronts p < q of one family by one front, and where
/// it goes: at the label X̄ that keeps the lab length of the pair, so that lab positions stay
/// continuous, X̄ = Xp + (Xq − Xp)(ℓM − ℓR)/(ℓL − ℓR) with ℓ = s/γ. For two steps of one sign
/// X̄ lies between them; for a bump (steps of opposite signs) outside, which is allowed as far
/// as the next node on that side. The cost is the L1 difference of the two profiles, with
/// a = J(M) − J(L) and b = J(R) − J(M) the steps in the family's own invariant.
double Tracker::merge_cost(int p, int q, double t, double* X_merged) const {
  const Node& np = nodes_[p];
  const Node& nq = nodes_[q];
  const Region& L = nodes_[np.prev].right;
  const State& M = np.right.state;
  const State& R = nq.right.state;
  const double lL = label_density(L.state), lM = label_density(M), lR = label_density(R);
  if (lL == lR) return kInf;
  const double Xp = np.X_at(t), Xq = nq.X_at(t), d = Xq - Xp;
  const double X = Xp + d * (lM - lR) / (lL - lR);
  const double lower = facing(np.prev, true).X_at(t), upper = facing(nq.next, false).X_at(t);
  const double margin = 64.0 * kEps * (1.0 + std::abs(X));
  if (!(X > lower + margin && X < upper - margin)) return kInf;
  if (X_merged != nullptr) *X_merged = X;
  const Material& m = *L.material;
  const double a = wave_strength(m, L.state, M, np.family), b = wave_strength(m, M, R, np.family);
  if (X < Xp) return std::abs(a + b) * (Xp - X) + std::abs(b) * d;
  if (X > Xq) return std::abs(a) * d + std::abs(a + b) * (X - Xq);
  return std::abs(a) * (X - Xp) + std::abs(b) * (Xq - X);
}

int Tracker::merge_neighbours(int id, double t) {
  for (;;) {
    if (id == kNone || !nodes_[id].alive || nodes_[id].kind != NodeKind::front) return id;
    double best_cost = policy_.merge_limit();
    const int best_left = cheapest_neighbour_merge(id, t, best_cost);
    if (best_left == kNone) return id;
    const int p = best_left, q = nodes_[p].next;
    const Region L = nodes_[nodes_[p].prev].right;
    const Region R = nodes_[q].right;
    FrontKind kind = FrontKind::contact;
    double off = 0.0;
    if (!merged_front_kind(*L.material, L.state, R.state, nodes_[p].family, kind, off)) return id;
    id = apply_merge_neighbours(p, q, L, R, best_cost, kind, off, t);
  }
}

int Tracker::cheapest_neighbour_merge(int id, double t, double& best_cost) const {
  int best_left = kNone;
  for (int side = 0; side < 2; ++side) {
    const int p = side == 0 ? nodes_[id].prev : id;
    const int q = side == 0 ? id : nodes_[id].next;
    if (p == kNone || q == kNone) continue;
    const Node& np = nodes_[p];
    const Node& nq = nodes_[q];
    if (np.kind != NodeKind::front || nq.kind != NodeKind::front || np.family != nq.family) continue;
    if (unsplit(p) || unsplit(q)) continue;  // a fan's wedge is no jump to move
    const Region& L = nodes_[np.prev].right;
    if (L.material != np.right.material || L.material != nq.right.material) continue;
    if (std::min(np.strength, nq.strength) * (nq.X_at(t) - np.X_at(t)) > best_cost) continue;
    // Two fan steps of one family expand the same way, and each carries 2|ΔΨ| in its own
    // invariant: together they span the sum, which the merged step may not (below). Most
    // neighbours are steps of one fan (each between one and two fan steps wide): refused
    // here, before the curves are evaluated. The margin covers a step's distance from its
    // curve (star_mismatch_) and round-off.
    if (np.front_kind == FrontKind::rarefaction && nq.front_kind == FrontKind::rarefaction &&
        0.5 * (np.strength + nq.strength) > 2.0 * policy_.fan_step() * (1.0 + 1e-9) + 2.0 * star_mismatch_)
      continue;
    const double cost = merge_cost(p, q, t, nullptr);
    if (cost <= best_cost) {
      best_cost = cost;
      best_left = p;
    }
  }
  return best_left;
}

bool Tracker::merged_front_kind(const Material& m, const State& left, const State& right, int family, FrontKind& kind,
                                double& off) const {
  if (m.linearly_degenerate()) return true;
  const State& outer = family < 0 ? left : right;
  const State& inner = family < 0 ? right : left;
  if (same_state(outer, inner)) return false;
  if (wave_is_shock(m, outer, inner.stretch, family)) {
    kind = FrontKind::shock;
    const Solved<double> exact = hugoniot_rapidity(m, outer, inner.stretch, family);
    if (!exact.ok()) return false;
    off = std::abs(exact.value - inner.rapidity);
    if (!(off < policy_.weak_wave())) return false;
  } else {
    kind = FrontKind::rarefaction;
    if (std::abs(m.riemann_psi(outer.stretch) - m.riemann_psi(inner.stretch)) >= 2.0 * policy_.fan_step()) return false;
  }
  return std::abs(label_jump_speeds(m, left, right, family).lab) < 1.0;  // no faster than light
}

int Tracker::apply_merge_neighbours(int p, int q, const Region& L, const Region& R, double cost, FrontKind kind,
                                    double off, double t) {
  const int family = nodes_[p].family;
  const Material& m = *L.material;
  double X = 0.0;
  merge_cost(p, q, t, &X);
  const double x = nodes_[p].x_at(t) + (X - nodes_[p].X_at(t)) * label_density(L.state);
  const double strength_p = std::abs(wave_strength(m, L.state, nodes_[p].right.state, family));
  const double strength_q = std::abs(wave_strength(m, nodes_[p].right.state, R.state, family));
  const int kept = strength_p >= strength_q ? p : q;
  const int gone = kept == p ? q : p;
  nodes_[kept].smooth = nodes_[p].smooth && nodes_[q].smooth;
  // The merged front carries both fronts' errors, what their fan steps booked, and the merge's.
  double carried = nodes_[p].carried + nodes_[q].carried + ledger_.book_merge(cost);
  for (int n : {p, q}) {
    account_front_end(n, t);
    if (nodes_[n].front_kind == FrontKind::rarefaction) carried += book_fan_error(n, t);
    nodes_[n].carried = 0.0;
  }
  ++merged_;
  record_segment(nodes_[kept], t);
  close_defect(nodes_[kept], t);
  nodes_[p].right = R;  // p's right region was the middle state
  link(nodes_[gone].prev, nodes_[gone].next);
  if (kept == q) nodes_[q].right = R;
  kill_node(gone, t);
  set_front(kept, family, kind, m, L.state, R.state, t, X, x, off, t,
            std::abs(wave_strength(m, L.state, R.state, family)));
  nodes_[kept].carried = carried;
  if (nodes_[kept].prev != kNone) schedule_meet(nodes_[kept].prev);
  schedule_meet(kept);
  return kept;
}

void Tracker::apply_merge_across(int p, int q, std::size_t split, double X_merged, double cost, double j_before,
                                 double j_after_q, bool extend_left, double t) {
  const Material& m = *nodes_[p].right.material;
  const int f = nodes_[p].family;
  const int left_of_p = nodes_[p].prev, right_of_q = nodes_[q].next;
  ++merged_;
  const int start = left_of_p;
  double X_cursor = segments_.front().a;
  double x_cursor = extend_left ? nodes_[left_of_p].x_at(t) : nodes_[p].x_at(t);
  const double carried = nodes_[p].carried + nodes_[q].carried + ledger_.book_merge(cost);
  nodes_[p].carried = nodes_[q].carried = 0.0;
  const bool smooth = nodes_[p].smooth && nodes_[q].smooth;
  kill_node(p, t);
  kill_node(q, t);
  const int merged = new_node(NodeKind::front, nodes_[start].piece);
  live_fronts_max_ = std::max(live_fronts_max_, ++live_fronts_);
  ++result_.stats.fronts;
  Node& mn = nodes_[merged];
  mn.family = f;
  mn.front_kind = FrontKind::contact;
  mn.born = t;
  mn.strength = std::abs(j_after_q - j_before);
  mn.carried = carried;
  mn.smooth = smooth;
  int cursor = start;
  const auto advance = [&](double X, const State& st) {
    x_cursor += (X - X_cursor) * label_density(st);
    X_cursor = X;
  };
  const auto place = [&](int id) {
    Node& n = nodes_[id];
    if (id != merged) record_segment(n, t);
    link(cursor, id);
    n.t0 = t;
    n.X0 = X_cursor;
    n.x0 = x_cursor;
    ++n.version;
    cursor = id;
  };
  nodes_[cursor].right = Region{&m, split == 0 ? segments_.front().left : segments_.front().right};
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const MergeSegment& g = segments_[i];
    const State& here = i < split ? g.left : g.right;
    if (i == split) {
      advance(X_merged, g.left);
      nodes_[cursor].right = Region{&m, g.left};
      place(merged);
      nodes_[merged].right = Region{&m, g.right};
    } else {
      nodes_[cursor].right = Region{&m, here};
    }
    advance(g.b, here);
    if (g.right_node == right_of_q) break;
    if (g.right_node != kNone) place(g.right_node);
  }
  link(cursor, right_of_q);
  for (int n = nodes_[start].next; n != right_of_q; n = nodes_[n].next) {
    const FrontSpeeds sp = characteristic_speeds(m, nodes_[n].right.state, nodes_[n].family);
    nodes_[n].dXdt = sp.lagrangian;
    nodes_[n].dxdt = sp.lab;
  }
  if (nodes_[start].kind == NodeKind::front) {
    // Its right state changed: a front of this material keeps the speed of its side.
    reanchor(start, t);
    const FrontSpeeds sp = characteristic_speeds(m, nodes_[start].right.state, nodes_[start].family);
    nodes_[start].dXdt = sp.lagrangian;
    nodes_[start].dxdt = sp.lab;
  }
  if (nodes_[start].prev != kNone) schedule_meet(nodes_[start].prev);
  for (int n = start; n != right_of_q; n = nodes_[n].next) schedule_meet(n);
}

/// For a linearly degenerate material the jumps of J+ and J− are carried independently, so
/// two fronts p < q of one family f may be merged across fronts of the other family between
/// them: regions left of the merged front's label X̄ take the f-invariant from before p,
/// those right of it the one from after q; every region keeps its (−f)-invariant and the
/// fronts between keep their jumps. X̄ is where the lab length is unchanged, so that every
/// lab position outside stays as it was: between p and q for two steps of one sign, beyond
/// them (as far as the next node) for a bump. The nodes between are re-anchored with lab
/// positions rebuilt from the left. The L1 error is the f-invariant's change times the
/// length it changes over. Without this, the fronts of layered bodies (reflections at every
/// contact) multiply for ever, since same-family fronts are kept apart by the other
/// family's. Returns true if merged.
bool Tracker::merge_across(int p, int q, double t) {
  const int f = nodes_[p].family;
  const int left_of_p = nodes_[p].prev, right_of_q = nodes_[q].next;
  if (left_of_p == kNone || right_of_q == kNone) return false;
  const double limit = policy_.merge_limit();
  // No merge costs less than the weaker front times the distance: most are refused here.
  if (std::min(nodes_[p].strength, nodes_[q].strength) * (nodes_[q].X_at(t) - nodes_[p].X_at(t)) > limit) return false;
  const auto region_invariant = [&](const Region& r) { return r.state.rapidity + f * psi_of(r); };
  const double j_before = region_invariant(nodes_[left_of_p].right), j_after_p = region_invariant(nodes_[p].right);
  const double j_after_q = region_invariant(nodes_[q].right);
  const double Xp = nodes_[p].X_at(t), Xq = nodes_[q].X_at(t);
  const double sigma_p = j_after_p - j_before, sigma_q = j_after_q - j_after_p;
  const double weaker = std::min(std::abs(sigma_p), std::abs(sigma_q));
  if (weaker * (Xq - Xp) > limit) return false;
  // To first order in the jumps, keeping the lab length puts X̄ at the strength-weighted mean
  // of p and q for two steps of one sign (cost 2 σp σq/(σp + σq) × distance), and beyond the
  // weaker one for a bump (cost 2 min(|σp|, |σq|) × distance). Almost every merge refused is
  // refused here, before the new states are found; the margin leaves the rare one the
  // higher orders make cheaper to the exact cost below.
  const double estimate =
      (sigma_p * sigma_q > 0.0 ? 2.0 * sigma_p * sigma_q / (sigma_p + sigma_q) : 2.0 * weaker) * (Xq - Xp);
  if (estimate > kMergeEstimateMargin * limit) return false;
  bool extend_left = false;
  if (!merge_segments(p, q, j_before, j_after_p, j_after_q, extend_left, t)) return false;
  double X_merged = kInf;
  std::size_t split = 0;
  if (!merged_label(X_merged, split)) return false;
  const double cost = merge_across_cost(split, X_merged, j_before, j_after_q);
  if (cost > limit) return false;

  // p and q leave; one front of family f enters at X̄.
  apply_merge_across(p, q, split, X_merged, cost, j_before, j_after_q, extend_left, t);
  return true;
}

bool Tracker::merge_segments(int p, int q, double j_before, double j_after_p, double j_after_q, bool& extend_left,
                             double t) {
  const Material& m = *nodes_[p].right.material;
  const int f = nodes_[p].family;
  const int left_of_p = nodes_[p].prev, right_of_q = nodes_[q].next;
  const auto invariant = [&](const State& st, int family) { return st.rapidity + family * memo_->psi(m, st.stretch); };
  const State before = nodes_[left_of_p].right.state;
  const State after_q = nodes_[q].right.state;
  const double Xp = nodes_[p].X_at(t), Xq = nodes_[q].X_at(t);
  const auto with_invariant = [&](const State& st, double j_f) -> Solved<State> {
    const double j_other = invariant(st, -f);
    const double j_plus = f > 0 ? j_f : j_other, j_minus = f > 0 ? j_other : j_f;
    const double psi = 0.5 * (j_plus - j_minus);
    if (!(psi < m.psi_max() && psi > m.psi_min())) return Solved<State>::failure(Status::out_of_range);
    const Solved<Stretch> stretch = memo_->stretch_at_psi(m, psi);
    if (!stretch.ok()) return Solved<State>::failure(stretch.status);
    return Solved<State>{State{0.5 * (j_plus + j_minus), stretch.value}, Status::ok};
  };
  // Segments left to right: the region before p (if of this material), those between p and
  // q, the region after q (likewise). Each: its extent, old f-invariant, its states left and
  // right of X̄, and the node at its right edge (kNone where that edge is p or q, which go).
  segments_.clear();
  const auto add = [&](double a, double b, const State& old, double j_old, int right_node) {
    const Solved<State> left = with_invariant(old, j_before), right = with_invariant(old, j_after_q);
    if (!left.ok() || !right.ok()) return false;
    segments_.push_back(MergeSegment{a, b, old, j_old, left.value, right.value, right_node});
    return true;
  };
  extend_left = nodes_[left_of_p].kind == NodeKind::front && nodes_[nodes_[left_of_p].prev].right.material == &m;
  const bool extend_right = nodes_[right_of_q].kind == NodeKind::front && nodes_[right_of_q].right.material == &m;
  if (extend_left && !add(nodes_[left_of_p].X_at(t), Xp, before, j_before, kNone)) return false;
  double a = Xp;
  for (int n = nodes_[p].next;; n = nodes_[n].next) {
    const int prev = nodes_[n].prev;
    const double b = n == q ? Xq : nodes_[n].X_at(t);
    if (!add(a, b, nodes_[prev].right.state, j_after_p, n == q ? kNone : n)) return false;
    a = b;
    if (n == q) break;
  }
  if (extend_right && !add(Xq, nodes_[right_of_q].X_at(t), after_q, j_after_q, right_of_q)) return false;
  if (!extend_right) segments_.back().right_node = right_of_q;
  return true;
}

bool Tracker::merged_label(double& X_merged, std::size_t& split) const {
  // Lab length change as X̄ moves right from the first edge: all segments on their right
  // states at first, each turning to its left state as X̄ passes it.
  double change = 0.0;
  for (const MergeSegment& g : segments_) change += (label_density(g.right) - label_density(g.old)) * (g.b - g.a);
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const MergeSegment& g = segments_[i];
    const double rate = label_density(g.left) - label_density(g.right);
    const double next = change + rate * (g.b - g.a);
    if ((change <= 0.0 && next >= 0.0) || (change >= 0.0 && next <= 0.0)) {
      X_merged = rate == 0.0 ? g.a : std::clamp(g.a - change / rate, g.a, g.b);
      split = i;
      break;
    }
    change = next;
  }
  if (!std::isfinite(X_merged)) return false;
  const double margin = 64.0 * kEps * (1.0 + std::abs(X_merged));
  return !(X_merged <= segments_.front().a + margin || X_merged >= segments_.back().b - margin);
}

double Tracker::merge_across_cost(std::size_t split, double X_merged, double j_before, double j_after_q) const {
  double cost = 0.0;
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const MergeSegment& g = segments_[i];
    const double left_part = i < split ? g.b - g.a : i == split ? X_merged - g.a : 0.0;
    cost += std::abs(j_before - g.j_old) * left_part + std::abs(j_after_q - g.j_old) * (g.b - g.a - left_part);
  }
  return cost;
}

/// Looks for a front of the same family within a few nodes of `id`, across fronts of the
/// other family only, in one linearly degenerate material, and merges the two if cheap.
void Tracker::merge_nearby(int id, double t) {
  if (id == kNone || !nodes_[id].alive || nodes_[id].kind != NodeKind::front) return;
  const Material* m = nodes_[id].right.material;
  if (m == nullptr || !m->linearly_degenerate()) return;
  const int f = nodes_[id].family;
  const double X = nodes_[id].X_at(t), strength = nodes_[id].strength;
  for (int direction : {+1, -1}) {
    int n = id;
    for (int steps = 0; steps < kMergeReach; ++steps) {
      n = direction > 0 ? nodes_[n].next : nodes_[n].prev;
      if (n == kNone) break;
      const Node& other = nodes_[n];
      // A merge costs at least the weaker front's strength times the distance between the
      // two. Where this front times the distance already exceeds what a merge may cost, a
      // cheap pair needs the other front to be the weaker one, and that front looks for
      // this one when it next meets something: the walk stops (most crossings stop here,
      // so this is asked first).
      if (strength * std::abs(other.X_at(t) - X) > policy_.merge_limit()) break;
      if (other.kind != NodeKind::front || other.right.material != m) break;
      if (direction < 0 && nodes_[other.prev].right.material != m) break;
      if (other.family != f) continue;
      if (direction > 0 ? merge_across(id, n, t) : merge_across(n, id, t)) return;
      break;
    }
  }
}

double Tracker::fan_error(int id, double t, bool smooth_on) const {
  if (unsplit(id)) return 0.0;  // samples take the exact fan
  const Node& n = nodes_[id];
  const Region& left = nodes_[n.prev].right;
  const Region& right = n.right;
  const Material& m = *right.material;
  const double strength = std::abs(wave_strength(m, left.state, right.state, n.family));
  // A fan step's ramp spreads as its fan does; a step of a compression wave stands for the
  // ramp between its neighbours.
  const double spread =
      n.front_kind == FrontKind::rarefaction
          ? std::abs(speeds_of(left, n.family).lagrangian - speeds_of(right, n.family).lagrangian) * (t - n.born)
          : kInf;
  // A jump of σ in the middle of a ramp of width w misses it by two triangles, σ w/4 in
  // |δφ| + |δΨ| (σ/2 each, the other invariant being constant across a simple wave). The
  // ramp is no wider than the room between its neighbours: a staircase of steps stands for
  // a fan one spacing per step. A compression wave's ramp only narrows, and its step stands
  // half a strip inside it at its edge: beside a plateau (what a free end reflects of a fan's
  // last step as the end leaves a wall, say) it reaches no further out than the strip on the
  // other side.
  const double before = n.X_at(t) - nodes_[n.prev].X_at(t), after = nodes_[n.next].X_at(t) - n.X_at(t);
  const double room = n.front_kind == FrontKind::shock ? std::min(0.5 * (before + after), 2.0 * std::min(before, after))
                                                       : 0.5 * (before + after);
  const double staircase = 0.25 * strength * std::min(spread, room);
  return smooth_on ? std::min(staircase, reconstruction_error(id, t)) : staircase;
}

}  // namespace rigidity::characteristics
