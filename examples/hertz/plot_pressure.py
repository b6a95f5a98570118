#!/usr/bin/env python3
"""Plot the contact pressure p(r) of examples/hertz against Hertz's solution.

Usage (after `cargo run --release -- run examples/hertz/case.toml`):

    pip install meshio matplotlib
    python3 examples/hertz/plot_pressure.py [results folder]

Writes `pressure.png` in the results folder: every secondary node's
nominal pressure (force over reference area) against its distance from the axis, and Hertz's
p(r) = p0 sqrt(1 - r²/a²) with a and p0 from the computed total force.
"""
import json
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402

E, NU, R = 1000.0, 0.3, 1.0  # as in case.toml and hemisphere.geo

folder = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parent / "results"
summary = json.loads((folder / "summary.json").read_text())
last = summary["increments"][-1]
force = 4.0 * last["contact"]["pole"]["force"][2]  # quarter model
e_star = E / (1.0 - NU * NU)
a = (3.0 * force * R / (4.0 * e_star)) ** (1.0 / 3.0)
p0 = 3.0 * force / (2.0 * math.pi * a * a)

mesh = meshio.read(folder / last["file"])
x = mesh.points + mesh.point_data["displacement"]
secondary = ~np.isnan(mesh.point_data["gap"])
r = np.hypot(x[:, 0], x[:, 1])[secondary]
# the nominal pressure, the node's force over its reference area (Hertz's
# theory is small-strain): contact_traction's normal component on the plane
# z = 0; contact_pressure is the dual mortar multiplier, per current area
p = np.abs(mesh.point_data["contact_traction"][secondary][:, 2])

rr = np.linspace(0.0, 1.3 * a, 200)
plt.figure(figsize=(6, 4))
plt.plot(r / a, p / p0, ".", ms=3, label="signorini (nodes)")
plt.plot(rr / a, np.sqrt(np.clip(1 - (rr / a) ** 2, 0, None)), "k-", label="Hertz")
plt.xlim(0, 1.3)
plt.xlabel("r / a")
plt.ylabel("p / p0")
plt.title(f"Hertz contact: F = {force:.4g}, a = {a:.4g}, p0 = {p0:.4g}")
plt.legend()
plt.tight_layout()
plt.savefig(folder / "pressure.png", dpi=120)
print(f"wrote {folder / 'pressure.png'}")
