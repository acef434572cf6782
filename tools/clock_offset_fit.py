#!/usr/bin/env python3
"""Estimate the sonar clock's offset left after calibration.yaml's from the sensors alone: a SLAM
run's consecutive spIC matches against the MTi's heading log (docs/simulator.md, "Sonar clock
offset").

A scan whose beams happened tau later than their times say shows the vehicle turned by tau times
its yaw rate more (the filters' clock model, slam/calibration_model.hpp: h_tau = (-)(tau u_j) (+) h
(+) (tau u_k)). So for every valid match (accepted, or rejected only by the innovation gate) of a
scan against the one before it, spIC's relative yaw z against the heading log's own, Delta =
psi(t_k) - psi(t_j) as logged (no deviation removed):
  z - Delta = tau (omega_k - omega_j) - (d(psi_k) - d(psi_j)) + noise,
omega the log's yaw rate averaged over +-WINDOW s around the scan's time (default 6.9 s, half the
13.8 s revolution: the filters' revolution-mean velocity; 1.5 s was the first fit's) and d(psi) = a
cos(psi) + b sin(psi) the compass's one-cycle deviation, which the heading log carries and which
would otherwise alias into tau on a vehicle that turns where its yaw rate changes. Weighted least
squares for tau, a and b (weights 1 / spIC's yaw variance; matches with |z - Delta| over 15 deg
left out), standard errors scaled by the residuals' own scatter. tau is what a calibration.yaml
should add to the run's sonar.time_offset_s (the times in matches.csv have it applied already); a
and b are the compass's whole deviation, as tools/compass_deviation_fit.py's. The heading comes
straight from the log, not from the filter's state. Standard library only. Usage:
  tools/clock_offset_fit.py RUN_DIR [--dataset DIR] [--window S] [--mru-yaw-offset DEG]
"""
import argparse
import bisect
import csv
import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ left beside the tools

from stpere_logs import fail, find_log, rows, vehicle_yaw_rad

TOOL = "clock_offset_fit"


def solve3(m, v):
    """x with m x = v for a symmetric 3 x 3 m (Cramer's rule), and m's inverse; None if singular."""
    det = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
           - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
           + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    if abs(det) < 1e-12:
        return None
    inv = [[0.0] * 3 for _ in range(3)]
    for i in range(3):
        for j in range(3):
            rows_ = [r for r in range(3) if r != j]
            cols = [c for c in range(3) if c != i]
            minor = (m[rows_[0]][cols[0]] * m[rows_[1]][cols[1]]
                     - m[rows_[0]][cols[1]] * m[rows_[1]][cols[0]])
            inv[i][j] = (-1) ** (i + j) * minor / det
    return [sum(inv[i][j] * v[j] for j in range(3)) for i in range(3)], inv


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run", help="a SLAM run's output folder (its matches.csv)")
    ap.add_argument("--dataset", default=os.environ.get("MSISLAB_STPERE_DIR", "../shared/datasets/stpere"))
    ap.add_argument("--window", type=float, default=6.9)
    ap.add_argument("--mru-yaw-offset", type=float, default=86.0)
    o = ap.parse_args()
    if not o.window > 0.0:
        fail(TOOL, f"--window {o.window}: must be above 0 s")
    times, yaws = [], []
    for r in rows(find_log(o.dataset, "_MTi.log", TOOL)):
        times.append(float(r[0]))
        yaws.append(vehicle_yaw_rad(float(r[3]), o.mru_yaw_offset))
    if len(times) < 2:
        fail(TOOL, f"{o.dataset}: the MTi log has fewer than two rows")
    # The yaw unwrapped, so that a rate is a difference.
    unwrapped = [yaws[0]]
    for y in yaws[1:]:
        unwrapped.append(unwrapped[-1] + math.remainder(y - unwrapped[-1], 2 * math.pi))

    def yaw_at(t):
        i = min(max(bisect.bisect_left(times, t), 1), len(times) - 1)
        a = (t - times[i - 1]) / (times[i] - times[i - 1])
        return unwrapped[i - 1] + a * (unwrapped[i] - unwrapped[i - 1])

    def rate_at(t):
        return (yaw_at(t + o.window) - yaw_at(t - o.window)) / (2.0 * o.window)

    path = os.path.join(o.run, "matches.csv")
    if not os.path.isfile(path):
        fail(TOOL, f"no {path}")
    m = [[0.0] * 3 for _ in range(3)]
    v = [0.0] * 3
    samples = []
    with open(path) as f:
        for line, row in enumerate(csv.DictReader(f), start=2):
            try:
                consecutive = int(row["reference"]) == int(row["scan"]) - 1
                valid = row["outcome"] in ("accepted", "innovation") and row["z_yaw_rad"]
                if not consecutive or not valid:
                    continue
                tk, tj = float(row["t_s"]), float(row["t_reference_s"])
                z, var = float(row["z_yaw_rad"]), float(row["z_cov_yawyaw"])
            except (KeyError, TypeError, ValueError) as e:
                fail(TOOL, f"{path}:{line}: {e}")
            pk, pj = yaw_at(tk), yaw_at(tj)
            y = math.degrees(math.remainder(z - (pk - pj), 2 * math.pi))
            if abs(y) > 15.0 or not var > 0.0:
                continue
            x = [math.degrees(rate_at(tk) - rate_at(tj)),
                 -(math.cos(pk) - math.cos(pj)), -(math.sin(pk) - math.sin(pj))]
            w = 1.0 / math.degrees(math.sqrt(var)) ** 2
            samples.append((w, x, y))
            for i in range(3):
                v[i] += w * x[i] * y
                for j in range(3):
                    m[i][j] += w * x[i] * x[j]
    solved = solve3(m, v) if len(samples) >= 10 else None
    if solved is None:
        fail(TOOL, f"{path}: {len(samples)} usable consecutive matches: too few, or the yaw rate "
                   "never changes")
    (tau, a, b), inv = solved
    n = len(samples)
    chi2 = sum(w * (y - sum(p * q for p, q in zip((tau, a, b), x))) ** 2
               for w, x, y in samples) / (n - 3)
    scale = math.sqrt(max(chi2, 1.0))
    se = [scale * math.sqrt(inv[i][i]) for i in range(3)]
    print(f"{n} consecutive matches, yaw rate over +-{o.window:g} s: clock offset beyond the "
          f"run's {tau:.3f} s (se {se[0]:.3f}); deviation_cos_deg {a:.2f} (se {se[1]:.2f}), "
          f"deviation_sin_deg {b:.2f} (se {se[2]:.2f}); normalised residual variance {chi2:.2f}")


if __name__ == "__main__":
    main()
