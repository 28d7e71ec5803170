// The run output directory (SPEC §5): summary.json, probes.csv, snapshots.csv,
// fronts.csv and resolved_scene.yaml, written whole or not at all.
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/json_writer.hpp"
#include "rigidity/output.hpp"

namespace rigidity {

namespace fs = std::filesystem;

namespace {

// ---- buffered file ------------------------------------------------------------

/// A file written through a large buffer: numbers go straight from std::to_chars
/// into it, so millions of CSV rows cost no per-row stream formatting.
class BufferedFile {
 public:
  explicit BufferedFile(fs::path path) : path_(std::move(path)), file_(std::fopen(path_.c_str(), "wb")) {
    if (file_ == nullptr) fail("cannot create");
    buffer_.reserve(kCapacity);
  }
  ~BufferedFile() {
    if (file_ != nullptr) std::fclose(file_);
  }
  BufferedFile(const BufferedFile&) = delete;
  BufferedFile& operator=(const BufferedFile&) = delete;

  void put(std::string_view text) {
    if (buffer_.size() + text.size() > kCapacity) flush();
    buffer_.append(text);
  }
  void put(char c) {
    if (buffer_.size() + 1 > kCapacity) flush();
    buffer_.push_back(c);
  }
  /// The shortest form that reads back to the same double; -0 as 0. \pre finite
  void number(double value) {
    if (value == 0.0) value = 0.0;
    std::array<char, 32> digits{};
    const auto result = std::to_chars(digits.data(), digits.data() + digits.size(), value);
    put(std::string_view(digits.data(), static_cast<std::size_t>(result.ptr - digits.data())));
  }
  void integer(long value) {
    std::array<char, 24> digits{};
    const auto result = std::to_chars(digits.data(), digits.data() + digits.size(), value);
    put(std::string_view(digits.data(), static_cast<std::size_t>(result.ptr - digits.data())));
  }

  /// Flushes and closes, reporting any write error (a full disk shows up here).
  void close() {
    flush();
    std::FILE* file = file_;
    file_ = nullptr;
    if (std::fclose(file) != 0) fail("cannot write");
  }

 private:
  static constexpr std::size_t kCapacity = std::size_t{1} << 20;

  void flush() {
    if (buffer_.empty()) return;
    if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) fail("cannot write");
    buffer_.clear();
  }
  [[noreturn]] void fail(const char* what) const {
    throw std::runtime_error(std::string(what) + " " + path_.string() + ": " + std::strerror(errno));
  }

  fs::path path_;
  std::FILE* file_;
  std::string buffer_;
};

void write_text_file(const fs::path& path, std::string_view text) {
  BufferedFile file(path);
  file.put(text);
  file.close();
}

/// A CSV field: quoted (RFC 4180) only if it holds a comma, a quote or a line break.
std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + '"';
}

// ---- values in the scene's units, never NaN or inf -------------------------------

std::string short_number(double value) {
  std::string out;
  if (std::isfinite(value)) {
    append_shortest(out, value);
  } else {
    out = std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  }
  return out;
}

/// `natural_value` in the scene's units. \throws NumericalError, naming the value
/// by describe() (called only then), if it is not finite.
template <class Describe>
double output_value(double natural_value, Dimension dimension, UnitSystem units, const Describe& describe) {
  const double value = from_natural(natural_value, dimension, units);
  if (!std::isfinite(value)) [[unlikely]]
    throw NumericalError(describe() + " is " + short_number(value) + " (no NaN or inf is ever written)");
  return value;
}

// ---- the CSV files ----------------------------------------------------------------

void write_probes(const fs::path& path, const Scene& scene, const RunResult& result) {
  const std::vector<ProbeDecl>& probes = scene.outputs.probes;
  std::vector<std::string> names;
  for (const ProbeDecl& probe : probes) names.push_back(csv_field(probe.name));

  BufferedFile file(path);
  file.put("t,probe,quantity,value\n");
  for (const ProbeSample& sample : result.probes) {
    if (sample.probe < 0 || static_cast<std::size_t>(sample.probe) >= probes.size())
      throw std::runtime_error("probes.csv: a sample refers to probe " + std::to_string(sample.probe) +
                               " but the scene declares " + std::to_string(probes.size()));
    const auto where = [&] {
      return "probes.csv: probe '" + probes[sample.probe].name + "' quantity " +
             std::string(to_string(sample.quantity));
    };
    const double t = output_value(sample.t, Dimension::time, scene.units, [&] { return where() + ": t"; });
    const double value = output_value(sample.value, dimension_of(sample.quantity), scene.units,
                                      [&] { return where() + " at t = " + short_number(t) + ": value"; });
    file.number(t);
    file.put(',');
    file.put(names[sample.probe]);
    file.put(',');
    file.put(to_string(sample.quantity));
    file.put(',');
    file.number(value);
    file.put('\n');
  }
  file.close();
}

void write_snapshots(const fs::path& path, const Scene& scene, const RunResult& result) {
  std::vector<std::string> names;
  for (const std::string& name : result.body_names) names.push_back(csv_field(name));

  BufferedFile file(path);
  file.put("t,body,X,quantity,value\n");
  for (const SnapshotSample& sample : result.snapshots) {
    if (sample.body < 0 || static_cast<std::size_t>(sample.body) >= names.size())
      throw std::runtime_error("snapshots.csv: a sample refers to body " + std::to_string(sample.body) +
                               " but the run names " + std::to_string(names.size()));
    const auto where = [&] {
      return "snapshots.csv: body '" + result.body_names[sample.body] + "' quantity " +
             std::string(to_string(sample.quantity));
    };
    const double t = output_value(sample.t, Dimension::time, scene.units, [&] { return where() + ": t"; });
    const double X = output_value(sample.X, Dimension::length, scene.units,
                                  [&] { return where() + " at t = " + short_number(t) + ": X"; });
    const double value = output_value(sample.value, dimension_of(sample.quantity), scene.units, [&] {
      return where() + " at t = " + short_number(t) + ", X = " + short_number(X) + ": value";
    });
    file.number(t);
    file.put(',');
    file.put(names[sample.body]);
    file.put(',');
    file.number(X);
    file.put(',');
    file.put(to_string(sample.quantity));
    file.put(',');
    file.number(value);
    file.put('\n');
  }
  file.close();
}

void write_fronts(const fs::path& path, const Scene& scene, const RunResult& result) {
  BufferedFile file(path);
  file.put("t0,x0,t1,x1,kind,family\n");
  for (std::size_t i = 0; i < result.fronts.size(); ++i) {
    const FrontSegment& front = result.fronts[i];
    const auto where = [&](const char* column) {
      return [&i, column] { return "fronts.csv: front segment " + std::to_string(i) + ": " + column; };
    };
    file.number(output_value(front.t0, Dimension::time, scene.units, where("t0")));
    file.put(',');
    file.number(output_value(front.x0, Dimension::length, scene.units, where("x0")));
    file.put(',');
    file.number(output_value(front.t1, Dimension::time, scene.units, where("t1")));
    file.put(',');
    file.number(output_value(front.x1, Dimension::length, scene.units, where("x1")));
    file.put(',');
    file.put(to_string(front.kind));
    file.put(',');
    file.integer(front.family);
    file.put('\n');
  }
  file.close();
}

// ---- the directory, replaced whole --------------------------------------------------

/// The directory `dir` names, without a trailing separator.
fs::path output_path(const std::string& dir) {
  fs::path path = fs::path(dir).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();
  const fs::path name = path.filename();
  if (name.empty() || name == "." || name == "..")
    throw std::runtime_error("output directory '" + dir +
                             "' must name a directory of its own: it is replaced as a whole");
  return path;
}

/// Refuses to replace anything but an earlier run's output (or an empty directory):
/// `--out ~` must not wipe a home directory.
void check_replaceable(const fs::path& target) {
  const fs::file_status status = fs::status(target);
  if (!fs::exists(status)) return;
  if (!fs::is_directory(status))
    throw std::runtime_error("output directory " + target.string() + " exists and is not a directory");
  if (!fs::is_empty(target) && !fs::exists(target / "summary.json"))
    throw std::runtime_error("refusing to replace " + target.string() +
                             ": it is not empty and holds no earlier run (no summary.json)");
}

/// A sibling of `target` named "<target>.<tag>-XXXXXX" that does not exist yet.
fs::path unused_sibling(const fs::path& target, std::string_view tag) {
  thread_local std::mt19937_64 random{std::random_device{}()};
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::array<char, 16> hex{};
    const auto result = std::to_chars(hex.data(), hex.data() + hex.size(), random() & 0xFFFFFF, 16);
    std::string suffix = ".";
    suffix.append(tag).append(1, '-').append(hex.data(), result.ptr);
    fs::path candidate = target;
    candidate += suffix;
    if (!fs::exists(fs::symlink_status(candidate))) return candidate;
  }
  throw std::runtime_error("cannot find a free name for a temporary directory beside " + target.string());
}

/// The temporary sibling the outputs are written into; removed unless committed.
class TemporaryDirectory {
 public:
  explicit TemporaryDirectory(const fs::path& target) {
    for (int attempt = 0; attempt < 100 && path_.empty(); ++attempt) {
      fs::path candidate = unused_sibling(target, "tmp");
      if (fs::create_directory(candidate)) path_ = std::move(candidate);  // false: taken meanwhile
    }
    if (path_.empty()) throw std::runtime_error("cannot create a temporary directory beside " + target.string());
  }
  ~TemporaryDirectory() {
    if (path_.empty()) return;
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  [[nodiscard]] const fs::path& path() const { return path_; }

  /// Renames the directory to `target`, replacing what is there. At every moment
  /// `target` is the complete old run, absent, or the complete new run.
  void commit(const fs::path& target) {
    if (!fs::exists(fs::symlink_status(target))) {
      fs::rename(path_, target);
    } else {
      const fs::path old = unused_sibling(target, "old");
      fs::rename(target, old);
      try {
        fs::rename(path_, target);
      } catch (...) {
        std::error_code ignored;
        fs::rename(old, target, ignored);
        throw;
      }
      std::error_code ignored;
      fs::remove_all(old, ignored);
    }
    path_.clear();
  }

 private:
  fs::path path_;
};

}  // namespace

void write_run(const Scene& scene, const RunResult& result, const std::string& dir) {
  const fs::path target = output_path(dir);
  try {
    const std::string summary = summary_json(scene, result);  // checked before anything touches the disk
    check_replaceable(target);
    if (target.has_parent_path()) fs::create_directories(target.parent_path());

    TemporaryDirectory temporary(target);
    write_text_file(temporary.path() / "summary.json", summary);
    if (!scene.outputs.probes.empty()) write_probes(temporary.path() / "probes.csv", scene, result);
    if (!scene.outputs.snapshots.empty()) write_snapshots(temporary.path() / "snapshots.csv", scene, result);
    if (scene.outputs.fronts) write_fronts(temporary.path() / "fronts.csv", scene, result);
    write_text_file(temporary.path() / "resolved_scene.yaml", scene.resolved_yaml);
    temporary.commit(target);
  } catch (const NumericalError& error) {
    throw NumericalError(std::string(error.what()) + "; nothing was written to " + target.string());
  }
}

}  // namespace rigidity
