"""Reading St. Pere-format logs for the diagnostic scripts in tools/ (standard library only):
the rows of a log, the one log of a kind in a dataset, the MTi's vehicle yaw and the GPS track."""
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


def nmea_deg(value):
    """Degrees from an NMEA ddmm.mmmm field."""
    degrees = int(value / 100)
    return degrees + (value - 100 * degrees) / 60


def gps_track(dataset, tool):
    """The GPS fixes as (t, x East, y North) in metres from the first fix (a local tangent plane:
    within 0.1 % of the UTM grid msislab scores with over the St. Pere marina)."""
    fixes = [(float(r[0]), nmea_deg(float(r[1])), nmea_deg(float(r[2])))
             for r in rows(find_log(dataset, "_DGPS.log", tool))]
    if not fixes:
        fail(tool, f"{dataset}: no GPS fix in its _DGPS.log")
    lat0, lon0 = fixes[0][1], fixes[0][2]
    earth_m = 6378137.0
    return [(t, math.radians(lon - lon0) * math.cos(math.radians(lat0)) * earth_m,
             math.radians(lat - lat0) * earth_m) for t, lat, lon in fixes]
