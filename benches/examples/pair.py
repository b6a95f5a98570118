#!/usr/bin/env python3
"""Paired timings of the examples under two builds of signorini.

    benches/examples/pair.py --a BIN_A --b BIN_B [--runs 3] [--threads 2]
                             [--examples hertz,press-pull,...]

Runs `BIN run examples/NAME/case.toml --threads T --output TMP` for A and
B in turn (A B A B ..., after one warm-up of each), each under
`/usr/bin/time -v`, and prints per example the median wall and CPU
(user + sys) seconds, the peak resident memory, the Newton iterations of
`summary.json` and the median of the pair-by-pair ratios A/B with its
range. The machine's load (`/proc/loadavg`) is printed before and after,
since this machine is shared: quote the ratios, not the absolute times.

A typical use, "before" being a checkout of an older commit built with
`cargo build --release --bin signorini`:

    benches/examples/pair.py --a target/release/signorini \\
        --b ../before/target/release/signorini \\
        --b-examples ../before/examples --runs 3
"""
import argparse, json, os, re, shutil, statistics, subprocess, sys, tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DEFAULT = ["hertz", "press-pull", "ogden-plate", "indenter", "two-spheres",
           "thick-cylinder", "rubber-tension", "cattaneo-mindlin", "ironing",
           "inp-import"]


def one_run(binary, case, threads, out):
    """(wall s, cpu s, peak MiB, Newton iterations) of one run."""
    if out.exists():
        shutil.rmtree(out)
    cmd = ["/usr/bin/time", "-v", binary, "run", str(case), "--output", str(out)]
    if threads:
        cmd += ["--threads", str(threads)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd[2:])} failed ({p.returncode}):\n{p.stderr[-2000:]}")
    err = p.stderr

    def field(name):
        return re.search(rf"{re.escape(name)}: ([0-9.:]+)", err).group(1)

    wall = 0.0
    for part in field("Elapsed (wall clock) time (h:mm:ss or m:ss)").split(":"):
        wall = 60 * wall + float(part)
    cpu = float(field("User time (seconds)")) + float(field("System time (seconds)"))
    peak = float(field("Maximum resident set size (kbytes)")) / 1024
    summary = json.loads((out / "summary.json").read_text())
    iterations = sum(i["iterations"] for i in summary["increments"])
    return wall, cpu, peak, iterations


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--a", required=True, help="the build measured (A)")
    ap.add_argument("--b", required=True, help="the build compared with (B)")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--examples", default=",".join(DEFAULT))
    ap.add_argument("--b-examples", default=str(ROOT / "examples"),
                    help="B's own examples folder (an older build may not read "
                         "today's case files)")
    args = ap.parse_args()
    print(f"load before: {open('/proc/loadavg').read().strip()}")
    print("| example | runs | A/B wall (min-max) | A/B CPU (min-max) | wall s A / B "
          "| CPU s A / B | peak MiB A / B | Newton its A / B |")
    print("|---|---|---|---|---|---|---|---|")
    tmp = Path(tempfile.mkdtemp(prefix="pair-"))
    for name in args.examples.split(","):
        case = ROOT / "examples" / name / "case.toml"
        b_case = Path(args.b_examples) / name / "case.toml"
        if not b_case.exists():
            print(f"| {name} | B has no such example |")
            continue
        a_out, b_out = tmp / f"{name}-a", tmp / f"{name}-b"
        one_run(args.a, case, args.threads, a_out)  # warm-ups
        one_run(args.b, b_case, args.threads, b_out)
        a, b = [], []
        for _ in range(args.runs):
            a.append(one_run(args.a, case, args.threads, a_out))
            b.append(one_run(args.b, b_case, args.threads, b_out))
        med = lambda xs, k: statistics.median(x[k] for x in xs)
        # /usr/bin/time counts in 10 ms steps: a run under that reads 0
        ratio = lambda k: [max(x[k], 0.01) / max(y[k], 0.01) for x, y in zip(a, b)]
        rw, rc = ratio(0), ratio(1)
        print(f"| {name} | {args.runs}+{args.runs} "
              f"| {statistics.median(rw):.3f} ({min(rw):.3f}-{max(rw):.3f}) "
              f"| {statistics.median(rc):.3f} ({min(rc):.3f}-{max(rc):.3f}) "
              f"| {med(a, 0):.2f} / {med(b, 0):.2f} | {med(a, 1):.2f} / {med(b, 1):.2f} "
              f"| {med(a, 2):.0f} / {med(b, 2):.0f} | {a[0][3]} / {b[0][3]} |", flush=True)
    shutil.rmtree(tmp)
    print(f"load after: {open('/proc/loadavg').read().strip()}")


if __name__ == "__main__":
    main()
