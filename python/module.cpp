// rigidity's Python binding (the module rigidity._rigidity; the package rigidity/__init__.py
// shapes it as docs/python.md describes): scenes run in process with the GIL released (taken back
// every 0.1 s to run Python's signal handlers: Ctrl-C stops a run), their outputs handed over
// as NumPy arrays; materials built through the registry, their laws vectorised in
// C++; the exact Riemann problem; errors as Python exceptions carrying the file/line/key text.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "rigidity/errors.hpp"
#include "rigidity/output.hpp"
#include "rigidity/plugins.hpp"
#include "rigidity/quantity.hpp"
#include "rigidity/registry.hpp"
#include "rigidity/run_recorder.hpp"
#include "rigidity/scene_loader.hpp"
#include "rigidity/solvers/riemann.hpp"
#include "rigidity/solvers/solve.hpp"
#include "rigidity/solvers/wall_impact.hpp"
#include "rigidity/sweep.hpp"
#include "rigidity/units.hpp"

namespace py = pybind11;

namespace {

using rigidity::Material;
using rigidity::Stretch;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A solved scene: the scene as run and what the solver handed back.
struct Run {
  rigidity::Scene scene;
  rigidity::RunResult result;
};

/// How often a run looks at the Python signal handlers' flags [s of wall-clock time].
constexpr double kSignalCheckInterval_s = 0.1;

Run run_scene(rigidity::Scene scene) {
  Run run{std::move(scene), {}};
  // The exception a Python signal handler raised during the run (KeyboardInterrupt for Ctrl-C),
  // held with the GIL and raised once the run has stopped, with the run up to then attached.
  std::optional<py::error_already_set> raised;
  {
    rigidity::MemoryRecorder recorder;
    recorder.on_progress(
        [&raised, &recorder](const rigidity::RunProgress&) {
          if (raised) return;
          py::gil_scoped_acquire acquire;
          if (PyErr_CheckSignals() == 0) return;  // runs the handlers of signals caught since the last check
          raised.emplace();                       // takes the exception from the interpreter
          recorder.stop("interrupted by " + std::string(py::str(raised->type().attr("__name__"))));
        },
        0.0, kSignalCheckInterval_s);
    py::gil_scoped_release release;  // other Python threads go on while this scene is solved
    run.result = rigidity::solve(run.scene, recorder);
  }
  if (raised) {
    run.result.status = rigidity::to_string(rigidity::RunStatus::interrupted);
    raised->value().attr("run") = py::cast(std::move(run));
    throw std::move(*raised);
  }
  return run;
}

Run run_file(const std::string& path, const std::vector<std::string>& overrides) {
  return run_scene(rigidity::load_scene_file(path, overrides));
}

Run run_text(const std::string& text, const std::string& source, const std::vector<std::string>& overrides) {
  return run_scene(rigidity::load_scene_string(text, source, overrides));
}

py::array_t<double> column(const std::vector<double>& values) {
  py::array_t<double> out(static_cast<py::ssize_t>(values.size()));
  double* data = out.mutable_data();
  for (std::size_t i = 0; i < values.size(); ++i) data[i] = values[i];
  return out;
}

/// A value of the run in the scene's units: the conversion the CSV writers apply.
double in_scene_units(const Run& run, double natural_value, rigidity::Dimension dimension) {
  return rigidity::from_natural(natural_value, dimension, run.scene.units);
}

/// The unit of every column and quantity of the outputs in the scene's units: t, x, X, the
/// probe and snapshot quantities ("p": "Pa" in an SI scene, "rho c^2" in a natural one).
py::dict units(const Run& run) {
  using rigidity::Dimension;
  py::dict out;
  out["system"] = run.scene.units == rigidity::UnitSystem::si ? "si" : "natural";
  out["t"] = std::string(rigidity::unit_symbol(Dimension::time, run.scene.units));
  for (rigidity::Quantity q : rigidity::kAllQuantities)
    out[py::str(std::string(rigidity::to_string(q)))] =
        std::string(rigidity::unit_symbol(rigidity::dimension_of(q), run.scene.units));
  return out;
}

/// probes[name][quantity] = (t, value), in the scene's units
py::dict probes(const Run& run) {
  py::dict out;
  const auto& declared = run.scene.outputs.probes;
  std::vector<std::vector<std::pair<rigidity::Quantity, std::pair<std::vector<double>, std::vector<double>>>>> series(
      declared.size());
  for (const rigidity::ProbeSample& s : run.result.probes) {
    auto& of_probe = series[static_cast<std::size_t>(s.probe)];
    auto it = of_probe.begin();
    while (it != of_probe.end() && it->first != s.quantity) ++it;
    if (it == of_probe.end()) it = of_probe.insert(of_probe.end(), {s.quantity, {}});
    it->second.first.push_back(in_scene_units(run, s.t, rigidity::Dimension::time));
    it->second.second.push_back(in_scene_units(run, s.value, rigidity::dimension_of(s.quantity)));
  }
  for (std::size_t i = 0; i < declared.size(); ++i) {
    py::dict quantities;
    for (const auto& [quantity, values] : series[i])
      quantities[py::str(std::string(rigidity::to_string(quantity)))] =
          py::make_tuple(column(values.first), column(values.second));
    out[py::str(declared[i].name)] = quantities;
  }
  return out;
}

/// snapshots as columns: t, body, X, quantity, value (in the scene's units)
py::dict snapshots(const Run& run) {
  std::vector<double> t, X, value;
  py::list body, quantity;
  for (const rigidity::SnapshotSample& s : run.result.snapshots) {
    t.push_back(in_scene_units(run, s.t, rigidity::Dimension::time));
    X.push_back(in_scene_units(run, s.X, rigidity::Dimension::length));
    value.push_back(in_scene_units(run, s.value, rigidity::dimension_of(s.quantity)));
    body.append(run.result.body_names[static_cast<std::size_t>(s.body)]);
    quantity.append(std::string(rigidity::to_string(s.quantity)));
  }
  py::dict out;
  out["t"] = column(t);
  out["body"] = py::array(body);
  out["X"] = column(X);
  out["quantity"] = py::array(quantity);
  out["value"] = column(value);
  return out;
}

/// fronts as columns: t0, x0, t1, x1, kind, family (in the scene's units)
py::dict fronts(const Run& run) {
  std::vector<double> t0, x0, t1, x1;
  std::vector<int> family;
  py::list kind;
  for (const rigidity::FrontSegment& f : run.result.fronts) {
    t0.push_back(in_scene_units(run, f.t0, rigidity::Dimension::time));
    x0.push_back(in_scene_units(run, f.x0, rigidity::Dimension::length));
    t1.push_back(in_scene_units(run, f.t1, rigidity::Dimension::time));
    x1.push_back(in_scene_units(run, f.x1, rigidity::Dimension::length));
    family.push_back(f.family);
    kind.append(std::string(rigidity::to_string(f.kind)));
  }
  py::dict out;
  out["t0"] = column(t0);
  out["x0"] = column(x0);
  out["t1"] = column(t1);
  out["x1"] = column(x1);
  out["kind"] = py::array(kind);
  py::array_t<int> families(static_cast<py::ssize_t>(family.size()));
  for (std::size_t i = 0; i < family.size(); ++i) families.mutable_data()[i] = family[i];
  out["family"] = families;
  return out;
}

/// events as columns: t, kind, x, bodies (each a ';'-joined list), in the scene's units, as events.csv
py::dict events(const Run& run) {
  std::vector<double> t, x;
  py::list kind, bodies;
  for (const rigidity::RunEvent& e : run.result.events) {
    t.push_back(in_scene_units(run, e.t, rigidity::Dimension::time));
    x.push_back(in_scene_units(run, e.x, rigidity::Dimension::length));
    kind.append(e.kind);
    std::string joined;
    for (const std::string& b : e.bodies) joined += (joined.empty() ? "" : ";") + b;
    bodies.append(joined);
  }
  py::dict out;
  out["t"] = column(t);
  out["kind"] = py::array(kind);
  out["x"] = column(x);
  out["bodies"] = py::array(bodies);
  return out;
}

/// A function of the stretch, evaluated over a NumPy array (NaN outside the admissible range).
template <class F>
py::array_t<double> over_stretches(const Material& m, const py::array_t<double, py::array::forcecast>& s, F f) {
  py::array_t<double> out(s.request().shape);
  const double* in = s.data();
  double* o = out.mutable_data();
  const py::ssize_t n = s.size();
  {
    py::gil_scoped_release release;
    const rigidity::StretchRange range = m.admissible();
    for (py::ssize_t i = 0; i < n; ++i) {
      const double value = in[i];
      if (!(value > 0.0)) {
        o[i] = kNaN;
        continue;
      }
      const Stretch st = Stretch::from_value(value);
      o[i] = range.contains(st) ? f(st) : kNaN;
    }
  }
  return out;
}

/// The inverse of a law, over a NumPy array (NaN where no admissible stretch has the value).
template <class F>
py::array_t<double> inverse(const py::array_t<double, py::array::forcecast>& values, F f) {
  py::array_t<double> out(values.request().shape);
  const double* in = values.data();
  double* o = out.mutable_data();
  const py::ssize_t n = values.size();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) {
      const rigidity::Solved<Stretch> s = f(in[i]);
      o[i] = s.ok() ? s.value.value() : kNaN;
    }
  }
  return out;
}

std::shared_ptr<const Material> build(const std::string& name, const py::dict& parameters) {
  rigidity::ParameterValues values;
  for (const auto& item : parameters) {
    const std::string key = py::str(item.first);
    if (py::isinstance<py::str>(item.second)) {
      values.set(key, item.second.cast<std::string>());
    } else {
      values.set(key, item.second.cast<double>());
    }
  }
  return rigidity::build_material(name, values);
}

py::dict state_dict(const rigidity::State& s) {
  py::dict out;
  out["velocity"] = std::tanh(s.rapidity);
  out["rapidity"] = s.rapidity;
  out["stretch"] = s.stretch.value();
  return out;
}

rigidity::State state_from(double velocity, double stretch) {
  if (!(std::abs(velocity) < 1.0)) throw std::invalid_argument("a velocity must be below c in magnitude");
  if (!(stretch > 0.0)) throw std::invalid_argument("a stretch must be positive");
  return rigidity::State{std::atanh(velocity), Stretch::from_value(stretch)};
}

}  // namespace

/// A sweep run in this process, no files written: its table as columns (parameters as the
/// text given, figures NaN where undefined).
py::dict sweep_table(const std::string& path, unsigned jobs) {
  const rigidity::Sweep sweep = rigidity::load_sweep_file(path);
  std::vector<rigidity::SweepRow> rows(sweep.cases.size());
  {
    py::gil_scoped_release release;
    rigidity::warm_up(sweep);
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t i = next++; i < rows.size(); i = next++) rows[i] = rigidity::run_sweep_case(sweep, i);
    };
    std::vector<std::thread> workers;
    for (unsigned k = 1; k < std::max(1u, jobs); ++k) workers.emplace_back(work);
    work();
    for (std::thread& w : workers) w.join();
  }
  py::dict out;
  std::vector<double> index, exit_code, wall;
  py::list status, message;
  for (const rigidity::SweepRow& r : rows) {
    index.push_back(static_cast<double>(r.index));
    exit_code.push_back(r.exit_code);
    wall.push_back(r.wall_time_s);
    status.append(r.status);
    message.append(r.message);
  }
  out["case"] = column(index);
  for (std::size_t k = 0; k < sweep.parameters.size(); ++k) {
    py::list values;
    for (const std::vector<std::string>& c : sweep.cases) values.append(c[k]);
    out[py::str(sweep.parameters[k])] = py::array(values);
  }
  out["status"] = py::array(status);
  out["exit_code"] = column(exit_code);
  out["message"] = py::array(message);
  for (std::size_t f = 0; f < sweep.collect.size(); ++f) {
    std::vector<double> values;
    for (const rigidity::SweepRow& r : rows) values.push_back(r.figures[f].value_or(kNaN));
    out[py::str(sweep.collect[f].name)] = column(values);
  }
  out["wall_time_s"] = column(wall);
  return out;
}

PYBIND11_MODULE(_rigidity, m) {
  m.doc() = "rigidity's C++ core; use the package rigidity";

  // Errors: the package maps them to rigidity.InputError, InadmissibleError, NumericalError.
  static py::exception<rigidity::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<rigidity::InadmissibleError> inadmissible_error(m, "InadmissibleError", PyExc_ValueError);
  static py::exception<rigidity::NumericalError> numerical_error(m, "NumericalError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const rigidity::InputError& e) {
      input_error(e.what());
    } catch (const rigidity::InadmissibleError& e) {
      inadmissible_error(e.what());
    } catch (const rigidity::NumericalError& e) {
      numerical_error(e.what());
    }
  });

  py::class_<Run>(m, "Run")
      .def_property_readonly("summary_json", [](const Run& r) { return rigidity::summary_json(r.scene, r.result); })
      .def_property_readonly("probes", &probes)
      .def_property_readonly("snapshots", &snapshots)
      .def_property_readonly("fronts", &fronts)
      .def_property_readonly("events", &events)
      .def_property_readonly("units", &units)
      .def_property_readonly("warnings", [](const Run& r) { return r.result.warnings; })
      .def_property_readonly("status", [](const Run& r) { return r.result.status; });

  m.def("sweep", &sweep_table, py::arg("path"), py::arg("jobs") = 1u);
  m.def("run_file", &run_file, py::arg("path"), py::arg("overrides") = std::vector<std::string>{});
  m.def("run_text", &run_text, py::arg("text"), py::arg("source"), py::arg("overrides") = std::vector<std::string>{});

  m.def("materials", [] {
    py::list out;
    for (const std::string& name : rigidity::MaterialRegistry::instance().names()) {
      const rigidity::MaterialInfo& info = rigidity::MaterialRegistry::instance().at(name);
      py::list parameters;
      for (const rigidity::ParameterSpec& p : info.parameters) {
        py::dict d;
        d["name"] = p.name;
        d["doc"] = p.doc;
        d["required"] = p.required;
        d["range"] = p.range_text();
        if (p.default_number) d["default"] = *p.default_number;
        if (p.default_text) d["default"] = *p.default_text;
        parameters.append(d);
      }
      py::dict d;
      d["name"] = info.name;
      d["doc"] = info.doc;
      d["parameters"] = parameters;
      out.append(d);
    }
    return out;
  });

  m.def("load_plugin", [](const std::string& path) {
    const rigidity::LoadedPlugin& plugin = rigidity::load_plugin(std::filesystem::path(path));
    return plugin.materials;
  });

  py::class_<Material, std::shared_ptr<Material>>(m, "Material", py::dynamic_attr())
      .def_property_readonly("model", [](const Material& mat) { return std::string(mat.model()); })
      .def_property_readonly("rest_density", &Material::rest_density)
      .def_property_readonly("linearly_degenerate", &Material::linearly_degenerate)
      .def_property_readonly("cavitation_pressure", &Material::cavitation_pressure)
      .def_property_readonly("admissible_stretch",
                             [](const Material& mat) {
                               const rigidity::StretchRange r = mat.admissible();
                               return py::make_tuple(std::exp(r.log_min), std::exp(r.log_max));
                             })
      .def("p",
           [](const Material& mat, const py::array_t<double, py::array::forcecast>& s) {
             return over_stretches(mat, s, [&mat](Stretch st) { return mat.pressure(st); });
           })
      .def("e",
           [](const Material& mat, const py::array_t<double, py::array::forcecast>& s) {
             return over_stretches(mat, s, [&mat](Stretch st) { return mat.energy_density(st); });
           })
      .def("sound_speed",
           [](const Material& mat, const py::array_t<double, py::array::forcecast>& s) {
             return over_stretches(mat, s, [&mat](Stretch st) { return mat.sound_speed(st); });
           })
      .def("psi",
           [](const Material& mat, const py::array_t<double, py::array::forcecast>& s) {
             return over_stretches(mat, s, [&mat](Stretch st) { return mat.riemann_psi(st); });
           })
      .def("stretch_from_pressure",
           [](const Material& mat, const py::array_t<double, py::array::forcecast>& p) {
             return inverse(p, [&mat](double v) { return mat.stretch_at_pressure(v); });
           })
      .def("stretch_from_psi",
           [](const Material& mat, const py::array_t<double, py::array::forcecast>& psi) {
             return inverse(psi, [&mat](double v) { return mat.stretch_at_psi(v); });
           })
      .def("wall_impact",
           [](const Material& mat, double v) -> py::object {
             const rigidity::ImpactOutcome r = rigidity::wall_impact(mat, v);
             if (r.status != rigidity::Status::ok) return py::none();
             py::dict d;
             d["v"] = r.impact.v;
             d["s"] = r.impact.s;
             d["p"] = r.impact.p;
             d["front_speed"] = r.impact.front_speed;
             return d;
           })
      .def("hugoniot",
           [](const Material& mat, const py::array_t<double, py::array::forcecast>& s) {
             return over_stretches(mat, s, [&mat](Stretch st) {
               const std::optional<double> v = st.value() < 1.0 ? rigidity::hugoniot_speed(mat, st) : std::nullopt;
               return v ? *v : kNaN;
             });
           })
      .def("isentrope",
           [](const Material& mat, const py::array_t<double, py::array::forcecast>& s) {
             return over_stretches(
                 mat, s, [&mat](Stretch st) { return st.value() < 1.0 ? rigidity::isentrope_speed(mat, st) : kNaN; });
           })
      .def("crush_speed", [](const Material& mat) -> py::object {
        const std::optional<double> v = rigidity::crush_speed(mat);
        if (!v) return py::none();
        return py::float_(*v);
      });

  m.def(
      "material",
      [](const std::string& name, const py::dict& parameters) {
        return std::const_pointer_cast<Material>(build(name, parameters));
      },
      py::arg("name"), py::arg("parameters"));

  m.def(
      "riemann",
      [](const std::shared_ptr<Material>& left_material, double left_velocity, double left_stretch,
         const std::shared_ptr<Material>& right_material, double right_velocity, double right_stretch,
         double min_pressure) {
        const rigidity::State left = state_from(left_velocity, left_stretch);
        const rigidity::State right = state_from(right_velocity, right_stretch);
        rigidity::RiemannSolution sol;
        {
          py::gil_scoped_release release;
          sol = rigidity::solve_riemann(*left_material, left, *right_material, right, min_pressure);
        }
        if (sol.status == rigidity::Status::out_of_range)
          throw rigidity::InadmissibleError(
              "no classical solution: a side would leave its material's admissible range (crushed, or pulled "
              "beyond its largest tension)");
        if (sol.status != rigidity::Status::ok)
          throw rigidity::NumericalError("the Riemann problem could not be solved (" +
                                         std::string(rigidity::to_string(sol.status)) + ")");
        py::dict out;
        out["pressure"] = sol.pressure;
        out["parted"] = sol.parted;
        out["left"] = state_dict(sol.left);
        out["right"] = state_dict(sol.right);
        return out;
      },
      py::arg("left_material"), py::arg("left_velocity"), py::arg("left_stretch"), py::arg("right_material"),
      py::arg("right_velocity"), py::arg("right_stretch"), py::arg("min_pressure"));
}
