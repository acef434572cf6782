"""Reading St. Pere-format logs for the diagnostic scripts in tools/ (standard library only):
the rows of a log, the one log of a kind in a dataset, and the MTi's vehicle yaw."""
import glob
import math
import os
import sys


def rows(path):
    """The whitespace-split fields of every data row (header lines start with %)."""
    with open(path, encoding="latin-1") as f:
        for line in f:
            if line.startswith("%") or not line.strip():
                continue
            yield line.split()


def fail(tool, what):
    """One line on stderr, exit status 2 (bad input, as every msislab command)."""
    print(f"{tool}: {what}", file=sys.stderr)
    sys.exit(2)


def find_log(dataset, suffix, tool):
    """The dataset's one file ending in suffix; fails naming the folder otherwise."""
    found = glob.glob(os.path.join(dataset, "*" + suffix))
    if len(found) != 1:
        fail(tool, f"{dataset}: expected one *{suffix}, found {len(found)}")
    return found[0]


def vehicle_yaw_rad(yaw_mti_deg, yaw_offset_deg):
    """Vehicle yaw, counter-clockwise from East, from an MTi reading (docs/formats.md)."""
    return math.pi / 2 - math.radians(yaw_mti_deg - yaw_offset_deg)
