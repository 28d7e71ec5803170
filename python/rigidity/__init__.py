"""rigidity: relativistic continuum mechanics in one dimension, from Python.

    import rigidity
    r = rigidity.run("configs/paper_wall_impact.yaml")   # a path, YAML text, or a dict
    r.summary["conservation"]["energy_dissipated"]
    t, p = r.probes["wall"]["p"]                         # NumPy arrays
    m = rigidity.material("hooke", wave_speed=0.5)
    m.p(numpy.linspace(0.5, 1.5, 11))                    # vectorised in C++

Scenes run in the same process as the interpreter, with the GIL released while they are
solved; Ctrl-C stops a run within a tenth of a second or so and raises KeyboardInterrupt, whose
`result` attribute holds the run up to then (status "interrupted"). A run that a budget stops
(solver.max_fronts, solver.max_interactions: status "stopped") warns with RunStoppedWarning.
Errors arrive as rigidity.InputError (a bad scene: the message names file, line and
key), rigidity.InadmissibleError (a valid scene the physics refuses, e.g. a crushed body) and
rigidity.NumericalError.
"""

import json as _json
import os as _os
import sys as _sys
import warnings as _warnings


def _load_extension():
    """The compiled module rigidity._rigidity, or an ImportError that says what is missing for
    this interpreter and how to get it."""
    here = _os.path.dirname(_os.path.abspath(__file__))
    python = "%s (Python %d.%d)" % (_sys.executable or "this Python", *_sys.version_info[:2])
    try:
        import numpy  # noqa: F401
    except ImportError as error:
        raise ImportError(
            "rigidity needs NumPy, which %s cannot import (%s). Install it into this interpreter "
            "(`%s -m pip install numpy`), or use one that has it: Debian's /usr/bin/python3 with "
            "`apt-get install python3-numpy`, or a virtual environment made with "
            "`/usr/bin/python3 -m venv --system-site-packages`; docs/python.md says how to install rigidity."
            % (python, error, _sys.executable or "python3")) from None
    try:
        from . import _rigidity
        return _rigidity
    except ImportError as error:
        import glob
        import importlib.machinery
        built = sorted(_os.path.basename(f) for f in glob.glob(_os.path.join(here, "_rigidity*")))
        suffixes = importlib.machinery.EXTENSION_SUFFIXES
        install = ("from the repository's root, `%s -m pip install .` builds and installs it for this "
                   "interpreter (docs/python.md)" % (_sys.executable or "python3"))
        if not built:
            message = ("rigidity's compiled module _rigidity is not in %s (this is the package's source, "
                       "or an incomplete install): %s; or build the tree (bash scripts/test.sh) and put "
                       "build-tests/python on PYTHONPATH for Debian's /usr/bin/python3" % (here, install))
        elif not any("_rigidity" + suffix in built for suffix in suffixes):
            message = ("rigidity's compiled module in %s (%s) was built for another Python; %s loads only "
                       "_rigidity%s: %s" % (here, ", ".join(built), python, suffixes[0], install))
        else:
            raise ImportError("rigidity's compiled module in %s (%s) does not load in %s: %s" % (
                here, ", ".join(built), python, error)) from error
        raise ImportError(message) from None


_rigidity = _load_extension()

InputError = _rigidity.InputError
InadmissibleError = _rigidity.InadmissibleError
NumericalError = _rigidity.NumericalError
Material = _rigidity.Material

__all__ = [
    "run",
    "Result",
    "materials",
    "material",
    "riemann",
    "compare",
    "load_plugin",
    "sweep",
    "Material",
    "InputError",
    "InadmissibleError",
    "NumericalError",
    "RunStoppedWarning",
]


class RunStoppedWarning(RuntimeWarning):
    """A run stopped by a budget (solver.max_fronts, solver.max_interactions) before time.end:
    its result holds everything up to summary["t_reached"], and the message says what to change."""


class Result:
    """A solved scene: `summary` as summary.json, and the outputs the scene asked for, in the
    scene's units (SI in a `units: si` scene), the same numbers as the CSV files.

    probes[name][quantity]  -> (t, value), two NumPy arrays
    snapshots               -> dict of NumPy columns t, body, X, quantity, value
    fronts                  -> dict of NumPy columns t0, x0, t1, x1, kind, family
    events                  -> dict of NumPy columns t, kind, x, bodies
    units                   -> the unit of t and of each quantity (x, X, v, p, ...), and the
                               "system" ("si" or "natural"): units["p"] is "Pa" in an SI scene
    """

    def __init__(self, run):
        self._run = run
        self.summary = _json.loads(run.summary_json)
        self.probes = run.probes
        self.snapshots = run.snapshots
        self.fronts = run.fronts
        self.events = run.events
        self.units = run.units
        self.warnings = list(run.warnings)
        self.status = run.status

    def __repr__(self):
        return "<rigidity.Result %s status=%s t_end=%s>" % (
            self.summary.get("scene"), self.status, self.summary.get("t_end"))


def _overrides(set_):
    out = []
    for key, value in (set_ or {}).items():
        out.append("%s=%s" % (key, _json.dumps(value) if not isinstance(value, str) else value))
    return out


def _solved(solve, *args):
    """The Result of solve(*args); a stopped run warns, and an exception a signal handler
    raised during the run (KeyboardInterrupt) carries the run up to then as `result`."""
    try:
        solved = solve(*args)
    except BaseException as error:
        partial = getattr(error, "run", None)
        if isinstance(partial, _rigidity.Run):
            del error.run
            error.result = Result(partial)
        raise
    result = Result(solved)
    if result.status == "stopped":
        _warnings.warn("the run of %s stopped at t = %s of time.end = %s: %s" % (
            result.summary.get("scene"), result.summary.get("t_reached"), result.summary.get("t_end"),
            result.summary.get("stop_reason")), RunStoppedWarning, stacklevel=3)
    return result


def run(scene, set=None):  # noqa: A002 - the name of rigidity run's --set
    """Runs a scene: a dict (as its YAML would read), YAML text, or the path of a scene file.

    `set` overrides keys as `rigidity run --set` does: {"bodies.0.velocity": 0.8}. Ctrl-C
    raises KeyboardInterrupt with the run up to then as its `result`; a run stopped by a
    budget warns (RunStoppedWarning).
    """
    overrides = _overrides(set)
    if isinstance(scene, dict):
        # JSON is YAML: the dict reaches the same strict loader as a file does.
        return _solved(_rigidity.run_text, _scene_json(scene), "<dict>", overrides)
    if isinstance(scene, _os.PathLike):
        return _solved(_rigidity.run_file, _os.fspath(scene), overrides)
    if isinstance(scene, str):
        if "\n" not in scene and (scene.endswith((".yaml", ".yml")) or _os.path.isfile(scene)):
            return _solved(_rigidity.run_file, scene, overrides)
        return _solved(_rigidity.run_text, scene, "<text>", overrides)
    raise TypeError("rigidity.run takes a dict, YAML text or a path, not %s" % type(scene).__name__)


def materials():
    """The registered materials: name, doc, and parameters (name, doc, required, range, default)."""
    return _rigidity.materials()


def material(name, **parameters):
    """A registered material built as a scene builds it (declared defaults, ranges, and a check
    that it is hyperbolic and causal with these parameters). Its p, e, sound_speed, psi,
    stretch_from_pressure, stretch_from_psi, hugoniot and isentrope (the speed a compression
    from rest to s < 1 gives the material through a shock and through a smooth wave) take
    NumPy arrays (NaN outside its range); its
    `spec` is its scene entry, so that a scene dict may hold the Material itself."""
    try:
        made = _rigidity.material(name, parameters)
    except ValueError as error:  # std::invalid_argument: an unknown name or a bad parameter
        raise InputError(str(error)) from None
    made.spec = dict(model=name, **parameters)
    return made


def _material_from_function(p=None, W=None, stretch=(0.5, 2.0), rest_density=1.0, rows=801):
    """A material from a law written in Python: the pressure p(s), or the strain energy
    W(s) = e s (rest energy included: W(1) = 1), both in units of rest_density c^2 and
    vectorised over a NumPy array of stretches s. The law is tabulated once, at `rows`
    stretches evenly spaced in ln s over `stretch` = (smallest, largest), s = 1 among them,
    p = -dW/ds by a fourth-order central difference where W is given; the table is then a
    `tabulated` material, checked as a table in a scene is (the natural state unstressed, p
    falling as s grows, hyperbolic and causal between every pair of rows: errors name the row
    and its stretch), and runs as fast as one.

    The material's `spec` is its scene entry, {"model": "tabulated", "table": ..., ...}: a
    scene dict given to rigidity.run may hold the Material itself among its materials, and
    yaml.safe_dump(m.spec) writes it into a scene file (for sweeps and the command line).
    The table is in units of rest_density c^2 (`table_units`), so the entry means the same
    law in an SI scene, whose rest_density it takes from the number given here (kg/m^3)."""
    import numpy

    if (p is None) == (W is None):
        raise InputError("Material.from_function: give the pressure p(s) or the strain energy W(s), one of them")
    try:
        low, high = (float(x) for x in stretch)
    except (TypeError, ValueError):
        raise InputError("Material.from_function: stretch must be (smallest, largest), got %r" % (stretch,)) from None
    if not (0.0 < low < 1.0 < high and numpy.isfinite(high)):
        raise InputError("Material.from_function: stretch must hold the natural state: 0 < smallest < 1 < largest, "
                         "got (%r, %r)" % (low, high))
    rows = int(rows)
    if not 5 <= rows <= 100000:
        raise InputError("Material.from_function: rows must be in [5, 100000], got %d" % rows)
    # Rows evenly spaced in ln s on each side of s = 1, the natural state exactly among them.
    below = max(2, int(round((rows - 1) * -numpy.log(low) / (numpy.log(high) - numpy.log(low)))))
    above = max(2, rows - 1 - below)
    s = numpy.concatenate([numpy.exp(numpy.linspace(numpy.log(low), 0.0, below + 1))[:-1], [1.0],
                           numpy.exp(numpy.linspace(0.0, numpy.log(high), above + 1))[1:]])
    name = "p" if p is not None else "W"

    def evaluate(law, x):
        try:
            values = numpy.asarray(law(x.copy()), dtype=float)
        except Exception as error:  # the user's function: whatever it raises is reported with the law's name
            raise InputError("Material.from_function: %s(s) raised %s: %s" % (name, type(error).__name__, error)) from None
        if values.shape != x.shape:
            raise InputError("Material.from_function: %s(s) must return one value per stretch (shape %s), got shape %s"
                             % (name, x.shape, values.shape))
        bad = numpy.flatnonzero(~numpy.isfinite(values))
        if bad.size:
            raise InputError("Material.from_function: %s(s) is %r at s = %.12g" % (name, values[bad[0]], x[bad[0]]))
        return values

    if p is not None:
        pressure = evaluate(p, s)
    else:
        # p = -W'(s): the five-point central difference, steps h = 1e-3 s (truncation ~ h^4 W^(5),
        # rounding ~ 1e-16 W / h: both near 1e-13 for laws of order one).
        h = 1e-3 * s
        pressure = -(evaluate(W, s - 2 * h) - 8 * evaluate(W, s - h) + 8 * evaluate(W, s + h)
                     - evaluate(W, s + 2 * h)) / (12 * h)
        natural = float(evaluate(W, numpy.array([1.0]))[0])
        if abs(natural - 1.0) > 1e-9:
            raise InputError("Material.from_function: W(1) = %.12g; the strain energy includes the rest energy, "
                             "W(1) = 1 (units of rest_density c^2)" % natural)
    one = int(numpy.flatnonzero(s == 1.0)[0])
    scale = max(abs(pressure[one - 1]), abs(pressure[one + 1]))
    if abs(pressure[one]) > 1e-9 * max(scale, 1e-300) and abs(pressure[one]) > 1e-14:
        raise InputError("Material.from_function: p(1) = %.12g; the natural state s = 1 is unstressed, p(1) = 0"
                         % pressure[one])
    pressure[one] = 0.0
    table = "s,p\n" + "".join("%r,%r\n" % (float(a), float(b)) for a, b in zip(s, pressure))
    spec = {"model": "tabulated", "rest_density": float(rest_density), "table": table,
            "table_units": "rest_density c^2"}
    try:
        made = material("tabulated", **{k: v for k, v in spec.items() if k != "model"})
    except InputError as error:  # the checks of a table, which name its lines and rows
        raise InputError("Material.from_function: the law tabulated at %d rows over s in [%.12g, %.12g]: %s"
                         % (len(s), low, high, error)) from None
    made.spec = spec
    return made


Material.from_function = staticmethod(_material_from_function)


def compare(materials, out=None, stretch=(0.05, 4.0), speeds=None):
    """Materials side by side, as `rigidity compare` puts them, for any Material the package
    makes (registered, formula, plugin, from_function); natural units (c = 1). `materials`
    is a dict {label: Material} or a list (labelled by model). Returns {label: curves}, each
    a dict of NumPy arrays: s, p, sound_speed over `stretch` (NaN outside the material's
    range); s_compression, hugoniot, isentrope (the speed a compression from rest to s < 1
    gives the material through a shock and through a smooth wave); v, impact_p,
    front_speed (the wall impact at each of `speeds`, default 0.01 ... 0.99, NaN where the
    bar is crushed); and crush_speed (None if no speed crushes it). With `out`, a directory,
    draws stress_strain.png, sound_speed.png, impact.png and hugoniot.png there (Matplotlib)."""
    import numpy

    if not isinstance(materials, dict):
        materials = {m.model: m for m in materials}
    if speeds is None:
        speeds = numpy.linspace(0.01, 0.99, 99)
    speeds = numpy.asarray(speeds, dtype=float)
    s = numpy.geomspace(float(stretch[0]), float(stretch[1]), 400)
    compression = s[s < 1.0]
    curves = {}
    for label, m in materials.items():
        impacts = [m.wall_impact(float(v)) for v in speeds]
        curves[label] = {
            "s": s, "p": m.p(s), "sound_speed": m.sound_speed(s),
            "s_compression": compression, "hugoniot": m.hugoniot(compression),
            "isentrope": m.isentrope(compression), "v": speeds,
            "impact_p": numpy.array([i["p"] if i else numpy.nan for i in impacts]),
            "front_speed": numpy.array([i["front_speed"] if i else numpy.nan for i in impacts]),
            "crush_speed": m.crush_speed(),
        }
    if out is not None:
        _draw_comparison(curves, _os.fspath(out))
    return curves


def _draw_comparison(curves, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    _os.makedirs(out, exist_ok=True)
    charts = {
        "stress_strain": ("s", "p", "s = proper length / natural length", "p  [rho00 c^2]", "Stress-strain law p(s)"),
        "sound_speed": ("s", "sound_speed", "s = proper length / natural length", "c_s  [c]", "Sound speed c_s(s)"),
        "impact": ("v", "front_speed", "impact speed v  [c]", "front speed relative to the unstrained bar  [c]",
                   "Wall impact: the front's speed"),
    }
    for name, (x, y, xlabel, ylabel, title) in charts.items():
        fig, ax = plt.subplots(figsize=(8, 5))
        for k, (label, c) in enumerate(curves.items()):
            ax.plot(c[x], c[y], lw=2, ls="-" if k % 2 == 0 else "--", label=label)
            if name == "impact" and c["crush_speed"] is not None:
                ax.axvline(c["crush_speed"], ls=":", color=ax.lines[-1].get_color())
        ax.set(xlabel=xlabel, ylabel=ylabel, title=title)
        if name == "stress_strain":
            ax.axhline(0.0, color="k", lw=0.8)
        ax.grid(alpha=0.3)
        ax.legend()
        fig.savefig(_os.path.join(out, name + ".png"), dpi=100)
        plt.close(fig)
    fig, ax = plt.subplots(figsize=(8, 5))
    for label, c in curves.items():
        p = c["p"][: c["s_compression"].size]
        line = ax.plot(c["hugoniot"], p, lw=2, label=label + ": shock")[0]
        ax.plot(c["isentrope"], p, lw=2, ls="--", color=line.get_color(), label=label + ": smooth wave")
    ax.set(xlabel="speed of the material behind the wave  [c]", ylabel="p  [rho00 c^2]", yscale="log",
           title="Hugoniot against isentrope: compression from rest")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.savefig(_os.path.join(out, "hugoniot.png"), dpi=100)
    plt.close(fig)


def _scene_json(scene):
    """A scene dict as JSON, Material objects among its values written as their scene entries."""
    def entry(value):
        spec = getattr(value, "spec", None)
        if isinstance(value, Material) and isinstance(spec, dict):
            return spec
        raise TypeError("a scene dict holds numbers, text, lists and dicts (and Materials made in Python), "
                        "not %s" % type(value).__name__)
    return _json.dumps(scene, default=entry)


def riemann(left_material, left, right_material, right, min_pressure=None):
    """The exact Riemann problem between two uniform states, each a dict {velocity, stretch}
    (stretch 1 if left out). Sides that would pull harder than min_pressure part (default: the
    larger cavitation pressure of the two materials, or no limit). Returns the star pressure,
    whether the sides part, and the star state on each side."""
    if min_pressure is None:
        min_pressure = max(left_material.cavitation_pressure, right_material.cavitation_pressure)
    return _rigidity.riemann(left_material, float(left.get("velocity", 0.0)), float(left.get("stretch", 1.0)),
                             right_material, float(right.get("velocity", 0.0)), float(right.get("stretch", 1.0)),
                             float(min_pressure))


def load_plugin(path):
    """Loads a material plugin (a shared library); returns the names of its materials."""
    return _rigidity.load_plugin(_os.fspath(path))


def sweep(path, jobs=None):
    """Runs a sweep file (docs/sweeps.md) in this process, writing no files, and returns its table
    as a dict of NumPy columns: case, each parameter (as given), status, exit_code, message,
    each `collect` figure (NaN where undefined) and wall_time_s. `jobs` threads (default:
    the machine's cores); `rigidity sweep` writes the same table to sweep.csv."""
    if jobs is None:
        jobs = _os.cpu_count() or 1
    return _rigidity.sweep(_os.fspath(path), int(jobs))
