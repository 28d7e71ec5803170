#include "rigidity/solvers/characteristics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <sstream>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/sampling.hpp"

namespace rigidity {

namespace {

constexpr int kNone = -1;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Steps a single rarefaction fan may be split into; beyond it the fan is coarser
/// than solver.tolerance and the run says so in its warnings.
constexpr int kMaxFanSteps = 100000;
/// A merge of two neighbouring fronts may cost at most this fraction of the tolerance's L1
/// budget (tolerance × natural length of all bodies): thousands of merges fit in it.
constexpr double kMergeFraction = 1.0;
/// Live fronts per body beyond which merges may cost more (see Tracker::steer_merges):
/// kFrontsPerBody / tolerance, at least kMinFrontsPerBody.
constexpr double kFrontsPerBody = 0.5;
constexpr double kMinFrontsPerBody = 100.0;
/// The most a merge may cost, as a multiple of its cost while fronts are few.
constexpr double kMergeCeiling = 1e4;
/// Growth of an L1 error between the time it is made and t_end allowed for in the bound.
constexpr double kStability = 2.0;
/// How many fronts of the other family a merge of two fronts of one family may reach across.
constexpr int kMergeReach = 8;

enum class NodeKind : std::uint8_t { front, interface, left_end, right_end };
/// What a body end touches.
enum class Attach : std::uint8_t { free, boundary, body };

struct Region {
  const Material* material = nullptr;
  State state;
};

/// A node of a piece's list: a front, a material interface or an end. Between
/// interactions it moves on a straight line in both X and x.
struct Node {
  NodeKind kind = NodeKind::front;
  FrontKind front_kind = FrontKind::contact;
  int family = 0;
  double t0 = 0.0, X0 = 0.0, x0 = 0.0;  ///< anchor: label and lab position at time t0
  double dXdt = 0.0, dxdt = 0.0;
  int prev = kNone, next = kNone;       ///< neighbours within the piece
  Region right;                         ///< the state between this node and `next`
  std::uint32_t version = 0;
  bool alive = true;
  Attach attach = Attach::free;         ///< end nodes only
  int partner = kNone;                  ///< Attach::body: the touching end node; Attach::boundary: 0 left, 1 right
  int piece = kNone;
  double born = 0.0;                    ///< fronts: when the wave it carries was created (fan error grows from then)
  /// Interfaces and contacts: a wave weaker than the threshold that this node did not emit
  /// (its strength times its speed, the L1 error it adds per unit time), since when, and
  /// the most it can add (strength times the natural length it could sweep).
  double defect_rate = 0.0, defect_since = 0.0, defect_cap = 0.0;

  [[nodiscard]] double X_at(double t) const { return X0 + dXdt * (t - t0); }
  [[nodiscard]] double x_at(double t) const { return x0 + dxdt * (t - t0); }
  [[nodiscard]] bool is_end() const { return kind == NodeKind::left_end || kind == NodeKind::right_end; }
};

/// A connected piece of a body (a body that cavitates becomes several pieces).
struct Piece {
  int body = 0;
  int left_end = kNone, right_end = kNone;
};

/// A wall or piston. Its lab position is piecewise linear in time.
struct Wall {
  bool present = false;
  bool bonded = false;
  double t0 = 0.0, x0 = 0.0, rapidity = 0.0;
  std::size_t segment = 0;               ///< index into motion of the velocity in force
  PistonMotion motion;                   ///< empty for a fixed wall
  int attached = kNone;                  ///< the end node touching it
  std::uint32_t version = 0;
  double pressure_since = 0.0;           ///< for the impulse: time the current contact pressure started
  [[nodiscard]] double velocity() const { return std::tanh(rapidity); }
  [[nodiscard]] double x_at(double t) const { return x0 + velocity() * (t - t0); }
  [[nodiscard]] double next_change() const {
    return segment + 1 < motion.times.size() ? motion.times[segment + 1] : kInf;
  }
};

/// Events other than nodes meeting (those live in MeetingQueue).
enum class EventType : std::uint8_t { resolve, gap, wall_gap, piston };

struct Event {
  double t;
  std::uint64_t seq;
  EventType type;
  int a, b;               ///< nodes (b: wall side 0/1 for wall_gap; a: wall side for piston)
  std::uint32_t va, vb;
};

struct EventLater {
  bool operator()(const Event& x, const Event& y) const { return x.t != y.t ? x.t > y.t : x.seq > y.seq; }
};

/// The next meeting of each node with its right neighbour: a binary min-heap invalidated
/// lazily, as event-driven codes do. Each node has a stamp; scheduling or cancelling its
/// meeting bumps the stamp, and an entry whose stamp no longer matches is dropped when it
/// reaches the top. Nothing is erased from the middle of the heap; when stale entries
/// outnumber the live ones the heap is rebuilt from the live ones, so its size stays within
/// a few times the number of live fronts.
class MeetingQueue {
 public:
  struct Entry {
    double t;
    std::uint64_t seq;
    int node;
    std::uint32_t stamp;
  };

  /// Drops stale entries from the top; call before empty() and top().
  void prune() {
    while (!heap_.empty() && !current(heap_.front())) pop_heap();
  }
  [[nodiscard]] bool empty() const { return heap_.empty(); }
  [[nodiscard]] const Entry& top() const { return heap_.front(); }

  void set(int node, double t, std::uint64_t seq) {
    grow(node);
    if (!scheduled_[node]) ++live_;
    scheduled_[node] = true;
    heap_.push_back(Entry{t, seq, node, ++stamp_[node]});
    std::push_heap(heap_.begin(), heap_.end(), later);
    if (heap_.size() > 4 * static_cast<std::size_t>(live_) + 1024) compact();
  }

  void erase(int node) {
    if (node >= static_cast<int>(stamp_.size()) || !scheduled_[node]) return;
    scheduled_[node] = false;
    --live_;
    ++stamp_[node];
  }

 private:
  static bool later(const Entry& a, const Entry& b) { return a.t != b.t ? a.t > b.t : a.seq > b.seq; }
  [[nodiscard]] bool current(const Entry& e) const { return scheduled_[e.node] && stamp_[e.node] == e.stamp; }
  void grow(int node) {
    if (node < static_cast<int>(stamp_.size())) return;
    stamp_.resize(static_cast<std::size_t>(node) + 1, 0);
    scheduled_.resize(static_cast<std::size_t>(node) + 1, false);
  }
  void pop_heap() {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    heap_.pop_back();
  }
  void compact() {
    heap_.erase(std::remove_if(heap_.begin(), heap_.end(), [this](const Entry& e) { return !current(e); }),
                heap_.end());
    std::make_heap(heap_.begin(), heap_.end(), later);
  }

  std::vector<Entry> heap_;
  std::vector<std::uint32_t> stamp_;
  std::vector<bool> scheduled_;
  long live_ = 0;
};

/// One wave of a Riemann solution, as the states it passes through.
struct WaveStates {
  std::vector<State> states;  ///< outer state first, star state last
  bool shock = false;
};


/// The strength of a wave of family `family` between two states of one material: the jump
/// of its own Riemann invariant (J+ = φ + Ψ for a C+ wave, J− = φ − Ψ for a C− wave), in
/// units of rapidity whatever the material. Signed: from `a` to `b`.
double wave_strength(const Material& m, const State& a, const State& b, int family) {
  return (b.rapidity - a.rapidity) + family * (m.riemann_psi(b.stretch) - m.riemann_psi(a.stretch));
}

/// Both speeds of a front between states a (left) and b (right) from the label jump condition
/// m [s/γ] = −[v]; its lab speed is then the same seen from either side, so lab positions
/// stay continuous across it. Written without cancellation for weak fronts:
/// m = −sinh(φb − φa) / (sb cosh φa − sa cosh φb). Falls back to the mean characteristic
/// speed of family `family` where the jump is too small to define it.
FrontSpeeds label_jump_speeds(const Material& m, const State& a, const State& b, int family) {
  const double ca = std::cosh(a.rapidity);
  const double half = 0.5 * (b.rapidity - a.rapidity);
  const double denominator =
      a.stretch.value() * (std::expm1(b.stretch.log() - a.stretch.log()) * ca -
                           2.0 * std::sinh(0.5 * (a.rapidity + b.rapidity)) * std::sinh(half));
  const double speed = -std::sinh(b.rapidity - a.rapidity) / denominator;
  if (!std::isfinite(speed) || denominator == 0.0) {
    const FrontSpeeds sa = characteristic_speeds(m, a, family), sb = characteristic_speeds(m, b, family);
    return FrontSpeeds{0.5 * (sa.lagrangian + sb.lagrangian), 0.5 * (sa.lab + sb.lab)};
  }
  return FrontSpeeds{speed, std::tanh(a.rapidity) + speed * a.stretch.value() / ca};
}

/// The rapidity of the state at stretch `star` that a shock of family `family` connects to
/// `outer`, in closed form. In the rest frame of the outer state the label and momentum jump
/// conditions, with u = γv of the star, give Δp s0 γ = s (Δp + w u²) (w = e + p at the star),
/// a quadratic in Y = u²/Δp:  s²w² Y² + (2 s² w − Δp s0²) Y + (s² − s0²) = 0,
/// whose root of the sign of Δp is taken in its stable form. Rapidities add along the line.
Solved<double> hugoniot_rapidity(const Material& m, const State& outer, Stretch star, int family) {
  const double s0 = outer.stretch.value(), s = star.value();
  const double dp = m.pressure(star) - m.pressure(outer.stretch);
  const double w = m.enthalpy_density(star);
  const double qa = s * s * w * w;
  const double qb = 2.0 * s * s * w - dp * s0 * s0;
  const double qc = s0 * s0 * std::expm1(2.0 * (star.log() - outer.stretch.log()));
  const double disc = qb * qb - 4.0 * qa * qc;
  if (!(disc >= 0.0) || dp == 0.0) return Solved<double>::failure(Status::out_of_range);
  const double root = std::sqrt(disc);
  const double y = qb >= 0.0 ? 2.0 * qc / (-qb - root) : (-qb + root) / (2.0 * qa);
  const double u2 = dp * y;
  if (!(u2 >= 0.0) || !(dp + w * u2 != 0.0) || ((dp + w * u2) > 0.0) != (dp > 0.0))
    return Solved<double>::failure(Status::out_of_range);
  const double relative = std::asinh(std::sqrt(u2));
  // A compression slows the state behind a C− shock (it moves against the family's direction).
  const double direction = m.riemann_psi(star) > m.riemann_psi(outer.stretch) ? family : -family;
  return Solved<double>{outer.rapidity + direction * relative, Status::ok};
}

/// The rapidity at stretch e^z on the wave curve of family `family` through `outer`: the
/// closed-form Hugoniot where that wave is a shock, else the integral curve (the other
/// family's invariant carried across: φ = φ_outer + family (Ψ − Ψ_outer)).
Solved<double> curve_rapidity(const Material& m, const State& outer, double psi_outer, double z, int family) {
  const Stretch s = Stretch::from_log(z);
  if (wave_is_shock(m, outer, s, family)) return hugoniot_rapidity(m, outer, s, family);
  return Solved<double>{outer.rapidity + family * (m.riemann_psi(s) - psi_outer), Status::ok};
}

/// The exact star state between two states of one material: ln s* where the C− curve
/// through `left` meets the C+ curve through `right`, by secant steps from `guess` (the
/// two-rarefaction star, within third order of the answer for weak waves). Every curve is
/// closed form, so a weak interaction costs a few evaluations of the material.
Solved<State> same_material_star(const Material& m, const State& left, const State& right, const State& guess) {
  const double psi_left = m.riemann_psi(left.stretch), psi_right = m.riemann_psi(right.stretch);
  double rapidity = guess.rapidity;
  auto mismatch = [&](double z, double& g) {
    const Solved<double> a = curve_rapidity(m, left, psi_left, z, -1);
    const Solved<double> b = curve_rapidity(m, right, psi_right, z, +1);
    if (!a.ok() || !b.ok()) return false;
    g = a.value - b.value;
    rapidity = 0.5 * (a.value + b.value);
    return std::isfinite(g);
  };
  double z0 = guess.stretch.log(), g0 = 0.0;
  if (!mismatch(z0, g0)) return Solved<State>::failure(Status::not_converged);
  if (g0 == 0.0) return Solved<State>{State{rapidity, guess.stretch}, Status::ok};
  // dφ/d ln s is +c_s on the C− curve and −c_s on the C+ curve near the star: g' ≈ 2 c_s.
  double z1 = z0 - g0 / (2.0 * m.sound_speed(guess.stretch)), g1 = 0.0;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const StretchRange range = m.admissible();
    if (!(z1 > range.log_min && z1 < range.log_max)) return Solved<State>::failure(Status::out_of_range);
    if (!mismatch(z1, g1)) return Solved<State>::failure(Status::not_converged);
    if (g1 == 0.0 || std::abs(z1 - z0) <= 2.0 * kEps * (1.0 + std::abs(z1)))
      return Solved<State>{State{rapidity, Stretch::from_log(z1)}, Status::ok};
    if (g1 == g0) return Solved<State>::failure(Status::not_converged);
    const double z2 = z1 - g1 * (z1 - z0) / (g1 - g0);
    z0 = z1;
    g0 = g1;
    z1 = z2;
  }
  return Solved<State>::failure(Status::not_converged);
}

bool same_state(const State& a, const State& b) {
  return std::abs(a.rapidity - b.rapidity) <= 4.0 * kEps * (1.0 + std::abs(a.rapidity)) &&
         std::abs(a.stretch.log() - b.stretch.log()) <= 4.0 * kEps * (1.0 + std::abs(a.stretch.log()));
}

/// Lab positions equal up to the round-off of summing segment lengths.
bool touching(double x1, double x2) { return std::abs(x1 - x2) <= 64.0 * kEps * std::max({1.0, std::abs(x1), std::abs(x2)}); }

std::string number(double v) {
  std::ostringstream os;
  os.precision(12);
  os << v;
  return os.str();
}

class Tracker {
 public:
  explicit Tracker(const Scene& scene) : scene_(scene) {
    want_fronts_ = scene.outputs.fronts;
    fan_step_ = scene.solver.tolerance;
  }

  RunResult run();

 private:
  // ---- set-up -------------------------------------------------------------------
  void build_bodies();
  void build_walls();
  void collect_sample_times();

  // ---- node list ------------------------------------------------------------------
  int new_node(NodeKind kind, int piece) {
    int id;
    if (!free_nodes_.empty()) {
      id = free_nodes_.back();
      free_nodes_.pop_back();
      const std::uint32_t version = nodes_[id].version + 1;
      nodes_[id] = Node{};
      nodes_[id].version = version;
    } else {
      id = static_cast<int>(nodes_.size());
      nodes_.emplace_back();
    }
    nodes_[id].kind = kind;
    nodes_[id].piece = piece;
    return id;
  }
  /// Removes a node from the pool; a front's energy books must be closed first
  /// (account_front_end), while its neighbours are still its own.
  void kill_node(int id, double t) {
    Node& n = nodes_[id];
    if (n.kind == NodeKind::front) --live_fronts_;
    close_defect(n, t);
    record_segment(n, t);
    meetings_.erase(id);
    n.alive = false;
    ++n.version;
    free_nodes_.push_back(id);
  }
  void link(int a, int b) {
    if (a != kNone) nodes_[a].next = b;
    if (b != kNone) nodes_[b].prev = a;
  }

  // ---- events -----------------------------------------------------------------------
  void push(double t, EventType type, int a, int b, std::uint32_t va, std::uint32_t vb) {
    queue_.push(Event{t, seq_++, type, a, b, va, vb});
  }
  bool valid(const Event& e) const;
  void schedule_meet(int a);
  void schedule_gaps_around(int piece);
  void schedule_gap(int left_piece, int right_piece);
  void schedule_wall_gap(int side);
  void schedule_piston(int side);

  // ---- interactions -------------------------------------------------------------------
  void handle(const Event& e);
  void resolve(int seed_left, int seed_right, double t);
  bool rejoin(int right_end, int left_end, double t, double x);
  bool interact_in_place(int a, int b, double t);
  int merge_neighbours(int id, double t);
  bool merge_across(int p, int q, double t);
  void merge_nearby(int id, double t);
  struct MergeSegment {
    double a, b;             ///< label extent at the time of the merge
    State old;               ///< its state now
    double j_old;            ///< its f-invariant now
    State left, right;       ///< its state if left of the merged front, if right of it
    int right_node;          ///< the node at its right edge that stays (kNone: p or q)
  };
  std::vector<MergeSegment> segments_;
  double merge_cost(int p, int q, double t, double* X_merged) const;
  void set_front(int id, int family, FrontKind kind, const Material& m, const State& left, const State& right,
                 double t, double X, double x, double off_hugoniot, double born);
  void resolve_group(std::vector<int>& group, double t);
  void wave(const Material& m, const State& outer, const State& star, int family, WaveStates& w);
  void emit_fronts(const Material& m, const WaveStates& w, int family, int piece, double t, double X, double x,
                   std::vector<int>& out);
  void reanchor(int id, double t);
  void split_piece(int left_node, int right_node, const State& left_state, const State& right_state,
                   const Region& left_region, const Region& right_region, double t, double X, double x);
  void set_attach(int end, Attach attach, int partner, double t);
  void flush_wall(int side, double t);
  // ---- outputs --------------------------------------------------------------------------
  void record_segment(Node& n, double t);
  void account_front_end(int id, double t);
  void sample(const SampleTime& st);
  /// The region at label X of `body` at time t, with the lab position of X.
  bool locate(int body, double X, double t, Region& region, double& x) const;
  double quantity(Quantity q, const Region& r, double X, double x) const;
  void totals(double t, double& energy, double& momentum) const;
  void event(double t, const char* kind, double x, std::vector<std::string> bodies) {
    result_.events.push_back(RunEvent{t, kind, x, std::move(bodies)});
  }
  std::string piece_body_name(int piece) const { return scene_.bodies[pieces_[piece].body].name; }

  const Scene& scene_;
  bool want_fronts_ = false;
  double fan_step_ = 1e-12;
  bool fan_capped_ = false;
  // ---- the error budget (see README "What the tolerance means") --------------------
  double weak_ = 0.0;               ///< strength |ΔJ| below which an interface or contact emits no wave
  double weak_merging_ = 0.0;       ///< strength below which two fronts of one family merging emit no reflection
  double total_length_ = 1.0;       ///< natural length of all bodies: the error bound is per unit of it
  double error_defects_ = 0.0;      ///< L1 error of waves held back at interfaces and contacts
  double error_fans_ = 0.0;         ///< L1 error of fan steps whose fans are gone
  long suppressed_ = 0;             ///< weak waves held back
  double merge_base_ = 0.0;         ///< largest L1 error (strength × distance) of a merge while fronts are few
  double merge_ = 0.0;              ///< the same now: raised while the live fronts exceed front_cap_
  double front_cap_ = 0.0;
  /// A solution that grows rough (a pulse scattered by many contacts into more and more
  /// waves) cannot be held to a fixed L1 error by a bounded number of fronts. Work is bounded
  /// first: while more fronts live than front_cap_, the cost a merge may have grows by 1 %
  /// per interaction, and falls back towards merge_base_ once they are half as many. The
  /// bound reports what it cost.
  void steer_merges() {
    if (static_cast<double>(live_fronts_) > front_cap_) {
      merge_ = std::min(merge_ * 1.01, kMergeCeiling * merge_base_);
    } else if (merge_ > merge_base_ && static_cast<double>(live_fronts_) < 0.5 * front_cap_) {
      merge_ = std::max(merge_base_, merge_ / 1.01);
    }
  }
  double error_merges_ = 0.0;       ///< L1 error of fronts merged
  long merged_ = 0;
  long live_fronts_max_ = 0;

  void close_defect(Node& n, double t) {
    if (n.defect_rate <= 0.0) return;
    error_defects_ += std::min(n.defect_rate * (t - n.defect_since), n.defect_cap);
    n.defect_rate = 0.0;
  }
  /// The L1 error of a rarefaction step at time t: the exact fan spreads the step's jump σ
  /// over |Δλ| (t − born) in X (no more than the piece), which a jump in its middle misses
  /// by σ/4 of that width on average.
  double fan_error(int id, double t) const;
  double piece_length(int piece) const {
    return nodes_[pieces_[piece].right_end].X0 - nodes_[pieces_[piece].left_end].X0;  // ends move with the material
  }
  void hold_back_weak_wave(RiemannSolution& sol, const Region& left, const Region& right, int holder,
                           double min_pressure, double t);

  std::vector<Node> nodes_;
  std::vector<int> free_nodes_;
  std::vector<Piece> pieces_;
  std::vector<int> order_;  ///< pieces in lab order, left to right
  Wall walls_[2];
  std::priority_queue<Event, std::vector<Event>, EventLater> queue_;  ///< rare events: gaps, pistons, t = 0
  MeetingQueue meetings_;                                              ///< fronts meeting fronts, ends, interfaces
  std::uint64_t seq_ = 0;
  long live_fronts_ = 0;

  std::vector<SampleTime> samples_;
  RunResult result_;
  double impulse_ = 0.0, wall_work_ = 0.0, dissipated_ = 0.0;
  double last_interaction_t_ = -1.0;
  long interactions_at_this_t_ = 0;

  // scratch buffers reused by every interaction
  std::vector<int> group_, emitted_left_, emitted_right_, touched_;
  WaveStates wave_left_, wave_right_;
};

// =====================================================================================
// set-up

void Tracker::build_bodies() {
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const BodyDecl& body = scene_.bodies[b];
    const int piece = static_cast<int>(pieces_.size());
    pieces_.push_back(Piece{static_cast<int>(b), kNone, kNone});
    order_.push_back(piece);
    double X = 0.0, x = body.position;
    const int left = new_node(NodeKind::left_end, piece);
    nodes_[left].front_kind = FrontKind::boundary;
    nodes_[left].x0 = x;
    int last = left;
    for (std::size_t k = 0; k < body.segments.size(); ++k) {
      const Segment& seg = body.segments[k];
      const Region region{&scene_.material_of(seg), State{seg.rapidity, seg.stretch}};
      if (k > 0) {
        // An initial discontinuity: an interface between materials, else a
        // stationary jump resolved at t = 0.
        const bool interface = region.material != nodes_[last].right.material;
        const int n = new_node(interface ? NodeKind::interface : NodeKind::front, piece);
        nodes_[n].front_kind = interface ? FrontKind::interface : FrontKind::contact;
        nodes_[n].X0 = X;
        nodes_[n].x0 = x;
        if (!interface) ++live_fronts_;
        link(last, n);
        last = n;
      }
      nodes_[last].right = region;
      X += seg.length;
      x += seg.length * seg.stretch.value() / std::cosh(seg.rapidity);
    }
    const int right = new_node(NodeKind::right_end, piece);
    nodes_[right].front_kind = FrontKind::boundary;
    nodes_[right].X0 = X;
    nodes_[right].x0 = x;
    link(last, right);
    pieces_[piece].left_end = left;
    pieces_[piece].right_end = right;
    // End and interface nodes move with the material next to them.
    for (int n = left; n != kNone; n = nodes_[n].next) {
      if (nodes_[n].kind == NodeKind::front) continue;
      const Region& r = nodes_[n].kind == NodeKind::right_end ? nodes_[nodes_[n].prev].right : nodes_[n].right;
      nodes_[n].dxdt = std::tanh(r.state.rapidity);
    }
  }
}

void Tracker::build_walls() {
  const BoundaryDecl* decls[2] = {&scene_.left, &scene_.right};
  for (int side = 0; side < 2; ++side) {
    const BoundaryDecl& d = *decls[side];
    Wall& w = walls_[side];
    w.present = d.type != BoundaryType::free;
    if (!w.present) continue;
    w.bonded = d.bonded;
    w.x0 = d.position;
    w.t0 = 0.0;
    if (d.type == BoundaryType::piston) {
      w.motion = d.piston;
      w.rapidity = w.motion.rapidities.empty() ? 0.0 : w.motion.rapidities.front();
    }
  }
}

void Tracker::collect_sample_times() { samples_ = sample_times(scene_); }

// =====================================================================================
// events

bool Tracker::valid(const Event& e) const {
  switch (e.type) {
    case EventType::resolve: return nodes_[e.a].alive && nodes_[e.a].version == e.va;
    case EventType::gap:
      return nodes_[e.a].alive && nodes_[e.b].alive && nodes_[e.a].version == e.va &&
             nodes_[e.b].version == e.vb && nodes_[e.a].attach == Attach::free &&
             nodes_[e.b].attach == Attach::free;
    case EventType::wall_gap:
      return nodes_[e.a].alive && nodes_[e.a].version == e.va && walls_[e.b].version == e.vb &&
             nodes_[e.a].attach == Attach::free;
    case EventType::piston: return walls_[e.a].version == e.va;
  }
  return false;
}

void Tracker::schedule_meet(int a) {
  const Node& na = nodes_[a];
  const int b = na.next;
  if (b != kNone) {
    const Node& nb = nodes_[b];
    const double closing = na.dXdt - nb.dXdt;
    if (closing > 0.0) {
      const double t_ref = std::max(na.t0, nb.t0);
      const double gap = std::max(0.0, nb.X_at(t_ref) - na.X_at(t_ref));
      const double t = t_ref + gap / closing;
      if (t <= scene_.t_end) {
        meetings_.set(a, t, seq_++);
        return;
      }
    }
  }
  meetings_.erase(a);
}

void Tracker::schedule_gap(int left_piece, int right_piece) {
  const int a = pieces_[left_piece].right_end, b = pieces_[right_piece].left_end;
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  if (na.attach != Attach::free || nb.attach != Attach::free) return;
  const double closing = na.dxdt - nb.dxdt;
  if (!(closing > 0.0)) return;
  const double t_ref = std::max(na.t0, nb.t0);
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
  const double distance = side == 0 ? n.x_at(t_ref) - w.x_at(t_ref) : w.x_at(t_ref) - n.x_at(t_ref);
  const double t = t_ref + std::max(0.0, distance) / closing;
  if (t <= scene_.t_end && t <= w.next_change()) push(t, EventType::wall_gap, end, side, n.version, w.version);
}

void Tracker::schedule_piston(int side) {
  const Wall& w = walls_[side];
  const double t = w.next_change();
  if (w.present && t <= scene_.t_end) push(t, EventType::piston, side, 0, w.version, 0);
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

// =====================================================================================
// interactions

void Tracker::handle(const Event& e) {
  const double t = e.t;
  switch (e.type) {
    case EventType::resolve: resolve(e.a, e.a, t); break;
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
      w.x0 = w.x_at(t);
      w.t0 = t;
      ++w.segment;
      w.rapidity = w.motion.rapidities[w.segment];
      ++w.version;
      schedule_piston(e.a);
      if (w.attached != kNone) {
        resolve(w.attached, w.attached, t);
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
  order_.erase(std::find(order_.begin(), order_.end(), b));
  event(t, "rejoin", x, {piece_body_name(a)});
  resolve(junction, junction, t);
  schedule_gaps_around(a);
  return true;
}

/// Two fronts of one material meeting with nothing else there, done in place: they leave
/// as a C− front (in a's node) and a C+ front (in b's node) around the star state of the
/// two-rarefaction solver, J+ from the left state and J− from the right one. For a linearly
/// degenerate material that star is exact. For a genuinely nonlinear one it misses the exact
/// star by the jump of the other invariant across the shocks, third order in their strength:
/// it is used when that jump, computed from the closed-form Hugoniot, is below the weak-wave
/// threshold, and the front carries it as an error rate for as long as it lives; a C− wave
/// left weaker than the threshold by two fronts of one family merging is held back (its
/// strength times the length it could sweep is booked). Returns false (doing nothing) when
/// the full Riemann problem is needed: a crowd, a strong shock, a fan to split, cavitation.
bool Tracker::interact_in_place(int a, int b, double t) {
  if (result_.stats.interactions >= scene_.solver.max_interactions) return false;  // resolve_group reports it
  Node& na = nodes_[a];
  Node& nb = nodes_[b];
  if (na.kind != NodeKind::front || nb.kind != NodeKind::front) return false;
  const Node& before = nodes_[na.prev];
  const Node& after = nodes_[nb.next];
  const Material* m = before.right.material;
  if (m != nb.right.material || m != na.right.material) return false;
  const bool degenerate = m->linearly_degenerate();
  if (degenerate && (na.family != +1 || nb.family != -1)) return false;
  const double X = 0.5 * (na.X_at(t) + nb.X_at(t));
  const double tolerance = 8.0 * kEps * (1.0 + std::abs(X));
  if (before.X_at(t) >= X - tolerance || after.X_at(t) <= X + tolerance) return false;  // a crowd: resolve in full
  const State& left = before.right.state;
  const State& right = nb.right.state;
  const double j_plus = left.rapidity + m->riemann_psi(left.stretch);
  const double j_minus = right.rapidity - m->riemann_psi(right.stretch);
  const double psi_star = 0.5 * (j_plus - j_minus);
  if (!(psi_star < m->psi_max())) return false;
  if (m->cavitation_pressure() > -kInf) {
    const Solved<Stretch> parting = m->stretch_at_pressure(m->cavitation_pressure());
    if (!parting.ok() || psi_star < m->riemann_psi(parting.value)) return false;
  }
  const Solved<Stretch> star_stretch = m->stretch_at_psi(psi_star);
  if (!star_stretch.ok()) return false;
  State star{0.5 * (j_plus + j_minus), star_stretch.value};

  // The outgoing waves: kinds, and for shocks their distance from the exact Hugoniot.
  FrontKind kinds[2] = {FrontKind::contact, FrontKind::contact};
  double off_hugoniot[2] = {0.0, 0.0};
  bool held_back = false;  // the C− wave, weaker than the threshold, is not emitted
  double held_strength = 0.0;
  if (degenerate) {
    if (same_state(star, left) || same_state(star, right)) return false;  // a wave vanishes
  } else {
    const Solved<State> exact_star = same_material_star(*m, left, right, star);
    if (!exact_star.ok()) return false;
    star = exact_star.value;
    held_strength = std::abs(wave_strength(*m, left, star, -1));
    if (held_strength < weak_merging_ && na.family == nb.family) {
      held_back = true;
      star = left;
    }
    for (int k = held_back ? 1 : 0; k < 2; ++k) {
      const int family = k == 0 ? -1 : +1;
      const State& outer = k == 0 ? left : right;
      if (same_state(outer, star)) return false;
      if (wave_is_shock(*m, outer, star.stretch, family)) {
        kinds[k] = FrontKind::shock;
        const Solved<double> exact = hugoniot_rapidity(*m, outer, star.stretch, family);
        if (!exact.ok()) return false;
        off_hugoniot[k] = std::abs(exact.value - star.rapidity);
        if (!(off_hugoniot[k] < weak_)) return false;
      } else {
        kinds[k] = FrontKind::rarefaction;
        const double span = std::abs(m->riemann_psi(star.stretch) - m->riemann_psi(outer.stretch));
        if (span >= 2.0 * fan_step_) return false;  // a fan to split in steps
      }
    }
  }

  if (held_back && !(std::abs(label_jump_speeds(*m, left, right, +1).lab) < 1.0)) return false;  // no faster than light

  // Fan steps keep their age through the interaction when they leave as the only step of
  // their family; otherwise the error they carry is booked now.
  double born[2] = {t, t};
  for (Node* n : {&na, &nb}) {
    if (n->front_kind != FrontKind::rarefaction) continue;
    const int k = n->family > 0 ? 1 : 0;
    const bool continues = kinds[k] == FrontKind::rarefaction && !(held_back && k == 0) &&
                           (na.family != nb.family || degenerate);
    if (continues && born[k] == t) {
      born[k] = n->born;
    } else {
      error_fans_ += fan_error(static_cast<int>(n - nodes_.data()), t);
    }
  }

  ++result_.stats.interactions;
  steer_merges();
  const double x = 0.5 * (na.x_at(t) + nb.x_at(t));
  close_defect(na, t);
  close_defect(nb, t);
  record_segment(na, t);
  record_segment(nb, t);
  if (held_back) {
    error_defects_ += held_strength * std::min(piece_length(na.piece),
                                               std::abs(characteristic_speed(*m, left, -1)) * (scene_.t_end - t));
    ++suppressed_;
    const int keep_before = na.prev;
    account_front_end(a, t);  // its shock books close while its neighbours are still its own
    link(keep_before, b);
    kill_node(a, t);
    set_front(b, +1, kinds[1], *m, left, right, t, X, x, off_hugoniot[1], born[1]);
    schedule_meet(keep_before);
    schedule_meet(b);
    return true;
  }
  account_front_end(a, t);
  account_front_end(b, t);
  result_.stats.fronts += 2;
  set_front(a, -1, kinds[0], *m, left, star, t, X, x, off_hugoniot[0], born[0]);
  set_front(b, +1, kinds[1], *m, star, right, t, X, x, off_hugoniot[1], born[1]);
  na.right.state = star;
  schedule_meet(na.prev);
  schedule_meet(a);
  schedule_meet(b);
  if (degenerate) {
    merge_nearby(a, t);
    merge_nearby(b, t);
  } else {
    merge_neighbours(a, t);
    merge_neighbours(b, t);
  }
  return true;
}

/// A front of family `family` between the states `left` and `right` of material m, leaving
/// (X, x) at time t. Jumps of a linearly degenerate material move at the characteristic
/// speed; shocks and fan steps at the speed the label jump condition gives, so that the lab
/// position of every label stays continuous across them.
void Tracker::set_front(int id, int family, FrontKind kind, const Material& m, const State& left, const State& right,
                        double t, double X, double x, double off_hugoniot, double born) {
  Node& n = nodes_[id];
  const FrontSpeeds speeds = kind == FrontKind::contact ? characteristic_speeds(m, right, family)
                                                        : label_jump_speeds(m, left, right, family);
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

/// Two neighbouring fronts of one family in one material whose weaker one is within
/// `merge_` (strength times distance, the L1 error of moving it) of the other are one front:
/// the weaker one moves onto the stronger, which then joins the outer states. For a
/// linearly degenerate material that front is exact (the other invariant is the same on
/// all three states); a shock of a genuinely nonlinear one must stay near its Hugoniot and
/// a fan step within two fan steps. Keeps the fronts of long multi-body runs from growing
/// without bound; returns the surviving front.
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
  const double lower = nodes_[np.prev].X_at(t), upper = nodes_[nq.next].X_at(t);
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
    int best_left = kNone;
    double best_cost = merge_;
    for (int side = 0; side < 2; ++side) {
      const int p = side == 0 ? nodes_[id].prev : id;
      const int q = side == 0 ? id : nodes_[id].next;
      if (p == kNone || q == kNone) continue;
      const Node& np = nodes_[p];
      const Node& nq = nodes_[q];
      if (np.kind != NodeKind::front || nq.kind != NodeKind::front || np.family != nq.family) continue;
      const Region& L = nodes_[np.prev].right;
      if (L.material != np.right.material || L.material != nq.right.material) continue;
      const double cost = merge_cost(p, q, t, nullptr);
      if (cost <= best_cost) {
        best_cost = cost;
        best_left = p;
      }
    }
    if (best_left == kNone) return id;
    double X = 0.0;
    const int p = best_left, q = nodes_[p].next;
    const int family = nodes_[p].family;
    const Region L = nodes_[nodes_[p].prev].right;
    const Region R = nodes_[q].right;
    const Material& m = *L.material;
    const State& outer = family < 0 ? L.state : R.state;
    const State& inner = family < 0 ? R.state : L.state;
    FrontKind kind = FrontKind::contact;
    double off = 0.0;
    if (!m.linearly_degenerate()) {
      if (same_state(outer, inner)) return id;
      if (wave_is_shock(m, outer, inner.stretch, family)) {
        kind = FrontKind::shock;
        const Solved<double> exact = hugoniot_rapidity(m, outer, inner.stretch, family);
        if (!exact.ok()) return id;
        off = std::abs(exact.value - inner.rapidity);
        if (!(off < weak_)) return id;
      } else {
        kind = FrontKind::rarefaction;
        if (std::abs(m.riemann_psi(outer.stretch) - m.riemann_psi(inner.stretch)) >= 2.0 * fan_step_) return id;
      }
      if (!(std::abs(label_jump_speeds(m, L.state, R.state, family).lab) < 1.0)) return id;  // no faster than light
    }
    merge_cost(p, q, t, &X);
    const double x = nodes_[p].x_at(t) + (X - nodes_[p].X_at(t)) * label_density(L.state);
    const double strength_p = std::abs(wave_strength(m, L.state, nodes_[p].right.state, family));
    const double strength_q = std::abs(wave_strength(m, nodes_[p].right.state, R.state, family));
    const int kept = strength_p >= strength_q ? p : q;
    const int gone = kept == p ? q : p;
    for (int n : {p, q}) {
      account_front_end(n, t);
      if (nodes_[n].front_kind == FrontKind::rarefaction) error_fans_ += fan_error(n, t);
    }
    error_merges_ += best_cost;
    ++merged_;
    record_segment(nodes_[kept], t);
    close_defect(nodes_[kept], t);
    nodes_[p].right = R;  // p's right region was the middle state
    link(nodes_[gone].prev, nodes_[gone].next);
    if (kept == q) nodes_[q].right = R;
    kill_node(gone, t);
    set_front(kept, family, kind, m, L.state, R.state, t, X, x, off, t);
    if (nodes_[kept].prev != kNone) schedule_meet(nodes_[kept].prev);
    schedule_meet(kept);
    id = kept;
  }
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
  const Material& m = *nodes_[p].right.material;
  const int f = nodes_[p].family;
  const int left_of_p = nodes_[p].prev, right_of_q = nodes_[q].next;
  if (left_of_p == kNone || right_of_q == kNone) return false;
  const auto invariant = [&](const State& st, int family) { return st.rapidity + family * m.riemann_psi(st.stretch); };
  const State before = nodes_[left_of_p].right.state;
  const State after_q = nodes_[q].right.state;
  const double j_before = invariant(before, f), j_after_p = invariant(nodes_[p].right.state, f);
  const double j_after_q = invariant(after_q, f);
  const double Xp = nodes_[p].X_at(t), Xq = nodes_[q].X_at(t);
  if (std::min(std::abs(j_after_p - j_before), std::abs(j_after_q - j_after_p)) * (Xq - Xp) > merge_) return false;
  const auto with_invariant = [&](const State& st, double j_f) -> Solved<State> {
    const double j_other = invariant(st, -f);
    const double j_plus = f > 0 ? j_f : j_other, j_minus = f > 0 ? j_other : j_f;
    const double psi = 0.5 * (j_plus - j_minus);
    if (!(psi < m.psi_max() && psi > m.psi_min())) return Solved<State>::failure(Status::out_of_range);
    const Solved<Stretch> stretch = m.stretch_at_psi(psi);
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
  const bool extend_left = nodes_[left_of_p].kind == NodeKind::front && nodes_[nodes_[left_of_p].prev].right.material == &m;
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
  // Lab length change as X̄ moves right from the first edge: all segments on their right
  // states at first, each turning to its left state as X̄ passes it.
  double change = 0.0;
  for (const MergeSegment& g : segments_) change += (label_density(g.right) - label_density(g.old)) * (g.b - g.a);
  double X_merged = kInf;
  std::size_t split = 0;
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
  if (X_merged <= segments_.front().a + margin || X_merged >= segments_.back().b - margin) return false;
  double cost = 0.0;
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const MergeSegment& g = segments_[i];
    const double left_part = i < split ? g.b - g.a : i == split ? X_merged - g.a : 0.0;
    cost += std::abs(j_before - g.j_old) * left_part + std::abs(j_after_q - g.j_old) * (g.b - g.a - left_part);
  }
  if (cost > merge_) return false;

  // Apply: p and q leave; one front of family f enters at X̄.
  error_merges_ += cost;
  ++merged_;
  const int start = extend_left ? left_of_p : left_of_p;
  double X_cursor = segments_.front().a;
  double x_cursor = extend_left ? nodes_[left_of_p].x_at(t) : nodes_[p].x_at(t);
  kill_node(p, t);
  kill_node(q, t);
  const int merged = new_node(NodeKind::front, nodes_[start].piece);
  live_fronts_max_ = std::max(live_fronts_max_, ++live_fronts_);
  ++result_.stats.fronts;
  Node& mn = nodes_[merged];
  mn.family = f;
  mn.front_kind = FrontKind::contact;
  mn.born = t;
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
  return true;
}

/// Looks for a front of the same family within a few nodes of `id`, across fronts of the
/// other family only, in one linearly degenerate material, and merges the two if cheap.
void Tracker::merge_nearby(int id, double t) {
  if (id == kNone || !nodes_[id].alive || nodes_[id].kind != NodeKind::front) return;
  const Material* m = nodes_[id].right.material;
  if (m == nullptr || !m->linearly_degenerate()) return;
  const int f = nodes_[id].family;
  for (int direction : {+1, -1}) {
    int n = id;
    for (int steps = 0; steps < kMergeReach; ++steps) {
      n = direction > 0 ? nodes_[n].next : nodes_[n].prev;
      if (n == kNone || nodes_[n].kind != NodeKind::front || nodes_[n].right.material != m) break;
      if (direction < 0 && nodes_[nodes_[n].prev].right.material != m) break;
      if (nodes_[n].family != f) continue;
      if (direction > 0 ? merge_across(id, n, t) : merge_across(n, id, t)) return;
      break;
    }
  }
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

void Tracker::wave(const Material& m, const State& outer, const State& star, int family, WaveStates& w) {
  w.states.clear();
  w.shock = false;
  w.states.push_back(outer);
  if (same_state(outer, star)) return;
  if (m.linearly_degenerate()) {
    w.states.push_back(star);
    return;
  }
  if (wave_is_shock(m, outer, star.stretch, family)) {
    w.shock = true;
    w.states.push_back(star);
    return;
  }
  // A rarefaction fan: states along the invariant of the other family, in steps of Ψ.
  const double psi_outer = m.riemann_psi(outer.stretch), psi_star = m.riemann_psi(star.stretch);
  const double span = std::abs(psi_star - psi_outer);
  // Steps between one and two fan steps wide: a step that has grown through interactions is
  // split only once it has doubled, so that crossings do not multiply the fronts of a fan.
  // The step count in double first: span / tolerance overflows an int for tolerances of 1e-11.
  const double wanted = std::floor(span / fan_step_);
  if (wanted > kMaxFanSteps) fan_capped_ = true;
  const int steps = std::max(1, static_cast<int>(std::min(wanted, static_cast<double>(kMaxFanSteps))));
  // J carried across: J+ = φ + Ψ for a C− fan, J− = φ − Ψ for a C+ fan.
  const double invariant = family < 0 ? outer.rapidity + psi_outer : outer.rapidity - psi_outer;
  for (int k = 1; k < steps; ++k) {
    const double psi = psi_outer + (psi_star - psi_outer) * k / steps;
    const Solved<Stretch> s = m.stretch_at_psi(psi);
    if (!s.ok()) throw NumericalError("a rarefaction fan state could not be found (Ψ = " + number(psi) + ")");
    w.states.push_back(State{family < 0 ? invariant - psi : invariant + psi, s.value});
  }
  w.states.push_back(star);
  return;
}

void Tracker::emit_fronts(const Material& m, const WaveStates& w, int family, int piece, double t, double X,
                          double x, std::vector<int>& out) {
  out.clear();
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
    if (w.shock) {
      n.front_kind = FrontKind::shock;
      const FrontSpeeds sp = family < 0 ? label_jump_speeds(m, outer, inner, family)
                                        : label_jump_speeds(m, inner, outer, family);
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
        const FrontSpeeds sp = family < 0 ? label_jump_speeds(m, outer, inner, family)
                                          : label_jump_speeds(m, inner, outer, family);
        n.dXdt = sp.lagrangian;
        n.dxdt = sp.lab;
      }
    }
    out.push_back(id);
    live_fronts_max_ = std::max(live_fronts_max_, ++live_fronts_);
    ++result_.stats.fronts;
  }
  if (live_fronts_ > scene_.solver.max_fronts) {
    throw NumericalError("more than solver.max_fronts = " + std::to_string(scene_.solver.max_fronts) +
                         " live fronts at t = " + number(t) +
                         "; raise solver.tolerance (coarser fans) or solver.max_fronts");
  }
}

void Tracker::reanchor(int id, double t) {
  Node& n = nodes_[id];
  const double X = n.X_at(t), x = n.x_at(t);
  record_segment(n, t);
  n.t0 = t;
  n.X0 = X;
  n.x0 = x;
  ++n.version;
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
  wall_work_ += force * w.velocity() * dt;
  w.pressure_since = t;
}

void Tracker::split_piece(int left_node, int right_node, const State& left_state, const State& right_state,
                          const Region& left_region, const Region& right_region, double t, double X, double x) {
  // The piece parts between left_node and right_node (either may be an end of the
  // piece already): a new right end closes the left part, a new left end opens the right.
  const int old_piece = nodes_[left_node].piece;
  const int new_piece = static_cast<int>(pieces_.size());
  pieces_.push_back(Piece{pieces_[old_piece].body, kNone, kNone});
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

void Tracker::resolve_group(std::vector<int>& group, double t) {
  // Interactions that keep recreating themselves at one instant (a fan whose steps would
  // converge: a material not convex in the sense the Riemann solver assumes) stop the run.
  if (t != last_interaction_t_) {
    last_interaction_t_ = t;
    interactions_at_this_t_ = 0;
  } else if (++interactions_at_this_t_ > 100 * (static_cast<long>(nodes_.size()) + 100)) {
    throw NumericalError("the interactions at t = " + number(t) +
                         " do not advance in time: the waves of a material keep recreating each other there"
                         " (a material not convex in the sense the Riemann solver assumes?)");
  }
  steer_merges();
  if (++result_.stats.interactions > scene_.solver.max_interactions) {
    throw NumericalError("more than solver.max_interactions = " + std::to_string(scene_.solver.max_interactions) +
                         " interactions by t = " + number(t) + " (of t_end = " + number(scene_.t_end) +
                         "); the bodies keep fragmenting or colliding: shorten time.end, coarsen solver.tolerance"
                         " or raise solver.max_interactions");
  }
  const int first = group.front(), last = group.back();
  const Node& nf = nodes_[first];
  const Node& nl = nodes_[last];
  const bool left_boundary = nf.kind == NodeKind::left_end;
  const bool right_boundary = nl.kind == NodeKind::right_end;
  if (left_boundary && right_boundary) throw NumericalError("a piece of zero length at t = " + number(t));

  // Structural nodes that survive the interaction.
  int interface = kNone, contact_left = kNone, contact_right = kNone;
  for (int id : group) {
    const Node& n = nodes_[id];
    if (n.kind == NodeKind::interface) interface = id;
    if (n.kind == NodeKind::right_end && id != last) contact_left = id;
    if (n.kind == NodeKind::left_end && id != first) contact_right = id;
  }
  // Where the meeting happens in the lab and in each piece's labels.
  double x = 0.0;
  {
    int anchor = interface != kNone ? interface : contact_left != kNone ? contact_left : kNone;
    if (anchor == kNone && left_boundary) anchor = first;
    if (anchor == kNone && right_boundary) anchor = last;
    if (anchor != kNone) {
      x = nodes_[anchor].x_at(t);
    } else {
      double sum = 0.0;
      for (int id : group) sum += nodes_[id].x_at(t);
      x = sum / static_cast<double>(group.size());
    }
  }
  auto label_in = [&](int piece) {
    for (int id : group)
      if (nodes_[id].piece == piece && nodes_[id].kind != NodeKind::front) return nodes_[id].X_at(t);
    double sum = 0.0;
    int count = 0;
    for (int id : group)
      if (nodes_[id].piece == piece) sum += nodes_[id].X_at(t), ++count;
    return sum / count;
  };

  // The outer states and the problem they pose.
  const int before = left_boundary ? kNone : nf.prev;   // node whose right region is the left state
  const int after = right_boundary ? kNone : last;      // node whose right region is the right state
  const Region left_region = before != kNone ? nodes_[before].right : Region{};
  const Region right_region = after != kNone ? nodes_[after].right : Region{};
  const int left_piece = nf.piece, right_piece = nl.piece;

  // Walls attached at either end lose their current contact pressure now.
  if (left_boundary && nf.attach == Attach::boundary) flush_wall(nf.partner, t);
  if (right_boundary && nl.attach == Attach::boundary) flush_wall(nl.partner, t);

  // Remove the fronts of the group; keep ends and interfaces. Their energy books
  // are closed first, while each front's neighbours are still the states it separated.
  // A rarefaction step that leaves as the only step of its family keeps its age (its
  // fan error goes on growing); otherwise the error it carries is booked now.
  int steps_in[2] = {0, 0};
  double steps_born[2] = {0.0, 0.0}, steps_error[2] = {0.0, 0.0};
  for (int id : group) {
    Node& n = nodes_[id];
    close_defect(n, t);
    if (n.kind != NodeKind::front) continue;
    account_front_end(id, t);
    if (n.front_kind == FrontKind::rarefaction) {
      const int f = n.family > 0 ? 1 : 0;
      ++steps_in[f];
      steps_born[f] = n.born;
      steps_error[f] += fan_error(id, t);
    }
  }
  for (int id : group)
    if (nodes_[id].kind == NodeKind::front) {
      const int p = nodes_[id].prev, n = nodes_[id].next;
      link(p, n);
      kill_node(id, t);
    }

  RiemannSolution sol;
  const Material* mL = left_region.material;
  const Material* mR = right_region.material;
  if (left_boundary || right_boundary) {
    const int end = left_boundary ? first : last;
    const Node& e = nodes_[end];
    const Material& m = left_boundary ? *mR : *mL;
    const State& st = left_boundary ? right_region.state : left_region.state;
    const Side side = left_boundary ? Side::right : Side::left;
    if (e.attach == Attach::boundary) {
      const Wall& w = walls_[e.partner];
      const double min_p = w.bonded ? m.cavitation_pressure() : std::max(0.0, m.cavitation_pressure());
      sol = solve_wall(m, st, side, w.rapidity, min_p);
    } else {
      sol = solve_free_end(m, st, side);
    }
    require_solved(sol, m, t, x);
    if (sol.parted && e.attach == Attach::boundary) {
      Wall& w = walls_[e.partner];
      w.attached = kNone;
      ++w.version;
      set_attach(end, Attach::free, kNone, t);
      event(t, "separation", x, {piece_body_name(e.piece)});
    }
  } else {
    double min_p;
    if (contact_left != kNone) {
      min_p = std::max({0.0, mL->cavitation_pressure(), mR->cavitation_pressure()});
    } else {
      min_p = std::max(mL->cavitation_pressure(), mR->cavitation_pressure());
    }
    sol = solve_riemann(*mL, left_region.state, *mR, right_region.state, min_p);
    require_solved(sol, sol.status == Status::out_of_range && mR->psi_max() < mL->psi_max() ? *mR : *mL, t, x);
    const int holder = interface != kNone ? interface : contact_left;
    if (holder != kNone && !sol.parted) hold_back_weak_wave(sol, left_region, right_region, holder, min_p, t);
  }

  // Emit the waves.
  const double XL = label_in(left_piece), XR = label_in(right_piece);
  emitted_left_.clear();
  emitted_right_.clear();
  WaveStates& wl = wave_left_;
  WaveStates& wr = wave_right_;
  wl.states.clear();
  wr.states.clear();
  if (!left_boundary) {
    wave(*mL, left_region.state, sol.left, -1, wl);
    emit_fronts(*mL, wl, -1, left_piece, t, XL, x, emitted_left_);
  }
  if (!right_boundary) {
    wave(*mR, right_region.state, sol.right, +1, wr);
    emit_fronts(*mR, wr, +1, right_piece, t, XR, x, emitted_right_);
    // Emitted from the outer state inwards; in space the C+ fan's head (next to the
    // right state) is its rightmost front.
    std::reverse(emitted_right_.begin(), emitted_right_.end());
  }

  for (int f = 0; f < 2; ++f) {
    const std::vector<int>& out = f == 0 ? emitted_left_ : emitted_right_;
    if (steps_in[f] == 1 && out.size() == 1 && nodes_[out.front()].front_kind == FrontKind::rarefaction) {
      nodes_[out.front()].born = steps_born[f];
    } else {
      error_fans_ += steps_error[f];
    }
  }

  // Link: [before] − fronts [centre] + fronts [right state holder].
  // The region right of the C− fronts is the left star state, left of the C+ fronts the right star state.
  auto states_of_left = [&](std::size_t k) -> Region { return Region{mL, wl.states[k + 1]}; };
  auto states_of_right = [&](std::size_t k, std::size_t m) -> Region {
    // C+ fronts listed left to right: front k separates states m-k and m-k-1.
    return Region{mR, wr.states[m - k - 1]};
  };

  bool parted_inside = !left_boundary && !right_boundary && sol.parted && contact_left == kNone;
  if (!left_boundary && !right_boundary && sol.parted && contact_left != kNone) {
    // Two bodies in contact separate.
    set_attach(contact_left, Attach::free, kNone, t);
    set_attach(contact_right, Attach::free, kNone, t);
    event(t, "separation", x, {piece_body_name(left_piece), piece_body_name(right_piece)});
  }

  // Left part: before → C− fronts → (interface | contact_left | new right end | first C+ front ...)
  int cursor = left_boundary ? first : before;
  for (std::size_t k = 0; k < emitted_left_.size(); ++k) {
    const int id = emitted_left_[k];
    nodes_[id].right = states_of_left(k);
    const int next = nodes_[cursor].next;
    link(cursor, id);
    link(id, next);
    cursor = id;
  }
  // Right part, inserted after the node that holds the right star region.
  int right_holder;  // node whose right region becomes the right star state
  if (left_boundary) {
    right_holder = first;
  } else if (right_boundary) {
    right_holder = kNone;
  } else if (interface != kNone) {
    right_holder = interface;
  } else if (contact_right != kNone) {
    right_holder = contact_right;
  } else {
    right_holder = cursor;  // plain crossing: the C+ fronts follow the C− fronts
  }
  if (parted_inside) {
    // The body parts here (cavitation, or an interface that cannot hold).
    const int left_of_crack = cursor;
    int right_of_crack = nodes_[cursor].next;
    if (interface != kNone) {
      right_of_crack = nodes_[interface].next;
      link(nodes_[interface].prev, right_of_crack);
      kill_node(interface, t);
      interface = kNone;
    }
    const Region right_first = emitted_right_.empty() ? right_region : Region{mR, wr.states.back()};
    split_piece(left_of_crack, right_of_crack, sol.left, sol.right, Region{}, right_first, t, XL, x);
    right_holder = pieces_.back().left_end;
    event(t, "cavitation", x, {piece_body_name(left_piece)});
  }
  if (right_holder != kNone) {
    const std::size_t m = emitted_right_.size();
    nodes_[right_holder].right = m > 0 ? Region{mR, wr.states.back()} : right_region;
    int c = right_holder;
    for (std::size_t k = 0; k < m; ++k) {
      const int id = emitted_right_[k];
      nodes_[id].right = states_of_right(k, m);
      nodes_[id].piece = nodes_[c].piece;
      const int next = nodes_[c].next;
      link(c, id);
      link(id, next);
      c = id;
    }
  }

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
  if (left_boundary) settle(first);
  if (right_boundary) settle(last);
  settle(contact_left);
  settle(contact_right);
  if (parted_inside) {
    settle(pieces_[left_piece].right_end);
    settle(pieces_[new_piece].left_end);
  }

  // New meetings: each node of the rebuilt stretch with its right neighbour.
  touched_.push_back(left_boundary ? first : before);
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
  if (ends_moved || sol.parted)
    for (int p : {left_piece, right_piece, new_piece})
      if (p != kNone) schedule_gaps_around(p);
}

double Tracker::fan_error(int id, double t) const {
  const Node& n = nodes_[id];
  const Region& left = nodes_[n.prev].right;
  const Region& right = n.right;
  const Material& m = *right.material;
  const double strength = std::abs(wave_strength(m, left.state, right.state, n.family));
  const double spread = std::abs(characteristic_speed(m, left.state, n.family) -
                                 characteristic_speed(m, right.state, n.family)) * (t - n.born);
  // No wider than the room between its neighbours: a staircase of steps misses the ramp it
  // stands for by σ/4 of the spacing.
  const double room = 0.5 * (nodes_[n.next].X_at(t) - nodes_[n.prev].X_at(t));
  return 0.5 * strength * std::min(spread, room);
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
  if (!(weaker < weak_) || weaker == 0.0) return;
  const bool drop_left = weak_left <= weak_right;
  const Region& kept = drop_left ? left : right;    // the side whose wave is held back keeps its state
  const Region& moved = drop_left ? right : left;
  if (kept.material->pressure(kept.state.stretch) < min_pressure) return;  // it would part: solve in full
  const RiemannSolution other = solve_wall(*moved.material, moved.state, drop_left ? Side::right : Side::left,
                                           kept.state.rapidity, -kInf);
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

// =====================================================================================
// outputs

void Tracker::record_segment(Node& n, double t) {
  if (!want_fronts_) return;
  if (t <= n.t0) return;  // nothing travelled
  result_.fronts.push_back(FrontSegment{n.t0, n.x0, t, n.x_at(t), n.front_kind, n.family});
}

void Tracker::account_front_end(int id, double t) {
  const Node& n = nodes_[id];
  if (n.front_kind != FrontKind::shock || n.prev == kNone) return;
  const Region& left = nodes_[n.prev].right;
  const Region& right = n.right;
  if (left.material == nullptr || right.material == nullptr) return;
  // Energy removed per unit time at a front moving at m = dX/dt: m[E] − [F], with
  // E the energy and F = p v its flux per unit label (SPEC §1).
  const double jump_E = energy_density(*right.material, right.state) - energy_density(*left.material, left.state);
  const double flux_right = right.material->pressure(right.state.stretch) * std::tanh(right.state.rapidity);
  const double flux_left = left.material->pressure(left.state.stretch) * std::tanh(left.state.rapidity);
  dissipated_ += (n.dXdt * jump_E - (flux_right - flux_left)) * (t - n.t0);
}

bool Tracker::locate(int body, double X, double t, Region& region, double& x) const {
  for (int piece : order_) {
    if (pieces_[piece].body != body) continue;
    const Node& le = nodes_[pieces_[piece].left_end];
    const Node& re = nodes_[pieces_[piece].right_end];
    if (X < le.X_at(t) || X > re.X_at(t)) continue;
    int n = pieces_[piece].left_end;
    // The last node at or left of X (the region to its right holds X).
    for (int next = nodes_[n].next; next != kNone && nodes_[next].kind != NodeKind::right_end &&
                                    nodes_[next].X_at(t) <= X;
         next = nodes_[n].next)
      n = next;
    const Node& node = nodes_[n];
    region = node.right;
    const double Xn = node.X_at(t);
    x = node.x_at(t) + (X - Xn) * region.state.stretch.value() / std::cosh(region.state.rapidity);
    return true;
  }
  return false;
}

double Tracker::quantity(Quantity q, const Region& r, double X, double x) const {
  return quantity_value(q, *r.material, r.state, X, x);
}

void Tracker::sample(const SampleTime& st) {
  const double t = st.t;
  if (st.kind == 0) {
    const ProbeDecl& probe = scene_.outputs.probes[st.index];
    const int body = probe_body(scene_, probe);
    Region r;
    double x = 0.0;
    if (!locate(body, probe.X, t, r, x)) return;
    for (Quantity q : probe.quantities)
      result_.probes.push_back(ProbeSample{t, st.index, q, quantity(q, r, probe.X, x)});
    return;
  }
  const SnapshotDecl& snap = scene_.outputs.snapshots[st.index];
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const BodyDecl& body = scene_.bodies[b];
    if (!snapshot_includes(snap, body)) continue;
    const double l0 = body.natural_length();
    for (int i = 0; i < snap.samples; ++i) {
      const double X = l0 * i / (snap.samples - 1);
      Region r;
      double x = 0.0;
      if (!locate(static_cast<int>(b), X, t, r, x)) continue;
      for (Quantity q : snap.quantities)
        result_.snapshots.push_back(SnapshotSample{t, static_cast<int>(b), X, q, quantity(q, r, X, x)});
    }
  }
}

void Tracker::totals(double t, double& energy, double& momentum) const {
  energy = momentum = 0.0;
  for (const Piece& piece : pieces_) {
    if (piece.left_end == kNone) continue;  // rejoined into another piece
    for (int n = piece.left_end; nodes_[n].kind != NodeKind::right_end; n = nodes_[n].next) {
      const Node& node = nodes_[n];
      const double dX = nodes_[node.next].X_at(t) - node.X_at(t);
      energy += dX * energy_density(*node.right.material, node.right.state);
      momentum += dX * momentum_density(*node.right.material, node.right.state);
    }
  }
}

RunResult Tracker::run() {
  const auto start = std::chrono::steady_clock::now();
  build_bodies();
  build_walls();
  collect_sample_times();
  result_.solver = "characteristics";
  result_.solver_numbers = {{"tolerance", scene_.solver.tolerance}};
  for (const BodyDecl& b : scene_.bodies) result_.body_names.push_back(b.name);
  // The threshold of weak waves: each interface or contact holding back a wave weaker than
  // `weak_` adds at most weak_ × (the speeds of the waves on its two sides, ~1) per unit time
  // to the L1 error; over the time light takes to cross the bodies' natural length, for every
  // such place, that is about half the tolerance's budget. The thresholds do not depend on
  // time.end, so that the work per unit time does not either: a run much longer than that
  // crossing time reports a bound that grows with it.
  total_length_ = 0.0;
  int places = 0;
  for (const BodyDecl& b : scene_.bodies) {
    total_length_ += b.natural_length();
    for (std::size_t k = 1; k < b.segments.size(); ++k)
      places += b.segments[k].material != b.segments[k - 1].material ? 1 : 0;
  }
  places += static_cast<int>(scene_.bodies.size()) - 1;
  // Merges and the reflections of merging fronts come more often the finer the tolerance
  // (as fan steps, their number grows as 1/tolerance): what each may cost falls as its square,
  // so that their sum falls with the tolerance.
  const double tolerance = scene_.solver.tolerance;
  merge_base_ = merge_ = kMergeFraction * tolerance * tolerance * total_length_;
  weak_merging_ = 0.5 * tolerance * tolerance;
  front_cap_ = static_cast<double>(scene_.bodies.size()) *
               std::max(kMinFrontsPerBody, kFrontsPerBody / scene_.solver.tolerance);
  weak_ = 0.5 * scene_.solver.tolerance / std::max(1, places);
  totals(0.0, result_.conservation.energy_initial, result_.conservation.momentum_initial);

  // Contacts present at t = 0: walls at a body's end, bodies touching each other.
  for (int side = 0; side < 2; ++side) {
    Wall& w = walls_[side];
    if (!w.present) continue;
    const int end = side == 0 ? pieces_[order_.front()].left_end : pieces_[order_.back()].right_end;
    if (touching(nodes_[end].x0, w.x0)) {
      w.attached = end;
      nodes_[end].attach = Attach::boundary;
      nodes_[end].partner = side;
    }
    schedule_piston(side);
  }
  for (std::size_t i = 0; i + 1 < order_.size(); ++i) {
    const int a = pieces_[order_[i]].right_end, b = pieces_[order_[i + 1]].left_end;
    if (touching(nodes_[a].x0, nodes_[b].x0)) {
      nodes_[a].attach = nodes_[b].attach = Attach::body;
      nodes_[a].partner = b;
      nodes_[b].partner = a;
    }
  }
  // Resolve every initial discontinuity and end at t = 0, left to right.
  for (int piece : order_)
    for (int n = pieces_[piece].left_end; n != kNone; n = nodes_[n].next)
      push(0.0, EventType::resolve, n, n, nodes_[n].version, 0);
  for (std::size_t i = 0; i < pieces_.size(); ++i) schedule_gaps_around(static_cast<int>(i));

  std::size_t next_sample = 0;
  for (;;) {
    while (!queue_.empty() && !valid(queue_.top())) queue_.pop();
    meetings_.prune();
    // The earliest of the next rare event and the next meeting (ties in the order scheduled).
    const bool rare_first =
        !queue_.empty() && (meetings_.empty() || queue_.top().t < meetings_.top().t ||
                            (queue_.top().t == meetings_.top().t && queue_.top().seq < meetings_.top().seq));
    const double t_event = rare_first ? queue_.top().t : meetings_.empty() ? kInf : meetings_.top().t;
    const double t_sample = next_sample < samples_.size() ? samples_[next_sample].t : kInf;
    if (t_sample < t_event) {
      sample(samples_[next_sample++]);
      continue;
    }
    if (t_event > scene_.t_end) break;
    if (rare_first) {
      const Event e = queue_.top();
      queue_.pop();
      handle(e);
    } else {
      const MeetingQueue::Entry m = meetings_.top();

      meetings_.erase(m.node);
      if (!interact_in_place(m.node, nodes_[m.node].next, m.t)) resolve(m.node, nodes_[m.node].next, m.t);
    }
  }
  const double t_end = scene_.t_end;
  for (; next_sample < samples_.size(); ++next_sample) sample(samples_[next_sample]);

  // Close the books at t_end.
  for (int side = 0; side < 2; ++side) flush_wall(side, t_end);
  for (std::size_t id = 0; id < nodes_.size(); ++id) {
    Node& n = nodes_[id];
    if (!n.alive) continue;
    if (n.kind == NodeKind::front) account_front_end(static_cast<int>(id), t_end);
    record_segment(n, t_end);
  }
  double error_fans_alive = 0.0;
  for (std::size_t id = 0; id < nodes_.size(); ++id) {
    Node& n = nodes_[id];
    if (!n.alive) continue;
    close_defect(n, t_end);
    if (n.kind == NodeKind::front && n.front_kind == FrontKind::rarefaction)
      error_fans_alive += fan_error(static_cast<int>(id), t_end);
  }
  // Each error was measured when it was made; the evolution carries it on, and where waves
  // cross a material interface or a changed region it grows (transmission and reflection
  // together exceed the incoming strength for a wave entering a softer material). The bound
  // takes that growth as a factor kStability, measured on the test suite's scenes (at most
  // 1.4 there), not proven.
  const double booked = error_defects_ + error_fans_ + error_fans_alive + error_merges_;
  const double error_bound = kStability * booked / total_length_;
  result_.solver_numbers.emplace_back("error_bound", error_bound);
  result_.solver_numbers.emplace_back("weak_wave_threshold", weak_);
  result_.solver_numbers.emplace_back("waves_held_back", static_cast<double>(suppressed_));
  result_.solver_numbers.emplace_back("fronts_merged", static_cast<double>(merged_));
  result_.solver_numbers.emplace_back("error_defects", error_defects_ / total_length_);
  result_.solver_numbers.emplace_back("error_fans", (error_fans_ + error_fans_alive) / total_length_);
  result_.solver_numbers.emplace_back("error_merges", error_merges_ / total_length_);
  result_.solver_numbers.emplace_back("fronts_alive_max", static_cast<double>(live_fronts_max_));
  Conservation& c = result_.conservation;
  totals(t_end, c.energy_final, c.momentum_final);
  c.wall_impulse = impulse_;
  c.wall_work = wall_work_;
  c.energy_dissipated = dissipated_;

  // Bodies at t_end, pieces named name.1, name.2, ... left to right.
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    std::vector<int> parts;
    for (int piece : order_)
      if (pieces_[piece].body == static_cast<int>(b)) parts.push_back(piece);
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const Piece& piece = pieces_[parts[k]];
      BodyResult r;
      r.name = scene_.bodies[b].name + (parts.size() > 1 ? "." + std::to_string(k + 1) : "");
      r.x_left = nodes_[piece.left_end].x_at(t_end);
      r.x_right = nodes_[piece.right_end].x_at(t_end);
      double mass = 0.0, mass_velocity = 0.0;
      for (int n = piece.left_end; nodes_[n].kind != NodeKind::right_end; n = nodes_[n].next) {
        const Node& node = nodes_[n];
        const double dX = nodes_[node.next].X_at(t_end) - node.X_at(t_end);
        const Material& m = *node.right.material;
        mass += m.rest_density() * dX;
        mass_velocity += m.rest_density() * dX * std::tanh(node.right.state.rapidity);
        r.energy += dX * energy_density(m, node.right.state);
        r.momentum += dX * momentum_density(m, node.right.state);
      }
      r.velocity_mean = mass > 0.0 ? mass_velocity / mass : 0.0;
      result_.bodies.push_back(r);
    }
  }
  if (fan_capped_) {
    result_.warnings.push_back("rarefaction fans were split into at most " + std::to_string(kMaxFanSteps) +
                               " steps: coarser than solver.tolerance = " + number(scene_.solver.tolerance));
  }
  result_.stats.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result_;
}

}  // namespace

RunResult solve_characteristics(const Scene& scene) { return Tracker(scene).run(); }

}  // namespace rigidity
