/// `tabulated`: a material given by a table of p(s) or of e(s), read from a CSV file (or
/// written inline: `table` text with a line break is the table itself):
///
///   # comments and blank lines are skipped
///   s,p                       header: s and p, or s and e (p, e in the scene's units: Pa in an
///                             SI scene, units of rest_density c² in a natural one)
///   0.5,1.5                   one row per stretch, s increasing, p (or e) decreasing
///   1,0                       the natural state: p = 0 (or e = 1)
///   2,-0.375
///
/// p is interpolated in τ = ln s by GSL's Steffen method: monotone between rows, C¹, no
/// overshoot (GSL gives the slope at each row; the cubic between two rows is evaluated from the
/// nearer one, so that p keeps its relative precision next to s = 1). The law is then a
/// PressureLawMaterial (numeric_material.hpp), so that W, e, W'', c_s, Ψ and the inverses are
/// derived exactly as for any material given by p(s), from tables whose panels end at the rows:
/// W = ρ00 − ∫_1^s p dσ, W'' = −p', c_s² = s W''/(e + p). Accuracy against the law a table
/// samples (tabulated_test.cpp): p to third order in the row spacing and c_s to second inside
/// the table, c_s to first order in its first and last intervals (GSL's end slopes are secants).
///
/// An e table is first turned into a p table: p = −dW/ds with W = e s, by the fourth-order
/// difference over the five nearest rows (one-sided at the ends). c_s needs W'', and a C¹
/// interpolant of e itself would give it only to first order, discontinuous at the rows, and
/// concave in the first and last intervals (GSL's end slopes are the end secants); from p it is
/// a first derivative. The material's W then agrees with the rows' e s to the order of the
/// differences; p at s = 1 must come out small next to p at the neighbouring rows
/// (kNaturalPressureFraction), and is set to 0.
///
/// Admissibility is checked when the material is built, and every error names the file, line
/// and row: rows in order, the natural state present, p (or e) strictly decreasing, then,
/// between every pair of rows, the interpolated law sampled for e + p > 0, W'' > 0 (hyperbolic)
/// and c_s <= 1 (causal). The admissible range is [first row, last row].

#include <gsl/gsl_errno.h>
#include <gsl/gsl_interp.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "rigidity/numeric_material.hpp"
#include "rigidity/parameters.hpp"
#include "rigidity/registry.hpp"

namespace rigidity {
namespace {

/// Most rows a table may have, and most bytes its file.
constexpr std::size_t kMaxRows = 100000;
constexpr std::uintmax_t kMaxTableBytes = 16u << 20;
/// p at s = 1 (or e − 1) within this of 0 is the natural state, taken as exact.
constexpr double kNaturalStateTolerance = 1e-12;
/// Points at which the interpolated law is checked between two rows (ends included).
constexpr int kChecksPerInterval = 16;
/// c_s² above 1 by no more than this is rounding, not acausality.
constexpr double kCausalityTolerance = 1e-9;
/// |p(1)| an e table may give, as a fraction of |p| at the neighbouring rows, and still be
/// unstressed at s = 1: its rows approximate a law with p(1) = 0 to the order of the differences.
constexpr double kNaturalPressureFraction = 0.05;

enum class Column { pressure, energy };

struct Row {
  double s = 0.0;
  double value = 0.0;  ///< p or e as written: [Pa] in an SI scene, [ρ00 c²] in a natural one
  int line = 0;        ///< in the file, 1-based
};

struct Table {
  std::string file;
  Column column = Column::pressure;
  std::vector<Row> rows;
  std::vector<double> pressures;  ///< p of each row, in units of ρ00 c² (of an e table: derived)
  /// The rows' p or e times this is in units of ρ00 c²: 1 in a natural scene, 1/(ρ00 c²) in an
  /// SI scene (the pressure conversion of the scene loader, then ρ00).
  double scale = 1.0;
  std::string unit = "rest_density c^2";  ///< of the rows as written

  /// "FILE:LINE: row N (s = X)"
  [[nodiscard]] std::string at(std::size_t i) const {
    std::ostringstream os;
    os.precision(12);
    os << file << ":" << rows[i].line << ": row " << i + 1 << " (s = " << rows[i].s << ")";
    return os.str();
  }
  /// "FILE:LINES: between rows N and N+1 (s in [X, Y])"
  [[nodiscard]] std::string between(std::size_t i) const {
    std::ostringstream os;
    os.precision(12);
    os << file << ":" << rows[i].line << "-" << rows[i + 1].line << ": between rows " << i + 1 << " and " << i + 2
       << " (s in [" << rows[i].s << ", " << rows[i + 1].s << "])";
    return os.str();
  }
};

std::string text_of(double v) {
  std::ostringstream os;
  os.precision(12);
  os << v;
  return os.str();
}

std::string_view trimmed(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

/// A decimal number filling `text` (surrounding blanks aside), or nothing.
bool parse_number(std::string_view text, double& out) {
  text = trimmed(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size() && !text.empty();
}

/// dW/ds at row i from the five nearest rows: the derivative of their interpolating polynomial.
double derivative_at_row(const std::vector<double>& x, const std::vector<double>& y, std::size_t i) {
  const std::size_t n = x.size();
  const std::size_t first = std::min(i >= 2 ? i - 2 : 0, n >= 5 ? n - 5 : 0);
  const std::size_t last = std::min(first + 5, n);
  double slope = 0.0;
  for (std::size_t j = first; j < last; ++j) {
    // L_j'(x_i): for j = i, Σ_{l≠i} 1/(x_i − x_l); else Π_{l≠i,j} (x_i − x_l)/(x_j − x_l) / (x_j − x_i).
    double weight = 0.0;
    if (j == i) {
      for (std::size_t l = first; l < last; ++l)
        if (l != i) weight += 1.0 / (x[i] - x[l]);
    } else {
      weight = 1.0 / (x[j] - x[i]);
      for (std::size_t l = first; l < last; ++l)
        if (l != i && l != j) weight *= (x[i] - x[l]) / (x[j] - x[l]);
    }
    slope += weight * y[j];
  }
  return slope;
}

/// The pressures of an e table: p = −dW/ds, W = e s; checked to vanish at s = 1 and to fall.
void derive_pressures(Table& table, std::size_t natural) {
  std::vector<double> s;
  std::vector<double> w;
  for (const Row& row : table.rows) {
    s.push_back(row.s);
    w.push_back(row.value * row.s);
  }
  for (std::size_t i = 0; i < table.rows.size(); ++i) table.pressures[i] = -derivative_at_row(s, w, i);
  double beside = 0.0;  // |p| at the neighbouring rows
  if (natural > 0) beside = std::max(beside, std::abs(table.pressures[natural - 1]));
  if (natural + 1 < table.rows.size()) beside = std::max(beside, std::abs(table.pressures[natural + 1]));
  if (std::abs(table.pressures[natural]) > kNaturalPressureFraction * beside)
    throw std::invalid_argument(table.at(natural) +
                                ": the rows around it give p = -d(e s)/ds = " + text_of(table.pressures[natural]) +
                                " at s = 1, not close to 0 next to p = " + text_of(beside) +
                                " at the neighbouring rows: the natural state is unstressed (de/ds = -e there)");
  table.pressures[natural] = 0.0;
  for (std::size_t i = 1; i < table.rows.size(); ++i)
    if (!(table.pressures[i] < table.pressures[i - 1]))
      throw std::invalid_argument(table.at(i) + ": p = -d(e s)/ds = " + text_of(table.pressures[i]) +
                                  " does not fall below row " + std::to_string(i) + "'s " +
                                  text_of(table.pressures[i - 1]) + ": W = e s is not convex here (W'' <= 0)");
}

/// The checks on the rows themselves. \throws std::invalid_argument naming the row
void check_rows(Table& table) {
  const char* name = table.column == Column::pressure ? "p" : "e";
  std::size_t natural = table.rows.size();
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const Row& row = table.rows[i];
    if (i > 0 && !(row.s > table.rows[i - 1].s))
      throw std::invalid_argument(table.at(i) + ": s does not increase (row " + std::to_string(i) + " has s = " +
                                  text_of(table.rows[i - 1].s) + "); rows go from compressed to stretched");
    if (i > 0 && !(row.value < table.rows[i - 1].value))
      throw std::invalid_argument(table.at(i) + ": " + name + " = " + text_of(row.value) + " does not fall below row " +
                                  std::to_string(i) + "'s " + text_of(table.rows[i - 1].value) + ": " +
                                  (table.column == Column::pressure ? "p must decrease as s grows (W'' > 0)"
                                                                    : "e must decrease as s grows (e + p > 0)"));
    if (row.s == 1.0) natural = i;
  }
  if (natural == table.rows.size())
    throw std::invalid_argument("table '" + table.file +
                                "': no row at s = 1; the natural state must be one of the rows");
  Row& one = table.rows[natural];
  const double expected = table.column == Column::pressure ? 0.0 : 1.0;  // [ρ00 c²]
  if (std::abs(one.value * table.scale - expected) > kNaturalStateTolerance) {
    const bool si = table.unit == "Pa";
    const std::string unit = si ? " Pa" : "";
    throw std::invalid_argument(table.at(natural) + ": " + name + " = " + text_of(one.value) + unit +
                                "; at the natural state " + name + " = " + text_of(expected / table.scale) + unit +
                                (table.column == Column::pressure ? " (it is unstressed)"
                                 : si                             ? " (rest_density c^2)"
                                                                  : " (e is in units of rest_density c^2)"));
  }
  one.value = expected / table.scale;
  for (const Row& row : table.rows) table.pressures.push_back(row.value * table.scale);
  if (table.column == Column::energy) derive_pressures(table, natural);
}

/// Reads and checks the rows of `source`, written in `units`, for a material of rest density
/// `rest_density` (natural): a CSV file (relative paths from `directory`), or, where `source`
/// holds a line break, the table itself (written inline in the scene, or by
/// rigidity.Material.from_function), whose errors name its lines. \throws std::invalid_argument
Table read_table(const std::string& source, const std::string& directory, UnitSystem units, double rest_density) {
  namespace fs = std::filesystem;
  Table table;
  table.scale = to_natural(1.0, Dimension::pressure, units) / (units == UnitSystem::si ? rest_density : 1.0);
  table.unit = units == UnitSystem::si ? "Pa" : "rest_density c^2";
  std::ifstream file;
  std::istringstream inline_rows;
  const bool inline_table = source.find('\n') != std::string::npos;
  if (inline_table) {
    table.file = "inline table";
    if (source.size() > kMaxTableBytes)
      throw std::invalid_argument("inline table: larger than " + std::to_string(kMaxTableBytes) + " bytes");
    inline_rows.str(source);
  } else {
    const fs::path written(source);
    table.file = (written.is_absolute() || directory.empty() ? written : fs::path(directory) / written).string();
    std::error_code ec;
    if (!fs::is_regular_file(table.file, ec))
      throw std::invalid_argument("table '" + table.file +
                                  "': " + (fs::exists(table.file, ec) ? "not a file" : "no such file"));
    if (fs::file_size(table.file, ec) > kMaxTableBytes)
      throw std::invalid_argument("table '" + table.file + "': larger than " + std::to_string(kMaxTableBytes) +
                                  " bytes");
    file.open(table.file);
    if (!file) throw std::invalid_argument("table '" + table.file + "': cannot be opened for reading");
  }
  std::istream& in = inline_table ? static_cast<std::istream&>(inline_rows) : file;

  bool header_read = false;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::string_view content(line);
    content = trimmed(content.substr(0, content.find('#')));
    if (content.empty()) continue;
    const std::size_t comma = content.find(',');
    const std::string where = table.file + ":" + std::to_string(number) + ": ";
    if (comma == std::string_view::npos || content.find(',', comma + 1) != std::string_view::npos) {
      throw std::invalid_argument(where +
                                  (header_read ? "expected two numbers separated by a comma, got '"
                                               : "expected the header 's,p' or 's,e', got '") +
                                  std::string(content) + "'");
    }
    const std::string_view first = trimmed(content.substr(0, comma));
    const std::string_view second = trimmed(content.substr(comma + 1));
    if (!header_read) {
      if (first != "s" || (second != "p" && second != "e"))
        throw std::invalid_argument(where +
                                    "expected the header 's,p' or 's,e' (p or e in Pa in an SI scene, in units of "
                                    "rest_density c^2 in a natural one), got '" +
                                    std::string(content) + "'");
      table.column = second == "p" ? Column::pressure : Column::energy;
      header_read = true;
      continue;
    }
    Row row;
    row.line = number;
    if (!parse_number(first, row.s) || !parse_number(second, row.value))
      throw std::invalid_argument(where + "expected two numbers separated by a comma, got '" + std::string(content) +
                                  "'");
    if (!std::isfinite(row.s) || !std::isfinite(row.value))
      throw std::invalid_argument(where + "numbers must be finite, got '" + std::string(content) + "'");
    if (!(row.s > 0.0)) throw std::invalid_argument(where + "the stretch s must be positive, got " + text_of(row.s));
    table.rows.push_back(row);
    if (table.rows.size() > kMaxRows)
      throw std::invalid_argument(where + "more than " + std::to_string(kMaxRows) + " rows");
  }
  if (!header_read)
    throw std::invalid_argument("table '" + table.file + "': empty (expected the header 's,p' or 's,e')");
  if (table.rows.size() < 3)
    throw std::invalid_argument("table '" + table.file + "': " + std::to_string(table.rows.size()) +
                                " rows; the interpolation needs at least 3");
  check_rows(table);
  return table;
}

/// The unit system the table's p or e column is written in (`table_units`).
UnitSystem table_units(const ParameterValues& values) {
  const std::string& units = values.text("table_units");
  if (units == "scene") return values.units();
  if (units == "rest_density c^2") return UnitSystem::natural;
  throw ParameterError("table_units", "must be 'scene' or 'rest_density c^2', got '" + units + "'");
}

class Tabulated final : public PressureLawMaterial {
 public:
  static constexpr std::string_view kName = "tabulated";

  static std::string doc() {
    return "A law given as a table: p(s) or e(s) from a CSV file (header 's,p' or 's,e', then one row per stretch "
           "with s increasing; p and e in the scene's units: Pa in an SI scene, units of rest_density c^2 in a natural "
           "one; '#' starts a comment). p is "
           "interpolated in ln s by GSL's Steffen method (monotone, C1), and W = rho00 - integral of p ds; an e "
           "table is first turned into p = -d(e s)/ds by fourth-order differences of its rows. W'', c_s and the "
           "Riemann invariant follow from W as for every material. The table must hold the natural state s = 1 (p = 0, "
           "or e = 1), p (or e) must fall strictly as s "
           "grows, and the interpolated law must be hyperbolic and causal between all rows: errors name the row. "
           "Admissible from the first row's stretch to the last's.";
  }
  static std::vector<ParameterSpec> parameters() {
    return {rest_density_parameter(),
            ParameterSpec::text("table",
                                "CSV file of the law, p(s) or e(s); a relative path starts at the scene file's "
                                "directory. Text with a line break is the table itself (a YAML block scalar)")
                .require(),
            ParameterSpec::text("table_units",
                                "the units of the p or e column: 'scene' (Pa in an SI scene, rest_density c^2 in a "
                                "natural one) or 'rest_density c^2' (in any scene)")
                .defaults_to(std::string("scene"))};
  }

  explicit Tabulated(const ParameterValues& values)
      : Tabulated(values, read_table(values.text("table"), values.directory(), table_units(values),
                                     values.number("rest_density"))) {}

  [[nodiscard]] std::string_view model() const override { return kName; }
  [[nodiscard]] std::vector<double> law_breaks() const override { return log_stretches_; }

 private:
  Tabulated(const ParameterValues& values, Table table)
      : PressureLawMaterial(values.number("rest_density"),
                            StretchRange{std::log(table.rows.front().s), std::log(table.rows.back().s)}),
        table_(std::move(table)) {
    for (const Row& row : table_.rows) log_stretches_.push_back(std::log(row.s));
    // GSL's Steffen interpolant gives the slope at each row; the cubic between two rows is then
    // evaluated from the nearer row (pressure_law_at_log), so that p keeps its relative
    // precision next to the row where it vanishes, s = 1.
    const std::unique_ptr<gsl_interp, decltype(&gsl_interp_free)> steffen(
        gsl_interp_alloc(gsl_interp_steffen, log_stretches_.size()), &gsl_interp_free);
    if (!steffen) throw std::bad_alloc();
    const double* x = log_stretches_.data();
    const double* y = table_.pressures.data();
    if (gsl_interp_init(steffen.get(), x, y, log_stretches_.size()) != GSL_SUCCESS)
      throw std::invalid_argument("table '" + table_.file + "': GSL cannot interpolate it");
    for (const double t : log_stretches_) {
      double slope = 0.0;
      if (gsl_interp_eval_deriv_e(steffen.get(), x, y, t, nullptr, &slope) != GSL_SUCCESS || !std::isfinite(slope))
        throw std::invalid_argument("table '" + table_.file + "': GSL cannot interpolate it");
      slopes_.push_back(slope);
    }
    check_interpolated_law();
  }

  /// ρ00 P(ln s): on each interval between rows the cubic with the rows' values and Steffen
  /// slopes (Hermite form), from the nearer row; beyond the rows (only the difference formulas
  /// of the direct path look there) continued along the end slope.
  [[nodiscard]] double pressure_law_at_log(double log_s) const override {
    const std::vector<double>& x = log_stretches_;
    const std::vector<double>& y = table_.pressures;
    const std::size_t n = x.size();
    if (log_s <= x.front()) return rest_density() * (y.front() + slopes_.front() * (log_s - x.front()));
    if (log_s >= x.back()) return rest_density() * (y.back() + slopes_.back() * (log_s - x.back()));
    const std::size_t i = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), log_s) - x.begin()) - 1, n - 2);
    const double h = x[i + 1] - x[i];
    const double secant = (y[i + 1] - y[i]) / h;
    const double left = log_s - x[i];
    const double right = x[i + 1] - log_s;
    double p = 0.0;
    if (left <= right) {  // p = y_i + d_i δ + c2 δ² + c3 δ³, δ = ln s − x_i
      const double c2 = (3.0 * secant - 2.0 * slopes_[i] - slopes_[i + 1]) / h;
      const double c3 = (slopes_[i] + slopes_[i + 1] - 2.0 * secant) / (h * h);
      p = y[i] + left * (slopes_[i] + left * (c2 + left * c3));
    } else {  // the same cubic from the right: u = x_{i+1} − ln s
      const double c2 = (2.0 * slopes_[i + 1] + slopes_[i] - 3.0 * secant) / h;
      const double c3 = (2.0 * secant - slopes_[i] - slopes_[i + 1]) / (h * h);
      p = y[i + 1] + right * (-slopes_[i + 1] + right * (c2 + right * c3));
    }
    return rest_density() * p;
  }
  [[nodiscard]] double pressure_law(double s) const override { return pressure_law_at_log(std::log(s)); }

  /// Between every pair of rows: e + p > 0, W'' > 0 and c_s² <= 1 (within rounding).
  void check_interpolated_law() const {
    for (std::size_t i = 0; i + 1 < log_stretches_.size(); ++i) {
      const double a = log_stretches_[i];
      const double b = log_stretches_[i + 1];
      for (int k = 0; k <= kChecksPerInterval; ++k) {
        const double fraction = static_cast<double>(k) / kChecksPerInterval;
        const Stretch s = Stretch::from_log(a + (b - a) * fraction);
        const double enthalpy = enthalpy_density(s);
        const double stiffness_value = stiffness(s);
        const std::string where = table_.between(i) + ", at s = " + text_of(s.value()) + ": ";
        if (!(enthalpy > 0.0)) throw std::invalid_argument(where + "e + p = " + text_of(enthalpy) + " is not positive");
        if (!(stiffness_value > 0.0))
          throw std::invalid_argument(where + "not hyperbolic: W'' = " + text_of(stiffness_value) + " is not positive");
        const double square = s.value() * stiffness_value / enthalpy;  // c_s² = s W''/(e + p)  (docs/physics.md)
        if (!(square <= 1.0 + kCausalityTolerance))
          throw std::invalid_argument(where + "acausal: the sound speed c_s = " + text_of(std::sqrt(square)) +
                                      " exceeds c (the table's p and e are read in " + table_.unit +
                                      ", the units of the scene)");
      }
    }
  }

  Table table_;
  std::vector<double> log_stretches_;  ///< ln s of the rows
  std::vector<double> slopes_;         ///< dp/d ln s at the rows (Steffen), in units of ρ00
};

RIGIDITY_REGISTER_MATERIAL(Tabulated);

}  // namespace
}  // namespace rigidity
