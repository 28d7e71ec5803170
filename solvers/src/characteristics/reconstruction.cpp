// Smooth waves between their steps: a smooth wave (a fan, a piston's ramp, what they become) is
// moved as steps, fronts that are characteristics to second order, and sampled as the line
// through the values at those characteristics, not as the staircase of its steps.
#include <algorithm>
#include <cmath>
#include <limits>

#include "tracker.hpp"

namespace rigidity::characteristics {

/// A linear correction of one family's invariant, c(X) = c0 + q (X − X0), kept where its
/// sign is `sign` and zero elsewhere (sign 0: kept everywhere).
struct Ramp {
  double c0 = 0.0, q = 0.0, X0 = 0.0;
  int sign = 0;
  double from = -kInf, to = kInf;  ///< where it applies

  [[nodiscard]] double at(double X) const {
    if (X < from || X > to) return 0.0;
    const double c = c0 + q * (X - X0);
    return sign != 0 && sign * c <= 0.0 ? 0.0 : c;
  }
  /// ∫ c(X) dX over [a, b].
  [[nodiscard]] double integral(double a, double b) const {
    a = std::max(a, from);
    b = std::min(b, to);
    if (sign != 0 && q != 0.0) {
      const double zero = X0 - c0 / q;
      if (sign * q > 0.0) {
        a = std::max(a, zero);
      } else {
        b = std::min(b, zero);
      }
    }
    if (!(b > a)) return 0.0;
    return c0 * (b - a) + 0.5 * q * ((b - X0) * (b - X0) - (a - X0) * (a - X0));
  }
};

namespace {

/// A strip beside the one a line is drawn over: its width and the jump of the step beyond it
/// (kInf wide: none).
struct Beside {
  double width = kInf, jump = 0.0;
};

/// The line of one family's invariant over a strip of `width` between two smooth steps of
/// jumps ja and jb, with the wave's strips beside it: its slope and its value at either step,
/// relative to the strip's value; NaN where the strip is no part of one smooth wave or lies
/// between steps of opposite jumps (an extremum where two waves meet: each is carried on to
/// it). A step of a smooth wave moves at the mean of the characteristic speeds of its sides: it
/// is the characteristic of the mean of its sides' values, to second order, and that is its
/// value, however wide the strips beside it. A strip is a plateau between two waves, no part
/// of either, where it spreads the change of the invariant across it (half of each step's jump)
/// more than kPlateauRatio times as thinly as the thinner of the strips beside it does, or has
/// none beside it: so the steps of a wave may be irregular (two trains of steps of different
/// strengths interleaved, a weak step beside a strong one) and still draw its line.
struct Line {
  double slope = std::numeric_limits<double>::quiet_NaN(), at_a = 0.0, at_b = 0.0;
};
Line line_through(double ja, double jb, double width, Beside left, Beside right, double plateau_ratio) {
  const auto spread = [](double w, double j1, double j2) {
    const double change = 0.5 * std::abs(j1 + j2);
    return w < kInf && change > 0.0 ? w / change : kInf;
  };
  const double thinner = std::min(spread(left.width, left.jump, ja), spread(right.width, jb, right.jump));
  if (!(width > 0.0) || thinner == kInf || spread(width, ja, jb) > plateau_ratio * thinner) return {};
  if (!(ja * jb > 0.0)) return {};
  const double at_a = -0.5 * ja, at_b = 0.5 * jb;
  return {(at_b - at_a) / width, at_a, at_b};
}

/// The strips of a train beyond one of the two steps around X, up to kTrainReach of them: their
/// width and the change of the invariant across them (half of each bounding step's jump), and
/// the strip next to the step alone as line_through takes it.
struct Reach {
  double width = 0.0, change = 0.0;
  Beside next;
  void add(double w, double j_near, double j_far) {
    if (width == 0.0) next = Beside{w, j_far};
    width += w;
    change += 0.5 * (std::abs(j_near) + std::abs(j_far));
  }
};
constexpr int kTrainReach = 2;

/// A piece of a line: its slope, its value at `from`, and where it applies.
struct Segment {
  double slope = std::numeric_limits<double>::quiet_NaN(), at_from = 0.0, from = 0.0, to = 0.0;
};

/// The correction at X (relative to the staircase of its jumps) of a train of steps of one
/// sign, over the strip [Xa, Xb] between two of them of jumps ja and jb, with the train's
/// strips beyond; NaN where the strip is a plateau or has no strip of the train beyond it.
/// The steps of one wave (`at_means`) are drawn as the line through their values, each the
/// mean of its sides, the strip a plateau as line_through says. Steps riding on a wave may
/// belong to several trains interleaved (the weak waves a shock reflects, one train for each
/// wave that crossed it), of different strengths and spacings, so their strips alternate wide
/// and narrow, two steps a hair apart: such a strip is a plateau only where it spreads the
/// change of the invariant more than `plateau_ratio` times as thinly as the window of it and
/// its strips beyond does on average, and the line through the steps' means would rise by both
/// halves of a close pair across the hair; theirs is drawn through the staircase's values at
/// the strips' midpoints instead (through the step's mean where the strip beyond is a
/// plateau), which for one even train is the same line.
Segment train_segment(double X, double Xa, double Xb, double ja, double jb, Reach left, Reach right, bool at_means,
                      double plateau_ratio) {
  if (at_means) {  // one wave's steps
    const Line line = line_through(ja, jb, Xb - Xa, left.next, right.next, plateau_ratio);
    return std::isnan(line.slope) ? Segment{} : Segment{line.slope, line.at_a, Xa, Xb};
  }
  const double width = Xb - Xa, change = 0.5 * (std::abs(ja) + std::abs(jb));
  if (!(width > 0.0) || !(ja * jb > 0.0) || left.width + right.width == 0.0) return {};
  const double window = (left.width + width + right.width) / (left.change + change + right.change);
  if (width / change > plateau_ratio * window) return {};
  const auto inside = [&](const Reach& r, double j_near) {
    return r.next.width < kInf && r.next.width / (0.5 * std::abs(j_near + r.next.jump)) <= plateau_ratio * window;
  };
  const double mid = 0.5 * (Xa + Xb);
  if (X < mid) {
    const bool beside = inside(left, ja);
    const double X_left = beside ? Xa - 0.5 * left.next.width : Xa;
    const double at_left = beside ? -ja : -0.5 * ja;
    const double slope = -at_left / (mid - X_left);
    return {slope, at_left + slope * (Xa - X_left), Xa, mid};
  }
  const bool beside = inside(right, jb);
  const double X_right = beside ? Xb + 0.5 * right.next.width : Xb;
  const double slope = (beside ? jb : 0.5 * jb) / (X_right - mid);
  return {slope, 0.0, mid, Xb};
}

}  // namespace

int Tracker::strip_edge(int from, int family, int Node::*step) const {
  int id = from;
  for (;;) {
    const Node& n = nodes_[id];
    if (n.kind != NodeKind::front || !n.smooth || (n.family == family && !superposed(id, family))) return id;
    id = n.*step;
  }
}

double Tracker::own_jump(int id) const {
  const Node& f = nodes_[id];
  const Region& left = nodes_[f.prev].right;
  const Region& right = f.right;
  return (right.state.rapidity - left.state.rapidity) +
         f.family * (memo_->psi(*right.material, right.state.stretch) - memo_->psi(*left.material, left.state.stretch));
}

Tracker::Wedge Tracker::wedge(int a, int b, int family, double t) const {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const double Xa = nodes_[a].X_at(t), Xb = nodes_[b].X_at(t), width = Xb - Xa;
  if (!(width > 0.0)) return {kNaN, kNaN};
  const Material* m = nodes_[a].right.material;
  if (nodes_[nodes_[a].prev].right.material != m || nodes_[b].right.material != m) return {kNaN, kNaN};
  const int a2 = strip_edge(nodes_[a].prev, family, &Node::prev);
  const int b2 = strip_edge(nodes_[b].next, family, &Node::next);
  const double ja = own_jump(a), jb = own_jump(b);
  const Beside left = is_step(a2, family) ? Beside{Xa - nodes_[a2].X_at(t), own_jump(a2)} : Beside{};
  const Beside right = is_step(b2, family) ? Beside{nodes_[b2].X_at(t) - Xb, own_jump(b2)} : Beside{};
  const Line line = line_through(ja, jb, width, left, right, kPlateauRatio);
  if (std::isnan(line.slope)) return {kNaN, kNaN};
  const double at_a = line.at_a + nodes_[a].offset, at_b = line.at_b + nodes_[b].offset;
  return {(at_b - at_a) / width, at_a};
}

/// The nearest step of `family` whose jump has the sign `sign` and which rides on the wave
/// (superposed) or not as `weak` says, from node `from` on, walking by `step` past smooth fronts
/// (kNone: an end, an interface, a true jump or kMaxTrainWalk nodes come first).
int Tracker::train_step(int from, int family, int sign, bool weak, int Node::*step) const {
  int id = from;
  for (int k = 0; k < kMaxTrainWalk && id != kNone; ++k, id = nodes_[id].*step) {
    const Node& n = nodes_[id];
    if (n.kind != NodeKind::front || !n.smooth) return kNone;
    if (n.family == family && superposed(id, family) == weak && own_jump(id) * sign > 0.0) return id;
  }
  return kNone;
}

Tracker::Wedge Tracker::train_wedge(int n, double X, int family, int sign, bool weak, double t) const {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const int a = train_step(n, family, sign, weak, &Node::prev);
  const int b = a == kNone ? kNone : train_step(nodes_[n].next, family, sign, weak, &Node::next);
  if (b == kNone) return {kNaN, kNaN};
  const double Xa = nodes_[a].X_at(t), Xb = nodes_[b].X_at(t);
  if (!(X >= Xa && X <= Xb)) return {kNaN, kNaN};
  const auto reach = [&](int from, int Node::*step) {
    Reach r;
    for (int k = from, i = 0; i < kTrainReach; ++i) {
      const int beyond = train_step(nodes_[k].*step, family, sign, weak, step);
      if (beyond == kNone) break;
      r.add(std::abs(nodes_[beyond].X_at(t) - nodes_[k].X_at(t)), own_jump(k), own_jump(beyond));
      k = beyond;
    }
    return r;
  };
  const Segment line = train_segment(X, Xa, Xb, own_jump(a), own_jump(b), reach(a, &Node::prev), reach(b, &Node::next),
                                     !weak, kPlateauRatio);
  if (std::isnan(line.slope)) return {kNaN, kNaN};
  return {line.slope, line.at_from, line.from, line.to};
}

/// For each family, the strip of the region right of node n between the nearest fronts of
/// that family (or what bounds the strip: an end, an interface, a true jump), and on it:
///   - between two steps of one smooth wave, the line through their values (wedge);
///   - on a plateau next to a step whose wave goes on beyond it, that wave's line carried on
///     from the step's value until it meets the plateau's: the head or tail of the wave, whose
///     first step stands half a strip inside it (the plateau keeps its value: the steps
///     stand at the means of their sides, and the outermost has the plateau on one); carried
///     on to the end or interface that bounds the strip where the wave is reflecting there
///     (the steps of the other family leaving it are smooth, the nearest within the reach
///     of the wave's next strip) and the strip is no wider than kPlateauRatio of the wave's
///     strips.
/// Where the invariant changes so does the lab length per label, ρ = s/γ, at ∂ρ/∂J± = −ρ
/// (tanh φ ± 1/c_s)/2: the lab position moves by the integral of that change from the strip's
/// left edge, region by region, less the share of X − X_left of what it comes to over the
/// whole strip, so that the lab positions of the strip's edges stay those of the steps.
bool Tracker::reconstruct(int n, double X, double t, State& state, double& dx) const {
  const Node& node = nodes_[n];
  if (node.next == kNone || node.kind == NodeKind::right_end || node.kind == NodeKind::light_store) return false;
  const Region& region = node.right;
  const Material& m = *region.material;
  const double psi = memo_->psi(m, region.state.stretch);
  double j[2] = {region.state.rapidity - psi, region.state.rapidity + psi};  // [0] J−, [1] J+
  bool changed = false;
  dx = 0.0;
  for (int family : {-1, +1}) {
    StripWalk& w = strip_of(n, family, t);
    const int l = w.l, r = w.r;
    const double Xl = nodes_[l].X_at(t), Xr = nodes_[r].X_at(t);
    if (!(Xr > Xl)) continue;
    Ramp ramps[kMaxRamps];
    const int count = wave_ramps(n, X, family, t, l, r, ramps);
    const double at_end = end_condition(family, X, t, l, r, ramps, count);
    if (count == 0 && at_end == 0.0) continue;
    // The strip ends at an interface: the lab length is left as the staircase has it.
    if (!w.one_material) continue;
    double to_X = 0.0, to_r = 0.0;
    strip_shift(w, ramps, count, X, to_X, to_r);
    double correction = 0.0;
    for (int i = 0; i < count; ++i) correction += ramps[i].at(X);
    correction += at_end;
    j[family > 0 ? 1 : 0] += correction;
    dx += to_X - to_r * (X - Xl) / (Xr - Xl);
    changed = true;
  }
  if (!changed) return false;
  const Solved<Stretch> s = memo_->stretch_at_psi(m, 0.5 * (j[1] - j[0]));
  if (!s.ok() || !representable(s.value)) return false;
  state = State{0.5 * (j[1] + j[0]), s.value};
  return true;
}

Tracker::StripWalk& Tracker::strip_of(int n, int family, double t) const {
  StripWalk& w = strip_walks_[family > 0 ? 1 : 0];
  if (w.epoch == walk_epoch_ && !w.nodes.empty()) {
    if (w.cursor < w.nodes.size() && w.nodes[w.cursor] == n) return w;
    const auto at = std::find(w.nodes.begin() + static_cast<long>(w.cursor), w.nodes.end(), n);
    if (at != w.nodes.end()) {
      w.cursor = static_cast<std::size_t>(at - w.nodes.begin());
      return w;
    }
  }
  w.epoch = walk_epoch_;
  w.l = nodes_[n].kind == NodeKind::front ? strip_edge(n, family, &Node::prev) : n;
  w.r = strip_edge(nodes_[n].next, family, &Node::next);
  w.one_material = true;
  w.nodes.clear();
  w.rates.clear();
  w.lo.clear();
  w.count = -1;
  const Material* m = nodes_[n].right.material;
  for (int k = w.l; k != w.r; k = nodes_[k].next) {
    const Region& here = nodes_[k].right;
    if (here.material != m) {
      w.one_material = false;
      break;
    }
    const Hyperbolic& h = hyperbolic_of(here);
    w.nodes.push_back(k);
    w.rates.push_back(-0.5 * here.state.stretch.value() / h.cosh *
                      (h.sinh / h.cosh + family / m->sound_speed(here.state.stretch)));
    w.lo.push_back(nodes_[k].X_at(t));
  }
  w.lo.push_back(nodes_[w.r].X_at(t));
  const auto at = std::find(w.nodes.begin(), w.nodes.end(), n);
  w.cursor = static_cast<std::size_t>(at - w.nodes.begin());
  return w;
}

void Tracker::strip_shift(StripWalk& w, const Ramp* ramps, int count, double X, double& to_X, double& to_r) {
  std::array<double, 6 * kMaxRamps> lines{};
  for (int i = 0; i < count; ++i) {
    const Ramp& a = ramps[i];
    const double coefficients[6] = {a.c0, a.q, a.X0, static_cast<double>(a.sign), a.from, a.to};
    std::copy(coefficients, coefficients + 6, lines.begin() + 6 * i);
  }
  if (w.count != count || w.lines != lines) {
    w.count = count;
    w.lines = lines;
    w.before.assign(w.nodes.size(), 0.0);
    w.to_r = 0.0;
    for (std::size_t k = 0; k < w.nodes.size(); ++k) {
      w.before[k] = w.to_r;
      for (int i = 0; i < count; ++i) w.to_r += w.rates[k] * ramps[i].integral(w.lo[k], w.lo[k + 1]);
    }
  }
  double part = 0.0;
  for (int i = 0; i < count; ++i) part += ramps[i].integral(w.lo[w.cursor], X);
  to_X = w.before[w.cursor] + w.rates[w.cursor] * part;
  to_r = w.to_r;
}

double Tracker::end_condition(int family, double X, double t, int l, int r, const Ramp* ramps, int count) const {
  // The strip of `family` next to an end from which that family leaves (a left end for C+, a
  // right end for C−), and what the end does to the invariant arriving there: a free end or
  // a traction holds Ψ (the leaving invariant changes as the arriving one does), a wall or a
  // piston at constant speed holds φ (as much the other way).
  const bool left = family > 0;
  const int e = left ? l : r;
  const Node& end = nodes_[e];
  if (end.kind != (left ? NodeKind::left_end : NodeKind::right_end) || end.attach == Attach::body) return 0.0;
  double sigma = 1.0;
  if (end.attach == Attach::boundary) {
    const Wall& w = walls_[end.partner];
    if (w.motion.ramps) return 0.0;  // the staircase of its ramp: see set_offsets
    sigma = w.traction ? 1.0 : -1.0;
  }
  // The arriving wave's line at the end, over the strip of its family there.
  const int arriving = -family;
  const int n = left ? e : end.prev;
  const int la = left ? e : (nodes_[n].kind == NodeKind::front ? strip_edge(n, arriving, &Node::prev) : n);
  const int ra = left ? strip_edge(end.next, arriving, &Node::next) : e;
  const double X_end = end.X_at(t);
  Ramp in[kMaxRamps];
  const int in_count = wave_ramps(n, X_end, arriving, t, la, ra, in);
  double arrived = 0.0, leaving = 0.0;
  for (int i = 0; i < in_count; ++i) arrived += in[i].at(X_end);
  for (int i = 0; i < count; ++i) leaving += ramps[i].at(X_end);
  // The leaving invariant is drawn from the end's value to what the strip's far edge has: the
  // samples there hold the end's condition whatever the lines of the two waves make of it
  // (a leaving wave of a step or two has no line yet; an arriving one carried on to the end
  // has moved on from the region's value).
  const double X_far = nodes_[left ? r : l].X_at(t);
  const double share = (X_far - X) / (X_far - X_end);
  return (sigma * arrived - leaving) * std::clamp(share, 0.0, 1.0);
}

int Tracker::wave_ramps(int n, double X, int family, double t, int l, int r, Ramp* ramps) const {
  const double Xl = nodes_[l].X_at(t), Xr = nodes_[r].X_at(t);
  // An end or interface from which the steps of a smooth wave of `family` leave, the nearest
  // no farther from it than `reach` (kPlateauRatio of the arriving wave's strip: it left as the
  // wave's last step arrived): the wave that makes them by reflection (or transmission) reaches
  // it, and its line goes on to it. A smooth step of that family farther off belongs to another
  // wave, and the plateau between this wave and the end stands.
  const auto reflecting = [&](int edge, int fam, double reach) {
    const Node& e = nodes_[edge];
    if (e.kind == NodeKind::front) return false;
    const int step =
        e.kind == NodeKind::right_end ? strip_edge(e.prev, fam, &Node::prev) : strip_edge(e.next, fam, &Node::next);
    return step != kNone && is_step(step, fam) && std::abs(nodes_[step].X_at(t) - e.X_at(t)) <= reach;
  };
  int count = 0;
  bool interleaved = false;
  if (is_step(l, family) && is_step(r, family)) {
    // Steps of both signs among the two around X and their neighbours: two smooth waves of
    // the family superposed, their steps interleaved (in a linearly degenerate body they run
    // side by side for ever), or an extremum where one wave ends and the next begins. Each
    // wave is the line through the steps of its own sign; at an extremum neither line reaches
    // X and the plateau stands, each wave's line carried on to it (below).
    const int l2 = strip_edge(nodes_[l].prev, family, &Node::prev);
    const int r2 = strip_edge(nodes_[r].next, family, &Node::next);
    const double sign_l = own_jump(l);
    const bool mixed = sign_l * own_jump(r) < 0.0 || (is_step(l2, family) && sign_l * own_jump(l2) < 0.0) ||
                       (is_step(r2, family) && sign_l * own_jump(r2) < 0.0);
    if (!mixed) {
      const Wedge w = wedge(l, r, family, t);
      if (!std::isnan(w.slope)) ramps[count++] = Ramp{w.at_a, w.slope, Xl, 0};
    } else {
      for (int sign : {-1, +1}) {
        const Wedge train = train_wedge(n, X, family, sign, false, t);
        if (!std::isnan(train.slope))
          ramps[count++] = Ramp{train.at_a, train.slope, train.from, 0, train.from, train.to};
      }
      interleaved = count > 0;
    }
  }
  // (A step still on the line of its centred fan has the exact fan beyond it, see fan_sample,
  // up to the nearest front of the other family: beyond that the wave's line goes on.)
  if (count == 0 && is_step(r, family) &&
      (nodes_[r].fan == kNone || nodes_[n].next != r)) {  // a wave right of the plateau
    const int r2 = strip_edge(nodes_[r].next, family, &Node::next);
    const double jump = own_jump(r);
    const double reach = kPlateauRatio * (nodes_[r2].X_at(t) - Xr);
    const bool on = Xr - Xl <= reach && reflecting(l, -family, reach);
    const Wedge w = is_step(r2, family) ? wedge(r, r2, family, t) : Wedge{};
    if (w.slope * jump > 0.0) ramps[count++] = Ramp{w.at_a + jump, w.slope, Xr, on ? 0 : jump > 0.0 ? 1 : -1};
  }
  const bool in_wedge = count == 1 && ramps[0].sign == 0;
  if (!in_wedge && !interleaved && is_step(l, family) &&
      (nodes_[l].fan == kNone || l != n)) {  // a wave left of the plateau
    const int l2 = strip_edge(nodes_[l].prev, family, &Node::prev);
    const double jump = own_jump(l);
    const double X2 = nodes_[l2].X_at(t);
    const double reach = kPlateauRatio * (Xl - X2);
    const bool on = Xr - Xl <= reach && reflecting(r, -family, reach);
    const Wedge w = is_step(l2, family) ? wedge(l2, l, family, t) : Wedge{};
    if (w.slope * jump > 0.0)
      ramps[count++] = Ramp{w.at_a + w.slope * (Xl - X2) - jump, w.slope, Xl, on ? 0 : jump > 0.0 ? -1 : 1};
  }
  // A train of weak steps riding on the wave (superposed: each a jump on top of its line) is
  // a weak smooth wave of its own: drawn as the line through its steps' values between the two
  // of them around X, not as their staircase.
  for (int sign : {-1, +1}) {
    const Wedge riding = train_wedge(n, X, family, sign, true, t);
    if (!std::isnan(riding.slope))
      ramps[count++] = Ramp{riding.at_a, riding.slope, riding.from, 0, riding.from, riding.to};
  }
  return count;
}

double Tracker::reconstruction_error(int id, double t) const {
  const Node& n = nodes_[id];
  if (!n.smooth || superposed(id, n.family)) return kInf;  // a jump on top of the line
  const int l = strip_edge(n.prev, n.family, &Node::prev);
  const int r = strip_edge(n.next, n.family, &Node::next);
  const double left = is_step(l, n.family) ? wedge(l, id, n.family, t).slope : std::nan("");
  const double right = is_step(r, n.family) ? wedge(id, r, n.family, t).slope : std::nan("");
  const double X = n.X_at(t);
  double curvature = 0.0, width = 0.0;  // the change of slope across the step, and the strips' width
  double extremum = 0.0;
  if (!std::isnan(left) && !std::isnan(right)) {
    curvature = std::abs(right - left);
    width = 0.5 * (nodes_[r].X_at(t) - nodes_[l].X_at(t));
  } else if (!std::isnan(left) || !std::isnan(right)) {
    // The first or last step of its wave: the change of slope between the wave's first two
    // strips, which the line carried on to the plateau (see reconstruct) misses the wave by.
    const bool inward_right = !std::isnan(right);
    const int near = inward_right ? r : l;
    const int far = strip_edge(inward_right ? nodes_[near].next : nodes_[near].prev, n.family,
                               inward_right ? &Node::next : &Node::prev);
    if (!is_step(far, n.family)) return kInf;
    const double next = inward_right ? wedge(near, far, n.family, t).slope : wedge(far, near, n.family, t).slope;
    if (std::isnan(next)) return kInf;
    curvature = std::abs(next - (inward_right ? right : left));
    width = std::abs(nodes_[near].X_at(t) - X);
    // Beyond it, the first step of a wave of the other sign (not one of two waves interleaved),
    // no more than kPlateauRatio of the wave's strips away (a wider strip is a plateau between
    // the two waves): the strip between them holds an extremum, half of what it misses booked
    // by either step (extremum_miss).
    const int beyond = inward_right ? l : r;
    if (is_step(beyond, n.family) && own_jump(beyond) * own_jump(id) < 0.0) {
      const int after = strip_edge(inward_right ? nodes_[beyond].prev : nodes_[beyond].next, n.family,
                                   inward_right ? &Node::prev : &Node::next);
      const bool wave_beyond = is_step(after, n.family) && own_jump(after) * own_jump(beyond) > 0.0;
      const bool interleaved = is_step(after, n.family) && !wave_beyond;
      const double across = std::abs(nodes_[beyond].X_at(t) - X);
      const double other = !wave_beyond   ? std::nan("")
                           : inward_right ? wedge(after, beyond, n.family, t).slope
                                          : wedge(beyond, after, n.family, t).slope;
      if (!interleaved && across <= kPlateauRatio * width)
        extremum = 0.5 * extremum_miss(across, own_jump(id), std::abs(inward_right ? right : left), own_jump(beyond),
                                       std::abs(other));
    }
  } else {
    return kInf;
  }
  return curvature * width * width / 12.0 + extremum + drift_error(id, t);
}

double Tracker::extremum_miss(double across, double j1, double s1, double j2, double s2) {
  if (!(s1 > 0.0 && s2 > 0.0)) return 0.25 * std::max(std::abs(j1), std::abs(j2)) * across;
  const double gap = std::abs(across - 0.5 * std::abs(j1) / s1 - 0.5 * std::abs(j2) / s2);
  return 0.5 * gap * gap * s1 * s2 / (s1 + s2);
}

double Tracker::drift_error(int id, double t) const {
  const Node& n = nodes_[id];
  if (n.front_kind != FrontKind::rarefaction) return 0.0;
  const Region& before = nodes_[n.prev].right;
  const double mean = 0.5 * (speeds_of(before, n.family).lagrangian + speeds_of(n.right, n.family).lagrangian);
  return std::abs(own_jump(id)) * std::abs(n.dXdt - mean) * (t - n.born);
}

double Tracker::reflection_error(int id, double t) const {
  const Node& n = nodes_[id];
  const Region& before = nodes_[n.prev].right;
  if (before.material->linearly_degenerate()) return 0.0;
  const double other_change =
      std::abs(speeds_of(before, -n.family).lagrangian - speeds_of(n.right, -n.family).lagrangian);
  const double own_speed =
      0.5 * std::abs(speeds_of(before, n.family).lagrangian + speeds_of(n.right, n.family).lagrangian);
  // The room inward of it: to its neighbour on the side away from the end.
  const int inward = nodes_[n.prev].is_end() ? n.next : n.prev;
  const double room = std::abs(nodes_[inward].X_at(t) - n.X_at(t));
  if (!(own_speed > 0.0)) return 0.0;
  return 0.25 * std::abs(own_jump(id)) * other_change * room / own_speed;
}

bool Tracker::light_reconstruct(int piece, double x, double t, State& state) const {
  const LightPiece& lp = light_[piece];
  if (lp.lattice) return false;
  const Material& m = *nodes_[lp.store].right.material;
  double j[2] = {invariant(m, state, -1), invariant(m, state, +1)};  // [0] J−, [1] J+
  bool changed = false;
  for (int family : {-1, +1}) changed = light_line(piece, family, x, t, j[family > 0 ? 1 : 0]) || changed;
  if (!changed) return false;
  state = light_state(m, j[1], j[0]);
  return true;
}

/// One family's queue of a light piece at time t, read around lab position x: its fronts'
/// positions and jumps, and the walks light_line makes along it. C+ fronts stand right to left
/// in their queue, C− fronts left to right.
struct LightQueue {
  const std::deque<LightFront>& q;
  int family;
  double t, x, superposed;  ///< superposed: a riding step is weaker than this
  long n = static_cast<long>(q.size());
  long leftwards = family > 0 ? 1 : -1;
  long left_start = 0, right_start = 0;  ///< the first index left and right of x

  LightQueue(const std::deque<LightFront>& queue, int fam, double time, double at_x, double weak)
      : q(queue), family(fam), t(time), x(at_x), superposed(weak) {
    long k = 0;  // C+: fronts right of x; C−: fronts at or left of x
    while (k < n && (family > 0 ? at(k) > x : at(k) <= x)) ++k;
    left_start = family > 0 ? k : k - 1;
    right_start = family > 0 ? k - 1 : k;
  }
  [[nodiscard]] double at(long i) const { return q[static_cast<std::size_t>(i)].x_at(t, family); }
  /// Its own invariant's jump, right less left: a C+ front runs into j_ahead on its right.
  [[nodiscard]] double jump(long i) const {
    const LightFront& f = q[static_cast<std::size_t>(i)];
    return family > 0 ? f.j_ahead - f.j_behind : f.j_behind - f.j_ahead;
  }
  /// As on a node piece (strip_edge): a weak smooth step riding on the wave is a jump on top of
  /// its line, not one of the steps the line is drawn through.
  [[nodiscard]] bool riding(long i) const { return q[i].smooth && std::abs(jump(i)) < superposed; }
  [[nodiscard]] bool step(long i) const { return i != kNone && q[i].smooth; }
  /// The nearest front from index i on, walking by `by`, that is not riding (kNone: none).
  [[nodiscard]] long edge(long i, long by) const {
    while (i >= 0 && i < n && riding(i)) i += by;
    return i >= 0 && i < n ? i : static_cast<long>(kNone);
  }
  /// The line through the steps of one sign around x, the riding ones or the others as `weak`
  /// says, relative to the staircase of their jumps (see Tracker::train_wedge; NaN: none
  /// reaches x).
  [[nodiscard]] double train(int sign, bool weak) const {
    const auto nearest = [&](long i, long by) {
      for (int walked = 0; walked < Tracker::kMaxTrainWalk && i >= 0 && i < n; ++walked, i += by) {
        if (!q[i].smooth) break;  // a true jump
        if (riding(i) == weak && sign * jump(i) > 0.0) return i;
      }
      return static_cast<long>(kNone);
    };
    const long ta = nearest(left_start, leftwards);
    const long tb = ta == kNone ? kNone : nearest(right_start, -leftwards);
    if (tb == kNone) return std::numeric_limits<double>::quiet_NaN();
    const auto reach = [&](long from, long by) {
      Reach r;
      for (long k = from, i = 0; i < kTrainReach; ++i) {
        const long beyond = nearest(k + by, by);
        if (beyond == kNone) break;
        r.add(std::abs(at(beyond) - at(k)), jump(k), jump(beyond));
        k = beyond;
      }
      return r;
    };
    const double Xa = at(ta), Xb = at(tb);
    const Segment line = train_segment(x, Xa, Xb, jump(ta), jump(tb), reach(ta, leftwards), reach(tb, -leftwards),
                                       !weak, Tracker::kPlateauRatio);
    return line.at_from + line.slope * (x - line.from);
  }
};

bool Tracker::light_line(int piece, int family, double x, double t, double& j) const {
  const LightPiece& lp = light_[piece];
  const LightQueue lq(family > 0 ? lp.plus : lp.minus, family, t, x, kSuperposed * policy_.fan_step());
  const double before = j;
  // A train of riding steps of one sign is a weak smooth wave of its own, on top of the
  // region's value.
  for (int sign : {-1, +1}) {
    const double riding_line = lq.train(sign, true);
    if (!std::isnan(riding_line)) j += riding_line;
  }
  const long a = lq.edge(lq.left_start, lq.leftwards), b = lq.edge(lq.right_start, -lq.leftwards);
  const long a2 = a == kNone ? kNone : lq.edge(a + lq.leftwards, lq.leftwards);
  const long b2 = b == kNone ? kNone : lq.edge(b - lq.leftwards, -lq.leftwards);
  if (lq.step(a) && lq.step(b)) {
    // Steps of both signs among these: waves of the family superposed, or an extremum (see
    // reconstruct): each is the line through the steps of its own sign.
    const double ja = lq.jump(a);
    const bool mixed =
        ja * lq.jump(b) < 0.0 || (lq.step(a2) && ja * lq.jump(a2) < 0.0) || (lq.step(b2) && ja * lq.jump(b2) < 0.0);
    double wave_line = 0.0;
    bool drawn = false;
    if (mixed) {
      for (int sign : {-1, +1}) {
        const double line = lq.train(sign, false);
        if (!std::isnan(line)) wave_line += line, drawn = true;
      }
    } else {
      const double Xa = lq.at(a), Xb = lq.at(b);
      const Line line =
          line_through(ja, lq.jump(b), Xb - Xa, lq.step(a2) ? Beside{Xa - lq.at(a2), lq.jump(a2)} : Beside{},
                       lq.step(b2) ? Beside{lq.at(b2) - Xb, lq.jump(b2)} : Beside{}, kPlateauRatio);
      // The region's own value carries the riding steps between a and x that make no train as
      // the jumps they are.
      if (!std::isnan(line.slope)) wave_line = line.at_a + line.slope * (x - Xa), drawn = true;
    }
    if (drawn) {
      j += wave_line;
      return true;
    }
  }
  j += light_carried(piece, lq, a, b, b2, true) + light_carried(piece, lq, a, b, a2, false);
  return j != before;
}

double Tracker::light_carried(int piece, const LightQueue& lq, long a, long b, long far, bool wave_right) const {
  // No line reaches x: it lies on a plateau between a (or the left end) and b (or the right
  // end). The wave beside it (right of it from b, or left of it from a) carries on the line of
  // its first strip into it until the line meets the plateau's value, or to the end where the
  // wave is reflecting there (the front of the other family nearest that end is smooth and
  // no farther from it than the plateau may be wide) and
  // the plateau is no wider than kPlateauRatio of that strip (as on a node piece, see
  // reconstruct).
  const long near = wave_right ? b : a;
  if (!lq.step(near) || !lq.step(far) || lq.jump(near) * lq.jump(far) <= 0.0) return 0.0;
  const long outwards = wave_right ? -lq.leftwards : lq.leftwards;
  const long beyond = lq.edge(far + outwards, outwards);
  const double strip = std::abs(lq.at(far) - lq.at(near));
  const Beside beyond_strip = lq.step(beyond) && lq.jump(beyond) * lq.jump(far) > 0.0
                                  ? Beside{std::abs(lq.at(beyond) - lq.at(far)), lq.jump(beyond)}
                                  : Beside{};
  const Line line = wave_right
                        ? line_through(lq.jump(near), lq.jump(far), strip, Beside{}, beyond_strip, kPlateauRatio)
                        : line_through(lq.jump(far), lq.jump(near), strip, beyond_strip, Beside{}, kPlateauRatio);
  if (std::isnan(line.slope) || line.slope * lq.jump(near) <= 0.0) return 0.0;
  const Piece& pc = pieces_[piece];
  const double x_left = a != kNone ? lq.at(a) : nodes_[pc.left_end].x_at(lq.t);
  const double x_right = b != kNone ? lq.at(b) : nodes_[pc.right_end].x_at(lq.t);
  bool on = false;
  if ((wave_right ? a : b) == kNone && x_right - x_left <= kPlateauRatio * strip) {
    // The other family's front nearest that end (C− fronts stand left to right, C+ ones right
    // to left) is smooth: the wave is reflecting there.
    const LightPiece& lp = light_[piece];
    const std::deque<LightFront>& other = lq.family > 0 ? lp.minus : lp.plus;
    if (!other.empty()) {
      const LightFront& nearest = (lq.family > 0) == wave_right ? other.front() : other.back();
      const double x_end = wave_right ? x_left : x_right;
      on = nearest.smooth && std::abs(nearest.x_at(lq.t, -lq.family) - x_end) <= kPlateauRatio * strip;
    }
  }
  // Relative to the plateau: the wave's strip next to it differs from it by the near step's jump.
  const int clip = on ? 0 : (lq.jump(near) > 0.0) == wave_right ? 1 : -1;
  const Ramp ramp = wave_right ? Ramp{line.at_a + lq.jump(near), line.slope, lq.at(near), clip}
                               : Ramp{line.at_b - lq.jump(near), line.slope, lq.at(near), clip};
  return ramp.at(lq.x);
}

}  // namespace rigidity::characteristics
