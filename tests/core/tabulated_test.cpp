// The `tabulated` material (materials/tabulated.cpp): a law read from a CSV table reproduces the
// law the table was made from, converging as the rows get closer; an e(s) table is the same
// material as the p(s) table of the same law; every defect of a table is an error naming its
// file, line and row. The registry-wide contract suite (material_contract_test.cpp) checks it
// against the material contract on the tables in tests/data/tables/.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "material_test_support.hpp"
#include "rigidity/registry.hpp"

namespace rigidity::testing {
namespace {

namespace fs = std::filesystem;

/// The constant_sound_speed law (docs/materials.md), V = 0.5, in units of ρ00.
constexpr double kV2 = 0.25;
constexpr double kK = 1.0 + kV2;
double law_pressure(double s) { return kV2 / kK * (std::pow(s, -kK) - 1.0); }
double law_energy(double s) { return (std::pow(s, -kK) + kV2) / kK; }

/// A CSV file in the test's temporary directory, removed with the object.
class TableFile {
 public:
  explicit TableFile(const std::string& text) {
    // Unique across the processes ctest runs in parallel, as well as within one.
    static int count = 0;
    path_ = fs::path(::testing::TempDir()) /
            ("rigidity_tabulated_" + std::to_string(::getpid()) + "_" + std::to_string(++count) + ".csv");
    std::ofstream(path_) << text;
  }
  ~TableFile() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  TableFile(const TableFile&) = delete;
  TableFile& operator=(const TableFile&) = delete;
  [[nodiscard]] std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

/// "s,<column>" and `intervals` + 1 rows ln-spaced over [lo, hi], s = 1 exactly among them.
std::string table_text(char column, double lo, double hi, int intervals, const std::function<double(double)>& value) {
  std::ostringstream os;
  os.precision(17);
  os << "s," << column << "\n";
  const double a = std::log(lo);
  const double b = std::log(hi);
  for (int i = 0; i <= intervals; ++i) {
    double t = a + (b - a) * i / intervals;
    if (std::abs(t) < 1e-12) t = 0.0;
    const double s = std::exp(t);
    os << s << "," << value(s) << "\n";
  }
  return os.str();
}

std::shared_ptr<const Material> tabulated(const std::string& path, double rest_density = 1.0,
                                          const std::string& directory = "") {
  ParameterValues values;
  values.set("rest_density", rest_density);
  values.set("table", path);
  values.set_directory(directory);
  return build_material("tabulated", values);
}

/// The message a table is refused with ("" if accepted).
std::string refusal(const std::string& text) {
  const TableFile file(text);
  try {
    static_cast<void>(tabulated(file.path()));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Largest errors, over s in [from, to], of a table of the law with `intervals` + 1 rows
/// spanning s in [0.1, 10] (ln s: ±2.3).
struct Errors {
  double pressure = 0.0;     ///< |p − p_law| / (|p_law| + ρ00 V²), between rows
  double energy = 0.0;       ///< |e − e_law| / e_law
  double sound_speed = 0.0;  ///< |c_s − V| / V
  double psi = 0.0;          ///< |Ψ − Ψ_law|
};

Errors errors_of(int intervals, double from, double to) {
  const TableFile file(table_text('p', 0.1, 10.0, intervals, law_pressure));
  const auto m = tabulated(file.path());
  Errors out;
  for (int i = 0; i <= 400; ++i) {
    const Stretch s = Stretch::from_log(std::log(from) + (std::log(to) - std::log(from)) * i / 400.0);
    const double p = law_pressure(s.value());
    out.pressure = std::max(out.pressure, std::abs(m->pressure(s) - p) / (std::abs(p) + kV2));
    out.energy = std::max(out.energy, std::abs(m->energy_density(s) - law_energy(s.value())) / law_energy(s.value()));
    out.sound_speed = std::max(out.sound_speed, std::abs(m->sound_speed(s) - 0.5) / 0.5);
    out.psi = std::max(out.psi, std::abs(m->riemann_psi(s) - (-0.5 * s.log())));
  }
  return out;
}

TEST(Tabulated, ReproducesTheLawOfItsTableAndConvergesAsRowsGetCloser) {
  // Steffen's slopes are second order in the row spacing h inside the table and first order at
  // its two ends (GSL takes the end secants). Measured, rows from 41 to 81 (h = 0.115 to 0.058):
  // inside, s in [0.3, 3.3], p ~5e-5 -> 6e-6 (third order), c_s ~2e-3 -> 4e-4 (second), W ~1e-6 ->
  // 8e-8 and Psi ~1e-5 -> 1e-6; over the whole table c_s ~4e-2 -> 2e-2 (first order, at the ends).
  const Errors inner_coarse = errors_of(40, 0.3, 3.3);
  const Errors inner_fine = errors_of(80, 0.3, 3.3);
  const Errors whole_coarse = errors_of(40, 0.1, 10.0);
  const Errors whole_fine = errors_of(80, 0.1, 10.0);
  EXPECT_LT(inner_fine.pressure, 1e-5);
  EXPECT_LT(inner_fine.energy, 2e-7);
  EXPECT_LT(inner_fine.sound_speed, 6e-4);
  EXPECT_LT(inner_fine.psi, 2e-6);
  EXPECT_LT(whole_fine.sound_speed, 2.5e-2);
  EXPECT_LT(whole_fine.energy, 5e-6);
  // Observed orders (error ratios for rows twice as close): 3 for p and 2 for c_s inside, 1 at the ends.
  EXPECT_GT(inner_coarse.pressure / inner_fine.pressure, 6.0);
  EXPECT_GT(inner_coarse.sound_speed / inner_fine.sound_speed, 3.5);
  EXPECT_GT(whole_coarse.sound_speed / whole_fine.sound_speed, 1.8);
}

TEST(Tabulated, PressureIsTheTableAtItsRowsAndRestDensityScalesIt) {
  const std::string text = table_text('p', 0.01, 100.0, 40, law_pressure);
  const TableFile file(text);
  const auto m = tabulated(file.path(), 2.5);
  std::istringstream rows(text);
  std::string line;
  std::getline(rows, line);  // header
  while (std::getline(rows, line)) {
    const double s = std::stod(line.substr(0, line.find(',')));
    const double p = std::stod(line.substr(line.find(',') + 1));
    EXPECT_NEAR(m->pressure(Stretch::from_value(s)), 2.5 * p, 1e-14 * (2.5 * std::abs(p) + 1.0)) << "s = " << s;
  }
  EXPECT_EQ(m->admissible().log_min, std::log(0.01));
  EXPECT_NEAR(m->admissible().log_max, std::log(100.0), 1e-15);
  EXPECT_EQ(m->energy_density(Stretch::natural()), 2.5);
  EXPECT_EQ(m->riemann_psi(Stretch::natural()), 0.0);
}

TEST(Tabulated, KeepsFullPrecisionAtTinyStrains) {
  // The table is interpolated in ln s, so p(1 + ε) = P'(0) ln(1 + ε) (1 + O(ε)) for ε = 1e-12.
  const TableFile file(table_text('p', 0.1, 10.0, 40, law_pressure));
  const auto m = tabulated(file.path());
  const double slope = m->pressure(Stretch::from_log(1e-7)) / 1e-7;  // P'(0), to O(1e-7)
  for (double eps : {-1e-12, 1e-12}) {
    const Stretch s = Stretch::from_strain(eps);
    EXPECT_NEAR(m->pressure(s), slope * s.log(), 1e-6 * std::abs(slope * s.log())) << eps;
    const Solved<Stretch> back = m->stretch_at_pressure(m->pressure(s));
    ASSERT_TRUE(back.ok());
    EXPECT_NEAR(back.value.strain(), eps, 1e-10 * std::abs(eps)) << eps;
  }
}

TEST(Tabulated, AnEnergyTableIsThePressureTableOfTheSameLaw) {
  const TableFile p_file(table_text('p', 0.1, 10.0, 80, law_pressure));
  const TableFile e_file(table_text('e', 0.1, 10.0, 80, law_energy));
  const auto from_p = tabulated(p_file.path());
  const auto from_e = tabulated(e_file.path());
  for (double s_value : {0.1, 0.13, 0.5, 0.97, 1.0, 1.03, 2.0, 7.7, 10.0}) {
    const Stretch s = Stretch::from_value(s_value);
    SCOPED_TRACE(s_value);
    // Fourth-order differences of the rows, one-sided at the ends (measured: p ~7e-5, e ~3e-6 there).
    EXPECT_NEAR(from_e->pressure(s), from_p->pressure(s), 2e-4 * (std::abs(from_p->pressure(s)) + kV2));
    EXPECT_NEAR(from_e->energy_density(s), law_energy(s_value), 1e-5 * law_energy(s_value));
    EXPECT_NEAR(from_e->sound_speed(s), from_p->sound_speed(s), 2e-2);
  }
  EXPECT_EQ(from_e->pressure(Stretch::natural()), 0.0);
  EXPECT_EQ(from_e->energy_density(Stretch::natural()), 1.0);
}

TEST(Tabulated, RelativePathsStartAtTheSceneDirectory) {
  const TableFile file(table_text('p', 0.5, 2.0, 8, law_pressure));
  const fs::path path(file.path());
  EXPECT_NO_THROW(static_cast<void>(tabulated(path.filename().string(), 1.0, path.parent_path().string())));
  try {
    static_cast<void>(tabulated("no_such_table.csv", 1.0, path.parent_path().string()));
    FAIL() << "a missing table was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), (path.parent_path() / "no_such_table.csv").string())) << e.what();
    EXPECT_TRUE(contains(e.what(), "no such file")) << e.what();
  }
}

TEST(Tabulated, AnInlineTableIsTheFileItWouldBe) {
  const std::string text = table_text('p', 0.2, 5.0, 60, law_pressure);
  const TableFile file(text);
  const auto from_file = tabulated(file.path());
  const auto from_text = tabulated(text);
  for (int i = 0; i <= 100; ++i) {
    const Stretch s = Stretch::from_log(std::log(0.2) + (std::log(5.0) - std::log(0.2)) * i / 100.0);
    EXPECT_EQ(from_text->pressure(s), from_file->pressure(s)) << "s = " << s.value();
    EXPECT_EQ(from_text->sound_speed(s), from_file->sound_speed(s)) << "s = " << s.value();
  }
  // Its defects name the line of the text.
  try {
    static_cast<void>(tabulated("s,p\n0.5,1\n1,0\n2,0.1\n"));
    FAIL() << "a rising p was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "inline table:4: row 3 (s = 2)")) << e.what();
  }
}

TEST(Tabulated, ATableInRestDensityCSquaredMeansTheSameLawInAnSiScene) {
  const std::string text = table_text('p', 0.2, 5.0, 40, law_pressure);
  const double rest_density = 7850.0;  // kg/m^3
  ParameterValues natural;
  natural.set("rest_density", 1.0);
  natural.set("table", text);
  natural.set("table_units", std::string("scene"));
  ParameterValues si = natural;
  si.set_units(UnitSystem::si);
  si.set("rest_density", rest_density);  // a material's numbers arrive natural, the table's rows as written
  si.set("table_units", std::string("rest_density c^2"));
  const auto a = build_material("tabulated", natural);
  const auto b = build_material("tabulated", si);
  for (double s : {0.3, 0.8, 1.0, 1.7, 4.0}) {
    EXPECT_NEAR(b->pressure(Stretch::from_value(s)), rest_density * a->pressure(Stretch::from_value(s)),
                1e-14 * rest_density)
        << "s = " << s;
    EXPECT_NEAR(b->pressure(Stretch::from_value(s)), rest_density * law_pressure(s), 1e-4 * rest_density);  // 40 rows
  }
  // The same rows read in the SI scene's own units are pascals: a law 1/(rest_density c^2) as stiff.
  si.set("table_units", std::string("scene"));
  const auto pascals = build_material("tabulated", si);
  EXPECT_LT(std::abs(pascals->pressure(Stretch::from_value(0.5))), 1e-12 * rest_density * std::abs(law_pressure(0.5)));
  si.set("table_units", std::string("pascal"));
  try {
    static_cast<void>(build_material("tabulated", si));
    FAIL() << "an unknown table_units was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "'scene' or 'rest_density c^2'")) << e.what();
  }
}

TEST(Tabulated, CommentsAndBlankLinesAreSkipped) {
  EXPECT_EQ(refusal("# a table\n\ns, p   # header\n0.5,1\n\n1,0  # natural\n2,-0.1\n"), "");
}

TEST(Tabulated, EveryDefectNamesTheLineAndRow) {
  struct Case {
    std::string text;
    std::vector<std::string> expected;  ///< parts of the message
  };
  const std::vector<Case> cases = {
      {"", {"empty", "'s,p' or 's,e'"}},
      {"s,q\n0.5,1\n1,0\n2,-1\n", {":1:", "header 's,p' or 's,e'", "'s,q'"}},
      {"s,p\n0.5,1\n1,zero\n2,-1\n", {":3:", "two numbers", "'1,zero'"}},
      {"s,p\n0.5,1,2\n1,0\n2,-1\n", {":2:", "two numbers"}},
      {"s,p\n0.5,1\n1,0\n2,nan\n", {":4:", "finite"}},
      {"s,p\n-0.5,1\n1,0\n2,-1\n", {":2:", "positive"}},
      {"s,p\n1,0\n2,-0.1\n", {"2 rows", "at least 3"}},
      {"s,p\n0.5,1\n2,-0.1\n3,-0.2\n", {"no row at s = 1"}},
      {"s,p\n0.5,1\n1,0.01\n2,-0.1\n", {":3: row 2 (s = 1)", "p = 0.01", "unstressed"}},
      {"s,e\n0.5,2\n1,1.5\n2,0.4\n", {":3: row 2 (s = 1)", "e = 1.5", "units of rest_density"}},
      {"s,p\n0.5,1\n1,0\n0.9,-0.1\n", {":4: row 3 (s = 0.9)", "does not increase"}},
      {"# x\ns,p\n0.5,1\n0.7,1\n1,0\n2,-0.1\n", {":4: row 2 (s = 0.7)", "does not fall", "W'' > 0"}},
      // The rigid law scaled by 4: c_s = 2 > c.
      {table_text('p', 0.5, 2.0, 8, [](double s) { return 2.0 * (1.0 / (s * s) - 1.0); }),
       {"between rows 1 and 2", "acausal", "c_s = "}},
      // e falls, but beyond s = 2 the law bends: W = e s barely rises, so p = −W' rises there.
      {table_text(
           'e', 0.5, 4.0, 18,
           [](double s) { return s < 2.1 ? law_energy(s) : law_energy(2.0) * 2.0 / s * (1.0 + 0.01 * (s - 2.0)); }),
       {"row", "W = e s is not convex"}},
  };
  for (const Case& c : cases) {
    const std::string message = refusal(c.text);
    SCOPED_TRACE(c.text);
    ASSERT_FALSE(message.empty()) << "accepted";
    EXPECT_TRUE(contains(message, "rigidity_tabulated_")) << "names the file: " << message;
    for (const std::string& part : c.expected) EXPECT_TRUE(contains(message, part)) << part << " in: " << message;
  }
}

}  // namespace
}  // namespace rigidity::testing
