#!/bin/sh
# The million-dof benchmark (README.md beside this file): mesh the block at
# size N with gmsh, run it with PETSc's GMRES + GAMG under /usr/bin/time -v,
# and print dofs, wall time, peak memory, iterations, phase times and the
# contact's totals (half model). Run from the repository's root, after
# `cargo build --release --features petsc`:
#     sh benches/million/run.sh 60        # 1.09 M dofs
#     sh benches/million/run.sh 30        # 142 k dofs, the check's coarse run
# PETSc options in PETSC_EXTRA are appended to the case's [solver.petsc]
# options (which win over the environment's PETSC_OPTIONS; put -log_view
# there, it is read once per process). The work folder is
# target/million/nN (the mesh, the case and the results; WORK=DIR puts nN
# under DIR instead); KEEP=1 keeps the
# mesh and the VTU files, which are otherwise deleted after the run (the
# 1 M-dof mesh is about 37 MB, each VTU 17 MB).
# METHOD=uzawa runs the contact by Uzawa's augmented Lagrangian (an outer
# loop of multiplier updates on the penalty path, no multiplier unknowns,
# so GAMG still applies) instead of the case's penalty method.
# EXACT_STICK=false (or true) sets the contact's `exact_stick` (with uzawa
# the default is true: exact stick by a second, tangential, outer loop;
# false keeps the penalty run's regularised stick, so that only the normal
# enforcement differs from it). With uzawa GAMG is rebuilt at every solve
# (UZAWA_PETSC, default "-ksp_reuse_preconditioner 0", put before
# PETSC_EXTRA): the GAMG of the first, contact-free, tangent does not
# precondition contact rows 100 times the penalty's (README.md).
# Distributed (a `petsc` build with helper "mpi"'s `mpirun` support):
#     LAUNCH="mpirun -np 2 --allow-run-as-root --oversubscribe" THREADS=1 \
#         sh benches/million/run.sh 45
# /usr/bin/time then reports the largest process's peak memory.
set -eu
n=${1:?usage: run.sh N (30: 142 k dofs, 45: 465 k, 60: 1.09 M)}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
signorini=${SIGNORINI:-$root/target/release/signorini}
work=${WORK:-$root/target/million}/n$n
mkdir -p "$work"
gmsh -3 "$here/block.geo" -setnumber n "$n" -format msh41 -bin -o "$work/block.msh" > "$work/gmsh.log"
case ${METHOD:-penalty} in
uzawa) method_options=${UZAWA_PETSC--ksp_reuse_preconditioner 0} ;;
*) method_options= ;;
esac
sed -e "/^options = /s|\"\$| $method_options ${PETSC_EXTRA:-}\"|" \
    -e "/^method = /s|\"penalty\"|\"${METHOD:-penalty}\"|" \
    -e "/^method = /s|\$|${EXACT_STICK:+\\nexact_stick = $EXACT_STICK}|" "$here/case.toml" > "$work/case.toml"
rm -rf "$work/results"
load_before=$(uptime)
# shellcheck disable=SC2086 # LAUNCH is a command line to split
/usr/bin/time -v ${LAUNCH:-} "$signorini" run "$work/case.toml" --output "$work/results" --quiet \
    ${THREADS:+--threads "$THREADS"} \
    > "$work/run.log" 2> "$work/time.txt" || { tail -n 20 "$work/run.log" "$work/time.txt"; exit 1; }
load_after=$(uptime)
python3 - "$work" "$load_before" "$load_after" <<'PY'
import json, re, sys
work, before, after = sys.argv[1:4]
s = json.load(open(f"{work}/results/summary.json"))
t = open(f"{work}/time.txt").read()
wall = re.search(r"Elapsed \(wall clock\) time.*: (.*)", t).group(1)
rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", t).group(1))
last = s["increments"][-1]
c = last["contact"]["indentation"]
press = [i for i in s["increments"] if i["step_name"] == "press"][-1]
cp = press["contact"]["indentation"]
print(f"case        {work}/case.toml")
print(f"dofs        {s['dofs']} ({s['nodes']} nodes, {s['elements']} Hex8)")
print(f"wall        {wall} (summary {s['wall_time']:.1f} s), peak RSS {rss / 2**20:.2f} GiB")
print(f"increments  {len(s['increments'])}, Newton iterations "
      f"{sum(i['iterations'] for i in s['increments'])} {[i['iterations'] for i in s['increments']]}")
print(f"linear      {s['krylov_solves']} solves, {s['krylov_iterations']} Krylov iterations")
print("phases      " + ", ".join(f"{k} {v:.1f} s" for k, v in s["phase_times"].items()))
print(f"end press   normal force {-cp['force'][2]:.5f}, contact area {cp['area']:.5f}, "
      f"friction force x {cp['tangential_force'][0]:.5f}, closed nodes {cp['closed_nodes']}")
print(f"end shear   normal force {-c['force'][2]:.5f}, contact area {c['area']:.5f}, "
      f"friction force x {-c['tangential_force'][0]:.5f} (Q/muP {-c['tangential_force'][0] / (-0.3 * c['force'][2]):.3f}), "
      f"stick {c['stick_nodes']}, slip {c['slip_nodes']}")
log = open(f"{work}/results/million.log").read()
h = float(re.search(r"contact element size ([0-9.eE+-]+)", log).group(1))
# a Newton solve ends at an evaluation with no correction (0.0): one per
# solve, so the solves of an increment less one are its outer updates
# (Uzawa's multiplier updates, with exact stick the tangential ones too)
solves = [sum(1 for c in i["corrections"] if c == 0.0) for i in s["increments"]]
print(f"outer       Newton solves per increment {solves}, "
      f"{sum(solves) - len(solves)} multiplier updates (solves less one per increment)")
# the residual at the start of each solve after an update is the update's
# force (A_s Δλ): its ratio from one update to the next is the outer loop's
# measured contraction rate
for i in s["increments"]:
    starts = [r for r, c in zip(i["residuals"][1:], i["corrections"]) if c == 0.0]
    rates = [b / a for a, b in zip(starts, starts[1:]) if a > 0]
    if starts:
        print(f"  t = {i['time']:g}: residual after each update {', '.join(f'{r:.1e}' for r in starts)}; "
              f"ratios {', '.join(f'{q:.1e}' for q in rates) or '-'}")
pens = [i["contact"]["indentation"]["largest_penetration"] for i in s["increments"]]
worst = max(pens)
h_min = 0.3 / int(s_n) if (s_n := work.rstrip("/").rsplit("/n", 1)[-1]).isdigit() else float("nan")
print(f"penetration per increment {', '.join(f'{p:.2e}' for p in pens)}")
print(f"penetration largest over the increments {worst:.2e} = {worst / h:.2e} h "
      f"(h = {h:.3e}, the log's contact element size; exact contact: below 1e-8 h) "
      f"= {worst / h_min:.2e} h_min (h_min = 0.3/n = {h_min:.3e}, the finest element, at the origin)")
print(f"load        before: {before.strip()}")
print(f"            after:  {after.strip()}")
PY
if [ -z "${KEEP:-}" ]; then rm -f "$work/block.msh" "$work"/results/*.vtu "$work"/results/*.checkpoint; fi
