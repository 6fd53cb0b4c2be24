"""The raw MRCLAM files as the independent checks in scripts/ read them (standard library only,
none of locbench's code)."""
import bisect
import gzip
import math
import os
import sys


def rows(path):
    """The numbers of each line of a whitespace-separated file (.gz or plain), skipping blank
    lines and # comments."""
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as f:
        for line in f:
            s = line.strip()
            if s and not s.startswith("#"):
                yield [float(x) for x in s.split()]


def data_file(folder, name):
    """folder/name, or folder/name.gz; exits naming the file when neither exists."""
    for candidate in (name, name + ".gz"):
        path = os.path.join(folder, candidate)
        if os.path.exists(path):
            return path
    sys.exit(f"{folder}: no {name}[.gz]")


def wrap(a):
    """The angle a [rad] in [-pi, pi]."""
    return math.atan2(math.sin(a), math.cos(a))


def truth_at(truth, truth_t, t):
    """The Groundtruth pose (x, y, theta) linearly interpolated at time t, or None outside the
    record; truth_t = [p[0] for p in truth]."""
    i = bisect.bisect_left(truth_t, t)
    if i <= 0 or i >= len(truth):
        return None
    a, b = truth[i - 1], truth[i]
    f = (t - a[0]) / (b[0] - a[0])
    return a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]), a[3] + f * wrap(b[3] - a[3])


def landmark_sightings(folder, robot):
    """Each observation of a surveyed landmark inside the Vicon record of robot `robot`, as
    (t, range, bearing, truth pose (x, y, theta), landmark position (lx, ly))."""
    landmarks = {int(r[0]): (r[1], r[2]) for r in rows(data_file(folder, "Landmark_Groundtruth.dat"))}
    subject = {int(r[1]): int(r[0]) for r in rows(data_file(folder, "Barcodes.dat"))}
    truth = list(rows(data_file(folder, f"Robot{robot}_Groundtruth.dat")))
    truth_t = [p[0] for p in truth]
    for r in rows(data_file(folder, f"Robot{robot}_Measurement.dat")):
        s = subject.get(int(r[1]))
        if s not in landmarks:
            continue
        pose = truth_at(truth, truth_t, r[0])
        if pose is not None:
            yield r[0], r[2], r[3], pose, landmarks[s]
