// rigidity compare, end to end: materials.csv, the long-form curves, the charts, the
// markdown summary, and the wall impacts against the reference values of docs/materials.md and the
// jump conditions of labels and momentum.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "rigidity/registry.hpp"
#include "run_cli.hpp"

namespace rigidity::testing {
namespace {

const std::string kBuiltIns = "rigid,hooke,rigid_fluid,constant_sound_speed";

/// A CSV file as rows of named cells (no quoted fields: compare writes none for these materials).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields(1);
  for (const char c : line) {
    if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

Csv read_csv(const fs::path& path) {
  Csv csv;
  std::istringstream text(read_text(path));
  std::string line;
  if (!std::getline(text, line)) return csv;
  csv.header = split(line);
  while (std::getline(text, line)) {
    const std::vector<std::string> fields = split(line);
    EXPECT_EQ(fields.size(), csv.header.size()) << path << ": " << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < fields.size() && i < csv.header.size(); ++i) row[csv.header[i]] = fields[i];
    csv.rows.push_back(std::move(row));
  }
  return csv;
}

/// The cell as a number; fails the test (and returns NaN) if it is not one, or not finite.
double number(const std::map<std::string, std::string>& row, const std::string& column) {
  const auto it = row.find(column);
  if (it == row.end()) {
    ADD_FAILURE() << "no column " << column;
    return std::nan("");
  }
  char* end = nullptr;
  const double value = std::strtod(it->second.c_str(), &end);
  const bool whole = !it->second.empty() && end == it->second.c_str() + it->second.size();
  EXPECT_TRUE(whole && std::isfinite(value)) << column << " = '" << it->second << "'";
  return whole ? value : std::nan("");
}

const std::map<std::string, std::string>& row_of(const Csv& csv, const std::string& material) {
  for (const auto& row : csv.rows)
    if (row.at("material") == material) return row;
  ADD_FAILURE() << "no row for " << material;
  static const std::map<std::string, std::string> kNone;
  return kNone;
}

/// The impact.csv row of `material` at speed v.
const std::map<std::string, std::string>* impact_row(const Csv& csv, const std::string& material, double v) {
  for (const auto& row : csv.rows)
    if (row.at("material") == material && std::strtod(row.at("v").c_str(), nullptr) == v) return &row;
  return nullptr;
}

// ---- materials.csv ----------------------------------------------------------------------

TEST_F(CliTest, CompareWritesOneRowPerMaterial) {
  const CliOutcome r = rigidity("compare --materials " + kBuiltIns + " --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const Csv csv = read_csv(dir() / "cmp" / "materials.csv");
  EXPECT_EQ(csv.header, (std::vector<std::string>{"material", "parameters", "rest_density", "cs_unstrained",
                                                  "max_pressure", "max_tension", "linearly_degenerate", "impact_v",
                                                  "impact_s", "impact_p", "impact_front_speed", "crush_speed"}));
  ASSERT_EQ(csv.rows.size(), 4u);
  std::set<std::string> names;
  for (const auto& row : csv.rows) names.insert(row.at("material"));
  EXPECT_EQ(names, (std::set<std::string>{"rigid", "hooke", "rigid_fluid", "constant_sound_speed"}));

  const auto& rigid = row_of(csv, "rigid");
  EXPECT_EQ(rigid.at("parameters"), "");
  EXPECT_EQ(number(rigid, "rest_density"), 1.0);
  EXPECT_EQ(number(rigid, "cs_unstrained"), 1.0);
  EXPECT_EQ(rigid.at("max_pressure"), "inf");  // unbounded: written as inf, never as NaN
  EXPECT_EQ(number(rigid, "max_tension"), -0.5);
  EXPECT_EQ(rigid.at("linearly_degenerate"), "true");
  EXPECT_EQ(rigid.at("crush_speed"), "");  // no impact speed crushes it

  // hooke's required wave_speed takes the midpoint of (0, 1]: V = 0.5, the reference of docs/materials.md.
  const auto& hooke = row_of(csv, "hooke");
  EXPECT_EQ(hooke.at("parameters"), "wave_speed=0.5");
  EXPECT_EQ(number(hooke, "cs_unstrained"), 0.5);
  EXPECT_NEAR(number(hooke, "max_pressure"), 1.0 / 3.0, 1e-15);  // ρ00 V²/(1 − V²)
  EXPECT_NEAR(number(hooke, "max_tension"), -1.0 / 3.0, 1e-15);  // −ρ00 V/(1 + V)
  EXPECT_NEAR(number(hooke, "crush_speed"), 0.5, 1e-15);         // an impact at v >= V crushes it
  // At the default impact speed 0.5 = V: no classical solution, the cells are empty.
  EXPECT_EQ(number(hooke, "impact_v"), 0.5);
  for (const char* column : {"impact_s", "impact_p", "impact_front_speed"}) EXPECT_EQ(hooke.at(column), "") << column;

  const auto& fluid = row_of(csv, "rigid_fluid");
  EXPECT_EQ(number(fluid, "max_tension"), 0.0);

  const auto& css = row_of(csv, "constant_sound_speed");
  EXPECT_EQ(css.at("parameters"), "sound_speed=0.5");
  EXPECT_EQ(css.at("linearly_degenerate"), "false");
  EXPECT_NEAR(number(css, "max_tension"), -0.2, 1e-15);  // −ρ00 V²/(1 + V²)
}

TEST_F(CliTest, CompareMatchesTheReferenceWallImpacts) {
  // docs/materials.md: rigid at v = 0.6 and 0.8, hooke (V = 0.5) at v = 0.2.
  struct Reference {
    std::string material;
    double v, s, p, front_speed;
  };
  const Reference references[] = {{"rigid", 0.6, 0.5, 1.5, 1.0},
                                  {"rigid", 0.8, 1.0 / 3.0, 4.0, 1.0},
                                  {"hooke", 0.2, 0.6123724357, 0.1111111111, 0.5}};
  for (const Reference& ref : references) {
    SCOPED_TRACE(ref.material + " at v = " + std::to_string(ref.v));
    const CliOutcome r =
        rigidity("compare --materials " + ref.material + " --impact-speed " + std::to_string(ref.v) + " --out cmp");
    ASSERT_EQ(r.exit_status, 0) << r.err;
    const Csv csv = read_csv(dir() / "cmp" / "materials.csv");
    ASSERT_EQ(csv.rows.size(), 1u);
    const auto& row = csv.rows.front();
    EXPECT_NEAR(number(row, "impact_s"), ref.s, 1e-9);
    EXPECT_NEAR(number(row, "impact_p"), ref.p, 1e-9);
    EXPECT_NEAR(number(row, "impact_front_speed"), ref.front_speed, 1e-9);
  }

  // The same on the default grid of impact.csv, which holds 0.2 and 0.6.
  const CliOutcome r = rigidity("compare --materials " + kBuiltIns + " --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const Csv impacts = read_csv(dir() / "cmp" / "impact.csv");
  const auto* rigid = impact_row(impacts, "rigid", 0.6);
  const auto* hooke = impact_row(impacts, "hooke", 0.2);
  ASSERT_TRUE(rigid != nullptr && hooke != nullptr);
  EXPECT_NEAR(number(*rigid, "s"), 0.5, 1e-9);
  EXPECT_NEAR(number(*rigid, "p"), 1.5, 1e-9);
  EXPECT_NEAR(number(*rigid, "front_speed"), 1.0, 1e-9);
  EXPECT_NEAR(number(*hooke, "s"), 0.6123724357, 1e-9);
  EXPECT_NEAR(number(*hooke, "p"), 0.1111111111, 1e-9);
  EXPECT_NEAR(number(*hooke, "front_speed"), 0.5, 1e-9);
}

// ---- the curves ---------------------------------------------------------------------------

TEST_F(CliTest, CompareImpactsAreNanFreeAndObeyTheJumpConditions) {
  const CliOutcome r = rigidity("compare --materials " + kBuiltIns + " --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const Csv csv = read_csv(dir() / "cmp" / "impact.csv");
  EXPECT_EQ(csv.header, (std::vector<std::string>{"material", "v", "s", "p", "front_speed"}));
  EXPECT_EQ(read_text(dir() / "cmp" / "impact.csv").find("nan"), std::string::npos);
  std::map<std::string, int> rows;
  for (const auto& row : csv.rows) {
    const std::string& material = row.at("material");
    ++rows[material];
    const double v = number(row, "v"), s = number(row, "s"), p = number(row, "p"), u = number(row, "front_speed");
    SCOPED_TRACE(material + " at v = " + row.at("v"));
    EXPECT_TRUE(v > 0.0 && v < 1.0);
    EXPECT_TRUE(s > 0.0 && s < 1.0);
    EXPECT_GT(p, 0.0);
    EXPECT_TRUE(u > 0.0 && u <= 1.0);
    // Labels: in the bar's frame the front sweeps u unstrained labels per unit time into
    // material moving at −v with γ/s labels per unit length: u = γ (u − v)/s, u = γ v/(γ − s).
    const double gamma = 1.0 / std::sqrt((1.0 - v) * (1.0 + v));
    EXPECT_NEAR(u, gamma * v / (gamma - s), 1e-9 * u);
    // Momentum, in the wall's frame (where the solver's shock conditions hold): the front at lab
    // speed λ = (v − u)/(1 − u v) stops a flux γ²v of momentum density: p = γ² v (v − λ) = v u/(1 − u v).
    EXPECT_NEAR(p, v * u / (1.0 - u * v), 1e-9 * p);
    // Linearly degenerate: the front runs at the sound speed of the unstrained bar.
    if (material == "rigid" || material == "rigid_fluid") {
      EXPECT_NEAR(u, 1.0, 1e-12);
    }
    if (material == "hooke") {
      EXPECT_NEAR(u, 0.5, 1e-12);
      EXPECT_LT(v, 0.5);  // beyond the crush speed nothing is written
    }
  }
  EXPECT_EQ(rows["rigid"], 99);
  EXPECT_EQ(rows["rigid_fluid"], 99);
  EXPECT_EQ(rows["constant_sound_speed"], 99);
  EXPECT_EQ(rows["hooke"], 49);  // v = 0.01 ... 0.49
}

// The compressions from rest, through a shock and through a smooth wave, against closed forms
// written here: for `rigid` every wave is a jump, so the two coincide on the rigid law's
// isentrope φ = −ln s (v = (1 − s²)/(1 + s²)); for constant_sound_speed (V = 0.5, ρ00 = 1) the
// isentrope is φ = V |ln s| and the Hugoniot follows from the conservation of particles and
// momentum across a front at lab speed U into the bar at rest (energy is not conserved: an
// elastic shock dissipates): U = γ v/(γ − s) and p = w γ² v (U − v), so p γ = s (p + w γ² v²)
// with w = e + p, e = 1 + p/V²; solved for v by bisection.
TEST_F(CliTest, CompareHugoniotAndIsentropeMatchTheirClosedForms) {
  const CliOutcome r = rigidity("compare --materials rigid,constant_sound_speed --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const Csv csv = read_csv(dir() / "cmp" / "hugoniot.csv");
  EXPECT_EQ(csv.header, (std::vector<std::string>{"material", "s", "p", "v_shock", "v_smooth"}));
  std::map<std::string, int> rows;
  double widest_gap = 0.0;  // constant_sound_speed: how far the Hugoniot leaves the isentrope
  for (const auto& row : csv.rows) {
    const std::string& material = row.at("material");
    ++rows[material];
    const double s = number(row, "s"), p = number(row, "p");
    const double v_shock = number(row, "v_shock"), v_smooth = number(row, "v_smooth");
    SCOPED_TRACE(material + " at s = " + row.at("s"));
    ASSERT_TRUE(s > 0.0 && s < 1.0);
    if (material == "rigid") {
      const double v = (1.0 - s * s) / (1.0 + s * s);
      EXPECT_NEAR(v_smooth, v, 1e-12);
      EXPECT_NEAR(v_shock, v, 1e-12);
      continue;
    }
    constexpr double V = 0.5;
    EXPECT_NEAR(p, V * V / (1.0 + V * V) * (std::pow(s, -(1.0 + V * V)) - 1.0), 1e-12 * (1.0 + p));
    EXPECT_NEAR(v_smooth, std::tanh(V * std::abs(std::log(s))), 1e-12);
    const double w = 1.0 + p / (V * V) + p;
    double lo = 0.0, hi = 1.0;  // p γ − s (p + w γ² v²) falls from p (1 − s) > 0 as v grows
    for (int it = 0; it < 200; ++it) {
      const double v = 0.5 * (lo + hi), g2 = 1.0 / ((1.0 - v) * (1.0 + v));
      (p * std::sqrt(g2) - s * (p + w * g2 * v * v) > 0.0 ? lo : hi) = v;
    }
    EXPECT_NEAR(v_shock, 0.5 * (lo + hi), 1e-10);
    widest_gap = std::max(widest_gap, std::abs(v_shock - v_smooth));
  }
  EXPECT_EQ(rows["rigid"], rows["constant_sound_speed"]);
  EXPECT_GT(rows["rigid"], 100);
  EXPECT_GT(widest_gap, 0.01) << "a genuinely nonlinear law's shock is not its smooth wave";
}

TEST_F(CliTest, CompareStressStrainCurvesStayInsideEachMaterialsRange) {
  const CliOutcome r = rigidity("compare --materials " + kBuiltIns + " --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const Csv csv = read_csv(dir() / "cmp" / "stress_strain.csv");
  EXPECT_EQ(csv.header, (std::vector<std::string>{"material", "s", "p", "e", "cs"}));
  std::map<std::string, int> rows, natural;
  for (const auto& row : csv.rows) {
    const std::string& material = row.at("material");
    ++rows[material];
    const double s = number(row, "s"), p = number(row, "p"), e = number(row, "e"), cs = number(row, "cs");
    EXPECT_TRUE(cs > 0.0 && cs <= 1.0) << material << " s = " << s;
    EXPECT_GT(e + p, 0.0) << material << " s = " << s;
    if (material == "rigid") {
      EXPECT_NEAR(p, 0.5 * (1.0 / (s * s) - 1.0), 1e-12 * std::max(1.0, std::abs(p)));
    }
    if (material == "rigid_fluid") {
      EXPECT_LE(s, 1.0);  // it carries no tension: nothing beyond s = 1
    }
    if (s == 1.0) {
      ++natural[material];
      EXPECT_EQ(p, 0.0) << material;
      EXPECT_NEAR(e, 1.0, 1e-15) << material;
    }
  }
  for (const char* material : {"rigid", "hooke", "rigid_fluid", "constant_sound_speed"})
    EXPECT_EQ(natural[material], 1) << material;
  EXPECT_EQ(rows["rigid"], 401);
  EXPECT_EQ(rows["rigid_fluid"], 201);  // s = 1/50 ... 1
}

TEST_F(CliTest, CompareConstantSoundSpeedShocksHaveTheRightLimits) {
  // V = 1: the rigid law, linearly degenerate; the impacts coincide with rigid's.
  CliOutcome r = rigidity(
      "compare --materials constant_sound_speed,rigid --param constant_sound_speed.sound_speed=1 "
      "--speeds 0.1,0.5,0.9 --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  Csv csv = read_csv(dir() / "cmp" / "impact.csv");
  for (const double v : {0.1, 0.5, 0.9}) {
    const auto* fluid = impact_row(csv, "constant_sound_speed", v);
    const auto* rigid = impact_row(csv, "rigid", v);
    ASSERT_TRUE(fluid != nullptr && rigid != nullptr) << v;
    for (const char* column : {"s", "p", "front_speed"})
      EXPECT_NEAR(number(*fluid, column), number(*rigid, column), 1e-12 * number(*rigid, column)) << column;
  }
  // V = 0.5: a weak shock runs at the sound speed, a strong one faster.
  r = rigidity("compare --materials constant_sound_speed --speeds 1e-6,0.5,0.99 --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  csv = read_csv(dir() / "cmp" / "impact.csv");
  ASSERT_EQ(csv.rows.size(), 3u);
  EXPECT_NEAR(number(csv.rows[0], "front_speed"), 0.5, 1e-5);
  EXPECT_GT(number(csv.rows[1], "front_speed"), 0.5);
  EXPECT_GT(number(csv.rows[2], "front_speed"), number(csv.rows[1], "front_speed"));
  EXPECT_LT(number(csv.rows[2], "front_speed"), 1.0);
}

// ---- the summary and the charts -------------------------------------------------------------

TEST_F(CliTest, ComparePrintsAMarkdownSummary) {
  const CliOutcome r = rigidity("compare --materials " + kBuiltIns + " --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "| material | parameters |"));
  EXPECT_TRUE(contains(r.out, "|---|---|"));
  EXPECT_TRUE(contains(r.out, "| rigid | - | 1 | 1 | ∞ | -0.5 | yes | 0.57735 | 1 | 1 | - |"));
  EXPECT_TRUE(contains(r.out, "| hooke | wave_speed=0.5 | 1 | 0.5 | 0.333333 | -0.333333 | yes | crushed"));
  EXPECT_TRUE(contains(r.out, "| rigid_fluid |"));
  EXPECT_TRUE(contains(r.out, "| constant_sound_speed | sound_speed=0.5 |"));
  EXPECT_TRUE(contains(r.out, "hooke.wave_speed = 0.5: required, no default; the midpoint of (0, 1]"));
  EXPECT_TRUE(contains(r.out, "materials.csv"));
}

TEST_F(CliTest, CompareCoversEveryRegisteredMaterialByDefault) {
  const CliOutcome r = rigidity("compare --out cmp --speeds 0.5");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const Csv csv = read_csv(dir() / "cmp" / "materials.csv");
  std::set<std::string> rows;
  for (const auto& row : csv.rows) rows.insert(row.at("material"));
  for (const std::string& name : MaterialRegistry::instance().names())  // a material that cannot be set up is named
    EXPECT_TRUE(rows.count(name) == 1 || contains(r.out, "skipped " + name)) << name;
  EXPECT_EQ(rows.size(), csv.rows.size());
}

TEST_F(CliTest, CompareDrawsTheCharts) {
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot is not installed";
  const CliOutcome r = rigidity("compare --materials " + kBuiltIns + " --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  for (const char* chart : {"stress_strain", "sound_speed", "impact", "hugoniot"}) {
    EXPECT_TRUE(is_png(dir() / "cmp" / (std::string(chart) + ".png")));
    EXPECT_TRUE(fs::is_regular_file(dir() / "cmp" / (std::string(chart) + ".gp"))) << chart;
  }
  EXPECT_TRUE(r.err.empty()) << r.err;  // gnuplot had nothing to complain about
}

TEST_F(CliTest, CompareWithoutGnuplotWritesTheTablesAndWarns) {
  CliOutcome r;
  {
    const ScopedPath no_path("");
    r = rigidity("compare --materials rigid --out cmp");
  }
  EXPECT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "gnuplot not found"));
  EXPECT_TRUE(contains(r.out, "gnuplot not found"));
  for (const char* file : {"materials.csv", "stress_strain.csv", "impact.csv", "hugoniot.csv", "stress_strain.gp",
                           "impact.gp", "hugoniot.gp"})
    EXPECT_TRUE(fs::is_regular_file(dir() / "cmp" / file)) << file;
  EXPECT_FALSE(fs::exists(dir() / "cmp" / "impact.png"));
}

// ---- invalid input ------------------------------------------------------------------------

TEST_F(CliTest, CompareRejectsAnUnknownMaterialWithTheClosestMatch) {
  const CliOutcome r = rigidity("compare --materials rigid,hoke --out cmp");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "unknown material model 'hoke'"));
  EXPECT_TRUE(contains(r.err, "did you mean 'hooke'"));
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(fs::exists(dir() / "cmp"));  // nothing written
}

TEST_F(CliTest, CompareChecksParametersAndSpeeds) {
  CliOutcome r = rigidity("compare --materials hooke --param hooke.wave_sped=0.3 --out cmp");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "did you mean 'wave_speed'"));

  r = rigidity("compare --materials hooke --param hooke.wave_speed=1.5 --out cmp");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "must be in (0, 1]"));

  r = rigidity("compare --materials rigid --param hooke.wave_speed=0.3 --out cmp");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "not among the materials compared"));

  r = rigidity("compare --materials hooke --param wave_speed --out cmp");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "model.name=value"));

  for (const char* speeds : {"0,0.5", "0.5,1", "-0.2", "fast", "0.5,,0.6"}) {
    r = rigidity(std::string("compare --materials rigid --speeds ") + speeds + " --out cmp");
    EXPECT_EQ(r.exit_status, 2) << speeds;
  }
  EXPECT_EQ(rigidity("compare --impact-speed 1.2 --out cmp").exit_status, 2);
  EXPECT_FALSE(fs::exists(dir() / "cmp"));

  r = rigidity("compare --materials hooke --param hooke.wave_speed=0.3 --speeds 0.29,0.3 --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const Csv csv = read_csv(dir() / "cmp" / "materials.csv");
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_EQ(csv.rows[0].at("parameters"), "wave_speed=0.3");
  EXPECT_NEAR(number(csv.rows[0], "crush_speed"), 0.3, 1e-15);
  EXPECT_EQ(read_csv(dir() / "cmp" / "impact.csv").rows.size(), 1u);  // 0.3 crushes it
  EXPECT_FALSE(contains(r.out, "required, no default"));              // given, not chosen
}

TEST_F(CliTest, CompareTakesTheNamedMaterialsOfASceneFile) {
  // Two parameter sets of one model, under the scene's names. A Hooke front runs at V into
  // the bar: behind it s* = γ (V − v)/V (docs/materials.md with the paper's argument of §3).
  write_file("two_hookes.yaml",
             "name: two_hookes\n"
             "materials:\n"
             "  soft: {model: hooke, wave_speed: 0.5}\n"
             "  stiff: {model: hooke, wave_speed: 0.9, rest_density: 2}\n"
             "bodies: [{name: a, material: soft, length: 1}, {name: b, material: stiff, position: 1, length: 1}]\n"
             "time: {end: 1}\n");
  CliOutcome r = rigidity("compare --scene two_hookes.yaml --speeds 0.3 --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const Csv materials = read_csv(dir() / "cmp" / "materials.csv");
  ASSERT_EQ(materials.rows.size(), 2u);
  EXPECT_EQ(materials.rows[0].at("material"), "soft");
  EXPECT_EQ(materials.rows[0].at("parameters"), "model=hooke;wave_speed=0.5");
  EXPECT_EQ(materials.rows[1].at("material"), "stiff");
  EXPECT_EQ(materials.rows[1].at("parameters"), "model=hooke;wave_speed=0.9");
  EXPECT_NEAR(number(materials.rows[1], "crush_speed"), 0.9, 1e-12);
  const Csv impact = read_csv(dir() / "cmp" / "impact.csv");
  ASSERT_EQ(impact.rows.size(), 2u);
  const double gamma = 1.0 / std::sqrt(1.0 - 0.09);
  for (const auto& row : impact.rows) {
    const double V = row.at("material") == "soft" ? 0.5 : 0.9;
    EXPECT_NEAR(number(row, "s"), gamma * (V - 0.3) / V, 1e-12) << row.at("material");
  }
  // --materials picks among the scene's names; a name it does not declare, or --param
  // beside --scene, is invalid input.
  r = rigidity("compare --scene two_hookes.yaml --materials stiff --out cmp2");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_EQ(read_csv(dir() / "cmp2" / "materials.csv").rows.size(), 1u);
  r = rigidity("compare --scene two_hookes.yaml --materials stif --out cmp3");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "did you mean 'stiff'")) << r.err;
  EXPECT_EQ(rigidity("compare --scene two_hookes.yaml --param hooke.wave_speed=0.3 --out cmp3").exit_status, 2);
  write_file("broken.yaml", "name: broken\nmaterials: {m: {model: hooke}}\n");
  r = rigidity("compare --scene broken.yaml --out cmp3");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_TRUE(contains(r.err, "broken.yaml:")) << r.err;
  EXPECT_FALSE(fs::exists(dir() / "cmp3"));
}

TEST_F(CliTest, CompareOfAnSiSceneTakesAndPrintsSi) {
  // Steel as a Hooke material (rho00 = 7850 kg/m^3, V = 5100 m/s): speeds in m/s, the tables
  // in m/s and Pa. Behind a Hooke front s* = γ (V − v)/V, and the closed form of the wall
  // pressure at 1000 m/s is 4.0035e10 Pa.
  write_file("steel.yaml",
             "name: steel\nunits: si\nmaterials: {steel: {model: hooke, rest_density: 7850, wave_speed: 5100}}\n"
             "bodies: [{name: bar, material: steel, length: 1}]\ntime: {end: 1e-3}\n");
  const CliOutcome r = rigidity("compare --scene steel.yaml --speeds 100,1000 --impact-speed 1000 --out cmp");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const double c = 299792458.0;
  const Csv materials = read_csv(dir() / "cmp" / "materials.csv");
  ASSERT_EQ(materials.rows.size(), 1u);
  EXPECT_EQ(materials.rows[0].at("parameters"), "model=hooke;wave_speed=5100");
  EXPECT_NEAR(number(materials.rows[0], "cs_unstrained"), 5100.0, 1e-9);
  EXPECT_EQ(materials.rows[0].at("impact_v"), "1000");
  EXPECT_NEAR(number(materials.rows[0], "impact_p"), 4.0035e10, 1e6);
  EXPECT_NEAR(number(materials.rows[0], "crush_speed"), 5100.0, 1e-6);
  const Csv impact = read_csv(dir() / "cmp" / "impact.csv");
  ASSERT_EQ(impact.rows.size(), 2u);
  EXPECT_EQ(impact.rows[0].at("v"), "100");
  EXPECT_EQ(impact.rows[1].at("v"), "1000");
  for (const auto& row : impact.rows) {
    const double v = number(row, "v");
    EXPECT_NEAR(number(row, "s"), (5100.0 - v) / 5100.0 / std::sqrt(1.0 - (v / c) * (v / c)), 1e-12);
  }
  EXPECT_TRUE(contains(r.out, "SI units")) << r.out;
  // A speed of c or more is refused in the scene's units.
  const CliOutcome fast = rigidity("compare --scene steel.yaml --speeds 0.5,3e8 --out cmp2");
  EXPECT_EQ(fast.exit_status, 2);
  EXPECT_TRUE(contains(fast.err, "m/s")) << fast.err;
}

TEST_F(CliTest, CompareHasHelp) {
  const CliOutcome r = rigidity("compare --help");
  EXPECT_EQ(r.exit_status, 0);
  EXPECT_TRUE(contains(r.out, "usage: rigidity compare"));
  EXPECT_TRUE(contains(r.out, "--speeds"));
  EXPECT_TRUE(contains(rigidity("--help").out, "compare"));
}

}  // namespace
}  // namespace rigidity::testing
