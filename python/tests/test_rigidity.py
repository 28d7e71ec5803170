"""The Python package against closed forms (docs/physics.md, the paper's wall impact), not only
that calls return: run, materials, the exact Riemann problem, errors, and the GIL."""

import os
import threading
import time

import numpy as np
import pytest

import rigidity

SOURCE = os.environ.get("RIGIDITY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
PAPER = os.path.join(SOURCE, "configs", "paper_wall_impact.yaml")


def wall_scene(model, v, t_end=0.75, **parameters):
    material = {"model": model}
    material.update(parameters)
    return {
        "name": "wall_impact",
        "materials": {"m": material},
        "bodies": [{"name": "bar", "material": "m", "position": 0.0, "length": 1.0, "velocity": v}],
        "boundaries": {"left": {"type": "free"}, "right": {"type": "wall"}},
        "time": {"end": t_end},
        "outputs": {"probes": [{"name": "wall", "body": "bar", "at": "right", "quantities": ["p", "s", "v"],
                                "every": 0.05}]},
    }


def test_the_paper_scene_from_its_file():
    r = rigidity.run(PAPER)
    assert r.status == "ok"
    t, p = r.probes["wall"]["p"]
    assert isinstance(t, np.ndarray) and t.shape == p.shape
    # Behind the front p = 1.5 and s = 0.5 while the bar is on the wall (0 < t < 1).
    on_wall = (t > 0.0) & (t < 1.0)
    assert on_wall.sum() >= 15
    np.testing.assert_allclose(p[on_wall], 1.5, rtol=1e-12)
    _, s = r.probes["wall"]["s"]
    np.testing.assert_allclose(s[on_wall], 0.5, rtol=1e-12)
    # It leaves the wall unstrained at -v (footnote 2): momentum reversed, energy kept.
    c = r.summary["conservation"]
    assert c["momentum_final"] == pytest.approx(-c["momentum_initial"], rel=1e-12)
    assert c["energy_final"] == pytest.approx(c["energy_initial"], rel=1e-12)
    assert c["momentum_final"] - c["momentum_initial"] == pytest.approx(c["wall_impulse"], rel=1e-12)


@pytest.mark.parametrize("v", [0.1, 0.5, 0.9])
def test_rigid_wall_pressure_against_the_closed_form_for_a_dict_scene(v):
    # s = sqrt((1 - v)/(1 + v)), p = (rho00/2)(1/s^2 - 1) = rho00 v/(1 - v)
    r = rigidity.run(wall_scene("rigid", v, rest_density=2.0))
    t, p = r.probes["wall"]["p"]
    _, s = r.probes["wall"]["s"]
    hit = (t > 0.0) & (t < 0.5)
    np.testing.assert_allclose(p[hit], 2.0 * v / (1.0 - v), rtol=1e-12)
    np.testing.assert_allclose(s[hit], np.sqrt((1.0 - v) / (1.0 + v)), rtol=1e-12)


def test_set_overrides_keys_as_the_command_line_does():
    r = rigidity.run(PAPER, set={"bodies.0.velocity": 0.8, "time.end": 0.8})
    t, p = r.probes["wall"]["p"]
    np.testing.assert_allclose(p[(t > 0) & (t < 0.6)], 4.0, rtol=1e-12)  # docs/materials.md: p = 4 at v = 0.8
    assert r.summary["t_end"] == pytest.approx(0.8)


def test_snapshots_fronts_and_events_are_columns():
    r = rigidity.run(PAPER)
    snap = r.snapshots
    n = len(snap["t"])
    assert n > 0 and all(len(snap[k]) == n for k in ("body", "X", "quantity", "value"))
    p_at_half = snap["value"][(snap["quantity"] == "p") & (snap["t"] == 0.5)]
    np.testing.assert_allclose(p_at_half, 1.5, rtol=1e-12)  # the whole bar is stopped at t1 = 0.5
    fronts = r.fronts
    assert len(fronts["t0"]) > 0 and set(fronts["kind"]) <= {"shock", "contact", "rarefaction", "interface",
                                                              "boundary"}
    assert np.all(fronts["t1"] >= fronts["t0"])
    # The bar starts on the wall and leaves it at 2 t1 = 1 (footnote 2).
    assert list(r.events["kind"]) == ["separation"]
    np.testing.assert_allclose(r.events["t"], [1.0], rtol=1e-12)


def test_yaml_text_runs_too():
    with open(PAPER) as f:
        text = f.read()
    r = rigidity.run(text)
    assert r.summary["scene"] == "paper_wall_impact"


def test_a_bad_scene_is_an_input_error_naming_line_and_key():
    scene = wall_scene("rigid", 0.5)
    scene["bodies"][0]["velocty"] = 0.5
    with pytest.raises(rigidity.InputError) as error:
        rigidity.run(scene)
    assert "<dict>:1:" in str(error.value)
    assert "velocty" in str(error.value) and "velocity" in str(error.value)


def test_a_crushed_hooke_bar_is_inadmissible():
    # docs/materials.md: an impact at v >= V collapses a hooke bar: no classical solution.
    with pytest.raises(rigidity.InadmissibleError):
        rigidity.run(wall_scene("hooke", 0.6, wave_speed=0.5))


def test_materials_lists_the_registry():
    names = {m["name"] for m in rigidity.materials()}
    assert {"rigid", "hooke", "rigid_fluid", "constant_sound_speed"} <= names
    hooke = next(m for m in rigidity.materials() if m["name"] == "hooke")
    assert any(p["name"] == "wave_speed" for p in hooke["parameters"])


def test_material_laws_are_vectorised_and_match_the_spec():
    s = np.linspace(0.3, 0.99, 50)
    rigid = rigidity.material("rigid", rest_density=1.5)
    np.testing.assert_allclose(rigid.p(s), 0.75 * (1.0 / s**2 - 1.0), rtol=1e-13)
    np.testing.assert_allclose(rigid.sound_speed(s), 1.0, rtol=1e-14)
    b = 0.5
    hooke = rigidity.material("hooke", wave_speed=b)
    R = np.sqrt(b**2 + (1 - b**2) / s**2)
    e = (R - b**2) / (1 - b**2)
    np.testing.assert_allclose(hooke.e(s), e, rtol=1e-13)
    np.testing.assert_allclose(hooke.p(s), e / R - 1.0, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(hooke.sound_speed(s), np.sqrt(b**2 * s**2 / (b**2 * s**2 + 1 - b**2)), rtol=1e-13)
    V = 0.4
    gas = rigidity.material("constant_sound_speed", sound_speed=V)
    np.testing.assert_allclose(gas.p(s), V**2 / (1 + V**2) * (s ** -(1 + V**2) - 1), rtol=1e-12)
    # Inverses round-trip; a 2-d array keeps its shape.
    grid = s.reshape(5, 10)
    np.testing.assert_allclose(hooke.stretch_from_pressure(hooke.p(grid)), grid, rtol=1e-10)
    np.testing.assert_allclose(gas.stretch_from_psi(gas.psi(grid)), grid, rtol=1e-12)
    # Outside the admissible range: NaN, not a number that means nothing.
    fluid = rigidity.material("rigid_fluid")
    assert np.isnan(fluid.p(np.array([2.0]))[0])


def test_a_bad_parameter_is_an_input_error():
    with pytest.raises(rigidity.InputError):
        rigidity.material("hooke", wave_speed=2.0)
    with pytest.raises(rigidity.InputError):
        rigidity.material("no_such_model")


def test_riemann_matches_the_symmetric_collision_and_parts_a_fluid():
    rigid = rigidity.material("rigid")
    sol = rigidity.riemann(rigid, {"velocity": 0.6}, rigid, {"velocity": -0.6})
    assert sol["pressure"] == pytest.approx(1.5, rel=1e-12)
    assert sol["left"]["stretch"] == pytest.approx(0.5, rel=1e-12)
    assert sol["left"]["velocity"] == pytest.approx(0.0, abs=1e-14)
    fluid = rigidity.material("rigid_fluid")
    apart = rigidity.riemann(fluid, {"velocity": -0.3}, fluid, {"velocity": 0.3})
    assert apart["parted"] and apart["pressure"] == 0.0
    assert apart["left"]["velocity"] == pytest.approx(-0.3, rel=1e-12)


def test_wall_impact_and_crush_speed():
    hooke = rigidity.material("hooke", wave_speed=0.5)
    impact = hooke.wall_impact(0.2)
    assert impact["s"] == pytest.approx(0.6123724357, rel=1e-9)  # docs/materials.md reference values
    assert impact["p"] == pytest.approx(0.1111111111, rel=1e-9)
    assert impact["front_speed"] == pytest.approx(0.5, rel=1e-12)
    assert hooke.crush_speed() == pytest.approx(0.5, rel=1e-12)
    assert hooke.wall_impact(0.6) is None
    assert rigidity.material("rigid").crush_speed() is None


def test_compare_puts_any_materials_side_by_side(tmp_path):
    # Closed forms written here: the rigid law's shock and smooth wave are one, v = (1 - s^2)/(1 + s^2);
    # the gas's smooth wave is tanh(V |ln s|), its shock slower for the same pressure (p gamma = s (p + w u^2)).
    gas = rigidity.Material.from_function(p=lambda s: 0.2 * (s ** -1.25 - 1.0), stretch=(0.1, 4.0))  # V = 0.5
    curves = rigidity.compare({"rigid": rigidity.material("rigid"), "gas": gas,
                               "hooke": rigidity.material("hooke", wave_speed=0.5)}, out=tmp_path)
    rigid = curves["rigid"]
    s = rigid["s_compression"]
    assert s.size > 100 and (s < 1.0).all()
    np.testing.assert_allclose(rigid["hugoniot"], (1 - s * s) / (1 + s * s), rtol=1e-12)
    np.testing.assert_allclose(rigid["isentrope"], (1 - s * s) / (1 + s * s), rtol=1e-12)
    np.testing.assert_allclose(rigid["front_speed"], 1.0, rtol=1e-12)  # the seed paper's shock at c
    g = curves["gas"]
    inside = g["s_compression"] > 0.1
    np.testing.assert_allclose(g["isentrope"][inside], np.tanh(0.5 * -np.log(g["s_compression"][inside])),
                                  rtol=1e-6)  # a table of 801 rows: its Psi to about 1e-7
    p = g["p"][: g["s_compression"].size][inside]
    v = g["hugoniot"][inside]
    gamma = 1 / np.sqrt(1 - v * v)
    w = 1 + p / 0.25 + p
    np.testing.assert_allclose(p * gamma, g["s_compression"][inside] * (p + w * gamma ** 2 * v * v), rtol=1e-6)
    assert (g["hugoniot"][inside] > g["isentrope"][inside]).all()
    assert curves["hooke"]["crush_speed"] == pytest.approx(0.5, rel=1e-12)
    assert np.isnan(curves["hooke"]["front_speed"][curves["hooke"]["v"] >= 0.5]).all()
    for chart in ("stress_strain", "sound_speed", "impact", "hugoniot"):
        assert (tmp_path / (chart + ".png")).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_solve_releases_the_gil():
    # Two bars of 200 Hooke segments each ringing between bonded walls: long enough to watch
    # another thread run (a lone bar would be a lattice piece, solved in milliseconds).
    segments = [{"length": 0.01, "velocity": 0.2 if k % 2 == 0 else -0.2} for k in range(200)]
    scene = {
        "name": "ringing",
        "materials": {"soft": {"model": "hooke", "wave_speed": 0.5}},
        "bodies": [{"name": "left", "material": "soft", "position": 0.0, "segments": segments},
                   {"name": "right", "material": "soft", "position": 2.0, "segments": segments}],
        "boundaries": {"left": {"type": "wall", "bonded": True}, "right": {"type": "wall", "bonded": True}},
        "time": {"end": 60.0},
    }
    done = threading.Event()
    ticks = [0]

    def count():
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    start = time.perf_counter()
    counter.start()
    rigidity.run(scene)
    elapsed = time.perf_counter() - start
    done.set()
    counter.join()
    assert elapsed > 0.05, "the scene should take a while"
    # With the GIL held the counter could not tick while the scene was solved.
    assert ticks[0] > 0.2 * elapsed / 0.0011


def test_sweep_returns_the_table_against_the_closed_forms():
    table = rigidity.sweep(os.path.join(SOURCE, "examples", "sweeps", "paper_velocity.yaml"), jobs=2)
    v = table["bodies.0.velocity"].astype(float)
    assert len(v) == 19 and np.all(table["exit_code"] == 0)
    np.testing.assert_allclose(table["p_max"], v / (1 - v), rtol=1e-9)           # rho00 v/(1 - v)
    np.testing.assert_array_equal(table["bodies.0.velocity"][:3], ["0.05", "0.1", "0.15"])
    # The sweep runs to t = 2.5, past every separation: each row has its contact time.
    np.testing.assert_allclose(table["contact_time"], 2 * np.sqrt((1 - v) / (1 + v)), rtol=1e-9)
    np.testing.assert_allclose(table["rebound"], -v, rtol=1e-9)


C = 299792458.0  # m/s


def steel_wall(units):
    """A Hooke steel bar (rho00 = 7850 kg/m^3, V = 5100 m/s, 1 m) at 1000 m/s into a wall,
    written in SI or, the same scene, in natural units (lengths in m, times in m/c)."""
    si = units == "si"
    speed = (lambda v: v) if si else (lambda v: v / C)
    time = (lambda t: t) if si else (lambda t: t * C)
    return {
        "name": "steel_wall",
        "units": units,
        "materials": {"steel": {"model": "hooke", "rest_density": 7850.0, "wave_speed": speed(5100.0)}},
        "bodies": [{"name": "bar", "material": "steel", "position": 0.0, "length": 1.0, "velocity": speed(1000.0)}],
        "boundaries": {"left": {"type": "free"}, "right": {"type": "wall"}},
        "time": {"end": time(5e-4)},
        "outputs": {"probes": [{"name": "wall", "body": "bar", "at": "right", "quantities": ["p", "v", "x"],
                                "every": time(1e-4)}],
                    "snapshots": [{"times": [time(2e-4)], "quantities": ["p", "x"], "samples": 3}],
                    "fronts": True},
    }


def test_an_si_scene_gives_every_array_in_si():
    si, natural = rigidity.run(steel_wall("si")), rigidity.run(steel_wall("natural"))
    assert si.units["system"] == "si" and natural.units["system"] == "natural"
    assert (si.units["t"], si.units["p"], si.units["v"], si.units["x"]) == ("s", "Pa", "m/s", "m")
    t, p = si.probes["wall"]["p"]
    t_nat, p_nat = natural.probes["wall"]["p"]
    np.testing.assert_allclose(t, [0.0, 1e-4, 2e-4, 3e-4, 4e-4, 5e-4], rtol=1e-12, atol=0.0)
    np.testing.assert_allclose(t, t_nat / C, rtol=1e-12)
    np.testing.assert_allclose(p, p_nat * C**2, rtol=1e-12)
    assert p[1] == pytest.approx(4.0035e10, rel=1e-4)  # the wall pressure, Pa
    np.testing.assert_allclose(si.probes["wall"]["v"][1], natural.probes["wall"]["v"][1] * C, rtol=1e-12)
    np.testing.assert_allclose(si.probes["wall"]["x"][1], natural.probes["wall"]["x"][1], rtol=1e-12)
    np.testing.assert_allclose(si.events["t"], natural.events["t"] / C, rtol=1e-12)
    assert list(si.events["kind"]) == ["separation"]
    assert si.events["t"][0] == pytest.approx(si.summary["events"][0]["t"], rel=1e-15)
    np.testing.assert_allclose(si.snapshots["t"], natural.snapshots["t"] / C, rtol=1e-12)
    np.testing.assert_allclose(si.snapshots["value"][si.snapshots["quantity"] == "p"],
                               natural.snapshots["value"][natural.snapshots["quantity"] == "p"] * C**2, rtol=1e-12)
    np.testing.assert_allclose(si.fronts["t1"], natural.fronts["t1"] / C, rtol=1e-12)
    np.testing.assert_allclose(si.fronts["x1"], natural.fronts["x1"], rtol=1e-12)


@pytest.mark.skipif("RIGIDITY_EXECUTABLE" not in os.environ, reason="needs the built rigidity executable")
def test_an_si_scene_gives_the_numbers_of_the_csv_files(tmp_path):
    import json
    import subprocess

    scene = tmp_path / "steel_wall.yaml"
    scene.write_text(json.dumps(steel_wall("si")))  # JSON is YAML
    subprocess.run([os.environ["RIGIDITY_EXECUTABLE"], "run", str(scene), "--out", str(tmp_path / "out"), "--quiet"],
                   check=True)
    r = rigidity.run(str(scene))
    probes = np.genfromtxt(tmp_path / "out" / "probes.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    for quantity in ("p", "v", "x"):
        rows = probes[probes["quantity"] == quantity]
        t, value = r.probes["wall"][quantity]
        np.testing.assert_array_equal(t, rows["t"])
        np.testing.assert_array_equal(value, rows["value"])
    events = np.genfromtxt(tmp_path / "out" / "events.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    np.testing.assert_array_equal(r.events["t"], np.atleast_1d(events["t"]))
    np.testing.assert_array_equal(r.events["x"], np.atleast_1d(events["x"]))


@pytest.mark.skipif("RIGIDITY_EXECUTABLE" not in os.environ, reason="needs the built rigidity executable")
@pytest.mark.parametrize("units", ["natural", "si"])
def test_run_h5_holds_the_numbers_of_the_csv_files_with_their_units(tmp_path, units):
    import json
    import subprocess

    h5py = pytest.importorskip("h5py")
    scene = steel_wall(units)
    scene["outputs"]["hdf5"] = True
    path = tmp_path / "steel_wall.yaml"
    path.write_text(json.dumps(scene))  # JSON is YAML
    out = tmp_path / "out"
    subprocess.run([os.environ["RIGIDITY_EXECUTABLE"], "run", str(path), "--out", str(out), "--quiet"], check=True)
    read = lambda name: np.atleast_1d(np.genfromtxt(out / name, delimiter=",", names=True, dtype=None,
                                                    encoding="utf-8"))
    probes, snapshots, fronts, events = (read(n) for n in ("probes.csv", "snapshots.csv", "fronts.csv", "events.csv"))
    si = units == "si"
    with h5py.File(out / "run.h5", "r") as f:
        assert f.attrs["units"] == units
        assert json.loads(f.attrs["summary"]) == json.loads((out / "summary.json").read_text())
        for quantity, unit in (("p", "Pa" if si else "rho c^2"), ("v", "m/s" if si else "c"), ("x", "m" if si else "L")):
            rows = probes[probes["quantity"] == quantity]
            group = f["probes/wall/" + quantity]
            np.testing.assert_array_equal(group["t"][:], rows["t"])
            np.testing.assert_array_equal(group["value"][:], rows["value"])
            assert group["value"].attrs["unit"] == unit
            assert group["t"].attrs["unit"] == ("s" if si else "L/c")
        for quantity in ("p", "x"):
            rows = snapshots[snapshots["quantity"] == quantity]
            group = f["snapshots/bar/" + quantity]
            for column in ("t", "X", "value"):
                np.testing.assert_array_equal(group[column][:], rows[column])
        names = f["fronts"].attrs["kind_names"].split(",")
        for column in ("t0", "x0", "t1", "x1", "family"):
            np.testing.assert_array_equal(f["fronts/" + column][:], fronts[column])
        assert [names[k] for k in f["fronts/kind"][:]] == list(fronts["kind"])
        np.testing.assert_array_equal(f["events/t"][:], events["t"])
        assert list(f["events/kind"].asstr()[:]) == list(events["kind"])


def ringing_scene(t_end, **solver):
    """A bar of 300 Hooke segments ringing between bonded walls: about 10^4 time units a second."""
    segments = [{"length": 0.01, "velocity": 0.2 if k % 2 == 0 else -0.2} for k in range(300)]
    scene = {
        "name": "ringing",
        "materials": {"soft": {"model": "hooke", "wave_speed": 0.5}},
        "bodies": [{"name": "bar", "material": "soft", "segments": segments}],
        "boundaries": {"left": {"type": "wall", "bonded": True}, "right": {"type": "wall", "bonded": True}},
        "time": {"end": t_end},
        "outputs": {"probes": [{"name": "mid", "body": "bar", "at": 1.5, "quantities": ["p"], "every": 1.0}]},
    }
    if solver:
        scene["solver"] = solver
    return scene


def test_ctrl_c_stops_a_run_with_keyboard_interrupt_and_the_run_so_far(tmp_path):
    import json
    import signal
    import subprocess
    import sys

    # A run of minutes in a child interpreter, sent SIGINT (what Ctrl-C sends) once under way.
    script = tmp_path / "long_run.py"
    script.write_text(
        "import json, sys, rigidity\n"
        "scene = json.loads(sys.argv[1])\n"
        "print('running', flush=True)\n"
        "try:\n"
        "    rigidity.run(scene)\n"
        "except KeyboardInterrupt as e:\n"
        "    r = e.result\n"
        "    print(json.dumps({'status': r.status, 't_reached': r.summary['t_reached'],\n"
        "                      'summary_status': r.summary['status'], 'samples': len(r.probes['mid']['p'][0])}))\n"
        "    sys.exit(3)\n"
        "print('finished')\n")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in [os.path.dirname(os.path.dirname(rigidity.__file__)),
                                                                   os.environ.get("PYTHONPATH")] if p))
    child = subprocess.Popen([sys.executable, str(script), json.dumps(ringing_scene(1.0e6))], stdout=subprocess.PIPE,
                             text=True, env=env)
    try:
        assert child.stdout.readline().strip() == "running"
        time.sleep(1.0)
        child.send_signal(signal.SIGINT)
        sent = time.perf_counter()
        out, _ = child.communicate(timeout=20)
        took = time.perf_counter() - sent
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    assert child.returncode == 3, out
    assert took < 1.0  # measured 0.06 s: the run looks at Python's signal handlers every 0.1 s
    partial = json.loads(out)
    assert partial["status"] == "interrupted"
    assert partial["summary_status"] == "interrupted"
    assert 0.0 < partial["t_reached"] < 1.0e6
    assert partial["samples"] >= int(partial["t_reached"])  # a probe sample every time unit up to then


def test_a_run_stopped_by_a_budget_warns():
    with pytest.warns(rigidity.RunStoppedWarning, match="solver.max_interactions") as caught:
        r = rigidity.run(ringing_scene(100.0, max_interactions=2000))
    assert r.status == "stopped"
    assert r.summary["t_reached"] < 100.0
    assert caught[0].filename == __file__  # the warning points at the call
    # A run that reaches time.end says nothing.
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert rigidity.run(ringing_scene(1.0)).status == "ok"


# A law written in Python: constant_sound_speed's, p = V^2/k (s^-k - 1) with k = 1 + V^2, and
# its strain energy W = 1 - V^2/k ((s^(1-k) - 1)/(1 - k) - (s - 1)), written here from the
# closed form, not from the built-in material.
GAS_V = 0.5
GAS_K = 1.0 + GAS_V**2


def gas_pressure(s):
    return GAS_V**2 / GAS_K * (s**-GAS_K - 1.0)


def gas_strain_energy(s):
    return 1.0 - GAS_V**2 / GAS_K * ((s ** (1.0 - GAS_K) - 1.0) / (1.0 - GAS_K) - (s - 1.0))


@pytest.mark.parametrize("law", ["p", "W"])
def test_a_material_from_a_python_function_is_the_law_it_samples(law):
    given = {"p": gas_pressure} if law == "p" else {"W": gas_strain_energy}
    m = rigidity.Material.from_function(stretch=(0.3, 3.0), **given)
    s = np.linspace(0.31, 2.9, 97)
    np.testing.assert_allclose(m.p(s), gas_pressure(s), rtol=5e-8, atol=1e-12)  # 801 rows: third order
    np.testing.assert_allclose(m.sound_speed(s), GAS_V, rtol=1e-5)
    lo, hi = m.admissible_stretch
    assert lo == pytest.approx(0.3, rel=1e-12) and hi == pytest.approx(3.0, rel=1e-12)
    assert m.spec["model"] == "tabulated" and m.spec["table_units"] == "rest_density c^2"


def test_a_scene_dict_holding_a_python_law_runs_as_the_built_in_law(tmp_path):
    import json
    m = rigidity.Material.from_function(p=gas_pressure, stretch=(0.3, 3.0))
    scene = wall_scene("constant_sound_speed", 0.4, t_end=3.0, sound_speed=GAS_V)
    # Resolved to the tolerance: `auto` could take neighbouring resolutions for the two laws.
    scene["solver"] = {"tolerance": 1e-4, "resolution": "tolerance"}
    built_in = rigidity.run(scene)
    scene["materials"]["m"] = m
    from_python = rigidity.run(scene)
    t, p = from_python.probes["wall"]["p"]
    np.testing.assert_allclose(t, built_in.probes["wall"]["p"][0], rtol=0, atol=0)
    assert p.max() > 0.1  # the bar is on the wall, compressed
    # Within 1e-7 (the error bound is 5e-5 of the mean |dphi| + |dPsi|; the tables agree to 1e-8).
    np.testing.assert_allclose(p, built_in.probes["wall"]["p"][1], rtol=0, atol=1e-7)
    # Its scene entry written into a file (JSON is YAML) gives the same numbers.
    path = tmp_path / "scene.yaml"
    scene["materials"]["m"] = m.spec
    path.write_text(json.dumps(scene))
    np.testing.assert_array_equal(rigidity.run(str(path)).probes["wall"]["p"][1], p)


def test_a_python_law_in_an_si_scene_takes_its_units_from_the_scene():
    c = 299792458.0
    scene = {
        "name": "si_gas", "units": "si",
        "materials": {"gas": {"model": "constant_sound_speed", "rest_density": 7850.0, "sound_speed": GAS_V * c}},
        "bodies": [{"name": "bar", "material": "gas", "position": 0.0, "length": 1.0, "velocity": 0.4 * c}],
        "boundaries": {"left": {"type": "free"}, "right": {"type": "wall"}},
        "solver": {"tolerance": 1e-4},
        "time": {"end": 2e-9},
        "outputs": {"probes": [{"name": "wall", "body": "bar", "at": "right", "quantities": ["p"], "every": 2e-10}]},
    }
    built_in = rigidity.run(scene)
    scene["materials"]["gas"] = rigidity.Material.from_function(p=gas_pressure, stretch=(0.3, 3.0), rest_density=7850.0)
    t, p = rigidity.run(scene).probes["wall"]["p"]
    assert p.max() > 1e19  # Pa: rest_density c^2 is 7e20 Pa
    np.testing.assert_allclose(p, built_in.probes["wall"]["p"][1], rtol=1e-6)


@pytest.mark.parametrize("law, stretch, message", [
    (lambda s: np.where(s > 2.0, np.nan, gas_pressure(s)), (0.5, 3.0), "is nan at s = 2.0"),
    (lambda s: gas_pressure(s) + 0.01, (0.5, 2.0), "p(1) = 0.01"),
    (lambda s: 0.2 * np.sin(4 * np.log(s)) * -1.0, (0.3, 3.0), "row"),  # p rises again: not hyperbolic
    (lambda s: 2.0 * (1.0 / s**2 - 1.0), (0.5, 2.0), "causal"),  # four times the rigid law: c_s > c
    (lambda s: gas_pressure(s)[:-1], (0.5, 2.0), "one value per stretch"),
    (gas_pressure, (1.2, 2.0), "natural state"),
])
def test_a_bad_python_law_is_an_input_error_that_says_where(law, stretch, message):
    with pytest.raises(rigidity.InputError, match=message.replace("(", r"\(").replace(")", r"\)")):
        rigidity.Material.from_function(p=law, stretch=stretch)


def test_a_strain_energy_without_the_rest_energy_is_refused():
    with pytest.raises(rigidity.InputError, match=r"W\(1\) = 0"):
        rigidity.Material.from_function(W=lambda s: gas_strain_energy(s) - 1.0)


MURNAGHAN_PLUGIN = os.environ.get("RIGIDITY_MURNAGHAN_PLUGIN")


def murnaghan_pressure(s):
    return 0.01 / 4.0 * (s**-4.0 - 1.0)  # K = rho00 c0^2 with c0 = 0.1, n = 4


@pytest.mark.skipif(not MURNAGHAN_PLUGIN, reason="the example plugin is built with the tests")
def test_one_law_as_a_plugin_a_formula_and_a_python_function_gives_the_same_runs_and_sweep(tmp_path):
    # Murnaghan's solid three ways: the C++ plugin of examples/plugin (p in closed form, W, c_s
    # and Psi from its Chebyshev tables), a formula, and a NumPy function tabulated at 8001 rows.
    # A wall impact at 0.05 c to t = 30 (the shock, its reflection from the free end, the bar
    # leaving the wall), a shock tube (s = 0.8 | 1 at rest: a fan and a shock) and a sweep of the
    # impact speed (p_max and the contact time at 0.02, 0.05, 0.08 c). Measured against the
    # plugin, relative: the formula 2.7e-14 (wall p), 9e-15 (tube p), 7e-16 and 1e-14 (sweep):
    # the same law through the same tables; the Python law 3.7e-9, 5.7e-7 (the fan's samples,
    # through c_s from the table's slopes: 6.9e-5 at the default 801 rows), 4.5e-11 and 4.7e-10.
    # At 0.08 c a step of the release fan brings the wall to p = 0 within round-off: the contact
    # holds there for every law alike, and the bar leaves when the next step brings tension.
    import json
    laws = {
        "plugin": {"model": "murnaghan", "sound_speed": 0.1},
        "formula": {"model": "formula", "pressure": "rest_density*0.01/4*(s^(-4) - 1)", "min_stretch": 0.2,
                    "max_stretch": 10},
        "python": rigidity.Material.from_function(p=murnaghan_pressure, stretch=(0.2, 10.0), rows=8001),
    }

    def scene(law, tube):
        out = {
            "name": "three_ways",
            "plugins": [MURNAGHAN_PLUGIN],
            "materials": {"solid": law},
            "solver": {"tolerance": 1e-5, "resolution": "tolerance"},  # one resolution for all three
        }
        if tube:
            out["bodies"] = [{"name": "bar", "material": "solid",
                              "segments": [{"length": 0.5, "velocity": 0.0, "stretch": 0.8},
                                           {"length": 0.5, "velocity": 0.0, "stretch": 1.0}]}]
            out["boundaries"] = {"left": {"type": "wall"}, "right": {"type": "wall"}}
            out["time"] = {"end": 2.0}
            out["outputs"] = {"snapshots": [{"times": [2.0], "quantities": ["p", "v"], "samples": 201}]}
        else:
            out["bodies"] = [{"name": "bar", "material": "solid", "position": 0.0, "length": 1.0, "velocity": 0.05}]
            out["boundaries"] = {"left": {"type": "free"}, "right": {"type": "wall"}}
            out["time"] = {"end": 30.0}
            out["outputs"] = {"probes": [{"name": "wall", "body": "bar", "at": "right", "quantities": ["p"],
                                          "every": 0.25}]}
        return out

    def snapshot(r, quantity):
        return r.snapshots["value"][r.snapshots["quantity"] == quantity]

    def separation(r):
        return r.events["t"][r.events["kind"] == "separation"][0]

    wall = {name: rigidity.run(scene(law, False)) for name, law in laws.items()}
    tube = {name: rigidity.run(scene(law, True)) for name, law in laws.items()}
    t, p = wall["plugin"].probes["wall"]["p"]
    assert p.max() > 0.005 and (p == 0.0).any()  # on the wall, then off it
    for name, tolerance in (("formula", 1e-13), ("python", 2e-6)):
        other_t, other_p = wall[name].probes["wall"]["p"]
        np.testing.assert_array_equal(other_t, t)
        np.testing.assert_allclose(other_p, p, rtol=0, atol=tolerance * p.max(), err_msg=name)
        assert separation(wall[name]) == pytest.approx(separation(wall["plugin"]), rel=tolerance * 10), name
        tube_p = snapshot(tube["plugin"], "p")
        assert len(tube_p) == 201 and tube_p.max() > 0.003 and len(np.unique(tube_p)) > 10  # a fan, a shock
        np.testing.assert_allclose(snapshot(tube[name], "p"), tube_p, rtol=0, atol=tolerance * tube_p.max(),
                                   err_msg=name)

    # The sweep: each law's scene written as a file (JSON is YAML), its impact speed swept.
    tables = {}
    for name, law in laws.items():
        entry = law.spec if isinstance(law, rigidity.Material) else law
        (tmp_path / (name + ".yaml")).write_text(json.dumps(dict(scene(entry, False), name=name)))
        (tmp_path / (name + "_sweep.yaml")).write_text(
            "scene: %s.yaml\nparameters:\n  bodies.0.velocity: {values: [0.02, 0.05, 0.08]}\n"
            "collect:\n  p_max: probe.wall.p.max\n  contact_time: event.separation.first.t\n" % name)
        tables[name] = rigidity.sweep(tmp_path / (name + "_sweep.yaml"), jobs=2)
    assert list(tables["plugin"]["status"]) == ["ok"] * 3
    for name, tolerance in (("formula", 1e-13), ("python", 2e-6)):
        np.testing.assert_allclose(tables[name]["p_max"], tables["plugin"]["p_max"], rtol=tolerance * 10, err_msg=name)
        np.testing.assert_allclose(tables[name]["contact_time"], tables["plugin"]["contact_time"],
                                   rtol=tolerance * 10, err_msg=name)
