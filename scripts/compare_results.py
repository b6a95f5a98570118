#!/usr/bin/env python3
"""Compare two result folders of the same case (two strategies, two paths).

    scripts/compare_results.py FOLDER_A FOLDER_B [PROFILE.csv ...]

Prints, for the last increment of each run: whether the increment times
agree; every contact interface's numbers of `summary.json` (force,
tangential force, node counts, area, penetration) with their relative
difference; for each profile CSV named (such as `load_axis_shear.csv`),
the largest difference of `contact_pressure` and `tangential_traction`
over the largest magnitude in B, and the nodes whose stick/slip status
differs; and the largest difference of the last VTU's `displacement`
over the largest displacement in B, and of its `contact_traction` node
by node (apart on and off the planes of prescribed zero displacement).
A distributed run's last data set
(`.pvtu`) is read from its pieces, each node through `global_node`.

    --tolerance TOL   exit 1 unless the displacements agree to TOL of the
                      largest and each interface's force and tangential
                      force to TOL of the force's length

Used for issue 32's condensed against monolithic Cattaneo–Mindlin
(BENCHMARKS.md, session 15) and for issue 29's `mpirun -np 2` against
serial on the examples (`.ci/run`). Only the standard library is needed
(the VTU reader of `compare_examples.py`).
"""

import csv
import json
import re
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from compare_examples import read_point_field  # noqa: E402


def flat(value, prefix=""):
    """The numbers of a JSON value, keyed by their path."""
    if isinstance(value, dict):
        return {k: v for key, item in value.items() for k, v in flat(item, f"{prefix}.{key}").items()}
    if isinstance(value, list):
        return {k: v for i, item in enumerate(value) for k, v in flat(item, f"{prefix}[{i}]").items()}
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return {prefix: value}
    return {}


def last_field(folder, summary, field):
    """Point field `field` of the last increment, by global node: one
    `.vtu`, or a `.pvtu`'s pieces through their `global_node` arrays."""
    name = summary["increments"][-1]["file"]
    if not name.endswith(".pvtu"):
        return read_point_field(f"{folder}/{name}", field)
    whole = {}
    for piece in re.findall(r'Source="([^"]+)"', open(f"{folder}/{name}").read()):
        nodes = read_point_field(f"{folder}/{piece}", "global_node")
        values = read_point_field(f"{folder}/{piece}", field)
        for k, n in enumerate(nodes):
            whole[int(n)] = values[3 * k : 3 * k + 3]
    return [v for n in sorted(whole) for v in whole[n]]


def force_differences(ca, cb):
    """Each interface's largest difference of `force` and
    `tangential_force` over the length of B's force."""
    out = {}
    for name, b in cb.items():
        a = ca.get(name, {})
        scale = sum(f * f for f in b["force"]) ** 0.5 or 1.0
        for key in ["force", "tangential_force"]:
            out[f"{name}.{key}"] = max(abs(p - q) for p, q in zip(a[key], b[key])) / scale
    return out


def main():
    args = sys.argv[1:]
    tolerance = None
    if "--tolerance" in args:
        at = args.index("--tolerance")
        tolerance = float(args[at + 1])
        del args[at : at + 2]
    if len(args) < 2:
        sys.exit(__doc__)
    a, b, profiles = args[0], args[1], args[2:]
    sa = json.load(open(f"{a}/summary.json"))
    sb = json.load(open(f"{b}/summary.json"))
    times = lambda s: [i["time"] for i in s["increments"]]  # noqa: E731
    print(f"increments {len(sa['increments'])} and {len(sb['increments'])}, same times: {times(sa) == times(sb)}")
    ca, cb = flat(sa["increments"][-1]["contact"]), flat(sb["increments"][-1]["contact"])
    for key in ca:
        if key in cb:
            rel = abs(ca[key] - cb[key]) / max(abs(cb[key]), 1e-300)
            print(f"contact{key}: {ca[key]!r} and {cb[key]!r}, relative {rel:.3g}")
    for name in profiles:
        ra = list(csv.DictReader(open(f"{a}/{name}")))
        rb = list(csv.DictReader(open(f"{b}/{name}")))
        for key in ["contact_pressure", "tangential_traction"]:
            xa = [float(r[key]) for r in ra]
            xb = [float(r[key]) for r in rb]
            peak = max(abs(v) for v in xb) or 1.0
            print(f"{name} {key}: largest difference {max(abs(p - q) for p, q in zip(xa, xb)) / peak:.3g} of the peak")
        differ = [r["node"] for r, s in zip(ra, rb) if r["status"] != s["status"]]
        print(f"{name}: status differs at nodes {differ}")
    ua, ub = last_field(a, sa, "displacement"), last_field(b, sb, "displacement")
    if len(ua) != len(ub):
        sys.exit(f"{a} and {b}: {len(ua) // 3} and {len(ub) // 3} nodes")
    worst = {"displacement": max(abs(p - q) for p, q in zip(ua, ub)) / max(abs(v) for v in ub)}
    print(f"displacement: largest difference {worst['displacement']:.3g} of the largest")
    compare_tractions(a, sa, b, sb, ub)
    worst.update(force_differences(sa["increments"][-1]["contact"], sb["increments"][-1]["contact"]))
    if tolerance is not None:
        over = {k: v for k, v in worst.items() if not v <= tolerance}
        print(f"within {tolerance:g}: {'no: ' + repr(over) if over else 'yes'}")
        sys.exit(1 if over else 0)


def compare_tractions(a, sa, b, sb, ub):
    """The last VTU's `contact_traction` node by node, over the largest
    traction component in B: apart for the nodes with a displacement
    component exactly zero in B (on a symmetry plane, where the traction's
    component along the plane's normal is fixed by neither path's
    equations but through the primary weights off the plane: DESIGN.md,
    "Coulomb friction on the condensed path") and for the others, each with
    the node (0-based index) where it is largest."""
    ta = last_field(a, sa, "contact_traction")
    tb = last_field(b, sb, "contact_traction")
    peak = max(abs(v) for v in tb) or 1.0
    worst = {True: (0.0, None), False: (0.0, None)}
    for n in range(len(tb) // 3):
        on_plane = any(ub[3 * n + k] == 0.0 for k in range(3)) and any(tb[3 * n : 3 * n + 3])
        d = max(abs(ta[3 * n + k] - tb[3 * n + k]) for k in range(3)) / peak
        if d > worst[on_plane][0]:
            worst[on_plane] = (d, n)
    for on_plane, label in [(False, "off"), (True, "on")]:
        d, n = worst[on_plane]
        print(f"contact_traction {label} the planes of prescribed zero displacement: largest difference {d:.3g} of the peak (node index {n})")


if __name__ == "__main__":
    main()
