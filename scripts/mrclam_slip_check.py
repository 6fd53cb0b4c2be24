#!/usr/bin/env python3
"""Independent check of where a landmark filter's held-out NEES comes from on MRCLAM: wheel slip
(standard library only, none of locbench's code).

For each robot it reads the raw RobotN_Odometry and RobotN_Groundtruth files and cuts the second
half of the span both cover (the held-out half of `locbench run noise/landmark_logs`) into 5 s
windows. Per window it integrates the odometry's commanded velocities (the last record before
each instant, as logged) and compares them with Vicon: the turn (odometry ∫ω dt against Vicon's
change of heading) and, in windows that turn less than 0.3 rad (where the straight-line
displacement is close to the path), the distance (∫|v| dt against Vicon's displacement). It
prints the windows where the two disagree by more than the thresholds, with their time from the
half's start — slip or a stall — and the largest disagreement in heading over 40 s.

usage: scripts/mrclam_slip_check.py [FOLDER] [ROBOT ...]
  FOLDER defaults to $LOCBENCH_DATA/mrclam/MRCLAM_Dataset6, robots to 1 2 3 4 5.
"""
import math
import os
import sys

from mrclam_raw import data_file, rows, truth_at, wrap

WINDOW_S = 5.0
TURN_THRESHOLD_RAD = 0.15
DISTANCE_THRESHOLD_M = 0.08
LONG_S = 40.0
STRAIGHT_RAD = 0.3


def odometry_integral(odometry, t0, t1):
    """(∫ω dt, ∫|v| dt) over [t0, t1) of the records (t, v, ω), each held until the next."""
    turn = distance = 0.0
    for i in range(len(odometry) - 1):
        a, b = odometry[i][0], odometry[i + 1][0]
        lo, hi = max(a, t0), min(b, t1)
        if hi > lo:
            turn += odometry[i][2] * (hi - lo)
            distance += abs(odometry[i][1]) * (hi - lo)
    return turn, distance


def main():
    args = sys.argv[1:]
    folder = args[0] if args and not args[0].isdigit() else os.path.join(
        os.environ.get("LOCBENCH_DATA", "../shared/datasets"), "mrclam", "MRCLAM_Dataset6")
    robots = [int(a) for a in args if a.isdigit()] or [1, 2, 3, 4, 5]
    for robot in robots:
        truth = list(rows(data_file(folder, f"Robot{robot}_Groundtruth.dat")))
        odometry = list(rows(data_file(folder, f"Robot{robot}_Odometry.dat")))
        truth_t = [p[0] for p in truth]
        start = max(truth[0][0], odometry[0][0])
        end = min(truth[-1][0], odometry[-1][0])
        mid = start + 0.5 * (end - start)
        windows = []
        t = mid
        while t + WINDOW_S <= end:
            a, b = truth_at(truth, truth_t, t), truth_at(truth, truth_t, t + WINDOW_S)
            if a is not None and b is not None:
                turn, distance = odometry_integral(odometry, t, t + WINDOW_S)
                windows.append((t - mid, turn, wrap(b[2] - a[2]), distance, math.hypot(b[0] - a[0], b[1] - a[1])))
            t += WINDOW_S
        print(f"robot {robot}: held-out half {end - mid:.0f} s, {len(windows)} windows of {WINDOW_S:g} s")
        for since, turn, vicon_turn, distance, vicon_distance in windows:
            straight = abs(vicon_turn) < STRAIGHT_RAD
            if abs(turn - vicon_turn) > TURN_THRESHOLD_RAD or (straight and
                                                              abs(distance - vicon_distance) > DISTANCE_THRESHOLD_M):
                print(f"  +{since:5.0f} s  turn odometry {turn:+.3f} rad, Vicon {vicon_turn:+.3f} rad | "
                      f"distance odometry {distance:.3f} m, Vicon ≥ {vicon_distance:.3f} m")
        per_long = int(LONG_S / WINDOW_S)
        worst = max(((sum(w[1] - w[2] for w in windows[i:i + per_long]), windows[i][0])
                     for i in range(max(1, len(windows) - per_long + 1))), key=lambda x: abs(x[0]))
        print(f"  largest heading disagreement over {LONG_S:g} s: {worst[0]:+.3f} rad (odometry − Vicon) "
              f"from +{worst[1]:.0f} s")


if __name__ == "__main__":
    main()
