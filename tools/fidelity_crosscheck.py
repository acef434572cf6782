#!/usr/bin/env python3
"""The sonar rows of `msislab fidelity` recomputed apart from msislab's C++, from a dataset's
*_detections.csv[.gz] and *_IS_timestamps.log (and *_SETUP.log, msislab's default setup when
absent), so a test can hold fidelity.json against a second implementation
(tests/app/fidelity_crosscheck_test.cpp).

Prints JSON keyed by fidelity.json's row keys (the `key` of its `rows`), each row
{"real": x} for one dataset, {"real": x, "sim": y} for two, with "ks" on the two median rows
that carry a KS distance; null where a value is undefined (an empty sample). Rows:
  Per beam: empty_beams_percent, bins_per_beam_mean, bins_per_beam_p90, runs_per_beam_mean,
    multi_run_beams_percent, first_range_{p10,median,p90}_m
  Detected range by 10 m band: detected_range_{p10,median,p90}_m,
    detected_bins_A_B_m_percent and first_ranges_A_B_m_percent for every 10 m band
  Sonar rotation: beams_per_revolution, revolution_period_s
Not here: the echo extent by incidence, the points per scan (they need the project's
segmentation) and the navigation rows.

Where each definition comes from (docs/fidelity.md, "How each statistic is computed", and
docs/formats.md, "Dataset directory" and "Fidelity report"):
- counted beams: every beam of the keyframes from the first to the last in the file,
  360 deg / step_rad of *_SETUP.log (rounded) per keyframe; empty: counted minus the beams
  with rows (docs/fidelity.md, "Counted beams").
- detected bins per beam: a beam's rows, over all counted beams with the empty ones as 0.
- runs: bin = range / bin_m rounded, half away from zero (the docs say "rounded"; the half
  rule is the C++'s std::lround); a bin detected twice is one bin (eval/sonar_statistics.hpp,
  count_runs); a gap of one missing bin or more starts a run. Beams with 2+ runs are a share of
  the counted beams.
- quantiles: linear between order statistics at position (n - 1) p (docs/fidelity.md, "First
  detected range"), which is statistics.quantiles(method="inclusive").
- KS: sup |F_a(x) - F_b(x)| of the two empirical distribution functions.
- bands: [0, 10), [10, 20), ... m, as many as cover the sonar range (ceil(range / 10),
  report/fidelity_table.cpp), the last one including the range; shares of the whole sample.
- rotation (docs/fidelity.md, "Beams per revolution"): for every angle_idx with a beam in
  keyframes k and k + 1, its first beam in each (which beam pairs when a keyframe holds one
  angle twice is the C++'s choice, eval/sonar_statistics.cpp, add_rotation): the beam rows
  between them and their time difference in *_IS_timestamps.log; the medians.
Standard library only. Bad input: one line naming the file and place, exit status 2.
Usage: tools/fidelity_crosscheck.py REAL_DATASET [SIM_DATASET]
"""
import bisect
import collections
import glob
import gzip
import json
import math
import os
import statistics
import sys

sys.dont_write_bytecode = True  # no __pycache__ left beside the tools

from stpere_logs import fail, find_log, rows

TOOL = "fidelity_crosscheck"
BAND_M = 10.0
HEADER = ["keyframe", "beam_row", "t_log_s", "sensor_time_ms", "angle_idx", "angle_rad",
          "range_m"]
DEFAULT_SETUP = (50.0, 0.1, math.pi / 100)  # msislab's SonarSetup defaults (St. Pere)


def number(text, where):
    try:
        value = float(text)
    except ValueError:
        fail(TOOL, f"{where}: '{text}' is not a number")
    if not math.isfinite(value):
        fail(TOOL, f"{where}: '{text}' is not finite")
    return value


def integer(text, where):
    try:
        return int(text)
    except ValueError:
        fail(TOOL, f"{where}: '{text}' is not an integer")


def read_setup(dataset):
    """(range_m, bin_m, step_rad) of *_SETUP.log: one row of three numbers."""
    found = glob.glob(os.path.join(dataset, "*_SETUP.log"))
    if not found:
        return DEFAULT_SETUP
    path = find_log(dataset, "_SETUP.log", TOOL)
    data = list(rows(path))
    if len(data) != 1 or len(data[0]) != 3:
        fail(TOOL, f"{path}: expected one row 'range_m bin_m step_rad'")
    setup = tuple(number(x, path) for x in data[0])
    if min(setup) <= 0:
        fail(TOOL, f"{path}: range_m, bin_m and step_rad must be positive")
    return setup


def read_beam_times(dataset):
    """The log time of every beam row of *_IS_timestamps.log."""
    path = find_log(dataset, "_IS_timestamps.log", TOOL)
    times = []
    for i, fields in enumerate(rows(path)):
        if len(fields) != 2:
            fail(TOOL, f"{path}: data row {i + 1}: expected 2 columns, got {len(fields)}")
        times.append(number(fields[0], f"{path}: data row {i + 1}"))
    if not times:
        fail(TOOL, f"{path}: no data rows")
    return times


def detections_path(dataset):
    found = sorted(glob.glob(os.path.join(dataset, "*_detections.csv.gz")) +
                   glob.glob(os.path.join(dataset, "*_detections.csv")))
    if len(found) != 1:
        fail(TOOL, f"{dataset}: expected one *_detections.csv[.gz], found {len(found)}")
    return found[0]


def check_row(fields, where, beam_count, range_m):
    """Fails naming what is wrong in a detections row the fast path in read_beams refused."""
    if len(fields) != len(HEADER):
        fail(TOOL, f"{where}: expected {len(HEADER)} fields, got {len(fields)}")
    row = [integer(fields[i], where) for i in (0, 1, 4)][1]
    r = number(fields[6], where)
    if not 0 <= row < beam_count:
        fail(TOOL, f"{where}: beam_row {row} is not a row of the beam times ({beam_count})")
    if not 0.0 <= r <= range_m:
        fail(TOOL, f"{where}: range_m {fields[6]} outside the sonar range 0..{range_m}")
    fail(TOOL, f"{where}: unreadable row")


def read_lines(path):
    """The lines of a text file, gunzipped when its name ends in .gz."""
    opener = gzip.open if path.endswith(".gz") else open
    try:
        with opener(path, "rt", newline="") as f:
            return f.read().splitlines()
    except (OSError, EOFError, UnicodeDecodeError) as e:
        fail(TOOL, f"{path}: {e}")


def read_beams(path, beam_count, range_m):
    """The beams with rows, in file order: [beam_row, keyframe, angle_idx, [ranges]]."""
    lines = read_lines(path)
    if not lines or lines[0].split(",") != HEADER:
        fail(TOOL, f"{path}:1: expected the header {','.join(HEADER)}")
    beams = []
    beam = [-1, None, None, []]  # the beam the rows go to
    for line, text in enumerate(lines[1:], start=2):
        if not text.strip():
            continue
        fields = text.split(",")
        try:  # one try for the whole row: 1e6 rows
            keyframe, row, angle, r = int(fields[0]), int(fields[1]), int(fields[4]), float(fields[6])
            valid = len(fields) == len(HEADER) and 0 <= row < beam_count and 0.0 <= r <= range_m
        except (ValueError, IndexError):
            valid = False
        if not valid:
            check_row(fields, f"{path}:{line}", beam_count, range_m)
        if row == beam[0]:
            if keyframe != beam[1] or angle != beam[2]:
                fail(TOOL, f"{path}:{line}: keyframe or angle_idx differs within beam_row {row}")
            beam[3].append(r)
            continue
        if row < beam[0] or (beams and keyframe < beam[1]):
            fail(TOOL, f"{path}:{line}: beam_row or keyframe goes backwards")
        beam = [row, keyframe, angle, [r]]
        beams.append(beam)
    if not beams:
        fail(TOOL, f"{path}: no data rows")
    return beams


def check_keyframes(path, beams, per_revolution, beam_count):
    """A keyframe spans at most one revolution of beam rows; the counted beams exist."""
    first_row = {}
    for row, keyframe, _, _ in beams:
        first_row.setdefault(keyframe, row)
        if row - first_row[keyframe] + 1 > per_revolution:
            fail(TOOL, f"{path}: keyframe {keyframe} spans more than {per_revolution} beam rows")
    counted = (beams[-1][1] - beams[0][1] + 1) * per_revolution
    if counted > beam_count:
        fail(TOOL, f"{path}: keyframes make {counted} beams, the beam times have {beam_count}")
    return counted


def deciles(values):
    """p10 .. p90, linear between order statistics at (n - 1) p; None for an empty sample."""
    if len(values) < 2:
        return [values[0] if values else None] * 9
    return statistics.quantiles(values, n=10, method="inclusive")


def ks_distance(a, b):
    """sup over x of |F_a(x) - F_b(x)|; the sup is reached at a sample value."""
    if not a or not b:
        return None
    a, b = sorted(a), sorted(b)
    return max(abs(bisect.bisect_right(a, x) / len(a) - bisect.bisect_right(b, x) / len(b))
               for x in set(a) | set(b))


def band_percents(values, bands):
    """Percent of values in each [10 k, 10 (k + 1)) m; the top edge in the last band."""
    edges = [BAND_M * k for k in range(bands)]
    counts = [0] * bands
    for v, n in collections.Counter(values).items():
        if 0.0 <= v <= BAND_M * bands:
            counts[min(bisect.bisect_right(edges, v) - 1, bands - 1)] += n
    return [100.0 * c / len(values) if values else None for c in counts]


def runs(ranges_m, bin_m):
    bins = sorted({math.floor(r / bin_m + 0.5) for r in ranges_m})
    return 1 + sum(1 for lo, hi in zip(bins, bins[1:]) if hi - lo >= 2)


def rotation(beams, times):
    """(beam rows, seconds) between each angle's first beams of consecutive keyframes."""
    first = {}
    for row, keyframe, angle, _ in beams:
        first.setdefault(keyframe, {}).setdefault(angle, row)
    rows_between, periods_s = [], []
    for keyframe, angles in first.items():
        following = first.get(keyframe + 1, {})
        for angle, row in angles.items():
            if angle in following:
                rows_between.append(float(following[angle] - row))
                periods_s.append(times[following[angle]] - times[row])
    return rows_between, periods_s


def dataset_statistics(dataset):
    range_m, bin_m, step_rad = read_setup(dataset)
    per_revolution = round(2 * math.pi / step_rad)
    times = read_beam_times(dataset)
    path = detections_path(dataset)
    beams = read_beams(path, len(times), range_m)
    counted = check_keyframes(path, beams, per_revolution, len(times))
    bins = [len(b[3]) for b in beams] + [0] * (counted - len(beams))
    beam_runs = [runs(b[3], bin_m) for b in beams] + [0] * (counted - len(beams))
    first_m = [min(b[3]) for b in beams]
    detected_m = [r for b in beams for r in b[3]]
    beams_per_360, period_s = rotation(beams, times)
    return {
        "setup": (range_m, bin_m, per_revolution),
        "bands": max(1, math.ceil(range_m / BAND_M - 1e-9)),
        "empty_beams_percent": 100.0 * (counted - len(beams)) / counted,
        "bins_per_beam_mean": sum(bins) / counted,
        "bins_per_beam": bins,
        "runs_per_beam_mean": sum(beam_runs) / counted,
        "multi_run_beams_percent": 100.0 * sum(1 for n in beam_runs if n >= 2) / counted,
        "first_range": first_m,
        "detected_range": detected_m,
        "beams_per_revolution": beams_per_360,
        "revolution_period_s": period_s,
    }


def table(sides):
    """{row key: {side: value[, "ks": distance]}} over sides ({"real": stats[, "sim": stats]})."""
    out = {}

    def put(key, value_of):
        out[key] = {side: value_of(s) for side, s in sides.items()}

    def put_quantiles(prefix, sample):
        cuts = {side: deciles(s[sample]) for side, s in sides.items()}
        for name, i in (("p10", 0), ("median", 4), ("p90", 8)):
            out[f"{prefix}_{name}_m"] = {side: cuts[side][i] for side in sides}
        if len(sides) == 2:
            out[f"{prefix}_median_m"]["ks"] = ks_distance(sides["real"][sample],
                                                          sides["sim"][sample])

    def put_bands(prefix, sample):
        shares = {side: band_percents(s[sample], s["bands"]) for side, s in sides.items()}
        for k in range(sides["real"]["bands"]):
            out[f"{prefix}_{10 * k}_{10 * (k + 1)}_m_percent"] = {
                side: shares[side][k] for side in sides}

    put("empty_beams_percent", lambda s: s["empty_beams_percent"])
    put("bins_per_beam_mean", lambda s: s["bins_per_beam_mean"])
    put("bins_per_beam_p90", lambda s: deciles(s["bins_per_beam"])[8])
    put("runs_per_beam_mean", lambda s: s["runs_per_beam_mean"])
    put("multi_run_beams_percent", lambda s: s["multi_run_beams_percent"])
    put_quantiles("first_range", "first_range")
    put_quantiles("detected_range", "detected_range")
    put_bands("detected_bins", "detected_range")
    put_bands("first_ranges", "first_range")
    put("beams_per_revolution", lambda s: deciles(s["beams_per_revolution"])[4])
    put("revolution_period_s", lambda s: deciles(s["revolution_period_s"])[4])
    return out


def main():
    args = sys.argv[1:]
    if len(args) not in (1, 2) or args[0].startswith("-"):
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        sys.exit(2)
    for dataset in args:
        if not os.path.isdir(dataset):
            fail(TOOL, f"{dataset}: not a dataset folder")
    sides = {"real": dataset_statistics(args[0])}
    if len(args) == 2:
        sides["sim"] = dataset_statistics(args[1])
        (range_a, bin_a, steps_a), (range_b, bin_b, steps_b) = (sides[s]["setup"] for s in sides)
        # Equal to the 6 significant digits a setup log carries, as msislab compares them.
        if not (math.isclose(range_a, range_b, rel_tol=1e-6) and
                math.isclose(bin_a, bin_b, rel_tol=1e-6) and steps_a == steps_b):
            fail(TOOL, f"{args[1]}: sonar setup {sides['sim']['setup']} differs from "
                       f"{args[0]}'s {sides['real']['setup']}: the statistics would not compare")
    json.dump(table(sides), sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
