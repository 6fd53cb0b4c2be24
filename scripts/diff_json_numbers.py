#!/usr/bin/env python3
"""Compares two JSON files value by value: every number with a relative tolerance, every other
value exactly, and prints each difference with its path (exit code 1 when there is one).

Usage: diff_json_numbers.py A.json B.json [--rtol 1e-6] [--atol 1e-12] [--ignore KEY ...]
  a number x in A and y in B agree when |x − y| ≤ atol + rtol·max(|x|, |y|);
  --ignore leaves keys of that name out at any depth (e.g. timing fields).
Strings that differ only in numbers they contain (explanations, the verdict) are compared
number by number with the same tolerance. Used for before/after reports of a change that must not
change results (docs/decisions.md; algorithms/diagnosis/README.md, "Speed")."""
import json
import re
import sys

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def close(x, y, rtol, atol):
    return abs(x - y) <= atol + rtol * max(abs(x), abs(y))


def same_text(a, b, rtol, atol):
    if a == b:
        return True
    if NUMBER.sub("#", a) != NUMBER.sub("#", b):
        return False
    na, nb = NUMBER.findall(a), NUMBER.findall(b)
    # Printed numbers carry few digits: they agree when they print alike or are within tolerance.
    return all(p == q or close(float(p), float(q), max(rtol, 10.0 ** -(significant(p) - 1)), atol)
               for p, q in zip(na, nb))


def significant(text):
    digits = re.sub(r"[eE].*$", "", text).lstrip("+-").replace(".", "").lstrip("0")
    return max(len(digits), 1)


def walk(a, b, path, out, rtol, atol, ignore):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k in ignore:
                continue
            if k not in a or k not in b:
                out.append(f"{path}/{k}: only in {'B' if k not in a else 'A'}")
                continue
            walk(a[k], b[k], f"{path}/{k}", out, rtol, atol, ignore)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: length {len(a)} -> {len(b)}")
        for i, (x, y) in enumerate(zip(a, b)):
            walk(x, y, f"{path}[{i}]", out, rtol, atol, ignore)
    elif isinstance(a, bool) or isinstance(b, bool):
        if a != b:
            out.append(f"{path}: {a} -> {b}")
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if not close(a, b, rtol, atol):
            rel = abs(a - b) / max(abs(a), abs(b))
            out.append(f"{path}: {a!r} -> {b!r} (relative {rel:.2g})")
    elif isinstance(a, str) and isinstance(b, str):
        if not same_text(a, b, rtol, atol):
            out.append(f"{path}: {a!r} -> {b!r}")
    elif a != b:
        out.append(f"{path}: {a!r} -> {b!r}")


def main(argv):
    args, rtol, atol, ignore = [], 1e-6, 1e-12, set()
    it = iter(argv)
    for x in it:
        if x == "--rtol":
            rtol = float(next(it))
        elif x == "--atol":
            atol = float(next(it))
        elif x == "--ignore":
            ignore.add(next(it))
        else:
            args.append(x)
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    with open(args[0]) as fa, open(args[1]) as fb:
        a, b = json.load(fa), json.load(fb)
    out = []
    walk(a, b, "", out, rtol, atol, ignore)
    for line in out:
        print(line)
    print(f"{args[0]} vs {args[1]}: {len(out)} difference(s) at rtol {rtol:g}")
    return 1 if out else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
