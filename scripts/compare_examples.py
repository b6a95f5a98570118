#!/usr/bin/env python3
"""Run every example with two signorini binaries and compare their answers.

    scripts/compare_examples.py OLD_BINARY NEW_BINARY [EXAMPLE ...]

EXAMPLE: a folder of examples/ or a case file in one, such as
cattaneo-mindlin/coarse.toml or calculix-deck/deck_c3d10.inp. A folder
runs its case.toml; a folder without one runs each of its other case
files, `*.toml` and Abaqus/CalculiX `*.inp` decks (as `signorini run`
takes them: examples/calculix-deck runs deck.inp and deck_c3d10.inp); a
folder with neither (examples/python, a Python script) is skipped, said
so. Without EXAMPLE: every folder of examples/, so every example the
README lists that `signorini run` runs.

A behaviour-preserving change (a refactoring, a new backend that must give
the same numbers) is checked with it: both binaries run each of those
cases (with `--threads 1`, so that the parallel
factorisation sums in one order) into temporary folders, and the script
compares, increment by increment, what `summary.json` reports — the status,
the increment times and sizes, Newton iterations, cuts, every interface's
contact force, tangential force, closed/stick/slip counts, contact area and
largest penetration, the reaction forces of every surface set — and the
`displacement` field of the last VTU (against the largest displacement
of the run). Numbers must agree within 1e-10
relative to the largest magnitude of that quantity in the run (of any
component for a force, of any set's reaction for a reaction, of the final
displacement for the largest penetration: a penetration of 1e-27 against
1e-26 is the same zero); counts must be equal. Where the two runs'
increments part (another number of increments, or other times: a
different growth of the increment), that is said first, with the times
on both sides, and the runs are compared up to there, the displacement
at the last increment they share. Exit status 1 lists every difference.

Only the standard library is needed (the VTU reader decodes the inline
base64 arrays that `src/output/vtu.rs` writes, compressed or not).
"""

import base64
import json
import pathlib
import re
import subprocess
import sys
import tempfile
import zlib

RELATIVE = 1e-10
ROOT = pathlib.Path(__file__).resolve().parent.parent


def run(binary, case, out):
    proc = subprocess.run(
        [binary, "run", str(case), "--output", str(out), "--threads", "1", "--quiet"],
        capture_output=True,
        text=True,
    )
    return proc.returncode, proc.stderr


def read_point_field(path, name):
    """The values of point array `name` (Float64 or Int64) of a VTU written
    by signorini, compressed (zlib) or not; None if there is no such array."""
    import array
    import struct

    text = pathlib.Path(path).read_text()
    header_type = re.search(r'header_type="(\w+)"', text).group(1)
    compressed = 'compressor="vtkZLibDataCompressor"' in text
    m = re.search(
        r'<DataArray type="(Float64|Int64)" Name="%s"[^>]*format="binary">\s*([A-Za-z0-9+/=\s]+?)\s*</DataArray>'
        % re.escape(name),
        text,
    )
    if m is None:
        return None
    kind, body = m.group(1), "".join(m.group(2).split())
    size, word = (8, "Q") if header_type == "UInt64" else (4, "I")
    if compressed:
        # two base64 runs: the header [blocks, block size, last size,
        # compressed sizes...], then the compressed blocks
        blocks = struct.unpack("<" + word, base64.b64decode(body[:12])[:size])[0]
        header_len = -(-size * (3 + blocks) // 3) * 4
        header = struct.unpack("<%d%s" % (3 + blocks, word), base64.b64decode(body[:header_len]))
        data = base64.b64decode(body[header_len:])
        payload, at = b"", 0
        for s in header[3:]:
            payload += zlib.decompress(data[at : at + s])
            at += s
    else:
        payload = base64.b64decode(body)[size:]
    values = array.array("d" if kind == "Float64" else "q")
    values.frombytes(payload)
    return [float(v) for v in values]


def numbers(summary):
    """Flatten what the two runs must agree on into (key, value) pairs."""
    out = [("status", summary["status"]), ("increments", len(summary["increments"]))]
    for k, inc in enumerate(summary["increments"]):
        p = f"increment {k + 1}"
        for key in ("step_name", "iterations", "cuts"):
            out.append((f"{p} {key}", inc[key]))
        for key in ("time", "increment"):
            out.append((f"{p} {key}", float(inc[key])))
        for name, c in sorted(inc.get("contact", {}).items()):
            for key in ("stick_nodes", "slip_nodes", "closed_nodes"):
                out.append((f"{p} contact {name} {key}", c[key]))
            for key in ("force", "tangential_force", "primary_force"):
                for d, v in enumerate(c.get(key) or []):
                    out.append((f"{p} contact {name} {key}[{d}]", float(v)))
            for key in ("area", "largest_penetration"):
                out.append((f"{p} contact {name} {key}", float(c[key])))
        for name, f in sorted(inc.get("reaction_forces", {}).items()):
            for d, v in enumerate(f):
                out.append((f"{p} reaction {name}[{d}]", float(v)))
    return out


def family(key):
    """What a number is compared against: the same quantity over the run,
    all components of a force together, and all reaction forces together
    (a reaction component that is zero up to round-off, 1e-17 beside a
    load of 1, is compared with the run's reactions, not with itself)."""
    kind = re.sub(r"^increment \d+ ", "", key)
    if kind.startswith("reaction "):
        return "reaction"
    return re.sub(r"\[\d+\]$", "", kind)


def scale_of(key, pairs):
    """The largest magnitude of the quantity's family over the run."""
    kind = family(key)
    return max(
        (abs(v) for k, v in pairs if isinstance(v, float) and family(k) == kind),
        default=0.0,
    )


def parted_increments(old, new):
    """Where the two runs' increments part (a different number of
    increments, or times apart by more than RELATIVE of the run's end): the
    number of increments they share from the start, and the difference
    said as such; (None, None) if they go alike."""
    ta = [float(inc["time"]) for inc in old["increments"]]
    tb = [float(inc["time"]) for inc in new["increments"]]
    close = RELATIVE * max(map(abs, ta + tb), default=0.0)
    apart = (k for k, (x, y) in enumerate(zip(ta, tb)) if abs(x - y) > close)
    same = next(apart, min(len(ta), len(tb)))
    if len(ta) == len(tb) == same:
        return None, None
    shown = lambda ts: ", ".join(f"{t:.6g}" for t in ts[same : same + 4]) or "none"
    through = f"the same through t = {ta[same - 1]:.6g}" if same else "apart from the first"
    return same, (
        f"increments part: {len(ta)} vs {len(tb)}, {through}, then t = "
        f"{shown(ta)} vs {shown(tb)} (compared up to there)"
    )


def compare(old_dir, new_dir):
    diffs = []
    missing = [str(d.name) for d in (old_dir, new_dir) if not (d / "summary.json").exists()]
    if missing:
        return [f"no summary.json from {' and '.join(missing)}"]
    old = json.loads((old_dir / "summary.json").read_text())
    new = json.loads((new_dir / "summary.json").read_text())
    same, parted = parted_increments(old, new)
    if parted:
        # the increments both runs reach alike, and the displacement at the
        # last of them
        diffs.append(parted)
        old["increments"], new["increments"] = old["increments"][:same], new["increments"][:same]
    a, b = numbers(old), numbers(new)
    if [k for k, _ in a] != [k for k, _ in b]:
        only = sorted(set(k for k, _ in a) ^ set(k for k, _ in b))
        return [f"different quantities: {only[:5]}"]
    u0 = u1 = None
    if old["increments"] and new["increments"]:
        u0 = read_point_field(old_dir / old["increments"][-1]["file"], "displacement")
        u1 = read_point_field(new_dir / new["increments"][-1]["file"], "displacement")
    # the largest displacement of the run (a load there and back ends at
    # zero up to round-off): the scale of the final field's difference and
    # of a penetration, zero to round-off at 1e-27 against 1e-24
    length = max(map(abs, (u0 or []) + (u1 or [])), default=0.0)
    for inc in old["increments"][:-1]:
        if not inc.get("file") or not (old_dir / inc["file"]).exists():
            continue
        u = read_point_field(old_dir / inc["file"], "displacement") or []
        length = max(length, max(map(abs, u), default=0.0))
    for (key, x), (_, y) in zip(a, b):
        if isinstance(x, float):
            scale = max(scale_of(key, a), scale_of(key, b), 1e-300)
            if key.endswith("largest_penetration"):
                scale = max(scale, length)
            tolerance = RELATIVE * scale
            if not abs(x - y) <= tolerance:
                diffs.append(f"{key}: {x!r} vs {y!r}")
        elif x != y:
            diffs.append(f"{key}: {x!r} vs {y!r}")
    if old["increments"] and new["increments"]:
        if u0 is None or u1 is None:
            return diffs + ["no displacement field in the last VTU compared"]
        worst = max((abs(p - q) for p, q in zip(u0, u1)), default=0.0)
        if len(u0) != len(u1) or worst > RELATIVE * length:
            at = "final" if not parted else f"t = {float(old['increments'][-1]['time']):.6g}"
            diffs.append(f"{at} displacement differs by {worst:.3e} (largest {length:.3e})")
    return diffs


def cases(name):
    """The case files EXAMPLE `name` runs (see the help): a case file, or a
    folder's case.toml, else its *.toml and *.inp files; [] if none."""
    path = ROOT / "examples" / name
    if path.is_file():
        return [path]
    if (path / "case.toml").is_file():
        return [path / "case.toml"]
    return sorted(p for p in path.glob("*") if p.suffix in (".toml", ".inp") and p.is_file())


def main():
    if len(sys.argv) < 3 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if sys.argv[1:2] in (["-h"], ["--help"]) else 2
    old_bin, new_bin = sys.argv[1], sys.argv[2]
    names = sys.argv[3:] or sorted(p.name for p in (ROOT / "examples").iterdir() if p.is_dir())
    failed = False
    with tempfile.TemporaryDirectory() as tmp:
        for folder in names:
            found = cases(folder)
            if not found:
                print(f"{folder}: skipped, no case.toml, other .toml case or .inp deck")
                failed |= bool(sys.argv[3:])
            for case in found:
                failed |= compare_case(old_bin, new_bin, case, pathlib.Path(tmp))
    return 1 if failed else 0


def compare_case(old_bin, new_bin, case, tmp):
    """Run `case` with both binaries into `tmp`, print the outcome; whether
    the answers differ."""
    # examples/NAME/case.toml is NAME; another case file NAME-FILE
    folder = case.parent.name
    name = folder if case.name == "case.toml" else f"{folder}-{case.name}"
    dirs = []
    for tag, binary in (("old", old_bin), ("new", new_bin)):
        out = tmp / f"{name}-{tag}"
        code, err = run(binary, case, out)
        dirs.append(out)
        if code != 0:
            print(f"{name}: {tag} binary failed ({code}): {err.strip()[:300]}")
    diffs = compare(*dirs)
    status = "same" if not diffs else f"{len(diffs)} differences"
    print(f"{name}: {status}")
    for d in diffs[:20]:
        print(f"    {d}")
    return bool(diffs)


if __name__ == "__main__":
    sys.exit(main())
