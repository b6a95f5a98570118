"""Shared fixtures: the repository, the command line's binary, a reader of
the VTU files it writes, and a structured hexahedral cube as arrays."""

import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "scripts"))
import compare_examples  # noqa: E402


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def cli():
    """The command line `signorini` (SIGNORINI_BIN, else built by cargo
    at the repository's root: a no-op after `cargo test --release`)."""
    path = os.environ.get("SIGNORINI_BIN")
    if path:
        return pathlib.Path(path)
    subprocess.run(
        ["cargo", "build", "--release", "--quiet", "--bin", "signorini"],
        cwd=REPO,
        check=True,
    )
    return REPO / "target" / "release" / "signorini"


def run_cli(cli, case_file, output, threads=2):
    subprocess.run(
        [str(cli), "run", str(case_file), "--output", str(output),
         "--threads", str(threads), "--quiet"],
        check=True,
    )


def read_vtu_point_field(path, name):
    """Array `name` of a VTU written by signorini, as numpy (the stdlib
    reader of scripts/compare_examples.py)."""
    values = compare_examples.read_point_field(path, name)
    return None if values is None else np.array(values)


def hex_cube(n=3, length=1.0):
    """A cube [0, L]³ of n³ hexahedra (Gmsh/VTK node order): nodes,
    hexahedra, and the quadrangles of its bottom (z = 0) and top (z = L)."""
    g = np.linspace(0.0, length, n + 1)
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    nodes = np.column_stack([x.ravel(), y.ravel(), z.ravel()])

    def node(i, j, k):
        return i + (n + 1) * (j + (n + 1) * k)

    hexes = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                bottom = [node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k)]
                top = [node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)]
                hexes.append(bottom + top)

    def face(k):
        return np.array(
            [[node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k)]
             for j in range(n) for i in range(n)]
        )

    return nodes, np.array(hexes), {"bottom": face(0), "top": face(n)}


def write_msh22(path, nodes, hexes, regions, surfaces):
    """The same mesh as an ASCII MSH 2.2 file (1-based tags)."""
    names = [(3, name) for name in regions] + [(2, name) for name in surfaces]
    tag = {name: t + 1 for t, (_, name) in enumerate(names)}
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(names))]
    lines += [f'{dim} {tag[name]} "{name}"' for dim, name in names]
    lines += ["$EndPhysicalNames", "$Nodes", str(len(nodes))]
    lines += [f"{i + 1} {x!r} {y!r} {z!r}" for i, (x, y, z) in enumerate(nodes.tolist())]
    lines += ["$EndNodes"]
    elements = []
    for name, facets in surfaces.items():
        for f in facets:
            kind = 3 if len(f) == 4 else 2
            elements.append(f"{kind} 2 {tag[name]} {tag[name]} " + " ".join(str(v + 1) for v in f))
    for name, members in regions.items():
        for e in members:
            elements.append(f"5 2 {tag[name]} {tag[name]} " + " ".join(str(v + 1) for v in hexes[e]))
    lines += ["$Elements", str(len(elements))]
    lines += [f"{i + 1} {e}" for i, e in enumerate(elements)]
    lines += ["$EndElements", ""]
    pathlib.Path(path).write_text("\n".join(lines))
