#!/usr/bin/env python3
"""Compare two result folders of the same case: every number of
summary.json except times and the case path (iterations, residuals,
forces, largest penetration, counts), and every DataArray of every VTU
file (binary, UInt64 header), within a relative tolerance (default 1e-10,
against the array's or the figure's own scale).

    scripts/compare-run.py BEFORE_DIR AFTER_DIR [--tolerance 1e-10]

Exit status 1 and a list of the differences if any."""
import base64, json, math, re, struct, sys
from pathlib import Path

SKIP = {"wall_time", "phase_times", "case", "threads"}


def walk(a, b, path, out, tol):
    if isinstance(a, dict):
        if set(a) != set(b):
            out.append(f"{path}: keys {sorted(set(a) ^ set(b))}")
        for k in a:
            if k in SKIP or k not in b:
                continue
            walk(a[k], b[k], f"{path}.{k}", out, tol)
    elif isinstance(a, list):
        if len(a) != len(b):
            out.append(f"{path}: length {len(a)} vs {len(b)}")
            return
        scale = max([abs(x) for x in a if isinstance(x, (int, float)) and math.isfinite(x)] or [0])
        for i, (x, y) in enumerate(zip(a, b)):
            if isinstance(x, (int, float)) and isinstance(y, (int, float)):
                close(x, y, scale, f"{path}[{i}]", out, tol)
            else:
                walk(x, y, f"{path}[{i}]", out, tol)
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)):
        close(a, b, 0.0, path, out, tol)
    elif a != b:
        out.append(f"{path}: {a!r} vs {b!r}")


def close(x, y, scale, path, out, tol):
    if isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y):
        return
    if abs(x - y) > tol * max(abs(x), abs(y), scale, 1e-300):
        out.append(f"{path}: {x!r} vs {y!r}")


def arrays(vtu):
    text = Path(vtu).read_text()
    found = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)"[^>]*format="binary">\s*([^<]*)</DataArray>', text):
        kind, name, data = m.groups()
        raw = base64.b64decode(data.strip())
        n = struct.unpack("<Q", raw[:8])[0]
        code = {"Float64": "d", "Int64": "q", "UInt8": "B", "Int32": "i", "UInt64": "Q"}[kind]
        size = struct.calcsize(code)
        found[name] = list(struct.unpack(f"<{n // size}{code}", raw[8:8 + n]))
    return found


def main():
    args = sys.argv[1:]
    tol = 1e-10
    if "--tolerance" in args:
        i = args.index("--tolerance")
        tol = float(args[i + 1])
        del args[i:i + 2]
    before, after = map(Path, args)
    out = []
    walk(json.loads((before / "summary.json").read_text()),
         json.loads((after / "summary.json").read_text()), "summary", out, tol)
    files = sorted(p.name for p in before.glob("*.vtu"))
    if files != sorted(p.name for p in after.glob("*.vtu")):
        out.append("different VTU files")
    for f in files:
        a, b = arrays(before / f), arrays(after / f)
        if set(a) != set(b):
            out.append(f"{f}: fields {sorted(set(a) ^ set(b))}")
        for name in a:
            if name in b:
                walk(a[name], b[name], f"{f}:{name}", out, tol)
    for line in out[:40]:
        print(line)
    print(f"{before} vs {after}: {len(out)} differences ({len(files)} VTU files)")
    sys.exit(1 if out else 0)


main()
