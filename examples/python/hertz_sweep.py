#!/usr/bin/env python3
"""Parameter sweeps from Python with the signorini package.

1. Hertz (examples/hertz): the hemisphere pressed on the rigid plane by
   five prescribed displacements of its flat face; the contact radius a
   (least-squares fit of p² = p0²(1 − r²/a²) over the nodes with
   p > 0.2 p0, p the nominal pressure, force over reference area, as in
   examples/hertz/README.md) against the total force F,
   with Hertz's a = (3FR / 4E*)^(1/3), E* = E / (1 − ν²).
2. Friction (examples/press-pull): the block pressed by 20 and pulled by
   4.8 for five friction coefficients μ (capacity μN from 5 to 20): the
   share of slipping contact nodes and the pull-side displacement.

Usage (from the repository's root, after `pip install ./python matplotlib`):

    python3 examples/python/hertz_sweep.py [output folder]

Writes hertz_sweep.png into the folder (default examples/python/results)
and prints the numbers: ten runs, about 65 s of CPU time (2.8 to 3.9
minutes of wall time measured on two cores shared with other builds).
"""

import math
import pathlib
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import signorini  # noqa: E402

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]
E, NU, R = 1000.0, 0.3, 1.0  # examples/hertz/case.toml and hemisphere.geo
E_STAR = E / (1.0 - NU * NU)


def hertz_sweep(depths=(0.005, 0.0065, 0.008, 0.0095, 0.0115)):
    folder = EXAMPLES / "hertz"
    text = (folder / "case.toml").read_text()
    rows = []
    for depth in depths:
        case = signorini.Case.from_toml(text.replace("z = -0.0115", f"z = {-depth}"), folder)
        result = signorini.Simulation(case, threads=2).run()
        force = 4.0 * result.contact["pole"]["force"][2]  # quarter model
        a_hertz = (3.0 * force * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
        p0 = 3.0 * force / (2.0 * math.pi * a_hertz**2)
        # the nominal pressure: contact_traction's normal (z) component on the
        # plane; contact_pressure (dual mortar's multiplier) is per current area
        nominal = np.abs(result.last.contact_traction[:, 2])
        a_fit = signorini.contact_radius(case, result.last, 0.2 * p0, pressure=nominal)
        rows.append((depth, force, a_fit, a_hertz))
        print(f"depth {depth:.4f}: F = {force:.4f}, a = {a_fit:.5f}, Hertz {a_hertz:.5f} "
              f"({100 * (a_fit / a_hertz - 1):+.2f} %)")
    return np.array(rows)


def friction_sweep(mus=(0.25, 0.3, 0.4, 0.6, 1.0)):
    folder = EXAMPLES / "press-pull"
    text = (folder / "case.toml").read_text()
    rows = []
    for mu in mus:
        case = signorini.Case.from_toml(
            text.replace("friction_coefficient = 0.3", f"friction_coefficient = {mu}"), folder
        )
        result = signorini.Simulation(case, threads=2).run()
        status = result.contact_status[np.isfinite(result.gap)]
        closed = np.count_nonzero(status > 0)
        slip = np.count_nonzero(status == 2)
        right = case.surface_nodes("right")
        ux = result.displacement[right, 0].mean()
        ft = result.contact["base"]["tangential_force"][0]
        rows.append((mu, slip / closed, ux))
        print(f"mu {mu:.2f}: {slip}/{closed} nodes slip, friction force {ft:.4f}, "
              f"right side u_x {ux:.5f}")
    return np.array(rows)


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).parent / "results"
    out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    hertz = hertz_sweep()
    friction = friction_sweep()
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    forces = np.linspace(0.0, hertz[:, 1].max() * 1.1, 200)
    left.plot(forces, (3.0 * forces * R / (4.0 * E_STAR)) ** (1.0 / 3.0), "k-", label="Hertz")
    left.plot(hertz[:, 1], hertz[:, 2], "o", label="signorini (fit of p²)")
    left.set_xlabel("total force F")
    left.set_ylabel("contact radius a")
    left.set_title("Hertz: sphere on a rigid plane")
    left.legend()
    right.plot(friction[:, 0], friction[:, 1], "o-", label="slipping share of closed nodes")
    right.set_xlabel("friction coefficient μ")
    right.set_ylabel("slipping share")
    twin = right.twinx()
    twin.plot(friction[:, 0], friction[:, 2], "s--", color="C1", label="right side u_x")
    twin.set_ylabel("right side u_x")
    right.set_title("press-pull: N = 20, pull 4.8")
    right.legend(loc="upper right")
    fig.tight_layout()
    fig.savefig(out / "hertz_sweep.png", dpi=110)
    print(f"wrote {out / 'hertz_sweep.png'} in {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
