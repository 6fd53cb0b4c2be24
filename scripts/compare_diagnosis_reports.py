#!/usr/bin/env python3
"""Compares two sets of diagnosis reports at the CLI's printed precision (6 significant digits):
kept causes and their order, each cause's detected/validated flags and likelihood ratio, every
parameter's value and 95% interval (with how far the value moved, in interval widths, and the
ratio of the widths).

Usage: compare_diagnosis_reports.py A B [log ...] — reads A_<log>.json and B_<log>.json (written
by `locbench diagnose <log> --report A_<log>.json`) for the given logs, by default the 8 real
logs of the catalog. Used for before/after diagnosis reports (docs/decisions.md; algorithms/diagnosis/README.md,
"Speed")."""
import json, sys
a_tag, b_tag = sys.argv[1], sys.argv[2]
logs = sys.argv[3:] or ["aces", "intel", "mit_csail"] + [f"mrclam6_robot{i}" for i in range(1, 6)]
g = lambda x: "null" if x is None else f"{x:.6g}"
for log in logs:
    try:
        A = json.load(open(f"{a_tag}_{log}.json")); B = json.load(open(f"{b_tag}_{log}.json"))
    except FileNotFoundError as e:
        print(log, "missing", e.filename); continue
    same_detected = A["detected"] == B["detected"]
    diffs, total = [], 0
    ca = {c["id"]: c for c in A["causes"]}; cb = {c["id"]: c for c in B["causes"]}
    for cid in ca:
        x, y = ca[cid], cb.get(cid)
        if y is None: diffs.append(f"  {cid}: missing in {b_tag}"); continue
        if x["detected"] != y["detected"] or x["evidence"].get("heldout_validated") != y["evidence"].get("heldout_validated"):
            diffs.append(f"  {cid}: detected {x['detected']}->{y['detected']}")
        lr = (x["evidence"]["value"], y["evidence"]["value"])
        if g(lr[0]) != g(lr[1]): diffs.append(f"  {cid}: LR {g(lr[0])} -> {g(lr[1])}")
        for p, v in x["parameters"].items():
            if not isinstance(v, dict) or "value" not in v: continue
            w = y["parameters"][p]; total += 1
            s1 = f"{g(v['value'])} [{g(v['ci95'][0])}, {g(v['ci95'][1])}]"
            s2 = f"{g(w['value'])} [{g(w['ci95'][0])}, {g(w['ci95'][1])}]"
            if s1 != s2:
                wa = (v['ci95'][1] - v['ci95'][0]) if None not in v['ci95'] else float('nan')
                wb = (w['ci95'][1] - w['ci95'][0]) if None not in w['ci95'] else float('nan')
                sh = abs(w['value'] - v['value']) / wa if wa else float('nan')
                diffs.append(f"  {cid}.{p}: {s1} -> {s2}  (value moved {sh:.2g} of the width; width {wa/wb if wb else float('nan'):.4f}x)" if wb else f"  {cid}.{p}: {s1} -> {s2}")
    for k in ["verdict"]:
        if A[k] != B[k]: diffs.append(f"  verdict differs")
    print(f"{log}: detected {'same' if same_detected else 'DIFFERENT'} {A['detected']}; {total} parameters, {sum(1 for d in diffs if '[' in d)} differ at 6 digits")
    for d in diffs: print(d)
