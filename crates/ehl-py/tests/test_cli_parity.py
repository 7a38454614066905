"""Python results equal the `ehl` program's for the same case and overrides, to 1e-12."""

import csv
import json
import subprocess

import numpy as np
import pytest

import ehl
from conftest import example

RTOL = 1e-12

CASES = {
    "dry": ("dry_roller_mirror1_psi.toml", {"grid.nx": 64, "grid.ny": 64}),
    "ehl-sliding": (
        "ehl_thesis_ch2_roller.toml",
        {"grid.nx": 128, "grid.ny": 32, "motion.slide_to_roll": 0.1},
    ),
    "ball": ("ehl_ball_on_glass.toml", {"grid.nx": 48, "grid.ny": 48}),
    "transient": (
        "ehl_transient_line_groove.toml",
        {
            "grid.nx": 192,
            "motion.travel": {"from": -1.2e-3, "to": 1.0e-3, "steps": 30},
            "output.animation": False,
            "output.snapshots": [0.0],
        },
    ),
}


def close(a, b, where):
    """Numbers equal to RTOL (relative, with an absolute floor at 1e-300), recursively."""
    if isinstance(a, dict):
        assert set(a) == set(b), where
        for k in a:
            # wall times differ from run to run
            if k not in ("wall_time_s", "thermal_time"):
                close(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            close(x, y, f"{where}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert a == pytest.approx(b, rel=RTOL, abs=1e-300), where
    else:
        assert a == b, where


@pytest.mark.parametrize("name", sorted(CASES))
def test_python_equals_cli(name, cli, tmp_path):
    file, sets = CASES[name]
    case = ehl.Case.from_file(example(file))
    for k, v in sets.items():
        case.set(k, v)
    out = tmp_path / "cli"
    args = [str(cli), "run", str(example(file)), "--out", str(out), "--quiet"]
    for o in case.overrides:
        args += ["--set", o]
    r = subprocess.run(args, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    sol = ehl.solve(case, progress=False)

    written = json.loads((out / "summary.json").read_text())
    close(sol.summary, written, "summary")

    fields = np.load(out / "fields.npz")
    for k in ["x", "y"]:
        np.testing.assert_allclose(getattr(sol, k), fields[k], rtol=RTOL, atol=0)
    for k in ["pressure", "deformation", "film", "viscosity", "density"]:
        mine = getattr(sol, k)
        if mine is None:
            assert k not in fields.files, k
            continue
        np.testing.assert_allclose(mine, fields[k], rtol=RTOL, atol=1e-300, err_msg=k)

    if sol.timeline is not None:
        with open(out / "timeline.csv") as f:
            rows = list(csv.DictReader(f))
        for k, col in sol.timeline.items():
            if k == "wall_time_s":
                continue
            theirs = [r[k] for r in rows]
            if col.dtype == bool:
                assert list(col) == [t == "true" for t in theirs], k
            else:
                t = np.array([float(x) if x != "" else np.nan for x in theirs])
                np.testing.assert_allclose(col, t, rtol=RTOL, atol=1e-300, err_msg=k)
        frames = np.load(out / "frames.npz")
        np.testing.assert_array_equal([f["step"] for f in sol.frames], frames["step"])
        stack = np.stack([f["pressure"] for f in sol.frames])
        np.testing.assert_allclose(stack, frames["pressure"], rtol=RTOL, atol=1e-300)

    # and Solution.write gives the same summary.json as the program (but the wall time)
    mine = tmp_path / "py"
    sol.write(mine)
    close(json.loads((mine / "summary.json").read_text()), written, "written summary")
