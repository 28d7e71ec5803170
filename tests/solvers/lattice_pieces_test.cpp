// A lone body of a linearly degenerate material slower than light (`hooke`) is a lattice
// piece: its fronts' crossings are known from the hodograph coordinates of their
// characteristics, not visited. Checked against the same scenes on the node list, crossing
// by crossing (fronts.csv asked for: a lattice piece is not made then), to round-off; the
// crossings it reports against the interactions the node list makes; a crossing that would
// crush the bar found where the node list finds it; a piece past its cap handed back.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "error_bound.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"

namespace rigidity {
namespace {

/// A Hooke bar of `count` segments of uneven lengths (no two crossings at one instant) with
/// velocities and stretches of amplitude `amplitude`, between the given boundaries.
std::string hooke_bar(int count, double amplitude, const std::string& left, const std::string& right, double t_end,
                      double tolerance, bool fronts) {
  std::ostringstream y;
  y.precision(17);
  y << "name: lattice\nmaterials: {soft: {model: hooke, wave_speed: 0.6, rest_density: 2.0}}\n"
    << "bodies:\n  - name: bar\n    material: soft\n    position: 0\n    segments:\n";
  double total = 0.0;
  std::vector<double> lengths;
  for (int k = 0; k < count; ++k) total += lengths.emplace_back(1.0 + 0.37 * std::sin(2.9 * k + 0.4));
  for (int k = 0; k < count; ++k)
    y << "      - {length: " << lengths[k] / total << ", velocity: " << amplitude * std::sin(1.7 * k + 0.3)
      << ", stretch: " << 1.0 + 0.5 * amplitude * std::cos(2.3 * k) << "}\n";
  y << "boundaries:\n  left: " << left << "\n  right: " << right << "\n"
    << "solver: {method: characteristics, tolerance: " << tolerance << "}\n"
    << "time: {end: " << t_end << "}\n"
    << "outputs:\n"
    << "  probes: [{name: inside, body: bar, at: 0.3711, quantities: [p, v, x], every: 0.05},\n"
    << "           {name: end, body: bar, at: right, quantities: [p, v, x], every: 0.05}]\n"
    << "  snapshots: [{times: [" << 0.31 * t_end << ", " << 0.77 * t_end << ", " << t_end
    << "], quantities: [x, v, s, p], samples: 401}]\n"
    << "  fronts: " << (fronts ? "true" : "false") << "\n";
  return y.str();
}

using Key = std::tuple<double, int, double, int>;  // t, body or probe, X, quantity

std::map<Key, double> samples(const RunResult& r) {
  std::map<Key, double> out;
  for (const SnapshotSample& s : r.snapshots) out[{s.t, s.body, s.X, static_cast<int>(s.quantity)}] = s.value;
  for (const ProbeSample& s : r.probes) out[{s.t, -1 - s.probe, 0.0, static_cast<int>(s.quantity)}] = s.value;
  return out;
}

/// Every sample of two runs of one scene agrees to round-off.
void expect_same_samples(const RunResult& lattice, const RunResult& nodes) {
  const std::map<Key, double> a = samples(lattice), b = samples(nodes);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 1000u);
  int checked = 0;
  for (const auto& [key, value] : a) {
    const auto it = b.find(key);
    ASSERT_NE(it, b.end());
    EXPECT_NEAR(value, it->second, 1e-12 * (1.0 + std::abs(value)))
        << "t = " << std::get<0>(key) << ", X = " << std::get<2>(key) << ", quantity " << std::get<3>(key);
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(a.size()));
}

struct Ends {
  const char* name;
  const char* left;
  const char* right;
};

TEST(LatticePieces, AHookeBarIsWhatTheNodeListMakesOfItCrossingByCrossing) {
  for (const Ends& ends : {Ends{"bonded walls", "{type: wall, bonded: true}", "{type: wall, bonded: true}"},
                           Ends{"a wall it may leave and a free end", "{type: wall}", "{type: free}"},
                           Ends{"a bonded wall and a piston that stops and pulls", "{type: wall, bonded: true}",
                                "{type: piston, table: [[0.0, -0.05], [1.3, 0.0], [2.9, 0.04]]}"}}) {
    SCOPED_TRACE(ends.name);
    const std::string lattice_yaml = hooke_bar(60, 0.03, ends.left, ends.right, 5.0, 1e-6, false);
    const std::string nodes_yaml = hooke_bar(60, 0.03, ends.left, ends.right, 5.0, 1e-6, true);
    const RunResult lattice = solve(load_scene_string(lattice_yaml, "<lattice>"));
    const RunResult nodes = solve(load_scene_string(nodes_yaml, "<nodes>"));
    ASSERT_EQ(lattice.status, "ok");
    ASSERT_EQ(nodes.status, "ok");
    // The node list visits every crossing; the lattice piece only what reaches its ends.
    EXPECT_EQ(nodes.stats.crossings_unvisited, 0);
    EXPECT_GT(nodes.stats.interactions, 20 * lattice.stats.interactions);
    // Each crossing once: the lattice's unvisited ones and its end events are the node list's
    // interactions (no crowds here: the segments' lengths make every crossing its own instant).
    EXPECT_EQ(lattice.stats.interactions + lattice.stats.crossings_unvisited, nodes.stats.interactions);
    expect_same_samples(lattice, nodes);
    const Conservation& a = lattice.conservation;
    const Conservation& b = nodes.conservation;
    EXPECT_NEAR(a.energy_final, b.energy_final, 1e-12);
    EXPECT_NEAR(a.momentum_final, b.momentum_final, 1e-12);
    EXPECT_NEAR(a.wall_impulse, b.wall_impulse, 1e-12);
    EXPECT_NEAR(a.wall_work, b.wall_work, 1e-12);
    // Contacts only: energy changes by the work of the walls, to round-off.
    EXPECT_NEAR(a.energy_final - a.energy_initial, a.wall_work, 1e-12);
    EXPECT_NEAR(a.momentum_final - a.momentum_initial, a.wall_impulse, 1e-12);
  }
}

/// The time in "... at t = <number> ..." of an error message.
double time_in(const std::string& message);

TEST(LatticePieces, RandomBarsBetweenAnyEndsAreWhatTheNodeListMakesOfThem) {
  const CheckedInvariants checked;  // after every interaction
  // Hooke bars of 8–40 segments of random lengths, velocities and stretches, between free
  // ends, walls (bonded or not) and pistons (steady or changing speed, bonded or not), at a
  // tolerance that merges nothing: every sample (snapshots at an end's events included) as on
  // the node list, or the same crushing crossing at the same instant.
  std::mt19937 random(20261126);
  const auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(random); };
  const auto end = [&]() -> std::string {
    std::ostringstream e;
    switch (std::uniform_int_distribution<int>(0, 5)(random)) {
      case 0: return "{type: free}";
      case 1: return "{type: wall}";
      case 2: return "{type: wall, bonded: true}";
      case 3: e << "{type: piston, velocity: " << uniform(-0.1, 0.1) << "}"; return e.str();
      default: {
        e << "{type: piston, bonded: " << (uniform(0, 1) < 0.5 ? "true" : "false") << ", table: [";
        for (int k = 0; k < 6; ++k) e << (k > 0 ? ", " : "") << "[" << 0.5 * k << ", " << uniform(-0.15, 0.15) << "]";
        e << "]}";
        return e.str();
      }
    }
  };
  int compared = 0, crushed = 0;
  for (int scene = 0; scene < 16; ++scene) {
    const int count = std::uniform_int_distribution<int>(8, 40)(random);
    const double amplitude = uniform(0.003, 0.1);
    const double wave_speed = uniform(0.3, 0.9);
    std::ostringstream segments;
    segments.precision(17);
    for (int k = 0; k < count; ++k)
      segments << (k > 0 ? ", " : "") << "{length: " << uniform(0.5, 1.5) / count
               << ", velocity: " << uniform(-amplitude, amplitude)
               << ", stretch: " << 1.0 + 0.5 * uniform(-amplitude, amplitude) << "}";
    const std::string left = end(), right = end();
    std::string outcome[2];
    RunResult results[2];
    for (int fronts = 0; fronts < 2; ++fronts) {
      std::ostringstream y;
      y << "name: random_bar\nmaterials: {m: {model: hooke, wave_speed: " << wave_speed << "}}\n"
        << "bodies: [{name: bar, material: m, position: 0, segments: [" << segments.str() << "]}]\n"
        << "boundaries: {left: " << left << ", right: " << right << "}\n"
        << "solver: {tolerance: 1.0e-9}\ntime: {end: 6}\n"
        << "outputs: {probes: [{name: p, body: bar, at: 0.4321, quantities: [p, v, x], every: 0.0625}],\n"
        << "  snapshots: [{times: [1.5, 3.0, 6.0], quantities: [x, v, s, p], samples: 65}],\n"
        << "  fronts: " << (fronts == 1 ? "true" : "false") << "}\n";
      try {
        results[fronts] = solve(load_scene_string(y.str(), "<random bar>"));
        outcome[fronts] = "ok";
      } catch (const InadmissibleError& e) {
        outcome[fronts] = e.what();
      }
    }
    SCOPED_TRACE("scene " + std::to_string(scene) + ": " + left + " | " + right);
    if (outcome[1] != "ok") {
      ASSERT_NE(outcome[0], "ok") << outcome[1];
      EXPECT_NEAR(time_in(outcome[0]), time_in(outcome[1]), 1e-12) << outcome[0] << "\n" << outcome[1];
      ++crushed;
      continue;
    }
    ASSERT_EQ(outcome[0], "ok");
    for (const RunResult& r : results)
      for (const auto& [name, value] : r.solver_numbers)
        if (name == "fronts_merged") {
          ASSERT_EQ(value, 0.0);
        }
    expect_same_samples(results[0], results[1]);
    EXPECT_EQ(results[0].stats.interactions + results[0].stats.crossings_unvisited, results[1].stats.interactions);
    ++compared;
  }
  EXPECT_GE(compared, 8);
}

double time_in(const std::string& message) {
  const std::size_t at = message.find("t = ");
  if (at == std::string::npos) return -1.0;
  return std::stod(message.substr(at + 4));
}

TEST(LatticePieces, ACrossingThatWouldCrushTheBarIsFoundWhereTheNodeListFindsIt) {
  // Two pistons start at t = 0.3 into a ringing Hooke bar of V = 0.6 at 0.46c from both
  // sides: each wave alone leaves Ψ = artanh 0.46 ≈ 0.5 below Ψ_max = artanh 0.6 ≈ 0.69, but
  // where they cross the star would need Ψ ≈ 1. The lattice piece sees that the invariants it
  // now holds could meet there and hands its fronts back to the node list, which finds the
  // crossing in the middle of the bar.
  std::string messages[2];
  for (int fronts = 0; fronts < 2; ++fronts) {
    const std::string yaml = hooke_bar(30, 0.01, "{type: piston, table: [[0.0, 0.0], [0.3, 0.46]]}",
                                       "{type: piston, table: [[0.0, 0.0], [0.3, -0.46]]}", 1.3, 1e-6, fronts == 1);
    try {
      (void)solve(load_scene_string(yaml, "<test>"));
    } catch (const InadmissibleError& e) {
      messages[fronts] = e.what();
    }
  }
  ASSERT_NE(messages[1].find("crush"), std::string::npos) << messages[1];
  ASSERT_NE(messages[0].find("crush"), std::string::npos) << messages[0];
  const double t_lattice = time_in(messages[0]), t_nodes = time_in(messages[1]);
  ASSERT_GT(t_nodes, 0.0);
  EXPECT_NEAR(t_lattice, t_nodes, 1e-12) << messages[0] << "\n" << messages[1];
}

TEST(LatticePieces, APiecePastItsCapGoesBackToTheNodeList) {
  // A bonded piston that changes its speed forty times sends a front into the bar each time;
  // at tolerance 1e-2 the cap is 100 fronts per body, which the bar's 78 and the piston's
  // fronts pass: its fronts go back to the node list, where they are merged as on any piece.
  std::ostringstream table;
  table << "{type: piston, bonded: true, table: [";
  for (int k = 0; k < 40; ++k)
    table << (k > 0 ? ", " : "") << "[" << 0.1 * k << ", " << 0.03 * std::sin(1.3 * k) << "]";
  table << "]}";
  const RunResult lattice =
      solve(load_scene_string(hooke_bar(40, 0.03, "{type: wall}", table.str(), 6.0, 1e-2, false), "<lattice>"));
  const RunResult nodes =
      solve(load_scene_string(hooke_bar(40, 0.03, "{type: wall}", table.str(), 6.0, 1e-2, true), "<nodes>"));
  ASSERT_EQ(lattice.status, "ok");
  ASSERT_EQ(nodes.status, "ok");
  EXPECT_GT(lattice.stats.crossings_unvisited, 1000) << "a lattice piece at first";
  EXPECT_GT(lattice.stats.interactions, lattice.stats.crossings_unvisited) << "then crossings visited";
  // The hand-over comes at t = 2.2 here, when the piston's 22nd front makes 101. The lattice
  // carried the waves exactly until then and merges after; the node list merged its weakest
  // fronts from the start. Each run is within its bound of the truth, so the two agree
  // within the sum of their bounds (|Δv| + |Δs| over the bar's labels at t_end).
  const std::map<Key, double> a = samples(lattice), b = samples(nodes);
  const double t_end = 6.0;
  std::map<double, double> difference;  // by label: |Δv| + |Δs|
  for (const auto& [key, value] : a) {
    const auto [t, body, X, quantity] = key;
    if (t != t_end || body != 0) continue;
    if (quantity == static_cast<int>(Quantity::v) || quantity == static_cast<int>(Quantity::s))
      difference[X] += std::abs(value - b.at(key));
  }
  ASSERT_EQ(difference.size(), 401u);
  double distance = 0.0, previous_X = 0.0, previous = difference.begin()->second;
  for (const auto& [X, d] : difference) {
    distance += 0.5 * (d + previous) * (X - previous_X);
    previous_X = X;
    previous = d;
  }
  double bounds = 0.0;
  for (const RunResult* r : {&lattice, &nodes})
    for (const auto& [name, value] : r->solver_numbers)
      if (name == "error_bound") bounds += value;
  EXPECT_GT(distance, 0.0) << "the runs merged differently: the comparison checks something";
  EXPECT_LE(distance, bounds);
}

}  // namespace
}  // namespace rigidity
