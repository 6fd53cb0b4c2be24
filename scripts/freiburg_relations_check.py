#!/usr/bin/env python3
"""Independent checks of laser/real_logs on the Freiburg relations (README, "Real scans"),
computed without locbench's code. Python 3 standard library only.

  report REPORT.json          means, 95% intervals (normal approximation, n > 100) and paired
                              differences against odometry, from the per-relation values a
                              laser/real_logs report keeps (per_relation_values = true)
  triangles RELATIONS.gz      internal consistency of a .relations file: for every (a,b), (b,c)
                              and (a,c) present, |(a,b)∘(b,c) − (a,c)|
  timeshift CLF.gz RELATIONS.gz DELTA...
                              raw odometry's relation error (ODOM lines, linear interpolation)
                              with the relation stamps shifted by DELTA seconds
"""
import bisect
import gzip
import json
import math
import sys


def interval(v):
    n = len(v)
    mu = sum(v) / n
    sd = math.sqrt(sum((x - mu) ** 2 for x in v) / (n - 1))
    h = 1.96 * sd / math.sqrt(n)
    return mu, mu - h, mu + h


def report(path):
    r = json.load(open(path))
    res = {(m['method'], m['dataset'], m['variant']): m for m in r['results']}
    datasets, methods = [], []
    for (me, ds, va) in res:
        if ds not in datasets:
            datasets.append(ds)
        if va == 'rpe_translation' and me not in methods:
            methods.append(me)
    for ds in datasets:
        o_t = res[('odometry_raw', ds, 'rpe_translation')]['values']
        o_r = res[('odometry_raw', ds, 'rpe_rotation')]['values']
        print(f"== {ds}: {len(o_t)} relations; mean [95%] mm, deg | paired Δ vs odometry")
        odo_heading = interval([math.degrees(x) for x in o_r])
        for me in methods:
            t = res[(me, ds, 'rpe_translation')]['values']
            rr = res[(me, ds, 'rpe_rotation')]['values']
            ct = interval([1e3 * x for x in t])
            cr = interval([math.degrees(x) for x in rr])
            dt = interval([1e3 * (a - b) for a, b in zip(t, o_t)])
            dr = interval([math.degrees(a - b) for a, b in zip(rr, o_r)])
            print(f"{me:26s} {ct[0]:7.1f} [{ct[1]:6.1f},{ct[2]:6.1f}]  {cr[0]:5.2f} [{cr[1]:5.2f},{cr[2]:5.2f}]"
                  f" | Δt {dt[0]:+6.1f} [{dt[1]:+6.1f},{dt[2]:+6.1f}]  Δθ {dr[0]:+5.2f} [{dr[1]:+5.2f},{dr[2]:+5.2f}]"
                  f" | heading intervals separated: {'yes' if cr[2] < odo_heading[1] else 'no'}")


def read_relations(path):
    out = []
    for line in gzip.open(path, 'rt'):
        f = line.split()
        if len(f) >= 8:
            out.append((float(f[0]), float(f[1]), float(f[2]), float(f[3]), float(f[7])))
    return out


def compose(p, q):
    c, s = math.cos(p[2]), math.sin(p[2])
    return (p[0] + c * q[0] - s * q[1], p[1] + s * q[0] + c * q[1], p[2] + q[2])


def triangles(path):
    rel = {(round(t1, 4), round(t2, 4)): (x, y, th) for t1, t2, x, y, th in read_relations(path)}
    starts = {}
    for (a, b) in rel:
        starts.setdefault(a, []).append(b)
    et, er = [], []
    for (a, b), p in rel.items():
        for c in starts.get(b, []):
            if (a, c) in rel:
                x, y = compose(p, rel[(b, c)]), rel[(a, c)]
                et.append(math.hypot(x[0] - y[0], x[1] - y[1]))
                er.append(abs(math.remainder(x[2] - y[2], 2 * math.pi)))
    n = len(et)
    print(f"{path}: {len(rel)} relations, {n} closed triangles")
    if n:
        print(f"  mean translation mismatch {1e3 * sum(et) / n:.1f} mm, rotation {math.degrees(sum(er) / n):.2f} deg;"
              f" independent per-relation errors of this size imply a mean error per relation of"
              f" ≈ {1e3 * sum(et) / n / math.sqrt(3):.1f} mm")


def timeshift(clf, rels, deltas):
    T, X, Y, H = [], [], [], []
    for line in gzip.open(clf, 'rt'):
        f = line.split()
        if f and f[0] == 'ODOM':
            T.append(float(f[7]))
            X.append(float(f[1]))
            Y.append(float(f[2]))
            H.append(float(f[3]))
    for i in range(1, len(H)):  # unwrap
        H[i] = H[i - 1] + math.remainder(H[i] - H[i - 1], 2 * math.pi)

    def pose(t):
        i = bisect.bisect_left(T, t)
        if i <= 0 or i >= len(T):
            return None
        a = (t - T[i - 1]) / (T[i] - T[i - 1])
        return tuple(v[i - 1] + a * (v[i] - v[i - 1]) for v in (X, Y, H))

    R = [r for r in read_relations(rels) if r[1] - r[0] <= 30.0]
    for d in deltas:
        et = er = 0.0
        n = 0
        for t1, t2, x, y, yaw in R:
            a, b = pose(t1 + d), pose(t2 + d)
            if not a or not b:
                continue
            c, s = math.cos(a[2]), math.sin(a[2])
            dx, dy = b[0] - a[0], b[1] - a[1]
            mx, my, mth = c * dx + s * dy, -s * dx + c * dy, b[2] - a[2]
            c2, s2 = math.cos(yaw), math.sin(yaw)
            ex, ey = c2 * (mx - x) + s2 * (my - y), -s2 * (mx - x) + c2 * (my - y)
            et += math.hypot(ex, ey)
            er += abs(math.remainder(mth - yaw, 2 * math.pi))
            n += 1
        print(f"delta {d:+.3f} s: {n} relations, odometry mean error {1e3 * et / n:.1f} mm, {math.degrees(er / n):.2f} deg")


if __name__ == '__main__':
    if len(sys.argv) >= 3 and sys.argv[1] == 'report':
        report(sys.argv[2])
    elif len(sys.argv) >= 3 and sys.argv[1] == 'triangles':
        triangles(sys.argv[2])
    elif len(sys.argv) >= 5 and sys.argv[1] == 'timeshift':
        timeshift(sys.argv[2], sys.argv[3], [float(v) for v in sys.argv[4:]])
    else:
        sys.exit(__doc__)
