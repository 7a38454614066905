#!/usr/bin/env python3
"""docs/img/pits/amplitude_reduction.png: A_d / A_i of transverse waviness against nabla, the line
contact (infinite line, 2048 cells) and the circular contact (ball on flat, 256 x 128 cells),
our solutions beside the line-contact fit of Venner et al. (1997). The numbers are the ones of
docs/pits.md's two tables ("Amplitude reduction", "The circular contact"), measured with
`cargo test --release -p ehl --test transient waviness_amplitude_reduction_probe -- --ignored`
and `docs/scripts/ball_waviness_amplitude.py`; this script only draws them.

    python3 docs/scripts/amplitude_reduction_figure.py docs/img/pits/amplitude_reduction.png
"""
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

png = sys.argv[1]
nabla = [1, 2, 4, 10]
line = {  # M, L: A_d / A_i at nabla 1, 2, 4, 10 (2048 cells)
    "line, M = 20, L = 10": [0.962, 0.781, 0.493, 0.189],
    "line, M = 50, L = 10": [0.934, 0.762, 0.469, 0.1749],
    "line, M = 100, L = 10": [0.922, 0.7515, 0.4642, 0.1705],
}
circle = {  # nabla: value (256 x 128 cells)
    "circle, M = 19.5, L = 10": ([1, 2, 4, 10], [0.962, 0.967, 0.827, 0.481]),
    "circle, M = 50, L = 10": ([4, 10], [0.911, 0.560]),
}
fig, ax = plt.subplots(figsize=(8, 5.5))
n = np.geomspace(0.5, 20, 200)
ax.plot(n, 1 / (1 + 0.17 * n + 0.03 * n**2), "k-", label="line-contact fit, 1/(1 + 0.17 nabla + 0.03 nabla²)")
for (name, v), c in zip(line.items(), ["tab:blue", "tab:cyan", "tab:purple"]):
    ax.plot(nabla, v, "o--", color=c, label=name)
for (name, (x, v)), c in zip(circle.items(), ["tab:red", "tab:orange"]):
    ax.plot(x, v, "s-", color=c, label=name)
ax.plot([4], [0.4915], "D", color="tab:green", ms=9, label="finite roller 40 b long, centre row (2D solver)")
ax.set_xscale("log")
ax.set_xlabel("nabla = (lambda / b) M^(3/4) / L^(1/2)   (b: Hertz half-width, or radius a)")
ax.set_ylabel("A_d / A_i  (film amplitude at the centre / waviness amplitude)")
ax.set_ylim(0, 1.1)
ax.set_title("Transverse waviness in pure rolling: the circular contact flattens it less")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8, loc="lower left")
fig.tight_layout()
fig.savefig(png, dpi=110)
