#!/usr/bin/env python3
"""Writes the example decks: a pad pressed on a fixed meshed block, then
pulled sideways, as Abaqus/CAE writes a deck (parts, an assembly,
instances) with CalculiX's keywords.

Run: python3 generate.py > deck.inp              (the pad of C3D8)
     python3 generate.py --c3d10 > deck_c3d10.inp (the pad of C3D10)"""

import itertools
import sys


def block(nx, ny, nz, x0, y0, z0, dx, dy, dz):
    """Nodes (id, x, y, z) and C3D8 elements (id, 8 node ids) of a box,
    node id = 1 + i + (nx+1) j + (nx+1)(ny+1) k, bottom face first."""
    nid = lambda i, j, k: 1 + i + (nx + 1) * j + (nx + 1) * (ny + 1) * k
    nodes = [(nid(i, j, k), x0 + i * dx, y0 + j * dy, z0 + k * dz)
             for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)]
    elements = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                b = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k)]
                t = [nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]
                elements.append((1 + i + nx * j + nx * ny * k, b + t))
    return nid, nodes, elements


# C3D10: the corners of the faces S1-S4 (Abaqus's element library), and the
# mid-side nodes 5-10 on the edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4
TET_FACES = {1: (0, 1, 2), 2: (0, 1, 3), 3: (1, 2, 3), 4: (0, 2, 3)}
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]


def tet_block(nx, ny, nz, x0, y0, z0, dx, dy, dz):
    """Nodes and C3D10 elements of a box of nx x ny x nz cubes, each cut
    into the six tetrahedra of Kuhn's triangulation (one per order of the
    axes: conforming across the cubes). A node stands at each point
    (I, J, K) of the grid of half cells that a tetrahedron uses; the
    elements are positively oriented (node 4 on the side of 1-2-3 its
    right-hand normal points to). Returns nodes (id, x, y, z), elements
    (id, 10 ids) and the grid point of each node id."""
    tets = []
    for k, j, i in itertools.product(range(nz), range(ny), range(nx)):
        for order in itertools.permutations(range(3)):
            corner = [2 * i, 2 * j, 2 * k]
            corners = [tuple(corner)]
            for axis in order:
                corner[axis] += 2
                corners.append(tuple(corner))
            a, b, c, d = corners
            e = [[q[t] - a[t] for t in range(3)] for q in (b, c, d)]
            det = (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1])
                   - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0])
                   + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]))
            if det < 0:
                corners = [a, c, b, d]
            mids = [tuple((corners[p][t] + corners[q][t]) // 2 for t in range(3)) for p, q in TET_EDGES]
            tets.append(corners + mids)
    points = sorted({p for t in tets for p in t}, key=lambda p: (p[2], p[1], p[0]))
    ids = {p: n + 1 for n, p in enumerate(points)}
    nodes = [(ids[p], x0 + p[0] * dx / 2, y0 + p[1] * dy / 2, z0 + p[2] * dz / 2) for p in points]
    elements = [(e + 1, [ids[p] for p in t]) for e, t in enumerate(tets)]
    return nodes, elements, {ids[p]: p for p in points}


def part(name, nodes, elements, kind, material, sets):
    out = [f"*Part, name={name}", "*Node"]
    out += [f"{n:7d}, {x:13.6g}, {y:13.6g}, {z:13.6g}" for n, x, y, z in nodes]
    out.append(f"*Element, type={kind}")
    out += [f"{e}, " + ", ".join(str(n) for n in ns) for e, ns in elements]
    out.append(f"*Elset, elset={name}All, generate")
    out.append(f" 1, {len(elements)}, 1")
    out += sets
    out.append(f"*Solid Section, elset={name}All, material={material}")
    out.append(",")
    out.append("*End Part")
    return out


def rows(ids, per=8):
    return [", ".join(str(n) for n in ids[r:r + per]) for r in range(0, len(ids), per)]


def pad_sets(nx, ny, nz, nid):
    top = [nid(i, j, nz) for j in range(ny + 1) for i in range(nx + 1)]
    first_top = 1 + nx * ny * (nz - 1)
    return ["*Nset, nset=Top"] + rows(top) + [
        "*Elset, elset=TopLayer, generate", f" {first_top}, {nx * ny * nz}, 1",
        "*Elset, elset=BottomLayer, generate", f" 1, {nx * ny}, 1",
        "*Surface, type=ELEMENT, name=Bottom", "BottomLayer, S1",
    ]


def tet_pad_sets(elements, grid, top_k):
    """The top nodes, the elements by the face label (S1-S4) that lies on
    the top (TopS<k>) or the bottom (BottomS<k>), and the surface Bottom."""
    top = [n for n, p in grid.items() if p[2] == top_k]
    out = ["*Nset, nset=Top"] + rows(sorted(top))
    bottom = []
    for where, k_of in (("Top", top_k), ("Bottom", 0)):
        for label, face in TET_FACES.items():
            members = [e for e, ns in elements if all(grid[ns[c]][2] == k_of for c in face)]
            if members:
                out += [f"*Elset, elset={where}S{label}"] + rows(members, 16)
                if where == "Bottom":
                    bottom.append(f"BottomS{label}, S{label}")
                else:
                    TOP_LABELS.append(label)
    return out + ["*Surface, type=ELEMENT, name=Bottom"] + bottom


def base_sets():
    return ["*Nset, nset=BaseNodes, elset=BaseAll", "*Surface, type=ELEMENT, name=Top", "BaseAll, S2"]


TOP_LABELS = []
c3d10 = "--c3d10" in sys.argv[1:]
lines = ["*Heading", "** a pad pressed on a fixed meshed block, then pulled (signorini examples/calculix-deck)"]
# the pad, 1 x 1 x 0.5, centred on its axis; placed by its instance
if c3d10:
    lines[1] += ", the pad of C3D10"
    nodes, elements, grid = tet_block(4, 4, 2, -0.5, -0.5, 0.0, 0.25, 0.25, 0.25)
    sets = tet_pad_sets(elements, grid, 4)
    lines += part("Pad", nodes, elements, "C3D10", "PadMaterial", sets)
else:
    nid, nodes, elements = block(4, 4, 2, -0.5, -0.5, 0.0, 0.25, 0.25, 0.25)
    lines += part("Pad", nodes, elements, "C3D8", "Steel", pad_sets(4, 4, 2, nid))
# the block, 2 x 2 x 0.25 below z = 0: the "rigid plane", all its nodes fixed
_, nodes, elements = block(4, 4, 1, -0.5, -0.5, -0.25, 0.5, 0.5, 0.25)
lines += part("Base", nodes, elements, "C3D8", "Steel", base_sets())
lines += [
    "*Assembly, name=Assembly",
    "*Instance, name=Base-1, part=Base",
    "*End Instance",
    "** moved to x, y in [0, 1], then turned a quarter about its vertical axis",
    "*Instance, name=Pad-1, part=Pad",
    " 0.5, 0.5, 0.",
    " 0.5, 0.5, 0., 0.5, 0.5, 1., 90.",
    "*End Instance",
    "*End Assembly",
    "*Material, name=Steel",
    "*Elastic",
    " 210000., 0.3",
]
if c3d10:
    lines += [
        "** the pad without lateral contraction (nu = 0): pressed, its stress is",
        "** uniaxial and uniform although its top is held sideways",
        "*Material, name=PadMaterial",
        "*Elastic",
        " 210000., 0.",
    ]
lines += [
    "*Surface Interaction, name=Rough",
    "*Surface Behavior, pressure-overclosure=HARD",
    "*Friction",
    " 0.3, 1e7",
    "** secondary (the pad's bottom), primary (the block's top)",
    "*Contact Pair, interaction=Rough, type=SURFACE TO SURFACE",
    "Pad-1.Bottom, Base-1.Top",
    "*Step, name=Press",
    "*Static",
    " 0.5, 1., 1e-5, 1.",
    "*Boundary",
    "Base-1.BaseNodes, 1, 3",
    "Pad-1.Top, 1, 2",
    "*Dload",
]
if c3d10:
    lines += [f"Pad-1.TopS{k}, P{k}, 100." for k in TOP_LABELS]
else:
    lines += ["Pad-1.TopLayer, P2, 100."]
lines += [
    "*Node File",
    "U",
    "*El File",
    "S",
    "*Contact File",
    "CDIS, CSTR",
    "*Node Print, nset=Pad-1.Top",
    "RF",
    "*End Step",
    "*Step, name=Pull",
    "*Static",
    " 0.25, 1., 1e-5, 0.5",
    "*Boundary",
    "Pad-1.Top, 1, 1, 0.01",
    "*Node Print, nset=Pad-1.Top",
    "RF",
    "*End Step",
]
print("\n".join(lines))
