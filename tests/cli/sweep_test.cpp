// rigidity sweep (docs/sweeps.md): the figures it collects against the paper's closed forms,
// the same table whatever the number of threads, resumption, and bad input.
#include "rigidity/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/solve.hpp"
#include "run_cli.hpp"

namespace rigidity::testing {
namespace {

using Rows = std::vector<std::vector<std::string>>;

/// sweep.csv as cells (the sweeps here quote nothing but messages, which hold no newline).
Rows read_csv(const fs::path& file) {
  Rows rows;
  std::istringstream in(read_text(file));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quoted) {
        if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
          cell += '"';
          ++i;
        } else if (c == '"') {
          quoted = false;
        } else {
          cell += c;
        }
      } else if (c == '"') {
        quoted = true;
      } else if (c == ',') {
        cells.push_back(cell);
        cell.clear();
      } else {
        cell += c;
      }
    }
    cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

/// The table without its wall_time_s column (the one column that may differ between runs).
Rows without_wall_time(Rows rows) {
  for (auto& row : rows) row.pop_back();
  return rows;
}

std::size_t column(const Rows& rows, const std::string& name) {
  for (std::size_t i = 0; i < rows.front().size(); ++i)
    if (rows.front()[i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

constexpr const char* kPaperSweep =
    "parameters:\n"
    "  bodies.0.velocity: {linspace: [0.1, 0.9, 9]}\n"
    "  time.end: {values: [2.5]}\n"  // past the separation 2 sqrt((1-v)/(1+v)) of the slowest bar
    "collect:\n"
    "  p_max: probe.wall.p.max\n"
    "  contact_time: event.separation.first.t\n"
    "  rebound: body.bar.velocity_mean\n"
    "  cavitations: event.cavitation.count\n"
    "  error_bound: solver.error_bound\n";

class SweepTest : public CliTest {};

// The rigid bar of rest density 1 and length 1 against a wall (docs/materials.md, the paper's §3):
// behind the front s = sqrt((1-v)/(1+v)), p = (1/s^2 - 1)/2 = v/(1-v); the front's round
// trip at c takes 2 s; the bar leaves at -v.
TEST_F(SweepTest, PaperSceneAgainstClosedForms) {
  write_file("paper.yaml", kPaperSweep);
  const CliOutcome outcome = rigidity("sweep paper.yaml -j 2 --quiet");
  ASSERT_EQ(outcome.exit_status, 0) << outcome.err;
  const Rows rows = read_csv(dir() / "out/paper/sweep.csv");
  ASSERT_EQ(rows.size(), 10u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"case", "bodies.0.velocity", "time.end", "status", "exit_code",
                                               "message", "p_max", "contact_time", "rebound", "cavitations",
                                               "error_bound", "wall_time_s"}));
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double v = 0.1 * static_cast<double>(i);
    const auto& row = rows[i];
    EXPECT_EQ(row[0], std::to_string(i - 1));
    EXPECT_NEAR(std::stod(row[1]), v, 1e-15);
    EXPECT_EQ(row[column(rows, "status")], "ok");
    EXPECT_EQ(row[column(rows, "exit_code")], "0");
    const double s = std::sqrt((1.0 - v) / (1.0 + v));
    EXPECT_NEAR(std::stod(row[column(rows, "p_max")]), v / (1.0 - v), 1e-9 * v / (1.0 - v)) << "v = " << v;
    EXPECT_NEAR(std::stod(row[column(rows, "contact_time")]), 2.0 * s, 1e-9) << "v = " << v;
    EXPECT_NEAR(std::stod(row[column(rows, "rebound")]), -v, 1e-9) << "v = " << v;
    EXPECT_EQ(row[column(rows, "cavitations")], "0");
  }
  EXPECT_TRUE(contains(read_text(dir() / "out/paper/sweep.json"), "\"bodies.0.velocity\": 0.9"));
}

TEST_F(SweepTest, SameTableWhateverTheThreads) {
  write_file("paper.yaml", kPaperSweep);
  ASSERT_EQ(rigidity("sweep paper.yaml -j 1 --out one --quiet").exit_status, 0);
  ASSERT_EQ(rigidity("sweep paper.yaml -j 2 --out two --quiet").exit_status, 0);
  ASSERT_EQ(rigidity("sweep paper.yaml -j 5 --out five --quiet").exit_status, 0);
  const Rows one = without_wall_time(read_csv(dir() / "one/sweep.csv"));
  EXPECT_EQ(one, without_wall_time(read_csv(dir() / "two/sweep.csv")));
  EXPECT_EQ(one, without_wall_time(read_csv(dir() / "five/sweep.csv")));
}

TEST_F(SweepTest, InvalidAndInadmissibleCasesAreRows) {
  write_file("bad.yaml",
             "parameters:\n"
             "  bodies.0.velocity: {values: [0.5, 1.5]}\n"
             "collect: {p_max: probe.wall.p.max}\n");
  const CliOutcome outcome = rigidity("sweep bad.yaml -j 2");
  ASSERT_EQ(outcome.exit_status, 0) << outcome.err;
  EXPECT_TRUE(contains(outcome.out, "2 cases (2 run, 0 already in the table, 1 not ok)"));
  const Rows rows = read_csv(dir() / "out/bad/sweep.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1][2], "ok");
  EXPECT_EQ(rows[2][2], "invalid");
  EXPECT_EQ(rows[2][3], "2");
  EXPECT_TRUE(contains(rows[2][4], "error:"));
  EXPECT_TRUE(contains(rows[2][4], "velocity"));
  EXPECT_EQ(rows[2][5], "");  // undefined: an empty cell, never NaN
}

// wave_speed is a parameter of hooke, not of rigid: dropped for the rigid cases, with a note.
TEST_F(SweepTest, KeysTheModelLacksAreIgnored) {
  write_file("models.yaml",
             "parameters:\n"
             "  bodies.0.velocity: {values: [0.3]}\n"
             "  materials.rigid_steel.model: {values: [rigid, hooke]}\n"
             "  materials.rigid_steel.wave_speed: {values: [0.5]}\n"
             "collect: {p_max: probe.wall.p.max}\n");
  const CliOutcome outcome = rigidity("sweep models.yaml -j 2");
  ASSERT_EQ(outcome.exit_status, 0) << outcome.err;
  const Rows rows = read_csv(dir() / "out/models/sweep.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1][column(rows, "status")], "ok");
  EXPECT_TRUE(contains(rows[1][column(rows, "message")], "materials.rigid_steel.wave_speed ignored"));
  EXPECT_NEAR(std::stod(rows[1][column(rows, "p_max")]), 0.3 / 0.7, 1e-9);
  EXPECT_EQ(rows[2][column(rows, "status")], "ok");
  EXPECT_EQ(rows[2][column(rows, "message")], "");
  EXPECT_NE(rows[2][column(rows, "p_max")], rows[1][column(rows, "p_max")]);
}

TEST_F(SweepTest, ResumesWhereItStopped) {
  write_file("paper.yaml", kPaperSweep);
  ASSERT_EQ(rigidity("sweep paper.yaml -j 2 --quiet").exit_status, 0);
  const fs::path csv = dir() / "out/paper/sweep.csv";
  const std::string full = read_text(csv);
  // Keep the header and cases 0, 1 and 2, and a row cut short as a kill would leave it.
  std::istringstream in(full);
  std::string kept, line;
  for (int i = 0; i < 4 && std::getline(in, line); ++i) kept += line + "\n";
  std::getline(in, line);
  kept += line.substr(0, line.size() / 2);
  std::ofstream(csv, std::ios::trunc) << kept;

  const CliOutcome outcome = rigidity("sweep paper.yaml -j 2");
  ASSERT_EQ(outcome.exit_status, 0) << outcome.err;
  EXPECT_TRUE(contains(outcome.out, "9 cases (6 run, 3 already in the table"));
  const std::string resumed = read_text(csv);
  EXPECT_EQ(resumed.substr(0, kept.rfind('\n') + 1), kept.substr(0, kept.rfind('\n') + 1));  // wall times kept too
  EXPECT_EQ(without_wall_time(read_csv(csv)), without_wall_time(read_csv(dir() / "out/paper/sweep.csv")));
  std::ofstream(dir() / "full.csv") << full;
  EXPECT_EQ(without_wall_time(read_csv(csv)), without_wall_time(read_csv(dir() / "full.csv")));
}

TEST_F(SweepTest, BadSweepFileNamesTheKey) {
  write_file("typo.yaml",
             "parameters:\n"
             "  bodies.0.velocity: {values: [0.5]}\n"
             "colect: {p_max: probe.wall.p.max}\n");
  CliOutcome outcome = rigidity("sweep typo.yaml");
  EXPECT_EQ(outcome.exit_status, 2);
  EXPECT_TRUE(contains(outcome.err, "typo.yaml:3:1: error: key 'colect': unknown key; did you mean 'collect'?"));
  EXPECT_FALSE(fs::exists(dir() / "out"));

  write_file("type.yaml", "parameters:\n  bodies.0.velocity: {linspace: [0.1, 0.9, many]}\n");
  outcome = rigidity("sweep type.yaml");
  EXPECT_EQ(outcome.exit_status, 2);
  EXPECT_TRUE(contains(outcome.err, "type.yaml:2:"));
  EXPECT_TRUE(contains(outcome.err, "parameters.bodies.0.velocity.linspace"));

  write_file("figure.yaml", "parameters:\n  bodies.0.velocity: {values: [0.5]}\ncollect: {p: probe.wall.p.maximum}\n");
  outcome = rigidity("sweep figure.yaml");
  EXPECT_EQ(outcome.exit_status, 2);
  EXPECT_TRUE(contains(outcome.err, "figure.yaml:3:14: error: key 'collect.p'"));

  // stats and conservation have fixed fields: a misspelt one is refused, not an empty column.
  write_file("stats.yaml",
             "parameters:\n  bodies.0.velocity: {values: [0.5]}\ncollect: {time: stats.sampling_time, "
             "e: conservation.energy_dissipated}\n");
  outcome = rigidity("sweep stats.yaml");
  EXPECT_EQ(outcome.exit_status, 2);
  EXPECT_TRUE(contains(outcome.err, "key 'collect.time'"));
  EXPECT_TRUE(contains(outcome.err, "did you mean 'sampling_time_s'?"));
  write_file("books.yaml",
             "parameters:\n  bodies.0.velocity: {values: [0.5]}\ncollect: {e: conservation.energy_lost}\n");
  outcome = rigidity("sweep books.yaml");
  EXPECT_EQ(outcome.exit_status, 2);
  EXPECT_TRUE(contains(outcome.err, "unknown conservation field 'energy_lost'"));
  EXPECT_FALSE(fs::exists(dir() / "out"));
}

// A collect path that names nothing in the scene (a probe, a probe's quantity, a body, an
// event kind, a solver number of its method) would run every case for an empty column:
// refused before the first case, at the file, line and key of the path.
TEST_F(SweepTest, CollectNamesAreCheckedAgainstTheSceneBeforeAnyCase) {
  struct Typo {
    std::string path, message;
  };
  const std::vector<Typo> typos = {
      {"solver.error_bund", "'solver.error_bund': no solver number 'error_bund'; did you mean 'error_bound'?"},
      {"probe.wal.p.max",
       "'probe.wal.p.max': no probe 'wal'; did you mean 'wall'? (the default scene has: wall, rear)"},
      {"probe.rear.p.max", "'probe.rear.p.max': probe 'rear' does not record 'p'"},
      {"body.barr.velocity_mean", "'body.barr.velocity_mean': no body 'barr'; did you mean 'bar'?"},
      {"event.separaton.first.t", "'event.separaton.first.t': no event kind 'separaton'; did you mean 'separation'?"},
  };
  for (const Typo& typo : typos) {
    SCOPED_TRACE(typo.path);
    write_file("typo.yaml",
               "parameters:\n  bodies.0.velocity: {values: [0.5]}\ncollect:\n  ok: probe.wall.p.max\n"
               "  figure: " +
                   typo.path + "\n");
    const CliOutcome outcome = rigidity("sweep typo.yaml --quiet");
    EXPECT_EQ(outcome.exit_status, 2);
    EXPECT_TRUE(contains(outcome.err, "typo.yaml:5:11: error: key 'collect.figure': " + typo.message));
    EXPECT_FALSE(fs::exists(dir() / "out"));
  }

  // The finite-volume scheme's numbers are its own: a characteristics one is refused there,
  // and accepted when a parameter sweeps the method.
  write_file("fv.yaml",
             "name: fv\nmaterials: {m: {model: rigid}}\nbodies: [{name: bar, material: m, position: 0, length: 1, "
             "velocity: 0.5}]\nboundaries: {right: {type: wall}}\nsolver: {method: finite_volume, cells: 20}\n"
             "time: {end: 0.5}\n");
  write_file("fv_sweep.yaml",
             "scene: fv.yaml\nparameters:\n  bodies.0.velocity: {values: [0.5]}\n"
             "collect: {bound: solver.error_bound, steps: solver.steps}\n");
  EXPECT_THROW(static_cast<void>(load_sweep_file((dir() / "fv_sweep.yaml").string())), InputError);
  write_file("both_sweep.yaml",
             "scene: fv.yaml\nparameters:\n  solver.method: {values: [finite_volume, characteristics]}\n"
             "collect: {bound: solver.error_bound, steps: solver.steps}\n");
  EXPECT_NO_THROW(static_cast<void>(load_sweep_file((dir() / "both_sweep.yaml").string())));
}

// The check knows every number each solver reports in summary.json's "solver" block: a
// sweep may collect each of them.
TEST_F(SweepTest, EverySolverNumberMayBeCollected) {
  for (const std::string method : {"characteristics", "finite_volume"}) {
    SCOPED_TRACE(method);
    const std::string scene =
        "name: s\nmaterials: {m: {model: hooke, wave_speed: 0.5}}\nbodies: [{name: bar, material: "
        "m, position: 0, length: 1, velocity: 0.3}]\nboundaries: {right: {type: wall}}\n"
        "solver: {method: " +
        method + (method == "finite_volume" ? ", cells: 20" : ", resolution: auto") + "}\ntime: {end: 0.5}\n";
    write_file("scene.yaml", scene);
    const RunResult result = solve(load_scene_file((dir() / "scene.yaml").string()));
    ASSERT_FALSE(result.solver_numbers.empty());
    std::string collect;
    for (const auto& [name, value] : result.solver_numbers) collect += "  " + name + ": solver." + name + "\n";
    write_file("sweep.yaml",
               "scene: scene.yaml\nparameters:\n  bodies.0.velocity: {values: [0.3]}\ncollect:\n" + collect);
    EXPECT_NO_THROW(static_cast<void>(load_sweep_file((dir() / "sweep.yaml").string())));
  }
}

// examples/sweeps/paper_velocity.yaml: every row has its contact time (the run lasts past
// the separation at 2 sqrt((1-v)/(1+v)) of the slowest bar), and the velocities are written
// as the grid's decimals.
TEST_F(SweepTest, PaperVelocityExampleFillsEveryRow) {
  const CliOutcome outcome =
      rigidity("sweep " + shell_quote(std::string(RIGIDITY_SOURCE_DIR) + "/examples/sweeps/paper_velocity.yaml") +
               " --out table -j 2 --quiet");
  ASSERT_EQ(outcome.exit_status, 0) << outcome.err;
  const Rows rows = read_csv(dir() / "table/sweep.csv");
  ASSERT_EQ(rows.size(), 20u);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double v = 0.05 * static_cast<double>(i);
    char written[16];
    std::snprintf(written, sizeof written, "%g", v);
    EXPECT_EQ(rows[i][column(rows, "bodies.0.velocity")], written);
    const std::string& contact = rows[i][column(rows, "contact_time")];
    ASSERT_FALSE(contact.empty()) << "v = " << v;
    EXPECT_NEAR(std::stod(contact), 2.0 * std::sqrt((1.0 - v) / (1.0 + v)), 1e-9) << "v = " << v;
  }
}

TEST_F(SweepTest, GridValuesAreTheirDecimals) {
  write_file("grid.yaml",
             "parameters:\n"
             "  bodies.0.velocity: {linspace: [0.05, 0.95, 19]}\n"
             "  bodies.0.length: {logspace: [1e-6, 1e-2, 5]}\n");
  const Sweep grid = load_sweep_file((dir() / "grid.yaml").string());
  ASSERT_EQ(grid.cases.size(), 95u);
  const std::vector<std::string> lengths = {"1e-06", "1e-05", "1e-04", "0.001", "0.01"};
  for (std::size_t i = 0; i < 19; ++i)
    for (std::size_t j = 0; j < 5; ++j) {
      char velocity[16];
      std::snprintf(velocity, sizeof velocity, "%g", 0.05 * static_cast<double>(i + 1));
      EXPECT_EQ(grid.cases[5 * i + j], (std::vector<std::string>{velocity, lengths[j]}));
    }
}

// ---- the cases a sweep file lays out (library API) ------------------------------------

TEST_F(SweepTest, GridsZipAndSamples) {
  write_file("grid.yaml",
             "parameters:\n"
             "  bodies.0.velocity: {values: [0.2, 0.4]}\n"
             "  bodies.0.length: {logspace: [1, 100, 3]}\n"
             "  time.end: {linspace: [1, 2, 3]}\n"
             "zip: [[bodies.0.length, time.end]]\n");
  const Sweep grid = load_sweep_file((dir() / "grid.yaml").string());
  ASSERT_EQ(grid.cases.size(), 6u);  // 2 velocities x 3 zipped (length, end) pairs
  EXPECT_EQ(grid.cases[0], (std::vector<std::string>{"0.2", "1", "1"}));
  EXPECT_EQ(grid.cases[1], (std::vector<std::string>{"0.2", "10", "1.5"}));
  EXPECT_EQ(grid.cases[5], (std::vector<std::string>{"0.4", "100", "2"}));

  write_file("latin.yaml",
             "parameters:\n"
             "  bodies.0.velocity: {range: [0.1, 0.9]}\n"
             "  bodies.0.length: {range: [1, 2]}\n"
             "sample: {n: 8, seed: 7, method: latin}\n");
  const Sweep latin = load_sweep_file((dir() / "latin.yaml").string());
  ASSERT_EQ(latin.cases.size(), 8u);
  std::vector<int> strata(8, 0);
  for (const auto& c : latin.cases) {
    const double v = std::stod(c[0]);
    ASSERT_GE(v, 0.1);
    ASSERT_LT(v, 0.9);
    ++strata[static_cast<std::size_t>((v - 0.1) / 0.1)];
  }
  EXPECT_EQ(strata, std::vector<int>(8, 1));  // one sample in each eighth of the range
  EXPECT_EQ(load_sweep_file((dir() / "latin.yaml").string()).cases, latin.cases);  // seeded

  write_file("log.yaml",
             "parameters:\n  bodies.0.length: {range: [0.01, 100]}\nsample: {n: 50, method: log_uniform}\n");
  for (const auto& c : load_sweep_file((dir() / "log.yaml").string()).cases) {
    EXPECT_GE(std::stod(c[0]), 0.01);
    EXPECT_LE(std::stod(c[0]), 100.0);
  }

  write_file("short.yaml",
             "parameters:\n  bodies.0.velocity: {values: [0.2, 0.4]}\n  time.end: {values: [1]}\n"
             "zip: [[bodies.0.velocity, time.end]]\n");
  EXPECT_THROW(static_cast<void>(load_sweep_file((dir() / "short.yaml").string())), InputError);
}

// The executable links no MPI library: the MPI sweep is the module librigidity_mpi.so, loaded
// only under mpirun (cli/mpi_sweep.hpp).
TEST(SweepMpi, ExecutableLinksNoMpiLibrary) {
  FILE* pipe = ::popen(("ldd " + shell_quote(RIGIDITY_EXECUTABLE) + " 2>&1").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string libraries;
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) libraries += buffer.data();
  ASSERT_EQ(::pclose(pipe), 0) << libraries;
  EXPECT_TRUE(contains(libraries, "librigidity")) << "ldd lists the executable's libraries";
  EXPECT_EQ(libraries.find("libmpi"), std::string::npos) << libraries;
}

}  // namespace
}  // namespace rigidity::testing
