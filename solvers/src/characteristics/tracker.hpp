#pragma once
// The front tracker's state: the nodes of each piece of body (fronts, interfaces, ends),
// walls and pistons, the event queues, and the class whose member functions the files of
// this folder define, one responsibility each (docs/layout.md has the whole folder). It asks
// the ResolutionPolicy (policy.hpp) how finely to resolve, books every error in the
// ErrorLedger (ledger.hpp), and checks its invariants in validate.cpp:
//   tracker.cpp       set-up and the main loop (the cost model is written there)
//   interactions.cpp  fronts meeting: in place, or by a full Riemann problem; waves held back
//   coarsening.cpp    merging fronts and the error of fan steps
//   boundaries.cpp    walls, pistons, gaps, contacts, cracks and the rare events
//   outputs.cpp       samples, front segments, energy books
//   light.cpp         pieces whose sound travels at light speed, crossings not visited
//   lattice.cpp       pieces of any other linearly degenerate material, the same
//   reconstruction.cpp  smooth waves sampled between their steps, and the error of doing so
//   fans.cpp          centred fans: one front until reached, then split; their exact samples
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "front_math.hpp"
#include "ledger.hpp"
#include "meeting_queue.hpp"
#include "memo.hpp"
#include "policy.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/run_result.hpp"
#include "rigidity/scene.hpp"
#include "rigidity/solvers/budget.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/sampling.hpp"

namespace rigidity::characteristics {

/// Whether check_tracker_invariants is on (validate.cpp).
[[nodiscard]] bool validating();

constexpr int kNone = -1;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Steps a single rarefaction fan may be split into; beyond it the fan is coarser
/// than solver.tolerance and the run says so in its warnings.
constexpr int kMaxFanSteps = 100000;
/// Growth of an L1 error between the time it is made and t_end allowed for in the bound.
constexpr double kStability = 2.0;
/// The most an error carried by one wave may grow where that wave splits (see
/// Tracker::share_carried): a transmission into a softer or slower body grows it by up to
/// about twice the ratio of the label speeds.
constexpr double kMaxScattering = 8.0;
/// A crossing in a genuinely nonlinear body may leave its star this far (× tolerance², in
/// rapidity) from its waves' curves, booked on both fronts as they move on: the crossings of
/// a run at the front cap then book a small fraction of its budget, and most weak crossings
/// take the two-rarefaction star with one evaluation of the curves. At the default tolerance
/// it is below round-off: exact.
constexpr double kStarMismatch = 1e-3;
/// Relative precision of a shock's dissipation the energy books ask for, × tolerance: the
/// direct difference of energies where its round-off allows, Gauss–Legendre otherwise.
constexpr double kDissipationPrecision = 1.0;
/// A merge across fronts of the other family is tried in full only if its first-order cost
/// is at most this multiple of what a merge may cost (see Tracker::merge_across).
constexpr double kMergeEstimateMargin = 1.1;
/// How many fronts of the other family a merge of two fronts of one family may reach across.
constexpr int kMergeReach = 8;

/// light_store: the one node between the ends of a light piece (see LightPiece).
enum class NodeKind : std::uint8_t { front, interface, left_end, right_end, light_store };
/// What a front is as a wave: a shock, a jump that moves with the characteristics on both
/// sides (contact: every wave of a linearly degenerate material), or a step of a rarefaction
/// fan. Interfaces and ends carry interface and boundary, the lines they draw.
enum class FrontKind : std::uint8_t { shock, contact, rarefaction, interface, boundary };
/// The line a node draws in the x–t diagram (fronts.csv).
[[nodiscard]] constexpr SegmentKind segment_kind(FrontKind k) {
  switch (k) {
    case FrontKind::shock: return SegmentKind::shock;
    case FrontKind::contact: return SegmentKind::contact;
    case FrontKind::rarefaction: return SegmentKind::rarefaction;
    case FrontKind::interface: return SegmentKind::interface;
    case FrontKind::boundary: return SegmentKind::boundary;
  }
  return SegmentKind::contact;
}
/// What a body end touches.
enum class Attach : std::uint8_t { free, boundary, body };

/// A centred rarefaction fan while its steps keep the lines they were emitted on: between
/// them the solution is the exact self-similar fan (the state whose characteristic of the
/// fan's family runs from the centre to the sample), which samples take in place of the
/// steps' states. A step that interacts, or is re-anchored, leaves it.
///
/// A fan is born unsplit: one front between its outer and star states stands for the whole
/// wedge, samples and totals take the exact fan, and neighbours meet it at its edges. Only
/// when something reaches an edge is it split into its steps (Tracker::split_fan), each on
/// the line it would have had from the centre, so a fan nothing crosses costs nothing.
struct CentredFan {
  double t0 = 0.0, X0 = 0.0, x0 = 0.0;  ///< the centre
  int family = 0;
  const Material* material = nullptr;
  double j_other = 0.0;                 ///< the other family's invariant, the same across the fan
  double psi_a = 0.0, psi_b = 0.0;      ///< Ψ at its outer edge and at its star edge
  double speed_a = 0.0, speed_b = 0.0;  ///< the family's label speeds there
  int steps = 0;                        ///< steps still on their lines (0: a free slot)
  int unsplit = 0;                      ///< the steps the one front of an unsplit fan splits into; 0 once split
  bool capped = false;                  ///< that count was cut to kMaxFanSteps
};

/// A straight line in label space: X = X0 + speed (t − t0).
struct LabelRay {
  double t0 = 0.0, X0 = 0.0, speed = 0.0;
  [[nodiscard]] double X_at(double t) const { return X0 + speed * (t - t0); }
};

/// A state of a material between two nodes, with what crossings ask of it remembered:
/// Ψ of its stretch, the characteristic speeds of both families, and its pressure, energy
/// and momentum per unit label for the books of the fronts that bound it (NaN until asked
/// for; Tracker::psi_of, speeds_of and books_of fill them). A region is written whole, so a
/// new state never keeps the old one's values.
struct Region {
  const Material* material = nullptr;
  State state;
  mutable double psi = std::numeric_limits<double>::quiet_NaN();
  mutable FrontSpeeds speeds[2] = {{std::numeric_limits<double>::quiet_NaN(), 0.0},
                                   {std::numeric_limits<double>::quiet_NaN(), 0.0}};  ///< [0] C−, [1] C+
  mutable Hyperbolic hyperbolic{0.0, 0.0, 1.0, 1.0};  ///< of its rapidity (cosh 0 until asked for)
  /// Pressure, energy and momentum density per unit label, and the velocity.
  struct Books {
    double pressure = std::numeric_limits<double>::quiet_NaN(), energy = 0.0, momentum = 0.0, velocity = 0.0;
  };
  mutable Books books{};
};

/// A node of a piece's list: a front, a material interface or an end. Between
/// interactions it moves on a straight line in both X and x.
struct Node {
  NodeKind kind = NodeKind::front;
  FrontKind front_kind = FrontKind::contact;
  int family = 0;
  double t0 = 0.0, X0 = 0.0, x0 = 0.0;  ///< anchor: label and lab position at time t0
  double dXdt = 0.0, dxdt = 0.0;
  int prev = kNone, next = kNone;  ///< neighbours within the piece
  Region right;                    ///< the state between this node and `next`
  std::uint32_t version = 0;
  bool alive = true;
  Attach attach = Attach::free;  ///< end nodes only
  int partner = kNone;           ///< Attach::body: the touching end node; Attach::boundary: 0 left, 1 right
  int piece = kNone;
  double born = 0.0;      ///< fronts: when the wave it carries was created (fan error grows from then)
  double strength = 0.0;  ///< fronts: |jump of the family's own invariant| (J+ for C+, J− for C−)
  /// Fronts: the L1 error made on the wave it carries (merges, fan steps), travelling with
  /// it: a crossing hands it on with the wave, a split shares it among the outgoing waves
  /// (Tracker::share_carried), a merge adds the two fronts' and its own cost.
  double carried = 0.0;
  /// Fan steps still on the line they were emitted on: their centred fan (Tracker::fans_).
  int fan = kNone;
  /// Interfaces and contacts: a wave weaker than the threshold that this node did not emit
  /// (its strength times its speed, the L1 error it adds per unit time), since when, and
  /// the most it can add (strength times the natural length it could sweep).
  double defect_rate = 0.0, defect_since = 0.0, defect_cap = 0.0;
  /// True shocks: the energy removed per unit time, from the states set with the front (NaN:
  /// not known, account_front_end computes it from the regions; smooth steps need none).
  double dissipation = std::numeric_limits<double>::quiet_NaN();
  /// Fronts: one of the steps that stand for a smooth wave (a fan's, a piston ramp's, and
  /// what such steps become as they cross, reflect, transmit and merge), not a jump of the
  /// solution: samples reconstruct the wave between it and its neighbours of its family
  /// (Tracker::reconstruct).
  bool smooth = false;
  /// Jumps: how much the label speed changed when it last met a step of a smooth wave, and
  /// the time since the interaction before. A jump meeting a smooth wave step by step moves
  /// on a polygon that the path through the smooth wave cuts at each step's mean value; in
  /// between it is off by up to about kink × kink_dt / 2, which the bound takes at t_end.
  double kink = 0.0, kink_dt = 0.0;
  /// Smooth steps: the step's own value of its family's invariant less the one its sides give
  /// it (see Tracker::wedge). A step a ramping piston reflects leaves at the ramp's rapidity of
  /// that instant, where the region next to the piston holds the step of the staircase it is
  /// in: twice their difference; a step the piston's ramp takes itself carries the ramp's
  /// rapidity at that instant, not the mean of its two staircase steps': twice that
  /// difference; a wall reflects it with the invariant's sign, a free end as it is, crossings
  /// and transmissions carry it on.
  double offset = 0.0;

  [[nodiscard]] double X_at(double t) const { return X0 + dXdt * (t - t0); }
  [[nodiscard]] double x_at(double t) const { return x0 + dxdt * (t - t0); }
  [[nodiscard]] bool is_end() const { return kind == NodeKind::left_end || kind == NodeKind::right_end; }
};

/// A connected piece of a body (a body that cavitates becomes several pieces).
struct Piece {
  int body = 0;
  int left_end = kNone, right_end = kNone;
};

/// A wall or a piston (present), whose lab position is piecewise linear in time, or a traction:
/// a pressure applied to the outer end of the row of bodies, which the end never leaves (its
/// history in motion.times and pressures).
struct Wall {
  bool present = false;
  bool traction = false;
  double pressure = 0.0;  ///< a traction's, in force now
  std::vector<double> pressures;
  bool bonded = false;
  double t0 = 0.0, x0 = 0.0, rapidity = 0.0;
  std::size_t segment = 0;  ///< index into motion of the velocity in force
  PistonMotion motion;      ///< empty for a fixed wall
  int attached = kNone;     ///< the end node touching it
  std::uint32_t version = 0;
  double pressure_since = 0.0;  ///< for the impulse: time the current contact pressure started
  [[nodiscard]] double velocity() const { return std::tanh(rapidity); }
  [[nodiscard]] double x_at(double t) const { return x0 + velocity() * (t - t0); }
  [[nodiscard]] double next_change() const {
    return segment + 1 < motion.times.size() ? motion.times[segment + 1] : kInf;
  }
};

/// A front of a light or lattice piece, kept off the node list. In a light piece it moves on
/// the lab line x = intercept + family t from where it started until it reaches the end it
/// runs to. In a lattice piece it is a characteristic of the lattice (see LightPiece): `f`
/// and `p` are its hodograph coordinates, and `intercept` the label it started from at t0
/// (where it is at that instant exactly, not to the round-off of its coordinates).
struct LightFront {
  double intercept = 0.0;
  double j_ahead = 0.0, j_behind = 0.0;  ///< its own invariant on the side it runs into, and behind it
  double t0 = 0.0, x0 = 0.0;             ///< where it started (its segment in fronts.csv)
  double f = 0.0, p = 0.0;               ///< lattice pieces: (F, P) of a C+ front, (G, Q) of a C− one
  /// Fronts of the other family it meets in the piece: those there when it entered, plus those
  /// its far end emits after, counted there (LightPiece::minus_emitted); this is the first less the second.
  long meet_base = 0;
  /// Lattice pieces: the speed in the labels the other family has in the strip behind it
  /// (λ− where J+ is j_behind, for a C+ front; λ+ where J− is j_behind, for a C− one): what
  /// places the fronts of the other family that last met it, fixed for its life.
  double behind_speed = 0.0;
  double carried = 0.0;  ///< the L1 error its wave carries (Node::carried)
  bool smooth = false;   ///< a step of a smooth wave (Node::smooth): samples reconstruct its wave (light_reconstruct)
  [[nodiscard]] double x_at(double t, int family) const { return intercept + family * t; }
};

/// A characteristic of a lattice piece: a C+ one with (F, P), a C− one with (G, Q); the two
/// meet at t = F + G, X = P + Q.
struct Characteristic {
  double f = 0.0, p = 0.0;
};

/// A piece of a material whose sound travels at light speed and which carries any tension
/// (`rigid`): every front is a jump of one invariant moving at ±c in the lab whatever the
/// state, so fronts of the two families cross without changing each other's path or jump
/// (J+ and J− are carried, each by its own family). The piece keeps its fronts in two
/// queues in the order they run, and visits no crossing: a front costs its emission at one
/// end and its arrival at the other, O(fronts) per crossing time where a crossing-by-crossing
/// tracker pays O(fronts²). The node list holds the ends and one light_store node between
/// them: the left end's region is the state next to the left end, the store's the state next
/// to the right end. An arriving front is put back on the list for the end's Riemann problem
/// (resolve_group, as for any piece), and what that problem emits into the piece is taken off
/// it again (absorb_light). States between are built from the two invariants where asked for
/// (samples, totals), exactly as a crossing builds its star.
///
/// A lattice piece is the same for any other linearly degenerate material (`hooke`): the C+
/// speed in the labels, λ+, depends on J− alone and λ− on J+ alone, so between fronts of the
/// other family a front moves on a straight line in (X, t) whose slope only the other
/// family's fronts change. The fronts then form a lattice whose every vertex is known
/// without visiting it: the C+ front i and the C− front j meet at t = F_i + G_j and
/// X = P_i + Q_j (the hodograph of a linearly degenerate system, in which t and X are sums of
/// a function of J+ and one of J−). Two C+ fronts with J+ = a between them have
/// P₂ − P₁ = λ−(a) (F₂ − F₁) (a C− front crosses the strip between them at λ−(a)), two C−
/// fronts with J− = b between them Q₂ − Q₁ = λ+(b) (G₂ − G₁), and a front's place at time t
/// is on the line through its last vertex with its own speed there. Fronts keep the (F, P)
/// or (G, Q) they enter with; an arrival takes O(1), a sample the walk of the regions. The
/// piece goes back to the node list (dissolve_lattice) when its fronts outnumber its cap or
/// the invariants it holds could meet in a state the material cannot take (a bar crushed
/// by a crossing is found at that crossing on the node list). Only runs that do not write
/// fronts.csv make lattice pieces: their fronts' paths are polylines with a vertex at every
/// crossing, which that file would have to hold.
struct LightPiece {
  int store = kNone;
  std::deque<LightFront> plus;   ///< C+ fronts, the one nearest the right end first
  std::deque<LightFront> minus;  ///< C− fronts, the one nearest the left end first
  std::uint32_t version = 0;     ///< of its arrival events
  bool lattice = false;          ///< a lattice piece (else light)
  /// Lattice pieces: the C+ characteristic right of every C+ front (the last to reach the
  /// right end, or one through the right end when the piece was made), and the C−
  /// characteristic left of every C− front.
  Characteristic ref_plus, ref_minus;
  /// Lattice pieces: the extremes of J+ and J− the piece has held since it was made.
  double j_plus_min = kInf, j_plus_max = -kInf, j_minus_min = kInf, j_minus_max = -kInf;
  /// C− fronts its right end has emitted into the piece.
  long minus_emitted = 0;
};

/// Events other than nodes meeting (those live in MeetingQueue).
enum class EventType : std::uint8_t { resolve, gap, wall_gap, piston, arrival };

struct Event {
  double t;
  std::uint64_t seq;
  EventType type;
  int a, b;  ///< nodes (b: wall side 0/1 for wall_gap; a: wall side for piston; a: piece, b: family for arrival)
  std::uint32_t va, vb;
};

struct EventLater {
  bool operator()(const Event& x, const Event& y) const { return x.t != y.t ? x.t > y.t : x.seq > y.seq; }
};

/// Whether two fronts of one family that meet are steps of a compression wave converging
/// into a shock: both compressive, and neither a smooth step weaker than `superposed` (a weak
/// wave riding on the compression wave, as what a forming shock reflects does, which passes
/// its steps where their speeds differ by its own small jump: the two go on as one step of
/// the wave). Where one is expansive (a rarefaction step, or a weak wave that an interaction
/// left behind in a compression wave) they cancel, and no shock forms.
[[nodiscard]] inline bool converge(const Node& a, const Node& b, double superposed) {
  const auto riding = [superposed](const Node& n) { return n.smooth && n.strength < superposed; };
  return a.front_kind == FrontKind::shock && b.front_kind == FrontKind::shock && !riding(a) && !riding(b);
}

/// Which waves leaving an interaction go on as smooth waves, from the fronts that came in. A
/// wave of family f is smooth if a smooth step came in, no front of family f that came in was
/// a true jump (a shock or a jump goes on as itself), no two compressive fronts of family f
/// met (steps of a compression wave that meet make a shock, which is sharp, while what they
/// reflect is smooth; a compression step that overtakes a weak expansive one of its family
/// only cancels part of it, see converge) and, where the meeting is at an end, an interface
/// or a contact, no front that came in was a true jump (its reflection and transmission are
/// jumps too).
struct SmoothIn {
  bool any_smooth = false, any_sharp = false, structure = false;
  bool sharp[2] = {false, false}, met[2] = {false, false};  ///< [0] C−, [1] C+
  void add(int f, bool smooth, bool meets_its_family) {
    (smooth ? any_smooth : any_sharp) = true;
    sharp[f] = sharp[f] || !smooth;
    met[f] = met[f] || meets_its_family;
  }
  [[nodiscard]] bool out(int f) const { return any_smooth && !sharp[f] && !met[f] && !(structure && any_sharp); }
};

/// One wave of a Riemann solution, as the states it passes through.
struct WaveStates {
  std::vector<State> states;  ///< outer state first, star state last
  bool shock = false;
  int unsplit = 0;      ///< a new fan held as one front: the steps it splits into (states: outer, star)
  bool capped = false;  ///< that count was cut to kMaxFanSteps
  /// A wave that starts at `outer` and has no fronts yet.
  void start(const State& outer) {
    states.assign(1, outer);
    shock = false;
    unsplit = 0;
    capped = false;
  }
};

struct LightQueue;
struct Ramp;

class Tracker {
 public:
  Tracker(const Scene& scene, RunRecorder& recorder) : scene_(scene), recorder_(recorder), policy_(scene) {
    std::size_t segments = 0;
    for (const BodyDecl& body : scene.bodies) segments += body.segments.size();
    memo_ = std::make_unique<MaterialMemo>(std::bit_ceil(std::clamp<std::size_t>(64 * segments, 16, 1024)));
    want_fronts_ = scene.outputs.fronts;
  }

  RunResult run();
  /// Checks the invariants check_tracker_invariants names at time t (validate.cpp).
  void validate(double t) const;

 private:
  friend struct LightQueue;  // reads kMaxTrainWalk and kPlateauRatio
  // ---- set-up -------------------------------------------------------------------
  void build_bodies();
  void build_walls();
  // ---- the run's phases (tracker.cpp) ------------------------------------------------
  /// The bound's natural length and the thresholds of the tolerance that are no part of the
  /// resolution (star mismatch, dissipation precision; policy_ holds the others).
  void set_thresholds();
  /// Contacts present at t = 0 (walls, touching bodies), and the events that resolve every
  /// initial discontinuity and end.
  void schedule_start();
  /// Takes the earliest event until time.end, a budget or an inadmissible state stops the run.
  void event_loop();
  /// Closes every front's, wall's and light piece's books and fronts.csv segments at t_end.
  void close_books(double t_end);
  /// The error bound and the parts of it the warnings name.
  struct BoundParts {
    double error_bound = 0.0;       ///< per unit natural length, with kStability
    double carried = 0.0;           ///< what the fronts carry at t_end and what ended without a successor
    double error_fans_alive = 0.0;  ///< what the smooth steps and jumps alive at t_end book
  };
  [[nodiscard]] BoundParts error_bound_parts(double t_end) const;
  /// The solver numbers of the bound, and the warnings where it is above the tolerance.
  void report_error_bound(const BoundParts& bound);
  /// The error bound and its parts as solver numbers, with the counts and resolutions that made them.
  void report_bound_numbers(const BoundParts& bound);
  /// Where smooth waves' steps decided cracks: the time from which the result is qualitative, and a warning.
  void report_qualitative();
  /// Warns where a spray made the run resolve waves more coarsely than the tolerance; whether it did.
  bool warn_spray_coarsened();
  /// Warns that the bound is above the tolerance: which part holds it up, and what would lower it.
  void warn_bound_above_tolerance(const BoundParts& bound, bool spray_coarsened);
  /// Energy and momentum at t_end and what the books say made their changes.
  void report_conservation(double t_end);
  /// Each body's pieces at t_end: extent, energy, momentum, mean velocity.
  void report_bodies(double t_end);

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
    if (n.kind == NodeKind::front) {
      --live_fronts_;
      ledger_.lose(n.carried);  // a caller that hands the error on has taken it already
      n.carried = 0.0;
      leave_fan(n);
    }
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
  /// A rare event: into a binary heap whose superseded entries (an end that moved again
  /// before its gap closed) are dropped when they reach the top, or all at once when the
  /// heap has grown to twice what the last cleaning left (and beyond the pieces), so the
  /// heap stays as small as the scene and each cleaning is paid for by the pushes that made
  /// it necessary (a scene that starts with a thousand Riemann problems at t = 0 does not
  /// clean its heap at every push).
  void push(double t, EventType type, int a, int b, std::uint32_t va, std::uint32_t vb) {
    queue_.push_back(Event{t, seq_++, type, a, b, va, vb});
    std::push_heap(queue_.begin(), queue_.end(), EventLater{});
    if (queue_.size() > 2 * std::max(pieces_.size(), queue_after_cleaning_) + 64) {
      queue_.erase(std::remove_if(queue_.begin(), queue_.end(), [this](const Event& e) { return !valid(e); }),
                   queue_.end());
      std::make_heap(queue_.begin(), queue_.end(), EventLater{});
      queue_after_cleaning_ = queue_.size();
    }
  }
  void pop_event() {
    std::pop_heap(queue_.begin(), queue_.end(), EventLater{});
    queue_.pop_back();
  }
  bool valid(const Event& e) const;
  /// When node a meets its right neighbour (kInf: never, or after t_end).
  [[nodiscard]] double meeting_time(int a) const;
  void schedule_meet(int a);
  /// schedule_meet of a and of b; where a's meeting goes and b's comes (two fronts that
  /// have just crossed), a's entry is handed to b: one move in the queue instead of two.
  void schedule_meets(int a, int b);
  void schedule_gaps_around(int piece);
  void schedule_gap(int left_piece, int right_piece);
  void schedule_wall_gap(int side);
  void schedule_piston(int side);

  // ---- interactions -------------------------------------------------------------------
  void handle(const Event& e);
  void resolve(int seed_left, int seed_right, double t);
  bool rejoin(int right_end, int left_end, double t, double x);
  /// Two fronts a < b of one piece that meet at t crossed where they meet, without the full
  /// Riemann problem of resolve_group: the star from the invariants they bring (a linearly
  /// degenerate material), or where the wave curves meet (a genuinely nonlinear one, see
  /// same_material_star), the fronts re-set on the waves leaving, their books handed on. False
  /// where it must be resolved in full (cross_in_place says when).
  bool interact_in_place(int a, int b, double t);
  /// What a crossing in place emits: where, its star, and for each family ([0] C−, [1] C+) the
  /// kind of its wave, its strength and how far it lies off its wave curve; held_back: the C−
  /// wave, weaker than the threshold, is not emitted. What the wave curves evaluated on the way
  /// is kept for the fronts' speeds, jumps and dissipation.
  struct InPlace {
    double X = 0.0;
    State star;
    double psi_star = 0.0;
    FrontKind kinds[2] = {FrontKind::contact, FrontKind::contact};
    double off_curve[2] = {0.0, 0.0};
    double strength[2] = {0.0, 0.0};
    bool held_back = false;
    bool converged = false;  ///< the star found to round-off (star_speeds are its speeds)
    FrontSpeeds star_speeds[2];
    JumpLaws outer_laws[2], star_laws;  ///< p and e + p of left, right and the star, where evaluated
    /// What the incoming fronts hand on (hand_on_in_place): the age of a fan step that goes on
    /// as its family's only step, the errors each outgoing wave carries, which go on smooth.
    double born[2] = {0.0, 0.0};
    double carried[2] = {0.0, 0.0};
    SmoothIn smooth_in;
  };
  /// The crossing of fronts a < b at t, or false where it is no simple crossing in one
  /// material: a crowd at the point, a wave that vanishes or would part the body, a new fan
  /// to split, a star off its curves by more than the threshold, a wave faster than light.
  bool cross_in_place(int a, int b, double t, InPlace& c);
  /// The outer regions of a crossing in place, their Ψ, and the invariants they bring (J+ left, J− right).
  struct CrossingSides {
    const Region* left = nullptr;
    const Region* right = nullptr;
    double psi_left = 0.0, psi_right = 0.0, j_plus = 0.0, j_minus = 0.0;
  };
  /// Two steps of smooth waves crossing head-on (a C+ step a, a C− step b) are characteristics:
  /// each carries its own invariant's jump through the other, so the star is the
  /// two-rarefaction star, with no wave curve to meet (a compression's step misses its Hugoniot
  /// by a third-order term, which the smooth wave it stands for does not have), and each goes on
  /// as the kind of step it came in as (c.kinds). False where either is no smooth step.
  bool steps_pass(int a, int b, InPlace& c) const;
  /// The two-rarefaction star of fronts a < b at t (c.X, c.star, c.psi_star), or false where it is no simple crossing.
  bool two_rarefaction_star(int a, int b, double t, CrossingSides& s, InPlace& c);
  /// The first guess of a genuinely nonlinear crossing's star: each wave passed on with the other invariant's jump.
  State head_on_guess(int a, int b, const CrossingSides& s, const State& star);
  /// The star where the wave curves meet, the waves' strengths and distances off them, or false where none serves.
  bool star_on_curves(int a, int b, const CrossingSides& s, InPlace& c);
  /// Holds back a C− wave weaker than the threshold (the star: the left state); false where no C+ shock is found.
  bool hold_back_minus(const CrossingSides& s, bool shock[2], InPlace& c);
  /// The kinds of the waves leaving a crossing, or false where one vanishes, is off its curve or is a fan to split.
  bool outgoing_kinds(int a, int b, const CrossingSides& s, const bool shock[2], InPlace& c) const;
  /// What fronts a and b hand on to the waves leaving their crossing (c.born, c.carried,
  /// c.smooth_in): each front's carried error goes with the wave of its family, a fan step's
  /// age goes on where it leaves as the only step of its family, else its error is booked.
  void hand_on_in_place(int a, int b, double t, InPlace& c);
  /// A crossing in place whose C− wave is held back: a leaves with its strength booked, b joins the outer states.
  void hold_back_in_place(int a, int b, const InPlace& c, double x, double t);
  /// The region of c's star between the fronts a < b leave a crossing with: its Ψ, and its speeds where known.
  [[nodiscard]] Region crossing_star_region(int a, int b, const InPlace& c) const;
  /// Sets a and b on the C− and C+ waves leaving their crossing, the star between, with their books and kinks.
  void set_crossed_fronts(int a, int b, const InPlace& c, double x, double t);
  /// The two fronts leaving a crossing at label X merge where cheap (merge_nearby, or merge_neighbours).
  void merge_after_crossing(int a, int b, double X, double t);
  int merge_neighbours(int id, double t);
  /// The left one of the cheapest pair of id and a neighbour to merge costing at most best_cost (lowered to its cost).
  int cheapest_neighbour_merge(int id, double t, double& best_cost) const;
  /// The kind of the front that joins left to right, and how far off its Hugoniot; false where no one front may.
  bool merged_front_kind(const Material& m, const State& left, const State& right, int family, FrontKind& kind,
                         double& off) const;
  /// Puts neighbours p < q merged in place (p's left region L, q's right R): the stronger stays; returns it.
  int apply_merge_neighbours(int p, int q, const Region& L, const Region& R, double cost, FrontKind kind, double off,
                             double t);
  bool merge_across(int p, int q, double t);
  /// Puts merge_across's result in place: p and q leave, one front of their family enters at
  /// X_merged (in segments_[split]), the regions between take their new states, the nodes
  /// between are re-anchored with lab positions rebuilt from the left and their meetings
  /// rescheduled; the merge's cost is booked and carried with the two fronts' errors.
  void apply_merge_across(int p, int q, std::size_t split, double X_merged, double cost, double j_before,
                          double j_after_q, bool extend_left, double t);
  void merge_nearby(int id, double t);
  struct MergeSegment {
    double a, b;        ///< label extent at the time of the merge
    State old;          ///< its state now
    double j_old;       ///< its f-invariant now
    State left, right;  ///< its state if left of the merged front, if right of it
    int right_node;     ///< the node at its right edge that stays (kNone: p or q)
  };
  std::vector<MergeSegment> segments_;
  double merge_cost(int p, int q, double t, double* X_merged) const;
  /// segments_ of a merge across of p < q: the regions X̄ may lie in, with their states on either side of it.
  bool merge_segments(int p, int q, double j_before, double j_after_p, double j_after_q, bool& extend_left, double t);
  /// The label X̄ in segments_ that keeps the lab length, and its segment; false where none lies inside them.
  bool merged_label(double& X_merged, std::size_t& split) const;
  /// The L1 error of a merge across at X̄: each segment's f-invariant change times the length it changes over.
  [[nodiscard]] double merge_across_cost(std::size_t split, double X_merged, double j_before, double j_after_q) const;
  void set_front(int id, int family, FrontKind kind, const Material& m, const State& left, const State& right, double t,
                 double X, double x, double off_hugoniot, double born, double strength,
                 const FrontSpeeds* known = nullptr, const JumpLaws* laws = nullptr,
                 const Hyperbolic* at_left = nullptr, const Hyperbolic* at_right = nullptr);
  /// hyperbolic() of a region's rapidity, evaluated once per region.
  static const Hyperbolic& hyperbolic_of(const Region& r) {
    if (r.hyperbolic.cosh == 0.0) r.hyperbolic = hyperbolic(r.state.rapidity);
    return r.hyperbolic;
  }
  void resolve_group(std::vector<int>& group, double t);
  /// Where and between what a group of nodes meets.
  struct Meeting {
    int first = kNone, last = kNone;
    bool left_boundary = false, right_boundary = false;  ///< the group holds the row's outer end on that side
    int interface = kNone, contact_left = kNone, contact_right = kNone;  ///< structural nodes that survive
    double x = 0.0;                                                      ///< in the lab
    int before = kNone, after = kNone;  ///< the nodes whose right regions are the left and right states
    Region left_region, right_region;   ///< the Riemann problem's outer states
    int left_piece = kNone, right_piece = kNone;
  };
  [[nodiscard]] Meeting meet(const std::vector<int>& group, double t) const;
  /// The label in `piece` where the group meets: its end's or interface's there, else the
  /// mean of its fronts'.
  [[nodiscard]] double meeting_label(const std::vector<int>& group, int piece, double t) const;
  /// The Riemann problem of a meeting: at an end (a wall's, a piston's, a traction's or a free
  /// end's), or between its outer states (at a contact of bodies, an interface or inside a
  /// piece), with a weak wave held back at an interface or contact; a body that leaves a wall
  /// separates. No classical solution: the run stops at t, what the fronts taken in carried
  /// stays in the bound, and the right state is put back right of the meeting.
  /// What the fronts of a group bring to its Riemann problem, per family ([0] C−, [1] C+).
  struct Incoming {
    int steps_in[2] = {0, 0};  ///< rarefaction steps
    double steps_born[2] = {0.0, 0.0};
    double steps_error[2] = {0.0, 0.0};      ///< their errors (the reconstruction's, or the staircase's)
    double steps_staircase[2] = {0.0, 0.0};  ///< the staircase's errors of all smooth steps
    /// Steps of compression waves a jump of their family takes in, and that jump's speed and
    /// anchor time as it came in (see Node::kink).
    double steps_taken[2] = {0.0, 0.0}, jump_speed[2] = {kInf, kInf}, jump_since[2] = {0.0, 0.0};
    /// The errors the incoming fronts carry, and the rate at which they sweep L1 (strength ×
    /// speed in the labels), shared among the outgoing waves; what waves held back at its
    /// interfaces and ends booked while held (released).
    double carried_in = 0.0, sweep_in = 0.0, fastest_in = 0.0, released = 0.0;
    int fronts_in = 0;
    /// Which outgoing waves go on as smooth waves, and the offsets of their steps' values.
    SmoothIn smooth_in;
    double offset_in[2] = {0.0, 0.0};
    int count_in[2] = {0, 0};
    int families_in[2] = {kNone, kNone};  ///< the piece each family came in from
    int last_in[2] = {kNone, kNone};      ///< the last front of each family that came in
    /// A lone smooth step of each family arriving at an end that holds Ψ: the width of its
    /// wave's strip behind it (kInf: none), the change of the other family's speed across it
    /// (behind less ahead), and its speed (see shift_reflection).
    double reflect_width[2] = {kInf, kInf}, reflect_other_change[2] = {0.0, 0.0}, reflect_speed[2] = {0.0, 0.0};
    /// What a lone step's reflection at an end that holds Ψ shifts the reflected wave by
    /// (reflection_error), booked only where the reflected step cannot be placed.
    double reflect_error[2] = {0.0, 0.0};
  };
  /// A lone smooth step reflected at a free end or a traction as one smooth step: placed where
  /// its characteristic is (place_reflection), or, where it cannot be, booked with what the
  /// reflection shifts its wave by (Incoming::reflect_error). Each step crossing a wave of the other family meets its
  /// head half a strip late (the staircase holds the plateau's value up to the wave's first step, which stands at the
  /// mean of its sides, half a strip inside the wave) and makes it up at its tail; the arriving step turns back before
  /// it crosses the tail of the wave it is reflected into, and the reflected step will cross the tail of the arriving
  /// wave, not its head. Both shifts are known here: the reflected step starts ahead by what the arriving one lagged,
  /// less what it will lag itself.
  void shift_reflection(const Meeting& g, const Incoming& in, double t);
  /// shift_reflection's placing of a lone reflected step (false where the reflection is no
  /// lone smooth step in a genuinely nonlinear body at a free end or a traction, or the place
  /// is outward of the end or past kReflectionRoom of the room to the next node).
  bool place_reflection(const Meeting& g, const Incoming& in, double t);
  static constexpr double kReflectionRoom = 0.25;
  /// Closes the books of a group's fronts at t (energy, defects; a rarefaction step that leaves
  /// as the only step of its family keeps its age, otherwise its error is booked), sums what
  /// they bring into `in`, and takes them off the list: the ends and interfaces stay.
  void take_in(const std::vector<int>& group, double t, Incoming& in);
  RiemannSolution solve_meeting(const std::vector<int>& group, const Meeting& g, const Incoming& in, double t);
  /// Where a crack inside a piece would leave a droplet next to a free end, the droplet stays
  /// with the rest of the piece (absorb_droplet) and the solution takes the rest's state on
  /// that side: −1 (the droplet left of the crack), +1 (right of it) or 0.
  int keep_droplet(const Meeting& g, RiemannSolution& sol, double XL, double t);
  /// The waves of a meeting's solution as fronts (emitted_left_, emitted_right_ left to right;
  /// wave_left_, wave_right_ their states), smooth as the fronts that came in say; what those
  /// fronts brought handed on to them (ages, kinks, offsets, errors).
  void emit_waves(const Meeting& g, const RiemannSolution& sol, int droplet, double XL, double XR, Incoming& in,
                  double t);
  /// After a meeting is linked in: its structural nodes move with the material next to them
  /// (an end whose speed changed may close or open a gap), the rebuilt stretch's meetings are
  /// scheduled, the fronts emitted merge where cheap, and light pieces take theirs back.
  /// Links the emitted fronts in: the C− fronts after the left state's node, the C+ fronts
  /// after the node that holds the right star state (returned; kNone at a right end or where a
  /// droplet holds it); bodies in contact that part separate, a crack inside a piece splits it
  /// (parted_inside; an interface there goes, interface = kNone) and is qualitative if a smooth
  /// wave's step came in (smooth_in).
  int link_waves(const Meeting& g, const RiemannSolution& sol, int droplet, double XL, bool smooth_in, int& interface,
                 bool& parted_inside, double t);
  /// Links the C− fronts emitted (emitted_left_) in after the left state's node; returns the left part's last node.
  int link_left_waves(const Meeting& g, int droplet);
  /// The node whose right region becomes the right star state (kNone: none), `cursor` the last node of the left part.
  [[nodiscard]] int right_state_holder(const Meeting& g, int interface, int droplet, int cursor) const;
  /// Splits the piece at a crack right of `cursor` (an interface there goes); returns the new piece's left end.
  int crack_at_meeting(const Meeting& g, const RiemannSolution& sol, double XL, bool smooth_in, int cursor,
                       int& interface, double t);
  /// Links the C+ fronts emitted (emitted_right_) in after the node that holds the right star state.
  void link_right_waves(const Meeting& g, int right_holder);
  void settle_and_schedule(const Meeting& g, int interface, bool parted_inside, int droplet, int right_holder,
                           bool parted, double t);
  /// The offsets (Node::offset) of the smooth steps resolve_group has just emitted, from those
  /// of the fronts that came in (per family: their sum and count), or from a ramping piston's
  /// ramp where it took the step.
  void set_offsets(int first, int last, bool left_boundary, bool right_boundary, const double offset_in[2],
                   const int count_in[2], double t);
  /// The L1 error at time t of the region a ramping piston has left behind its last step: its
  /// characteristics carry the ramp's rapidity, the staircase holds the step's until the next.
  [[nodiscard]] double ramp_ahead_error(double t) const;
  /// The states of the wave of `family` from `outer` to `star`: a new rarefaction fan (`fresh`:
  /// no step of a smooth wave came in) in as many steps as ResolutionPolicy::fan_steps says; a
  /// step going on, one.
  void wave(const Material& m, const State& outer, const State& star, int family, bool fresh, WaveStates& w);
  /// The same for one piece of a wave whose kind is known (a shock, else a fan).
  void wave_piece(const Material& m, const State& outer, const State& star, int family, bool fresh, bool shock,
                  WaveStates& w);
  /// Emits the wave of `family` from `outer` to `star` as fronts (appended to `out`, from the outer
  /// state inwards), its states in w (outer first); a wave across an inflection of its law piece
  /// by piece as composite_wave builds it, each fan its own centred fan.
  void emit_wave(const Material& m, const State& outer, const State& star, int family, bool fresh, int piece, double t,
                 double X, double x, WaveStates& w, std::vector<int>& out);
  /// The states of a fan from `outer` to `star` in `steps` equal steps of Ψ (w.states).
  static void fan_states(const Material& m, const State& outer, const State& star, int family, int steps,
                         WaveStates& w);
  /// Emits the fronts of w, appended to `out`.
  void emit_fronts(const Material& m, const WaveStates& w, int family, int piece, double t, double X, double x,
                   std::vector<int>& out);
  void reanchor(int id, double t);
  void split_piece(int left_node, int right_node, const State& left_state, const State& right_state,
                   const Region& left_region, const Region& right_region, double t, double X, double x);
  int droplet_side(int piece, double X, double t) const;
  void absorb_droplet(int piece, int side, int before, double X, double x, const Region& straddling, const State& kept,
                      double t);
  double droplet_lab_length(int end, double X, const State& state, double t) const;
  bool room_for_end(int piece, int side, double x, double t) const;
  void set_attach(int end, Attach attach, int partner, double t);
  void flush_wall(int side, double t);
  // ---- light pieces (light.cpp) ----------------------------------------------------------
  [[nodiscard]] bool is_light(int piece) const {
    return piece >= 0 && static_cast<std::size_t>(piece) < light_.size() && light_[piece].store != kNone;
  }
  void make_light(double t);
  void schedule_arrivals(int piece);
  void arrive(int piece, int family, double t);
  void absorb_light(int piece, double t);
  /// The front just put at the back of a light or lattice piece's queue takes what node f
  /// carries. A lattice piece holds a smooth wave as the staircase of its steps: a step that
  /// follows another of its wave into it books the staircase's σ/4 of the strip between them.
  /// A light piece reconstructs it as the node list did: what its line misses the wave by is
  /// booked where the run ends (light_alive_error).
  void enter_light(std::deque<LightFront>& queue, const Node& f, double t, bool lattice);
  /// What the lines of a light piece's smooth waves miss them by at time t: for each smooth
  /// front, the change of its train's slope across it times the strips' width squared over 12
  /// (a train's first or last step: its slope, the plateau beyond being flat), a lone step the
  /// staircase's σ/4 of the room to its nearest neighbour. A light piece's waves keep their
  /// lines as they cross and reflect (its material is linearly degenerate): this is a state
  /// error, booked where the run ends, as the node list's smooth steps book theirs.
  double light_alive_error(int piece) const;
  bool merge_light(int piece, int family, double t);
  /// A merge of a light piece's two newest fronts of one family, as merge_light works it out.
  struct LightMerge {
    /// A lab extent (from, to: away from the new front's end), the other family's invariant there and this one's now.
    struct Part {
      double from, to, j_other, j_old;
    };
    int family = 0;
    /// The family's invariant between the two fronts, ahead of the older one and behind the newer one.
    double j_between = 0.0, j_near_old = 0.0, j_near_new = 0.0;
    double x_old = 0.0, x_new = 0.0;     ///< the two fronts' lab positions
    double x_limit = 0.0, x_stop = 0.0;  ///< how far the merged front may go, and how far the parts reach
    std::vector<Part> parts;
    /// Labels per lab length of each part: now, with j_near_new, with j_near_old.
    std::vector<double> density_old, density_new, density_near_old;
    double place = kInf, swept_in_split = 0.0;  ///< the merged front's lab position, and how far into its part
    std::size_t split = 0;                      ///< the part it lies in
  };
  /// The parts of a light merge: the lab extents the merged front may sweep, split at the other family's fronts.
  void light_merge_parts(int piece, double t, LightMerge& g) const;
  /// The place of a light merge that keeps the piece's natural length, or false where there is none.
  bool light_merge_place(int piece, LightMerge& g) const;
  /// The L1 error of a light merge: |δJ| of its family times the natural length it changes over.
  [[nodiscard]] double light_merge_cost(const LightMerge& g) const;
  /// Puts a light merge in place: the older front takes the newer one's books and moves to the place; the newer leaves.
  void apply_merge_light(int piece, const LightMerge& g, double cost, double t);
  [[nodiscard]] State light_state(const Material& m, double j_plus, double j_minus) const;
  // ---- lattice pieces (lattice.cpp) ------------------------------------------------------
  bool make_lattice(int piece, double t);
  [[nodiscard]] double lattice_arrival(int piece, int family) const;
  void lattice_enter(int piece, int family, int id, double t);
  void note_invariants(LightPiece& lp, const Material& m, const State& s) const;
  [[nodiscard]] bool lattice_safe(const LightPiece& lp, const Material& m) const;
  void dissolve_lattice(int piece, double t);
  /// A front of a lattice piece at time t, in the order walk_lattice meets them.
  struct LatticeFront {
    double X;
    int family;
    const LightFront* front;
  };
  /// The fronts of a lattice piece at time t, left to right, with the state left of each:
  /// visit(front, state left of it); returns the state next to the right end.
  template <class Visit>
  void walk_lattice_fronts(int piece, double t, Visit&& visit) const;
  long lattice_crossings_done(int piece, double t) const;
  /// Ψ of a region's state, remembered in the region.
  double psi_of(const Region& r) {
    if (std::isnan(r.psi)) r.psi = memo_->psi(*r.material, r.state.stretch);
    return r.psi;
  }
  /// A region's pressure, energy and momentum density, remembered in the region.
  const Region::Books& books_of(const Region& r) const {
    Region::Books& b = r.books;
    if (std::isnan(b.pressure)) {
      const Hyperbolic& h = hyperbolic_of(r);
      b.pressure = r.material->pressure(r.state.stretch);
      const double s = r.state.stretch.value(), enthalpy = r.material->enthalpy_density(r.state.stretch);
      b.energy = energy_density(s, h.cosh, b.pressure, enthalpy);
      b.momentum = momentum_density(s, h.sinh, enthalpy);
      b.velocity = h.sinh / h.cosh;
    }
    return b;
  }
  /// The characteristic speeds of family `family` in a region's state, remembered in the region.
  const FrontSpeeds& speeds_of(const Region& r, int family) const {
    FrontSpeeds& sp = r.speeds[family > 0 ? 1 : 0];
    if (std::isnan(sp.lagrangian)) {
      // Both families from the exponentials they share: a region is asked for both more
      // often than not (each of its two bounding fronts asks for its own family).
      if (std::isnan(r.speeds[family > 0 ? 0 : 1].lagrangian)) {
        characteristic_speeds_both(*r.material, r.state, r.speeds);
      } else {
        sp = characteristic_speeds(*r.material, r.state, family);
      }
    }
    return sp;
  }
  [[nodiscard]] double invariant(const Material& m, const State& st, int family) const {
    return st.rapidity + family * memo_->psi(m, st.stretch);
  }
  /// The regions of a light or lattice piece at time t, left to right: visit(x_a, x_b, X_a,
  /// X_b, state, last) (a light piece's labels from the left end's, by the label density of
  /// each region; a lattice piece's lab positions so).
  template <class Visit>
  void walk_light(int piece, double t, Visit&& visit) const;
  void record_light_segments(int piece, double t);
  // ---- outputs --------------------------------------------------------------------------
  void record_segment(Node& n, double t);
  void account_front_end(int id, double t);
  void sample(const SampleTime& st);
  /// Records probe `index` at time t: the quantities at its label, or at the label its lab position holds.
  void sample_probe(int index, double t);
  /// Records body b's samples of a snapshot at time t, in one walk along its pieces and their nodes.
  void snapshot_body(const SnapshotDecl& snap, int b, double t);
  /// Records the samples of a snapshot from the i-th on that light piece `piece` of body b holds; returns how many.
  int snapshot_light_piece(const SnapshotDecl& snap, int b, int piece, int i, double t);
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
  /// Ψ, stretches and characteristic speeds of the states linearly degenerate crossings revisit.
  std::unique_ptr<MaterialMemo> memo_;
  bool fan_capped_ = false;
  /// Cracks that a smooth wave's steps decided (a step came in where the body parted): where
  /// and when the body parts then depends on the steps, so what follows is qualitative.
  double qualitative_since_ = kInf;
  long qualitative_cracks_ = 0;
  int qualitative_body_ = kNone;  ///< the body of the first such crack
  /// Cracks after a droplet was kept (absorb_droplet): the droplet would have broken off and
  /// come back, so where and when bodies part from then on depends on the droplet limit, which
  /// follows the tolerance; the first droplet's time and body.
  long cracks_after_droplets_ = 0;
  double first_droplet_ = kInf;
  int first_droplet_body_ = kNone;
  std::vector<CentredFan> fans_;
  std::vector<int> free_fans_;
  /// A step leaves its centred fan (it interacts, or moves off its line).
  void leave_fan(Node& n) {
    if (n.fan == kNone) return;
    if (--fans_[n.fan].steps == 0) free_fans_.push_back(n.fan);
    n.fan = kNone;
  }
  // ---- centred fans (fans.cpp) -----------------------------------------------------------
  /// The one front of a fan not split yet (CentredFan::unsplit).
  [[nodiscard]] bool unsplit(int id) const {
    const Node& n = nodes_[id];
    return n.kind == NodeKind::front && n.fan != kNone && fans_[n.fan].unsplit > 0;
  }
  /// An unsplit fan's edge: its fastest characteristic (`fast`, the edge its right region
  /// touches) or its slowest, a ray from the centre.
  [[nodiscard]] LabelRay fan_edge(int id, bool fast) const {
    const CentredFan& f = fans_[nodes_[id].fan];
    return LabelRay{f.t0, f.X0, fast ? std::max(f.speed_a, f.speed_b) : std::min(f.speed_a, f.speed_b)};
  }
  /// The line a neighbour meets: an unsplit fan's edge on that side, else the node's own.
  [[nodiscard]] LabelRay facing(int id, bool fast) const {
    const Node& n = nodes_[id];
    return unsplit(id) ? fan_edge(id, fast) : LabelRay{n.t0, n.X0, n.dXdt};
  }
  /// The labels [Xa, Xb] at time t of the constant region right of node n (to an unsplit
  /// fan's edge where n or its right neighbour is one).
  void region_span(int n, double t, double& Xa, double& Xb) const {
    Xa = facing(n, true).X_at(t);
    Xb = facing(nodes_[n].next, false).X_at(t);
  }
  /// Replaces the one front of an unsplit fan by its steps, each on its line from the
  /// centre, as if the fan had been emitted split; reschedules their meetings.
  void split_fan(int id, double t);
  /// Splits the unsplit fans a meeting of node a with its right neighbour at t is with
  /// (the meeting is then the fan's edge reached); whether there were any.
  bool split_reached_fan(int a, double t);
  /// Calls add(dX, material, state) over the wedge of unsplit fan `id` at time t: Gauss–
  /// Legendre nodes of the exact fan, dX their weights (the integrals of totals and sums).
  template <class Add>
  void fan_wedge(int id, double t, Add&& add) const;
  /// Calls add(dX, material, state) over piece `piece` at time t, region by region (light and
  /// lattice pieces through walk_light, unsplit fans through fan_wedge): what totals and the
  /// bodies' sums integrate.
  template <class Add>
  void integrate_piece(int piece, double t, Add&& add) const;
  /// Records an unsplit fan's two edges in fronts.csv, up to t.
  void record_fan_edges(int id, double t);
  /// Where label X at time t lies in the region right of node n and in the centred fan of n
  /// or of its right neighbour: the exact state there and its lab position.
  bool fan_sample(int n, double X, double t, State& state, double& x) const;
  /// The state at label X at time t in the region right of node n (the exact fan's where X
  /// lies in an uncrossed one, see fan_sample), and the lab position of X.
  void region_at(int n, double X, double t, Region& region, double& x) const;
  // ---- smooth waves between their steps (reconstruction.cpp) ----------------------------
  /// A front that is a step of a smooth wave of `family`.
  [[nodiscard]] bool is_step(int id, int family) const {
    const Node& n = nodes_[id];
    return n.kind == NodeKind::front && n.smooth && n.family == family && !unsplit(id);
  }
  /// A smooth step of `family` weaker than kSuperposed fan steps: a weak wave superposed on
  /// the wave it runs in (what a shock reflects as it forms or takes in steps, and what that
  /// becomes at an end), not a sample of it. The line of the wave is drawn past it, and its
  /// jump stays a jump on top (a staircase of strength ~ fan step³ in a compression wave).
  [[nodiscard]] bool superposed(int id, int family) const {
    const Node& n = nodes_[id];
    return n.kind == NodeKind::front && n.smooth && n.family == family &&
           std::abs(own_jump(id)) < kSuperposed * policy_.fan_step();
  }
  static constexpr double kSuperposed = 0.1;
  /// Walking from node `from` towards `step` (&Node::prev or &Node::next) past smooth steps of
  /// the other family and superposed ones of `family`: the first node that is a front of
  /// `family`, or anything that bounds the strip a smooth wave of `family` may fill (an end,
  /// an interface, a true jump).
  [[nodiscard]] int strip_edge(int from, int family, int Node::*step) const;
  /// The line of `family`'s invariant over the strip between its smooth steps a < b at time t:
  /// through the values at the steps' own characteristics, each the mean of its two sides'
  /// values (a step moves at the mean of their characteristic speeds: the characteristic of
  /// that mean, to second order). Its slope in X and its value at a, relative to the
  /// strip's; NaN where the strip is no part of one smooth wave: spreading the change of the
  /// invariant across it more than kPlateauRatio times as thinly as the thinner strip next to
  /// it (see line_through), with no strip of the wave next to it, between
  /// steps of opposite jumps (an extremum where two waves meet), or holding another material.
  struct Wedge {
    double slope = std::numeric_limits<double>::quiet_NaN(), at_a = 0.0;
    double from = 0.0, to = 0.0;  ///< train_wedge: the labels of its two steps
  };
  /// The line of a train of steps of `family` of one sign, the weak ones riding on the wave
  /// (superposed) or the others as `weak` says, over the strip between the two of them around
  /// label X (X in the region right of node n), relative to the staircase of their jumps: NaN
  /// where X has no such step on either side within kMaxTrainWalk nodes, or the strip is no
  /// part of a train (see line_through).
  [[nodiscard]] Wedge train_wedge(int n, double X, int family, int sign, bool weak, double t) const;
  [[nodiscard]] int train_step(int from, int family, int sign, bool weak, int Node::*step) const;
  static constexpr int kMaxTrainWalk = 64;
  [[nodiscard]] Wedge wedge(int a, int b, int family, double t) const;
  static constexpr double kPlateauRatio = 3.0;
  /// What the plateau of a strip `across` wide between two waves of one family and opposite
  /// signs (an extremum) misses the extremum by: each wave's line, of slope s1 or s2 (in
  /// magnitude) from the mean of its last step (of jump j1 or j2), reaches the plateau half
  /// a step on, and carried on they meet at the extremum of the profile they draw, a tent on
  /// the plateau (or a notch in it) of base g, the gap between where they reach it, and height
  /// g s1 s2/(s1 + s2): the L1 error of its triangle (a piston's ramp up and down: the tent
  /// from its linear rows). Without the slope of either (a lone step beyond): the most the
  /// peak can stand off the plateau, half the larger jump over the strip's width, halved.
  static double extremum_miss(double across, double j1, double s1, double j2, double s2);
  /// The state at label X of the region right of node n with the smooth waves through it
  /// reconstructed, and the lab position's change dx (see reconstruction.cpp). Returns false
  /// where nothing is reconstructed.
  bool reconstruct(int n, double X, double t, State& state, double& dx) const;
  /// reconstruct for one family: the lines (ramps, at most kMaxRamps) of its smooth waves over
  /// the strip between l and r, its nearest fronts around label X; how many.
  int wave_ramps(int n, double X, int family, double t, int l, int r, Ramp* ramps) const;
  /// Where the strip [l, r] of `family` (holding X, with its lines `ramps`) touches an end from
  /// which that family leaves: what makes the leaving invariant at the end what the end makes
  /// of the arriving wave's line there (a free end or a traction keeps Ψ, a wall or a steady
  /// piston φ), drawn in linearly from the strip's far edge; 0 elsewhere (and at ends touching
  /// another body or a ramping piston).
  double end_condition(int family, double X, double t, int l, int r, const Ramp* ramps, int count) const;
  static constexpr int kMaxRamps = 5;
  /// The strip of `family` that holds the region right of node n at time t: its bounds l and
  /// r (the nearest fronts of the family either side, or what bounds the strip: an end, an
  /// interface, a true jump; see strip_edge), its regions and how the lab length per label,
  /// ρ = s/γ, changes with the family's invariant in each, ∂ρ/∂J± = −ρ (tanh φ ± 1/c_s)/2. A
  /// snapshot's samples rise in X, so consecutive ones share a strip: it is kept for them
  /// within one walk_epoch_ (one snapshot or probe, while the nodes stand still), with the
  /// lines last drawn over it.
  struct StripWalk {
    long epoch = -1;
    int l = kNone, r = kNone;
    bool one_material = true;       ///< no interface inside
    std::vector<int> nodes;         ///< the strip's regions, left to right
    std::vector<double> rates, lo;  ///< ∂ρ/∂J of each, and its left edge
    std::size_t cursor = 0;         ///< where the last sample was
    int count = -1;                 ///< the lines (ramps) `before` and to_r are for
    std::array<double, 6 * kMaxRamps> lines{};
    std::vector<double> before;  ///< the lab length the lines add over the regions left of each
    double to_r = 0.0;           ///< and over the whole strip
  };
  /// The strip of `family` around n, from strip_walks_ or walked anew.
  StripWalk& strip_of(int n, int family, double t) const;
  /// The lab length the lines `ramps` add over the strip `w` up to X (in the region right of n,
  /// to_X) and over all of it (to_r): ∫ ∂ρ/∂J · Σ ramps dX.
  static void strip_shift(StripWalk& w, const Ramp* ramps, int count, double X, double& to_X, double& to_r);
  mutable StripWalk strip_walks_[2];  ///< [0] C−, [1] C+
  long walk_epoch_ = 0;
  /// The same in a light piece (whose fronts run on lab lines), at lab position x where the
  /// staircase's state is `state`: between two smooth steps of one wave, each family's
  /// invariant on the line through the steps' values (the edges of waves stay as they are).
  /// Lattice pieces are sampled as their staircases. Returns false where nothing changes.
  bool light_reconstruct(int piece, double x, double t, State& state) const;
  /// light_reconstruct for one family: adds to its invariant `j` at lab position x the line of
  /// the smooth wave there; false if none reaches x.
  bool light_line(int piece, int family, double x, double t, double& j) const;
  /// light_line where no line reaches x: what the wave beside the plateau that holds x carries
  /// into it (see the definition).
  double light_carried(int piece, const LightQueue& lq, long a, long b, long far, bool wave_right) const;
  // ---- the error budget (see docs/solvers.md, "What the tolerance means") --------------------
  double star_mismatch_ = 0.0;          ///< kStarMismatch × tolerance²
  double dissipation_precision_ = 0.0;  ///< kDissipationPrecision × tolerance
  double total_length_ = 1.0;           ///< natural length of all bodies: the error bound is per unit of it
  /// Every error booked, by kind, and what the waves carry of it.
  ErrorLedger ledger_;
  long suppressed_ = 0;  ///< weak waves held back
  /// The thresholds that set how finely waves and droplets are resolved, and their controllers.
  ResolutionPolicy policy_;
  long light_fronts_ = 0;
  double light_bodies_ = 0.0;                             ///< bodies whose one piece is light
  double droplet_energy_ = 0.0, droplet_momentum_ = 0.0;  ///< what keeping them changed
  std::vector<int> body_pieces_;                          ///< per body: its pieces
  long droplets_ = 0;
  long merged_ = 0;
  long live_fronts_max_ = 0;

  /// Books the error of the node's defect up to t (a wave held back, a front off its curve)
  /// and returns it.
  double close_defect(Node& n, double t) {
    if (n.defect_rate <= 0.0) return 0.0;
    if (n.kind != NodeKind::front) book_held_back(n, t);
    const double booked = std::min(n.defect_rate * (t - n.defect_since), n.defect_cap);
    ledger_.book_defect(booked);
    n.defect_rate = 0.0;
    return booked;
  }
  /// The momentum and energy a weak wave held back at interface or contact n made up to t:
  /// its two sides keep one velocity v but pressures p_L ≠ p_R, which makes p_R − p_L of
  /// momentum and v (p_R − p_L) of energy per unit time.
  void book_held_back(const Node& n, double t) {
    if (n.prev == kNone) return;
    const Region& left = nodes_[n.prev].right;
    const Region* right = &n.right;
    if (n.kind == NodeKind::right_end) {
      if (n.attach != Attach::body || n.partner == kNone) return;
      right = &nodes_[n.partner].right;
    }
    if (left.material == nullptr || right->material == nullptr) return;
    const double dp = right->material->pressure(right->state.stretch) - left.material->pressure(left.state.stretch);
    const double dt = t - n.defect_since;
    waves_momentum_ += dp * dt;
    waves_energy_ += dp * 0.5 * (std::tanh(left.state.rapidity) + std::tanh(right->state.rapidity)) * dt;
  }
  /// The L1 error of a smooth step at time t. As a staircase: the exact fan spreads a fan
  /// step's jump σ over |Δλ| (t − born) in X, a compression wave's step stands for the ramp
  /// to its neighbours (no more than the room between them either way), which a jump in its
  /// middle misses by σ/4 of that width on average. With smooth_on (its wave goes on as a
  /// smooth wave: it crosses, merges, reflects, meets a shock or is sampled) the least of
  /// that and what the reconstruction misses it by (reconstruction_error); without (a crack
  /// takes it in) the staircase's.
  double fan_error(int id, double t, bool smooth_on = true) const;
  /// The jump of front `id`'s own invariant (J+ for a C+ front, J− for a C− one), right side
  /// less left side.
  double own_jump(int id) const;
  /// The L1 error at time t of smooth step `id` where the samples reconstruct its wave (see
  /// reconstruct): what the lines through the steps' values miss the wave's curvature by,
  /// |ΔJ'| w²/12 with ΔJ' the change of slope across the step (for the first or last step of a
  /// wave, between the wave's first two strips) and w the strips' width, and, for a fan step
  /// of a genuinely nonlinear body, how far its path has drifted since it was born from the
  /// characteristic of its mean value (its jump times the difference of its speed from the
  /// mean of its sides' characteristic speeds, times its age). kInf where its wave is not
  /// reconstructed next to it (a lone step, a step between plateaus).
  double reconstruction_error(int id, double t) const;
  /// How far a fan step's path has drifted since it was born from the characteristic of its
  /// mean value, times its jump: what it carries of the reconstruction's error wherever its
  /// wave goes on.
  double drift_error(int id, double t) const;
  /// The L1 error smooth step `id` makes as it reflects at time t at an end that holds Ψ (a
  /// free end, a traction), its wave going on as the reflected one (reconstructed there: see
  /// end_condition; Tracker::take_in): the staircase holds the
  /// plateau ahead of a wave until its first step, half a strip past the wave's edge, so each
  /// step of a wave crossing the head of another reaches it a little late, by the change of its
  /// speed across that head over the time it takes to cross half a strip; a step crossing the
  /// whole wave makes it up at the tail, but at an end the arriving steps turn back before they
  /// cross the reflected wave's tail (a free end shifts the reflected wave by about 0.7 δ² in
  /// the labels for steps δ). Booked as a quarter of the step's jump times the change of the
  /// other family's speed across it times the time its wave takes to cross the room inward of
  /// it: nothing in a linearly degenerate body, second order in the step in any other. Booked
  /// only where the reflected step is not placed where its characteristic is (shift_reflection).
  double reflection_error(int id, double t) const;
  /// Books fan step `id`'s error up to t in the ledger and returns it, for the wave that
  /// carries it on (every error in the bound travels with a wave or stays where booked).
  double book_fan_error(int id, double t, bool smooth_on = true) {
    const double booked = fan_error(id, t, smooth_on);
    return ledger_.book_fan(booked);
  }
  double piece_length(int piece) const {
    return nodes_[pieces_[piece].right_end].X0 - nodes_[pieces_[piece].left_end].X0;  // ends move with the material
  }
  void share_carried(double carried_in, double sweep_in, int fronts_in, double fastest_in, double released);
  void hold_back_weak_wave(RiemannSolution& sol, const Region& left, const Region& right, int holder,
                           double min_pressure, double t);

  std::vector<Node> nodes_;
  std::vector<int> free_nodes_;
  std::vector<Piece> pieces_;
  std::vector<int> order_;         ///< pieces in lab order, left to right
  std::vector<LightPiece> light_;  ///< by piece (store kNone: an ordinary piece)
  bool light_made_ = false;
  Wall walls_[2];
  std::vector<Event> queue_;              ///< rare events (a heap, EventLater): gaps, pistons, t = 0
  std::size_t queue_after_cleaning_ = 0;  ///< entries left by the last cleaning of queue_
  MeetingQueue meetings_;                 ///< fronts meeting fronts, ends, interfaces
  std::uint64_t seq_ = 0;
  long live_fronts_ = 0;

  SampleSchedule samples_{scene_};
  RunResult result_;
  double impulse_ = 0.0, wall_work_ = 0.0, dissipated_ = 0.0;
  /// Energy and momentum the waves followed approximately made: a step of a smooth wave moves
  /// at the speed that keeps lab positions continuous, which conserves them only to third order
  /// in its strength; a weak wave held back leaves its interface or contact with a pressure
  /// jump that pushes on both sides alike.
  double waves_energy_ = 0.0, waves_momentum_ = 0.0;
  double last_interaction_t_ = -1.0;
  long interactions_at_this_t_ = 0;

  /// Fronts emitted by the interaction being resolved continue smooth waves: every front
  /// that came in was a smooth step and none of them met another of its own family, or a
  /// piston ramp's step changes the piston's speed.
  bool emit_smooth_ = false;

  // scratch buffers reused by every interaction
  std::vector<int> group_, emitted_left_, emitted_right_, emitted_split_, touched_;
  WaveStates wave_left_, wave_right_, wave_split_, wave_piece_;
};

/// Gauss–Legendre nodes and weights on [0, 1] for the integrals over a fan's wedge.
struct QuadraturePoint {
  double at = 0.0, weight = 0.0;
};
[[nodiscard]] const std::vector<QuadraturePoint>& fan_quadrature();

template <class Add>
void Tracker::integrate_piece(int piece, double t, Add&& add) const {
  const int left_end = pieces_[piece].left_end;
  if (is_light(piece)) {
    const Material& m = *nodes_[left_end].right.material;
    walk_light(piece, t,
               [&](double, double, double X_a, double X_b, const State& state, bool) { add(X_b - X_a, m, state); });
    return;
  }
  for (int n = left_end; nodes_[n].kind != NodeKind::right_end; n = nodes_[n].next) {
    if (unsplit(n)) fan_wedge(n, t, add);
    double Xa = 0.0, Xb = 0.0;
    region_span(n, t, Xa, Xb);
    add(Xb - Xa, *nodes_[n].right.material, nodes_[n].right.state);
  }
}

template <class Add>
void Tracker::fan_wedge(int id, double t, Add&& add) const {
  const Node& n = nodes_[id];
  const CentredFan& f = fans_[n.fan];
  const double lo = std::min(f.speed_a, f.speed_b), hi = std::max(f.speed_a, f.speed_b), dt = t - f.t0;
  if (!(dt > 0.0)) return;
  for (const QuadraturePoint& q : fan_quadrature()) {
    const double speed = lo + (hi - lo) * q.at;
    const Solved<State> s = centred_fan_state(*f.material, f.family, f.j_other, f.psi_a, f.psi_b, speed);
    if (!s.ok()) throw NumericalError("a rarefaction fan state could not be found (label speed " + number(speed) + ")");
    add((hi - lo) * q.weight * dt, *f.material, s.value);
  }
}

template <class Visit>
void Tracker::walk_lattice_fronts(int piece, double t, Visit&& visit) const {
  const LightPiece& lp = light_[piece];
  const Node& left = nodes_[pieces_[piece].left_end];
  const Material& m = *left.right.material;
  const double X_right = nodes_[pieces_[piece].right_end].X_at(t);
  double X = left.X_at(t);
  State state = left.right.state;  // next to the left end: exactly as stored
  double j_plus = invariant(m, state, +1), j_minus = invariant(m, state, -1);
  Characteristic met = lp.ref_minus;  // the last C− characteristic left of the walk
  // λ+ in the strip right of `met`, and λ− right of every C+ front (next to the right end).
  double plus_speed = speeds_of(left.right, +1).lagrangian;
  const double minus_speed_at_right = speeds_of(nodes_[lp.store].right, -1).lagrangian;
  // C+ fronts from the leftmost (the back of their queue), C− from the leftmost (the front).
  auto p = lp.plus.rbegin();
  auto q = lp.minus.begin();
  while (p != lp.plus.rend() || q != lp.minus.end()) {
    // A C− front is left of a C+ front once their vertex is past: F + G <= t.
    const bool minus = q != lp.minus.end() && (p == lp.plus.rend() || p->f + q->f <= t);
    double X_next;
    const LightFront& f = minus ? *q : *p;
    if (t == f.t0) {
      X_next = f.intercept;  // where it entered, this instant
    } else if (minus) {
      // On the line through its vertex with the nearest C+ characteristic right of it, at λ−
      // of the strip behind that one.
      const bool plus_left = p != lp.plus.rend();
      const Characteristic c = plus_left ? Characteristic{p->f, p->p} : lp.ref_plus;
      X_next = c.p + q->p + (plus_left ? p->behind_speed : minus_speed_at_right) * (t - c.f - q->f);
    } else {
      X_next = p->p + met.p + plus_speed * (t - p->f - met.f);
    }
    X_next = std::clamp(X_next, X, X_right);
    visit(LatticeFront{X_next, minus ? -1 : +1, minus ? &*q : &*p}, state);
    X = X_next;
    if (minus) {
      j_minus = q->j_behind;
      met = Characteristic{q->f, q->p};
      plus_speed = q->behind_speed;
      ++q;
    } else {
      j_plus = p->j_ahead;
      ++p;
    }
    state = light_state(m, j_plus, j_minus);
  }
}

template <class Visit>
void Tracker::walk_light(int piece, double t, Visit&& visit) const {
  const LightPiece& lp = light_[piece];
  const Node& left = nodes_[pieces_[piece].left_end];
  const Node& right = nodes_[pieces_[piece].right_end];
  const Material& m = *left.right.material;
  const double x_left = left.x_at(t), x_right = right.x_at(t);
  if (lp.lattice) {
    double x = x_left, X = left.X_at(t);
    walk_lattice_fronts(piece, t, [&](const LatticeFront& f, const State& state) {
      const double x_next = x + (f.X - X) * label_density(state);
      visit(x, x_next, X, f.X, state, false);
      x = x_next;
      X = f.X;
    });
    visit(x, x_right, X, right.X_at(t), nodes_[lp.store].right.state, true);  // next to the right end: as stored
    return;
  }
  double x = x_left, X = left.X_at(t);
  State state = left.right.state;  // next to the left end: exactly as stored
  double j_plus = invariant(m, state, +1), j_minus = invariant(m, state, -1);
  // C+ fronts from the leftmost (the back of their queue), C− from the leftmost (the front).
  auto p = lp.plus.rbegin();
  auto q = lp.minus.begin();
  for (;;) {
    const double xp = p != lp.plus.rend() ? std::clamp(p->x_at(t, +1), x_left, x_right) : kInf;
    const double xq = q != lp.minus.end() ? std::clamp(q->x_at(t, -1), x_left, x_right) : kInf;
    const bool last = p == lp.plus.rend() && q == lp.minus.end();
    const double x_next = last ? x_right : std::min(xp, xq);
    if (last) state = nodes_[lp.store].right.state;  // next to the right end: exactly as stored
    const double X_next = X + (x_next - x) / label_density(state);
    visit(x, x_next, X, X_next, state, last);
    if (last) return;
    x = x_next;
    X = X_next;
    if (xp <= xq) {
      j_plus = p->j_ahead;
      ++p;
    } else {
      j_minus = q->j_behind;
      ++q;
    }
    state = light_state(m, j_plus, j_minus);
  }
}

}  // namespace rigidity::characteristics
