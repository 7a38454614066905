"""docs/img/thermal_passage.png: the groove of examples/ehl_thermal_transient_groove.toml passing
through the thesis Table 3.6 line, thermal against isothermal, at SRR 0.3 and 1.0:

    for s in 0.3 1.0; do
      ehl run examples/ehl_thermal_transient_groove.toml --set motion.slide_to_roll=$s --out out/tt_$s
      ehl run examples/ehl_transient_line_groove.toml --set grid.nx=256 --set motion.slide_to_roll=$s --out out/ti_$s
    done
    python docs/scripts/thermal_passage.py out docs/img/thermal_passage.png

docs/img/thermal_pit_passage.png: the thesis single pit (examples/ehl_thesis_ch3_single_pit.toml)
on the finite rollers, 128 x 128 cells, thermal (its case with the [thermal] table of
ehl_thermal_transient_groove.toml appended, as pit_thermal.toml) against isothermal:

    for s in 0.3 1.0; do
      ehl run pit_thermal.toml --set grid.nx=128 --set grid.ny=128 --set motion.slide_to_roll=$s --out out/pt_$s
      ehl run examples/ehl_thesis_ch3_single_pit.toml --set grid.nx=128 --set grid.ny=128 --set motion.slide_to_roll=$s --out out/pi_$s
    done
    python docs/scripts/thermal_passage.py out docs/img/thermal_pit_passage.png pit
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
kind = sys.argv[3] if len(sys.argv) > 3 else "groove"
thermal_dir, iso_dir = ("pt", "pi") if kind == "pit" else ("tt", "ti")
fig, axes = plt.subplots(3, 2, figsize=(12, 10), sharex=True)
for c, s in enumerate(["0.3", "1.0"]):
    th = read(f"{root}/{thermal_dir}_{s}/timeline.csv")
    iso = read(f"{root}/{iso_dir}_{s}/timeline.csv")
    x_t, x_i = col(th, "x_p_m", 1e3), col(iso, "x_p_m", 1e3)
    a = axes[0][c]
    f_i, f_t = col(iso, "friction_coefficient"), col(th, "friction_coefficient")
    if kind == "pit":
        # a pit on a finite roller moves f by hundredths of a percent: show the change
        a.plot(x_i, [100 * (v / f_i[0] - 1) for v in f_i], "--", label=f"isothermal (f = {f_i[0]:.5f} at the start)")
        a.plot(x_t, [100 * (v / f_t[0] - 1) for v in f_t], "-", label=f"thermal (f = {f_t[0]:.5f} at the start)")
        a.set_ylabel("friction coefficient, change\nfrom the start (%)")
    else:
        a.plot(x_i, f_i, "--", label="isothermal")
        a.plot(x_t, f_t, "-", label="thermal")
        a.set_ylabel("friction coefficient f")
        a.set_ylim(bottom=0)
    a.set_title(f"SRR {s}")
    b = axes[1][c]
    b.plot(x_i, col(iso, "central_film_m", 1e6), "--", color="C0", label="central, isothermal")
    b.plot(x_t, col(th, "central_film_m", 1e6), "-", color="C0", label="central, thermal")
    # a finite roller's overall minimum sits at its free ends: the pit's row shows the pit
    mkey, mname = ("centerline_min_film_m", "minimum on the row y = 0") if kind == "pit" else ("min_film_m", "minimum")
    b.plot(x_i, col(iso, mkey, 1e6), "--", color="C2", label=f"{mname}, isothermal")
    b.plot(x_t, col(th, mkey, 1e6), "-", color="C2", label=f"{mname}, thermal")
    b.set_ylabel("film thickness (um)")
    b.set_ylim(bottom=0)
    t = axes[2][c]
    t0 = 313.0
    t.plot(x_t, [v - t0 for v in col(th, "max_film_temperature_k")], label="film, max across z")
    t.plot(x_t, [v - t0 for v in col(th, "max_surface_temperature_1_k")], label=f"surface of body 1 ({kind})")
    t.plot(x_t, [v - t0 for v in col(th, "max_surface_temperature_2_k")], label="surface of body 2")
    t.set_ylabel("largest rise above 313 K (K)")
    t.set_xlabel(f"x_p, {kind} centre (mm)")
    t.set_ylim(bottom=0)
    for ax in (a, b, t):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
if kind == "pit":
    fig.suptitle(
        "Thesis pit 0.38 x 0.5 mm x 25 nm on body 1 through the Table 3.6 finite rollers"
        " (128 x 128 cells, 150 steps)"
    )
else:
    fig.suptitle("Groove 0.38 mm x 0.25 um on body 1 through the thesis Table 3.6 line (256 cells, 200 steps)")
fig.tight_layout()
fig.savefig(out, dpi=90)
