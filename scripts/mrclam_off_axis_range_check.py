#!/usr/bin/env python3
"""Independent check of the landmark channel's `landmark_range_off_axis_scale` on MRCLAM
(standard library only, none of locbench's code).

For each robot it reads the raw RobotN_Measurement and RobotN_Groundtruth files, Barcodes and
Landmark_Groundtruth, takes every observation of a surveyed landmark inside the Vicon record, and
computes the true range rho and bearing phi from the Vicon pose interpolated at the observation
time. It prints two things computed another way than the channel's likelihood fit:
  1. the median relative range error (z_r - rho) / rho in bins of 0.1 rad of phi (no model);
  2. a least-squares fit (once more without the observations beyond 3 robust sigmas) of z_r - rho = (s - 1 + k1*phi + k2*phi^2)*rho + b over the
     observations within 1 m of the truth, with the robust spread (1.4826 * MAD) of what is left,
     beside the same fit without k1, k2.
A range scale that changes off the camera's axis shows as bins that fall away from phi = 0 and
as a spread that shrinks when k1, k2 are fitted.

usage: scripts/mrclam_off_axis_range_check.py [FOLDER] [ROBOT ...]
  FOLDER defaults to $LOCBENCH_DATA/mrclam/MRCLAM_Dataset6, robots to 1 2 3 4 5.
"""
import math
import os
import statistics
import sys

from mrclam_raw import landmark_sightings, wrap


def robust_sigma(v):
    m = statistics.median(v)
    return 1.4826 * statistics.median([abs(x - m) for x in v])


def least_squares(columns, y):
    """The coefficients c minimising |sum_j c_j * columns[j] - y|^2 (normal equations, Gauss-Jordan)."""
    n = len(columns)
    a = [[sum(p * q for p, q in zip(columns[i], columns[j])) for j in range(n)]
         + [sum(p * q for p, q in zip(columns[i], y))] for i in range(n)]
    for c in range(n):
        pivot = max(range(c, n), key=lambda r: abs(a[r][c]))
        a[c], a[pivot] = a[pivot], a[c]
        for r in range(n):
            if r != c:
                f = a[r][c] / a[c][c]
                a[r] = [u - f * v for u, v in zip(a[r], a[c])]
    return [a[i][n] / a[i][i] for i in range(n)]


def fit(columns, y):
    """Least squares, then again on the observations within 3 robust sigmas of the first fit
    (misread barcodes are far off); the coefficients and the robust spread left."""
    keep = list(range(len(y)))
    for _ in range(2):
        c = least_squares([[col[i] for i in keep] for col in columns], [y[i] for i in keep])
        left = [v - sum(ci * col[i] for ci, col in zip(c, columns)) for i, v in enumerate(y)]
        spread = robust_sigma(left)
        keep = [i for i, v in enumerate(left) if abs(v) <= 3.0 * spread]
    return c, spread


def observations(folder, robot):
    out = []
    for _, z, _, (x, y, theta), (lx, ly) in landmark_sightings(folder, robot):
        out.append((math.hypot(lx - x, ly - y), wrap(math.atan2(ly - y, lx - x) - theta), z))
    return out


def main():
    data = os.environ.get("LOCBENCH_DATA", "../shared/datasets")
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(data, "mrclam", "MRCLAM_Dataset6")
    robots = [int(r) for r in sys.argv[2:]] or [1, 2, 3, 4, 5]
    for robot in robots:
        seen = observations(folder, robot)
        bins = {}
        for rho, phi, z in seen:
            bins.setdefault(round(phi / 0.1), []).append((z - rho) / rho)
        print(f"robot {robot}: {len(seen)} observations; median (z_r - rho)/rho per bin of bearing [rad]:")
        print("  " + "  ".join(f"{k / 10:+.1f}: {statistics.median(v):+.3f}" for k, v in sorted(bins.items())
                               if len(v) >= 20))
        near = [(rho, phi, z) for rho, phi, z in seen if abs(z - rho) <= 1.0]
        y = [z - rho for rho, _, z in near]
        rho_col = [rho for rho, _, _ in near]
        one = [1.0] * len(near)
        (s0, b0), spread0 = fit([rho_col, one], y)
        (s, k1, k2, b), spread = fit([rho_col, [rho * phi for rho, phi, _ in near],
                                      [rho * phi * phi for rho, phi, _ in near], one], y)
        print(f"  least squares on {len(near)} within 1 m: scale {1 + s0:.4f}, bias {b0:+.3f} m: spread {spread0:.3f} m"
              f" | scale {1 + s:.4f}, k1 {k1:+.3f}/rad, k2 {k2:+.3f}/rad^2, bias {b:+.3f} m: spread {spread:.3f} m")


if __name__ == "__main__":
    main()
