#!/usr/bin/env python3
"""Time two commands as whole processes, alternating A B A B, and print ratios.

    scripts/paired_timing.py [-n RUNS] [--warmup W] --vs 'COMMAND_B' -- COMMAND_A [ARG ...]

How BENCHMARKS.md's paired figures are taken: the machine these figures
come from is shared and its speed drifts, so A and B run in turn and the
ratio A/B is taken pair by pair, where both saw the same load. Each run's
user + system seconds ("cpu") and peak resident memory are the kernel's
own accounting of the finished child (`os.wait4`'s resource usage: of the
child and the children it waited for; under `mpirun`, use `/usr/bin/time
-v` per process instead); "wall" is a monotonic clock around the run.
W warm-up pairs (default 1) run first and are not counted. Every figure is
printed as median (min–max): quote the median; a wide spread says the
machine was noisy. The 1-minute load average is printed before and after.

COMMAND_B is one string split as a shell splits words (`shlex`); neither
command is given a shell (write `sh -c '...'` for a pipe or a redirection).
Their output is discarded. Exit status: 0 when every run was started and
reaped (a command's own non-zero exit is printed, not acted on), 2 for
unusable arguments.

Only the standard library is needed.
"""

import argparse
import os
import shlex
import statistics
import subprocess
import sys
import time


def run_once(command):
    """(cpu seconds, wall seconds, peak MiB, exit code) of one run of `command`."""
    start = time.monotonic()
    child = subprocess.Popen(command, stdin=subprocess.DEVNULL,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.monotonic() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    cpu = usage.ru_utime + usage.ru_stime
    return cpu, wall, usage.ru_maxrss / 1024.0, child.returncode


def spread(values, digits=3):
    """`median (min–max)` of `values`."""
    return f"{statistics.median(values):.{digits}f} ({min(values):.{digits}f}–{max(values):.{digits}f})"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-n", "--runs", type=int, default=5, help="counted pairs (default 5)")
    parser.add_argument("--warmup", type=int, default=1, help="uncounted pairs first (default 1)")
    parser.add_argument("--vs", required=True, help="COMMAND_B, one string")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- COMMAND_A [ARG ...]")
    args = parser.parse_args()
    a = args.command[1:] if args.command[:1] == ["--"] else args.command
    b = shlex.split(args.vs)
    if not a or not b or args.runs < 1 or args.warmup < 0:
        parser.error("give -n ≥ 1, --vs 'COMMAND_B' and -- COMMAND_A")
    load_before = os.getloadavg()[0]
    for _ in range(args.warmup):
        run_once(a)
        run_once(b)
    pairs = [(run_once(a), run_once(b)) for _ in range(args.runs)]
    load_after = os.getloadavg()[0]
    print(f"{args.runs} pairs, A then B, load {load_before:.1f} → {load_after:.1f}")
    for name, index in (("A", 0), ("B", 1)):
        runs = [pair[index] for pair in pairs]
        codes = sorted({r[3] for r in runs})
        print(f"{name}: cpu {spread([r[0] for r in runs])} s, wall {spread([r[1] for r in runs])} s, "
              f"peak {spread([r[2] for r in runs], 0)} MiB, exit {codes}")
    print(f"A/B cpu  {spread([pa[0] / pb[0] for pa, pb in pairs])}")
    print(f"A/B wall {spread([pa[1] / pb[1] for pa, pb in pairs])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
