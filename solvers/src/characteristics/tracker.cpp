// Set-up of bodies and walls, and the main loop of the front tracker.
#include "tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/number_text.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/units.hpp"

namespace rigidity::characteristics {

void Tracker::build_bodies() {
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const BodyDecl& body = scene_.bodies[b];
    const int piece = static_cast<int>(pieces_.size());
    pieces_.push_back(Piece{static_cast<int>(b), kNone, kNone});
    order_.push_back(piece);
    body_pieces_.push_back(1);
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
    if (d.type == BoundaryType::traction) {
      w.traction = true;
      w.motion.times = d.traction_times;
      w.pressures = d.traction_pressures;
      w.pressure = w.pressures.front();
    }
    w.present = stands(d.type);
    if (!w.present) continue;
    w.bonded = d.bonded;
    w.x0 = d.position;
    w.t0 = 0.0;
    if (d.type == BoundaryType::piston) {
      // A linear table's ramps in steps of the width fans have: smooth waves between them.
      w.motion =
          d.piston.ramps ? linear_piston(d.piston.row_times, d.piston.row_rapidities, policy_.fan_step()) : d.piston;
      w.rapidity = w.motion.rapidities.empty() ? 0.0 : w.motion.rapidities.front();
    }
  }
}

RunResult Tracker::run() {
  const auto start = std::chrono::steady_clock::now();
  build_bodies();
  build_walls();
  result_.solver = "characteristics";
  result_.solver_numbers = {{"tolerance", scene_.solver.tolerance}};
  for (const BodyDecl& b : scene_.bodies) result_.body_names.push_back(b.name);
  set_thresholds();
  totals(0.0, result_.conservation.energy_initial, result_.conservation.momentum_initial);
  schedule_start();
  event_loop();
  const double t_end = recorder_.stopped() ? recorder_.t_reached() : scene_.t_end;
  while (!samples_.done() && !recorder_.stopped()) sample(samples_.pop());

  close_books(t_end);
  const BoundParts parts = error_bound_parts(t_end);
  report_error_bound(parts);
  report_conservation(t_end);
  report_bodies(t_end);
  if (fan_capped_ && scene_.solver.tolerance_given) {  // the default asks for no more than the cap gives
    result_.warnings.push_back("rarefaction fans were split into at most " + std::to_string(kMaxFanSteps) +
                               " steps: coarser than solver.tolerance = " + number(scene_.solver.tolerance));
  }
  result_.stats.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - result_.stats.sampling_time_s;
  return result_;
}

void Tracker::set_thresholds() {
  total_length_ = 0.0;
  for (const BodyDecl& b : scene_.bodies) total_length_ += b.natural_length();
  const double tolerance = scene_.solver.wave_resolution();
  star_mismatch_ = kStarMismatch * tolerance * tolerance;
  dissipation_precision_ = kDissipationPrecision * tolerance;
}

void Tracker::schedule_start() {
  // Contacts present at t = 0: walls at a body's end, bodies touching each other.
  for (int side = 0; side < 2; ++side) {
    Wall& w = walls_[side];
    if (!w.present && !w.traction) continue;
    const int end = side == 0 ? pieces_[order_.front()].left_end : pieces_[order_.back()].right_end;
    if (w.traction || touching(nodes_[end].x0, w.x0)) {
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
}

void Tracker::event_loop() {
  // The cost model. Each pass of the loop takes the earliest event: a meeting of two
  // neighbouring nodes (the heap holds one current entry per node, and stale ones at most a
  // few times as many), a gap closing, a piston changing speed, or a sample. An interaction
  // emits at most one front per family, except a fan, split into steps of Ψ between one and
  // two tolerances wide; it removes those it resolves. Live fronts are bounded by the cap
  // bodies × front cap, front cap = max(kMinFrontsPerBody, kFrontsPerBody/tolerance)
  // (ResolutionPolicy; merges grow costlier while it is exceeded), so a crossing of the bodies
  // by the waves costs at most about (front cap)²/4 interactions and the interactions grow
  // linearly with time.end. Fans alone need about (their span in Ψ)/tolerance steps: a
  // genuinely nonlinear body costs ~1/tolerance² per crossing. A spray whose droplets book more
  // than the tolerance coarsens all this to its own level (ResolutionPolicy::at_droplet): its
  // cost per crossing then no longer grows as the tolerance falls.
  for (;;) {
    while (!queue_.empty() && !valid(queue_.front())) pop_event();
    // The earliest of the next rare event and the next meeting (ties in the order scheduled).
    const bool rare_first =
        !queue_.empty() && (meetings_.empty() || queue_.front().t < meetings_.top().t ||
                            (queue_.front().t == meetings_.top().t && queue_.front().seq < meetings_.top().seq));
    const double t_event = rare_first ? queue_.front().t : meetings_.empty() ? kInf : meetings_.top().t;
    if (samples_.next_time() < t_event) {
      sample(samples_.pop());
      continue;
    }
    if (!light_made_ && t_event > 0.0) {
      make_light(0.0);  // once every discontinuity of t = 0 is resolved
      continue;
    }
    if (t_event > scene_.t_end) break;
    if (recorder_.poll(t_event, live_fronts_, result_.stats.interactions)) break;  // a budget, Ctrl-C; progress
    try {
      if (rare_first) {
        const Event e = queue_.front();
        pop_event();
        handle(e);
      } else {
        // A crossing done in place reschedules (or removes) the meeting it was, which moves
        // the entry down from the top once instead of removing it and inserting another.
        const MeetingQueue::Entry m = meetings_.top();
        if (split_reached_fan(m.node, m.t)) {
          // A fan's edge was reached: its steps take its place, and the meetings they make go on.
        } else if (interact_in_place(m.node, nodes_[m.node].next, m.t)) {
          if (!meetings_.empty() && meetings_.top().node == m.node && meetings_.top().seq == m.seq)
            meetings_.erase(m.node);
        } else {
          meetings_.erase(m.node);
          resolve(m.node, nodes_[m.node].next, m.t);
        }
      }
    } catch (const InadmissibleError& e) {
      // No classical solution from t_event on (a material crushed, ...): the books close at
      // t_event. The interaction that found it emitted nothing; the fronts it took in met at
      // one point, so what lay between them has no length at t_event.
      recorder_.halt(t_event, e.what());
      result_.inadmissible = e.where().value_or(Inadmissibility::at(t_event));
      break;
    }
    if (validating()) validate(t_event);
  }
}

void Tracker::close_books(double t_end) {
  // Close the books at t_end.
  for (int side = 0; side < 2; ++side) flush_wall(side, t_end);
  for (std::size_t id = 0; id < nodes_.size(); ++id) {
    Node& n = nodes_[id];
    if (!n.alive || n.kind == NodeKind::light_store) continue;
    if (n.kind == NodeKind::front) account_front_end(static_cast<int>(id), t_end);
    if (unsplit(static_cast<int>(id))) {
      record_fan_edges(static_cast<int>(id), t_end);
    } else {
      record_segment(n, t_end);
    }
  }
  for (std::size_t piece = 0; piece < light_.size(); ++piece) {
    if (!is_light(static_cast<int>(piece))) continue;
    record_light_segments(static_cast<int>(piece), t_end);
    result_.stats.crossings_unvisited += lattice_crossings_done(static_cast<int>(piece), t_end);
  }
  // Waves held back at interfaces and contacts, fronts off their curves: booked up to t_end.
  for (Node& n : nodes_)
    if (n.alive) close_defect(n, t_end);
}

Tracker::BoundParts Tracker::error_bound_parts(double t_end) const {
  double error_fans_alive = 0.0, carried_alive = 0.0;
  for (std::size_t id = 0; id < nodes_.size(); ++id) {
    const Node& n = nodes_[id];
    if (!n.alive || n.kind != NodeKind::front) continue;
    carried_alive += n.carried;
    // A step still on its line stands for its centred fan, which the samples take exactly.
    // Every other step of a smooth wave (a fan's, a piston ramp's, what they become in linearly
    // degenerate bodies and as weak shocks) books the reconstruction's error where it applies,
    // the staircase's where the samples take the staircase (a step between plateaus, a
    // superposed one).
    if ((n.front_kind == FrontKind::rarefaction || n.smooth) && n.fan == kNone)
      error_fans_alive += fan_error(static_cast<int>(id), t_end);
    // A jump that met a smooth wave is off its path by up to about kink × kink_dt / 2.
    if (n.kink > 0.0) error_fans_alive += 0.5 * n.strength * n.kink * std::min(t_end - n.t0, n.kink_dt);
  }
  for (std::size_t piece = 0; piece < light_.size(); ++piece) {
    const LightPiece& lp = light_[piece];
    for (const std::deque<LightFront>* queue : {&lp.plus, &lp.minus})
      for (const LightFront& f : *queue) carried_alive += f.carried;
    if (lp.store != kNone) error_fans_alive += light_alive_error(static_cast<int>(piece));
  }
  error_fans_alive += ramp_ahead_error(t_end);
  // Each error was measured when it was made. Those of merges and fan steps travel with the
  // waves they were made on, and where a wave splits at an interface or an end its error
  // splits with it, grown or shrunk as the outgoing waves are (share_carried): what the
  // fronts carry at t_end, and what they carried when they ended without a successor. Held-
  // back waves, star mismatches and droplets stay where they were booked. On top of that the
  // bound allows a factor kStability for what the linear picture misses (crossings of
  // genuinely nonlinear waves change each other's strengths), measured on the test suite's
  // scenes, not proven.
  const double carried = ledger_.on_waves(carried_alive);
  const double booked = ledger_.booked(carried, error_fans_alive);
  const double error_bound = kStability * booked / total_length_;
  return BoundParts{error_bound, carried, error_fans_alive};
}

namespace {

/// A number said to be above the tolerance, with the digits (two at least) that print it above
/// the tolerance as printed: never "0.001 is above solver.tolerance = 0.001".
std::string above_tolerance(double v, double tolerance) {
  const double printed_tolerance = std::stod(number(tolerance));
  for (int digits = 2; digits <= 17; ++digits) {
    const std::string text = significant(v, digits);
    if (std::stod(text) > printed_tolerance) return text;
  }
  return number(v);
}

}  // namespace

void Tracker::report_error_bound(const BoundParts& bound) {
  report_bound_numbers(bound);
  report_qualitative();
  const bool spray_coarsened = warn_spray_coarsened();
  // A bound above the tolerance asked for: say which part holds it up and what would lower it.
  if (scene_.solver.tolerance_given && bound.error_bound > scene_.solver.tolerance &&
      !fan_capped_) {  // (or the fan cap says why)
    warn_bound_above_tolerance(bound, spray_coarsened);
  }
}

void Tracker::report_bound_numbers(const BoundParts& bound) {
  const double error_bound = bound.error_bound, carried = bound.carried, error_fans_alive = bound.error_fans_alive;
  result_.solver_numbers.emplace_back("error_bound", error_bound);
  result_.solver_numbers.emplace_back("weak_wave_threshold", policy_.weak_wave());
  result_.solver_numbers.emplace_back("waves_held_back", static_cast<double>(suppressed_));
  result_.solver_numbers.emplace_back("fronts_merged", static_cast<double>(merged_));
  result_.solver_numbers.emplace_back("error_defects", ledger_.defects() / total_length_);
  result_.solver_numbers.emplace_back("error_fans", (ledger_.fans() + error_fans_alive) / total_length_);
  result_.solver_numbers.emplace_back("error_merges", ledger_.merges() / total_length_);
  result_.solver_numbers.emplace_back("error_carried", carried / total_length_);
  result_.solver_numbers.emplace_back("droplets", static_cast<double>(droplets_));
  result_.solver_numbers.emplace_back("error_droplets", ledger_.droplets() / total_length_);
  result_.solver_numbers.emplace_back("fronts_alive_max", static_cast<double>(live_fronts_max_));
  result_.solver_numbers.emplace_back("wave_resolution", policy_.coarsest_resolution());
  result_.solver_numbers.emplace_back("fan_step_max", policy_.widest_fan_step());
}

void Tracker::report_qualitative() {
  if (qualitative_cracks_ <= 0 && cracks_after_droplets_ <= 0) return;
  // In the scene's units, as every time a run reports.
  const std::string unit(unit_symbol(Dimension::time, scene_.units));
  const double since = from_natural(qualitative_since_, Dimension::time, scene_.units);
  result_.solver_numbers.emplace_back("qualitative_from", since);
  result_.solver_numbers.emplace_back("cracks_by_smooth_waves", static_cast<double>(qualitative_cracks_));
  result_.solver_numbers.emplace_back("cracks_after_droplets", static_cast<double>(cracks_after_droplets_));
  const auto cracks = [](long n) { return std::to_string(n) + (n == 1 ? " crack" : " cracks"); };
  std::string why;
  if (qualitative_cracks_ > 0)
    why = "body '" + scene_.bodies[qualitative_body_].name + "' cracked where the steps of a smooth wave decided it (" +
          cracks(qualitative_cracks_) + ")";
  if (cracks_after_droplets_ > 0)
    why += std::string(why.empty() ? "" : ", and ") + "bodies cracked after a droplet was kept in body '" +
           scene_.bodies[first_droplet_body_].name +
           "' at t = " + number(from_natural(first_droplet_, Dimension::time, scene_.units)) + " " + unit + " (" +
           cracks(cracks_after_droplets_) + ": with a finer tolerance it would have broken off)";
  result_.warnings.push_back("from t = " + number(since) + " " + unit + " the result is qualitative: " + why +
                             ", so where and when bodies part, and all that follows, changes with solver.tolerance; "
                             "the error bound does not cover it");
}

bool Tracker::warn_spray_coarsened() {
  // Coarser than the run started at (which `resolution: auto` may set above the tolerance).
  const bool spray_coarsened =
      policy_.coarsest_resolution() > std::max(scene_.solver.tolerance, scene_.solver.wave_resolution());
  if (spray_coarsened) {
    result_.warnings.push_back("the droplets of a spray booked " +
                               significant(kStability * ledger_.droplets() / total_length_, 2) +
                               " of the error bound, which no tolerance reduces: while they dominated, waves and "
                               "droplets were resolved more coarsely than solver.tolerance = " +
                               number(scene_.solver.tolerance) + ", at most to " +
                               above_tolerance(policy_.coarsest_resolution(), scene_.solver.tolerance));
  }
  return spray_coarsened;
}

void Tracker::warn_bound_above_tolerance(const BoundParts& bound, bool spray_coarsened) {
  const double error_bound = bound.error_bound, carried = bound.carried, error_fans_alive = bound.error_fans_alive;
  const double parts[4] = {ledger_.merges(), ledger_.fans() + error_fans_alive, ledger_.defects(), ledger_.droplets()};
  const int largest = static_cast<int>(std::max_element(parts, parts + 4) - parts);
  const std::string why[4] = {
      "merges that held the live fronts to their cap (max(" + number(ResolutionPolicy::kMinFrontsPerBody) + ", " +
          number(ResolutionPolicy::kFrontsPerBody) +
          "/tolerance) per body): the waves scatter into more fronts than the cap lets the run follow",
      ("the steps of smooth waves (fans and piston ramps, reconstructed between them where they "
       "cross only each other, staircases where shocks and rigid bodies meet them; the widest step is "
       "fan_step_max)"),
      "weak waves held back at interfaces and contacts", "droplets kept with their pieces"};
  // What a smaller tolerance does to each part, and at what cost.
  static constexpr const char* kLower[4] = {
      "a smaller tolerance raises the cap, at a cost that grows as its inverse square",
      ("a smaller tolerance lowers it in proportion where the waves are reconstructed (and as its square root "
       "where they are staircases), at a cost that grows as its inverse"),
      "a smaller tolerance lowers it in proportion", "a smaller tolerance lowers it"};
  if (largest == 3 && spray_coarsened) return;  // a spray has said so above
  // What merges and fan steps made, once the waves that carry it have split at
  // interfaces, contacts and ends, may have grown: say so where it has.
  const double made = ledger_.merges() + ledger_.fans() + error_fans_alive;
  const std::string grown = largest <= 1 && carried + error_fans_alive > 1.5 * made
                                ? " (what merges and fan steps booked grew to " +
                                      significant(kStability * (carried + error_fans_alive) / total_length_, 2) +
                                      " as the waves carried it through interfaces, contacts and ends)"
                                : "";
  result_.warnings.push_back("the error bound " + above_tolerance(error_bound, scene_.solver.tolerance) +
                             " is above solver.tolerance = " + number(scene_.solver.tolerance) + ": most of it (" +
                             significant(kStability * parts[largest] / total_length_, 2) + ") booked by " +
                             why[largest] + grown + "; " + kLower[largest] + ", a shorter time.end in proportion");
}

void Tracker::report_conservation(double t_end) {
  Conservation& c = result_.conservation;
  totals(t_end, c.energy_final, c.momentum_final);
  c.wall_impulse = impulse_;
  c.wall_work = wall_work_;
  c.energy_dissipated = dissipated_;
  c.energy_droplets = droplet_energy_;
  c.momentum_droplets = droplet_momentum_;
  c.energy_waves = waves_energy_;
  c.momentum_waves = waves_momentum_;
}

void Tracker::report_bodies(double t_end) {
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
      // One region of natural length dX in state `state`.
      const auto add = [&](double dX, const Material& m, const State& state) {
        mass += m.rest_density() * dX;
        mass_velocity += m.rest_density() * dX * std::tanh(state.rapidity);
        r.energy += dX * energy_density(m, state);
        r.momentum += dX * momentum_density(m, state);
        const EnergyParts split = energy_parts(m, state);
        r.kinetic_energy += dX * split.kinetic;
        r.internal_energy += dX * split.internal;
        r.rest_energy += dX * split.rest;
      };
      integrate_piece(parts[k], t_end, add);
      r.velocity_mean = mass > 0.0 ? mass_velocity / mass : 0.0;
      result_.bodies.push_back(r);
    }
  }
}

}  // namespace rigidity::characteristics
