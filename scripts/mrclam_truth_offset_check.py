#!/usr/bin/env python3
"""Is robot 5's noisier held-out half (noise/landmark_logs) the camera's or the truth's?
Standard library only, reads the raw MRCLAM Dataset 6 files, none of locbench's code.

If Vicon's pose were displaced by e in a camera frame, every landmark's range residual (measured
minus the range from the Vicon pose) would be −u·e (u the unit vector to the landmark) and its
bearing residual would move by (Δy·e_x − Δx·e_y)/ρ². For every frame with ≥ 3 landmarks this fits
e to the range residuals (least squares) and prints, per half of the log (the experiment's split):
the fitted |e|, the frame's range spread before and after removing it, and the correlation and
slope between the bearing residuals it predicts and those observed (each less its frame's mean,
which a heading error would shift alike). A displaced truth gives slope ≈ 1; camera range errors
give ≈ 0.

usage: mrclam_truth_offset_check.py [ROBOT ...] (default 1 2 3 4 5; $LOCBENCH_DATA or ../shared/datasets)
"""
import bisect
import collections
import math
import os
import statistics
import sys

from mrclam_raw import rows, wrap

ROOT = os.path.join(os.environ.get("LOCBENCH_DATA", "../shared/datasets"), "mrclam", "MRCLAM_Dataset6")


def rows_of(name):
    return rows(os.path.join(ROOT, name))


def truth_at(truth, times, t):
    i = bisect.bisect_left(times, t)
    if i <= 0 or i >= len(times):
        return None
    a, b = truth[i - 1], truth[i]
    f = (t - a[0]) / (b[0] - a[0])
    return (a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]), a[3] + f * wrap(b[3] - a[3]))


def frame_fit(obs, pose, landmarks):
    """The offset e fitted to one frame's range residuals; None when the directions do not fix it."""
    a, y, bearing_seen, bearing_from_e = [], [], [], []
    for subject, r, b in obs:
        dx, dy = landmarks[subject][0] - pose[0], landmarks[subject][1] - pose[1]
        rho = math.hypot(dx, dy)
        a.append((-dx / rho, -dy / rho))  # range residual = −u·e
        y.append(r - rho)
        bearing_seen.append(wrap(b - wrap(math.atan2(dy, dx) - pose[2])))
        bearing_from_e.append((dy / rho**2, -dx / rho**2))  # bearing shift = (Δy·e_x − Δx·e_y)/ρ²
    s11 = sum(u[0] * u[0] for u in a)
    s12 = sum(u[0] * u[1] for u in a)
    s22 = sum(u[1] * u[1] for u in a)
    det = s11 * s22 - s12 * s12
    if det < 0.3:
        return None
    b1 = sum(u[0] * v for u, v in zip(a, y))
    b2 = sum(u[1] * v for u, v in zip(a, y))
    ex, ey = (s22 * b1 - s12 * b2) / det, (s11 * b2 - s12 * b1) / det
    left = [v - (u[0] * ex + u[1] * ey) for u, v in zip(a, y)]
    predicted = [c[0] * ex + c[1] * ey for c in bearing_from_e]
    ms, mp = statistics.mean(bearing_seen), statistics.mean(predicted)
    return {
        "e": math.hypot(ex, ey),
        "spread_before": statistics.pstdev(y),
        "spread_after": statistics.pstdev(left),
        "seen": [x - ms for x in bearing_seen],
        "predicted": [x - mp for x in predicted],
    }


def check(robot, landmarks, subject_of):
    truth = list(rows_of(f"Robot{robot}_Groundtruth.dat.gz"))
    times = [p[0] for p in truth]
    measurements = list(rows_of(f"Robot{robot}_Measurement.dat.gz"))
    t0 = max(truth[0][0], measurements[0][0])
    mid = (t0 + min(truth[-1][0], measurements[-1][0])) / 2
    frames = collections.defaultdict(list)
    for t, code, r, b in measurements:
        subject = subject_of.get(int(code))
        if subject in landmarks:
            frames[t].append((subject, r, b))
    halves = ([], [])
    for t, obs in sorted(frames.items()):
        if len(obs) < 3:
            continue
        pose = truth_at(truth, times, t - 0.04)  # the camera's ~40 ms delay (diagnosis README)
        fit = frame_fit(obs, pose, landmarks) if pose else None
        if fit:
            halves[0 if t < mid else 1].append(fit)
    for h, fits in enumerate(halves):
        if not fits:
            continue
        e = sorted(f["e"] for f in fits)
        xs = [v for f in fits for v in f["seen"]]
        ys = [v for f in fits for v in f["predicted"]]
        mx, my = statistics.mean(xs), statistics.mean(ys)
        cov = sum((a - mx) * (b - my) for a, b in zip(xs, ys))
        vx = sum((a - mx) ** 2 for a in xs)
        vy = sum((b - my) ** 2 for b in ys)
        print(
            f"robot {robot} half {h + 1}: {len(fits)} frames, |e| median {statistics.median(e):.3f} m; "
            f"range spread {statistics.median([f['spread_before'] for f in fits]):.3f} -> "
            f"{statistics.median([f['spread_after'] for f in fits]):.3f} m; bearing residuals against those e "
            f"predicts: r {cov / math.sqrt(vx * vy):.2f}, slope {cov / vy:.2f} (a displaced truth: 1)"
        )


def main():
    subject_of = {int(r[1]): int(r[0]) for r in rows_of("Barcodes.dat.gz")}
    landmarks = {int(r[0]): (r[1], r[2]) for r in rows_of("Landmark_Groundtruth.dat.gz")}
    for robot in [int(a) for a in sys.argv[1:]] or [1, 2, 3, 4, 5]:
        check(robot, landmarks, subject_of)


if __name__ == "__main__":
    main()
