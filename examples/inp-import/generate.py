#!/usr/bin/env python3
"""Writes block.inp and block_nodes.inp: a quarter of a 4 x 4 x 1 block
(0 <= x, y <= 2, 0 <= z <= 1) of 4 x 4 x 2 C3D8 elements, as an Abaqus deck
with *SURFACE face sets, *NSET with GENERATE, an *INCLUDE for the nodes and
the physics keywords an Abaqus user would have (which signorini ignores: the
case file gives the physics).

    python3 generate.py
"""

NX, NY, NZ = 4, 4, 2
LX, LY, LZ = 2.0, 2.0, 1.0


def node(i, j, k):
    return 1 + i + (NX + 1) * (j + (NY + 1) * k)


def element(i, j, k):
    return 1 + i + NX * (j + NY * k)


with open("block_nodes.inp", "w") as f:
    f.write("** nodes of block.inp: id = 1 + i + 5 j + 25 k\n*NODE\n")
    for k in range(NZ + 1):
        for j in range(NY + 1):
            for i in range(NX + 1):
                f.write(f"{node(i, j, k)}, {LX * i / NX:g}, {LY * j / NY:g}, {LZ * k / NZ:g}\n")

with open("block.inp", "w") as f:
    f.write("*HEADING\n Quarter of a block pressed on a rigid plane (examples/inp-import)\n")
    f.write("*INCLUDE, INPUT=block_nodes.inp\n")
    f.write("*ELEMENT, TYPE=C3D8, ELSET=BLOCK\n")
    for k in range(NZ):
        for j in range(NY):
            for i in range(NX):
                c = [node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k)]
                c += [n + (NX + 1) * (NY + 1) for n in c]
                f.write(f"{element(i, j, k)}, " + ", ".join(map(str, c)) + "\n")
    # the bottom and top layers of elements
    f.write("*ELSET, ELSET=BOTTOM_LAYER, GENERATE\n")
    f.write(f"1, {NX * NY}, 1\n")
    f.write("*ELSET, ELSET=TOP_LAYER, GENERATE\n")
    f.write(f"{NX * NY * (NZ - 1) + 1}, {NX * NY * NZ}, 1\n")
    # symmetry planes x = 0 (every NX+1-th node) and y = 0 (one row per layer)
    f.write("*NSET, NSET=SYMMETRY_X, GENERATE\n")
    f.write(f"1, {node(NX, NY, NZ)}, {NX + 1}\n")
    f.write("*NSET, NSET=SYMMETRY_Y, GENERATE\n")
    for k in range(NZ + 1):
        f.write(f"{node(0, 0, k)}, {node(NX, 0, k)}, 1\n")
    # S1 is the face 1-2-3-4 (z = 0 of the bottom layer), S2 the face 5-8-7-6
    f.write("*SURFACE, NAME=BOTTOM, TYPE=ELEMENT\nBOTTOM_LAYER, S1\n")
    f.write("*SURFACE, NAME=TOP, TYPE=ELEMENT\nTOP_LAYER, S2\n")
    f.write("** the physics as an Abaqus deck would give it; signorini reads it from case.toml\n")
    f.write("*MATERIAL, NAME=BLOCK_MATERIAL\n*ELASTIC\n1000., 0.3\n")
    f.write("*SOLID SECTION, ELSET=BLOCK, MATERIAL=BLOCK_MATERIAL\n")
    f.write("*STEP\n*STATIC\n*BOUNDARY\nSYMMETRY_X, 1, 1\nSYMMETRY_Y, 2, 2\n")
    f.write("*DSLOAD\nTOP, P, 10.\n*END STEP\n")
