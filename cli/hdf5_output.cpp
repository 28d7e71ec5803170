// run.h5: the whole run in one HDF5 file beside the CSV files (outputs.hdf5), written from
// those files once they are complete, so that both hold the same numbers to the bit:
//
//   /probes/<probe>/<quantity>/{t, value}
//   /snapshots/<body>/<quantity>/{t, X, value}
//   /fronts/{t0, x0, t1, x1, family, kind}    kind: codes, named by the attribute kind_names
//   /events/{t, x, kind, bodies}              kind and bodies as strings
//
// Each numeric dataset has an attribute `unit` (the scene's: SI or natural), the root the
// attributes `summary` (summary.json as text) and `units`.
#include "hdf5_output.hpp"

#include <hdf5.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "rigidity/quantity.hpp"
#include "rigidity/run_result.hpp"
#include "rigidity/units.hpp"

namespace rigidity::cli {
namespace {

namespace fs = std::filesystem;

/// An HDF5 handle closed with its own function when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("HDF5: cannot " + what);
  }
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  [[nodiscard]] hid_t id() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: cannot " + what);
}

/// The group at `path` (slash-separated, from the root), made with its parents.
hid_t group(hid_t file, const std::string& path) {
  if (H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0) return H5Gopen2(file, path.c_str(), H5P_DEFAULT);
  const Handle links(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "make a property list");
  check(H5Pset_create_intermediate_group(links.id(), 1), "set a property");
  return H5Gcreate2(file, path.c_str(), links.id(), H5P_DEFAULT, H5P_DEFAULT);
}

/// A text attribute (a variable-length UTF-8 string: h5py reads it as str).
void string_attribute(hid_t object, const char* name, const std::string& value) {
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "make a string type");
  check(H5Tset_size(type.id(), H5T_VARIABLE), "size a string type");
  check(H5Tset_cset(type.id(), H5T_CSET_UTF8), "set a string type's characters");
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose, "make a dataspace");
  const Handle attribute(H5Acreate2(object, name, type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                         std::string("make the attribute ") + name);
  const char* text = value.c_str();
  check(H5Awrite(attribute.id(), type.id(), &text), std::string("write the attribute ") + name);
}

/// A one-dimensional dataset `name` in `where` of doubles (H5T_IEEE_F64LE) or small integers.
template <class T>
void dataset(hid_t where, const std::string& name, const std::vector<T>& values, const std::string& unit = "") {
  const hsize_t size = values.size();
  const Handle space(H5Screate_simple(1, &size, nullptr), H5Sclose, "make a dataspace");
  const hid_t file_type = std::is_same_v<T, double> ? H5T_IEEE_F64LE : H5T_STD_I8LE;
  const hid_t memory_type = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_SCHAR;
  const Handle set(H5Dcreate2(where, name.c_str(), file_type, space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   H5Dclose, "make the dataset " + name);
  if (size > 0) check(H5Dwrite(set.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "write " + name);
  if (!unit.empty()) string_attribute(set.id(), "unit", unit);
}

/// A one-dimensional dataset of variable-length strings.
void strings(hid_t where, const std::string& name, const std::vector<std::string>& values) {
  const hsize_t size = values.size();
  const Handle space(H5Screate_simple(1, &size, nullptr), H5Sclose, "make a dataspace");
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "make a string type");
  check(H5Tset_size(type.id(), H5T_VARIABLE), "size a string type");
  check(H5Tset_cset(type.id(), H5T_CSET_UTF8), "set a string type's characters");
  const Handle set(H5Dcreate2(where, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   H5Dclose, "make the dataset " + name);
  std::vector<const char*> pointers;
  for (const std::string& v : values) pointers.push_back(v.c_str());
  if (size > 0) check(H5Dwrite(set.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()), "write " + name);
}

/// The rows of a CSV file written by the run (no quoting: names are identifiers), header apart.
std::vector<std::vector<std::string>> rows_of(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  if (!in) return rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream split(line);
    std::string field;
    while (std::getline(split, field, ',')) fields.push_back(field);
    rows.push_back(std::move(fields));
  }
  return rows;
}

double number_of(const std::string& text, const fs::path& file) {
  std::size_t used = 0;
  const double value = std::stod(text, &used);
  if (used != text.size()) throw std::runtime_error("run.h5: '" + text + "' in " + file.string() + " is no number");
  return value;
}

std::string unit_of_quantity(const std::string& name, UnitSystem units) {
  const std::optional<Quantity> q = quantity_from_string(name);
  return q ? std::string(unit_symbol(dimension_of(*q), units)) : std::string();
}

void write_file(const fs::path& dir, const fs::path& path, UnitSystem units) {
  const Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                    "create " + path.string());
  const std::string time = std::string(unit_symbol(Dimension::time, units));
  const std::string length = std::string(unit_symbol(Dimension::length, units));
  {
    std::ifstream summary(dir / "summary.json");
    std::stringstream text;
    text << summary.rdbuf();
    string_attribute(file.id(), "summary", text.str());
    string_attribute(file.id(), "units", units == UnitSystem::si ? "si" : "natural");
  }
  // probes.csv: t,probe,quantity,value
  std::map<std::pair<std::string, std::string>, std::pair<std::vector<double>, std::vector<double>>> probes;
  for (const auto& row : rows_of(dir / "probes.csv")) {
    if (row.size() != 4) throw std::runtime_error("run.h5: probes.csv has a row of " + std::to_string(row.size()));
    auto& [t, value] = probes[{row[1], row[2]}];
    t.push_back(number_of(row[0], dir / "probes.csv"));
    value.push_back(number_of(row[3], dir / "probes.csv"));
  }
  for (const auto& [key, columns] : probes) {
    const Handle g(group(file.id(), "/probes/" + key.first + "/" + key.second), H5Gclose, "make a group");
    dataset(g.id(), "t", columns.first, time);
    dataset(g.id(), "value", columns.second, unit_of_quantity(key.second, units));
  }
  // snapshots.csv: t,body,X,quantity,value
  struct Snapshot {
    std::vector<double> t, X, value;
  };
  std::map<std::pair<std::string, std::string>, Snapshot> snapshots;
  for (const auto& row : rows_of(dir / "snapshots.csv")) {
    if (row.size() != 5) throw std::runtime_error("run.h5: snapshots.csv has a row of " + std::to_string(row.size()));
    Snapshot& s = snapshots[{row[1], row[3]}];
    s.t.push_back(number_of(row[0], dir / "snapshots.csv"));
    s.X.push_back(number_of(row[2], dir / "snapshots.csv"));
    s.value.push_back(number_of(row[4], dir / "snapshots.csv"));
  }
  for (const auto& [key, s] : snapshots) {
    const Handle g(group(file.id(), "/snapshots/" + key.first + "/" + key.second), H5Gclose, "make a group");
    dataset(g.id(), "t", s.t, time);
    dataset(g.id(), "X", s.X, length);
    dataset(g.id(), "value", s.value, unit_of_quantity(key.second, units));
  }
  // fronts.csv: t0,x0,t1,x1,kind,family
  if (fs::exists(dir / "fronts.csv")) {
    std::vector<double> t0, x0, t1, x1;
    std::vector<signed char> family, kind;
    constexpr SegmentKind kKinds[] = {SegmentKind::shock, SegmentKind::contact, SegmentKind::rarefaction,
                                      SegmentKind::interface, SegmentKind::boundary};
    std::string names;
    for (const SegmentKind k : kKinds) names += (names.empty() ? "" : ",") + std::string(to_string(k));
    for (const auto& row : rows_of(dir / "fronts.csv")) {
      if (row.size() != 6) throw std::runtime_error("run.h5: fronts.csv has a row of " + std::to_string(row.size()));
      t0.push_back(number_of(row[0], dir / "fronts.csv"));
      x0.push_back(number_of(row[1], dir / "fronts.csv"));
      t1.push_back(number_of(row[2], dir / "fronts.csv"));
      x1.push_back(number_of(row[3], dir / "fronts.csv"));
      signed char code = -1;
      for (std::size_t i = 0; i < std::size(kKinds); ++i)
        if (row[4] == to_string(kKinds[i])) code = static_cast<signed char>(i);
      kind.push_back(code);
      family.push_back(static_cast<signed char>(number_of(row[5], dir / "fronts.csv")));
    }
    const Handle g(group(file.id(), "/fronts"), H5Gclose, "make a group");
    dataset(g.id(), "t0", t0, time);
    dataset(g.id(), "x0", x0, length);
    dataset(g.id(), "t1", t1, time);
    dataset(g.id(), "x1", x1, length);
    dataset(g.id(), "family", family);
    dataset(g.id(), "kind", kind);
    string_attribute(g.id(), "kind_names", names);
  }
  // events.csv: t,kind,x,bodies
  std::vector<double> t, x;
  std::vector<std::string> kinds, bodies;
  for (const auto& row : rows_of(dir / "events.csv")) {
    if (row.size() < 3) throw std::runtime_error("run.h5: events.csv has a row of " + std::to_string(row.size()));
    t.push_back(number_of(row[0], dir / "events.csv"));
    kinds.push_back(row[1]);
    x.push_back(number_of(row[2], dir / "events.csv"));
    bodies.push_back(row.size() > 3 ? row[3] : std::string());
  }
  const Handle g(group(file.id(), "/events"), H5Gclose, "make a group");
  dataset(g.id(), "t", t, time);
  dataset(g.id(), "x", x, length);
  strings(g.id(), "kind", kinds);
  strings(g.id(), "bodies", bodies);
}

}  // namespace

void write_hdf5(const std::string& dir, UnitSystem units) {
  const fs::path final_path = fs::path(dir) / "run.h5";
  const fs::path partial = fs::path(dir) / ".run.h5.partial";
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported by exception, not printed
  try {
    write_file(dir, partial, units);
  } catch (...) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw;
  }
  fs::rename(partial, final_path);
}

}  // namespace rigidity::cli
