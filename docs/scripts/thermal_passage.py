"""docs/img/thermal_passage.png: the groove of examples/ehl_thermal_transient_groove.toml passing
through the thesis Table 3.6 line, thermal against isothermal, at SRR 0.3 and 1.0:

    for s in 0.3 1.0; do
      ehl run examples/ehl_thermal_transient_groove.toml --set motion.slide_to_roll=$s --out out/tt_$s
      ehl run examples/ehl_transient_line_groove.toml --set grid.nx=256 --set motion.slide_to_roll=$s --out out/ti_$s
    done
    python docs/scripts/thermal_passage.py out docs/img/thermal_passage.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def col(rows, key, scale=1.0):
    return [float(r[key]) * scale if r[key] else float("nan") for r in rows]


root, out = sys.argv[1:3]
fig, axes = plt.subplots(3, 2, figsize=(12, 10), sharex=True)
for c, s in enumerate(["0.3", "1.0"]):
    th = read(f"{root}/tt_{s}/timeline.csv")
    iso = read(f"{root}/ti_{s}/timeline.csv")
    x_t, x_i = col(th, "x_p_m", 1e3), col(iso, "x_p_m", 1e3)
    a = axes[0][c]
    a.plot(x_i, col(iso, "friction_coefficient"), "--", label="isothermal")
    a.plot(x_t, col(th, "friction_coefficient"), "-", label="thermal")
    a.set_ylabel("friction coefficient f")
    a.set_title(f"SRR {s}")
    a.set_ylim(bottom=0)
    b = axes[1][c]
    b.plot(x_i, col(iso, "central_film_m", 1e6), "--", color="C0", label="central, isothermal")
    b.plot(x_t, col(th, "central_film_m", 1e6), "-", color="C0", label="central, thermal")
    b.plot(x_i, col(iso, "min_film_m", 1e6), "--", color="C2", label="minimum, isothermal")
    b.plot(x_t, col(th, "min_film_m", 1e6), "-", color="C2", label="minimum, thermal")
    b.set_ylabel("film thickness (um)")
    b.set_ylim(bottom=0)
    t = axes[2][c]
    t0 = 313.0
    t.plot(x_t, [v - t0 for v in col(th, "max_film_temperature_k")], label="film, max across z")
    t.plot(x_t, [v - t0 for v in col(th, "max_surface_temperature_1_k")], label="surface of body 1 (groove)")
    t.plot(x_t, [v - t0 for v in col(th, "max_surface_temperature_2_k")], label="surface of body 2")
    t.set_ylabel("largest rise above 313 K (K)")
    t.set_xlabel("x_p, groove centre (mm)")
    t.set_ylim(bottom=0)
    for ax in (a, b, t):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
fig.suptitle("Groove 0.38 mm x 0.25 um on body 1 through the thesis Table 3.6 line (256 cells, 200 steps)")
fig.tight_layout()
fig.savefig(out, dpi=90)
