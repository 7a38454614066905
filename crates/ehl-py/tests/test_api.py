"""The Python API: cases, errors, solutions, arrays, writing."""

import copy
import json
import math
import pathlib
import threading
import time

import numpy as np
import pytest

import ehl
from conftest import example


def small_ehl() -> ehl.Case:
    c = ehl.Case.from_file(example("ehl_thesis_ch2_roller.toml"))
    c.set("grid.nx", 128)
    c.set("grid.ny", 32)
    return c


def case_check(c: ehl.Case) -> dict:
    """`c.check()` without `memory_limit_bytes`: that is the machine's available memory at the
    call (MemAvailable), not a property of the case, and moves between two calls."""
    d = c.check()
    assert d["memory_limit_bytes"] > 0
    del d["memory_limit_bytes"]
    # (and a transient [stress] case's frames kept in memory, sized from the same budget)
    if d.get("transient"):
        d["transient"].pop("frames_every", None)
        d["transient"].pop("frames_bytes", None)
    return d


def test_from_file_set_check():
    c = ehl.Case.from_file(example("ehl_thesis_ch2_roller.toml"))
    assert c.kind == "ehl" and not c.transient
    hertz = c.check()["hertz_pressure_pa"]
    c.set("load.force", 5000)
    assert c.get("load.force") == 5000
    assert c.overrides == ["load.force=5000"]
    d = c.check()
    # line contact: p_h grows with the square root of the load
    assert d["hertz_pressure_pa"] == pytest.approx(hertz * math.sqrt(5000 / 6000), rel=1e-12)
    assert d["load_n"] == pytest.approx(5000, rel=1e-12)
    for key in ["W", "U", "G", "moes_M", "moes_L", "reduced_modulus_pa", "hertz_half_width_m"]:
        assert d[key] > 0, key
    names = [f["formula"] for f in d["film_estimates"]]
    assert "Pan-Hamrock (1989)" in names
    assert d["transient"] is None
    assert "ehl.Case(" in repr(c) and "load 5000.0 N" in repr(c)


def test_check_gives_the_stress_figures(monkeypatch):
    # the memory limit pinned (it is the machine's free memory otherwise, which moves between
    # two calls and on a loaded machine may fall below any estimate)
    monkeypatch.setenv("EHL_MEMORY_LIMIT", "1e10")
    c = ehl.Case.from_file(example("stress_line_sliding.toml"))
    assert c.check()["stress"]["fatigue"]["stress_exponent"] == pytest.approx(31 / 3)
    c.set("fatigue.stress_exponent", 40)
    st = c.check()["stress"]
    assert st["layers"] == c.get("stress.layers") and st["depth_over_b"] == pytest.approx(3.0)
    assert st["fatigue"]["stress_exponent"] == 40 and st["window_m"] is None
    assert c.check()["memory_limit_bytes"] == 1e10
    assert 0 < c.check()["memory_estimate_bytes"] < 1e10
    assert ehl.Case.from_file(example("ehl_thesis_ch2_roller.toml")).check()["stress"] is None


def test_check_gives_the_thermal_figures():
    c = ehl.Case.from_file(example("ehl_thermal_line.toml"))
    d = c.check()
    t = d["thermal"]
    # L = eta0 beta u_e^2 / k_f with u_e = U E' R / eta0 (the example: eta0 0.04 Pa s, k_f 0.14)
    u_e = d["U"] * d["reduced_modulus_pa"] * d["reduced_radius_m"] / 0.04
    assert t["thermal_loading_L"] == pytest.approx(0.04 * t["viscosity_beta_1_k"] * u_e**2 / 0.14, rel=1e-12)
    assert 0 < t["gupta_film_ratio"] < t["murch_wilson_film_ratio"] < 1
    assert t["points_across_film"] == 7 and t["inlet_temperature_k"] == 313.0
    assert not t["above_converged_loading"]
    # L grows with the square of the speed
    c.set("motion.dimensionless_speed", 2 * c.get("motion.dimensionless_speed"))
    t2 = c.check()["thermal"]
    assert t2["thermal_loading_L"] == pytest.approx(4 * t["thermal_loading_L"], rel=1e-12)
    assert t2["above_converged_loading"]
    assert ehl.Case.from_file(example("ehl_friction_line.toml")).check()["thermal"] is None


def test_check_gives_the_steps_for_one_cell_a_step():
    c = ehl.Case.from_file(example("ehl_transient_line_groove.toml"))
    t = c.check()["transient"]
    # the example moves its groove 1.55 cells a step: not coarse
    assert t["steps_for_one_cell"] is None and 1 < t["feature_cells_per_step"] < 2
    c.set("motion.travel.steps", 50)
    t = c.check()["transient"]
    assert t["steps_for_one_cell"] == math.ceil(50 * t["feature_cells_per_step"])
    c.set("motion.travel.steps", t["steps_for_one_cell"])
    t = c.check()["transient"]
    assert t["steps_for_one_cell"] is None and t["feature_cells_per_step"] <= 1


def test_from_toml_and_from_dict_give_the_same_case():
    path = example("dry_roller_mirror1_psi.toml")
    a = ehl.Case.from_file(path)
    b = ehl.Case.from_toml(path.read_text(), file=str(path))
    c = ehl.Case.from_dict(a.to_dict())
    for x in (b, c):
        assert case_check(x) == case_check(a)
    assert case_check(ehl.Case.from_toml(a.to_toml())) == case_check(a)


def test_set_accepts_tables_lists_and_numpy_values():
    c = ehl.Case.from_file(example("dry_roller_mirror1_psi.toml"))
    c.set("body1.profile", {"kind": "crowned", "crown_radius": 0.5})
    assert c.get("body1.profile") == {"kind": "crowned", "crown_radius": 0.5}
    c.set("grid.nx", np.int64(64))
    c.set("load.force", np.float64(4000.0))
    assert c.get("grid.nx") == 64 and c.get("load.force") == 4000.0
    t = ehl.Case.from_file(example("ehl_thesis_ch3_single_pit.toml"))
    t.set("output.snapshots", np.array([-0.5e-3, 0.0]))
    assert t.get("output.snapshots") == [-0.5e-3, 0.0]
    t.set("features[0].depth", 5e-8)
    assert t.get("features[0].depth") == 5e-8
    assert t.transient and t.check()["transient"]["steps"] == 150


def test_get_follows_every_index_or_says_why_not():
    t = ehl.Case.from_file(example("ehl_thesis_ch3_single_pit.toml"))
    t.set("output.snapshots", [-0.5e-3, 0.0])
    assert t.get("features[0]")["depth"] == t.get("features[0].depth")
    assert t.get("features.0.depth") == t.get("features[0].depth")
    assert t.get("output.snapshots") == [-0.5e-3, 0.0]
    # more indices than the value has, or an index past the end: an error, never the array
    for key in ["features[0][1]", "features[0][0].depth", "features[5].depth",
                "output.snapshots[0]", "output.snapshots[0][1]"]:
        with pytest.raises(ehl.CaseError) as e:
            t.get(key)
        assert e.value.key is not None, key
    # an entry past the end is said to be missing, not to have a default (a scan)
    with pytest.raises(ehl.CaseError, match="index 5 does not exist: `features` has 1 entry"):
        t.get("features[5].depth")


def test_a_bad_key_raises_case_error_naming_the_key():
    c = ehl.Case.from_file(example("ehl_thesis_ch2_roller.toml"))
    with pytest.raises(ehl.CaseError) as e:
        c.set("load.forse", 5000)
    assert e.value.key == "load.forse"
    assert "load.force" in e.value.reason  # the closest valid key
    assert e.value.file.endswith("ehl_thesis_ch2_roller.toml")
    assert "--set" not in str(e.value)
    assert c.overrides == []  # unchanged
    # a bad value names its key too
    with pytest.raises(ehl.CaseError) as e:
        c.set("body1.radius", -1.0)
    assert e.value.key == "body1.radius"
    with pytest.raises(ehl.CaseError) as e:
        c.set("grid.nx", None)
    assert e.value.key == "grid.nx"
    with pytest.raises(ehl.CaseError) as e:
        c.set("grid.nx", object())
    assert e.value.key == "grid.nx"
    # an unknown key in a dict, and text that is not TOML
    d = c.to_dict()
    d["lubricant"]["viscosty"] = 0.04
    with pytest.raises(ehl.CaseError) as e:
        ehl.Case.from_dict(d)
    assert e.value.key == "lubricant.viscosty" and e.value.file == "<dict>"
    # a value with no case-file form names its key, also inside a list of tables
    d = c.to_dict()
    d["load"]["force"] = object()
    with pytest.raises(ehl.CaseError) as e:
        ehl.Case.from_dict(d)
    assert e.value.key == "load.force" and "load.force" in str(e.value)
    d = ehl.Case.from_file(example("ehl_thesis_ch3_single_pit.toml")).to_dict()
    d["features"][0]["depth"] = {1: 2}
    with pytest.raises(ehl.CaseError) as e:
        ehl.Case.from_dict(d)
    assert e.value.key == "features[0].depth"
    with pytest.raises(ehl.CaseError) as e:
        ehl.Case.from_dict({1: 2})
    assert e.value.key is None and "not a string" in e.value.reason
    with pytest.raises(ehl.CaseError) as e:
        ehl.Case.from_toml("kind = ")
    assert e.value.key is None and "TOML" in e.value.reason
    with pytest.raises(ehl.CaseError):
        ehl.Case.from_file("no/such/case.toml")
    # CaseError is a ValueError, and every error an EhlError
    assert issubclass(ehl.CaseError, ValueError) and issubclass(ehl.CaseError, ehl.EhlError)


def test_set_and_solve_in_two_threads_raise_no_panic():
    """One thread changes a case while others solve and read it: no PanicException (Case.set
    used to release the GIL while parsing, and a solve meeting the case borrowed panicked)."""
    case = ehl.Case.from_file(example("dry_ball_on_flat.toml"))
    case.set("grid.nx", 16)
    case.set("grid.ny", 16)
    errors = []
    stop = threading.Event()

    def guarded(f):
        def run():
            try:
                while not stop.is_set():
                    f()
            except BaseException as e:  # PanicException is a BaseException
                errors.append(e)
                stop.set()
        return run

    loads = iter(range(10**9))
    threads = [
        threading.Thread(target=guarded(lambda: case.set("load.force", 100.0 + next(loads) % 7))),
        threading.Thread(target=guarded(lambda: ehl.solve(case, progress=False))),
        threading.Thread(target=guarded(lambda: (case.check(), case.get("load.force")))),
    ]
    for t in threads:
        t.start()
    time.sleep(1.5)
    stop.set()
    for t in threads:
        t.join()
    assert not errors, repr(errors)


def test_poll_nan_is_the_default():
    sol = ehl._solve(small_ehl(), None, float("nan"))
    assert sol.converged


def test_copy_is_independent():
    a = small_ehl()
    b = a.copy()
    b.set("load.force", 3000)
    assert "load.force=3000" not in a.overrides
    c = copy.deepcopy(b)
    assert c.overrides == b.overrides


def test_solution_arrays_are_read_only_views_of_the_right_shape():
    sol = ehl.solve(small_ehl(), progress=False)
    assert sol.converged
    ny, nx = 32, 128
    assert sol.x.shape == (nx,) and sol.y.shape == (ny,)
    for name in ["pressure", "film", "deformation", "viscosity", "density"]:
        a = getattr(sol, name)
        assert a.shape == (ny, nx) and a.dtype == np.float64, name
        assert not a.flags.writeable, name
        # no copy: two reads share the solution's memory
        assert np.shares_memory(a, getattr(sol, name)), name
        with pytest.raises(ValueError):
            a[0, 0] = 1.0
    p = sol.pressure
    del sol  # the view keeps the solution alive
    assert np.isfinite(p).all() and p.max() > 1e8
    s = ehl.solve(small_ehl(), progress=False)
    summ = s.summary
    assert summ["converged"] is True
    assert summ["max_pressure_pa"] == pytest.approx(s.pressure.max(), rel=1e-15)
    assert summ["grid_m"]["nx"] == nx and summ["case"]["grid"]["nx"] == nx
    assert s.timeline is None and s.frames is None
    r = repr(s)
    assert "converged" in r and "GPa" in r and "Thesis ch. 2" in r


def test_dry_solution_has_no_viscosity():
    c = ehl.Case.from_file(example("dry_roller_mirror1_psi.toml"))
    c.set("grid.nx", 48)
    c.set("grid.ny", 48)
    sol = ehl.solve(c, progress=False)
    assert sol.converged and sol.viscosity is None and sol.density is None
    assert sol.film.shape == (48, 48)


def test_thermal_solution_has_temperatures():
    c = ehl.Case.from_file(example("ehl_thermal_line.toml"))
    c.set("grid.nx", 128)
    sol = ehl.solve(c, progress=False)
    assert sol.converged
    t = sol.temperature
    assert set(t) >= {"mid_film", "max_film", "surface_1", "surface_2", "film_section",
                      "section_z", "section_y", "inlet"}
    for name in ["mid_film", "max_film", "surface_1", "surface_2"]:
        assert t[name].shape == (1, 128) and not t[name].flags.writeable, name
    nz = c.get("thermal.points_across_film")
    assert t["film_section"].shape == (nz, 128) and t["section_z"].shape == (nz, 128)
    # the summary's maximum is the maximum of the map (NaN where no film was solved)
    assert np.nanmax(t["max_film"]) == pytest.approx(sol.summary["max_film_temperature_k"], rel=1e-15)
    # the hottest point across the film is at least its hotter surface's temperature (the
    # surfaces are points of the section), and each body, heated by the sheared film upstream
    # of every point (SRR 0.3; Jaeger's moving source), stays above the inlet temperature:
    # measured at least 313.01 K on both surfaces and 319.6 K for the film's hottest point
    assert t["inlet"] == 313.0 and np.nanmin(t["max_film"]) > 313.0
    # an isothermal run has none
    assert ehl.solve(small_ehl(), progress=False).temperature is None


def test_a_case_pickles_with_its_overrides():
    import pickle

    c = ehl.Case.from_file(example("ehl_thesis_ch2_roller.toml"))
    c.set("grid.nx", 40)
    c.set("load.force", 5000)
    d = pickle.loads(pickle.dumps(c))
    assert d.to_dict() == c.to_dict() and d.file == c.file
    assert d.get("grid.nx") == 40 and d.get("load.force") == 5000
    assert case_check(d) == case_check(c)


def test_stress_solution_has_the_fields_of_stress_npz():
    c = ehl.Case.from_file(example("stress_line_sliding.toml"))
    c.set("grid.nx", 128)
    sol = ehl.solve(c, progress=False)
    assert sol.converged
    s = sol.stress
    nz = len(s["z"])
    assert c.get("stress.body") == "both"
    for body in [1, 2]:
        for name in ["sxx", "syy", "szz", "syz", "sxz", "sxy", "von_mises", "tresca"]:
            a = s[f"{name}_{body}"]
            assert a.shape == (nz, 1, 128) and a.dtype == np.float32, name
    # the summary's maximum is the field's (float32 storage: 1e-6 relative)
    vm = max(float(np.max(s[k])) for k in s if k.startswith("von_mises_"))
    assert vm == pytest.approx(sol.summary["max_von_mises_pa"], rel=1e-6)
    assert s["x"].shape == (128,) and s["x_p_m"] is None and s["with_traction"]
    # a case without [stress] has none
    assert ehl.solve(small_ehl(), progress=False).stress is None


def test_not_converged_returns_a_solution():
    c = small_ehl()
    c.set("solver.max_iterations", 1)
    sol = ehl.solve(c, progress=False)
    assert sol.converged is False
    assert sol.summary["converged"] is False
    assert "NOT converged" in repr(sol)


def test_transient_timeline_and_frames():
    c = ehl.Case.from_file(example("ehl_transient_line_groove.toml"))
    c.set("grid.nx", 128)
    c.set("motion.travel", {"from": -1.2e-3, "to": 1.0e-3, "steps": 20})
    c.set("output.frames_every", 5)
    c.set("output.snapshots", [0.0])
    sol = ehl.solve(c, progress=False)
    tl = sol.timeline
    assert list(tl["step"]) == list(range(21))
    assert tl["converged"].dtype == bool and tl["x_p_m"][0] == pytest.approx(-1.2e-3)
    assert [f["step"] for f in sol.frames] == [0, 5, 10, 15, 20]
    assert sol.frames[2]["pressure"].shape == (1, 128)
    assert sol.snapshots[0]["pressure"].shape == (1, 128)
    assert "time steps" in repr(sol)


def test_thermal_transient_timeline_has_temperatures():
    c = ehl.Case.from_file(example("ehl_thermal_transient_groove.toml"))
    c.set("grid.nx", 128)
    c.set("output.snapshots", [])
    c.set("motion.travel", {"from": -0.3e-3, "to": 0.0, "steps": 8})
    sol = ehl.solve(c, progress=False)
    assert sol.converged, sol.summary["termination"]
    tl = sol.timeline
    t = tl["max_film_temperature_k"]
    assert t.shape == (9,) and np.all(t > 313.0)
    assert np.all(np.abs(tl["energy_balance_error"]) < 1e-2)
    assert tl["thermal_passes"].dtype == np.int64
    # the summary's extreme over the travel is the timeline's
    assert sol.summary["max_film_temperature_over_travel_k"] == pytest.approx(t.max(), rel=1e-15)
    # the temperature maps are the last step's
    assert sol.temperature["max_film"].shape == (1, 128)


def test_progress_callback_sees_the_end():
    seen = []
    ehl.solve(small_ehl(), progress=lambda f, m: seen.append((f, m)))
    assert seen and seen[-1][0] == 1.0
    # progress=True off a terminal and without a notebook: no bar, no error
    ehl.solve(small_ehl(), progress=True)


def test_a_thermal_solve_reports_progress_that_never_goes_back():
    # the isothermal start filled the bar to 0.95 and the thermal iterations then reported 0.9
    # (a scan); now the fractions only grow, and the thermal ones come after the start's
    c = ehl.Case.from_file(example("ehl_thermal_line.toml"))
    c.set("grid.nx", 256)
    seen = []
    # the callback gets the latest report once per poll: at the default 0.05 s poll the thermal
    # iterations of a 128-cell line (~30 ms since 2026-11-27) could pass unseen, so poll every
    # millisecond on a line twice as long
    ehl._solve(c, lambda f, m: seen.append((f, m)), 0.001)
    known = [f for f, _ in seen if f == f]
    assert known == sorted(known), known
    assert any(m.startswith("thermal") for _, m in seen) and seen[-1][0] == 1.0


def test_a_value_that_contains_itself_is_a_case_error():
    # to_toml recursed without end and crashed the interpreter (a scan)
    d = {"kind": "ehl"}
    d["me"] = d
    with pytest.raises(ehl.CaseError, match="nests more than"):
        ehl.Case.from_dict(d)
    deep = 1.0
    for _ in range(20000):
        deep = [deep]
    c = small_ehl()
    with pytest.raises(ehl.CaseError, match="nests more than"):
        c.set("body1.profile", deep)
    assert c.get("grid.nx") == 128


def test_a_relative_height_map_is_found_after_a_change_of_folder(tmp_path, monkeypatch):
    # the case file's folder was kept relative, so after os.chdir a set or an unpickling read
    # the height map from the wrong place (a scan)
    import pickle

    (tmp_path / "case").mkdir()
    np.save(tmp_path / "case" / "surf.npy", np.full((2, 2), 1e-6))
    text = pathlib.Path(example("dry_ball_on_flat.toml")).read_text()
    text += '\n[[features]]\nkind = "height-map"\nfile = "surf.npy"\ndx = 1e-5\ndy = 1e-5\n'
    (tmp_path / "case" / "case.toml").write_text(text)
    monkeypatch.chdir(tmp_path)
    c = ehl.Case.from_file("case/case.toml")
    monkeypatch.chdir(tmp_path / "case")
    c.set("load.force", 10.0)
    d = pickle.loads(pickle.dumps(c))
    assert d.get("load.force") == 10.0 and case_check(d) == case_check(c)


def test_an_exception_in_the_callback_stops_the_solve():
    def boom(f, m):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        ehl.solve(small_ehl(), progress=boom)


def test_write_gives_the_cli_outputs_and_refuses_foreign_folders(tmp_path):
    sol = ehl.solve(small_ehl(), progress=False)
    out = tmp_path / "out"
    assert sol.write(out) == out and isinstance(sol.write(out), pathlib.Path)
    names = {p.name for p in out.iterdir()}
    assert {"summary.json", "fields.npz", "centerline.csv", "pressure.png", ".ehl-output"} <= names
    written = json.loads((out / "summary.json").read_text())
    mine = sol.summary
    for k in ["max_pressure_pa", "min_film_m", "central_film_m", "load_n"]:
        assert written[k] == mine[k]
    sol.write(out)  # ehl's own folder is replaced
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("keep")
    with pytest.raises(ehl.OutputError) as e:
        sol.write(foreign)
    assert isinstance(e.value, OSError) and "mine" in e.value.path
    assert [p.name for p in foreign.iterdir()] == ["notes.txt"]
    # nothing else was left beside the folders (no temporary folders, no lock files)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine", "out"]


def test_solve_takes_a_path():
    sol = ehl.solve(example("dry_ball_on_flat.toml"), progress=False)
    assert sol.converged


def test_a_tqdm_bar_on_a_terminal(monkeypatch, capsys):
    pytest.importorskip("tqdm")
    monkeypatch.setattr(ehl, "_interactive", lambda: True)  # as on a terminal or in a notebook
    ehl.solve(small_ehl(), progress=True)
    err = capsys.readouterr().err
    assert "100%" in err and "Thesis ch. 2" in err


def test_a_notebook_kernel_counts_as_interactive(monkeypatch):
    # the branch a Jupyter kernel takes, whatever stderr is: an IPython module whose shell
    # runs under an IPKernelApp
    import sys
    import types

    class Shell:
        config = {"IPKernelApp": {}}

    fake = types.ModuleType("IPython")
    fake.get_ipython = lambda: Shell()  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "IPython", fake)
    monkeypatch.setattr(sys, "stderr", open(__file__))  # a file: not a terminal
    try:
        assert ehl._interactive()
        Shell.config = {"TerminalIPythonApp": {}}  # IPython in a terminal, stderr redirected
        assert not ehl._interactive()
    finally:
        sys.stderr.close()


@pytest.mark.parametrize(
    "kind, cls, parent",
    [
        ("solver", ehl.SolverError, RuntimeError),
        ("case", ehl.CaseError, ValueError),
        ("case-file", ehl.CaseError, ValueError),
        ("output", ehl.OutputError, OSError),
    ],
)
def test_library_errors_become_their_python_classes(kind, cls, parent):
    e = ehl._ehl._exception_for(kind, "what went wrong")
    assert isinstance(e, cls) and isinstance(e, parent) and isinstance(e, ehl.EhlError)
    assert e.reason == "what went wrong" and "what went wrong" in str(e)
    if kind == "case":
        assert (e.file, e.key) == ("case.toml", "load.force")
    if kind == "output":
        assert e.path == "out"
    assert isinstance(ehl._ehl._exception_for("cancelled", ""), KeyboardInterrupt)
    with pytest.raises(ValueError):
        ehl._ehl._exception_for("no-such-kind", "")


def test_the_type_stubs_name_what_the_module_has():
    # every class, function and member of the compiled module is in _ehl.pyi, and the stubs
    # name nothing the module lacks
    import ast
    import inspect

    stub = ast.parse((pathlib.Path(ehl.__file__).parent / "_ehl.pyi").read_text())
    declared = {}
    for node in stub.body:
        if isinstance(node, ast.ClassDef):
            members = set()
            for n in node.body:
                if isinstance(n, ast.FunctionDef):
                    members.add(n.name)
                elif isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name):
                    members.add(n.target.id)
            declared[node.name] = members
        elif isinstance(node, ast.FunctionDef):
            declared[node.name] = None
    module = ehl._ehl
    actual = {n for n in dir(module) if not n.startswith("__")}
    assert set(declared) == actual, set(declared) ^ actual
    for name, members in declared.items():
        obj = getattr(module, name)
        if members is None:
            assert callable(obj), name
            continue
        have = {m for m, _ in inspect.getmembers(obj) if not m.startswith("__")}
        public = {m for m in members if not m.startswith("__")}
        assert public == have, f"{name}: {public ^ have}"
        for dunder in members - public:
            assert hasattr(obj, dunder), f"{name}.{dunder}"
