#!/usr/bin/env python3
"""Kill `signorini run` with SIGKILL at random moments and check the folder.

    scripts/kill_test.py [--kills N] [--seed S] [--binary PATH] [--case CASE]

Runs CASE (default examples/press-pull/case.toml, `--threads 1 --quiet`)
and kills it with SIGKILL after a random delay: a third of the kills in the
first 0.3 s (while the run takes its output folder over from the earlier
run), the rest anywhere up to 1.2 × the length of a whole run (so some runs
complete). Half of the runs write into a fresh folder each time, half into
one folder reused by every such run, which so holds whatever the killed or
completed run before left. After each run it checks that

- `summary.json`, if there, is valid JSON and every `file` of its
  `increments` exists and is a readable VTU with a `displacement` array;
- every VTU the `.pvd` lists exists and is readable in the same way;
- after a *completed* run the folder holds no temporary `.FILE.PID-N.tmp`
  file and exactly the files of `NAME.manifest` (for the reused folder).

It prints the counts and exits with status 1 on any violation. Only the
standard library is needed (the VTU reader is `read_point_field` of
scripts/compare_examples.py).
"""

import argparse
import json
import os
import pathlib
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from compare_examples import read_point_field  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
TEMPORARY = re.compile(r"^\..+\.\d+-\d+\.tmp$")


def readable_vtu(path):
    """Whether `path` is a VTU whose `displacement` array decodes."""
    try:
        values = read_point_field(path, "displacement")
    except Exception:  # a truncated or garbled file
        return False
    return values is not None and len(values) > 0


def check(out, name):
    """The violations in folder `out` of the series `name`, and the number
    of VTU files checked."""
    problems, checked = [], 0
    summary = out / "summary.json"
    if summary.exists():
        try:
            data = json.loads(summary.read_text())
        except ValueError as e:
            return ["summary.json is not valid JSON: %s" % e], 0
        for inc in data.get("increments", []):
            f = inc.get("file", "")
            if not f:
                continue
            checked += 1
            if not readable_vtu(out / f):
                problems.append("summary.json names %s: missing or unreadable" % f)
    pvd = out / ("%s.pvd" % name)
    if pvd.exists():
        for f in re.findall(r'file="([^"]+)"', pvd.read_text()):
            checked += 1
            if not readable_vtu(out / f):
                problems.append("%s.pvd lists %s: missing or unreadable" % (name, f))
    return problems, checked


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--kills", type=int, default=120)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--binary", default=str(ROOT / "target/release/signorini"))
    parser.add_argument("--case", default=str(ROOT / "examples/press-pull/case.toml"))
    parser.add_argument("--name", default="press-pull", help="the case's [output] name")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    work = pathlib.Path(tempfile.mkdtemp(prefix="kill_test_"))
    reused = work / "reused"

    def start(out):
        return subprocess.Popen(
            [args.binary, "run", args.case, "--output", str(out), "--threads", "1", "--quiet"],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )

    t0 = time.monotonic()
    proc = start(work / "timing")
    if proc.wait() != 0:
        sys.exit("the case does not run: %s" % args.case)
    whole = time.monotonic() - t0
    print("one whole run: %.2f s" % whole)

    kills = completed = runs = checked = temporaries = 0
    problems = []
    fresh_count = 0
    while kills < args.kills:
        runs += 1
        if runs % 2:
            fresh_count += 1
            out = work / ("fresh%d" % fresh_count)
        else:
            out = reused
        delay = rng.uniform(0, 0.3) if rng.random() < 1 / 3 else rng.uniform(0, 1.2 * whole)
        proc = start(out)
        try:
            proc.wait(timeout=delay)
            finished = True
        except subprocess.TimeoutExpired:
            proc.send_signal(signal.SIGKILL)
            proc.wait()
            finished = False
        kills += not finished
        if finished:
            completed += 1
            if proc.returncode != 0:
                problems.append("run %d exited with %d" % (runs, proc.returncode))
        found, n = check(out, args.name) if out.exists() else ([], 0)
        checked += n
        problems += ["run %d (%s, %s): %s" % (runs, out.name, "completed" if finished else "killed after %.3f s" % delay, p) for p in found]
        if out.exists():
            # the folder's lock file is the folder's, not a run's (DESIGN.md "Output safety")
            files = set(os.listdir(out)) - {".signorini.lock"}
            left = {f for f in files if TEMPORARY.match(f)}
            temporaries += len(left)
            if finished:
                if left:
                    problems.append("run %d completed with temporary files %s" % (runs, sorted(left)))
                manifest = out / ("%s.manifest" % args.name)
                listed = set(manifest.read_text().split()) if manifest.exists() else set()
                if files != listed:
                    problems.append(
                        "run %d completed: not in the manifest %s, listed but missing %s"
                        % (runs, sorted(files - listed), sorted(listed - files))
                    )
        if out != reused:
            shutil.rmtree(out, ignore_errors=True)

    shutil.rmtree(work, ignore_errors=True)
    print(
        "%d runs: %d killed with SIGKILL, %d completed; %d VTU listings checked; "
        "%d temporary files found after kills (removed by the next run); %d violations"
        % (runs, kills, completed, checked, temporaries, len(problems))
    )
    for p in problems[:50]:
        print("  " + p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
