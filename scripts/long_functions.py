#!/usr/bin/env python3
"""List the functions in src/ longer than a limit (default 100 lines).

    python3 scripts/long_functions.py [LIMIT] [ROOT]

A function's length is the number of lines from its `fn` line to its
closing brace (doc comments and attributes not counted). Braces in
comments, strings, raw strings and character literals are skipped; a
`fn` without a body (a trait's declaration) is not a function here.
Prints `lines  path:line  name`, longest first, and exits 0 (a report,
not a check).
"""

import os
import re
import sys

FN = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)")


def code_only(text):
    """The text with comments, strings and char literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif re.match(r'b?r#*"', text[i:i + 8]) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'(b?r)(#*)"', text[i:])
            end = '"' + m.group(2)
            j = text.find(end, i + len(m.group(0)))
            j = n if j < 0 else j + len(end)
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j += 1
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == "'":
            # a char literal ('x', '\n', '\u{..}'), not a lifetime ('a)
            m = re.match(r"'(\\u\{[0-9a-fA-F]+\}|\\.|[^\\'])'", text[i:])
            if m:
                out.append(" " * len(m.group(0)))
                i += len(m.group(0))
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    """(name, first line, lines) of every function with a body in `path`."""
    with open(path, encoding="utf-8") as f:
        code = code_only(f.read())
    found = []
    for m in FN.finditer(code):
        # the body: the first `{` before any `;` at depth 0 of the signature
        i, depth = m.end(), 0
        while i < len(code):
            ch = code[i]
            if ch in "(<[":
                depth += 1
            elif ch in ")>]":
                depth -= 1
            elif ch == ";" and depth <= 0:
                i = -1
                break
            elif ch == "{" and depth <= 0:
                break
            i += 1
        if i < 0 or i >= len(code):
            continue
        level, j = 0, i
        while j < len(code):
            if code[j] == "{":
                level += 1
            elif code[j] == "}":
                level -= 1
                if level == 0:
                    break
            j += 1
        first = code.count("\n", 0, m.start()) + 1
        last = code.count("\n", 0, j) + 1
        found.append((m.group(1), first, last - first + 1))
    return found


def main():
    limit = int(sys.argv[1]) if len(sys.argv) > 1 else 100
    root = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "..", "src")
    rows = []
    for folder, _, files in os.walk(root):
        for name in files:
            if name.endswith(".rs"):
                path = os.path.join(folder, name)
                for fn, line, length in functions(path):
                    if length > limit:
                        rel = os.path.relpath(path, os.path.join(root, ".."))
                        rows.append((length, f"{rel}:{line}", fn))
    rows.sort(key=lambda r: (-r[0], r[1]))
    for length, where, fn in rows:
        print(f"{length:5d}  {where}  {fn}")
    print(f"{len(rows)} functions over {limit} lines")


if __name__ == "__main__":
    main()
