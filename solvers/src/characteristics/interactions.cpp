// Fronts meeting: the next meeting of a node, interactions done in place, full Riemann problems at a point, the waves
// they emit, and weak waves held back at interfaces and contacts.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "tracker.hpp"

namespace rigidity::characteristics {

double Tracker::meeting_time(int a) const {
  const Node& na = nodes_[a];
  const int b = na.next;
  if (b == kNone || na.kind == NodeKind::light_store) return kInf;  // a light piece's store meets nothing
  // An unsplit fan is met at its edge: a's fastest characteristic, b's slowest.
  const LabelRay ra = facing(a, true), rb = facing(b, false);
  const double closing = ra.speed - rb.speed;
  if (!(closing > 0.0)) return kInf;
  const double t_ref = std::max(ra.t0, rb.t0);
  const double gap = std::max(0.0, rb.X_at(t_ref) - ra.X_at(t_ref));
  const double t = t_ref + gap / closing;
  return t <= scene_.t_end ? t : kInf;
}

void Tracker::schedule_meet(int a) {
  const double t = meeting_time(a);
  if (t < kInf) {
    meetings_.set(a, t, seq_++);
  } else {
    meetings_.erase(a);
  }
}

void Tracker::schedule_meets(int a, int b) {
  const double ta = meeting_time(a), tb = meeting_time(b);
  if (ta == kInf && tb < kInf && meetings_.contains(a) && !meetings_.contains(b)) {
    meetings_.move(a, b, tb, seq_++);  // a's entry (the top, after a crossing) becomes b's
    return;
  }
  if (ta < kInf) {
    meetings_.set(a, ta, seq_++);
  } else {
    meetings_.erase(a);
  }
  if (tb < kInf) {
    meetings_.set(b, tb, seq_++);
  } else {
    meetings_.erase(b);
  }
}

/// Two fronts of one material meeting with nothing else there, done in place: they leave
/// as a C− front (in a's node) and a C+ front (in b's node) around the star state, J+ from
/// the left state and J− from the right one. For a linearly degenerate material that
/// two-rarefaction star is exact. For a genuinely nonlinear one the star is where the two
/// wave curves meet (Hugoniot for a shock, integral curve for a fan step), found from that
/// guess by secant steps to round-off, or until they miss each other by less than
/// star_mismatch_; each front carries what its state misses its curve by as an error rate
/// for as long as it lives. Two steps of smooth waves crossing head-on are characteristics
/// and take the two-rarefaction star as it is (steps_pass). A C− wave left weaker than the
/// threshold by two fronts of one family merging is held back (its strength times the length
/// it could sweep is booked). Returns false (doing nothing) when the full Riemann problem is
/// needed: a crowd, a strong shock, a fan to split, cavitation.
bool Tracker::cross_in_place(int a, int b, double t, InPlace& c) {
  CrossingSides s;
  if (!two_rarefaction_star(a, b, t, s, c)) return false;
  const Material* m = s.left->material;
  const State& left = s.left->state;
  const State& right = s.right->state;

  // The outgoing waves: kinds, strengths, and how far each is from its wave curve.
  // J− across the C− front, J+ across the C+ front (for a linearly degenerate material,
  // those the fronts brought in, passed on).
  c.strength[0] = std::abs(s.j_minus - (left.rapidity - s.psi_left));
  c.strength[1] = std::abs(right.rapidity + s.psi_right - s.j_plus);
  if (m->linearly_degenerate() || steps_pass(a, b, c)) {
    if (same_state(c.star, left) || same_state(c.star, right)) return false;  // a wave vanishes
  } else if (!star_on_curves(a, b, s, c)) {
    return false;
  }

  if (c.held_back && !(std::abs(label_jump_speeds(*m, left, right, +1).lab) < 1.0))
    return false;  // no faster than light
  return true;
}

bool Tracker::steps_pass(int a, int b, InPlace& c) const {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  if (!na.smooth || !nb.smooth || na.family != +1 || nb.family != -1) return false;
  c.kinds[0] = nb.front_kind;
  c.kinds[1] = na.front_kind;
  return true;
}

bool Tracker::two_rarefaction_star(int a, int b, double t, CrossingSides& s, InPlace& c) {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  const Node& before = nodes_[na.prev];
  const Node& after = nodes_[nb.next];
  const Material* m = before.right.material;
  if (m != nb.right.material || m != na.right.material) return false;
  const bool degenerate = m->linearly_degenerate();
  if (degenerate && (na.family != +1 || nb.family != -1)) return false;
  c.X = 0.5 * (na.X_at(t) + nb.X_at(t));
  const double X = c.X;
  const double tolerance = 8.0 * kEps * (1.0 + std::abs(X));
  if (before.X_at(t) >= X - tolerance || after.X_at(t) <= X + tolerance) return false;  // a crowd: resolve in full
  s.left = &before.right;
  s.right = &nb.right;
  const State& left = before.right.state;
  const State& right = nb.right.state;
  s.psi_left = psi_of(before.right);
  s.psi_right = psi_of(nb.right);
  s.j_plus = left.rapidity + s.psi_left;
  s.j_minus = right.rapidity - s.psi_right;
  const double psi_star = 0.5 * (s.j_plus - s.j_minus);
  if (!(psi_star < m->psi_max())) return false;
  if (m->cavitation_pressure() > -kInf) {
    const Solved<double> parting = memo_->parting_psi(*m);
    if (!parting.ok() || psi_star < parting.value) return false;
  }
  const Solved<Stretch> star_stretch = memo_->stretch_at_psi(*m, psi_star);
  if (!star_stretch.ok() || !representable(star_stretch.value)) return false;  // resolved in full, and reported
  c.star = State{0.5 * (s.j_plus + s.j_minus), star_stretch.value};
  c.psi_star = psi_star;
  return true;
}

State Tracker::head_on_guess(int a, int b, const CrossingSides& s, const State& star) {
  // Two waves crossing head-on pass through each other nearly unchanged: each outgoing
  // wave carries the jump in the other family's invariant its incoming self had (zero
  // for a fan step; a shock's, third order in its strength, off the integral curve).
  // The star from those jumps misses the exact one by a fourth-order term where the
  // two-rarefaction star misses it by a third-order one.
  const Node& na = nodes_[a];
  const Material* m = s.left->material;
  const State& left = s.left->state;
  const State& right = s.right->state;
  State guess = star;
  if (na.family > 0 && nodes_[b].family < 0) {
    const State& middle = na.right.state;
    const double psi_middle = psi_of(na.right);
    const double carried_plus = (right.rapidity + s.psi_right) - (middle.rapidity + psi_middle);  // J+ across b
    const double carried_minus = (middle.rapidity - psi_middle) - (left.rapidity - s.psi_left);   // J− across a
    if (carried_plus != 0.0 || carried_minus != 0.0) {
      const Solved<Stretch> st = m->stretch_at_psi(0.5 * ((s.j_plus + carried_plus) - (s.j_minus - carried_minus)));
      if (st.ok() && representable(st.value)) guess.stretch = st.value;
    }
  }
  return guess;
}

bool Tracker::star_on_curves(int a, int b, const CrossingSides& s, InPlace& c) {
  const Material* m = s.left->material;
  const State& left = s.left->state;
  const State& right = s.right->state;
  // The star where the two wave curves meet, to round-off, or as soon as they miss each
  // other by less than star_mismatch_ (then booked on both fronts like a shock held off
  // its Hugoniot: a weak crossing often takes the two-rarefaction star as it is).
  CrossingEnds ends{CurveEnd{left, s.psi_left, speeds_of(*s.left, -1).lagrangian, {}},
                    CurveEnd{right, s.psi_right, speeds_of(*s.right, +1).lagrangian, {}}};
  const State guess = head_on_guess(a, b, s, c.star);
  const Solved<SameMaterialStar> found = same_material_star(*m, ends, guess, star_mismatch_);
  if (!found.ok()) return false;
  c.star = found.value.state;
  c.converged = found.value.converged;
  c.star_speeds[0] = found.value.speeds[0];
  c.star_speeds[1] = found.value.speeds[1];
  c.outer_laws[0] = ends.left.laws;
  c.outer_laws[1] = ends.right.laws;
  c.star_laws = found.value.laws;
  c.psi_star = m->riemann_psi(c.star.stretch);
  bool shock[2] = {found.value.shock[0], found.value.shock[1]};
  for (int k = 0; k < 2; ++k) c.off_curve[k] = shock[k] || !found.value.converged ? found.value.off[k] : 0.0;
  c.strength[0] = std::abs((c.star.rapidity - left.rapidity) - (c.psi_star - s.psi_left));
  c.strength[1] = std::abs((right.rapidity - c.star.rapidity) + (s.psi_right - c.psi_star));
  if (c.strength[0] < policy_.weak_merging() && nodes_[a].family == nodes_[b].family) {
    if (!hold_back_minus(s, shock, c)) return false;
  }
  return outgoing_kinds(a, b, s, shock, c);
}

bool Tracker::hold_back_minus(const CrossingSides& s, bool shock[2], InPlace& c) {
  const Material* m = s.left->material;
  const State& left = s.left->state;
  const State& right = s.right->state;
  c.held_back = true;
  c.star = left;
  c.psi_star = s.psi_left;
  // The C+ wave now joins `left` to `right`: its curve through `right` at left's stretch.
  shock[1] = wave_is_shock(*m, right, c.star.stretch, +1);
  c.off_curve[1] = 0.0;
  if (shock[1]) {
    const Solved<double> exact = hugoniot_rapidity(*m, right, c.star.stretch, +1);
    if (!exact.ok()) return false;
    c.off_curve[1] = std::abs(exact.value - c.star.rapidity);
  }
  c.strength[1] = std::abs((right.rapidity - left.rapidity) + (s.psi_right - s.psi_left));
  return true;
}

bool Tracker::outgoing_kinds(int a, int b, const CrossingSides& s, const bool shock[2], InPlace& c) const {
  for (int k = c.held_back ? 1 : 0; k < 2; ++k) {
    const State& outer = k == 0 ? s.left->state : s.right->state;
    if (same_state(outer, c.star)) return false;
    if (shock[k]) {
      c.kinds[k] = FrontKind::shock;
      if (!(c.off_curve[k] < policy_.weak_wave())) return false;
    } else {
      c.kinds[k] = FrontKind::rarefaction;
      const double span = std::abs(c.psi_star - (k == 0 ? s.psi_left : s.psi_right));
      // A new fan is split in steps; a step of a smooth wave goes on as one step.
      if (span >= 2.0 * policy_.fan_step() && !nodes_[a].smooth && !nodes_[b].smooth) return false;
    }
  }
  return true;
}

void Tracker::hand_on_in_place(int a, int b, double t, InPlace& c) {
  Node& na = nodes_[a];
  Node& nb = nodes_[b];
  const bool degenerate = na.right.material->linearly_degenerate();
  // Fan steps keep their age through the interaction when they leave as the only step of
  // their family; otherwise the error they carry is booked now.
  c.born[0] = c.born[1] = t;
  c.smooth_in.add(na.family > 0 ? 1 : 0, na.smooth, false);
  c.smooth_in.add(nb.family > 0 ? 1 : 0, nb.smooth,
                  na.family == nb.family && converge(na, nb, kSuperposed * policy_.fan_step()));
  // The errors the outgoing waves carry ([0] C−, [1] C+): each incoming front's goes on with
  // the wave of its family (two of one family merge into one), with what its fan step booked.
  for (Node* n : {&na, &nb}) {
    const int k = n->family > 0 ? 1 : 0;
    c.carried[k] += n->carried;
    n->carried = 0.0;
    const int id = static_cast<int>(n - nodes_.data());
    if (n->front_kind == FrontKind::rarefaction) {
      const bool continues =
          c.kinds[k] == FrontKind::rarefaction && !(c.held_back && k == 0) && (na.family != nb.family || degenerate);
      if (continues && c.born[k] == t) {
        c.born[k] = n->born;
      } else {
        c.carried[k] += book_fan_error(id, t);
      }
    } else if (n->smooth && !c.smooth_in.out(k)) {
      c.carried[k] += book_fan_error(id, t);  // a step of a compression wave a jump takes in
    }
  }
}

bool Tracker::interact_in_place(int a, int b, double t) {
  if (result_.stats.interactions >= scene_.solver.max_interactions) return false;  // resolve_group reports it
  Node& na = nodes_[a];
  Node& nb = nodes_[b];
  if (na.kind != NodeKind::front || nb.kind != NodeKind::front) return false;
  InPlace c;
  if (!cross_in_place(a, b, t, c)) return false;

  hand_on_in_place(a, b, t, c);

  ++result_.stats.interactions;
  policy_.after_interaction(live_fronts_, light_fronts_, light_bodies_);
  const double x = 0.5 * (na.x_at(t) + nb.x_at(t));
  close_defect(na, t);
  close_defect(nb, t);
  record_segment(na, t);
  record_segment(nb, t);
  if (c.held_back) {
    hold_back_in_place(a, b, c, x, t);
    return true;
  }
  account_front_end(a, t);
  account_front_end(b, t);
  result_.stats.fronts += 2;
  set_crossed_fronts(a, b, c, x, t);
  schedule_meet(na.prev);
  schedule_meets(a, b);
  merge_after_crossing(a, b, c.X, t);
  return true;
}

void Tracker::hold_back_in_place(int a, int b, const InPlace& c, double x, double t) {
  const Node& na = nodes_[a];
  const Node& before = nodes_[na.prev];
  const Material* m = before.right.material;
  const State& left = before.right.state;
  const State& right = nodes_[b].right.state;
  ledger_.book_defect(c.strength[0] * std::min(piece_length(na.piece),
                                               std::abs(speeds_of(before.right, -1).lagrangian) * (scene_.t_end - t)));
  ++suppressed_;
  const int keep_before = na.prev;
  account_front_end(a, t);  // its shock books close while its neighbours are still its own
  link(keep_before, b);
  kill_node(a, t);
  ledger_.lose(c.carried[0]);  // the C− wave held back (its strength is booked above)
  nodes_[b].carried = c.carried[1];
  nodes_[b].smooth = c.smooth_in.out(1);
  nodes_[b].kink = 0.0;
  nodes_[b].offset = 0.0;
  set_front(b, +1, c.kinds[1], *m, left, right, t, c.X, x, c.off_curve[1], c.born[1], c.strength[1]);
  schedule_meet(keep_before);
  schedule_meet(b);
}

Region Tracker::crossing_star_region(int a, int b, const InPlace& c) const {
  const Region& left = nodes_[nodes_[a].prev].right;
  const Region& right = nodes_[b].right;
  // The star's Ψ is at hand; in a linearly degenerate material its C− speeds are those of
  // `left` (J+ is the same) and its C+ speeds those of `right` (J− is), and so are the
  // speeds of the two fronts.
  Region star_region{left.material, c.star};
  star_region.psi = c.psi_star;
  if (left.material->linearly_degenerate()) {
    star_region.speeds[0] = speeds_of(left, -1);
    star_region.speeds[1] = speeds_of(right, +1);
  } else if (c.converged) {
    // A fan step's curve was asked for its speeds at the star (to round-off) already.
    star_region.speeds[0] = c.star_speeds[0];
    star_region.speeds[1] = c.star_speeds[1];
  }
  return star_region;
}

void Tracker::set_crossed_fronts(int a, int b, const InPlace& c, double x, double t) {
  Node& na = nodes_[a];
  Node& nb = nodes_[b];
  const Node& before = nodes_[na.prev];
  const Material* m = before.right.material;
  const bool degenerate = m->linearly_degenerate();
  const State& left = before.right.state;
  const State& right = nb.right.state;
  const State& star = c.star;
  Region star_region = crossing_star_region(a, b, c);
  // The laws at the outer states and the star, where the crossing's wave curves asked for them.
  const JumpLaws laws_minus[2] = {c.outer_laws[0], c.star_laws};
  const JumpLaws laws_plus[2] = {c.star_laws, c.outer_laws[1]};
  // cosh and sinh of the three rapidities, for the label jumps of the two fronts and their
  // shocks' dissipation: the outer regions keep theirs for the crossings they meet next.
  const Hyperbolic* at[3] = {nullptr, nullptr, nullptr};
  if (!degenerate) {
    star_region.hyperbolic = hyperbolic(star.rapidity);
    at[0] = &hyperbolic_of(before.right);
    at[1] = &star_region.hyperbolic;
    at[2] = &hyperbolic_of(nb.right);
  }
  // A jump that meets a step of a smooth wave changes its speed: by how much (Node::kink).
  const Node* jump_in = na.smooth != nb.smooth ? (na.smooth ? &nb : &na) : nullptr;
  const double jump_speed = jump_in != nullptr ? jump_in->dXdt : 0.0;
  const double jump_since = jump_in != nullptr ? jump_in->t0 : 0.0;
  const int jump_family = jump_in != nullptr ? jump_in->family : 0;
  na.kink = nb.kink = 0.0;
  // Each wave's step goes on with its value (two of one family meeting make a jump).
  const double offset_minus = na.family != nb.family ? (na.family < 0 ? na.offset : nb.offset) : 0.0;
  const double offset_plus = na.family != nb.family ? (na.family > 0 ? na.offset : nb.offset) : 0.0;
  na.offset = c.smooth_in.out(0) ? offset_minus : 0.0;
  nb.offset = c.smooth_in.out(1) ? offset_plus : 0.0;
  na.smooth = c.smooth_in.out(0);
  nb.smooth = c.smooth_in.out(1);
  set_front(a, -1, c.kinds[0], *m, left, star, t, c.X, x, c.off_curve[0], c.born[0], c.strength[0],
            degenerate ? &star_region.speeds[0] : nullptr, laws_minus, at[0], at[1]);
  set_front(b, +1, c.kinds[1], *m, star, right, t, c.X, x, c.off_curve[1], c.born[1], c.strength[1],
            degenerate ? &star_region.speeds[1] : nullptr, laws_plus, at[1], at[2]);
  na.right = star_region;
  na.carried = c.carried[0];
  nb.carried = c.carried[1];
  if (jump_in != nullptr) {
    Node& jump = jump_family < 0 ? na : nb;
    jump.kink = std::abs(jump.dXdt - jump_speed);
    jump.kink_dt = t - jump_since;
  }
}

void Tracker::merge_after_crossing(int a, int b, double X, double t) {
  const Node& before = nodes_[nodes_[a].prev];
  const Node& after = nodes_[nodes_[b].next];
  if (before.right.material->linearly_degenerate()) {
    // The two new fronts sit together; the nearest others are `before` and `after`. A
    // front's walk for a merge stops at the first one whose distance times the front's
    // strength exceeds what a merge may cost (merge_nearby): asked here first, as it
    // usually settles it for both.
    const double nearest = std::min(X - before.X_at(t), after.X_at(t) - X);
    if (!(std::min(nodes_[a].strength, nodes_[b].strength) * nearest > policy_.merge_limit())) {
      merge_nearby(a, t);
      merge_nearby(b, t);
    }
  } else {
    merge_neighbours(a, t);
    merge_neighbours(b, t);
  }
}

/// A front of family `family` between the states `left` and `right` of material m, leaving
/// (X, x) at time t. Jumps of a linearly degenerate material move at the characteristic
/// speed; shocks and fan steps at the speed the label jump condition gives, so that the lab
/// position of every label stays continuous across them. `known`: the front's speeds where
/// the caller has them (a linearly degenerate crossing takes them from its neighbours).
/// A shock's dissipation is worked out here, from the label jump its speeds come from, and
/// `laws` (p and e + p of left and right) where the caller has them.
void Tracker::set_front(int id, int family, FrontKind kind, const Material& m, const State& left, const State& right,
                        double t, double X, double x, double off_hugoniot, double born, double strength,
                        const FrontSpeeds* known, const JumpLaws* laws, const Hyperbolic* at_left,
                        const Hyperbolic* at_right) {
  Node& n = nodes_[id];
  leave_fan(n);
  n.strength = strength;
  n.dissipation = std::numeric_limits<double>::quiet_NaN();
  FrontSpeeds speeds;
  if (known != nullptr) {
    speeds = *known;
  } else if (kind == FrontKind::contact) {
    speeds = memo_->speeds(m, right, family);
  } else {
    LabelJump jump = at_left != nullptr ? label_jump(left, *at_left, right) : label_jump(left, right);
    if (at_right != nullptr) {
      jump.right = *at_right;
      jump.right_known = true;
    }
    speeds = label_jump_speeds(m, left, right, family, jump);
    // A true shock's dissipation, for its energy books (account_front_end); a step of a smooth
    // compression wave books what its jump speed makes instead, and needs none.
    if (kind == FrontKind::shock && !n.smooth) {
      const Solved<double> rate =
          shock_dissipation_rate(m, left, laws != nullptr ? laws[0] : JumpLaws{}, right,
                                 laws != nullptr ? laws[1] : JumpLaws{}, jump, dissipation_precision_);
      if (rate.ok()) n.dissipation = rate.value;
    }
  }
  n.born = born;
  n.family = family;
  n.front_kind = kind;
  n.dXdt = speeds.lagrangian;
  n.dxdt = speeds.lab;
  n.t0 = t;
  n.X0 = X;
  n.x0 = x;
  ++n.version;
  n.defect_rate = off_hugoniot * std::abs(speeds.lagrangian);
  n.defect_since = t;
  n.defect_cap = off_hugoniot * piece_length(n.piece);
}

void Tracker::resolve(int seed_left, int seed_right, double t) {
  group_.clear();
  // Gather every node at the meeting point: the seeds, their neighbours at the same
  // label, and across a body contact the other body's nodes at its end.
  int first = seed_left;
  for (;;) {
    const Node& n = nodes_[first];
    if (n.kind == NodeKind::left_end) {
      if (n.attach != Attach::body) break;
      first = n.partner;
      continue;
    }
    const int p = n.prev;
    if (p == kNone) break;
    const double X = n.X_at(t), Xp = nodes_[p].X_at(t);
    if (!(Xp >= X - 8.0 * kEps * (1.0 + std::abs(X)))) break;
    first = p;
  }
  int last = seed_right;
  for (;;) {
    const Node& n = nodes_[last];
    if (n.kind == NodeKind::right_end) {
      if (n.attach != Attach::body) break;
      last = n.partner;
      continue;
    }
    const int q = n.next;
    if (q == kNone) break;
    const double X = n.X_at(t), Xq = nodes_[q].X_at(t);
    if (!(Xq <= X + 8.0 * kEps * (1.0 + std::abs(X)))) break;
    last = q;
  }
  for (int n = first;;) {
    group_.push_back(n);
    if (n == last) break;
    const Node& node = nodes_[n];
    n = node.kind == NodeKind::right_end ? node.partner : node.next;
  }
  resolve_group(group_, t);
}

void Tracker::emit_wave(const Material& m, const State& outer, const State& star, int family, bool fresh, int piece,
                        double t, double X, double x, WaveStates& w, std::vector<int>& out) {
  if (m.linearly_degenerate() || !crosses_inflection(m, outer.stretch, star.stretch)) {
    wave(m, outer, star, family, fresh, w);
    emit_fronts(m, w, family, piece, t, X, x, out);
    return;
  }
  const Solved<CompositeWave> composite = composite_wave(m, outer, star.stretch, family);
  if (!composite.ok())
    throw NumericalError("the composite wave of a law with an inflection could not be built at t = " + number(t));
  w.start(outer);
  State from = outer;
  const std::vector<WavePiece>& pieces = composite.value.pieces;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    // The last piece ends at the star as the Riemann problem found it (the same state to round-off).
    const State& to = k + 1 == pieces.size() ? star : pieces[k].end;
    wave_piece(m, from, to, family, fresh, pieces[k].shock, wave_piece_);
    emit_fronts(m, wave_piece_, family, piece, t, X, x, out);
    w.states.insert(w.states.end(), wave_piece_.states.begin() + 1, wave_piece_.states.end());
    from = to;
  }
}

void Tracker::wave(const Material& m, const State& outer, const State& star, int family, bool fresh, WaveStates& w) {
  wave_piece(m, outer, star, family, fresh, !m.linearly_degenerate() && wave_is_shock(m, outer, star.stretch, family),
             w);
}

void Tracker::wave_piece(const Material& m, const State& outer, const State& star, int family, bool fresh, bool shock,
                         WaveStates& w) {
  w.start(outer);
  if (same_state(outer, star)) return;
  if (m.linearly_degenerate()) {
    w.states.push_back(star);
    return;
  }
  if (shock) {
    w.shock = true;
    w.states.push_back(star);
    return;
  }
  // A rarefaction fan: states along the invariant of the other family, in steps of Ψ.
  const double psi_outer = m.riemann_psi(outer.stretch), psi_star = m.riemann_psi(star.stretch);
  const double span = std::abs(psi_star - psi_outer);
  // A new fan in steps between one and two fan steps wide. A step of a smooth wave that has
  // grown through interactions goes on as one step: the steps it would split into would all
  // leave from where it is, not from where their characteristics are, half its width apart.
  const double speed_outer = characteristic_speeds(m, outer, family).lagrangian;
  const double speed_star = characteristic_speeds(m, star, family).lagrangian;
  const double wanted = fresh ? policy_.fan_steps(span, speed_outer, speed_star) : 1.0;
  const int steps = std::max(1, static_cast<int>(std::min(wanted, static_cast<double>(kMaxFanSteps))));
  if (fresh && steps > 1) {
    // A new centred fan, held as one front until something reaches it (split_fan).
    w.unsplit = steps;
    w.capped = wanted > kMaxFanSteps;
    w.states.push_back(star);
    return;
  }
  fan_states(m, outer, star, family, steps, w);
}

void Tracker::fan_states(const Material& m, const State& outer, const State& star, int family, int steps,
                         WaveStates& w) {
  w.states.clear();
  w.states.push_back(outer);
  const double psi_outer = m.riemann_psi(outer.stretch), psi_star = m.riemann_psi(star.stretch);
  // J carried across: J+ = φ + Ψ for a C− fan, J− = φ − Ψ for a C+ fan.
  const double invariant = family < 0 ? outer.rapidity + psi_outer : outer.rapidity - psi_outer;
  for (int k = 1; k < steps; ++k) {
    const double psi = psi_outer + (psi_star - psi_outer) * k / steps;
    const Solved<Stretch> s = m.stretch_at_psi(psi);
    if (!s.ok()) throw NumericalError("a rarefaction fan state could not be found (Ψ = " + number(psi) + ")");
    w.states.push_back(State{family < 0 ? invariant - psi : invariant + psi, s.value});
  }
  w.states.push_back(star);
}

void Tracker::emit_fronts(const Material& m, const WaveStates& w, int family, int piece, double t, double X, double x,
                          std::vector<int>& out) {
  const std::size_t first = out.size();
  const std::size_t jumps = w.states.size() - 1;
  for (std::size_t k = 0; k < jumps; ++k) {
    const State& outer = w.states[k];
    const State& inner = w.states[k + 1];
    const int id = new_node(NodeKind::front, piece);
    Node& n = nodes_[id];
    n.family = family;
    n.t0 = t;
    n.X0 = X;
    n.x0 = x;
    n.born = t;
    n.strength = std::abs(wave_strength(m, outer, inner, family));
    n.smooth = emit_smooth_ || (!w.shock && !m.linearly_degenerate());  // a fan's steps are smooth
    if (w.shock) {
      n.front_kind = FrontKind::shock;
      const FrontSpeeds sp =
          family < 0 ? label_jump_speeds(m, outer, inner, family) : label_jump_speeds(m, inner, outer, family);
      n.dXdt = sp.lagrangian;
      n.dxdt = sp.lab;
    } else {
      if (m.linearly_degenerate()) {
        // A linearly degenerate jump moves at the characteristic speed, the same on both sides.
        n.front_kind = FrontKind::contact;
        const FrontSpeeds sp = characteristic_speeds(m, inner, family);
        n.dXdt = sp.lagrangian;
        n.dxdt = sp.lab;
      } else {
        // A fan step moves at the speed the label jump condition gives it, within second
        // order of the mean of the characteristic speeds on its two sides.
        n.front_kind = FrontKind::rarefaction;
        const FrontSpeeds sp =
            family < 0 ? label_jump_speeds(m, outer, inner, family) : label_jump_speeds(m, inner, outer, family);
        n.dXdt = sp.lagrangian;
        n.dxdt = sp.lab;
      }
    }
    out.push_back(id);
    live_fronts_max_ = std::max(live_fronts_max_, ++live_fronts_);
    ++result_.stats.fronts;
  }
  if (!w.shock && !m.linearly_degenerate() && out.size() > first) {
    // A new centred fan: its steps stand for it until one of them interacts.
    int id;
    if (!free_fans_.empty()) {
      id = free_fans_.back();
      free_fans_.pop_back();
    } else {
      id = static_cast<int>(fans_.size());
      fans_.emplace_back();
    }
    CentredFan& f = fans_[id];
    const State& outer = w.states.front();
    const State& star = w.states.back();
    f.t0 = t;
    f.X0 = X;
    f.x0 = x;
    f.family = family;
    f.material = &m;
    f.psi_a = m.riemann_psi(outer.stretch);
    f.psi_b = m.riemann_psi(star.stretch);
    f.j_other = family < 0 ? outer.rapidity + f.psi_a : outer.rapidity - f.psi_a;
    f.speed_a = characteristic_speeds(m, outer, family).lagrangian;
    f.speed_b = characteristic_speeds(m, star, family).lagrangian;
    f.steps = static_cast<int>(out.size() - first);
    f.unsplit = w.unsplit;
    f.capped = w.capped;
    for (std::size_t k = first; k < out.size(); ++k) nodes_[out[k]].fan = id;
  }
  if (live_fronts_ > scene_.solver.max_fronts) {
    recorder_.stop(budget_stop_reason(scene_, Budget::fronts, t));  // the run stops after this interaction
  }
}

void Tracker::reanchor(int id, double t) {
  Node& n = nodes_[id];
  leave_fan(n);
  const double X = n.X_at(t), x = n.x_at(t);
  record_segment(n, t);
  n.t0 = t;
  n.X0 = X;
  n.x0 = x;
  ++n.version;
}

void Tracker::take_in(const std::vector<int>& group, double t, Incoming& in) {
  // Remove the fronts of the group; keep ends and interfaces. Their energy books
  // are closed first, while each front's neighbours are still the states it separated.
  // A rarefaction step that leaves as the only step of its family keeps its age (its
  // fan error goes on growing); otherwise the error it carries is booked now.
  // At an end that holds Ψ (a free end, a traction), a smooth wave goes on as the reflected
  // wave, reconstructed there as it was here: a step that arrives alone is reflected where its
  // characteristic is (shift_reflection), and books what the reflection shifts the reflected
  // wave by (reflection_error) only where it cannot be placed so; steps arriving together book
  // it here. A fan step with no line of its wave next to it books the drift it has carried,
  // not the staircase the reflected wave no longer is. At an end that holds φ (a wall, a
  // piston) the shift the arriving steps take at the reflected wave's head is undone as the
  // reflected steps cross the arriving wave's tail; its books are the crossings'.
  bool holds_psi = false;
  int fronts = 0;
  for (int id : group) {
    const Node& e = nodes_[id];
    if (e.is_end() && e.attach != Attach::body) holds_psi = e.attach == Attach::free || walls_[e.partner].traction;
    fronts += e.kind == NodeKind::front ? 1 : 0;
  }
  const bool lone = fronts == 1;  // one step reflected: see shift_reflection
  for (int id : group) {
    Node& n = nodes_[id];
    const double defect = close_defect(n, t);
    if (n.kind != NodeKind::front) {
      in.released += defect;  // a wave held back here leaves now, late by as much
      in.smooth_in.structure = true;
      continue;
    }
    const int f = n.family > 0 ? 1 : 0;
    in.smooth_in.add(
        f, n.smooth,
        in.families_in[f] == n.piece && converge(nodes_[in.last_in[f]], n, kSuperposed * policy_.fan_step()));
    in.last_in[f] = id;
    in.offset_in[f] += n.offset;
    ++in.count_in[f];
    in.families_in[f] = n.piece;
    in.carried_in += n.carried;
    n.carried = 0.0;
    // A front back from a light piece has its lab line but no label speed: that of its
    // family where it runs (the same on both sides of a linearly degenerate jump).
    const double label_speed = n.dXdt != 0.0 ? n.dXdt : speeds_of(n.right, n.family).lagrangian;
    in.sweep_in += n.strength * std::abs(label_speed);
    in.fastest_in = std::max(in.fastest_in, std::abs(label_speed));
    ++in.fronts_in;
    account_front_end(id, t);
    if (n.front_kind == FrontKind::rarefaction || n.smooth) {
      // The staircase's error, and the least of it and the reconstruction's (fan_error).
      const double staircase = fan_error(id, t, false);
      const double line = reconstruction_error(id, t);
      const double reconstructed =
          std::min(staircase, holds_psi && n.smooth && !(line < kInf) ? drift_error(id, t) : line);
      if (holds_psi && n.smooth) {
        const double shift = reflection_error(id, t);
        if (lone) {
          in.reflect_error[f] = shift;
        } else {
          in.carried_in += ledger_.book_fan(shift);
        }
      }
      in.steps_staircase[f] += staircase;
      if (n.front_kind == FrontKind::rarefaction) {
        ++in.steps_in[f];
        in.steps_born[f] = n.born;
        in.steps_error[f] += reconstructed;
      } else {
        in.steps_taken[f] += reconstructed;
      }
    }
    if (!n.smooth) {
      in.jump_speed[f] = n.dXdt;
      in.jump_since[f] = n.t0;
    } else if (lone && holds_psi && n.prev != kNone && n.next != kNone) {
      // What shift_reflection places the step it becomes by. A C− step arrives at a left end,
      // a C+ step at a right end: behind it is away from the end.
      const bool to_left = n.family < 0;
      const int behind = strip_edge(to_left ? n.next : n.prev, n.family, to_left ? &Node::next : &Node::prev);
      if (is_step(behind, n.family)) in.reflect_width[f] = std::abs(nodes_[behind].X_at(t) - n.X_at(t));
      const Region& ahead_region = to_left ? nodes_[n.prev].right : n.right;
      const Region& behind_region = to_left ? n.right : nodes_[n.prev].right;
      if (ahead_region.material == behind_region.material)
        in.reflect_other_change[f] =
            speeds_of(behind_region, -n.family).lagrangian - speeds_of(ahead_region, -n.family).lagrangian;
      in.reflect_speed[f] = n.dXdt;
    }
  }
  for (int id : group)
    if (nodes_[id].kind == NodeKind::front) {
      const int p = nodes_[id].prev, n = nodes_[id].next;
      link(p, n);
      kill_node(id, t);
    }
}

Tracker::Meeting Tracker::meet(const std::vector<int>& group, double t) const {
  Meeting g;
  g.first = group.front();
  g.last = group.back();
  const Node& nf = nodes_[g.first];
  const Node& nl = nodes_[g.last];
  g.left_boundary = nf.kind == NodeKind::left_end;
  g.right_boundary = nl.kind == NodeKind::right_end;
  if (g.left_boundary && g.right_boundary)
    throw NumericalError("body '" + scene_.bodies[pieces_[nf.piece].body].name + "' at t = " + number(t) +
                         ": a piece of it is compressed to a lab length that double precision does not resolve "
                         "against the time and positions there (its two ends meet to the last digit); an impact "
                         "this strong is beyond what the front tracker can follow");
  // Structural nodes that survive the interaction.
  for (int id : group) {
    const Node& n = nodes_[id];
    if (n.kind == NodeKind::interface) g.interface = id;
    if (n.kind == NodeKind::right_end && id != g.last) g.contact_left = id;
    if (n.kind == NodeKind::left_end && id != g.first) g.contact_right = id;
  }
  // Where the meeting happens in the lab.
  int anchor = g.interface != kNone ? g.interface : g.contact_left != kNone ? g.contact_left : kNone;
  if (anchor == kNone && g.left_boundary) anchor = g.first;
  if (anchor == kNone && g.right_boundary) anchor = g.last;
  if (anchor != kNone) {
    g.x = nodes_[anchor].x_at(t);
  } else {
    double sum = 0.0;
    for (int id : group) sum += nodes_[id].x_at(t);
    g.x = sum / static_cast<double>(group.size());
  }
  // The outer states and the problem they pose.
  g.before = g.left_boundary ? kNone : nf.prev;
  g.after = g.right_boundary ? kNone : g.last;
  if (g.before != kNone) g.left_region = nodes_[g.before].right;
  if (g.after != kNone) g.right_region = nodes_[g.after].right;
  g.left_piece = nf.piece;
  g.right_piece = nl.piece;
  return g;
}

double Tracker::meeting_label(const std::vector<int>& group, int piece, double t) const {
  for (int id : group)
    if (nodes_[id].piece == piece && nodes_[id].kind != NodeKind::front) return nodes_[id].X_at(t);
  double sum = 0.0;
  int count = 0;
  for (int id : group)
    if (nodes_[id].piece == piece) sum += nodes_[id].X_at(t), ++count;
  return sum / count;
}

RiemannSolution Tracker::solve_meeting(const std::vector<int>& group, const Meeting& g, const Incoming& in, double t) {
  RiemannSolution sol;
  // No classical solution: the run stops at t and Tracker::run closes the books there. The
  // errors the fronts taken in carried stay in its bound, and the right state, which the last
  // of them took with it, is put back right of the meeting: on the last end or interface of
  // the group, else on a front of no strength at x.
  const auto require = [&](const Material& limiting) {
    try {
      require_solved(sol, limiting, t, g.x, scene_.units);
    } catch (const InadmissibleError&) {
      ledger_.lose(in.carried_in +
                   ledger_.book_fan(in.steps_error[0] + in.steps_error[1] + in.steps_taken[0] + in.steps_taken[1]));
      if (g.after != kNone && !nodes_[g.after].alive) {
        int holder = kNone;
        for (auto id = group.rbegin(); id != group.rend() && holder == kNone; ++id)
          if (nodes_[*id].alive) holder = *id;
        if (holder == kNone) {
          const double X = meeting_label(group, g.right_piece, t);
          holder = new_node(NodeKind::front, g.right_piece);
          Node& h = nodes_[holder];
          h.front_kind = FrontKind::contact;
          h.family = 1;
          h.t0 = t;
          h.x0 = g.x;
          h.X0 = X;
          ++live_fronts_;
          const int next = nodes_[g.before].next;
          link(g.before, holder);
          link(holder, next);
        }
        nodes_[holder].right = g.right_region;
      }
      throw;
    }
  };
  const Material* mL = g.left_region.material;
  const Material* mR = g.right_region.material;
  if (g.left_boundary || g.right_boundary) {
    const int end = g.left_boundary ? g.first : g.last;
    const Node& e = nodes_[end];
    const Material& m = g.left_boundary ? *mR : *mL;
    const State& st = g.left_boundary ? g.right_region.state : g.left_region.state;
    const Side side = g.left_boundary ? Side::right : Side::left;
    if (e.attach == Attach::boundary && walls_[e.partner].traction) {
      sol = solve_traction_end(m, st, side, walls_[e.partner].pressure);
    } else if (e.attach == Attach::boundary) {
      const Wall& w = walls_[e.partner];
      const double min_p = w.bonded ? m.cavitation_pressure() : std::max(0.0, m.cavitation_pressure());
      sol = solve_wall(m, st, side, w.rapidity, min_p);
    } else {
      sol = solve_free_end(m, st, side);
    }
    require(m);
    if (sol.parted && e.attach == Attach::boundary) {
      const int wall = e.partner;
      Wall& w = walls_[wall];
      w.attached = kNone;
      ++w.version;            // events of the contact are stale,
      schedule_piston(wall);  // but not a piston's next change of speed
      set_attach(end, Attach::free, kNone, t);
      event(t, "separation", g.x, {piece_body_name(e.piece)});
    }
  } else {
    double min_p;
    if (g.contact_left != kNone) {
      min_p = std::max({0.0, mL->cavitation_pressure(), mR->cavitation_pressure()});
    } else {
      min_p = std::max(mL->cavitation_pressure(), mR->cavitation_pressure());
    }
    sol = solve_riemann(*mL, g.left_region.state, *mR, g.right_region.state, min_p);
    require(sol.status == Status::out_of_range && mR->psi_max() < mL->psi_max() ? *mR : *mL);
    const int holder = g.interface != kNone ? g.interface : g.contact_left;
    if (holder != kNone && !sol.parted) hold_back_weak_wave(sol, g.left_region, g.right_region, holder, min_p, t);
  }

  return sol;
}

int Tracker::keep_droplet(const Meeting& g, RiemannSolution& sol, double XL, double t) {
  const Material* mL = g.left_region.material;
  const Material* mR = g.right_region.material;
  // A crack this close to a free end would leave a droplet: the droplet stays with the
  // rest of the piece (see absorb_droplet), and only the rest's wave is emitted.
  int droplet = 0;
  if (sol.parted && !g.left_boundary && !g.right_boundary && g.contact_left == kNone && g.interface == kNone &&
      g.left_piece == g.right_piece && mL == mR) {
    const int body = pieces_[g.left_piece].body;
    policy_.at_crack(body, body_pieces_[body]);
    droplet = droplet_side(g.left_piece, XL, t);
    if (droplet != 0) {
      const State& kept = droplet < 0 ? sol.right : sol.left;  // the rest's released state
      const int end = droplet < 0 ? pieces_[g.left_piece].left_end : pieces_[g.left_piece].right_end;
      if (!room_for_end(g.left_piece, droplet, g.x + droplet * droplet_lab_length(end, XL, kept, t), t)) droplet = 0;
    }
    if (droplet != 0) {
      const State& kept = droplet < 0 ? sol.right : sol.left;
      absorb_droplet(g.left_piece, droplet, g.before, XL, g.x, droplet < 0 ? g.left_region : g.right_region, kept, t);
      (droplet < 0 ? sol.left : sol.right) = kept;
      sol.parted = false;
    }
  }

  return droplet;
}

void Tracker::emit_waves(const Meeting& g, const RiemannSolution& sol, int droplet, double XL, double XR, Incoming& in,
                         double t) {
  const Material* mL = g.left_region.material;
  const Material* mR = g.right_region.material;
  // Emit the waves. Each is smooth as smooth_in says, or, with no front coming in, if a piston
  // ramp's step starts it (handle sets emit_smooth_ for it); a crack inside a piece makes
  // jumps (a body leaving a wall or another body reflects a smooth wave as a free end does).
  const bool crack = sol.parted && !g.left_boundary && !g.right_boundary && g.contact_left == kNone;
  bool smooth_out[2];
  for (int f = 0; f < 2; ++f) {
    smooth_out[f] = !crack && (in.fronts_in > 0 ? in.smooth_in.out(f) : emit_smooth_);
    if (crack) {
      in.steps_error[f] = in.steps_staircase[f];  // a crack took the steps in
    } else if (!smooth_out[f]) {
      in.steps_error[f] += in.steps_taken[f];
    }
  }
  // A smooth wave's step comes in, or a piston ramp's step starts one: what leaves are steps of
  // a smooth wave, not new centred fans.
  const bool of_smooth_wave = in.smooth_in.any_smooth || (in.fronts_in == 0 && emit_smooth_);
  emitted_left_.clear();
  emitted_right_.clear();
  WaveStates& wl = wave_left_;
  WaveStates& wr = wave_right_;
  wl.states.clear();
  wr.states.clear();
  if (!g.left_boundary && droplet >= 0) {
    emit_smooth_ = smooth_out[0];
    emit_wave(*mL, g.left_region.state, sol.left, -1, !of_smooth_wave, g.left_piece, t, XL, g.x, wl, emitted_left_);
  }
  if (!g.right_boundary && droplet <= 0) {
    emit_smooth_ = smooth_out[1];
    emit_wave(*mR, g.right_region.state, sol.right, +1, !of_smooth_wave, g.right_piece, t, XR, g.x, wr, emitted_right_);
    // Emitted from the outer state inwards; in space the C+ fan's head (next to the
    // right state) is its rightmost front.
    std::reverse(emitted_right_.begin(), emitted_right_.end());
  }
  emit_smooth_ = false;
  if (of_smooth_wave) {
    // What a smooth wave's step becomes is a step of that wave, not a centred fan of its own.
    for (int id : emitted_left_) leave_fan(nodes_[id]);
    for (int id : emitted_right_) leave_fan(nodes_[id]);
    set_offsets(g.first, g.last, g.left_boundary, g.right_boundary, in.offset_in, in.count_in, t);
  }

  for (int f = 0; f < 2; ++f) {
    const std::vector<int>& out = f == 0 ? emitted_left_ : emitted_right_;
    if (in.smooth_in.any_smooth && in.jump_speed[f] < kInf && out.size() == 1) {
      Node& jump = nodes_[out.front()];  // a jump that met a smooth wave's step (Node::kink)
      jump.kink = std::abs(jump.dXdt - in.jump_speed[f]);
      jump.kink_dt = t - in.jump_since[f];
    }
    if (in.steps_in[f] == 1 && out.size() == 1 && nodes_[out.front()].front_kind == FrontKind::rarefaction) {
      // A step of an older fan goes on: no new centred fan here.
      nodes_[out.front()].born = in.steps_born[f];
      leave_fan(nodes_[out.front()]);
    } else {
      in.carried_in += ledger_.book_fan(in.steps_error[f]);
    }
  }
  share_carried(in.carried_in, in.sweep_in, in.fronts_in, in.fastest_in, in.released);
}

void Tracker::settle_and_schedule(const Meeting& g, int interface, bool parted_inside, int droplet, int right_holder,
                                  bool parted, double t) {
  // Structural nodes move with the material next to them; an end whose lab speed
  // changes may now close (or open) a gap.
  touched_.clear();
  bool ends_moved = false;
  auto settle = [&](int id) {
    if (id == kNone || !nodes_[id].alive) return;
    const Node& n = nodes_[id];
    const Region& r = n.kind == NodeKind::right_end ? nodes_[n.prev].right : n.right;
    const double v = std::tanh(r.state.rapidity);
    if (v == n.dxdt) return;
    reanchor(id, t);
    nodes_[id].dxdt = v;
    if (nodes_[id].is_end()) ends_moved = true;
  };
  const int new_piece = parted_inside ? static_cast<int>(pieces_.size()) - 1 : kNone;
  settle(interface);
  if (g.left_boundary) settle(g.first);
  if (g.right_boundary) settle(g.last);
  settle(g.contact_left);
  settle(g.contact_right);
  if (parted_inside) {
    settle(pieces_[g.left_piece].right_end);
    settle(pieces_[new_piece].left_end);
  }
  if (droplet < 0) settle(pieces_[g.left_piece].left_end);
  if (droplet > 0) settle(pieces_[g.left_piece].right_end);

  // New meetings: each node of the rebuilt stretch with its right neighbour.
  touched_.push_back(g.left_boundary ? g.first : droplet < 0 ? pieces_[g.left_piece].left_end : g.before);
  touched_.insert(touched_.end(), emitted_left_.begin(), emitted_left_.end());
  if (right_holder != kNone) touched_.push_back(right_holder);
  touched_.insert(touched_.end(), emitted_right_.begin(), emitted_right_.end());
  if (interface != kNone) touched_.push_back(interface);
  std::sort(touched_.begin(), touched_.end());
  touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
  for (int id : touched_) schedule_meet(id);
  for (int id : emitted_left_) merge_neighbours(id, t);
  for (int id : emitted_right_) merge_neighbours(id, t);
  for (int id : emitted_left_) merge_nearby(id, t);
  for (int id : emitted_right_) merge_nearby(id, t);
  if (ends_moved || parted || droplet != 0)
    for (int p : {g.left_piece, g.right_piece, new_piece})
      if (p != kNone) schedule_gaps_around(p);
  // Light pieces take what was emitted into them off the node list, and their next arrivals
  // follow their ends.
  if (is_light(g.left_piece)) absorb_light(g.left_piece, t);
  if (g.right_piece != g.left_piece && is_light(g.right_piece)) absorb_light(g.right_piece, t);
}

int Tracker::link_waves(const Meeting& g, const RiemannSolution& sol, int droplet, double XL, bool smooth_in,
                        int& interface, bool& parted_inside, double t) {
  parted_inside = !g.left_boundary && !g.right_boundary && sol.parted && g.contact_left == kNone;
  if (!g.left_boundary && !g.right_boundary && sol.parted && g.contact_left != kNone) {
    // Two bodies in contact separate.
    set_attach(g.contact_left, Attach::free, kNone, t);
    set_attach(g.contact_right, Attach::free, kNone, t);
    event(t, "separation", g.x, {piece_body_name(g.left_piece), piece_body_name(g.right_piece)});
  }
  // Link: [before] − fronts [centre] + fronts [right state holder]. The region right of the
  // C− fronts is the left star state, left of the C+ fronts the right star state.
  const int cursor = link_left_waves(g, droplet);
  int right_holder = right_state_holder(g, interface, droplet, cursor);
  if (parted_inside) right_holder = crack_at_meeting(g, sol, XL, smooth_in, cursor, interface, t);
  if (right_holder != kNone) link_right_waves(g, right_holder);
  return right_holder;
}

int Tracker::link_left_waves(const Meeting& g, int droplet) {
  const Material* mL = g.left_region.material;
  const WaveStates& wl = wave_left_;
  // Left part: before → C− fronts → (interface | contact_left | new right end | first C+ front ...)
  int cursor = g.left_boundary ? g.first : droplet < 0 ? pieces_[g.left_piece].left_end : g.before;
  for (std::size_t k = 0; k < emitted_left_.size(); ++k) {
    const int id = emitted_left_[k];
    nodes_[id].right = Region{mL, wl.states[k + 1]};
    const int next = nodes_[cursor].next;
    link(cursor, id);
    link(id, next);
    cursor = id;
  }
  return cursor;
}

int Tracker::right_state_holder(const Meeting& g, int interface, int droplet, int cursor) const {
  if (g.left_boundary) return g.first;
  if (g.right_boundary) return kNone;
  if (interface != kNone) return interface;
  if (g.contact_right != kNone) return g.contact_right;
  if (droplet > 0) return kNone;  // the last C− front holds the droplet's state, up to the right end
  return cursor;                  // plain crossing: the C+ fronts follow the C− fronts
}

int Tracker::crack_at_meeting(const Meeting& g, const RiemannSolution& sol, double XL, bool smooth_in, int cursor,
                              int& interface, double t) {
  // The body parts here (cavitation, or an interface that cannot hold).
  const Material* mR = g.right_region.material;
  const int left_of_crack = cursor;
  int right_of_crack = nodes_[cursor].next;
  if (interface != kNone) {
    right_of_crack = nodes_[interface].next;
    link(nodes_[interface].prev, right_of_crack);
    kill_node(interface, t);
    interface = kNone;
  }
  const Region right_first = emitted_right_.empty() ? g.right_region : Region{mR, wave_right_.states.back()};
  split_piece(left_of_crack, right_of_crack, sol.left, sol.right, Region{}, right_first, t, XL, g.x);
  const int right_holder = pieces_.back().left_end;
  event(t, "cavitation", g.x, {piece_body_name(g.left_piece)});
  if (smooth_in) {
    // A smooth wave's step decided this crack: a finer step would part the body elsewhere.
    if (qualitative_cracks_++ == 0) qualitative_body_ = pieces_[g.left_piece].body;
    qualitative_since_ = std::min(qualitative_since_, t);
  } else if (droplets_ > 0) {
    // The waves of a kept droplet (or its absence) reach this crack: with a finer tolerance the
    // droplet would have broken off and come back, and the body parts elsewhere or not at all.
    ++cracks_after_droplets_;
    qualitative_since_ = std::min(qualitative_since_, t);
  }
  return right_holder;
}

void Tracker::link_right_waves(const Meeting& g, int right_holder) {
  const Material* mR = g.right_region.material;
  const WaveStates& wr = wave_right_;
  const std::size_t m = emitted_right_.size();
  nodes_[right_holder].right = m > 0 ? Region{mR, wr.states.back()} : g.right_region;
  int c = right_holder;
  for (std::size_t k = 0; k < m; ++k) {
    const int id = emitted_right_[k];
    // C+ fronts listed left to right: front k separates states m-k and m-k-1.
    nodes_[id].right = Region{mR, wr.states[m - k - 1]};
    nodes_[id].piece = nodes_[c].piece;
    const int next = nodes_[c].next;
    link(c, id);
    link(id, next);
    c = id;
  }
}

void Tracker::resolve_group(std::vector<int>& group, double t) {
  // Interactions that keep recreating themselves at one instant (fronts emitted converging, as a
  // fan's steps would on a law whose inflections were missed) stop the run.
  if (t != last_interaction_t_) {
    last_interaction_t_ = t;
    interactions_at_this_t_ = 0;
  } else if (++interactions_at_this_t_ > 100 * (static_cast<long>(nodes_.size()) + 100)) {
    throw NumericalError("the interactions at t = " + number(t) +
                         " do not advance in time: the waves of a material keep recreating each other there"
                         " (an inflection of its law narrower than the scan of Material::inflection_logs?)");
  }
  policy_.after_interaction(live_fronts_, light_fronts_, light_bodies_);
  if (++result_.stats.interactions > scene_.solver.max_interactions) {
    recorder_.stop(budget_stop_reason(scene_, Budget::interactions, t));  // the run stops after this interaction
  }
  const Meeting g = meet(group, t);
  const Node& nf = nodes_[g.first];
  const Node& nl = nodes_[g.last];
  // Walls attached at either end lose their current contact pressure now.
  if (g.left_boundary && nf.attach == Attach::boundary) flush_wall(nf.partner, t);
  if (g.right_boundary && nl.attach == Attach::boundary) flush_wall(nl.partner, t);

  // What the fronts of the group bring (their books closed, their errors and ages, which
  // waves go on smooth), and the group without them.
  Incoming in;
  take_in(group, t, in);
  RiemannSolution sol = solve_meeting(group, g, in, t);

  // A crack this close to a free end would leave a droplet: the droplet stays with the rest of
  // the piece (see absorb_droplet), and only the rest's wave is emitted.
  const double XL = meeting_label(group, g.left_piece, t), XR = meeting_label(group, g.right_piece, t);
  const int droplet = keep_droplet(g, sol, XL, t);  // −1: the droplet is left of the crack, +1: right of it
  emit_waves(g, sol, droplet, XL, XR, in, t);
  // Link: [before] − fronts [centre] + fronts [right state holder]; a crack splits the piece
  // (and an interface there goes).
  int interface = g.interface;
  bool parted_inside = false;
  const int right_holder = link_waves(g, sol, droplet, XL, in.smooth_in.any_smooth, interface, parted_inside, t);
  if (g.left_boundary != g.right_boundary) shift_reflection(g, in, t);
  settle_and_schedule(g, interface, parted_inside, droplet, right_holder, sol.parted, t);
}

/// The errors the fronts of a group carried in (and what their fan steps booked there) go on
/// with the waves it emitted, each taking a share in proportion to the rate at which it
/// sweeps L1, strength × |dX/dt|. A lone wave that splits (a transmission and a reflection
/// at an interface or a contact, a reflection at an end) hands on its error times the ratio
/// of the outgoing rates to its own: the linear scattering of a small error, measured rather
/// than assumed, so that an error carried into a softer body grows as the wave does. Where
/// several fronts meet, the error does not shrink with their cancellation, only with the
/// label speeds (the ratio is at least the slowest outgoing over the fastest incoming speed,
/// at most 1, so that an error carried from a fast body into a slow one shrinks with it); a
/// wave that sets off far stronger ones (a front that makes an interface part) hands on at
/// most kMaxScattering times its error. A wave held back at the node (see
/// hold_back_weak_wave) leaves now, late: the error it booked while held goes on with the
/// outgoing waves as well. With no wave out, it all stays in the bound as it was.
void Tracker::share_carried(double carried_in, double sweep_in, int fronts_in, double fastest_in, double released) {
  if (carried_in == 0.0 && released == 0.0) return;
  double sweep_out = 0.0, slowest_out = kInf;
  for (const std::vector<int>* out : {&emitted_left_, &emitted_right_})
    for (int id : *out) {
      sweep_out += nodes_[id].strength * std::abs(nodes_[id].dXdt);
      if (nodes_[id].strength > 0.0) slowest_out = std::min(slowest_out, std::abs(nodes_[id].dXdt));
    }
  if (!(sweep_out > 0.0) || !std::isfinite(sweep_out)) {
    ledger_.lose(carried_in);  // a held-back wave's error stays with the defects
    return;
  }
  double ratio = sweep_in > 0.0 ? sweep_out / sweep_in : 1.0;
  // Several waves in: their outgoing waves may partly cancel where the exact ones, each
  // arriving at its own moment, do not. Each wave's own scattering keeps at least its
  // strength (reflected plus transmitted strength is never less than the incident), so
  // its error moves on at least in the ratio of the label speeds; only that may shrink it.
  if (fronts_in > 1 && fastest_in > 0.0) ratio = std::max(ratio, std::min(1.0, slowest_out / fastest_in));
  ratio = std::min(ratio, kMaxScattering);
  const double per_sweep = (ledger_.scale(carried_in, ratio) + ledger_.release(released)) / sweep_out;
  for (const std::vector<int>* out : {&emitted_left_, &emitted_right_})
    for (int id : *out) nodes_[id].carried += per_sweep * nodes_[id].strength * std::abs(nodes_[id].dXdt);
}

/// Bressan's idea at an interface or a contact, where a wave arriving splits in two: when
/// one of the outgoing waves is weaker than the threshold, it is not emitted. The side it
/// would have crossed keeps its state, the other side's wave is re-solved to the same
/// velocity (so the bodies stay together and every lab position stays consistent), and
/// the pressure jump left at the node is the wave held back. It leaves with the next wave
/// that reaches the node, which solves the node's full Riemann problem again; until then
/// it costs its strength times the distance it would have travelled.
void Tracker::hold_back_weak_wave(RiemannSolution& sol, const Region& left, const Region& right, int holder,
                                  double min_pressure, double t) {
  const double weak_left = std::abs(wave_strength(*left.material, left.state, sol.left, -1));
  const double weak_right = std::abs(wave_strength(*right.material, right.state, sol.right, +1));
  const double weaker = std::min(weak_left, weak_right);
  if (!(weaker < policy_.weak_wave()) || weaker == 0.0) return;
  const bool drop_left = weak_left <= weak_right;
  const Region& kept = drop_left ? left : right;  // the side whose wave is held back keeps its state
  const Region& moved = drop_left ? right : left;
  if (kept.material->pressure(kept.state.stretch) < min_pressure) return;  // it would part: solve in full
  const RiemannSolution other =
      solve_wall(*moved.material, moved.state, drop_left ? Side::right : Side::left, kept.state.rapidity, -kInf);
  if (other.status != Status::ok || other.pressure < min_pressure) return;
  (drop_left ? sol.left : sol.right) = kept.state;
  (drop_left ? sol.right : sol.left) = other.left;
  Node& node = nodes_[holder];
  // The wave held back is missing on its side, and the re-solved wave on the other side is off
  // by as much (a velocity matched instead of a pressure): both regions grow at their speeds.
  node.defect_rate = weaker * (std::abs(characteristic_speed(*kept.material, kept.state, drop_left ? -1 : +1)) +
                               std::abs(characteristic_speed(*moved.material, moved.state, drop_left ? +1 : -1)));
  node.defect_since = t;
  const int far_piece = node.kind == NodeKind::right_end ? nodes_[node.partner].piece : node.piece;
  node.defect_cap = weaker * (piece_length(node.piece) + piece_length(far_piece));
  ++suppressed_;
}

void Tracker::shift_reflection(const Meeting& g, const Incoming& in, double t) {
  const bool left = g.left_boundary;
  const std::vector<int>& out = left ? emitted_right_ : emitted_left_;
  const int f_in = left ? 0 : 1;
  if (!place_reflection(g, in, t)) {
    const double unplaced = in.reflect_error[f_in];
    if (unplaced > 0.0) {
      const double booked = ledger_.book_fan(unplaced);
      if (out.empty()) {
        ledger_.lose(booked);
      } else {
        nodes_[out.front()].carried += booked;
      }
    }
  }
}

bool Tracker::place_reflection(const Meeting& g, const Incoming& in, double t) {
  const bool left = g.left_boundary;
  const std::vector<int>& out = left ? emitted_right_ : emitted_left_;
  const int f_in = left ? 0 : 1;
  if (out.size() != 1 || in.count_in[f_in] != 1 || in.count_in[1 - f_in] != 0) return false;
  if (!(in.reflect_width[f_in] < kInf) || in.reflect_speed[f_in] == 0.0) return false;
  Node& end = nodes_[left ? g.first : g.last];
  // An end that moves with the material: a free end or a traction (at a wall or a piston the
  // arriving step's lag and the reflected step's cancel).
  if (!end.is_end() ||
      !(end.attach == Attach::free || (end.attach == Attach::boundary && walls_[end.partner].traction)))
    return false;
  Node& r = nodes_[out.front()];
  if (!r.smooth || r.prev == kNone || r.next == kNone) return false;
  const Region& behind = left ? nodes_[r.prev].right : r.right;  // the end's side
  const Region& ahead = left ? r.right : nodes_[r.prev].right;
  if (behind.material != ahead.material || behind.material->linearly_degenerate()) return false;
  const int family_in = left ? -1 : +1;
  const double speed_in = std::abs(in.reflect_speed[f_in]), speed_out = std::abs(r.dXdt);
  if (!(speed_in > 0.0 && speed_out > 0.0)) return false;
  const double closing = speed_in + speed_out;
  // The strip of the arriving wave behind the step, and of the reflected wave it becomes.
  const double width_in = in.reflect_width[f_in], width_out = width_in * speed_out / speed_in;
  // Over the half strip ahead of the reflected wave's first step the staircase holds the
  // plateau's value where the wave has a quarter of that step's jump more on average: the
  // arriving step moves that much off its characteristic's speed for the time it takes to
  // cross it (its lag, in X), and arrives late by as much over its speed.
  const double change_in = speeds_of(behind, family_in).lagrangian - speeds_of(ahead, family_in).lagrangian;
  const double lag_in = -0.25 * change_in * 0.5 * width_out / closing;
  const double late = (family_in < 0 ? 1.0 : -1.0) * lag_in / speed_in;
  // The reflected step, leaving the arriving wave at its tail, will gain as much the other way
  // over the half strip behind that wave's last step.
  const double lag_out = 0.25 * in.reflect_other_change[f_in] * 0.5 * width_in / closing;
  const double d = r.dXdt * late - lag_out;
  const double X = r.X_at(t);
  const int inward = left ? r.next : r.prev;
  const double room = std::abs(nodes_[inward].X_at(t) - X);
  if (!((left ? d : -d) >= 0.0) || !(std::abs(d) < kReflectionRoom * room)) return false;
  // The labels it passes over change state: what that makes of the totals is booked with what
  // the smooth steps make. The lab positions keep the longer region ahead of it as it was,
  // and the end, which moved at its old velocity while the step was late, takes the
  // difference (third order in the step).
  const Region::Books& b_behind = books_of(behind);
  const Region::Books& b_ahead = books_of(ahead);
  const double moved = left ? d : -d;  // labels taken from the region ahead into the one behind
  waves_energy_ += moved * (b_behind.energy - b_ahead.energy);
  waves_momentum_ += moved * (b_behind.momentum - b_ahead.momentum);
  const double dx = d * label_density(ahead.state);
  end.x0 = end.x_at(t) + d * (label_density(ahead.state) - label_density(behind.state));
  end.X0 = end.X_at(t);
  end.t0 = t;
  ++end.version;
  r.x0 = r.x_at(t) + dx;
  r.X0 = X + d;
  r.t0 = t;
  ++r.version;
  return true;
}

void Tracker::set_offsets(int first, int last, bool left_boundary, bool right_boundary, const double offset_in[2],
                          const int count_in[2], double t) {
  if (left_boundary != right_boundary) {
    // A reflection at an end: the one step that came in leaves as the one step of the other
    // family, its value mirrored by a wall or piston and kept by a free end; a ramping piston
    // adds twice what its ramp's rapidity now is beyond the staircase step it is on.
    const std::vector<int>& out = left_boundary ? emitted_right_ : emitted_left_;
    const int f_in = left_boundary ? 0 : 1;
    const Node& end = nodes_[left_boundary ? first : last];
    if (out.size() == 1 && count_in[0] == 0 && count_in[1] == 0 && nodes_[out.front()].smooth &&
        end.attach == Attach::boundary && walls_[end.partner].motion.ramps) {
      // A ramping piston's own step, taken when the ramp's velocity is the mean of the two
      // steps of its staircase: its value is the ramp's rapidity then, not the mean of theirs
      // (twice the difference, in the invariant of a simple wave).
      Node& step = nodes_[out.front()];
      const Wall& w = walls_[end.partner];
      const double mean = 0.5 * (w.rapidity + w.motion.rapidities[w.segment - 1]);
      step.offset = 2.0 * (ramp_rapidity(w.motion.row_times, w.motion.row_rapidities, t) - mean);
      return;
    }
    if (out.size() != 1 || count_in[f_in] != 1 || count_in[1 - f_in] != 0) return;
    double offset = offset_in[f_in];
    Node& step = nodes_[out.front()];
    if (end.attach == Attach::boundary && !walls_[end.partner].traction) {
      const Wall& w = walls_[end.partner];
      offset = -offset;
      if (w.motion.ramps) {
        const double ahead = 2.0 * (ramp_rapidity(w.motion.row_times, w.motion.row_rapidities, t) - w.rapidity);
        offset += ahead;
        // Until the piston's next step, the region it leaves behind the step holds the
        // staircase's value, off by up to `ahead` from the ramp's over what the step sweeps.
        const double until = std::min(w.next_change(), scene_.t_end) - t;
        const double error = 0.5 * std::abs(ahead) * std::abs(step.dXdt) * std::max(0.0, until);
        step.carried += ledger_.book_fan(error);
      }
    }
    if (step.smooth) step.offset = offset;
    return;
  }
  // A crossing or a transmission: each family's one step goes on with its value.
  for (int f = 0; f < 2; ++f) {
    const std::vector<int>& out = f == 0 ? emitted_left_ : emitted_right_;
    if (out.size() == 1 && count_in[f] == 1 && nodes_[out.front()].smooth) nodes_[out.front()].offset = offset_in[f];
  }
}

}  // namespace rigidity::characteristics
