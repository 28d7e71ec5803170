// What the outputs read from the tracker: front segments, probe and snapshot samples, the energy books.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "tracker.hpp"

namespace rigidity::characteristics {

void Tracker::record_segment(Node& n, double t) {
  if (!want_fronts_) return;
  if (t <= n.t0) return;  // nothing travelled
  recorder_.front(FrontSegment{n.t0, n.x0, t, n.x_at(t), segment_kind(n.front_kind), n.family});
}

void Tracker::account_front_end(int id, double t) {
  const Node& n = nodes_[id];
  if (n.prev == kNone || !(t > n.t0)) return;
  const bool jump = n.front_kind == FrontKind::shock && !n.smooth;
  // Contacts conserve both exactly; an unsplit fan is the exact fan, which does too.
  if (!jump && (!n.smooth || unsplit(id))) return;
  const Region& left = nodes_[n.prev].right;
  const Region& right = n.right;
  if (left.material == nullptr || right.material == nullptr) return;
  if (!jump && right.material->linearly_degenerate()) return;  // moves at its characteristic speed: exact
  // [F] with F = p v, the energy flux per unit label.
  const auto jump_F = [](const Region::Books& l, const Region::Books& r) {
    return r.pressure * r.velocity - l.pressure * l.velocity;
  };
  if (!jump) {
    // A step of a smooth wave: what its label-jump speed m misses of m[E] = [F] and
    // m[P] = [p], differences of O(1) numbers that are third order in its strength.
    const Region::Books& l = books_of(left);
    const Region::Books& r = books_of(right);
    waves_energy_ -= (n.dXdt * (r.energy - l.energy) - jump_F(l, r)) * (t - n.t0);
    waves_momentum_ -= (n.dXdt * (r.momentum - l.momentum) - (r.pressure - l.pressure)) * (t - n.t0);
    return;
  }
  // Energy removed per unit time at a front moving at m = dX/dt: m[E] − [F], with E the
  // energy and F = p v its flux per unit label, computed from the jump itself (cubic in a
  // weak shock's strength, where the difference of O(1) energies would cancel): by set_front
  // for the states it set, else here.
  const Solved<double> from_jump =
      !std::isnan(n.dissipation)
          ? Solved<double>{n.dissipation, Status::ok}
          : shock_dissipation_rate(*right.material, left.state, right.state, dissipation_precision_);
  double rate = from_jump.value;
  if (!from_jump.ok()) {
    const Region::Books& l = books_of(left);
    const Region::Books& r = books_of(right);
    rate = n.dXdt * (r.energy - l.energy) - jump_F(l, r);
  }
  dissipated_ += rate * (t - n.t0);
}

bool Tracker::locate(int body, double X, double t, Region& region, double& x) const {
  for (int piece : order_) {
    if (pieces_[piece].body != body) continue;
    const Node& le = nodes_[pieces_[piece].left_end];
    const Node& re = nodes_[pieces_[piece].right_end];
    if (X < le.X_at(t) || X > re.X_at(t)) continue;
    if (is_light(piece)) {
      bool found = false;
      walk_light(piece, t, [&](double x_a, double, double X_a, double X_b, const State& state, bool last) {
        if (found || (X >= X_b && !last)) return;  // at a front: the region right of it, as below
        found = true;
        x = x_a + (X - X_a) * label_density(state);
        State smooth = state;
        light_reconstruct(piece, x, t, smooth);
        region = Region{le.right.material, smooth};
      });
      return found;
    }
    int n = pieces_[piece].left_end;
    // The last node at or left of X (the region to its right holds X).
    for (int next = nodes_[n].next;
         next != kNone && nodes_[next].kind != NodeKind::right_end && nodes_[next].X_at(t) <= X; next = nodes_[n].next)
      n = next;
    region_at(n, X, t, region, x);
    return true;
  }
  return false;
}

void Tracker::region_at(int n, double X, double t, Region& region, double& x) const {
  const Node& node = nodes_[n];
  region = node.right;
  State in_fan;
  if (fan_sample(n, X, t, in_fan, x)) {
    region = Region{region.material, in_fan};
    return;
  }
  if (unsplit(n)) {
    // Right of an unsplit fan's wedge: the region starts at the fan's fastest characteristic.
    const CentredFan& f = fans_[node.fan];
    const double x_edge = f.x0 + characteristic_speeds(*region.material, region.state, f.family).lab * (t - f.t0);
    x = x_edge + (X - fan_edge(n, true).X_at(t)) * label_density(region.state);
  } else {
    x = node.x_at(t) + (X - node.X_at(t)) * label_density(region.state);
  }
  State smooth;
  double dx = 0.0;
  if (reconstruct(n, X, t, smooth, dx)) {
    region = Region{region.material, smooth};
    x += dx;
  }
}

double Tracker::quantity(Quantity q, const Region& r, double X, double x) const {
  return quantity_value(q, *r.material, r.state, X, x);
}

void Tracker::sample(const SampleTime& st) {
  const SamplingTimer timer(result_.stats.sampling_time_s);
  if (st.kind == SampleTime::Kind::probe) {
    sample_probe(st.index, st.t);
    return;
  }
  // A snapshot's labels rise, and so do the pieces of a body in lab order and the nodes of
  // each piece: one walk along them finds every sample's region (what locate finds for each
  // X alone), in O(samples + nodes).
  const SnapshotDecl& snap = scene_.outputs.snapshots[st.index];
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    if (!snapshot_includes(snap, scene_.bodies[b])) continue;
    snapshot_body(snap, static_cast<int>(b), st.t);
  }
}

void Tracker::sample_probe(int index, double t) {
  ++walk_epoch_;
  const ProbeDecl& probe = scene_.outputs.probes[index];
  const int body = probe_body(scene_, probe);
  Region r;
  double x = 0.0, X = probe.X;
  if (probe.lab_x) {
    // The piece of the body that covers the lab position, and the label there.
    bool covered = false;
    for (int piece : order_) {
      if (pieces_[piece].body != body) continue;
      const Node& le = nodes_[pieces_[piece].left_end];
      const Node& re = nodes_[pieces_[piece].right_end];
      if (*probe.lab_x < le.x_at(t) || *probe.lab_x > re.x_at(t)) continue;
      X = label_at_lab(*probe.lab_x, le.X_at(t), re.X_at(t), [&](double label) {
        double at = 0.0;
        return locate(body, label, t, r, at) ? at : label;
      });
      covered = true;
      break;
    }
    if (!covered) return;
  }
  if (!locate(body, X, t, r, x)) return;
  for (Quantity q : probe.quantities) recorder_.probe(ProbeSample{t, index, q, quantity(q, r, X, x)});
}

void Tracker::snapshot_body(const SnapshotDecl& snap, int b, double t) {
  ++walk_epoch_;
  const double l0 = scene_.bodies[b].natural_length();
  auto piece = order_.begin();
  const auto next_piece = [&] {
    while (piece != order_.end() && pieces_[*piece].body != b) ++piece;
  };
  next_piece();
  int n = piece != order_.end() ? pieces_[*piece].left_end : kNone;
  for (int i = 0; i < snap.samples; ++i) {
    const double X = l0 * i / (snap.samples - 1);
    while (piece != order_.end() && X > nodes_[pieces_[*piece].right_end].X_at(t)) {
      ++piece;
      next_piece();
      if (piece != order_.end()) n = pieces_[*piece].left_end;
    }
    if (piece == order_.end()) break;
    if (X < nodes_[pieces_[*piece].left_end].X_at(t)) continue;  // in no piece
    if (is_light(*piece)) {
      i += std::max(snapshot_light_piece(snap, b, *piece, i, t), 1) - 1;
      continue;
    }
    for (int next = nodes_[n].next;
         next != kNone && nodes_[next].kind != NodeKind::right_end && nodes_[next].X_at(t) <= X; next = nodes_[n].next)
      n = next;
    Region r;
    double x = 0.0;
    region_at(n, X, t, r, x);
    for (Quantity q : snap.quantities) recorder_.snapshot(SnapshotSample{t, b, X, q, quantity(q, r, X, x)});
  }
}

int Tracker::snapshot_light_piece(const SnapshotDecl& snap, int b, int piece, int i, double t) {
  // One walk along the light piece's regions for all the samples it holds.
  const double l0 = scene_.bodies[b].natural_length();
  const Material& m = *nodes_[pieces_[piece].left_end].right.material;
  const double X_end = nodes_[pieces_[piece].right_end].X_at(t);
  int taken = 0;
  walk_light(piece, t, [&](double x_a, double, double X_a, double X_b, const State& state, bool last) {
    for (;;) {
      const double Xi = l0 * (i + taken) / (snap.samples - 1);
      if (i + taken >= snap.samples || Xi > X_end || (Xi >= X_b && !last)) return;
      const double x = x_a + (Xi - X_a) * label_density(state);
      State smooth = state;
      light_reconstruct(piece, x, t, smooth);
      for (Quantity q : snap.quantities)
        recorder_.snapshot(SnapshotSample{t, b, Xi, q, quantity_value(q, m, smooth, Xi, x)});
      ++taken;
    }
  });
  return taken;
}

void Tracker::totals(double t, double& energy, double& momentum) const {
  energy = momentum = 0.0;
  for (std::size_t p = 0; p < pieces_.size(); ++p) {
    if (pieces_[p].left_end == kNone) continue;  // rejoined into another piece
    integrate_piece(static_cast<int>(p), t, [&](double dX, const Material& m, const State& state) {
      energy += dX * energy_density(m, state);
      momentum += dX * momentum_density(m, state);
    });
  }
}

}  // namespace rigidity::characteristics
