"""Hertz check of a two-spheres run: python3 hertz_check.py OUTDIR [MESH].

Peak nodal contact pressure and contact radius of the upper (secondary)
cap against Hertz with R* = R/2 = 0.5 and E* = E/(2(1 - nu^2)) and the
computed total force F (4 x the quarter's, from summary.json):
a = (3 F R* / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2). The radius is the fit
of p^2 = A + B r^2 over the closed nodes with r < 0.8 a (a_fit = sqrt(-A/B)),
and the outermost closed node's r is printed beside it.

With MESH (the run's .msh, format 4.1), also the nominal pressure: each
node's force over its reference area, lambda_j * A_j(current) / A_j(reference),
with A_j the node's share of its upper_contact faces (1/3 of a Tri3; 2/15 at
a Tri6 corner and 1/5 at a mid-side node, the integrals of the mortar
basis on flat faces, on the corner triangle). Mortar's multiplier lambda_j
is the force over the current area D_j (the Cauchy pressure); Hertz's
linear theory, and node-to-surface's contact_pressure, are per reference
area. Under the spheres' poles the surface contracts by ~3.6 % in area
((1 - 2 nu)(1 + nu) p0 / E in each direction)."""
import json
import math
import re
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts"))
from compare_examples import read_point_field  # noqa: E402

out = pathlib.Path(sys.argv[1])
summary = json.loads((out / "summary.json").read_text())
last = sorted(out.glob("*.vtu"))[-1]
p = read_point_field(last, "contact_pressure")
pts = read_point_field(last, "Points")
xyz = [pts[3 * i:3 * i + 3] for i in range(len(pts) // 3)]
inc = summary["increments"][-1]
F = 4 * inc["contact"]["poles"]["force"][2]
E, nu, R = 1000.0, 0.3, 1.0
Rs, Es = R / 2, E / (2 * (1 - nu * nu))
a = (3 * F * Rs / (4 * Es)) ** (1 / 3)
p0 = 3 * F / (2 * math.pi * a * a)


def surface_shares(msh, name):
    """Per node tag: its reference coordinates and [(weight, corner tags)] of
    the faces of physical surface `name` of a MSH 4.1 file."""
    lines = pathlib.Path(msh).read_text().split("\n")
    i = lines.index("$PhysicalNames")
    tags = [int(l.split()[1]) for l in lines[i + 2:i + 2 + int(lines[i + 1])]
            if l.split()[0] == "2" and re.search(f'"{name}"', l)]
    i = lines.index("$Entities")
    npt, ncv, nsf, _ = map(int, lines[i + 1].split())
    entities = set()
    for l in lines[i + 2 + npt + ncv:i + 2 + npt + ncv + nsf]:
        f = l.split()
        if any(int(t) in tags for t in f[8:8 + int(f[7])]):
            entities.add(int(f[0]))
    i = lines.index("$Nodes")
    blocks, k, coords = int(lines[i + 1].split()[0]), i + 2, {}
    for _ in range(blocks):
        count = int(lines[k].split()[3])
        ids = [int(t) for t in lines[k + 1:k + 1 + count]]
        for n, l in zip(ids, lines[k + 1 + count:k + 1 + 2 * count]):
            coords[n] = [float(v) for v in l.split()]
        k += 1 + 2 * count
    i = lines.index("$Elements")
    blocks, k, shares = int(lines[i + 1].split()[0]), i + 2, {}
    for _ in range(blocks):
        dim, entity, _, count = map(int, lines[k].split())
        for l in lines[k + 1:k + 1 + count]:
            nodes = [int(t) for t in l.split()[1:]]
            if dim == 2 and entity in entities:
                weights = [1 / 3] * 3 if len(nodes) == 3 else [2 / 15] * 3 + [1 / 5] * 3
                for n, w in zip(nodes, weights):
                    shares.setdefault(n, []).append((w, nodes[:3]))
        k += 1 + count
    return coords, shares


def triangle_area(a, b, c):
    u = [b[d] - a[d] for d in range(3)]
    v = [c[d] - a[d] for d in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    return 0.5 * math.sqrt(sum(x * x for x in n))


def peak_and_fit(closed):
    """The largest value, and p0 and a of the fit p^2 = A + B r^2 over r < 0.8 a."""
    fit = [(r * r, q * q) for r, q in closed if r < 0.8 * a]
    n = len(fit)
    sx, sy = sum(t for t, _ in fit), sum(v for _, v in fit)
    sxx, sxy = sum(t * t for t, _ in fit), sum(t * v for t, v in fit)
    B = (n * sxy - sx * sy) / (n * sxx - sx * sx)
    A = (sy - B * sx) / n
    return max(q for _, q in closed), math.sqrt(A), math.sqrt(-A / B)


# the upper cap's nodes (z > -g0/2)
closed = [(math.hypot(x[0], x[1]), q) for x, q in zip(xyz, p) if q > 0 and x[2] > -5e-6]
peak = max(q for _, q in closed)
rmax = max(r for r, _ in closed)
peak, p0_fit, afit = peak_and_fit(closed)
print(f"F {F:.5f}  Hertz a {a:.5f} p0 {p0:.3f}")
print(f"peak nodal pressure {peak:.3f} ({100 * (peak / p0 - 1):+.2f} %), "
      f"fitted p0 {p0_fit:.3f} ({100 * (p0_fit / p0 - 1):+.2f} %)")
print(f"contact radius fit {afit:.5f} ({100 * (afit / a - 1):+.2f} %), outermost closed node "
      f"{rmax:.5f} ({100 * (rmax / a - 1):+.2f} %), closed nodes {len(closed)}")
print(f"increments {len(summary['increments'])}, Newton iterations "
      f"{sum(i['iterations'] for i in summary['increments'])}")
if len(sys.argv) > 2:
    coords, shares = surface_shares(sys.argv[2], "upper_contact")
    u = read_point_field(last, "displacement")
    index = {tuple(round(c, 9) for c in x): i for i, x in enumerate(xyz)}
    nominal = []
    for n, faces in shares.items():
        i = index.get(tuple(round(c, 9) for c in coords[n]))
        if i is None or p[i] <= 0 or coords[n][2] <= -5e-6:
            continue
        current = lambda m: [coords[m][d] + u[3 * index[tuple(round(c, 9) for c in coords[m])] + d]
                             for d in range(3)]
        ref = sum(w * triangle_area(*(coords[m] for m in c)) for w, c in faces)
        cur = sum(w * triangle_area(*(current(m) for m in c)) for w, c in faces)
        nominal.append((math.hypot(coords[n][0], coords[n][1]), p[i] * cur / ref))
    peak, p0_fit, afit = peak_and_fit(nominal)
    print(f"nominal pressure (force over reference area): peak {peak:.3f} "
          f"({100 * (peak / p0 - 1):+.2f} %), fitted p0 {p0_fit:.3f} "
          f"({100 * (p0_fit / p0 - 1):+.2f} %), contact radius fit {afit:.5f} "
          f"({100 * (afit / a - 1):+.2f} %)")
