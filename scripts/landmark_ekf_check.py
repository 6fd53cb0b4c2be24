#!/usr/bin/env python3
"""Independent check of noise/landmark_logs' fixed-Q EKF on MRCLAM (standard library only; none
of locbench's code). For each robot it reads the raw Dataset 6 files, takes the same span (odometry
and Vicon overlap), halves it, measures the nominal sensor noise on the first half (1.4826·MAD of
the range and bearing residuals against Vicon), and runs a plain EKF on the second half from the
Vicon pose at its start: unicycle prediction on the logged (v, ω) held over each record interval
(midpoint rule), Q = fixed_q_per_s · process_scale · dt, range-bearing updates (Probabilistic
Robotics Table 7.2) with R = diag(σ_r², σ_φ²) · R scale, a χ²₂(0.999) gate and an ungated update
after 10 consecutive rejections. The Q and R scales are the ones the report says fixed_q was tuned
to, so the two held-out RMSEs should agree up to the differences in stepping (locbench merges the
67 Hz records into ≥ 0.08 s steps and cuts them at the observations).

usage: landmark_ekf_check.py REPORT.json [DATA_ROOT]
"""
import bisect
import json
import math
import statistics
import sys

from mrclam_raw import rows, wrap

GATE = 13.815510557964274  # χ²₂(0.999)


class Truth:
    def __init__(self, poses):
        self.p = poses
        self.t = [q[0] for q in poses]

    def at(self, t):
        i = bisect.bisect_left(self.t, t)
        if i <= 0 or i >= len(self.t):
            return None
        a, b = self.p[i - 1], self.p[i]
        f = (t - a[0]) / (b[0] - a[0])
        return (a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]), a[3] + f * wrap(b[3] - a[3]))


def mad_sigma(v):
    m = statistics.median(v)
    return 1.4826 * statistics.median([abs(x - m) for x in v])


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(len(b))) for j in range(len(b[0]))] for i in range(len(a))]


def transpose(a):
    return [list(r) for r in zip(*a)]


def nees3(e, P):
    """e' P^-1 e for a 3-vector and a symmetric 3x3 matrix (cofactor inverse)."""
    a, b, c = P[0]
    d, f, g = P[1]
    h, i, j = P[2]
    A, B, C = f * j - g * i, -(d * j - g * h), d * i - f * h
    det = a * A + b * B + c * C
    inv = [[A, -(b * j - c * i), b * g - c * f], [B, a * j - c * h, -(a * g - c * d)], [C, -(a * i - b * h), a * f - b * d]]
    return sum(e[r] * inv[r][k] * e[k] for r in range(3) for k in range(3)) / det


def check_robot(root, robot, q_per_s, q_scale, r_scale):
    d = root + "/mrclam/MRCLAM_Dataset6/"
    landmarks = {int(r[0]): (r[1], r[2]) for r in rows(d + "Landmark_Groundtruth.dat.gz")}
    subject = {int(r[1]): int(r[0]) for r in rows(d + "Barcodes.dat.gz")}
    odo = list(rows(d + f"Robot{robot}_Odometry.dat.gz"))
    truth = Truth(list(rows(d + f"Robot{robot}_Groundtruth.dat.gz")))
    obs = [(m[0], subject.get(int(m[1])), m[2], m[3]) for m in rows(d + f"Robot{robot}_Measurement.dat.gz")]
    obs = [o for o in obs if o[1] in landmarks]
    t0 = max(odo[0][0], truth.t[0])
    t1 = min(odo[-1][0], truth.t[-1])
    mid = t0 + 0.5 * (t1 - t0)
    # Nominal sensor noise on the first half.
    rr, bb = [], []
    for t, s, r, b in obs:
        if not (t0 <= t <= mid):
            continue
        p = truth.at(t)
        if p is None:
            continue
        dx, dy = landmarks[s][0] - p[0], landmarks[s][1] - p[1]
        rr.append(r - math.hypot(dx, dy))
        bb.append(wrap(b - (math.atan2(dy, dx) - p[2])))
    sr, sb = mad_sigma(rr), mad_sigma(bb)
    # Held-out half.
    x = list(truth.at(mid))
    P = [[0.02**2 if i == j else 0.0 for j in range(3)] for i in range(3)]
    events = [(o[0], 1, o) for o in obs if mid <= o[0] <= t1] + [(r[0], 0, r) for r in odo if mid <= r[0] <= t1]
    events.sort(key=lambda e: (e[0], e[1]))
    v = w = 0.0
    k = bisect.bisect_right([r[0] for r in odo], mid) - 1
    if k >= 0:
        v, w = odo[k][1], odo[k][2]
    t = mid
    sq, n, gated, used, starving, nees = 0.0, 0, 0, 0, 0, 0.0
    for te, kind, e in events:
        dt = te - t
        if dt > 0:
            th = x[2] + 0.5 * w * dt
            x = [x[0] + v * dt * math.cos(th), x[1] + v * dt * math.sin(th), wrap(x[2] + w * dt)]
            F = [[1, 0, -v * dt * math.sin(th)], [0, 1, v * dt * math.cos(th)], [0, 0, 1]]
            P = mat_mul(mat_mul(F, P), transpose(F))
            for i in range(3):
                P[i][i] += q_per_s[i] * q_scale * dt
            t = te
        if kind == 0:
            v, w = e[1], e[2]
        else:
            lx, ly = landmarks[e[1]]
            dx, dy = lx - x[0], ly - x[1]
            q = dx * dx + dy * dy
            rq = math.sqrt(q)
            H = [[-dx / rq, -dy / rq, 0.0], [dy / q, -dx / q, -1.0]]
            nu = [e[2] - rq, wrap(e[3] - (math.atan2(dy, dx) - x[2]))]
            S = mat_mul(mat_mul(H, P), transpose(H))
            S[0][0] += sr * sr * r_scale
            S[1][1] += sb * sb * r_scale
            det = S[0][0] * S[1][1] - S[0][1] * S[1][0]
            Si = [[S[1][1] / det, -S[0][1] / det], [-S[1][0] / det, S[0][0] / det]]
            nis = sum(nu[i] * Si[i][j] * nu[j] for i in range(2) for j in range(2))
            if nis > GATE and starving < 10:
                gated += 1
                starving += 1
            else:
                starving = 0
                used += 1
                K = mat_mul(mat_mul(P, transpose(H)), Si)
                x = [x[i] + K[i][0] * nu[0] + K[i][1] * nu[1] for i in range(3)]
                x[2] = wrap(x[2])
                KH = mat_mul(K, H)
                P = mat_mul([[(1.0 if i == j else 0.0) - KH[i][j] for j in range(3)] for i in range(3)], P)
                P = [[0.5 * (P[i][j] + P[j][i]) for j in range(3)] for i in range(3)]
        p = truth.at(t)
        if p is not None:
            sq += (p[0] - x[0]) ** 2 + (p[1] - x[1]) ** 2
            nees += nees3([p[0] - x[0], p[1] - x[1], wrap(p[2] - x[2])], P)
            n += 1
    return math.sqrt(sq / n), nees / n, sr, sb, gated / max(1, gated + used)


def main():
    report = json.load(open(sys.argv[1]))
    root = sys.argv[2] if len(sys.argv) > 2 else "../shared/datasets"
    q_per_s = report["configuration"]["fixed_q_per_s"]
    res = {r["name"]: r for r in report["results"]}
    print("| robot | locbench fixed_q held-out RMSE [m], NEES | this check [m], NEES | check σ_r [m], σ_φ [rad] | check gated |")
    print("|---|---|---|---|---|")
    for d in sorted({r["dataset"] for r in report["results"]}):
        if not d.startswith("mrclam6_robot"):
            continue
        robot = int(d[-1])
        q = res[f"fixed_q/{d}/tuned_process_scale"]["mean"]
        rs = res[f"fixed_q/{d}/tuned_second_knob"]["mean"]
        ours = res[f"fixed_q/{d}/heldout_position_rmse"]["mean"]
        our_nees = res[f"fixed_q/{d}/heldout_nees_time_average"]["mean"]
        rmse, nees, sr, sb, g = check_robot(root, robot, q_per_s, q, rs)
        print(f"| {robot} | {ours:.3f}, {our_nees:.2f} | {rmse:.3f}, {nees:.2f} | {sr:.3f}, {sb:.4f} | {100 * g:.0f}% |")


if __name__ == "__main__":
    main()
