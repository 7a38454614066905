"""docs/img/pits/thesis_pits_difference.png: what the thesis chapter 3 pits (25 nm deep) change in
the pressure and the film when they sit at the contact centre (x_p = 0), against the smooth
rollers on the same grid: the maps of p - p_smooth (MPa) and the film change along the roller
axis through the pits' row, for one pit, three pits and nine pits (thesis figs. 3.8-3.22).

    ehl run examples/ehl_thesis_ch3_single_pit.toml --out out/ch3_1pit
    ehl run examples/ehl_thesis_ch3_3_pits.toml --out out/ch3_3pits
    ehl run examples/ehl_thesis_ch3_9_pits.toml --out out/ch3_9pits
    ehl run examples/ehl_thesis_ch3_single_pit.toml --set 'features[0].depth=0.0' \
        --set motion.travel.steps=10 --set 'output.snapshots=[]' --out out/ch3_smooth
    ehl run examples/ehl_thesis_ch3_9_pits.toml --set 'features[0].depth=0.0' \
        --set motion.travel.steps=10 --set 'output.snapshots=[]' --out out/ch3_9smooth
    python docs/scripts/thesis_pits_difference.py out docs/img/pits/thesis_pits_difference.png

(the smooth runs' last step is the smooth steady solution: a zero-depth pit leaves every step on
it, tests/transient.rs)
"""
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

out, png = sys.argv[1], sys.argv[2]
cases = [
    ("one pit", "ch3_1pit", "ch3_smooth"),
    ("three pits", "ch3_3pits", "ch3_smooth"),
    ("nine pits", "ch3_9pits", "ch3_9smooth"),
]
fig, axes = plt.subplots(2, 3, figsize=(15, 8.5), gridspec_kw={"height_ratios": [3, 2]})
for col, (name, run, smooth) in enumerate(cases):
    f = np.load(f"{out}/{run}/snapshots/xp_0.000mm/fields.npz")
    s = np.load(f"{out}/{smooth}/fields.npz")
    x, y = f["x"] * 1e3, f["y"] * 1e3
    dp = (f["pressure"] - s["pressure"]) * 1e-6
    lim = np.abs(dp).max()
    ax = axes[0, col]
    im = ax.pcolormesh(x, y, dp, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="nearest")
    ax.set_xlim(-0.8, 0.8)
    ax.set_xlabel("x, rolling direction (mm)")
    ax.set_ylabel("y, roller axis (mm)")
    peak = f["pressure"].max() * 1e-9
    ax.set_title(f"{name} at x_p = 0: p - p_smooth\n(peak {peak:.4f} GPa, smooth {s['pressure'].max() * 1e-9:.4f} GPa)")
    fig.colorbar(im, ax=ax, label="pressure change (MPa)")
    # the film change along x through the middle of the pits' row nearest the roller's centre
    # (the row of the largest pressure change)
    j = int(np.argmax(np.abs(dp).max(axis=1)))
    h, h0 = f["film"][j], s["film"][j]
    ax = axes[1, col]
    ax.plot(x, (h - h0) * 1e9, color="tab:blue")
    ax.set_xlim(-0.8, 0.8)
    ax.set_xlabel(f"x, rolling direction (mm), along y = {y[j]:.3f} mm (through a pit)")
    ax.set_ylabel("film change h - h_smooth (nm)")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_title(f"film along that row: min {h.min() * 1e6:.3f} um (smooth {h0.min() * 1e6:.3f} um)")
fig.suptitle(
    "Thesis ch. 3 pits (0.38 x 0.5 mm, 25 nm deep, SRR 0.02, Table 3.6 rollers): "
    "the change they make at the contact centre",
    fontsize=13,
)
fig.tight_layout()
fig.savefig(png, dpi=90)
