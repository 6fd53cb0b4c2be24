"""The raw MRCLAM files as the independent checks in scripts/ read them (standard library only,
none of locbench's code)."""
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
