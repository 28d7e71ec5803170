// The finite-volume baseline: a Lagrangian Godunov / MUSCL–Hancock scheme for the
// label and momentum laws of docs/physics.md (see finite_volume.hpp for the method).
#include "rigidity/solvers/finite_volume.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/number_text.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/sampling.hpp"

namespace rigidity {

namespace {

using finite_volume::Conserved;
using finite_volume::FaceFlux;
using finite_volume::Flux;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
/// Passes of the predictor allowed to land a step on a gap closure (order 2: the
/// face velocities depend a little on the step through the predictor).
constexpr int kGapClosurePasses = 4;
/// Void fraction of a clamped cell above which the material is said to cavitate.
constexpr double kVoidFraction = 1.0e-9;

std::string number(double v) { return twelve_digits(v); }

/// Lab positions equal up to the round-off of summing segment lengths (as in the
/// characteristics solver).
bool touching(double x1, double x2) {
  return std::abs(x1 - x2) <= 64.0 * kEps * std::max({1.0, std::abs(x1), std::abs(x2)});
}

/// The minimum pressure a contact can carry: a push-only contact (0), a material
/// that cavitates, or a bonded junction of solids (−inf).
double min_pressure(const Material& a, const Material& b, bool push_only) {
  const double parting = std::max(a.cavitation_pressure(), b.cavitation_pressure());
  return push_only ? std::max(0.0, parting) : parting;
}

/// A wall or piston; its lab position is integrated step by step.
struct Wall {
  bool present = false;
  bool bonded = false;
  double x = 0.0;           ///< lab position now
  double rapidity = 0.0;    ///< in force now
  std::size_t segment = 0;  ///< index into motion of the velocity in force
  PistonMotion motion;      ///< empty for a fixed wall
  [[nodiscard]] double velocity() const { return std::tanh(rapidity); }
  [[nodiscard]] double next_change() const {
    return segment + 1 < motion.times.size() ? motion.times[segment + 1] : kInf;
  }
};

/// A pressure applied to the outer end of the row of bodies (a traction boundary): p =
/// pressures[i] from times[i] on.
struct Traction {
  bool present = false;
  std::vector<double> times, pressures;
  std::size_t segment = 0;
  [[nodiscard]] double pressure() const { return pressures[segment]; }
  [[nodiscard]] double next_change() const { return segment + 1 < times.size() ? times[segment + 1] : kInf; }
};

/// Where two neighbours in lab order meet. Junction j is left of body j: junction 0
/// is the left boundary, junction B (B bodies) the right one.
///
/// Its sides exchange flux through the push-only (or bonded) Riemann problem while
/// they touch (gap within round-off); if that problem parts them, each side is a
/// free end for the step. Events follow the geometry, so that round-off in a
/// pressure near zero cannot make a contact flicker: "separation" when the gap has
/// opened (dated at the step whose Riemann problem parted it), "contact" when a gap
/// closes (steps are clipped to land on the closure).
struct Junction {
  bool touching = false;    ///< the sides touch at the start of the step being taken
  bool parted = false;      ///< ... and its Riemann problem parted them
  bool in_contact = false;  ///< contact as last reported
  double parted_since = std::numeric_limits<double>::quiet_NaN();  ///< start of the current parting
  double parted_x = 0.0;                                           ///< where it parted
};

struct Body {
  int first = 0, count = 0;            ///< its cells: first, ..., first + count − 1
  double length = 0.0;                 ///< natural length l0
  double x_left = 0.0, x_right = 0.0;  ///< lab positions of the ends, integrated from their face velocities
  bool cavitated = false;              ///< some cell was clamped at the parting stretch in the last step
};

/// Slopes of the Riemann invariants J± per unit label.
struct InvariantSlopes {
  double plus = 0.0, minus = 0.0;
};

/// The scheme on every body of a scene. One step from t:
///   1. Δt from the CFL condition on the Lagrangian characteristic speeds of the cells,
///      clipped to the next sample time, piston change or t_end;
///   2. order 2: limited slopes of J± and the half-step predictor at the faces;
///   3. a flux at every face: HLL or exact inside a body, the exact boundary problem
///      at walls, pistons, free ends and contacts; Δt shrinks to land on the
///      closure of a gap;
///   4. the conservative update of U, the ends and walls moved, the walls' impulse
///      and work booked;
///   5. contacts made or lost; (φ, s) recovered from U in every cell.
class Scheme {
 public:
  Scheme(const Scene& scene, RunRecorder& recorder) : scene_(scene), recorder_(recorder), order_(scene.solver.order) {}
  RunResult run();

 private:
  // ---- set-up -----------------------------------------------------------------------
  void build_cells();
  void build_walls();

  // ---- one step -----------------------------------------------------------------------
  [[nodiscard]] double stable_step();
  /// λ∓ of cell c's state, each time the state is set.
  void set_speeds(std::size_t c) {
    const finite_volume::LagrangianSpeeds speeds = finite_volume::lagrangian_speeds(*material_[c], state_[c]);
    speed_minus_[c] = speeds.minus;
    speed_plus_[c] = speeds.plus;
  }
  void reconstruct(double dt);
  void face_fluxes(double t);
  FaceFlux interior_flux(int left_cell, int right_cell, double t);
  void junction_flux(int j, double t);
  [[nodiscard]] double closing_time(int j) const;
  void advance(double dt);
  void recover(double t);
  /// Lab positions of the two sides of junction j (walls or body ends).
  void side_positions(int j, double& x_left, double& x_right) const;
  /// Of cell k (global index): the fraction of its lab width that holds no material.
  [[nodiscard]] double void_fraction(int k) const;
  /// Appends body b at t_end to the result: whole, or as its pieces if it holds void inside.
  void list_pieces(int b);
  /// The sides of junction j touch (a gap within round-off, or none).
  [[nodiscard]] bool sides_touch(int j) const;
  /// After a step from t_start to t_end: contacts made and lost, with their events.
  void update_junctions(double t_start, double t_end);

  // ---- cells and faces --------------------------------------------------------------------
  [[nodiscard]] int left_face(int c) const { return c + body_of_[c]; }
  [[nodiscard]] int right_face(int c) const { return c + body_of_[c] + 1; }
  [[nodiscard]] const State& left_face_state(int c) const { return order_ == 2 ? face_left_[c] : state_[c]; }
  [[nodiscard]] const State& right_face_state(int c) const { return order_ == 2 ? face_right_[c] : state_[c]; }
  [[nodiscard]] bool junction_can_touch(int j) const {
    const int last = static_cast<int>(bodies_.size());
    if (j == 0) return walls_[0].present;
    if (j == last) return walls_[1].present;
    return true;
  }
  /// The Riemann invariants (J+, J−) of a mirror cell beyond the end of body b on
  /// `side` (−1 left, +1 right), reflecting cell c; false where no mirror applies
  /// (a contact with another body).
  bool ghost_invariants(int b, int side, int c, double& j_plus, double& j_minus) const;
  /// Lab position of the left face of cell c.
  [[nodiscard]] double x_of_cell(int c) const;

  // ---- errors -------------------------------------------------------------------------------
  void check(const RiemannSolution& sol, const Material& m, double t, double x) const;
  [[nodiscard]] std::string where_is_cell(int c) const;

  // ---- outputs -----------------------------------------------------------------------------
  void sample(const SampleTime& st);
  /// The cell of `body` that holds label X, and the lab position of X.
  [[nodiscard]] int locate(int body, double X, double& x) const;
  [[nodiscard]] double quantity(Quantity q, int c, double X, double x) const;
  void totals(double& energy, double& momentum) const;
  /// Events wait in pending_events_ until no later step can date one before them
  /// (a separation is dated at the step that parted it): the recorder gets them in time order.
  void event(double t, const char* kind, double x, std::vector<std::string> bodies) {
    pending_events_.push_back(RunEvent{t, kind, x, std::move(bodies)});
  }
  /// Hands the recorder, in time order, the pending events dated at or before `t`.
  void release_events(double t);
  /// The earliest time a later step can date an event: now, or the start of a parting not reported yet.
  [[nodiscard]] double earliest_event_time(double t) const;
  [[nodiscard]] const std::string& body_name(int b) const { return scene_.bodies[b].name; }

  const Scene& scene_;
  RunRecorder& recorder_;  ///< samples and events go there as they are produced
  int order_ = 2;

  // cells, left to right in lab order, body after body
  std::vector<const Material*> material_;
  std::vector<finite_volume::RecoveryBounds> bounds_;  ///< of each cell's material, for the recovery of (φ, s)
  std::vector<int> body_of_;
  std::vector<double> width_;       ///< ΔX
  std::vector<double> label_left_;  ///< X of the left face, in its body's labels
  std::vector<double> psi_free_;    ///< Ψ of the cell's material at its free-end pressure
  std::vector<bool> has_psi_free_;
  std::vector<Conserved> u_;
  std::vector<State> state_;
  std::vector<double> speed_minus_, speed_plus_;  ///< λ∓ (Lagrangian) of the cell state, set with it
  // A cell whose U no step changed (its two face fluxes equal: a uniform region, common in
  // these scenes of piecewise constant states) keeps its state, speeds and flux as they were.
  std::vector<finite_volume::Recovered> recovered_;  ///< the last recovery of each cell: the next one starts there
  std::vector<char> moved_;                          ///< U changed in the last step: recover (φ, s)
  std::vector<char> flux_stale_;                     ///< the state changed since cell_flux_ was computed
  std::vector<char> clamped_cell_;                   ///< held at the parting stretch with void beyond kVoidFraction
  std::vector<FaceFlux> cell_flux_;                  ///< v and p of the cell state (the flux between equal states)
  std::vector<char> face_is_cell_;                   ///< order 2: no slope, the face states are the cell state
  std::vector<State> face_left_, face_right_;        ///< order 2: predicted states at the faces
  std::vector<FaceFlux> face_;                       ///< left face of cell c is c + body_of_[c]
  std::vector<double> j_plus_, j_minus_;             ///< order 2: J± of every cell

  std::vector<Body> bodies_;
  std::vector<Junction> junctions_;
  Wall walls_[2];
  Traction traction_[2];

  SampleSchedule samples_{scene_};
  RunResult result_;
  std::vector<RunEvent> pending_events_;
  double impulse_ = 0.0, wall_work_ = 0.0;
  long steps_ = 0;
  bool cavitation_warned_ = false;
};

// =====================================================================================
// set-up

/// Cells of each segment: `cells` shared in proportion to natural length (largest
/// remainder), at least one per segment.
std::vector<int> cells_per_segment(const BodyDecl& body, int cells) {
  const double l0 = body.natural_length();
  const std::size_t n = body.segments.size();
  std::vector<int> count(n);
  std::vector<double> remainder(n);
  int used = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double quota = cells * body.segments[k].length / l0;
    const double whole = std::floor(quota);
    count[k] = std::max(1, static_cast<int>(whole));
    remainder[k] = quota - whole;
    used += count[k];
  }
  while (used < cells) {
    const std::size_t k =
        static_cast<std::size_t>(std::max_element(remainder.begin(), remainder.end()) - remainder.begin());
    ++count[k];
    remainder[k] = -1.0;
    ++used;
    if (std::all_of(remainder.begin(), remainder.end(), [](double r) { return r < 0.0; }))
      std::fill(remainder.begin(), remainder.end(), 0.0);
  }
  return count;
}

void Scheme::build_cells() {
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const BodyDecl& decl = scene_.bodies[b];
    Body body;
    body.first = static_cast<int>(state_.size());
    body.length = decl.natural_length();
    body.x_left = decl.position;
    double X = 0.0, x = decl.position;
    const std::vector<int> counts = cells_per_segment(decl, scene_.solver.cells);
    for (std::size_t k = 0; k < decl.segments.size(); ++k) {
      const Segment& seg = decl.segments[k];
      const Material& m = scene_.material_of(seg);
      const State st{seg.rapidity, seg.stretch};
      // Ψ at the pressure of a free end (p = 0, or the cavitation pressure if higher).
      const Solved<Stretch> free_stretch = m.stretch_at_pressure(std::max(0.0, m.cavitation_pressure()));
      const double dX = seg.length / counts[k];
      const finite_volume::RecoveryBounds bounds = finite_volume::recovery_bounds(m);
      for (int i = 0; i < counts[k]; ++i) {
        material_.push_back(&m);
        bounds_.push_back(bounds);
        body_of_.push_back(static_cast<int>(b));
        width_.push_back(dX);
        label_left_.push_back(X + i * dX);
        psi_free_.push_back(free_stretch.ok() ? m.riemann_psi(free_stretch.value) : 0.0);
        has_psi_free_.push_back(free_stretch.ok());
        state_.push_back(st);
        u_.push_back(finite_volume::conserved(m, st));
      }
      X += seg.length;
      x += seg.length * seg.stretch.value() / std::cosh(seg.rapidity);
    }
    body.count = static_cast<int>(state_.size()) - body.first;
    body.x_right = x;
    bodies_.push_back(body);
  }
  const std::size_t n = state_.size();
  speed_minus_.assign(n, 0.0);
  speed_plus_.assign(n, 0.0);
  moved_.assign(n, 1);
  recovered_.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    recovered_[c].state = state_[c];
    set_speeds(c);
  }
  flux_stale_.assign(n, 1);
  clamped_cell_.assign(n, 0);
  cell_flux_.assign(n, FaceFlux{});
  face_is_cell_.assign(n, 0);
  if (order_ == 2) {
    face_left_.assign(n, State{});
    face_right_.assign(n, State{});
  }
  face_.assign(n + bodies_.size(), FaceFlux{});
}

void Scheme::build_walls() {
  const BoundaryDecl* decls[2] = {&scene_.left, &scene_.right};
  junctions_.assign(bodies_.size() + 1, Junction{});
  for (int side = 0; side < 2; ++side) {
    const BoundaryDecl& d = *decls[side];
    if (d.type == BoundaryType::traction) traction_[side] = Traction{true, d.traction_times, d.traction_pressures, 0};
    Wall& w = walls_[side];
    w.present = stands(d.type);
    if (!w.present) continue;
    w.bonded = d.bonded;
    w.x = d.position;
    if (d.type == BoundaryType::piston) {
      w.motion = d.piston;
      w.rapidity = w.motion.rapidities.empty() ? 0.0 : w.motion.rapidities.front();
    }
  }
  // Contacts present at t = 0: walls at a body's end, bodies touching each other.
  for (int j = 0; j < static_cast<int>(junctions_.size()); ++j) {
    junctions_[j].touching = sides_touch(j);
    junctions_[j].in_contact = junctions_[j].touching;
  }
}

// =====================================================================================
// one step

double Scheme::stable_step() {
  double dt = kInf;
  for (std::size_t c = 0; c < state_.size(); ++c) {
    const double fastest = std::max(-speed_minus_[c], speed_plus_[c]);
    dt = std::min(dt, width_[c] / fastest);
  }
  return scene_.solver.cfl * dt;
}

bool Scheme::ghost_invariants(int b, int side, int c, double& j_plus, double& j_minus) const {
  const int j = side < 0 ? b : b + 1;
  const bool boundary = j == 0 || j == static_cast<int>(bodies_.size());
  const bool wall = boundary && junctions_[j].touching;
  if (!boundary && junctions_[j].touching) return false;  // a contact with another body
  const double phi = state_[c].rapidity, psi = material_[c]->riemann_psi(state_[c].stretch);
  if (wall) {
    // Mirror about the wall: φ_g = 2 φ_wall − φ, Ψ_g = Ψ.
    const double phi_wall = walls_[j == 0 ? 0 : 1].rapidity;
    j_plus = 2.0 * phi_wall - (phi - psi);
    j_minus = 2.0 * phi_wall - (phi + psi);
    return true;
  }
  if (boundary && traction_[j == 0 ? 0 : 1].present) {
    // Mirror about the end's pressure: φ_g = φ, Ψ_g = 2 Ψ(p) − Ψ.
    const Material& m = *material_[c];
    const Solved<Stretch> held =
        m.stretch_at_pressure(std::max(traction_[j == 0 ? 0 : 1].pressure(), m.cavitation_pressure()));
    if (!held.ok()) return false;
    const double psi_held = m.riemann_psi(held.value);
    j_plus = phi + 2.0 * psi_held - psi;
    j_minus = phi - 2.0 * psi_held + psi;
    return true;
  }
  // Mirror about a free end: φ_g = φ, Ψ_g = 2 Ψ_free − Ψ.
  if (!has_psi_free_[c]) return false;
  j_plus = phi + 2.0 * psi_free_[c] - psi;
  j_minus = phi - 2.0 * psi_free_[c] + psi;
  return true;
}

void Scheme::reconstruct(double dt) {
  if (order_ != 2) return;
  const std::size_t n = state_.size();
  // Riemann invariants of every cell.
  std::vector<double>& jp = j_plus_;
  std::vector<double>& jm = j_minus_;
  jp.resize(n);
  jm.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    const double psi = material_[c]->riemann_psi(state_[c].stretch);
    jp[c] = state_[c].rapidity + psi;
    jm[c] = state_[c].rapidity - psi;
  }
  for (int c = 0; c < static_cast<int>(n); ++c) {
    const Body& body = bodies_[body_of_[c]];
    const Material* m = material_[c];
    // Neighbours' invariants and the distance between centres, on each side.
    double left_plus = 0.0, left_minus = 0.0, right_plus = 0.0, right_minus = 0.0;
    double left_distance = width_[c], right_distance = width_[c];
    bool has_left = false, has_right = false;
    if (c > body.first) {
      has_left = material_[c - 1] == m;  // invariants jump at a material interface
      left_plus = jp[c - 1];
      left_minus = jm[c - 1];
      left_distance = 0.5 * (width_[c - 1] + width_[c]);
    } else {
      has_left = ghost_invariants(body_of_[c], -1, c, left_plus, left_minus);
    }
    if (c < body.first + body.count - 1) {
      has_right = material_[c + 1] == m;
      right_plus = jp[c + 1];
      right_minus = jm[c + 1];
      right_distance = 0.5 * (width_[c + 1] + width_[c]);
    } else {
      has_right = ghost_invariants(body_of_[c], +1, c, right_plus, right_minus);
    }
    InvariantSlopes slope;
    if (has_left && has_right) {
      slope.plus =
          finite_volume::mc_limited_slope((jp[c] - left_plus) / left_distance, (right_plus - jp[c]) / right_distance);
      slope.minus =
          finite_volume::mc_limited_slope((jm[c] - left_minus) / left_distance, (right_minus - jm[c]) / right_distance);
    }
    face_left_[c] = face_right_[c] = state_[c];
    face_is_cell_[c] = 1;
    if (slope.plus == 0.0 && slope.minus == 0.0) continue;
    // MUSCL–Hancock predictor in characteristic form: J± at the faces at t + Δt/2,
    // from ∂t J± + λ± ∂X J± = 0 (docs/physics.md).
    const double h = width_[c];
    const double plus_right = jp[c] + 0.5 * (h - dt * speed_plus_[c]) * slope.plus;
    const double plus_left = jp[c] - 0.5 * (h + dt * speed_plus_[c]) * slope.plus;
    const double minus_right = jm[c] + 0.5 * (h - dt * speed_minus_[c]) * slope.minus;
    const double minus_left = jm[c] - 0.5 * (h + dt * speed_minus_[c]) * slope.minus;
    const Solved<Stretch> s_left = m->stretch_at_psi(0.5 * (plus_left - minus_left));
    const Solved<Stretch> s_right = m->stretch_at_psi(0.5 * (plus_right - minus_right));
    if (!s_left.ok() || !s_right.ok()) continue;  // beyond the material's range: first order here
    face_left_[c] = State{0.5 * (plus_left + minus_left), s_left.value};
    face_right_[c] = State{0.5 * (plus_right + minus_right), s_right.value};
    face_is_cell_[c] = 0;
  }
}

FaceFlux Scheme::interior_flux(int a, int c, double t) {
  const Material& mL = *material_[a];
  const Material& mR = *material_[c];
  const State& left = right_face_state(a);
  const State& right = left_face_state(c);
  const double p_min = min_pressure(mL, mR, false);
  if (&mL == &mR && left.rapidity == right.rapidity && left.stretch == right.stretch) {
    // No jump: the flux of the state itself (the exact Riemann problem is costly for a
    // genuinely nonlinear material, and uniform regions are common), that of cell a's
    // state kept while it does not change.
    const auto flux_of_state = [&] {
      FaceFlux f;
      f.velocity_left = f.velocity_right = std::tanh(left.rapidity);
      f.pressure = mL.pressure(left.stretch);
      return f;
    };
    const bool is_cell_state = order_ == 1 || face_is_cell_[a];
    if (is_cell_state && flux_stale_[a]) {
      cell_flux_[a] = flux_of_state();
      flux_stale_[a] = 0;
    }
    const FaceFlux f = is_cell_state ? cell_flux_[a] : flux_of_state();
    if (f.pressure >= p_min) return f;
  }
  if (scene_.solver.flux == FluxType::hll) {
    const FaceFlux f = finite_volume::hll_flux(mL, left, mR, right);
    if (f.pressure >= p_min) return f;
    // HLL would put a material that cavitates into tension: take the exact solution.
  }
  const RiemannSolution sol = solve_riemann(mL, left, mR, right, p_min);
  if (sol.status != Status::ok) check(sol, mR.psi_max() < mL.psi_max() ? mR : mL, t, x_of_cell(c));
  FaceFlux f;
  f.pressure = sol.pressure;
  if (sol.parted) {
    // The material parts here: one label flux for both cells (at the mean of the two
    // free-surface velocities), so that the opening is void inside the cells.
    f.velocity_left = f.velocity_right = 0.5 * (std::tanh(sol.left.rapidity) + std::tanh(sol.right.rapidity));
  } else {
    f.velocity_left = f.velocity_right = std::tanh(sol.left.rapidity);
  }
  return f;
}

void Scheme::junction_flux(int j, double t) {
  const int last = static_cast<int>(bodies_.size());
  Junction& junction = junctions_[j];
  junction.parted = false;
  // One face per body end meeting here.
  const int left_cell = j > 0 ? bodies_[j - 1].first + bodies_[j - 1].count - 1 : -1;
  const int right_cell = j < last ? bodies_[j].first : -1;
  auto set_face = [&](int face, const State& star, double pressure, bool parted) {
    FaceFlux& f = face_[face];
    f.velocity_left = f.velocity_right = std::tanh(star.rapidity);
    f.pressure = pressure;
    f.parted = parted;
  };

  if (left_cell < 0 || right_cell < 0) {
    // A body end at a boundary: a wall or piston in contact, or a free end.
    const bool left_boundary = left_cell < 0;
    const int c = left_boundary ? right_cell : left_cell;
    const Material& m = *material_[c];
    const State& st = left_boundary ? left_face_state(c) : right_face_state(c);
    const Side side = left_boundary ? Side::right : Side::left;
    const double x = left_boundary ? bodies_.front().x_left : bodies_.back().x_right;
    RiemannSolution sol;
    if (junction.touching) {
      const Wall& w = walls_[left_boundary ? 0 : 1];
      sol = solve_wall(m, st, side, w.rapidity,
                       w.bonded ? m.cavitation_pressure() : std::max(0.0, m.cavitation_pressure()));
      junction.parted = sol.parted;
    } else if (const Traction& held = traction_[left_boundary ? 0 : 1]; held.present) {
      sol = solve_traction_end(m, st, side, held.pressure());
    } else {
      sol = solve_free_end(m, st, side);
    }
    check(sol, m, t, x);
    set_face(left_boundary ? left_face(c) : right_face(c), left_boundary ? sol.right : sol.left, sol.pressure,
             sol.parted);
    return;
  }

  const Material& mL = *material_[left_cell];
  const Material& mR = *material_[right_cell];
  const State& left = right_face_state(left_cell);
  const State& right = left_face_state(right_cell);
  const double x = bodies_[j].x_left;
  if (junction.touching) {
    // Two bodies in contact: push-only.
    const RiemannSolution sol = solve_riemann(mL, left, mR, right, min_pressure(mL, mR, true));
    check(sol, sol.status == Status::out_of_range && mR.psi_max() < mL.psi_max() ? mR : mL, t, x);
    junction.parted = sol.parted;
    set_face(right_face(left_cell), sol.left, sol.pressure, sol.parted);
    set_face(left_face(right_cell), sol.right, sol.pressure, sol.parted);
    return;
  }
  // A gap: two free ends.
  const RiemannSolution a = solve_free_end(mL, left, Side::left);
  check(a, mL, t, bodies_[j - 1].x_right);
  const RiemannSolution b = solve_free_end(mR, right, Side::right);
  check(b, mR, t, x);
  set_face(right_face(left_cell), a.left, a.pressure, true);
  set_face(left_face(right_cell), b.right, b.pressure, true);
}

void Scheme::face_fluxes(double t) {
  for (const Body& body : bodies_)
    for (int c = body.first + 1; c < body.first + body.count; ++c) face_[left_face(c)] = interior_flux(c - 1, c, t);
  for (int j = 0; j <= static_cast<int>(bodies_.size()); ++j) junction_flux(j, t);
  result_.stats.interactions += static_cast<long>(face_.size());
}

double Scheme::closing_time(int j) const {
  if (junctions_[j].touching || !junction_can_touch(j)) return kInf;
  const int last = static_cast<int>(bodies_.size());
  // Position and velocity of the left side (a wall or a body's right end) and the right side.
  double x_left, v_left, x_right, v_right;
  if (j == 0) {
    x_left = walls_[0].x;
    v_left = walls_[0].velocity();
  } else {
    const Body& b = bodies_[j - 1];
    x_left = b.x_right;
    v_left = face_[right_face(b.first + b.count - 1)].velocity_left;
  }
  if (j == last) {
    x_right = walls_[1].x;
    v_right = walls_[1].velocity();
  } else {
    const Body& b = bodies_[j];
    x_right = b.x_left;
    v_right = face_[left_face(b.first)].velocity_right;
  }
  const double closing = v_left - v_right;
  if (!(closing > 0.0)) return kInf;
  return std::max(0.0, x_right - x_left) / closing;
}

void Scheme::advance(double dt) {
  for (std::size_t i = 0; i < state_.size(); ++i) {
    const int c = static_cast<int>(i);
    const FaceFlux& fl = face_[left_face(c)];
    const FaceFlux& fr = face_[right_face(c)];
    // U_i −= Δt/ΔX (F_{i+1/2} − F_{i−1/2}), F = (−v, p).
    const Flux left{-fl.velocity_right, fl.pressure};
    const Flux right{-fr.velocity_left, fr.pressure};
    const Flux difference = right - left;
    moved_[i] = difference[0] != 0.0 || difference[1] != 0.0;
    if (moved_[i]) u_[i] -= (dt / width_[i]) * difference;
  }
  for (Body& b : bodies_) {
    b.x_left += face_[left_face(b.first)].velocity_right * dt;
    b.x_right += face_[right_face(b.first + b.count - 1)].velocity_left * dt;
  }
  const int last = static_cast<int>(bodies_.size());
  for (int side = 0; side < 2; ++side) {
    if (traction_[side].present) {
      // The traction pushes the end with force p towards the body, at the end's velocity.
      const FaceFlux& f = side == 0 ? face_[left_face(bodies_.front().first)]
                                    : face_[right_face(bodies_.back().first + bodies_.back().count - 1)];
      const double force = side == 0 ? f.pressure : -f.pressure;
      impulse_ += force * dt;
      wall_work_ += force * (side == 0 ? f.velocity_right : f.velocity_left) * dt;
    }
    Wall& w = walls_[side];
    if (!w.present) continue;
    const Junction& junction = junctions_[side == 0 ? 0 : last];
    if (junction.touching) {
      // The wall pushes the body with force p towards it: +p at the left wall, −p at the right.
      const double p = side == 0 ? face_[left_face(bodies_.front().first)].pressure
                                 : face_[right_face(bodies_.back().first + bodies_.back().count - 1)].pressure;
      const double force = side == 0 ? p : -p;
      impulse_ += force * dt;
      wall_work_ += force * w.velocity() * dt;
    }
    w.x += w.velocity() * dt;
  }
}

void Scheme::recover(double t) {
  std::vector<bool> clamped(bodies_.size(), false);
  std::vector<int> first_clamped(bodies_.size(), -1);
  for (std::size_t i = 0; i < state_.size(); ++i) {
    const int c = static_cast<int>(i);
    if (!moved_[i]) {
      if (clamped_cell_[i]) {
        const int b = body_of_[c];
        if (!clamped[b]) first_clamped[b] = c;
        clamped[b] = true;
      }
      continue;
    }
    const finite_volume::Recovered r = finite_volume::recover_state(*material_[i], bounds_[i], u_[i], recovered_[i]);
    if (!r.ok()) {
      std::ostringstream os;
      os.precision(12);
      os << "finite_volume: at t = " << t << ", " << where_is_cell(c) << " holds s/gamma = " << u_[i][0]
         << " and momentum " << u_[i][1] << " per unit label, which no uniform state of '" << material_[i]->model()
         << "' has (" << to_string(r.status)
         << "): the set of admissible conserved states is not convex, and a cell average of strongly "
            "relativistic states can leave it; use solver.method characteristics";
      throw NumericalError(os.str());
    }
    state_[i] = r.state;
    recovered_[i] = r;
    set_speeds(i);
    flux_stale_[i] = 1;
    clamped_cell_[i] = 0;
    // Clamps of a cell at the parting stretch by round-off (a free surface of a fluid
    // sits exactly there) hold no void worth the name: only a void fraction beyond
    // kVoidFraction counts as cavitation.
    if (r.cavitated && 1.0 - r.state.stretch.value() / std::cosh(r.state.rapidity) / u_[i][0] > kVoidFraction) {
      clamped_cell_[i] = 1;
      const int b = body_of_[c];
      if (!clamped[b]) first_clamped[b] = c;
      clamped[b] = true;
    }
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (clamped[b] && !bodies_[b].cavitated) {
      event(t, "cavitation", x_of_cell(first_clamped[b]), {body_name(static_cast<int>(b))});
      if (!cavitation_warned_) {
        result_.warnings.push_back(
            "finite_volume: cells that would go into tension beyond the cavitation pressure are clamped there and "
            "hold void; a body with void inside at t_end is listed as its pieces, cut in the middle of its most void "
            "cell (to within a cell of where the characteristics solver parts it)");
        cavitation_warned_ = true;
      }
    }
    bodies_[b].cavitated = clamped[b];
  }
}

double Scheme::void_fraction(int k) const {
  return 1.0 - state_[k].stretch.value() / std::cosh(state_[k].rapidity) / u_[k][0];
}

void Scheme::list_pieces(int b) {
  const Body& body = bodies_[b];
  const int end = body.first + body.count;
  // A body that holds void inside at t_end (cells clamped at the parting stretch, with
  // material on both sides) has parted: it is listed as its pieces, each run of void cut
  // in its most void cell, whose material goes half to each side. Void at an end is a
  // free surface pulling away, not a crack.
  std::vector<int> cuts;
  for (int k = body.first; k < end;) {
    if (!(void_fraction(k) > kVoidFraction)) {
      ++k;
      continue;
    }
    int most = k, after = k;
    for (; after < end && void_fraction(after) > kVoidFraction; ++after)
      if (void_fraction(after) > void_fraction(most)) most = after;
    if (k > body.first && after < end) cuts.push_back(most);
    k = after;
  }
  // A piece's lab length is that of its material (the void is the gap between pieces): the
  // first is measured from the body's left end, every other one back from its right end
  // (the body's right end, or the middle of the material of the cell it is cut in).
  BodyResult r;
  double mass = 0.0, mass_velocity = 0.0, material_length = 0.0;
  const auto add = [&](int k, double share) {
    const double w = share * width_[k];
    const double rest_mass = material_[k]->rest_density() * w;
    mass += rest_mass;
    mass_velocity += rest_mass * std::tanh(state_[k].rapidity);
    material_length += w * label_density(state_[k]);
    r.energy += w * energy_density(*material_[k], state_[k]);
    r.momentum += w * u_[k][1];
    const EnergyParts parts = energy_parts(*material_[k], state_[k]);
    r.kinetic_energy += w * parts.kinetic;
    r.internal_energy += w * parts.internal;
    r.rest_energy += w * parts.rest;
  };
  const auto close = [&](double x_right, std::size_t number) {
    r.name = scene_.bodies[b].name + (cuts.empty() ? "" : "." + std::to_string(number));
    r.x_left = number == 1 ? body.x_left : x_right - material_length;
    r.x_right = number == 1 && !cuts.empty() ? body.x_left + material_length : x_right;
    r.velocity_mean = mass > 0.0 ? mass_velocity / mass : 0.0;
    result_.bodies.push_back(r);
    r = BodyResult{};
    mass = mass_velocity = material_length = 0.0;
  };
  double x = body.x_left;  // left face of cell k
  std::size_t next_cut = 0;
  for (int k = body.first; k < end; ++k) {
    const double cell = u_[k][0] * width_[k];
    if (next_cut < cuts.size() && cuts[next_cut] == k) {
      add(k, 0.5);
      close(x + 0.5 * width_[k] * label_density(state_[k]), next_cut + 1);
      add(k, 0.5);
      ++next_cut;
    } else {
      add(k, 1.0);
    }
    x += cell;
  }
  close(body.x_right, cuts.size() + 1);
}

void Scheme::side_positions(int j, double& x_left, double& x_right) const {
  const int last = static_cast<int>(bodies_.size());
  x_left = j == 0 ? walls_[0].x : bodies_[j - 1].x_right;
  x_right = j == last ? walls_[1].x : bodies_[j].x_left;
}

bool Scheme::sides_touch(int j) const {
  if (!junction_can_touch(j)) return false;
  double x_left = 0.0, x_right = 0.0;
  side_positions(j, x_left, x_right);
  return x_right - x_left <= 0.0 || touching(x_left, x_right);
}

void Scheme::update_junctions(double t_start, double t_end) {
  const int last = static_cast<int>(bodies_.size());
  for (int j = 0; j <= last; ++j) {
    Junction& junction = junctions_[j];
    if (!junction_can_touch(j)) continue;
    double x_left = 0.0, x_right = 0.0;
    side_positions(j, x_left, x_right);
    if (junction.touching && junction.parted) {
      if (std::isnan(junction.parted_since)) {
        // Where the sides were at the start of the step: the left side moved at its face velocity since.
        const double v = j == 0 ? walls_[0].velocity()
                                : face_[right_face(bodies_[j - 1].first + bodies_[j - 1].count - 1)].velocity_left;
        junction.parted_since = t_start;
        junction.parted_x = x_left - v * (t_end - t_start);
      }
    } else if (junction.touching) {
      junction.parted_since = std::numeric_limits<double>::quiet_NaN();
    }
    junction.touching = sides_touch(j);
    if (junction.touching == junction.in_contact) continue;
    junction.in_contact = junction.touching;
    std::vector<std::string> names;
    if (j > 0) names.push_back(body_name(j - 1));
    if (j < last) names.push_back(body_name(j));
    if (junction.touching) {
      event(t_end, "contact", j == 0 ? x_left : j == last ? x_right : 0.5 * (x_left + x_right), std::move(names));
      junction.parted_since = std::numeric_limits<double>::quiet_NaN();
    } else {
      const bool dated = !std::isnan(junction.parted_since);
      event(dated ? junction.parted_since : t_start, "separation", dated ? junction.parted_x : x_left,
            std::move(names));
    }
  }
}

// =====================================================================================
// errors

std::string Scheme::where_is_cell(int c) const {
  const int b = body_of_[c];
  std::ostringstream os;
  os.precision(12);
  os << "cell " << c - bodies_[b].first << " of body '" << body_name(b) << "' (X = " << label_left_[c] << " to "
     << label_left_[c] + width_[c] << ")";
  return os.str();
}

void Scheme::check(const RiemannSolution& sol, const Material& m, double t, double x) const {
  require_solved(sol, m, t, x, scene_.units);
}

// =====================================================================================
// outputs

double Scheme::x_of_cell(int c) const {
  const Body& b = bodies_[body_of_[c]];
  double x = b.x_left;
  for (int k = b.first; k < c; ++k) x += u_[k][0] * width_[k];
  return x;
}

int Scheme::locate(int body, double X, double& x) const {
  const Body& b = bodies_[body];
  // The last cell whose left face is at or left of X.
  const auto begin = label_left_.begin() + b.first, end = begin + b.count;
  int c = static_cast<int>(std::upper_bound(begin + 1, end, X) - label_left_.begin()) - 1;
  c = std::clamp(c, b.first, b.first + b.count - 1);
  x = x_of_cell(c) + (X - label_left_[c]) * u_[c][0];
  return c;
}

double Scheme::quantity(Quantity q, int c, double X, double x) const {
  return quantity_value(q, *material_[c], state_[c], X, x);
}

void Scheme::sample(const SampleTime& st) {
  const SamplingTimer timer(result_.stats.sampling_time_s);
  const double t = st.t;
  if (st.kind == SampleTime::Kind::probe) {
    const ProbeDecl& probe = scene_.outputs.probes[st.index];
    const int body = probe_body(scene_, probe);
    double x = 0.0, X = probe.X;
    if (probe.lab_x) {
      const double l0 = bodies_[body].length;
      const auto x_of = [&](double label) {
        double at = 0.0;
        static_cast<void>(locate(body, label, at));
        return at;
      };
      if (*probe.lab_x < x_of(0.0) || *probe.lab_x > x_of(l0)) return;  // the body is not there
      X = label_at_lab(*probe.lab_x, 0.0, l0, x_of);
    }
    const int c = locate(body, X, x);
    for (Quantity q : probe.quantities) recorder_.probe(ProbeSample{t, st.index, q, quantity(q, c, X, x)});
    return;
  }
  const SnapshotDecl& snap = scene_.outputs.snapshots[st.index];
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const BodyDecl& decl = scene_.bodies[b];
    if (!snapshot_includes(snap, decl)) continue;
    const Body& body = bodies_[b];
    const double l0 = body.length;
    // One sweep from the left end, summing (s/γ) ΔX.
    int c = body.first;
    double x_face = body.x_left;
    for (int i = 0; i < snap.samples; ++i) {
      const double X = l0 * i / (snap.samples - 1);
      while (c + 1 < body.first + body.count && label_left_[c + 1] <= X) {
        x_face += u_[c][0] * width_[c];
        ++c;
      }
      const double x = x_face + (X - label_left_[c]) * u_[c][0];
      for (Quantity q : snap.quantities)
        recorder_.snapshot(SnapshotSample{t, static_cast<int>(b), X, q, quantity(q, c, X, x)});
    }
  }
}

void Scheme::release_events(double t) {
  std::stable_sort(pending_events_.begin(), pending_events_.end(),
                   [](const RunEvent& a, const RunEvent& b) { return a.t < b.t; });
  const auto later =
      std::find_if(pending_events_.begin(), pending_events_.end(), [t](const RunEvent& e) { return e.t > t; });
  for (auto e = pending_events_.begin(); e != later; ++e) recorder_.event(*e);
  pending_events_.erase(pending_events_.begin(), later);
}

double Scheme::earliest_event_time(double t) const {
  double earliest = t;
  for (const Junction& junction : junctions_)
    if (junction.touching && !std::isnan(junction.parted_since)) earliest = std::min(earliest, junction.parted_since);
  return earliest;
}

void Scheme::totals(double& energy, double& momentum) const {
  energy = momentum = 0.0;
  for (std::size_t c = 0; c < state_.size(); ++c) {
    energy += width_[c] * energy_density(*material_[c], state_[c]);
    momentum += width_[c] * u_[c][1];
  }
}

// =====================================================================================
// the run

RunResult Scheme::run() {
  const auto start = std::chrono::steady_clock::now();
  build_cells();
  build_walls();
  result_.solver = "finite_volume";
  for (const BodyDecl& b : scene_.bodies) result_.body_names.push_back(b.name);
  totals(result_.conservation.energy_initial, result_.conservation.momentum_initial);
  if (scene_.outputs.fronts) result_.warnings.push_back("finite_volume tracks no fronts: fronts.csv is empty");

  const double t_end = scene_.t_end;
  double t = 0.0;
  for (;;) {
    while (samples_.next_time() <= t) sample(samples_.pop());
    if (t >= t_end) break;
    if (recorder_.poll(t, -1, result_.stats.interactions)) break;  // Ctrl-C; progress
    // The next time a step must land on.
    double target = t_end;
    target = std::min(target, samples_.next_time());
    for (const Wall& w : walls_)
      if (w.present) target = std::min(target, w.next_change());
    for (const Traction& held : traction_)
      if (held.present) target = std::min(target, held.next_change());

    const double stable = stable_step();
    if (!(stable > 0.0) || !std::isfinite(stable)) {
      throw NumericalError("finite_volume: no stable time step at t = " + number(t) + " (signal speeds not finite)");
    }
    double dt = target - t;
    bool lands_on_target = true;
    if (dt > stable) {
      // Split the remaining interval evenly rather than leave a sliver for the last step.
      dt = dt < 2.0 * stable ? 0.5 * dt : stable;
      lands_on_target = false;
    }
    try {
      reconstruct(dt);
      face_fluxes(t);
      // A gap that closes within the step: land on its closure.
      for (int pass = 0; pass < kGapClosurePasses; ++pass) {
        double closure = kInf;
        for (int j = 0; j <= static_cast<int>(bodies_.size()); ++j) closure = std::min(closure, closing_time(j));
        if (!(closure < dt)) break;
        dt = closure;
        lands_on_target = false;
        if (order_ == 1) break;  // first-order fluxes do not depend on the step
        reconstruct(dt);
        face_fluxes(t);
      }
    } catch (const InadmissibleError& e) {
      // No classical solution at a face from t on (a material crushed, ...): the cells are
      // still at t, where the books close.
      recorder_.halt(t, e.what());
      result_.inadmissible = e.where().value_or(Inadmissibility::at(t));
      break;
    }
    advance(dt);
    const double t_next = lands_on_target ? target : t + dt;
    for (Wall& w : walls_) {
      while (w.present && w.next_change() <= t_next) {
        ++w.segment;
        w.rapidity = w.motion.rapidities[w.segment];
      }
    }
    for (Traction& held : traction_)
      while (held.present && held.next_change() <= t_next) ++held.segment;
    update_junctions(t, t_next);
    recover(t_next);
    t = t_next;
    ++steps_;
    release_events(earliest_event_time(t));
  }

  // Any samples beyond t_end (none if the run stopped early: its state is at t).
  while (!samples_.done() && !recorder_.stopped()) sample(samples_.pop());
  release_events(kInf);

  // Close the books at t_end.
  Conservation& c = result_.conservation;
  totals(c.energy_final, c.momentum_final);
  c.wall_impulse = impulse_;
  c.wall_work = wall_work_;
  c.energy_dissipated = c.energy_initial + c.wall_work - c.energy_final;

  for (std::size_t b = 0; b < bodies_.size(); ++b) list_pieces(static_cast<int>(b));
  result_.solver_numbers = {{"cells", static_cast<double>(scene_.solver.cells)},
                            {"cells_total", static_cast<double>(state_.size())},
                            {"order", static_cast<double>(order_)},
                            {"cfl", scene_.solver.cfl},
                            {"steps", static_cast<double>(steps_)}};
  result_.stats.fronts = 0;
  result_.stats.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - result_.stats.sampling_time_s;
  return result_;
}

}  // namespace

RunResult solve_finite_volume(const Scene& scene, RunRecorder& recorder) {
  RunResult result = Scheme(scene, recorder).run();
  recorder.complete(result, scene.t_end);
  return result;
}

RunResult solve_finite_volume(const Scene& scene) {
  MemoryRecorder recorder;
  return solve_finite_volume(scene, recorder);
}

}  // namespace rigidity
