#!/usr/bin/env python3
"""Independent check of the diagnosis's landmark channel on MRCLAM (standard library only).

Reads the raw RobotN_Measurement.dat.gz, RobotN_Groundtruth.dat.gz, Barcodes.dat.gz and
Landmark_Groundtruth.dat.gz of one MRCLAM dataset folder, none of locbench's code, and prints per
robot, for the observations of the 15 surveyed landmarks (subjects 6-20) with the Vicon pose
linearly interpolated at the observation time (heading on the shorter arc):
  - median and robust spread (1.4826 * MAD) of the range residual z_r - |m - p| [m] and of the
    bearing residual wrap(z_b - atan2(m - p) + theta) [rad];
  - an ordinary least-squares fit z_r = scale * rho + bias, on all observations and on those
    within 5 robust spreads of the median (outliers out);
  - the bearing bias (median; mean of the inliers);
  - the time offset (logged - true) minimising the inliers' bearing residual sum of squares over
    a grid of 5 ms in [-0.3, 0.3] s (the truth read at t - offset);
  - per landmark: count, median range and bearing residual.
Observations between Vicon samples more than 0.1 s apart are skipped (Vicon dropouts).

usage: scripts/mrclam_landmark_check.py [FOLDER] [ROBOT ...]
  FOLDER defaults to $LOCBENCH_DATA/mrclam/MRCLAM_Dataset6, robots to 1 2 3 4 5.
"""
import bisect
import math
import os
import statistics
import sys

from mrclam_raw import data_file, rows


def wrap(a):
    return (a + math.pi) % (2.0 * math.pi) - math.pi


def mad_sigma(v):
    m = statistics.median(v)
    return 1.4826 * statistics.median([abs(x - m) for x in v])


def ols(x, y):
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    sxx = sum((a - mx) ** 2 for a in x)
    sxy = sum((a - mx) * (b - my) for a, b in zip(x, y))
    scale = sxy / sxx
    return scale, my - scale * mx


class Truth:
    def __init__(self, path):
        r = list(rows(path))
        self.t = [a[0] for a in r]
        self.p = [(a[1], a[2], a[3]) for a in r]

    def at(self, t):
        k = bisect.bisect_left(self.t, t)
        if k == 0 or k == len(self.t):
            return None
        t0, t1 = self.t[k - 1], self.t[k]
        if t1 - t0 > 0.1:
            return None
        f = (t - t0) / (t1 - t0)
        (x0, y0, h0), (x1, y1, h1) = self.p[k - 1], self.p[k]
        return x0 + f * (x1 - x0), y0 + f * (y1 - y0), h0 + f * wrap(h1 - h0)


def residuals(obs, truth, marks, offset):
    out = []
    for t, subject, z_r, z_b in obs:
        p = truth.at(t - offset)
        if p is None:
            continue
        mx, my = marks[subject]
        rho = math.hypot(mx - p[0], my - p[1])
        phi = math.atan2(my - p[1], mx - p[0]) - p[2]
        out.append((subject, rho, z_r - rho, wrap(z_b - phi), z_r))
    return out


def check(folder, robot):
    subject_of = {int(b): int(s) for s, b in rows(data_file(folder, "Barcodes.dat"))}
    marks = {int(r[0]): (r[1], r[2]) for r in rows(data_file(folder, "Landmark_Groundtruth.dat"))}
    truth = Truth(data_file(folder, "Robot%d_Groundtruth.dat" % robot))
    obs, other = [], 0
    for t, barcode, z_r, z_b in rows(data_file(folder, "Robot%d_Measurement.dat" % robot)):
        s = subject_of.get(int(barcode))
        if s in marks:
            obs.append((t, s, z_r, z_b))
        else:
            other += 1
    res = residuals(obs, truth, marks, 0.0)
    rr = [x[2] for x in res]
    rb = [x[3] for x in res]
    med_r, sd_r = statistics.median(rr), mad_sigma(rr)
    med_b, sd_b = statistics.median(rb), mad_sigma(rb)
    inl = [x for x in res if abs(x[2] - med_r) <= 5 * sd_r and abs(x[3] - med_b) <= 5 * sd_b]
    scale_all, bias_all = ols([x[1] for x in res], [x[4] for x in res])
    scale_in, bias_in = ols([x[1] for x in inl], [x[4] for x in inl])

    def bearing_ss(offset):
        r = residuals(obs, truth, marks, offset)
        b = [x[3] for x in r if abs(x[2] - med_r) <= 5 * sd_r]
        m = statistics.median(b)
        s = mad_sigma(b)
        b = [x - m for x in b if abs(x - m) <= 5 * s]
        return sum(x * x for x in b) / len(b)

    grid = [k * 0.005 for k in range(-60, 61)]
    best = min(grid, key=bearing_ss)
    print("robot %d: %d landmark observations used, %d of other subjects left out, %d outside Vicon"
          % (robot, len(res), other, len(obs) - len(res)))
    print("  range   residual: median %+.4f m, robust sd %.4f m" % (med_r, sd_r))
    print("  bearing residual: median %+.5f rad, robust sd %.5f rad" % (med_b, sd_b))
    print("  least squares z_r = scale*rho + bias: all scale %.4f bias %+.4f m; inliers (%d) scale %.4f bias %+.4f m"
          % (scale_all, bias_all, len(inl), scale_in, bias_in))
    print("  bearing bias: median %+.5f rad, inlier mean %+.5f rad" % (med_b, statistics.fmean([x[3] for x in inl])))
    print("  time offset minimising the inlier bearing residuals: %+.3f s" % best)
    print("  per landmark: id n median_range_m median_bearing_rad")
    for s in sorted(marks):
        r = [x for x in res if x[0] == s]
        if r:
            print("    %2d %4d %+.4f %+.5f" % (s, len(r), statistics.median([x[2] for x in r]),
                                            statistics.median([x[3] for x in r])))


def main():
    args = sys.argv[1:]
    folder = args[0] if args else os.path.join(os.environ.get("LOCBENCH_DATA", "../shared/datasets"),
                                               "mrclam", "MRCLAM_Dataset6")
    robots = [int(a) for a in args[1:]] or [1, 2, 3, 4, 5]
    for robot in robots:
        check(folder, robot)


if __name__ == "__main__":
    main()
