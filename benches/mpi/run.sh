#!/bin/bash
# The distributed-run measurements of BENCHMARKS.md ("Distributed runs"):
# a Hex8 block pressed on a rigid plane (penalty contact, GAMG), at two
# sizes on 1 and 2 processes, one thread each; wall time and peak memory
# (max RSS) per process from /usr/bin/time. Needs a `--features petsc`
# build (BIN, default target/release/signorini) and Open MPI.
#   benches/mpi/run.sh [WORK_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
BIN="${BIN:-$here/../../target/release/signorini}"
work="${1:-${TMPDIR:-/tmp}/signorini-mpi-bench}"
mpirun=(mpirun -np)
if mpirun --version | grep -q "Open MPI"; then mpirun=(mpirun --allow-run-as-root --oversubscribe -np); fi
for size in "40 40 20 A" "56 56 20 B"; do
  set -- $size
  d="$work/$4"; mkdir -p "$d"
  [ -f "$d/block.msh" ] || python3 "$here/block.py" "$1" "$2" "$3" "$d/block.msh"
  cp "$here/case.toml" "$d/"
  for np in 1 2; do
    echo "== $4 ($1 x $2 x $3) np=$np load $(cut -d' ' -f1-3 /proc/loadavg) $(date -u +%T)"
    "${mpirun[@]}" "$np" /usr/bin/time -f "rank max RSS %M KB, wall %e s" \
      "$BIN" run "$d/case.toml" --threads 1 --quiet --output "$d/out-np$np" 2>&1 | tail -"$np"
    python3 -c "
import json; s=json.load(open('$d/out-np$np/summary.json'))
print(s['status'], 'wall', round(s['wall_time'], 2), 'newton', [i['iterations'] for i in s['increments']],
      'krylov', s['krylov_solves'], s['krylov_iterations'], 'assembly', round(s['phase_times']['assembly'], 2),
      'petsc', round(s['phase_times']['factorisation'], 2), 'force', s['increments'][-1]['contact']['base']['force'][2],
      'nnz', s['matrix_nnz'])"
  done
done
