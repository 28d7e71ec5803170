// rigidity plot RUN_DIR [--out DIR]: a run's outputs drawn with gnuplot (the x–t
// diagram, probe histories, snapshot profiles), and the gnuplot plumbing that
// `rigidity compare` shares: find gnuplot on PATH, write a script, run it, check it.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <tuple>
#include <unordered_set>
#include <vector>

#include "rigidity/cli.hpp"
#include "rigidity/errors.hpp"
#include "rigidity/number_text.hpp"
#include "rigidity/quantity.hpp"
#include "rigidity/units.hpp"

namespace rigidity::cli {

namespace fs = std::filesystem;

// ---- gnuplot ------------------------------------------------------------------------

namespace {

/// `text` quoted for /bin/sh.
std::string shell_quote(std::string_view text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool is_executable_file(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error) && ::access(path.c_str(), X_OK) == 0;
}

}  // namespace

fs::path find_gnuplot() {
  const char* path = std::getenv("PATH");
  // execvp's default search path when PATH is unset.
  const std::string_view directories = path != nullptr ? std::string_view(path) : std::string_view("/bin:/usr/bin");
  std::size_t start = 0;
  while (start <= directories.size()) {
    const std::size_t end = std::min(directories.find(':', start), directories.size());
    const std::string_view directory = directories.substr(start, end - start);
    if (!directory.empty()) {
      fs::path candidate = fs::path(directory) / "gnuplot";
      if (is_executable_file(candidate)) return candidate;
    }
    start = end + 1;
  }
  return {};
}

std::string gnuplot_quote(std::string_view text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string gnuplot_comment(std::string_view text) {
  constexpr std::size_t kWidth = 100;
  std::string out, line = "#";
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find(' ', start), text.size());
    const std::string_view word = text.substr(start, end - start);
    if (line.size() > 1 && line.size() + 1 + word.size() > kWidth) {
      out += line + "\n";
      line = "#";
    }
    if (!word.empty()) line += " " + std::string(word);
    start = end + 1;
  }
  return out + line + "\n";
}

void render_gnuplot(const fs::path& gnuplot, const fs::path& dir, const std::string& name, const std::string& script,
                    std::string_view image) {
  const std::string script_name = name + ".gp";
  const fs::path png = dir / (name + "." + std::string(image));
  {
    std::ofstream file(dir / script_name, std::ios::binary);
    file << script;
    file.close();
    if (!file) throw CommandError(kExitInternal, "cannot write " + (dir / script_name).string());
  }
  std::error_code ignored;
  fs::remove(png, ignored);  // a PNG left from an earlier call must not pass for this one

  // Run in `dir`, so that the script's relative paths hold when it is rerun by hand there.
  const std::string command = "cd " + shell_quote(dir.string()) + " && " + shell_quote(gnuplot.string()) + " " +
                              shell_quote(script_name) + " 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) throw CommandError(kExitInternal, "cannot start gnuplot (" + gnuplot.string() + ")");
  std::string messages;
  std::array<char, 4096> buffer{};
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) messages.append(buffer.data(), n);
  const int status = ::pclose(pipe);

  const std::string where = (dir / script_name).string();
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = status != -1 && WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                                              : std::string("abnormal termination");
    throw CommandError(kExitInternal, "gnuplot failed on " + where + " (" + how + ")" +
                                          (messages.empty() ? std::string() : ":\n" + messages));
  }
  if (!fs::is_regular_file(png, ignored) || fs::file_size(png, ignored) == 0)
    throw CommandError(kExitInternal, "gnuplot ran " + where + " but wrote no " + png.string() +
                                          (messages.empty() ? std::string() : ":\n" + messages));
}

// ---- rigidity plot ------------------------------------------------------------------

namespace {

/// The fields of one CSV line (RFC 4180 quoting, as the run writers quote).
std::vector<std::string> csv_fields(std::string_view line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

/// Calls `row` with the fields of every data row of a CSV file; returns the number of
/// rows, or nullopt if the file does not exist. \throws CommandError (exit 2) if the
/// header is not `expected_header`.
std::optional<long> for_each_row(const fs::path& path, std::string_view expected_header,
                                 const std::function<void(const std::vector<std::string>&)>& row) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != expected_header)
    throw CommandError(kExitInvalidInput, path.string() + ": expected the header '" + std::string(expected_header) +
                                              "', found '" + line + "'");
  long rows = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line == "\r") continue;
    row(csv_fields(line));
    ++rows;
  }
  return rows;
}

/// Distinct values in the order they first appear.
class Distinct {
 public:
  void add(const std::string& value) {
    if (seen_.insert(value).second) values_.push_back(value);
  }
  [[nodiscard]] const std::vector<std::string>& values() const { return values_; }
  [[nodiscard]] bool contains(const std::string& value) const { return seen_.count(value) != 0; }

 private:
  std::vector<std::string> values_;
  std::unordered_set<std::string> seen_;
};

/// What summary.json says about the run: its scene name and unit system.
struct RunInfo {
  std::string scene;
  UnitSystem units = UnitSystem::natural;
  bool piecewise_constant = false;  ///< front tracking: every profile is a staircase of jumps
};

/// The string value of `"key": "..."` in a JSON text written by rigidity's JsonWriter, if any.
std::optional<std::string> json_string_member(const std::string& json, std::string_view key) {
  const std::string pattern = "\"" + std::string(key) + "\": \"";
  const std::size_t start = json.find(pattern);
  if (start == std::string::npos) return std::nullopt;
  std::string value;
  for (std::size_t i = start + pattern.size(); i < json.size() && json[i] != '"'; ++i) {
    if (json[i] == '\\' && i + 1 < json.size()) ++i;
    value += json[i];
  }
  return value;
}

RunInfo read_run_info(const fs::path& run_dir) {
  RunInfo info;
  info.scene = fs::absolute(run_dir).lexically_normal().filename().string();
  if (info.scene.empty()) info.scene = fs::absolute(run_dir).lexically_normal().parent_path().filename().string();
  std::ifstream in(run_dir / "summary.json", std::ios::binary);
  if (!in) return info;
  std::ostringstream text;
  text << in.rdbuf();
  const std::string json = text.str();
  if (const auto scene = json_string_member(json, "scene")) info.scene = *scene;
  if (const auto system = json_string_member(json, "system"); system && *system == "si") info.units = UnitSystem::si;
  if (const auto method = json_string_member(json, "method")) info.piecewise_constant = *method == "characteristics";
  return info;
}

/// "name [unit]" for an axis.
std::string axis_label(std::string_view name, Dimension dimension, UnitSystem units) {
  if (dimension == Dimension::dimensionless) return std::string(name);
  return std::string(name) + " [" + std::string(unit_symbol(dimension, units)) + "]";
}

std::string quantity_label(const std::string& quantity, UnitSystem units) {
  const std::optional<Quantity> q = quantity_from_string(quantity);
  return axis_label(quantity, q ? dimension_of(*q) : Dimension::dimensionless, units);
}

/// The first lines of every script: PNG output with literal (not "enhanced") text, CSV input.
std::string script_header(std::string_view what, std::string_view name, int width, int height) {
  std::string out = gnuplot_comment(what);
  out += "# Written by `rigidity plot`; edit and rerun from this directory: gnuplot " + std::string(name) + ".gp\n";
  out += "set terminal pngcairo size " + std::to_string(width) + "," + std::to_string(height) +
         " font 'Sans,11' noenhanced\n";
  out += "set encoding utf8\n";
  out += "set output " + gnuplot_quote(std::string(name) + ".png") + "\n";
  out += "set datafile separator ','\n";
  out += "set datafile missing NaN  # rows filtered out as NaN do not break a line\n";
  out += "set grid lc rgb '#dddddd'\n";
  return out;
}

/// Rows and columns of a multiplot of n panels: one column up to 2 panels, else two.
std::pair<int, int> panel_grid(std::size_t n) {
  const int columns = n <= 2 ? 1 : 2;
  const int rows = static_cast<int>((n + static_cast<std::size_t>(columns) - 1) / static_cast<std::size_t>(columns));
  return {rows, columns};
}

std::string join_plot(const std::vector<std::string>& elements) {
  std::string out = "plot ";
  for (std::size_t i = 0; i < elements.size(); ++i) out += (i == 0 ? "" : ", \\\n     ") + elements[i];
  return out + "\n";
}

// ---- the three plots ------------------------------------------------------------------

/// Front kinds (docs/cli.md, "What a run writes") and their colours, as in scripts/plot_xt.sh.
struct KindStyle {
  std::string_view kind;
  std::string_view colour;
  std::string_view width;
  std::string_view legend;  ///< what the key says: the physics, not the file's word
};
constexpr KindStyle kKindStyles[] = {
    {"contact", "#d62728", "1.5", "jump at c_s (linearly degenerate: compression or release)"},
    {"shock", "#9467bd", "2", "shock"},
    {"rarefaction", "#1f77b4", "1", "rarefaction fan step"},
    {"interface", "#2ca02c", "1.5", "material interface"},
    {"boundary", "#222222", "2.5", "body end"}};

/// The front kinds a run has, in the order of kKindStyles; a kind this version does not know,
/// in grey under its own name.
std::vector<std::pair<std::string, KindStyle>> present_kinds(const Distinct& kinds) {
  std::vector<std::pair<std::string, KindStyle>> present;
  for (const KindStyle& style : kKindStyles)
    if (kinds.contains(std::string(style.kind))) present.emplace_back(std::string(style.kind), style);
  for (const std::string& kind : kinds.values())
    if (std::none_of(std::begin(kKindStyles), std::end(kKindStyles),
                     [&](const KindStyle& s) { return s.kind == kind; }))
      present.emplace_back(kind, KindStyle{kind, "#999999", "1", kind});
  return present;
}

/// The fields of a line of fronts.csv (t0,x0,t1,x1,kind,family; numbers and a bare word),
/// split without copying; false if the line has not six fields.
bool front_fields(std::string_view line, std::array<std::string_view, 6>& fields) {
  std::size_t start = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    const std::size_t end = i == 5 ? line.size() : line.find(',', start);
    if (end == std::string_view::npos) return false;
    fields[i] = line.substr(start, end - start);
    start = end + 1;
  }
  if (!fields[5].empty() && fields[5].back() == '\r') fields[5].remove_suffix(1);
  return fields[5].find(',') == std::string_view::npos;
}

bool parse_double(std::string_view text, double& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

/// Streams the data rows of fronts.csv: `row(t0, x0, t1, x1, kind)` for every well-formed
/// line. Returns the number of such rows, or nullopt if the file does not exist.
/// \throws CommandError (exit 2) on another header.
std::optional<long> for_each_front(const fs::path& csv,
                                   const std::function<void(const std::array<double, 4>&, std::string_view)>& row) {
  std::ifstream in(csv, std::ios::binary);
  if (!in) return std::nullopt;
  std::vector<char> buffer(1 << 20);
  in.rdbuf()->pubsetbuf(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  constexpr std::string_view kHeader = "t0,x0,t1,x1,kind,family";
  if (line != kHeader)
    throw CommandError(kExitInvalidInput,
                       csv.string() + ": expected the header '" + std::string(kHeader) + "', found '" + line + "'");
  long rows = 0;
  std::array<std::string_view, 6> f;
  std::array<double, 4> v{};
  while (std::getline(in, line)) {
    if (!front_fields(line, f)) continue;
    if (!parse_double(f[0], v[0]) || !parse_double(f[1], v[1]) || !parse_double(f[2], v[2]) ||
        !parse_double(f[3], v[3]))
      continue;
    row(v, f[4]);
    ++rows;
  }
  return rows;
}

/// fronts.csv as drawn: the segments that can be seen at the x-t diagram's resolution,
/// grouped by kind (one gnuplot data block per kind, in the order of `kinds`).
constexpr double kInf = std::numeric_limits<double>::infinity();

struct DecimatedFronts {
  long rows = 0;  ///< segments in fronts.csv
  long kept = 0;  ///< segments in the decimated file
  std::vector<std::pair<std::string, KindStyle>> kinds;
  double t_min = kInf, t_max = -kInf, x_min = kInf, x_max = -kInf;
};

/// The grid that decides what can be seen: about one cell per pixel of xt.png's plot area.
/// Two segments of one kind whose ends fall in the same cells draw the same pixels, and so do
/// two segments shorter than a cell in t and in x whose middles fall in one cell: only the
/// first is kept. A front made of pieces shorter than a pixel keeps one piece per pixel.
constexpr int kGridX = 800, kGridT = 560;
/// At most this many segments go to gnuplot; above it, the grid is coarsened.
constexpr long kMaxDrawnSegments = 300000;

/// Writes the decimated fronts of `csv` to `out` (t0,x0,t1,x1 in blocks by kind, each block
/// a gnuplot `index`). Two streaming passes (extents, then decimation); nullopt if fronts.csv
/// is missing or has no segment.
std::optional<DecimatedFronts> decimate_fronts(const fs::path& csv, const fs::path& out) {
  DecimatedFronts d;
  Distinct kind_names;
  const std::optional<long> rows = for_each_front(csv, [&](const std::array<double, 4>& v, std::string_view kind) {
    d.t_min = std::min({d.t_min, v[0], v[2]});
    d.t_max = std::max({d.t_max, v[0], v[2]});
    d.x_min = std::min({d.x_min, v[1], v[3]});
    d.x_max = std::max({d.x_max, v[1], v[3]});
    if (!kind_names.contains(std::string(kind))) kind_names.add(std::string(kind));
  });
  if (!rows || *rows == 0) return std::nullopt;
  d.rows = *rows;
  d.kinds = present_kinds(kind_names);
  std::map<std::string, std::size_t, std::less<>> kind_index;
  for (std::size_t k = 0; k < d.kinds.size(); ++k) kind_index[d.kinds[k].first] = k;

  std::vector<std::vector<std::array<double, 4>>> kept(d.kinds.size());
  for (int coarsening = 1;; coarsening *= 2) {
    const long nx = std::max(1, kGridX / coarsening), nt = std::max(1, kGridT / coarsening);
    const double sx = d.x_max > d.x_min ? static_cast<double>(nx) / (d.x_max - d.x_min) : 0.0;
    const double st = d.t_max > d.t_min ? static_cast<double>(nt) / (d.t_max - d.t_min) : 0.0;
    const auto cell = [&](double t, double x) -> std::uint64_t {
      const long i = std::clamp(static_cast<long>((x - d.x_min) * sx), 0L, nx);
      const long j = std::clamp(static_cast<long>((t - d.t_min) * st), 0L, nt);
      return static_cast<std::uint64_t>(j * (nx + 1) + i);
    };
    std::unordered_set<std::uint64_t> seen;
    for (auto& k : kept) k.clear();
    long count = 0;
    bool over = false;
    std::string_view last_kind;
    std::size_t last_index = 0;
    for_each_front(csv, [&](const std::array<double, 4>& v, std::string_view kind) {
      if (over) return;
      if (kind != last_kind) {
        last_index = kind_index.find(kind)->second;
        last_kind = kind_index.find(kind)->first;
      }
      std::uint64_t a = cell(v[0], v[1]), b = cell(v[2], v[3]);
      if (a > b) std::swap(a, b);
      // Shorter than a cell in t and in x: it draws one pixel, that of its middle.
      if (a != b && std::abs(v[3] - v[1]) * sx < 1.0 && std::abs(v[2] - v[0]) * st < 1.0)
        a = b = cell(0.5 * (v[0] + v[2]), 0.5 * (v[1] + v[3]));
      const std::uint64_t key = (static_cast<std::uint64_t>(last_index) << 42) ^ (a << 21) ^ b;
      if (!seen.insert(key).second) return;
      kept[last_index].push_back(v);
      if (++count > kMaxDrawnSegments) over = true;
    });
    if (!over || (nx == 1 && nt == 1)) {
      d.kept = count;
      break;
    }
  }
  std::ofstream file(out, std::ios::binary);
  file << "# The segments of fronts.csv that xt.png can show (written by `rigidity plot`): t0,x0,t1,x1,\n"
       << "# one block per kind (gnuplot index 0, 1, ...):";
  for (const auto& [kind, style] : d.kinds) file << " " << kind;
  file << "\n";
  for (std::size_t k = 0; k < kept.size(); ++k) {
    if (k > 0) file << "\n\n";
    for (const auto& v : kept[k])
      file << shortest(v[0]) << ',' << shortest(v[1]) << ',' << shortest(v[2]) << ',' << shortest(v[3]) << '\n';
  }
  file.close();
  if (!file) throw CommandError(kExitInternal, "cannot write " + out.string());
  return d;
}

/// An SI axis in a prefixed unit (µs, mm, ...) so that its tick labels stay short: the
/// factor that takes the data to it and its label.
struct ScaledAxis {
  double factor = 1.0;
  std::string label;
};
ScaledAxis scaled_axis(std::string_view name, Dimension dimension, UnitSystem units, double lo, double hi) {
  ScaledAxis axis{1.0, axis_label(name, dimension, units)};
  const std::string_view unit = unit_symbol(dimension, units);
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  if (units != UnitSystem::si || (unit != "m" && unit != "s") || !(magnitude > 0.0)) return axis;
  static constexpr std::pair<int, std::string_view> kPrefixes[] = {{-12, "p"}, {-9, "n"}, {-6, "µ"}, {-3, "m"},
                                                                   {0, ""},    {3, "k"},  {6, "M"},  {9, "G"}};
  const int exponent = std::clamp(3 * static_cast<int>(std::floor(std::log10(magnitude) / 3.0)), -12, 9);
  for (const auto& [e, prefix] : kPrefixes)
    if (e == exponent) {
      axis.factor = std::pow(10.0, -e);
      axis.label = std::string(name) + " [" + std::string(prefix) + std::string(unit) + "]";
    }
  return axis;
}

/// The x-t diagram of the decimated fronts in `data`: the diagram fills the figure, its
/// key in one small row below it.
std::string xt_script(const DecimatedFronts& fronts, const std::string& data, const RunInfo& run) {
  const ScaledAxis x = scaled_axis("x", Dimension::length, run.units, fronts.x_min, fronts.x_max);
  const ScaledAxis t = scaled_axis("t", Dimension::time, run.units, fronts.t_min, fronts.t_max);
  std::string out = script_header(
      "The x-t diagram of " + run.scene + ": every front segment of fronts.csv (t0,x0,t1,x1,kind,family) " +
          "drawn from (x0, t0) to (x1, t1), coloured by kind. " + std::to_string(fronts.rows) +
          " segments; the data file holds the " + std::to_string(fronts.kept) +
          " that can be seen at this resolution (of two that draw the same pixels, one).",
      "xt", 900, 650);
  out += "set title " + gnuplot_quote(run.scene + ": fronts in the lab frame") + "\n";
  out += "set xlabel " + gnuplot_quote(x.label) + "\n";
  out += "set ylabel " + gnuplot_quote(t.label) + "\n";
  out += "sx = " + shortest(x.factor) + "  # data to axis units\nst = " + shortest(t.factor) + "\n";
  if (fronts.x_max > fronts.x_min)
    out += "set xrange [" + shortest(fronts.x_min * x.factor) + ":" + shortest(fronts.x_max * x.factor) + "]\n";
  if (fronts.t_max > fronts.t_min)
    out += "set yrange [" + shortest(fronts.t_min * t.factor) + ":" + shortest(fronts.t_max * t.factor) + "]\n";
  out += "set xtics scale 0.5\nset ytics scale 0.5\n";
  out += "set key below horizontal center font ',9' samplen 2 spacing 1 width -2\n";
  out += "data = " + gnuplot_quote(data) + "\n";
  std::vector<std::string> elements;
  for (std::size_t k = 0; k < fronts.kinds.size(); ++k) {
    const KindStyle& style = fronts.kinds[k].second;
    elements.push_back("data index " + std::to_string(k) +
                       " using ($2*sx):($1*st):(($4-$2)*sx):(($3-$1)*st) with vectors nohead lw " +
                       std::string(style.width) + " lc rgb '" + std::string(style.colour) + "' title " +
                       gnuplot_quote(std::string(style.legend)));
  }
  return out + join_plot(elements);
}

/// Frames of animation.gif.
constexpr int kAnimationFrames = 60;
/// Above this many drawn segments the animation is skipped unless asked for (--animation):
/// 60 frames of it would take minutes.
constexpr long kAnimationMaxSegments = 20000;

/// The run as an animation (animation.gif), from the decimated fronts alone: above, the x-t
/// diagram drawn up to the frame's time; below, the bodies at that time, each front where it
/// is then (body ends in black, waves coloured by kind), so the fronts are seen running
/// through the bars, reflecting and letting go. For teaching the paper's scene.
std::optional<std::string> animation_script(const DecimatedFronts& fronts, const std::string& data,
                                            const RunInfo& run) {
  const double t_max = fronts.t_max, x_min = fronts.x_min, x_max = fronts.x_max;
  if (!(t_max > 0.0) || !(x_max > x_min)) return std::nullopt;
  const double margin = 0.05 * (x_max - x_min);
  std::string out = gnuplot_comment("An animation of " + run.scene + " from the fronts of " + data +
                                    " (t0,x0,t1,x1, one block per kind): " + std::to_string(kAnimationFrames) +
                                    " frames; above, the x-t diagram up to the frame's time; below, every front "
                                    "where it is at that time.");
  out += "# Written by `rigidity plot`; edit and rerun from this directory: gnuplot animation.gp\n";
  out += "set terminal gif animate delay 8 loop 0 size 900,700 font 'Sans,10' noenhanced\n";
  out += "set output 'animation.gif'\n";
  out += "set datafile separator ','\nset datafile missing NaN\nset grid lc rgb '#dddddd'\n";
  out += "data = " + gnuplot_quote(data) + "\n";
  out += "t_max = " + shortest(t_max) + "\n";
  out += "set xrange [" + shortest(x_min - margin) + ":" + shortest(x_max + margin) + "]\n";
  out += "set xlabel " + gnuplot_quote(axis_label("x", Dimension::length, run.units)) + "\n";
  // A segment drawn up to the frame's time, and where it is at that time.
  out += "frac(t0, t1) = t1 > t0 ? (T - t0)/(t1 - t0) : 1\n";
  out += "upto(t0, t1) = T < t0 ? NaN : (T > t1 ? 1 : frac(t0, t1))\n";
  out += "at(t0, x0, t1, x1) = (T >= t0 && T <= t1) ? x0 + (x1 - x0)*frac(t0, t1) : NaN\n";
  std::vector<std::string> diagram, strip;
  for (std::size_t k = 0; k < fronts.kinds.size(); ++k) {
    const auto& [kind, style] = fronts.kinds[k];
    const std::string block = "data index " + std::to_string(k);
    diagram.push_back(block + " using 2:1:(($4-$2)*upto($1,$3)):(($3-$1)*upto($1,$3)) with vectors nohead lw " +
                      std::string(style.width) + " lc rgb '" + std::string(style.colour) + "' title " +
                      gnuplot_quote(std::string(style.legend)));
    strip.push_back(block + " using (at($1,$2,$3,$4)):(-1):(0):(2) with vectors nohead lw " +
                    std::string(kind == "boundary" ? "3" : style.width) + " lc rgb '" + std::string(style.colour) +
                    "' notitle");
  }
  out += "do for [frame = 0:" + std::to_string(kAnimationFrames - 1) + "] {\n";
  out += "  T = t_max * frame / " + std::to_string(kAnimationFrames - 1) + ".0\n";
  out += "  set multiplot layout 2,1 title sprintf(" + gnuplot_quote(run.scene + ": t = %.4g") + ", T)\n";
  out += "  set size 1,0.68\n  set origin 0,0.3\n  set key top left opaque box font ',8'\n";
  out += "  set ylabel " + gnuplot_quote(axis_label("t", Dimension::time, run.units)) + "\n";
  out += "  set yrange [0:t_max]\n";
  out += "  set arrow 1 from graph 0, first T to graph 1, first T nohead lc rgb '#888888' dt 2\n";
  out += "  " + join_plot(diagram);
  out += "  unset arrow 1\n";
  out += "  set size 1,0.3\n  set origin 0,0\n  unset key\n  unset ytics\n  set ylabel 'fronts at t'\n";
  out += "  set yrange [-1.5:1.5]\n";
  out += "  " + join_plot(strip);
  out += "  set ytics\n  unset multiplot\n}\n";
  return out;
}

std::optional<std::string> probes_script(const fs::path& csv, const std::string& data, const RunInfo& run) {
  Distinct quantities;
  std::vector<std::pair<std::string, Distinct>> probes_of;  // quantity -> probes that sample it
  const std::optional<long> rows = for_each_row(csv, "t,probe,quantity,value", [&](const auto& f) {
    if (f.size() != 4) return;
    if (!quantities.contains(f[2])) probes_of.emplace_back(f[2], Distinct{});
    quantities.add(f[2]);
    for (auto& [quantity, probes] : probes_of)
      if (quantity == f[2]) probes.add(f[1]);
  });
  if (!rows || *rows == 0) return std::nullopt;

  const auto [panel_rows, panel_columns] = panel_grid(probes_of.size());
  std::string out = script_header(
      "Probe histories of " + run.scene + " from probes.csv (t,probe,quantity,value): one panel per quantity.",
      "probes", panel_columns == 1 ? 900 : 1300, 80 + 330 * panel_rows);
  out += "data = " + gnuplot_quote(data) + "\n";
  out += "set multiplot layout " + std::to_string(panel_rows) + "," + std::to_string(panel_columns) + " title " +
         gnuplot_quote(run.scene + ": probe histories") + "\n";
  out += "set xlabel " + gnuplot_quote(axis_label("t", Dimension::time, run.units)) + "\n";
  out += "set key top right\n";
  for (const auto& [quantity, probes] : probes_of) {
    out += "set title " + gnuplot_quote(quantity) + "\n";
    out += "set ylabel " + gnuplot_quote(quantity_label(quantity, run.units)) + "\n";
    // Front tracking's states hold between jumps: each jump drawn as a step at the first
    // sample past it, not as a ramp between samples; the lab position x is continuous.
    const std::string style = run.piecewise_constant && quantity != "x" ? "steps" : "lines";
    std::vector<std::string> elements;
    for (const std::string& probe : probes.values())
      elements.push_back("data skip 1 using 1:(strcol(2) eq " + gnuplot_quote(probe) + " && strcol(3) eq " +
                         gnuplot_quote(quantity) + " ? $4 : NaN) with " + style + " lw 2 title " +
                         gnuplot_quote(probe));
    out += join_plot(elements);
  }
  return out + "unset multiplot\n";
}

/// The profiles of snapshots.csv against the lab position: dir/snapshots_lab.csv
/// (t,body,x,quantity,value), each sample at the x the same snapshot gives its label. Only
/// when the snapshots sample x. Returns whether it was written.
bool write_lab_profiles(const fs::path& csv, const fs::path& out) {
  std::map<std::tuple<std::string, std::string, std::string>, std::string> x_of;  // (t, body, X) -> x
  std::vector<std::vector<std::string>> samples;
  const std::optional<long> rows = for_each_row(csv, "t,body,X,quantity,value", [&](const auto& f) {
    if (f.size() != 5) return;
    if (f[3] == "x") {
      x_of[{f[0], f[1], f[2]}] = f[4];
    } else if (f[3] != "X") {
      samples.push_back(f);
    }
  });
  if (!rows || x_of.empty() || samples.empty()) return false;
  std::ofstream file(out, std::ios::binary);
  file << "t,body,x,quantity,value\n";
  for (const auto& f : samples) {
    const auto x = x_of.find({f[0], f[1], f[2]});
    if (x != x_of.end()) file << f[0] << "," << f[1] << "," << x->second << "," << f[3] << "," << f[4] << "\n";
  }
  file.close();
  if (!file) throw CommandError(kExitInternal, "cannot write " + out.string());
  return true;
}

/// The initial lab position of each body, from the resolved scene the run wrote
/// (resolved_scene.yaml: `bodies:` as a block list of `- name:` with `position:`).
std::map<std::string, double> body_positions(const fs::path& run_dir) {
  std::map<std::string, double> positions;
  std::ifstream in(run_dir / "resolved_scene.yaml", std::ios::binary);
  std::string line, body;
  bool in_bodies = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && line[0] != ' ' && line[0] != '-') {
      in_bodies = line == "bodies:";
      continue;
    }
    if (!in_bodies) continue;
    const std::size_t name = line.find("- name: ");
    if (name != std::string::npos && line.find_first_not_of(' ') == name) {
      body = line.substr(name + 8);
      continue;
    }
    const std::size_t position = line.find("position: ");
    if (!body.empty() && position != std::string::npos && line.find_first_not_of(' ') == position)
      if (const auto x = parse_number(line.substr(position + 10))) positions[body] = *x;
  }
  return positions;
}

std::optional<std::string> profiles_script(const fs::path& csv, const std::string& data, const RunInfo& run, bool lab) {
  const std::string position = lab ? "x" : "X";
  Distinct times, bodies, quantities;
  const std::optional<long> rows = for_each_row(csv, "t,body," + position + ",quantity,value", [&](const auto& f) {
    if (f.size() != 5 || f[3] == position) return;  // X against X says nothing
    times.add(f[0]);
    bodies.add(f[1]);
    quantities.add(f[3]);
  });
  if (!rows || quantities.values().empty()) return std::nullopt;

  const auto [panel_rows, panel_columns] = panel_grid(quantities.values().size());
  std::string out =
      script_header("Snapshot profiles of " + run.scene +
                        (lab ? " against the lab position, from snapshots_lab.csv (t,body,x,quantity,value)"
                             : " from snapshots.csv (t,body,X,quantity,value)") +
                        ": one panel per quantity, one line per time (colour) and body (dash).",
                    lab ? "snapshots_lab" : "snapshots", panel_columns == 1 ? 900 : 1300, 80 + 330 * panel_rows);
  out += "data = " + gnuplot_quote(data) + "\n";
  out += "set palette defined (0 '#1f3b99', 0.5 '#2ca02c', 1 '#d62728')  # early to late\n";
  out += "unset colorbox\n";
  out += "set multiplot layout " + std::to_string(panel_rows) + "," + std::to_string(panel_columns) + " title " +
         gnuplot_quote(run.scene + (lab ? ": snapshots in the lab frame" : ": snapshots")) + "\n";
  // Several bodies against their labels: each body shifted by its initial position, so that
  // they lie side by side as in the scene rather than over one another from X = 0.
  std::map<std::string, double> offsets;
  if (!lab && bodies.values().size() > 1) offsets = body_positions(csv.parent_path());
  const bool side_by_side = !offsets.empty();
  out += "set xlabel " +
         gnuplot_quote(axis_label(lab            ? "x (lab position)"
                                  : side_by_side ? "X + the body's initial position (label, bodies side by side)"
                                                 : "X (label)",
                                  Dimension::length, run.units)) +
         "\n";
  out += "set key outside right top\n";
  // Front tracking's states are staircases: drawn as steps (each jump at the first sample
  // past it), not as ramps between samples; the lab position x, continuous in X, and
  // finite-volume profiles as lines.
  const std::size_t curves = times.values().size() * bodies.values().size();
  for (const std::string& quantity : quantities.values()) {
    out += "set title " + gnuplot_quote(quantity) + "\n";
    out += "set ylabel " + gnuplot_quote(quantity_label(quantity, run.units)) + "\n";
    const std::string style = run.piecewise_constant && quantity != "x" ? "steps" : "lines";
    std::vector<std::string> elements;
    for (std::size_t i = 0; i < times.values().size(); ++i) {
      const std::string& t = times.values()[i];
      const double fraction =
          times.values().size() > 1 ? static_cast<double>(i) / static_cast<double>(times.values().size() - 1) : 0.0;
      for (std::size_t b = 0; b < bodies.values().size(); ++b) {
        const std::string& body = bodies.values()[b];
        const std::size_t index = i * bodies.values().size() + b;
        const bool titled = curves <= 12 || index == 0 || index + 1 == curves;  // a readable key
        std::string title = "t = " + t + (bodies.values().size() > 1 ? " " + body : std::string());
        std::array<char, 32> frac{};
        std::snprintf(frac.data(), frac.size(), "%.4f", fraction);
        const auto offset = offsets.find(body);
        const std::string x_column =
            offset == offsets.end() || offset->second == 0.0 ? "3" : "($3+" + shortest(offset->second) + ")";
        elements.push_back("data skip 1 using " + x_column + ":(strcol(1) eq " + gnuplot_quote(t) +
                           " && strcol(2) eq " + gnuplot_quote(body) + " && strcol(4) eq " + gnuplot_quote(quantity) +
                           " ? $5 : NaN) with " + style + " lw 2 dt " + std::to_string(b % 5 + 1) +
                           " lc palette frac " + frac.data() +
                           (titled ? " title " + gnuplot_quote(title) : std::string(" notitle")));
      }
    }
    out += join_plot(elements);
  }
  return out + "unset multiplot\n";
}

std::optional<std::string> snapshots_script(const fs::path& csv, const std::string& data, const RunInfo& run) {
  return profiles_script(csv, data, run, false);
}

/// `target` as seen from `base` (relative if possible), for the scripts' data paths.
std::string path_from(const fs::path& base, const fs::path& target) {
  std::error_code error;
  const fs::path relative = fs::relative(target, base, error);
  if (!error && !relative.empty()) return relative.generic_string();
  return fs::absolute(target).generic_string();
}

}  // namespace

int plot_command(std::span<const std::string> args, std::ostream& out) {
  static constexpr OptionSpec kOptions[] = {{"--out", true}, {"--no-animation", false}, {"--animation", false}};
  const Arguments parsed = parse_arguments("plot", args, kOptions);
  if (parsed.help) {
    out << help("plot");
    return kExitOk;
  }
  if (parsed.positional.size() != 1) throw usage_error("plot", "plot takes one run directory");

  const fs::path run_dir = parsed.positional[0];
  std::error_code error;
  if (!fs::is_directory(run_dir, error))
    throw CommandError(kExitInvalidInput, "run directory " + run_dir.string() + " not found");
  constexpr std::string_view kRunFiles[] = {"summary.json", "fronts.csv", "probes.csv", "snapshots.csv"};
  if (std::none_of(std::begin(kRunFiles), std::end(kRunFiles),
                   [&](std::string_view f) { return fs::exists(run_dir / f, error); }))
    throw CommandError(kExitInvalidInput, run_dir.string() +
                                              " is not a run directory: it holds none of summary.json, fronts.csv, "
                                              "probes.csv, snapshots.csv (written by `rigidity run`)");

  const fs::path gnuplot = find_gnuplot();
  if (gnuplot.empty())
    throw CommandError(kExitInternal,
                       "gnuplot not found on PATH: `rigidity plot` draws with gnuplot "
                       "(Debian: apt-get install gnuplot-nox)");

  const fs::path out_dir = parsed.value("--out").value_or(run_dir.string());
  fs::create_directories(out_dir, error);
  if (!fs::is_directory(out_dir, error))
    throw CommandError(kExitInvalidInput, "cannot create the output directory " + out_dir.string());

  const RunInfo run = read_run_info(run_dir);
  std::vector<std::string> drawn;
  bool animated = false;
  // The x-t diagram, from fronts.csv decimated to what it can show (xt_fronts.csv).
  const fs::path fronts = run_dir / "fronts.csv";
  const fs::path fronts_data = out_dir / "xt_fronts.csv";
  const std::optional<DecimatedFronts> decimated =
      fs::exists(fronts, error) ? decimate_fronts(fronts, fronts_data) : std::nullopt;
  if (decimated) {
    render_gnuplot(gnuplot, out_dir, "xt", xt_script(*decimated, "xt_fronts.csv", run));
    drawn.emplace_back("xt");
  } else {
    out << "skipped xt.png: " << fronts.string() << (fs::exists(fronts, error) ? " has no data" : " not found") << "\n";
  }
  struct Plot {
    std::string_view name;
    std::string_view csv;
    std::optional<std::string> (*script)(const fs::path&, const std::string&, const RunInfo&);
  };
  constexpr Plot kPlots[] = {{"probes", "probes.csv", probes_script}, {"snapshots", "snapshots.csv", snapshots_script}};
  for (const Plot& plot : kPlots) {
    const fs::path csv = run_dir / plot.csv;
    const std::optional<std::string> script = plot.script(csv, path_from(out_dir, csv), run);
    if (!script) {
      out << "skipped " << plot.name << ".png: " << csv.string()
          << (fs::exists(csv, error) ? " has no data" : " not found") << "\n";
      continue;
    }
    render_gnuplot(gnuplot, out_dir, std::string(plot.name), *script);
    drawn.push_back(std::string(plot.name));
  }
  // The same profiles against the lab position, when the snapshots sample x.
  const fs::path snapshots = run_dir / "snapshots.csv";
  const fs::path lab = out_dir / "snapshots_lab.csv";
  if (fs::exists(snapshots, error) && write_lab_profiles(snapshots, lab)) {
    if (const std::optional<std::string> script = profiles_script(lab, path_from(out_dir, lab), run, true)) {
      render_gnuplot(gnuplot, out_dir, "snapshots_lab", *script);
      drawn.push_back("snapshots_lab");
    }
  }
  // The animation (a GIF of the x-t diagram growing, with the bodies below): skipped when
  // asked, and by default when the fronts are too many to animate within seconds.
  if (decimated && !parsed.has("--no-animation")) {
    if (decimated->kept > kAnimationMaxSegments && !parsed.has("--animation")) {
      out << "skipped animation.gif: " << decimated->kept << " front segments to draw (more than "
          << kAnimationMaxSegments << " take minutes to animate; --animation draws it anyway)\n";
    } else if (const std::optional<std::string> script = animation_script(*decimated, "xt_fronts.csv", run)) {
      render_gnuplot(gnuplot, out_dir, "animation", *script, "gif");
      animated = true;
    }
  }
  if (drawn.empty()) {
    out << "nothing to plot in " << run_dir.string() << "\n";
    return kExitOk;
  }
  out << "plots in " << out_dir.string() << (out_dir.string().ends_with('/') ? "" : "/") << ":";
  for (std::size_t i = 0; i < drawn.size(); ++i) out << (i == 0 ? " " : ", ") << drawn[i] << ".png";
  if (animated) out << ", animation.gif";
  out << " (gnuplot scripts beside them: ";
  for (std::size_t i = 0; i < drawn.size(); ++i) out << (i == 0 ? "" : ", ") << drawn[i] << ".gp";
  if (animated) out << ", animation.gp";
  out << ")\n";
  return kExitOk;
}

}  // namespace rigidity::cli
