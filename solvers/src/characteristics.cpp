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
#include "rigidity/run_recorder.hpp"
#include "rigidity/solvers/budget.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/sampling.hpp"

namespace rigidity {

namespace {

constexpr int kNone = -1;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Steps a single rarefaction fan may be split into; beyond it the fan is coarser
/// than solver.tolerance and the run says so in its warnings.
constexpr int kMaxFanSteps = 2000;

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

/// The next meeting of each node with its right neighbour: a binary min-heap with
/// one entry per node at most, which knows where each node's entry sits so that a
/// meeting can be moved or cancelled when a neighbour changes. Front tracking of a
/// many-segment bar spends most of its time here, so no stale entries are kept.
class MeetingQueue {
 public:
  struct Entry {
    double t;
    std::uint64_t seq;
    int node;
  };

  [[nodiscard]] bool empty() const { return heap_.empty(); }
  [[nodiscard]] const Entry& top() const { return heap_.front(); }

  void set(int node, double t, std::uint64_t seq) {
    if (node >= static_cast<int>(position_.size())) position_.resize(static_cast<std::size_t>(node) + 1, kNone);
    int i = position_[node];
    if (i == kNone) {
      i = static_cast<int>(heap_.size());
      heap_.push_back(Entry{t, seq, node});
      position_[node] = i;
      up(i);
      return;
    }
    const bool earlier = before(Entry{t, seq, node}, heap_[i]);
    heap_[i] = Entry{t, seq, node};
    earlier ? up(i) : down(i);
  }

  void erase(int node) {
    if (node >= static_cast<int>(position_.size()) || position_[node] == kNone) return;
    const int i = position_[node];
    const int last = static_cast<int>(heap_.size()) - 1;
    position_[node] = kNone;
    if (i != last) {
      heap_[i] = heap_[last];
      position_[heap_[i].node] = i;
      heap_.pop_back();
      up(i);
      down(i);
    } else {
      heap_.pop_back();
    }
  }

 private:
  static bool before(const Entry& a, const Entry& b) { return a.t != b.t ? a.t < b.t : a.seq < b.seq; }
  void place(int i, const Entry& e) {
    heap_[i] = e;
    position_[e.node] = i;
  }
  void up(int i) {
    const Entry e = heap_[i];
    while (i > 0) {
      const int parent = (i - 1) / 2;
      if (!before(e, heap_[parent])) break;
      place(i, heap_[parent]);
      i = parent;
    }
    place(i, e);
  }
  void down(int i) {
    const Entry e = heap_[i];
    const int n = static_cast<int>(heap_.size());
    for (;;) {
      int child = 2 * i + 1;
      if (child >= n) break;
      if (child + 1 < n && before(heap_[child + 1], heap_[child])) ++child;
      if (!before(heap_[child], e)) break;
      place(i, heap_[child]);
      i = child;
    }
    place(i, e);
  }

  std::vector<Entry> heap_;
  std::vector<int> position_;
};

/// One wave of a Riemann solution, as the states it passes through.
struct WaveStates {
  std::vector<State> states;  ///< outer state first, star state last
  bool shock = false;
};


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
  Tracker(const Scene& scene, RunRecorder& recorder) : scene_(scene), recorder_(recorder) {
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
  bool cross_in_place(int a, int b, double t);
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
    recorder_.event(RunEvent{t, kind, x, std::move(bodies)});
  }
  std::string piece_body_name(int piece) const { return scene_.bodies[pieces_[piece].body].name; }

  const Scene& scene_;
  RunRecorder& recorder_;  ///< fronts, samples and events go there as they are produced
  bool want_fronts_ = false;
  double fan_step_ = 1e-12;
  bool fan_capped_ = false;

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

/// The common interaction of a linearly degenerate material, done in place: a C+
/// front a meets a C− front b inside one material and nothing else is there. They
/// leave as a C− front (in a's node) and a C+ front (in b's node) around the closed-form
/// star state; the outer regions are untouched. Returns false (doing nothing) when
/// the general resolution is needed.
bool Tracker::cross_in_place(int a, int b, double t) {
  if (result_.stats.interactions >= scene_.solver.max_interactions) return false;  // resolve_group reports it
  Node& na = nodes_[a];
  Node& nb = nodes_[b];
  if (na.kind != NodeKind::front || nb.kind != NodeKind::front || na.family != +1 || nb.family != -1) return false;
  const Node& before = nodes_[na.prev];
  const Node& after = nodes_[nb.next];
  const Material* m = before.right.material;
  if (m != nb.right.material || !m->linearly_degenerate()) return false;
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
  const State star{0.5 * (j_plus + j_minus), star_stretch.value};
  if (same_state(star, left) || same_state(star, right)) return false;  // a wave vanishes

  ++result_.stats.interactions;
  result_.stats.fronts += 2;
  const double x = 0.5 * (na.x_at(t) + nb.x_at(t));
  record_segment(na, t);
  record_segment(nb, t);
  const FrontSpeeds minus = characteristic_speeds(*m, star, -1);
  const FrontSpeeds plus = characteristic_speeds(*m, star, +1);
  na.family = -1;
  na.dXdt = minus.lagrangian;
  na.dxdt = minus.lab;
  na.right.state = star;
  nb.family = +1;
  nb.dXdt = plus.lagrangian;
  nb.dxdt = plus.lab;
  for (Node* n : {&na, &nb}) {
    n->t0 = t;
    n->X0 = X;
    n->x0 = x;
    ++n->version;
  }
  schedule_meet(na.prev);
  schedule_meet(a);
  schedule_meet(b);
  return true;
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
  // The step count in double first: span / tolerance overflows an int for tolerances of 1e-11.
  const double wanted = std::ceil(span / fan_step_);
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
    if (w.shock) {
      n.front_kind = FrontKind::shock;
      const FrontSpeeds sp = shock_speeds(m, outer, inner, family);
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
        // A fan step moves at the mean of the characteristic speeds on its two sides.
        n.front_kind = FrontKind::rarefaction;
        const FrontSpeeds a = characteristic_speeds(m, outer, family), b = characteristic_speeds(m, inner, family);
        n.dXdt = 0.5 * (a.lagrangian + b.lagrangian);
        n.dxdt = 0.5 * (a.lab + b.lab);
      }
    }
    out.push_back(id);
    ++live_fronts_;
    ++result_.stats.fronts;
  }
  if (live_fronts_ > scene_.solver.max_fronts) {
    recorder_.stop(budget_stop_reason(scene_, Budget::fronts, t));  // the run stops after this interaction
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
  if (++result_.stats.interactions > scene_.solver.max_interactions) {
    recorder_.stop(budget_stop_reason(scene_, Budget::interactions, t));  // the run stops after this interaction
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
  for (int id : group)
    if (nodes_[id].kind == NodeKind::front) account_front_end(id, t);
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

  // Link: [before] − fronts [centre] + fronts [right state holder].
  // The region right of the C− fronts is the left star state, left of the C+ fronts the right star state.
  auto states_of_left = [&](std::size_t k) -> Region { return Region{mL, wl.states[k + 1]}; };
  auto states_of_right = [&](std::size_t k, std::size_t m) -> Region {
    // C+ fronts listed left to right: front k separates states m-k and m-k-1.
    return Region{mR, wr.states[m - k - 1]};
  };

  const bool parted_inside = !left_boundary && !right_boundary && sol.parted && contact_left == kNone;
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
  if (ends_moved || sol.parted)
    for (int p : {left_piece, right_piece, new_piece})
      if (p != kNone) schedule_gaps_around(p);
}

// =====================================================================================
// outputs

void Tracker::record_segment(Node& n, double t) {
  if (!want_fronts_) return;
  if (t <= n.t0) return;  // nothing travelled
  recorder_.front(FrontSegment{n.t0, n.x0, t, n.x_at(t), n.front_kind, n.family});
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
      recorder_.probe(ProbeSample{t, st.index, q, quantity(q, r, probe.X, x)});
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
        recorder_.snapshot(SnapshotSample{t, static_cast<int>(b), X, q, quantity(q, r, X, x)});
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
    if (recorder_.poll(t_event, live_fronts_, result_.stats.interactions)) break;  // a budget, Ctrl-C; progress
    if (rare_first) {
      const Event e = queue_.top();
      queue_.pop();
      handle(e);
    } else {
      const MeetingQueue::Entry m = meetings_.top();
      meetings_.erase(m.node);
      if (!cross_in_place(m.node, nodes_[m.node].next, m.t)) resolve(m.node, nodes_[m.node].next, m.t);
    }
  }
  const double t_end = recorder_.stopped() ? recorder_.t_reached() : scene_.t_end;
  for (; next_sample < samples_.size() && !recorder_.stopped(); ++next_sample) sample(samples_[next_sample]);

  // Close the books at t_end.
  for (int side = 0; side < 2; ++side) flush_wall(side, t_end);
  for (std::size_t id = 0; id < nodes_.size(); ++id) {
    Node& n = nodes_[id];
    if (!n.alive) continue;
    if (n.kind == NodeKind::front) account_front_end(static_cast<int>(id), t_end);
    record_segment(n, t_end);
  }
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

RunResult solve_characteristics(const Scene& scene, RunRecorder& recorder) {
  RunResult result = Tracker(scene, recorder).run();
  recorder.complete(result, scene.t_end);
  return result;
}

RunResult solve_characteristics(const Scene& scene) {
  MemoryRecorder recorder;
  return solve_characteristics(scene, recorder);
}

}  // namespace rigidity
