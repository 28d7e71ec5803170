// Walls, pistons, gaps between bodies, contacts and cracks: the rare events and the ends of pieces.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "tracker.hpp"

namespace rigidity::characteristics {

bool Tracker::valid(const Event& e) const {
  switch (e.type) {
    case EventType::resolve: return nodes_[e.a].alive && nodes_[e.a].version == e.va;
    case EventType::gap:
      return nodes_[e.a].alive && nodes_[e.b].alive && nodes_[e.a].version == e.va && nodes_[e.b].version == e.vb &&
             nodes_[e.a].attach == Attach::free && nodes_[e.b].attach == Attach::free;
    case EventType::wall_gap:
      return nodes_[e.a].alive && nodes_[e.a].version == e.va && walls_[e.b].version == e.vb &&
             nodes_[e.a].attach == Attach::free;
    case EventType::piston: return walls_[e.a].version == e.va;
    case EventType::arrival: return is_light(e.a) && light_[static_cast<std::size_t>(e.a)].version == e.va;
  }
  return false;
}

namespace {
/// Two things that touch and close no faster than the round-off of their speeds (the two
/// free surfaces of a contact that has just parted at zero pressure, equal speeds but for the
/// last bit) are not to meet again at this instant, which would part them again, and so on
/// without end: they move on together until something changes their speeds.
bool closing_by_round_off(double closing, double x1, double x2) { return closing <= 16.0 * kEps && touching(x1, x2); }
}  // namespace

void Tracker::schedule_gap(int left_piece, int right_piece) {
  const int a = pieces_[left_piece].right_end, b = pieces_[right_piece].left_end;
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  if (na.attach != Attach::free || nb.attach != Attach::free) return;
  const double closing = na.dxdt - nb.dxdt;
  if (!(closing > 0.0)) return;
  const double t_ref = std::max(na.t0, nb.t0);
  if (closing_by_round_off(closing, na.x_at(t_ref), nb.x_at(t_ref))) return;
  const double t = t_ref + std::max(0.0, nb.x_at(t_ref) - na.x_at(t_ref)) / closing;
  if (t <= scene_.t_end) push(t, EventType::gap, a, b, na.version, nb.version);
}

void Tracker::schedule_wall_gap(int side) {
  const Wall& w = walls_[side];
  if (!w.present || order_.empty() || w.attached != kNone) return;
  const int end = side == 0 ? pieces_[order_.front()].left_end : pieces_[order_.back()].right_end;
  const Node& n = nodes_[end];
  if (n.attach != Attach::free) return;
  // Closing speed of the end towards the wall.
  const double closing = side == 0 ? w.velocity() - n.dxdt : n.dxdt - w.velocity();
  if (!(closing > 0.0)) return;
  const double t_ref = std::max(n.t0, w.t0);
  if (closing_by_round_off(closing, n.x_at(t_ref), w.x_at(t_ref))) return;
  const double distance = side == 0 ? n.x_at(t_ref) - w.x_at(t_ref) : w.x_at(t_ref) - n.x_at(t_ref);
  const double t = t_ref + std::max(0.0, distance) / closing;
  if (t <= scene_.t_end && t <= w.next_change()) push(t, EventType::wall_gap, end, side, n.version, w.version);
}

void Tracker::schedule_piston(int side) {
  const Wall& w = walls_[side];
  const double t = w.next_change();
  if ((w.present || w.traction) && t <= scene_.t_end) push(t, EventType::piston, side, 0, w.version, 0);
}

void Tracker::schedule_gaps_around(int piece) {
  const auto it = std::find(order_.begin(), order_.end(), piece);
  if (it == order_.end()) return;
  const std::size_t i = static_cast<std::size_t>(it - order_.begin());
  if (i > 0) schedule_gap(order_[i - 1], piece);
  if (i + 1 < order_.size()) schedule_gap(piece, order_[i + 1]);
  if (i == 0) schedule_wall_gap(0);
  if (i + 1 == order_.size()) schedule_wall_gap(1);
}

void Tracker::handle(const Event& e) {
  const double t = e.t;
  switch (e.type) {
    case EventType::resolve: resolve(e.a, e.a, t); break;
    case EventType::arrival: arrive(e.a, e.b, t); break;
    case EventType::gap: {
      const double x = 0.5 * (nodes_[e.a].x_at(t) + nodes_[e.b].x_at(t));
      if (rejoin(e.a, e.b, t, x)) break;
      set_attach(e.a, Attach::body, e.b, t);
      set_attach(e.b, Attach::body, e.a, t);
      event(t, "contact", x, {piece_body_name(nodes_[e.a].piece), piece_body_name(nodes_[e.b].piece)});
      resolve(e.a, e.b, t);
      break;
    }
    case EventType::wall_gap: {
      Wall& w = walls_[e.b];
      w.attached = e.a;
      w.pressure_since = t;
      set_attach(e.a, Attach::boundary, e.b, t);
      event(t, "contact", w.x_at(t), {piece_body_name(nodes_[e.a].piece)});
      resolve(e.a, e.a, t);
      break;
    }
    case EventType::piston: {
      Wall& w = walls_[e.a];
      flush_wall(e.a, t);
      if (w.traction) {  // the end's pressure changes: its Riemann problem anew
        ++w.segment;
        w.pressure = w.pressures[w.segment];
        ++w.version;
        schedule_piston(e.a);
        resolve(w.attached, w.attached, t);
        break;
      }
      w.x0 = w.x_at(t);
      w.t0 = t;
      ++w.segment;
      w.rapidity = w.motion.rapidities[w.segment];
      ++w.version;
      schedule_piston(e.a);
      if (w.attached != kNone) {
        emit_smooth_ = w.motion.ramps;
        resolve(w.attached, w.attached, t);
        emit_smooth_ = false;
      } else {
        schedule_wall_gap(e.a);
      }
      break;
    }
  }
}

/// Two pieces of one body that parted at a crack meet again at it: the void closes
/// and they are one piece again, with a jump at the old crack resolved at once.
/// Returns false if the ends do not belong together (different bodies, or not the
/// two faces of one crack).
bool Tracker::rejoin(int right_end, int left_end, double t, double x) {
  const int a = nodes_[right_end].piece, b = nodes_[left_end].piece;
  if (pieces_[a].body != pieces_[b].body) return false;
  const double X = nodes_[right_end].X_at(t);
  if (std::abs(nodes_[left_end].X_at(t) - X) > 8.0 * kEps * (1.0 + std::abs(X))) return false;

  const int junction = new_node(NodeKind::front, a);
  Node& j = nodes_[junction];
  j.front_kind = FrontKind::contact;
  j.t0 = t;
  j.X0 = X;
  j.x0 = x;
  j.right = nodes_[left_end].right;
  ++live_fronts_;
  const int before = nodes_[right_end].prev, after = nodes_[left_end].next;
  kill_node(right_end, t);
  kill_node(left_end, t);
  link(before, junction);
  link(junction, after);
  for (int n = junction; n != kNone; n = nodes_[n].next) nodes_[n].piece = a;
  pieces_[a].right_end = pieces_[b].right_end;
  pieces_[b].left_end = pieces_[b].right_end = kNone;  // gone
  --body_pieces_[pieces_[a].body];
  order_.erase(std::find(order_.begin(), order_.end(), b));
  event(t, "rejoin", x, {piece_body_name(a)});
  resolve(junction, junction, t);
  schedule_gaps_around(a);
  return true;
}

/// A crack closer to a free end of its piece than the droplet limit (ResolutionPolicy::droplet_limit: the
/// resolution × the droplet scale × the body's natural length) would leave a droplet. Which side, if any (−1: the
/// droplet is left of label X, +1: right of it; 0: no droplet, or it holds an interface or touches something).
int Tracker::droplet_side(int piece, double X, double t) const {
  const Piece& p = pieces_[piece];
  const double limit = policy_.droplet_limit(p.body, scene_.bodies[p.body].natural_length());
  const double left = X - nodes_[p.left_end].X_at(t), right = nodes_[p.right_end].X_at(t) - X;
  const int side = left <= right ? -1 : +1;
  if (!(std::min(left, right) < limit)) return 0;
  const int end = side < 0 ? p.left_end : p.right_end;
  if (nodes_[end].attach != Attach::free) return 0;
  for (int n = side < 0 ? nodes_[end].next : nodes_[end].prev; n != kNone && !nodes_[n].is_end();
       n = side < 0 ? nodes_[n].next : nodes_[n].prev) {
    const double Xn = nodes_[n].X_at(t);
    if (side < 0 ? Xn > X : Xn < X) break;
    if (nodes_[n].kind == NodeKind::interface) return 0;
  }
  return side;
}

/// The droplet model. Where a body that carries no tension cracks so close to a free end
/// that the piece broken off would be shorter than the tolerance allows for (droplet_side),
/// the droplet stays with the rest of the piece: it takes the state the rest is released
/// to at the crack, its own waves are dropped, and only the rest's wave leaves the crack,
/// which is exact. Without it a spray of ever smaller droplets (a rigid fluid's collisions
/// knock pieces off like a Newton's cradle) would ring and collide at a cost without bound.
/// What it changes is booked: the droplet's length times |δφ| + |δΨ| of each of its regions.
/// `before` is the node left of the crack, `straddling` the droplet's region at the crack.
void Tracker::absorb_droplet(int piece, int side, int before, double X, double x, const Region& straddling,
                             const State& kept, double t) {
  const Material& m = *straddling.material;
  const double psi_kept = memo_->psi(m, kept.stretch);
  const double energy_kept = energy_density(m, kept), momentum_kept = momentum_density(m, kept);
  auto book = [&](const Region& r, double length) {
    ledger_.book_droplet(std::abs(length) * (std::abs(r.state.rapidity - kept.rapidity) +
                                             std::abs(memo_->psi(*r.material, r.state.stretch) - psi_kept)));
    droplet_energy_ += length * (energy_kept - energy_density(*r.material, r.state));
    droplet_momentum_ += length * (momentum_kept - momentum_density(*r.material, r.state));
  };
  // The fronts inside the droplet: between the left end and the crack, or the crack and the right end.
  std::vector<int>& inside = touched_;
  inside.clear();
  const int first = side < 0 ? nodes_[pieces_[piece].left_end].next : nodes_[before].next;
  const int stop = side < 0 ? nodes_[before].next : pieces_[piece].right_end;
  for (int n = first; n != stop; n = nodes_[n].next) inside.push_back(n);
  if (side < 0) {
    for (int n = pieces_[piece].left_end; n != before; n = nodes_[n].next)
      book(nodes_[n].right, nodes_[nodes_[n].next].X_at(t) - nodes_[n].X_at(t));
    book(straddling, X - nodes_[before].X_at(t));
  } else {
    book(straddling, (inside.empty() ? nodes_[stop].X_at(t) : nodes_[inside.front()].X_at(t)) - X);
    for (int n : inside) book(nodes_[n].right, nodes_[nodes_[n].next].X_at(t) - nodes_[n].X_at(t));
  }
  policy_.at_droplet(ledger_);
  for (int n : inside) {
    account_front_end(n, t);
    // Its fan error goes with the error it carries, lost with it as it is killed.
    if (nodes_[n].front_kind == FrontKind::rarefaction) nodes_[n].carried += book_fan_error(n, t);
  }
  for (int n : inside) kill_node(n, t);
  if (side < 0) {
    link(pieces_[piece].left_end, stop);
  } else {
    link(before, stop);
  }
  // The end moves to where the droplet's new state puts it, so that lab lengths stay the
  // labels' lengths times s/γ (droplet_side checked that there is room).
  const int end = side < 0 ? pieces_[piece].left_end : pieces_[piece].right_end;
  reanchor(end, t);
  nodes_[end].x0 = x + side * droplet_lab_length(end, X, kept, t);
  if (droplets_++ == 0) {
    first_droplet_ = t;
    first_droplet_body_ = pieces_[piece].body;
  }
}

double Tracker::droplet_lab_length(int end, double X, const State& state, double t) const {
  return std::abs(nodes_[end].X_at(t) - X) * state.stretch.value() / std::cosh(state.rapidity);
}

/// Whether the end of a piece may move to lab position x at time t without reaching past
/// its neighbour (the next piece in lab order, or the wall).
bool Tracker::room_for_end(int piece, int side, double x, double t) const {
  const auto it = std::find(order_.begin(), order_.end(), piece);
  if (side < 0) {
    if (it != order_.begin()) return x >= nodes_[pieces_[*(it - 1)].right_end].x_at(t);
    return !walls_[0].present || x >= walls_[0].x_at(t);
  }
  if (it + 1 != order_.end()) return x <= nodes_[pieces_[*(it + 1)].left_end].x_at(t);
  return !walls_[1].present || x <= walls_[1].x_at(t);
}

void Tracker::set_attach(int end, Attach attach, int partner, double t) {
  reanchor(end, t);
  nodes_[end].attach = attach;
  nodes_[end].partner = partner;
}

void Tracker::flush_wall(int side, double t) {
  Wall& w = walls_[side];
  if (w.attached == kNone) return;
  const Node& end = nodes_[w.attached];
  const Region& r = end.kind == NodeKind::left_end ? end.right : nodes_[end.prev].right;
  const double p = r.material->pressure(r.state.stretch);
  const double dt = t - w.pressure_since;
  // The wall pushes the body with force p towards the body: +p at the left wall, −p at the right.
  const double force = side == 0 ? p : -p;
  impulse_ += force * dt;
  // A wall's work at its own velocity; a traction's at the end's, which it holds.
  wall_work_ += force * (w.traction ? end.dxdt : w.velocity()) * dt;
  w.pressure_since = t;
}

double Tracker::ramp_ahead_error(double t) const {
  double error = 0.0;
  for (int side = 0; side < 2; ++side) {
    const Wall& w = walls_[side];
    if (!w.motion.ramps || w.attached == kNone) continue;
    const double since = w.motion.times[w.segment];  // when the piston took its last step
    if (!(t > since)) continue;
    const Node& end = nodes_[w.attached];
    const Region& r = end.kind == NodeKind::left_end ? end.right : nodes_[end.prev].right;
    if (r.material == nullptr) continue;
    // The characteristics that left the piston since then carry its ramp's value, the staircase
    // the step's: off by 2 |ramp − step| in |δφ| + |δΨ| (the wave is simple next to the piston).
    constexpr int kPoints = 16;
    double off = 0.0;
    for (int i = 0; i < kPoints; ++i)
      off += std::abs(
          ramp_rapidity(w.motion.row_times, w.motion.row_rapidities, since + (i + 0.5) / kPoints * (t - since)) -
          w.rapidity);
    const double speed = std::abs(speeds_of(r, side == 0 ? +1 : -1).lagrangian);
    error += 2.0 * off / kPoints * speed * (t - since);
  }
  return error;
}

void Tracker::split_piece(int left_node, int right_node, const State& left_state, const State& right_state,
                          const Region& left_region, const Region& right_region, double t, double X, double x) {
  // The piece parts between left_node and right_node (either may be an end of the
  // piece already): a new right end closes the left part, a new left end opens the right.
  const int old_piece = nodes_[left_node].piece;
  const int new_piece = static_cast<int>(pieces_.size());
  pieces_.push_back(Piece{pieces_[old_piece].body, kNone, kNone});
  ++body_pieces_[pieces_[old_piece].body];
  const int old_right_end = pieces_[old_piece].right_end;

  const int r_end = new_node(NodeKind::right_end, old_piece);
  const int l_end = new_node(NodeKind::left_end, new_piece);
  for (int id : {r_end, l_end}) {
    nodes_[id].front_kind = FrontKind::boundary;
    nodes_[id].t0 = t;
    nodes_[id].X0 = X;
    nodes_[id].x0 = x;
  }
  nodes_[r_end].dxdt = std::tanh(left_state.rapidity);
  nodes_[l_end].dxdt = std::tanh(right_state.rapidity);
  (void)left_region;
  nodes_[l_end].right = right_region;
  link(left_node, r_end);
  link(l_end, right_node);
  nodes_[l_end].prev = kNone;
  nodes_[r_end].next = kNone;
  pieces_[old_piece].right_end = r_end;
  pieces_[new_piece].left_end = l_end;
  pieces_[new_piece].right_end = old_right_end;
  for (int n = l_end; n != kNone; n = nodes_[n].next) nodes_[n].piece = new_piece;
  const auto it = std::find(order_.begin(), order_.end(), old_piece);
  order_.insert(it + 1, new_piece);
  // A wall attached to the old right end now holds the new piece.
  if (nodes_[old_right_end].attach == Attach::boundary) walls_[nodes_[old_right_end].partner].attached = old_right_end;
}

}  // namespace rigidity::characteristics
