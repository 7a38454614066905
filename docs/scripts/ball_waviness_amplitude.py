#!/usr/bin/env python3
"""Amplitude reduction of transverse waviness in a circular EHL contact, pure rolling
(docs/pits.md, "Amplitude reduction", circular contact).

A ball (R = 12.5 mm) on a flat, E' = 219.8 GPa, Roelands and Dowson-Higginson, G = 4000; a
harmonic waviness of amplitude 5 % of the Hamrock-Dowson central film and crests along y on
the ball passes through the contact at the mean speed. The run goes on, one cell per step,
until the start's disturbance has crossed from the inlet (-4.5 a) to the centre, then one
period; A_d is half the range of the central film over that period.

  python3 docs/scripts/ball_waviness_amplitude.py W U NABLA [NX NY]

W = F / (E' R^2), U = eta0 u_e / (E' R) (point-contact groups; `ehl check` prints Moes' M and L
for them), NABLA = (lambda / a) M^(3/4) / L^(1/2), the line contact's group of Venner et al.
(1997), used here with the point contact's M, L and radius a. Needs the release build
(`cargo build --release`), or the program in $EHL.
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

EHL = os.environ.get("EHL", os.path.join(os.path.dirname(__file__), "..", "..", "target", "release", "ehl"))

CASE = """title = "circular contact, transverse waviness on the ball, pure rolling"
kind = "ehl"
[body1]
shape = "ball"
radius = 0.0125
youngs_modulus = 200e9
poisson_ratio = 0.3
[body2]
shape = "flat"
youngs_modulus = 200e9
poisson_ratio = 0.3
[load]
dimensionless_load = 3.05e-7
[motion]
dimensionless_speed = 1.95e-11
slide_to_roll = 0.0
[lubricant]
viscosity = 0.04
dimensionless_material = 4000
density = 870.0
viscosity_model = "roelands"
density_model = "dowson-higginson"
[grid]
nx = 256
ny = 128
x_min = -4.5
x_max = 1.5
y_min = -3.0
y_max = 3.0
[solver]
tolerance = 1e-6
"""
E_RED, RADIUS, ETA0 = 219.78e9, 0.0125, 0.04


def check(case, sets):
    """a (m), Moes M and L, and the Hamrock-Dowson central film (m) from `ehl check`."""
    cmd = [EHL, "check", case] + [a for s in sets for a in ("--set", s)]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    got = {}
    for line in out.splitlines():
        s = line.split()
        if line.strip().startswith("Hertz half-width b"):
            got["a"] = float(s[-2]) * 1e-6
        elif line.strip().startswith("Moes M"):
            got["M"] = float(s[-1])
        elif line.strip().startswith("Moes L"):
            got["L"] = float(s[-1])
        elif line.strip().startswith("Hamrock-Dowson"):
            got["hc"] = float(s[2]) * 1e-9
    return got["a"], got["M"], got["L"], got["hc"]


def amplitude_ratio(w, u, nabla, nx=256, ny=128):
    with tempfile.TemporaryDirectory() as tmp:
        case = os.path.join(tmp, "ball.toml")
        with open(case, "w") as f:
            f.write(CASE)
        sets = [f"load.dimensionless_load={w}", f"motion.dimensionless_speed={u}"]
        a, m, l, hc = check(case, sets)
        ue = u * E_RED * RADIUS / ETA0
        lam = nabla * math.sqrt(l) / m**0.75 * a
        dx = 6.0 * a / nx
        flush = math.ceil(4.5 * a / dx) + 20
        steps = flush + math.ceil(lam / dx)
        ai = 0.05 * hc
        sets += [
            f"grid.nx={nx}",
            f"grid.ny={ny}",
            f"motion.travel={{ duration = {steps * dx / ue}, steps = {steps} }}",
            f'features=[{{ kind = "waviness", body = 1, amplitude = {ai}, wavelength = {lam}, x = 0.0, y = 0.0 }}]',
            "output.frames_every=100000",
            "output.animation=false",
        ]
        out = os.path.join(tmp, "out")
        cmd = [EHL, "run", case, "-q", "--out", out] + [a for s in sets for a in ("--set", s)]
        subprocess.run(cmd, check=True, capture_output=True)
        with open(os.path.join(out, "timeline.csv")) as f:
            h = [float(r["central_film_m"]) for r in list(csv.DictReader(f))[flush + 1:]]
    return m, l, lam / a, lam / dx, (max(h) - min(h)) / 2.0 / ai


if __name__ == "__main__":
    w, u, nabla = map(float, sys.argv[1:4])
    nx = int(sys.argv[4]) if len(sys.argv) > 4 else 256
    ny = int(sys.argv[5]) if len(sys.argv) > 5 else 128
    m, l, lam_a, cells, ratio = amplitude_ratio(w, u, nabla, nx, ny)
    line = 1.0 / (1.0 + 0.17 * nabla + 0.03 * nabla**2)
    print(f"M {m:.1f} L {l:.2f} nabla {nabla:g} lambda/a {lam_a:.3f} ({cells:.0f} cells a wavelength): "
          f"A_d/A_i {ratio:.4f} (line-contact fit {line:.4f})")
