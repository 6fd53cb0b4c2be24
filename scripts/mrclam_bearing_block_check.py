#!/usr/bin/env python3
"""Independent check of bearing errors that move within a minute on MRCLAM (standard library
only, none of locbench's code).

For one robot it takes the landmark observations of the second half of the span its odometry and
Vicon both cover (the held-out half of `locbench run noise/landmark_logs`) and the bearing each
should have had from the Vicon pose, and prints the mean bearing residual (observed − predicted,
raw: no fitted bias or scale) inside a stretch [FROM, TO] seconds from the half's start and
outside it, before and after, overall and per landmark. A constant bearing bias shifts every
number alike; a difference between the stretch and the rest is an error that moves.

usage: scripts/mrclam_bearing_block_check.py [FOLDER] [ROBOT FROM TO]
  FOLDER defaults to $LOCBENCH_DATA/mrclam/MRCLAM_Dataset6; ROBOT FROM TO to 3 130 210.
"""
import math
import os
import sys

from mrclam_raw import data_file, landmark_sightings, rows, wrap


def mean(v):
    return sum(v) / len(v) if v else float("nan")


def main(argv):
    folder = argv[1] if len(argv) > 1 and not argv[1].isdigit() else os.path.join(
        os.environ.get("LOCBENCH_DATA", "../shared/datasets"), "mrclam", "MRCLAM_Dataset6")
    rest = [a for a in argv[1:] if a != folder]
    robot, start, end = (int(rest[0]), float(rest[1]), float(rest[2])) if len(rest) >= 3 else (3, 130.0, 210.0)
    odometry_t = [r[0] for r in rows(data_file(folder, f"Robot{robot}_Odometry.dat"))]
    truth_t = [r[0] for r in rows(data_file(folder, f"Robot{robot}_Groundtruth.dat"))]
    t0, t1 = max(odometry_t[0], truth_t[0]), min(odometry_t[-1], truth_t[-1])
    mid = t0 + 0.5 * (t1 - t0)
    parts = {"before": [], "inside": [], "after": []}
    per_landmark = {}
    for t, rng, bearing, (x, y, th), (lx, ly) in landmark_sightings(folder, robot):
        if t < mid or t > t1:
            continue
        s = t - mid
        predicted = wrap(math.atan2(ly - y, lx - x) - th)
        e = wrap(bearing - predicted)
        part = "before" if s < start else "inside" if s < end else "after"
        parts[part].append(e)
        key = (round(lx, 3), round(ly, 3))
        per_landmark.setdefault(key, {"inside": [], "outside": [], "range": []})
        per_landmark[key]["inside" if part == "inside" else "outside"].append(e)
        if part == "inside":
            per_landmark[key]["range"].append(math.hypot(lx - x, ly - y))
    print(f"robot {robot}, held-out half from {mid:.1f} s; stretch +{start:g} … +{end:g} s")
    for name, v in parts.items():
        print(f"  {name:6} {len(v):5d} observations, mean bearing residual {1000 * mean(v):+6.1f} mrad")
    print("  per landmark (x, y): inside the stretch / outside [mrad], mean range inside [m]")
    for key, v in sorted(per_landmark.items()):
        if v["inside"]:
            print(f"    {key}: {1000 * mean(v['inside']):+6.1f} ({len(v['inside'])}) / "
                  f"{1000 * mean(v['outside']):+6.1f} ({len(v['outside'])}), {mean(v['range']):.2f} m")


if __name__ == "__main__":
    main(sys.argv)
