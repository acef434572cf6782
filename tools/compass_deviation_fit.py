#!/usr/bin/env python3
"""Estimate the MRU compass's one-cycle deviation from the sensors alone: a SLAM run's spIC
matches against the raw heading log (docs/trajectory_slam.md, "Which sensor carries the heading
function").

For every valid match (accepted, or rejected only by the innovation gate) of a run's
matches.csv, the heading's own relative yaw between the two scans, Delta = psi_read(t_k) -
psi_read(t_j) from the MTi log as logged (no deviation removed), minus spIC's relative yaw z:
Delta - z = d(psi_k) - d(psi_j) + noise with d(psi) = a cos(psi) + b sin(psi). Weighted least
squares (weights 1 / spIC's yaw variance; matches with |Delta - z| over 15 deg left out) for a and
b, the values calibration.yaml's mru.deviation_cos_deg and deviation_sin_deg take. The heading
comes straight from the log, not from the filter's state, so the compass updates cannot absorb
part of it. Standard library only. Usage:
  tools/compass_deviation_fit.py RUN_DIR [--dataset DIR] [--mru-yaw-offset DEG]
"""
import argparse
import bisect
import csv
import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ left beside the tools

from stpere_logs import fail, find_log, rows, vehicle_yaw_rad

TOOL = "compass_deviation_fit"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run", help="a SLAM run's output folder (its matches.csv)")
    ap.add_argument("--dataset", default=os.environ.get("MSISLAB_STPERE_DIR", "../shared/datasets/stpere"))
    ap.add_argument("--mru-yaw-offset", type=float, default=86.0)
    o = ap.parse_args()
    times, yaws = [], []
    for r in rows(find_log(o.dataset, "_MTi.log", TOOL)):
        times.append(float(r[0]))
        yaws.append(vehicle_yaw_rad(float(r[3]), o.mru_yaw_offset))

    def yaw_at(t):
        i = min(max(bisect.bisect_left(times, t), 1), len(times) - 1)
        a = (t - times[i - 1]) / (times[i] - times[i - 1])
        return yaws[i - 1] + a * math.remainder(yaws[i] - yaws[i - 1], 2 * math.pi)

    path = os.path.join(o.run, "matches.csv")
    if not os.path.isfile(path):
        fail(TOOL, f"no {path}")
    m = [[0.0] * 2 for _ in range(2)]
    v = [0.0, 0.0]
    used = 0
    samples = []
    with open(path) as f:
        for row in csv.DictReader(f):
            if row["outcome"] not in ("accepted", "innovation") or not row["z_yaw_rad"]:
                continue
            pk, pj = yaw_at(float(row["t_s"])), yaw_at(float(row["t_reference_s"]))
            r = math.degrees(math.remainder(pk - pj - float(row["z_yaw_rad"]), 2 * math.pi))
            if abs(r) > 15.0:
                continue
            w = 1.0 / math.degrees(math.sqrt(float(row["z_cov_yawyaw"]))) ** 2
            x = [math.cos(pk) - math.cos(pj), math.sin(pk) - math.sin(pj)]
            samples.append((w, x, r))
            for i in range(2):
                v[i] += w * x[i] * r
                for j in range(2):
                    m[i][j] += w * x[i] * x[j]
            used += 1
    det = m[0][0] * m[1][1] - m[0][1] * m[1][0]
    if used < 10 or abs(det) < 1e-12:
        fail(TOOL, f"{path}: {used} usable matches: too few, or no turning")
    a = (m[1][1] * v[0] - m[0][1] * v[1]) / det
    b = (m[0][0] * v[1] - m[1][0] * v[0]) / det
    # Standard errors scaled by the residuals' own scatter (spIC's yaw variances are the weights'
    # shape, not necessarily their size).
    chi2 = sum(w * (r - a * x[0] - b * x[1]) ** 2 for w, x, r in samples) / (used - 2)
    scale = math.sqrt(max(chi2, 1.0))
    print(f"{used} matches: deviation_cos_deg {a:.2f} (se {scale * math.sqrt(m[1][1] / det):.2f}), "
          f"deviation_sin_deg {b:.2f} (se {scale * math.sqrt(m[0][0] / det):.2f}); "
          f"normalised residual variance {chi2:.2f}")


if __name__ == "__main__":
    main()
