#!/usr/bin/env python3
"""Writes deck.inp: a pad pressed on a fixed meshed block, then pulled
sideways, as Abaqus/CAE writes a deck (parts, an assembly, instances) with
CalculiX's keywords. Run: python3 generate.py > deck.inp"""


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


def part(name, nx, ny, nz, x0, y0, z0, dx, dy, dz, sets):
    nid, nodes, elements = block(nx, ny, nz, x0, y0, z0, dx, dy, dz)
    out = [f"*Part, name={name}", "*Node"]
    out += [f"{n:7d}, {x:13.6g}, {y:13.6g}, {z:13.6g}" for n, x, y, z in nodes]
    out.append("*Element, type=C3D8")
    out += [f"{e}, " + ", ".join(str(n) for n in ns) for e, ns in elements]
    out.append(f"*Elset, elset={name}All, generate")
    out.append(f" 1, {len(elements)}, 1")
    out += sets(nx, ny, nz, nid)
    out.append(f"*Solid Section, elset={name}All, material=Steel")
    out.append(",")
    out.append("*End Part")
    return out


def pad_sets(nx, ny, nz, nid):
    top = [nid(i, j, nz) for j in range(ny + 1) for i in range(nx + 1)]
    first_top = 1 + nx * ny * (nz - 1)
    return ["*Nset, nset=Top"] + [", ".join(str(n) for n in top[r:r + 8]) for r in range(0, len(top), 8)] + [
        "*Elset, elset=TopLayer, generate", f" {first_top}, {nx * ny * nz}, 1",
        "*Elset, elset=BottomLayer, generate", f" 1, {nx * ny}, 1",
        "*Surface, type=ELEMENT, name=Bottom", "BottomLayer, S1",
    ]


def base_sets(nx, ny, nz, nid):
    return ["*Nset, nset=BaseNodes, elset=BaseAll", "*Surface, type=ELEMENT, name=Top", "BaseAll, S2"]


lines = ["*Heading", "** a pad pressed on a fixed meshed block, then pulled (signorini examples/calculix-deck)"]
# the pad, 1 x 1 x 0.5, centred on its axis; placed by its instance
lines += part("Pad", 4, 4, 2, -0.5, -0.5, 0.0, 0.25, 0.25, 0.25, pad_sets)
# the block, 2 x 2 x 0.25 below z = 0: the "rigid plane", all its nodes fixed
lines += part("Base", 4, 4, 1, -0.5, -0.5, -0.25, 0.5, 0.5, 0.25, base_sets)
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
    "Pad-1.TopLayer, P2, 100.",
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
