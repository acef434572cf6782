#!/usr/bin/env python3
"""How a SLAM run's consecutive spIC matches move the vehicle against the truth, segment by
segment: their length and their direction (docs/trajectory_slam.md, "Where the real canal is
lost").

For every accepted match of a scan against the one before it (matches.csv; with --gap N, against
the scan N before it), the true displacement
between the two scans' times (the simulation's positions, or the GPS; pairs under 1 m apart or
across a truth gap over 5 s left out) is put in the reference scan's frame by the run's own yaw of
that scan (scans.csv), as metrics.json's `consecutive_match_scale` does. Per window (the whole run,
then each of metrics.json's segment windows, seconds from the first truth stamp) it prints:
  scale       sum of the spIC translation projected on the true one over the true lengths (1 is
              unbiased; the whole run's is metrics.json's consecutive_match_scale);
  direction   the spIC translation's direction minus the true one's, deg, mean and standard error
              (positive: anticlockwise, to the vehicle's left);
and the same two for the filter's prediction of the match (pred_*: the dead-reckoning motion for
a step's first match), then spIC's direction against the prediction's, which needs no truth.
Standard library only. Usage:
  tools/match_direction_check.py RUN_DIR [--dataset DIR] [--gap N]
"""
import argparse
import bisect
import csv
import json
import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ left beside the tools

from stpere_logs import fail, gps_track

TOOL = "match_direction_check"
MIN_DISPLACEMENT_M = 1.0
MAX_FIX_GAP_S = 5.0


def read_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail(TOOL, f"{path}: {e.strerror if isinstance(e, OSError) else e}")


def read_csv(path, columns):
    """The rows of a CSV file with their line numbers; fails naming the file when it is missing
    a column or cannot be read."""
    try:
        with open(path, encoding="utf-8", newline="") as f:
            reader = csv.DictReader(f)
            missing = [c for c in columns if c not in (reader.fieldnames or [])]
            if missing:
                fail(TOOL, f"{path}: no column {missing[0]}")
            return list(enumerate(reader, start=2))
    except OSError as e:
        fail(TOOL, f"{path}: {e.strerror}")


def number(path, line, row, column):
    try:
        value = float(row[column])
    except (TypeError, ValueError):
        fail(TOOL, f"{path}:{line}: {column} is not a number")
    if not math.isfinite(value):
        fail(TOOL, f"{path}:{line}: {column} is not finite")
    return value


def simulation_track(dataset):
    """The simulation's positions (t, x, y) from truth/trajectory.tum."""
    path = os.path.join(dataset, "truth", "trajectory.tum")
    track = []
    try:
        with open(path, encoding="utf-8") as f:
            for line_number, line in enumerate(f, start=1):
                if line.startswith("#") or not line.strip():
                    continue
                fields = line.split()
                try:
                    track.append((float(fields[0]), float(fields[1]), float(fields[2])))
                except (IndexError, ValueError):
                    fail(TOOL, f"{path}:{line_number}: not a TUM pose")
    except OSError as e:
        fail(TOOL, f"{path}: {e.strerror}")
    if not track:
        fail(TOOL, f"{path}: no pose")
    return track


def position_at(track, times, t):
    """The track's position at t, linear between the fixes around it; None outside the track or
    across a gap over MAX_FIX_GAP_S."""
    i = bisect.bisect_left(times, t)
    if i < len(times) and times[i] == t:
        return track[i][1], track[i][2]
    if i == 0 or i == len(times):
        return None
    (t0, x0, y0), (t1, x1, y1) = track[i - 1], track[i]
    if t1 - t0 > MAX_FIX_GAP_S:
        return None
    w = (t - t0) / (t1 - t0)
    return x0 + w * (x1 - x0), y0 + w * (y1 - y0)


def wrapped_deg(angle_rad):
    return math.degrees(math.atan2(math.sin(angle_rad), math.cos(angle_rad)))


def mean_se(values):
    n = len(values)
    mean = sum(values) / n
    if n < 2:
        return mean, float("nan")
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    return mean, sd / math.sqrt(n)


def summary(pairs):
    """The window's figures from its (spIC, prediction, truth) translations."""
    true_m = sum(math.hypot(*g) for _, _, g in pairs)
    out = []
    for which in (0, 1):
        along = sum((v[which][0] * v[2][0] + v[which][1] * v[2][1]) / math.hypot(*v[2])
                    for v in pairs)
        angles = [wrapped_deg(math.atan2(v[which][1], v[which][0]) - math.atan2(v[2][1], v[2][0]))
                  for v in pairs]
        out.append((along / true_m, *mean_se(angles)))
    against = [wrapped_deg(math.atan2(z[1], z[0]) - math.atan2(p[1], p[0])) for z, p, _ in pairs]
    return out, mean_se(against)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run", help="a SLAM run's output folder (matches.csv, scans.csv, metrics.json)")
    ap.add_argument("--dataset", help="the dataset it ran on (default: metrics.json's)")
    ap.add_argument("--gap", type=int, default=1,
                    help="match scan k against scan k - GAP (default 1: consecutive scans)")
    o = ap.parse_args()
    if o.gap < 1:
        fail(TOOL, f"--gap {o.gap}: must be at least 1")

    metrics = read_json(os.path.join(o.run, "metrics.json"))
    dataset = o.dataset or metrics.get("dataset")
    truth = metrics.get("truth")
    if not dataset:
        fail(TOOL, f"{os.path.join(o.run, 'metrics.json')}: no dataset; give --dataset")
    if truth == "simulation":
        track = simulation_track(dataset)
    elif truth == "gps":
        track = gps_track(dataset, TOOL)
    else:
        fail(TOOL, f"{os.path.join(o.run, 'metrics.json')}: truth '{truth}' is neither "
                   "'simulation' nor 'gps'")
    times = [p[0] for p in track]
    windows = [("whole run", None)] + [(name, w) for name, w in
                                       (metrics.get("segment_windows") or {}).items()]

    scans_path = os.path.join(o.run, "scans.csv")
    yaw_by_time = {}
    for line, row in read_csv(scans_path, ["t_s", "yaw_rad"]):
        yaw_by_time[round(number(scans_path, line, row, "t_s"), 6)] = \
            number(scans_path, line, row, "yaw_rad")

    matches_path = os.path.join(o.run, "matches.csv")
    columns = ["t_s", "scan", "reference", "t_reference_s", "outcome", "z_x_m", "z_y_m",
               "pred_x_m", "pred_y_m"]
    pairs = []  # (t from the first truth stamp, spIC translation, prediction, truth)
    for line, row in read_csv(matches_path, columns):
        if row["outcome"] != "accepted":
            continue
        if number(matches_path, line, row, "scan") != number(matches_path, line, row,
                                                               "reference") + o.gap:
            continue
        t_s = number(matches_path, line, row, "t_s")
        t_reference_s = number(matches_path, line, row, "t_reference_s")
        yaw = yaw_by_time.get(round(t_reference_s, 6))
        if yaw is None:
            fail(TOOL, f"{matches_path}:{line}: no scan at t_reference_s {t_reference_s} in "
                       f"{scans_path}")
        a, b = position_at(track, times, t_reference_s), position_at(track, times, t_s)
        if a is None or b is None:
            continue
        dx, dy = b[0] - a[0], b[1] - a[1]
        if math.hypot(dx, dy) < MIN_DISPLACEMENT_M:
            continue
        c, s = math.cos(yaw), math.sin(yaw)
        g = (c * dx + s * dy, -s * dx + c * dy)
        z = (number(matches_path, line, row, "z_x_m"), number(matches_path, line, row, "z_y_m"))
        p = (number(matches_path, line, row, "pred_x_m"),
             number(matches_path, line, row, "pred_y_m"))
        pairs.append((t_s - times[0], z, p, g))

    which = "consecutive matches" if o.gap == 1 else f"matches of scan k against k - {o.gap}"
    print(f"{o.run}: accepted {which} against the {truth} truth "
          "(direction: deg anticlockwise of the truth's, mean (standard error))")
    for name, window in windows:
        chosen = [v[1:] for v in pairs if window is None or window[0] <= v[0] < window[1]]
        if not chosen:
            print(f"{name}: no match")
            continue
        ((z_scale, z_dir, z_se), (p_scale, p_dir, p_se)), (against, against_se) = summary(chosen)
        print(f"{name}: {len(chosen)} matches; spIC scale {z_scale:.3f} direction {z_dir:+.2f} "
              f"({z_se:.2f}); prediction scale {p_scale:.3f} direction {p_dir:+.2f} ({p_se:.2f}); "
              f"spIC against the prediction {against:+.2f} ({against_se:.2f}) deg")


if __name__ == "__main__":
    main()
