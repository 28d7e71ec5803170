// Centred rarefaction fans: held as one front until something reaches them, split into their
// steps then, and sampled and integrated exactly while their steps keep their lines.
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "rigidity/errors.hpp"
#include "tracker.hpp"

namespace rigidity::characteristics {

/// How far (relative to the fan's width in speed) a front along a fan's edge may run inside it
/// and still be taken for the edge: a shock attached at a sonic point runs at the edge's speed
/// to the round-off of the construction that found that point.
constexpr double kAttachedEdge = 1e-9;

const std::vector<QuadraturePoint>& fan_quadrature() {
  // The exact fan is analytic across its wedge: 48 Gauss–Legendre points integrate its
  // energy and momentum to round-off.
  static const std::vector<QuadraturePoint> points = [] {
    constexpr std::size_t kPoints = 48;
    const std::unique_ptr<gsl_integration_glfixed_table, decltype(&gsl_integration_glfixed_table_free)> rule(
        gsl_integration_glfixed_table_alloc(kPoints), &gsl_integration_glfixed_table_free);
    std::vector<QuadraturePoint> p(kPoints);
    for (std::size_t i = 0; i < kPoints; ++i)
      gsl_integration_glfixed_point(0.0, 1.0, i, &p[i].at, &p[i].weight, rule.get());
    return p;
  }();
  return points;
}

void Tracker::split_fan(int id, double t) {
  const Node& F = nodes_[id];
  const CentredFan f = fans_[F.fan];
  const Material& m = *f.material;
  const int family = F.family, piece = F.piece, before = F.prev, after = F.next;
  const State& left = nodes_[before].right.state;
  const State& right = F.right.state;
  WaveStates& w = wave_split_;
  fan_states(m, family < 0 ? left : right, family < 0 ? right : left, family, f.unsplit, w);
  w.shock = false;
  w.unsplit = 0;
  if (f.capped) fan_capped_ = true;
  std::vector<int>& out = emitted_split_;
  out.clear();
  emit_fronts(m, w, family, piece, f.t0, f.X0, f.x0, out);
  // States listed from the outer one; in space a C+ fan's outer state is on its right.
  const std::size_t count = out.size();
  if (family > 0) std::reverse(out.begin(), out.end());
  int cursor = before;
  for (std::size_t k = 0; k < count; ++k) {
    nodes_[out[k]].right = Region{&m, w.states[family < 0 ? k + 1 : count - k - 1]};
    link(cursor, out[k]);
    cursor = out[k];
  }
  link(cursor, after);
  // What the one front carried goes on with the step that leads the fan.
  Node& one = nodes_[id];
  nodes_[out[family < 0 ? 0 : count - 1]].carried += one.carried;
  one.carried = 0.0;
  // The one front stood for the wedge, whose steps now draw it from the centre.
  one.X0 = one.X_at(t);
  one.x0 = one.x_at(t);
  one.t0 = t;
  kill_node(id, t);
  schedule_meet(before);
  for (const int step : out) schedule_meet(step);
}

bool Tracker::split_reached_fan(int a, double t) {
  const int b = nodes_[a].next;
  const bool split_a = unsplit(a), split_b = b != kNone && unsplit(b);
  if (split_a) split_fan(a, t);
  if (split_b) split_fan(b, t);
  return split_a || split_b;
}

void Tracker::record_fan_edges(int id, double t) {
  if (!want_fronts_) return;
  const Node& n = nodes_[id];
  const CentredFan& f = fans_[n.fan];
  if (t <= f.t0) return;
  for (const int side : {0, 1}) {
    const State& s = side == 0 ? nodes_[n.prev].right.state : n.right.state;
    const double lab = characteristic_speeds(*f.material, s, f.family).lab;
    recorder_.front(FrontSegment{f.t0, f.x0, t, f.x0 + lab * (t - f.t0), SegmentKind::rarefaction, f.family});
  }
}

bool Tracker::fan_sample(int n, double X, double t, State& state, double& x) const {
  for (const int id : {n, nodes_[n].next}) {
    if (id == kNone || nodes_[id].kind != NodeKind::front || nodes_[id].fan == kNone) continue;
    const CentredFan& f = fans_[nodes_[id].fan];
    if (!(t > f.t0)) return false;
    const double speed = (X - f.X0) / (t - f.t0);
    const double slowest = std::min(f.speed_a, f.speed_b), fastest = std::max(f.speed_a, f.speed_b);
    if (!(speed > slowest && speed < fastest)) continue;
    // The region's other edge is a step of the same fan, or lies beyond the fan: a wave that
    // has entered the fan's wedge without meeting a step yet has changed the state behind it. A
    // shock attached to the fan (a composite wave) runs along its edge, at its speed to round-off.
    const int other = id == n ? nodes_[n].next : n;
    // A front of the other family that bounds the region on the side it comes from (a C− front
    // on its right, a C+ front on its left) has not reached it yet: the region is still the fan.
    const bool arriving = other != kNone && nodes_[other].kind == NodeKind::front &&
                          nodes_[other].family == -f.family && (other == nodes_[n].next) == (nodes_[other].family < 0);
    if (!arriving && (other == kNone || nodes_[other].fan != nodes_[id].fan)) {
      const double edge = other == kNone ? (id == n ? kInf : -kInf) : (nodes_[other].X_at(t) - f.X0) / (t - f.t0);
      const double round_off = kAttachedEdge * (fastest - slowest);
      if (id == n ? edge < fastest - round_off : edge > slowest + round_off) return false;
    }
    const Solved<State> exact = centred_fan_state(*f.material, f.family, f.j_other, f.psi_a, f.psi_b, speed);
    if (!exact.ok()) return false;  // the steps' state, then
    state = exact.value;
    // Every characteristic of the fan is a straight line from its centre in the lab as well.
    x = f.x0 + characteristic_speeds(*f.material, state, f.family).lab * (t - f.t0);
    return true;
  }
  return false;
}

}  // namespace rigidity::characteristics
