#!/usr/bin/env python3
"""Does the heading agree with the GPS track? A diagnostic of a St. Pere-format dataset, outside
the pipeline (docs/trajectory_slam.md, "Which sensor carries the heading function").

Over windows of --window seconds, the direction of the GPS displacement minus the direction of
the displacement the heading and the DVL integrate over the same window (DVL bottom velocity
rotated into the vehicle frame by the DVL mount, then into the world by the MTi heading), for
windows over 3 m of travel and under --max-turn degrees of turn; fitted by least squares as
c + a sin(yaw) + b cos(yaw) degrees, yaw the window's mean vehicle yaw (counter-clockwise from
East). A compass deviation d(yaw) in the heading shows as -d(yaw); --deviation-cos/--deviation-sin
remove one from the heading first (as calibration.yaml's mru.deviation_* would).
Standard library only. Usage:
  tools/heading_course_check.py [--dataset DIR] [--window S] [--max-turn DEG]
                                [--deviation-cos A --deviation-sin B]
"""
import argparse
import bisect
import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ left beside the tools

from stpere_logs import fail, find_log, gps_track, rows, vehicle_yaw_rad

TOOL = "heading_course_check"


def solve3(pairs):
    """Least squares for 3 unknowns: the solution and its standard errors."""
    m = [[sum(a[i] * a[j] for a, _ in pairs) for j in range(3)] for i in range(3)]
    v = [sum(a[i] * b for a, b in pairs) for i in range(3)]
    # Gauss-Jordan on [m | I | v].
    aug = [m[i] + [1.0 if i == j else 0.0 for j in range(3)] + [v[i]] for i in range(3)]
    for i in range(3):
        p = max(range(i, 3), key=lambda r: abs(aug[r][i]))
        aug[i], aug[p] = aug[p], aug[i]
        pivot = aug[i][i]
        aug[i] = [x / pivot for x in aug[i]]
        for r in range(3):
            if r != i:
                f = aug[r][i]
                aug[r] = [x - f * y for x, y in zip(aug[r], aug[i])]
    x = [aug[i][6] for i in range(3)]
    res = [b - sum(xi * ai for xi, ai in zip(x, a)) for a, b in pairs]
    sd = math.sqrt(sum(r * r for r in res) / (len(pairs) - 3))
    return x, [sd * math.sqrt(aug[i][3 + i]) for i in range(3)], sd


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dataset", default=os.environ.get("MSISLAB_STPERE_DIR", "../shared/datasets/stpere"))
    ap.add_argument("--window", type=float, default=20.0)
    ap.add_argument("--max-turn", type=float, default=90.0)
    ap.add_argument("--mru-yaw-offset", type=float, default=86.0)
    ap.add_argument("--dvl-yaw", type=float, default=293.5)
    ap.add_argument("--deviation-cos", type=float, default=0.0)
    ap.add_argument("--deviation-sin", type=float, default=0.0)
    o = ap.parse_args()

    gps = gps_track(o.dataset, TOOL)
    heading = []
    for r in rows(find_log(o.dataset, "_MTi.log", TOOL)):
        read = vehicle_yaw_rad(float(r[3]), o.mru_yaw_offset)
        yaw = read
        for _ in range(12):  # read = yaw + d(yaw), solved for yaw
            yaw = read - math.radians(o.deviation_cos * math.cos(yaw) + o.deviation_sin * math.sin(yaw))
        heading.append((float(r[0]), yaw))
    c, s = math.cos(math.radians(o.dvl_yaw)), math.sin(math.radians(o.dvl_yaw))
    dvl = []
    for r in rows(find_log(o.dataset, "_DVL.log", TOOL)):
        if int(float(r[14])) != 1:  # bottomVelStatus: no bottom lock
            continue
        bx, by = float(r[11]) / 100, float(r[12]) / 100
        dvl.append((float(r[0]), c * bx - s * by, s * bx + c * by))

    heading_t = [h[0] for h in heading]
    gps_t = [g[0] for g in gps]

    def yaw_at(t):
        i = min(max(bisect.bisect_left(heading_t, t), 1), len(heading_t) - 1)
        return heading[i][1]

    def gps_at(t):
        i = min(max(bisect.bisect_left(gps_t, t), 1), len(gps_t) - 1)
        (t0, x0, y0), (t1, x1, y1) = gps[i - 1], gps[i]
        a = (t - t0) / (t1 - t0)
        return x0 + a * (x1 - x0), y0 + a * (y1 - y0)

    pairs = []
    t = gps[0][0]
    while t + o.window < gps[-1][0]:
        seg = [d for d in dvl if t <= d[0] < t + o.window]
        if len(seg) >= int(o.window * 1.2):
            dx = dy = 0.0
            yaws = []
            for k, (td, vx, vy) in enumerate(seg):
                yaw = yaw_at(td)
                yaws.append(yaw)
                dt = (seg[k + 1][0] if k + 1 < len(seg) else t + o.window) - td
                dx += (math.cos(yaw) * vx - math.sin(yaw) * vy) * dt
                dy += (math.sin(yaw) * vx + math.cos(yaw) * vy) * dt
            (x0, y0), (x1, y1) = gps_at(seg[0][0]), gps_at(t + o.window)
            turn = max(abs(math.remainder(y - yaws[0], 2 * math.pi)) for y in yaws)
            if math.hypot(x1 - x0, y1 - y0) > 3.0 and turn < math.radians(o.max_turn):
                d = math.degrees(math.remainder(math.atan2(y1 - y0, x1 - x0) - math.atan2(dy, dx),
                                                2 * math.pi))
                mean = math.atan2(sum(map(math.sin, yaws)), sum(map(math.cos, yaws)))
                if abs(d) < 30.0:
                    pairs.append(([1.0, math.sin(mean), math.cos(mean)], d))
        t += o.window
    if len(pairs) < 10:
        fail(TOOL, f"only {len(pairs)} windows; try a longer --window")
    x, se, sd = solve3(pairs)
    print(f"{len(pairs)} windows of {o.window:g} s: GPS course - heading-and-DVL course = "
          f"{x[0]:.2f} (se {se[0]:.2f}) + {x[1]:.2f} (se {se[1]:.2f}) sin(yaw) + "
          f"{x[2]:.2f} (se {se[2]:.2f}) cos(yaw) deg; residual sd {sd:.2f} deg")


if __name__ == "__main__":
    main()
