"""docs/img/thermal_ball_traction.png from four `ehl sweep` runs over the slide-to-roll ratio of
the glass-disc ball at 3 m/s (examples/ehl_thermal_ball.toml and its isothermal twin,
examples/ehl_ball_on_glass.toml, the same ball, oil and grid), each with the example's
Newtonian oil and with Carreau and a limiting shear stress:

    V=motion.slide_to_roll=0.02,0.05,0.1,0.2,0.3,0.5,0.7,1.0,1.5,2.0
    C='lubricant.rheology={ model = "carreau", shear_modulus = 4.5e6, power_law_index = 0.57, limiting_shear_coefficient = 0.07 }'
    S=motion.entrainment_speed=3
    ehl sweep examples/ehl_thermal_ball.toml --set $S --vary $V --out out/ball-thermal-newt
    ehl sweep examples/ehl_thermal_ball.toml --set $S --set "$C" --vary $V --out out/ball-thermal-car
    ehl sweep examples/ehl_ball_on_glass.toml --set $S --vary $V --out out/ball-iso-newt
    ehl sweep examples/ehl_ball_on_glass.toml --set $S --set "$C" --vary $V --out out/ball-iso-car
    python docs/scripts/thermal_ball_traction.py out/ball docs/img/thermal_ball_traction.png
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
    col = lambda k, s=1.0: [float(r[k]) * s if r[k] else float("nan") for r in rows]
    return {
        "srr": col("motion.slide_to_roll"),
        "f": col("friction_coefficient"),
        "h": col("central_film_m", 1e6),
        "t": col("max_film_temperature_k"),
    }


prefix, out = sys.argv[1:3]
runs = {k: read(f"{prefix}-{k}") for k in ("thermal-newt", "thermal-car", "iso-newt", "iso-car")}
style = {
    "newt": ("C0", "Newtonian (the example's oil)"),
    "car": ("C1", "Carreau + limiting shear stress (Lambda 0.07)"),
}
fig, (a, b, c) = plt.subplots(1, 3, figsize=(16, 4.8))
for oil, (color, name) in style.items():
    th, iso = runs[f"thermal-{oil}"], runs[f"iso-{oil}"]
    a.loglog(iso["srr"], iso["f"], "s--", color=color, mfc="none", label=f"{name}, isothermal")
    a.loglog(th["srr"], th["f"], "o-", color=color, label=f"{name}, thermal")
    b.semilogx(iso["srr"], iso["h"], "s--", color=color, mfc="none", label=f"{name}, isothermal")
    b.semilogx(th["srr"], th["h"], "o-", color=color, label=f"{name}, thermal")
    c.semilogx(th["srr"], th["t"], "o-", color=color, label=f"{name}, thermal")
a.set_xlabel("slide-to-roll ratio SRR")
a.set_ylabel("friction coefficient f")
a.set_title("Traction")
a.legend(fontsize=8)
b.set_xlabel("slide-to-roll ratio SRR")
b.set_ylabel("central film thickness (um)")
b.set_title("Central film")
b.legend(fontsize=8)
c.set_xlabel("slide-to-roll ratio SRR")
c.set_ylabel("largest film temperature (K)")
c.set_title("Film temperature (inlet 313 K)")
c.legend(fontsize=8)
for ax in (a, b, c):
    ax.grid(True, which="both", alpha=0.3)
fig.suptitle(
    "Steel ball R = 12.5 mm on a glass disc, 15 N, u_e = 3 m/s, 129 x 129 cells "
    "(SRR 2: the disc at rest)"
)
fig.tight_layout()
fig.savefig(out, dpi=110)
