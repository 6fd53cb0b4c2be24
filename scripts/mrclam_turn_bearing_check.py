#!/usr/bin/env python3
"""Independent check of the landmark channel's `landmark_turn_dependent_bearing_noise` on MRCLAM
(standard library only, none of locbench's code).

For each robot it reads the raw RobotN_Measurement, RobotN_Groundtruth and RobotN_Odometry files,
Barcodes and Landmark_Groundtruth, takes every observation of a surveyed landmark inside the Vicon
record, computes the range and bearing residuals against the Vicon pose interpolated at the
observation time, and splits the observations into quartiles of the odometry's |turn rate| (the
last odometry record before the observation). It prints, per quartile, the median |ω| and the
robust spread (1.4826 * MAD) of the bearing and range residuals. Bearing noise that grows with
the turn rate shows as a larger bearing spread in the top quartile.

usage: scripts/mrclam_turn_bearing_check.py [FOLDER] [ROBOT ...]
  FOLDER defaults to $LOCBENCH_DATA/mrclam/MRCLAM_Dataset6, robots to 1 2 3 4 5.
"""
import bisect
import math
import os
import statistics
import sys

from mrclam_raw import data_file, landmark_sightings, rows, wrap


def robust_sigma(v):
    m = statistics.median(v)
    return 1.4826 * statistics.median([abs(x - m) for x in v])


def main():
    data = os.environ.get("LOCBENCH_DATA", "../shared/datasets")
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(data, "mrclam", "MRCLAM_Dataset6")
    robots = [int(r) for r in sys.argv[2:]] or [1, 2, 3, 4, 5]
    for robot in robots:
        odometry = list(rows(data_file(folder, f"Robot{robot}_Odometry.dat")))
        odometry_t = [o[0] for o in odometry]
        seen = []
        for t, z_range, z_bearing, (x, y, theta), (lx, ly) in landmark_sightings(folder, robot):
            j = bisect.bisect_left(odometry_t, t)
            if j <= 0:
                continue
            rho = math.hypot(lx - x, ly - y)
            bearing = wrap(z_bearing - wrap(math.atan2(ly - y, lx - x) - theta))
            seen.append((abs(odometry[j - 1][2]), bearing, z_range - rho))
        seen.sort(key=lambda p: p[0])  # by |ω| only (ties keep time order)
        n = len(seen)
        print(f"robot {robot}: {n} observations; per quartile of |turn rate|: median |ω| [rad/s], "
              "bearing σ [rad], range σ [m]")
        for q in range(4):
            part = seen[q * n // 4:(q + 1) * n // 4]
            print(f"  Q{q + 1}: |ω| {part[len(part) // 2][0]:.2f}  bearing σ {robust_sigma([p[1] for p in part]):.4f}"
                  f"  range σ {robust_sigma([p[2] for p in part]):.3f}")


if __name__ == "__main__":
    main()
