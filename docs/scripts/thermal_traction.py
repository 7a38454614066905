"""docs/img/thermal_traction.png from two `ehl sweep` runs over the slide-to-roll ratio:

    V=motion.slide_to_roll=0.01,0.02,0.05,0.1,0.15,0.2,0.3,0.5,0.7,1.0
    ehl sweep examples/ehl_thermal_line.toml  --set grid.nx=256 --vary $V --out out/traction-thermal
    ehl sweep examples/ehl_friction_line.toml --set grid.nx=256 --vary $V --out out/traction-iso
    python docs/scripts/thermal_traction.py out/traction-thermal out/traction-iso docs/img/thermal_traction.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(folder):
    with open(f"{folder}/sweep.csv") as f:
        rows = [r for r in csv.DictReader(f) if r["converged"] == "true"]
    rows.sort(key=lambda r: float(r["motion.slide_to_roll"]))
    s = [float(r["motion.slide_to_roll"]) for r in rows]
    f = [float(r["friction_coefficient"]) for r in rows]
    h = [float(r["central_film_m"]) * 1e6 for r in rows]
    return s, f, h


thermal, iso, out = sys.argv[1:4]
st, ft, ht = read(thermal)
si, fi, hi = read(iso)
fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))
a.semilogx(si, fi, "s--", label="isothermal (thesis model)")
a.semilogx(st, ft, "o-", label="thermal (this work)")
a.set_xlabel("slide-to-roll ratio SRR")
a.set_ylabel("friction coefficient f")
a.set_title("Traction, thesis Table 3.7 line (U = 7.3e-11, 256 cells)")
b.semilogx(si, hi, "s--", label="isothermal (thesis model)")
b.semilogx(st, ht, "o-", label="thermal (this work)")
b.set_xlabel("slide-to-roll ratio SRR")
b.set_ylabel("central film (um)")
b.set_title("Central film")
for ax in (a, b):
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
fig.tight_layout()
fig.savefig(out, dpi=100)
