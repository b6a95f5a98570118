#!/usr/bin/env python3
"""A peer race: signorini against CalculiX (ccx) on the same Hertz mesh.

The Hertz quarter sphere of examples/hertz (R = 1, E = 1000, nu = 0.3,
linear elastic, small strain, frictionless, the flat face z = R pushed
down by 0.0115 onto the rigid plane z = 0, symmetry planes x = 0 and
y = 0) is meshed with gmsh from `hemisphere.geo` at one or two sizes, and
the one mesh is written once as an Abaqus/CalculiX deck `mesh.inp`
(C3D4, node sets, the contact surface as element faces). Both solvers
read that file:

- CalculiX: `ccx.inp` includes it and adds the physics (material,
  symmetry and top displacements, a fixed C3D8 slab whose top face is the
  rigid plane z = 0, penalty contact, one static step);
- signorini: `case.toml` names it as its mesh (`[mesh] file = "mesh.inp"`;
  signorini reads only the mesh from a deck) and gives the same physics.

The two are run alternately (CalculiX, signorini, signorini, CalculiX, ...)
with the same number of threads, and for each run the script prints the
wall time, the peak memory (ru_maxrss of the child, from wait4), the
Newton iterations, the total force, the contact radius and the peak
pressure against Hertz, and the largest penetration; then the time ratio.

Usage:
    python3 benches/race/race.py                       # small, 2 repetitions
    python3 benches/race/race.py --size large --repeat 1
    python3 benches/race/race.py --dry-run --size both # decks only, no solver

Needs: Python 3 (standard library), gmsh on PATH, the signorini binary
(`cargo build --release`; `--signorini PATH` to choose), and ccx
(installed with apt-get when missing and the script runs as root).
See README.md beside this file for the settings and why.
"""

import argparse
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent

# signorini's VTU reader (standard library) from scripts/compare_examples.py
sys.dont_write_bytecode = True
sys.path.insert(0, str(ROOT / "scripts"))
from compare_examples import read_point_field  # noqa: E402

# The model (as examples/hertz/case.toml).
E, NU, R, DEPTH = 1000.0, 0.3, 1.0, 0.0115
E_STAR = E / (1.0 - NU * NU)

# Threshold-field sizes of hemisphere.geo per race size: (hmin, hmax).
# With gmsh 4.8.4 these give 6 121 nodes (18 363 dofs) and 36 149 nodes
# (108 447 dofs); another gmsh version may give slightly other counts.
SIZES = {"small": (0.0068, 0.17), "large": (0.0036, 0.09)}

# CalculiX's penalty slope K = CCX_SLOPE_FACTOR * E / hmin (pressure per length):
# README.md, "The model and the CalculiX settings", says why.
CCX_SLOPE_FACTOR = 100.0


# ---------------------------------------------------------------- mesh


class Mesh:
    """A Tet4 mesh: nodes {id: (x, y, z)}, tets [(n1..n4)], and per
    physical surface its triangles [(a, b, c)]."""

    def __init__(self):
        self.nodes = {}
        self.tets = []
        self.surfaces = {}


def gmsh_mesh(size, work):
    """Mesh hemisphere.geo with gmsh at `size`; returns the .msh path."""
    hmin, hmax = SIZES[size]
    msh = work / "hemisphere.msh"
    cmd = [
        "gmsh", "-3", str(HERE / "hemisphere.geo"),
        "-setnumber", "hmin", repr(hmin), "-setnumber", "hmax", repr(hmax),
        "-format", "msh22", "-o", str(msh),
    ]
    try:
        done = subprocess.run(cmd, capture_output=True, text=True)
    except FileNotFoundError:
        sys.exit("error: gmsh not found on PATH (apt-get install gmsh, or gmsh.info)")
    if done.returncode != 0 or not msh.exists():
        sys.exit(f"error: gmsh failed on {HERE / 'hemisphere.geo'}:\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    return msh


def read_msh22(path):
    """Read an ASCII MSH 2.2 file: Tet4 (type 4) of the volume group and the
    triangles (type 2) of each physical surface, by name."""
    lines = path.read_text().split("\n")
    names = {}
    mesh = Mesh()
    i = 0
    while i < len(lines):
        tag = lines[i].strip()
        if tag == "$PhysicalNames":
            for k in range(int(lines[i + 1])):
                dim, num, name = lines[i + 2 + k].split(maxsplit=2)
                names[(int(dim), int(num))] = name.strip('"')
        elif tag == "$Nodes":
            n = int(lines[i + 1])
            for k in range(n):
                f = lines[i + 2 + k].split()
                mesh.nodes[int(f[0])] = (float(f[1]), float(f[2]), float(f[3]))
            i += n + 1
        elif tag == "$Elements":
            n = int(lines[i + 1])
            for k in range(n):
                f = [int(v) for v in lines[i + 2 + k].split()]
                kind, ntags = f[1], f[2]
                phys, conn = f[3], f[3 + ntags:]
                if kind == 4:
                    mesh.tets.append(tuple(conn))
                elif kind == 2:
                    mesh.surfaces.setdefault(names[(2, phys)], []).append(tuple(conn))
            i += n + 1
        i += 1
    return mesh


def compact(mesh):
    """Keep only the nodes of tetrahedra (gmsh also saves the field's
    point at the pole), numbered 1..N in their old order, and orient every
    tet positively ((n2-n1) x (n3-n1) . (n4-n1) > 0, as C3D4 wants)."""
    used = sorted({n for t in mesh.tets for n in t})
    new = {old: k + 1 for k, old in enumerate(used)}
    out = Mesh()
    out.nodes = {new[o]: mesh.nodes[o] for o in used}
    for t in mesh.tets:
        a, b, c, d = (new[n] for n in t)
        if signed_volume(out.nodes, (a, b, c, d)) < 0.0:
            b, c = c, b
        out.tets.append((a, b, c, d))
    out.surfaces = {k: [tuple(new[n] for n in tri) for tri in v] for k, v in mesh.surfaces.items()}
    return out


def signed_volume(nodes, tet):
    p = [nodes[n] for n in tet]
    u = [p[1][i] - p[0][i] for i in range(3)]
    v = [p[2][i] - p[0][i] for i in range(3)]
    w = [p[3][i] - p[0][i] for i in range(3)]
    return (
        u[0] * (v[1] * w[2] - v[2] * w[1])
        - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
    ) / 6.0


# Abaqus C3D4 faces: S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1.
C3D4_FACES = ((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0))


def element_faces(mesh, triangles):
    """The (element, face number) of each triangle."""
    faces = {}
    for e, t in enumerate(mesh.tets, start=1):
        for k, f in enumerate(C3D4_FACES, start=1):
            faces[frozenset(t[i] for i in f)] = (e, k)
    return [faces[frozenset(tri)] for tri in triangles]


def write_mesh_inp(mesh, path):
    """The mesh both solvers read: nodes, C3D4 elements (ELSET=BALL), node
    sets TOP, SYMMETRY_X, SYMMETRY_Y, and the element-face surface CONTACT."""
    out = ["*HEADING", "Hertz quarter sphere (benches/race/hemisphere.geo)", "*NODE, NSET=NBALL"]
    out += [f"{n}, {x:.14g}, {y:.14g}, {z:.14g}" for n, (x, y, z) in sorted(mesh.nodes.items())]
    out.append("*ELEMENT, TYPE=C3D4, ELSET=BALL")
    out += [f"{e}, {a}, {b}, {c}, {d}" for e, (a, b, c, d) in enumerate(mesh.tets, start=1)]
    for group, name in (("top", "TOP"), ("symmetry_x", "SYMMETRY_X"), ("symmetry_y", "SYMMETRY_Y")):
        ids = sorted({n for tri in mesh.surfaces[group] for n in tri})
        out.append(f"*NSET, NSET={name}")
        out += [", ".join(map(str, ids[k:k + 12])) for k in range(0, len(ids), 12)]
    out.append("*SURFACE, NAME=CONTACT, TYPE=ELEMENT")
    out += [f"{e}, S{k}" for e, k in element_faces(mesh, mesh.surfaces["contact"])]
    path.write_text("\n".join(out) + "\n")


def contact_nodes(mesh):
    return sorted({n for tri in mesh.surfaces["contact"] for n in tri})


# ---------------------------------------------------------------- decks


def write_ccx_deck(mesh, hmin, work):
    """ccx.inp: the mesh, a fixed slab under z = 0 as the rigid plane, and
    the physics of examples/hertz (README.md, "CalculiX settings")."""
    n0 = max(mesh.nodes) + 1
    e0 = len(mesh.tets) + 1
    lo, hi, depth = -0.5, 1.5, 0.5
    corners = [(lo, lo), (hi, lo), (hi, hi), (lo, hi)]
    slab = [(x, y, -depth) for x, y in corners] + [(x, y, 0.0) for x, y in corners]
    slope = CCX_SLOPE_FACTOR * E / hmin
    deck = [
        "** Hertz quarter sphere on a rigid plane: written by benches/race/race.py",
        "*INCLUDE, INPUT=mesh.inp",
        "** the rigid plane z = 0: top face of a slab with every node fixed",
        "*NODE, NSET=SLAB",
        *(f"{n0 + k}, {x!r}, {y!r}, {z!r}" for k, (x, y, z) in enumerate(slab)),
        "*ELEMENT, TYPE=C3D8, ELSET=SLAB",
        f"{e0}, " + ", ".join(str(n0 + k) for k in range(8)),
        "*SURFACE, NAME=FLOOR, TYPE=ELEMENT",
        f"{e0}, S2",
        "*MATERIAL, NAME=BALL",
        "*ELASTIC",
        f"{E!r}, {NU!r}",
        "*SOLID SECTION, ELSET=BALL, MATERIAL=BALL",
        "*SOLID SECTION, ELSET=SLAB, MATERIAL=BALL",
        "*SURFACE INTERACTION, NAME=FRICTIONLESS",
        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
        f"{slope!r}",
        "*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=NODE TO SURFACE",
        "CONTACT, FLOOR",
        "*BOUNDARY",
        "SYMMETRY_X, 1, 1, 0.",
        "SYMMETRY_Y, 2, 2, 0.",
        "SLAB, 1, 3, 0.",
        "*STEP",
        "*STATIC, SOLVER=SPOOLES",
        "1., 1.",
        "*BOUNDARY",
        f"TOP, 3, 3, {-DEPTH!r}",
        "*NODE PRINT, NSET=TOP, TOTALS=ONLY",
        "RF",
        "*NODE FILE",
        "U",
        "*CONTACT FILE",
        "CSTR, CDIS",
        "*END STEP",
    ]
    (work / "ccx.inp").write_text("\n".join(deck) + "\n")
    return len(mesh.nodes) + 8


def write_signorini_case(work):
    """case.toml: examples/hertz/case.toml on mesh.inp, one increment."""
    (work / "case.toml").write_text(
        f"""# written by benches/race/race.py: examples/hertz/case.toml on mesh.inp
[mesh]
file = "mesh.inp"

[[material]]
region = "BALL"
model = "linear_elastic"
youngs_modulus = {E!r}
poisson_ratio = {NU!r}

[[displacement]]
nodes = "SYMMETRY_X"
x = 0.0

[[displacement]]
nodes = "SYMMETRY_Y"
y = 0.0

[[displacement]]
nodes = "TOP"
z = {-DEPTH!r}

[[obstacle]]
name = "floor"
shape = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[contact]]
name = "pole"
surface = "CONTACT"
obstacle = "floor"
method = "rockafellar"

[[step]]
name = "press"
end_time = 1.0
initial_increment = 1.0

[output]
name = "race"
"""
    )


# ---------------------------------------------------------------- running


def ensure_ccx():
    """ccx on PATH, else install Debian's calculix-ccx with apt-get."""
    if shutil.which("ccx"):
        return
    if os.geteuid() != 0 or not shutil.which("apt-get"):
        sys.exit("error: ccx not on PATH; install CalculiX (Debian/Ubuntu: apt-get install calculix-ccx)")
    print("ccx not found: apt-get update && apt-get install -y calculix-ccx", flush=True)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    for cmd in (["apt-get", "update"], ["apt-get", "install", "-y", "calculix-ccx"]):
        if subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL).returncode != 0:
            sys.exit(f"error: {' '.join(cmd)} failed")
    if not shutil.which("ccx"):
        sys.exit("error: calculix-ccx installed but ccx is not on PATH")


def measured(cmd, cwd, env, log, timeout):
    """Run cmd; return (wall s, peak RSS MiB, exit status, CPU s). The peak
    RSS is ru_maxrss of the child from wait4 (KiB on Linux), the CPU time
    its user + system time (all its threads)."""
    with open(log, "w") as out:
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT)
        deadline = start + timeout
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() > deadline:
                proc.kill()
                pid, status, usage = os.wait4(proc.pid, 0)
                break
            time.sleep(0.05)
        wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    return wall, usage.ru_maxrss / 1024.0, proc.returncode, usage.ru_utime + usage.ru_stime


def run_ccx(work, threads, timeout):
    for name in ("ccx.dat", "ccx.frd", "ccx.sta", "ccx.cvg"):
        (work / name).unlink(missing_ok=True)
    env = dict(os.environ)
    for var in ("OMP_NUM_THREADS", "CCX_NPROC_EQUATION_SOLVER", "CCX_NPROC_STIFFNESS", "CCX_NPROC_RESULTS", "NUMBER_OF_CPUS"):
        env[var] = str(threads)
    return measured(["ccx", "-i", "ccx"], work, env, work / "ccx.log", timeout)


def run_signorini(binary, work, threads, timeout):
    cmd = [str(binary), "run", "case.toml", "--threads", str(threads), "--quiet", "--output", "results"]
    return measured(cmd, work, dict(os.environ), work / "signorini.log", timeout)


# ---------------------------------------------------------------- results


def signorini_results(work, mesh):
    summary = json.loads((work / "results" / "summary.json").read_text())
    incs = summary["increments"]
    last = incs[-1]
    vtu = work / "results" / last["file"]
    u, p = read_point_field(vtu, "displacement"), read_point_field(vtu, "contact_pressure")
    point = {int(n): k for k, n in enumerate(read_point_field(vtu, "node_id"))}  # mesh.inp id -> VTU point
    nodes = []
    for n in contact_nodes(mesh):
        x, y, z = mesh.nodes[n]
        k = point[n]
        nodes.append((math.hypot(x + u[3 * k], y + u[3 * k + 1]), p[k], z + u[3 * k + 2], math.hypot(x, y)))
    return {
        "iterations": sum(i["iterations"] for i in incs),
        "increments": len(incs),
        "cuts": sum(i["cuts"] for i in incs),
        "force": -4.0 * last["reaction_forces"]["TOP"][2],
        "nodes": nodes,
        "dofs": summary["dofs"],
    }


def frd_blocks(path):
    """Nodal result blocks of a CalculiX .frd (ASCII): {name: {node: [values]}},
    the last block of each name, and the node coordinates."""
    blocks, coords, current, name = {}, {}, None, None
    with open(path) as f:
        for line in f:
            key = line[:3]
            if line.startswith("    2C"):
                current, name = coords, "coords"
            elif line.startswith(" -4"):
                name = line.split()[1]
                current = blocks[name] = {}
            elif key == " -1" and current is not None:
                node = int(line[3:13])
                vals = [float(line[13 + 12 * k:25 + 12 * k]) for k in range((len(line.rstrip("\n")) - 13) // 12)]
                current[node] = vals
            elif key == " -3":
                current = None
    return blocks, coords


def ccx_results(work, mesh):
    blocks, _ = frd_blocks(work / "ccx.frd")
    disp, cont = blocks["DISP"], blocks.get("CONTACT", {})
    nodes = []
    for n in contact_nodes(mesh):
        x, y, z = mesh.nodes[n]
        ux, uy, uz = disp[n][:3]
        press = cont[n][3] if n in cont else 0.0  # COPEN, CSLIP1, CSLIP2, CPRESS, ...
        nodes.append((math.hypot(x + ux, y + uy), press, z + uz, math.hypot(x, y)))
    # total reaction on TOP from the .dat (the last "total force" block)
    force = None
    lines = (work / "ccx.dat").read_text().split("\n")
    for k, line in enumerate(lines):
        if "total force" in line:
            for follow in lines[k + 1:k + 4]:
                if follow.strip():
                    force = -4.0 * float(follow.split()[2])
                    break
    # Newton iterations of every attempt (.cvg: one line per iteration)
    its, incs, cuts = 0, 0, 0
    for line in (work / "ccx.cvg").read_text().split("\n"):
        f = line.split()
        if len(f) >= 5 and all(v.isdigit() for v in f[:4]):
            its += 1
    for line in (work / "ccx.sta").read_text().split("\n"):
        f = line.split()
        if len(f) >= 4 and all(v.isdigit() for v in f[:4]):
            incs += 1
            cuts += int(f[2]) - 1
    return {"iterations": its, "increments": incs, "cuts": cuts, "force": force, "nodes": nodes}


def ellipse_fit(pairs, p0):
    """Least-squares fit of p^2 = p_fit^2 (1 - r^2/a_fit^2) (Hertz's
    ellipsoidal pressure) to the (r, p) pairs with p > 0.2 p0: returns
    (a_fit, p_fit)."""
    fit = [(r * r, p * p) for r, p in pairs if p > 0.2 * p0]
    m = len(fit)
    sx = sum(f[0] for f in fit)
    sy = sum(f[1] for f in fit)
    sxx = sum(f[0] * f[0] for f in fit)
    sxy = sum(f[0] * f[1] for f in fit)
    slope = (m * sxy - sx * sy) / (m * sxx - sx * sx)
    intercept = (sy - slope * sx) / m
    return math.sqrt(-intercept / slope), math.sqrt(intercept)


def hertz(res):
    """Hertz's a and p0 from the total force F (4 x the quarter's reaction on
    TOP): a = (3FR/4E*)^(1/3), p0 = 3F/(2 pi a^2); the contact radius and
    peak pressure from the ellipse fit of p^2 = p0^2 (1 - r^2/a^2) over the
    nodes with p > 0.2 p0, r the node's reference radius (Hertz's theory
    and both solvers' small-strain models place the contact area in the
    reference configuration; a node at the edge moves inwards by
    u_r(a) = -(1 - 2 nu)(1 + nu) a p0 / (3E), -1.3 % of a here: Johnson,
    Contact Mechanics, 1985, eq. 3.41b); the fit against the deformed
    radius (as tests/cases.rs) and the largest nodal pressure for
    reference; and the largest penetration max(0, -z) of the deformed
    contact nodes."""
    force = res["force"]
    a = (3.0 * force * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
    p0 = 3.0 * force / (2.0 * math.pi * a * a)
    a_fit, p_fit = ellipse_fit([(n[3], n[1]) for n in res["nodes"]], p0)
    a_deformed, _ = ellipse_fit([(n[0], n[1]) for n in res["nodes"]], p0)
    peak = max(n[1] for n in res["nodes"])
    pen = max(0.0, max(-n[2] for n in res["nodes"]))
    return {"a": a, "p0": p0, "a_fit": a_fit, "p_fit": p_fit, "a_deformed": a_deformed, "peak": peak, "pen": pen}


# ---------------------------------------------------------------- main


def prepare(size, root):
    work = root / size
    work.mkdir(parents=True, exist_ok=True)
    mesh = compact(read_msh22(gmsh_mesh(size, work)))
    write_mesh_inp(mesh, work / "mesh.inp")
    ccx_nodes = write_ccx_deck(mesh, SIZES[size][0], work)
    write_signorini_case(work)
    return work, mesh, ccx_nodes


def self_check(binary, work, mesh, ccx_nodes):
    """The two decks hold the same mesh: signorini's `check` reads as many
    nodes and elements from case.toml as mesh.inp holds, and ccx.inp is
    mesh.inp plus the 8 nodes of the slab."""
    done = subprocess.run([str(binary), "check", "case.toml"], cwd=work, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"error: signorini check failed:\n{done.stdout}{done.stderr}")
    read = {}
    for line in done.stdout.splitlines():
        f = line.split()
        if len(f) >= 2 and f[0] in ("nodes", "elements"):
            read[f[0]] = int(f[1])
        elif line.strip().startswith("surface set 'CONTACT':"):
            read["contact facets"], read["contact nodes"] = int(f[3]), int(f[5])
    want = {
        "nodes": len(mesh.nodes),
        "elements": len(mesh.tets),
        "contact facets": len(mesh.surfaces["contact"]),
        "contact nodes": len(contact_nodes(mesh)),
    }
    if read != want:
        sys.exit(f"error: signorini check read {read} from {work / 'case.toml'}, mesh.inp holds {want}")
    if ccx_nodes != len(mesh.nodes) + 8:
        sys.exit("error: ccx.inp does not hold mesh.inp + 8 slab nodes")
    print(f"  same mesh: {len(mesh.nodes)} nodes ({3 * len(mesh.nodes)} dofs), {len(mesh.tets)} C3D4, "
          f"{len(mesh.surfaces['contact'])} contact faces on {len(contact_nodes(mesh))} nodes "
          "(signorini check reads the same); ccx adds the 8 fixed slab nodes")


def fmt_row(label, runs, res, h, hmin):
    walls = [r[0] for r in runs]
    cpus = [r[3] for r in runs]
    mems = [r[1] for r in runs]
    return (
        f"| {label} | {statistics.median(walls):.2f} ({', '.join(f'{w:.1f}' for w in walls)}) "
        f"| {statistics.median(cpus):.2f} ({', '.join(f'{c:.1f}' for c in cpus)}) "
        f"| {max(mems):.0f} | {res['iterations']} ({res['increments']} inc, {res['cuts']} cuts) "
        f"| {res['force']:.4f} | {h['a_fit']:.5f} ({100 * (h['a_fit'] / h['a'] - 1):+.2f} %; "
        f"deformed r {100 * (h['a_deformed'] / h['a'] - 1):+.2f} %) "
        f"| {h['p_fit']:.2f} ({100 * (h['p_fit'] / h['p0'] - 1):+.2f} %; "
        f"largest nodal {100 * (h['peak'] / h['p0'] - 1):+.2f} %) "
        f"| {h['pen']:.2e} ({h['pen'] / hmin:.1e} h) |"
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", choices=["small", "large", "both"], default="small")
    ap.add_argument("--repeat", type=int, default=2, help="runs of each solver per size (default 2)")
    ap.add_argument("--threads", type=int, default=2, help="threads for both solvers (default 2)")
    ap.add_argument("--timeout", type=float, default=3600.0, help="seconds per run before it is killed")
    ap.add_argument("--work", type=Path, default=ROOT / "target" / "race", help="working folder")
    ap.add_argument("--signorini", type=Path, default=ROOT / "target" / "release" / "signorini")
    ap.add_argument("--dry-run", action="store_true", help="write the decks and check them; run no solver")
    args = ap.parse_args()
    if not args.signorini.exists():
        sys.exit(f"error: {args.signorini} not found: run `cargo build --release` first, or pass --signorini PATH")
    sizes = ["small", "large"] if args.size == "both" else [args.size]
    if not args.dry_run:
        ensure_ccx()
    for size in sizes:
        work, mesh, ccx_nodes = prepare(size, args.work)
        print(f"== {size}: {work}")
        self_check(args.signorini, work, mesh, ccx_nodes)
        if args.dry_run:
            continue
        hmin = SIZES[size][0]
        runs = {"ccx": [], "signorini": []}
        loads = [os.getloadavg()[0]]
        for rep in range(args.repeat):
            order = ["ccx", "signorini"] if rep % 2 == 0 else ["signorini", "ccx"]
            for who in order:
                if who == "ccx":
                    r = run_ccx(work, args.threads, args.timeout)
                else:
                    r = run_signorini(args.signorini, work, args.threads, args.timeout)
                loads.append(os.getloadavg()[0])
                print(f"  {who:9s} run {rep + 1}: {r[0]:8.2f} s wall, {r[3]:8.2f} s CPU, {r[1]:7.0f} MiB, exit {r[2]}, "
                      f"load {loads[-1]:.1f}", flush=True)
                if r[2] != 0:
                    sys.exit(f"error: {who} failed (exit {r[2]}); see {work / (who + '.log')}")
                runs[who].append(r)
        res = {"ccx": ccx_results(work, mesh), "signorini": signorini_results(work, mesh)}
        h = {k: hertz(v) for k, v in res.items()}
        med = {k: statistics.median(r[0] for r in v) for k, v in runs.items()}
        cpu = {k: statistics.median(r[3] for r in v) for k, v in runs.items()}
        pairs = [c[0] / s[0] for c, s in zip(runs["ccx"], runs["signorini"])]
        print()
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
        print(f"{time.strftime('%Y-%m-%d %H:%M', time.gmtime())} UTC, commit {commit or '?'}, {args.signorini}")
        print(f"{size}: {len(mesh.nodes)} nodes, {3 * len(mesh.nodes)} dofs, {len(mesh.tets)} Tet4, "
              f"h = {hmin} at the pole; {args.threads} threads; {args.repeat} runs each, alternating; "
              f"1-min load {min(loads):.1f}-{max(loads):.1f}")
        print(f"Hertz (R = {R}, E* = {E_STAR:.2f}) from each run's own total force F")
        print("| solver | wall s, median (runs) | CPU s (user + sys), median (runs) | peak MiB | Newton its | F | contact radius (ellipse fit, reference r) vs Hertz | peak pressure (ellipse fit) vs p0 | largest penetration |")
        print("|---|---|---|---|---|---|---|---|---|")
        print(fmt_row("CalculiX " + ccx_version(), runs["ccx"], res["ccx"], h["ccx"], hmin))
        print(fmt_row("signorini", runs["signorini"], res["signorini"], h["signorini"], hmin))
        print(f"ratio CalculiX / signorini: wall {med['ccx'] / med['signorini']:.2f}x of the medians, "
              f"{statistics.median(pairs):.2f}x the median of the pairs ("
              f"{', '.join(f'{p:.2f}' for p in pairs)}); CPU {cpu['ccx'] / cpu['signorini']:.2f}x of the medians; peak memory "
              f"{max(r[1] for r in runs['ccx']) / max(r[1] for r in runs['signorini']):.2f}x")
        print(f"Hertz: a = {h['signorini']['a']:.5f} (signorini's F), {h['ccx']['a']:.5f} (CalculiX's F); "
              f"p0 = {h['signorini']['p0']:.3f}, {h['ccx']['p0']:.3f}")
        print()


def ccx_version():
    try:
        out = subprocess.run(["ccx", "-v"], capture_output=True, text=True).stdout
        for word in out.split():
            if word[:1].isdigit():
                return word.rstrip(".")
    except OSError:
        pass
    return ""


if __name__ == "__main__":
    main()
