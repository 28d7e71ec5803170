// The run output directory (docs/cli.md, "What a run writes"): summary.json, probes.csv, snapshots.csv,
// fronts.csv, events.csv and resolved_scene.yaml, streamed into a temporary
// directory as the solver produces them and renamed into place whole at the end.
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
    throw OutputError(std::string(what) + " " + path_.string() + ": " + std::strerror(errno));
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

// ---- the directory, replaced whole --------------------------------------------------

/// The directory `dir` names, without a trailing separator.
fs::path output_path(const std::string& dir) {
  fs::path path = fs::path(dir).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();
  const fs::path name = path.filename();
  if (name.empty() || name == "." || name == "..")
    throw OutputError("output directory '" + dir + "' must name a directory of its own: it is replaced as a whole");
  return path;
}

/// Refuses to replace anything but an earlier run's output (or an empty directory):
/// `--out ~` must not wipe a home directory.
}  // namespace

bool is_run_file(std::string_view name) {
  static constexpr std::string_view kRunFiles[] = {
      "summary.json", "events.csv", "probes.csv",    "snapshots.csv", "fronts.csv", "resolved_scene.yaml",
      "xt.png",       "probes.png", "snapshots.png", "xt.gp",         "probes.gp",  "snapshots.gp"};
  for (std::string_view file : kRunFiles)
    if (name == file) return true;
  return false;
}

namespace {

void check_replaceable(const fs::path& target) {
  const fs::file_status status = fs::status(target);
  if (!fs::exists(status)) return;
  if (!fs::is_directory(status))
    throw OutputRefused("output directory " + target.string() + " exists and is not a directory");
  if (!fs::is_empty(target) && !fs::exists(target / "summary.json"))
    throw OutputRefused("refusing to write a run into " + target.string() +
                        ": it is not empty and holds no earlier run (no summary.json); give --out an empty "
                        "or new directory");
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
  throw OutputError("cannot find a free name for a temporary directory beside " + target.string());
}

/// The temporary sibling the outputs are written into; removed unless committed.
class TemporaryDirectory {
 public:
  explicit TemporaryDirectory(const fs::path& target) {
    for (int attempt = 0; attempt < 100 && path_.empty(); ++attempt) {
      fs::path candidate = unused_sibling(target, "tmp");
      if (fs::create_directory(candidate)) path_ = std::move(candidate);  // false: taken meanwhile
    }
    if (path_.empty()) throw OutputError("cannot create a temporary directory beside " + target.string());
  }
  ~TemporaryDirectory() {
    if (path_.empty()) return;
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  [[nodiscard]] const fs::path& path() const { return path_; }

  /// Renames the directory to `target`, replacing the earlier run there. The files there
  /// that are not a run's own (is_run_file) move into the new run first, so they stay. At
  /// every moment `target` holds the complete old run or the complete new run (or is absent
  /// for the instant of the swap), and a failure puts every moved file back.
  void commit(const fs::path& target) {
    if (!fs::exists(fs::symlink_status(target))) {
      fs::rename(path_, target);
      path_.clear();
      return;
    }
    std::vector<std::string> kept;  // the user's files, moved into the new run
    const auto move_back = [&] {
      std::error_code ignored;
      for (const std::string& name : kept) fs::rename(path_ / name, target / name, ignored);
    };
    try {
      for (const fs::directory_entry& entry : fs::directory_iterator(target)) {
        const std::string name = entry.path().filename().string();
        if (is_run_file(name)) continue;
        fs::rename(entry.path(), path_ / name);
        kept.push_back(name);
      }
    } catch (...) {
      move_back();
      throw;
    }
    const fs::path old = unused_sibling(target, "old");
    try {
      fs::rename(target, old);
    } catch (...) {
      move_back();
      throw;
    }
    try {
      fs::rename(path_, target);
    } catch (...) {
      std::error_code ignored;
      fs::rename(old, target, ignored);
      move_back();
      throw;
    }
    std::error_code ignored;
    fs::remove_all(old, ignored);
    path_.clear();
  }

 private:
  fs::path path_;
};

/// The parent directories of `target` that do not exist yet, created; removed again
/// (if still empty) unless kept, so that a failed run leaves nothing behind.
class CreatedParents {
 public:
  explicit CreatedParents(const fs::path& target) {
    for (fs::path p = target.parent_path(); !p.empty() && !fs::exists(fs::symlink_status(p)); p = p.parent_path()) {
      created_.push_back(p);
      if (p == p.parent_path()) break;
    }
    if (target.has_parent_path()) fs::create_directories(target.parent_path());
  }
  ~CreatedParents() {
    for (const fs::path& p : created_) {  // deepest first
      std::error_code ignored;
      fs::remove(p, ignored);  // fails harmlessly if something else is there now
    }
  }
  CreatedParents(const CreatedParents&) = delete;
  CreatedParents& operator=(const CreatedParents&) = delete;
  void keep() { created_.clear(); }

 private:
  std::vector<fs::path> created_;
};

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ";") + name;
  return out;
}

/// `what` for a filesystem error, as an OutputError.
template <class F>
auto filesystem_step(const char* what, F&& step) {
  try {
    return step();
  } catch (const fs::filesystem_error& e) {
    throw OutputError(std::string(what) + ": " + e.what());
  }
}

}  // namespace

// ---- the streaming recorder ---------------------------------------------------------

struct StreamingRecorder::Files {
  Files(const Scene& s, const fs::path& t) : scene(s), target(t), parents(t), temporary(t) {}

  const Scene& scene;
  fs::path target;
  CreatedParents parents;
  TemporaryDirectory temporary;
  std::unique_ptr<BufferedFile> probes, snapshots, fronts, events;
  std::vector<std::string> probe_names, body_names;  ///< CSV fields
  long front_count = 0;

  [[nodiscard]] std::string nothing_written() const { return "; nothing was written to " + target.string(); }

  void probe(const ProbeSample& sample) {
    if (!probes) return;  // the scene asks for none
    const std::vector<ProbeDecl>& decls = scene.outputs.probes;
    if (sample.probe < 0 || static_cast<std::size_t>(sample.probe) >= decls.size())
      throw OutputError("probes.csv: a sample refers to probe " + std::to_string(sample.probe) +
                        " but the scene declares " + std::to_string(decls.size()));
    const auto where = [&] {
      return "probes.csv: probe '" + decls[sample.probe].name + "' quantity " + std::string(to_string(sample.quantity));
    };
    const double t = output_value(sample.t, Dimension::time, scene.units, [&] { return where() + ": t"; });
    const double value = output_value(sample.value, dimension_of(sample.quantity), scene.units,
                                      [&] { return where() + " at t = " + short_number(t) + ": value"; });
    BufferedFile& file = *probes;
    file.number(t);
    file.put(',');
    file.put(probe_names[sample.probe]);
    file.put(',');
    file.put(to_string(sample.quantity));
    file.put(',');
    file.number(value);
    file.put('\n');
  }

  void snapshot(const SnapshotSample& sample) {
    if (!snapshots) return;
    if (sample.body < 0 || static_cast<std::size_t>(sample.body) >= body_names.size())
      throw OutputError("snapshots.csv: a sample refers to body " + std::to_string(sample.body) +
                        " but the scene has " + std::to_string(body_names.size()));
    const auto where = [&] {
      return "snapshots.csv: body '" + scene.bodies[sample.body].name + "' quantity " +
             std::string(to_string(sample.quantity));
    };
    const double t = output_value(sample.t, Dimension::time, scene.units, [&] { return where() + ": t"; });
    const double X = output_value(sample.X, Dimension::length, scene.units,
                                  [&] { return where() + " at t = " + short_number(t) + ": X"; });
    const double value = output_value(sample.value, dimension_of(sample.quantity), scene.units, [&] {
      return where() + " at t = " + short_number(t) + ", X = " + short_number(X) + ": value";
    });
    BufferedFile& file = *snapshots;
    file.number(t);
    file.put(',');
    file.put(body_names[sample.body]);
    file.put(',');
    file.number(X);
    file.put(',');
    file.put(to_string(sample.quantity));
    file.put(',');
    file.number(value);
    file.put('\n');
  }

  void front(const FrontSegment& front) {
    const long i = front_count++;
    if (!fronts) return;
    const auto where = [&](const char* column) {
      return [&i, column] { return "fronts.csv: front segment " + std::to_string(i) + ": " + column; };
    };
    BufferedFile& file = *fronts;
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

  void event(const RunEvent& event) {
    const auto where = [&](const char* column) {
      return [&event, column] { return "events.csv: event '" + event.kind + "': " + column; };
    };
    BufferedFile& file = *events;
    file.number(output_value(event.t, Dimension::time, scene.units, where("t")));
    file.put(',');
    file.put(csv_field(event.kind));
    file.put(',');
    file.number(output_value(event.x, Dimension::length, scene.units, where("x")));
    file.put(',');
    file.put(csv_field(join_names(event.bodies)));
    file.put('\n');
  }
};

StreamingRecorder::StreamingRecorder(const Scene& scene, const std::string& dir) {
  const fs::path target = output_path(dir);
  filesystem_step("cannot prepare the output directory", [&] {
    check_replaceable(target);
    files_ = std::make_unique<Files>(scene, target);
  });
  Files& f = *files_;
  const fs::path& tmp = f.temporary.path();
  for (const ProbeDecl& probe : scene.outputs.probes) f.probe_names.push_back(csv_field(probe.name));
  for (const BodyDecl& body : scene.bodies) f.body_names.push_back(csv_field(body.name));
  f.events = std::make_unique<BufferedFile>(tmp / "events.csv");
  f.events->put("t,kind,x,bodies\n");
  if (!scene.outputs.probes.empty()) {
    f.probes = std::make_unique<BufferedFile>(tmp / "probes.csv");
    f.probes->put("t,probe,quantity,value\n");
  }
  if (!scene.outputs.snapshots.empty()) {
    f.snapshots = std::make_unique<BufferedFile>(tmp / "snapshots.csv");
    f.snapshots->put("t,body,X,quantity,value\n");
  }
  if (scene.outputs.fronts) {
    f.fronts = std::make_unique<BufferedFile>(tmp / "fronts.csv");
    f.fronts->put("t0,x0,t1,x1,kind,family\n");
  }
}

StreamingRecorder::~StreamingRecorder() = default;

const fs::path& StreamingRecorder::target() const { return files_->target; }

// A non-finite value is refused where it arrives, and the run fails with nothing written.
void StreamingRecorder::record_front(const FrontSegment& segment) {
  try {
    files_->front(segment);
  } catch (const NumericalError& e) {
    throw NumericalError(e.what() + files_->nothing_written());
  }
}

void StreamingRecorder::record_probe(const ProbeSample& sample) {
  try {
    files_->probe(sample);
  } catch (const NumericalError& e) {
    throw NumericalError(e.what() + files_->nothing_written());
  }
}

void StreamingRecorder::record_snapshot(const SnapshotSample& sample) {
  try {
    files_->snapshot(sample);
  } catch (const NumericalError& e) {
    throw NumericalError(e.what() + files_->nothing_written());
  }
}

void StreamingRecorder::record_event(const RunEvent& event) {
  try {
    files_->event(event);
  } catch (const NumericalError& e) {
    throw NumericalError(e.what() + files_->nothing_written());
  }
}

void StreamingRecorder::commit(const RunResult& result) {
  Files& f = *files_;
  std::string summary;
  try {
    summary = summary_json(f.scene, result);
  } catch (const NumericalError& e) {
    throw NumericalError(e.what() + f.nothing_written());
  }
  for (std::unique_ptr<BufferedFile>* file : {&f.events, &f.probes, &f.snapshots, &f.fronts})
    if (*file) (*file)->close();
  const fs::path& tmp = f.temporary.path();
  write_text_file(tmp / "summary.json", summary);
  write_text_file(tmp / "resolved_scene.yaml", f.scene.resolved_yaml());
  filesystem_step("cannot move the outputs into place", [&] { f.temporary.commit(f.target); });
  f.parents.keep();
}

void write_run(const Scene& scene, const RunResult& result, const std::string& dir) {
  const fs::path target = output_path(dir);
  try {
    (void)summary_json(scene, result);  // checked before anything touches the disk
  } catch (const NumericalError& e) {
    throw NumericalError(std::string(e.what()) + "; nothing was written to " + target.string());
  }
  StreamingRecorder recorder(scene, dir);
  for (const RunEvent& event : result.events) recorder.event(event);
  for (const ProbeSample& sample : result.probes) recorder.probe(sample);
  for (const SnapshotSample& sample : result.snapshots) recorder.snapshot(sample);
  for (const FrontSegment& front : result.fronts) recorder.front(front);
  recorder.commit(result);
}

}  // namespace rigidity
