#!/usr/bin/env python3
"""Dead reckoning as an external msislab method (Python 3 standard library only).

Usage: dead_reckoning.py DATASET_DIR OUT_DIR [--seed N] [--config SLAM.yaml] [--scan-period S]

Integrates the DVL bottom velocity, turned into the world frame by the MTi heading, from the start
pose every msislab method starts from (simulation: the first pose of truth/trajectory.tum; real
data: the first GPS fix after the first heading, heading from the MTi), and propagates a position
covariance from the DVL and heading noise of the SLAM config. Writes OUT_DIR/trajectory.tum (a pose
at every heading reading) and OUT_DIR/scans.csv (a pose with its covariance every scan period,
13.8 s by default: one sonar revolution of the St. Pere head). Formats: docs/formats.md.
"""
import argparse
import glob
import math
import os
import sys

ST_PERE_ORIGIN_DEG = (42.0 + 12.225 / 60.0, 3.0 + 6.2832 / 60.0)
EARTH_RADIUS_M = 6378137.0


def find_one(dataset, suffix):
    """The one file of the dataset whose name ends in suffix, or None."""
    found = sorted(glob.glob(os.path.join(dataset, "*" + suffix)))
    if len(found) > 1:
        sys.exit("%s: two files end in %s" % (dataset, suffix))
    return found[0] if found else None


def read_yaml_numbers(path):
    """'section.key' -> float for a two-level YAML file (calibration.yaml, the SLAM config)."""
    values, section = {}, ""
    if not path or not os.path.exists(path):
        return values
    with open(path) as f:
        for raw in f:
            line = raw.split("#", 1)[0].rstrip()
            if not line.strip() or ":" not in line:
                continue
            key, value = [part.strip() for part in line.split(":", 1)]
            if not raw.startswith((" ", "\t")):
                section = key
            try:
                values[section + "." + key if raw.startswith((" ", "\t")) else key] = float(value)
            except ValueError:
                pass
    return values


def log_rows(path):
    """The numeric rows of a St. Pere log: '%' headers and blank lines skipped."""
    with open(path, encoding="latin-1") as f:
        for line in f:
            if line.startswith("%") or not line.strip():
                continue
            yield [float(v) for v in line.split()]


def vehicle_yaw(yaw_mti_deg, calibration):
    """psi = pi/2 - (yaw_mti - offset), the compass deviation a cos psi + b sin psi removed."""
    offset = calibration.get("mru.yaw_offset_deg", 86.0)
    a = calibration.get("mru.deviation_cos_deg", 0.0)
    b = calibration.get("mru.deviation_sin_deg", 0.0)
    read = math.pi / 2 - math.radians(yaw_mti_deg - offset)
    psi = read
    for _ in range(8):
        psi = read - math.radians(a * math.cos(psi) + b * math.sin(psi))
    return math.atan2(math.sin(psi), math.cos(psi))


def read_headings(path, calibration):
    """(t_s, yaw_rad) per MTi row; 11 columns carry the [idSensor] column after logTime."""
    return [(r[0], vehicle_yaw(r[4] if len(r) == 11 else r[3], calibration))
            for r in log_rows(path)]


def read_velocities(path, calibration):
    """(t_s, u_mps, v_mps) in the vehicle frame per DVL row with bottom lock."""
    yaw = math.radians(calibration.get("dvl.yaw_deg", 293.5))
    c, s = math.cos(yaw), math.sin(yaw)
    rows = []
    for r in log_rows(path):
        k = 1 if len(r) == 33 else 0
        vx, vy, status = r[11 + k] / 100.0, r[12 + k] / 100.0, r[14 + k]
        if status == 1:
            rows.append((r[0], c * vx - s * vy, s * vx + c * vy))
    return rows


def nmea_degrees(value):
    sign = -1.0 if value < 0 else 1.0
    value = abs(value)
    return sign * (int(value / 100) + (value - 100 * int(value / 100)) / 60.0)


def start_pose(dataset, headings, calibration):
    """(t_s, x_m, y_m, yaw_rad): the first truth pose, else the first GPS fix after the first
    heading (local frame: East and North metres from the calibration's origin)."""
    truth = os.path.join(dataset, "truth", "trajectory.tum")
    if os.path.exists(truth):
        for pose in read_tum(truth):
            return pose
    gps = find_one(dataset, "_DGPS.log")
    if gps is None:
        t0, yaw0 = headings[0]
        return (t0, 0.0, 0.0, yaw0)
    lat0 = calibration.get("frame.origin_latitude_deg", ST_PERE_ORIGIN_DEG[0])
    lon0 = calibration.get("frame.origin_longitude_deg", ST_PERE_ORIGIN_DEG[1])
    for r in log_rows(gps):
        if r[3] <= 0 or r[0] < headings[0][0]:
            continue
        lat, lon = nmea_degrees(r[1]), nmea_degrees(r[2])
        x = math.radians(lon - lon0) * EARTH_RADIUS_M * math.cos(math.radians(lat0))
        y = math.radians(lat - lat0) * EARTH_RADIUS_M
        return (r[0], x, y, min(headings, key=lambda h: abs(h[0] - r[0]))[1])
    sys.exit("%s: no GPS fix after the first heading" % gps)


def read_tum(path):
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            t, x, y, _z, qx, qy, qz, qw = [float(v) for v in line.split()]
            yield (t, x, y, math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz)))


def integrate(headings, velocities, start, sigma_v, sigma_yaw, scan_period_s):
    """Poses at every heading reading after the start, and scan rows with their covariance.

    Position error: dp = dt (R(psi) dv + R'(psi) v dpsi). A DVL reading's error dv is held until
    the next reading, so its effect over the hold is A dv with A = sum dt R(psi), added as
    sigma_v^2 A A^T when the hold ends; each heading reading's error is independent."""
    t, x, y, yaw = start
    poses, scans = [(t, x, y, yaw)], []
    P = [0.0, 0.0, 0.0]  # xx, xy, yy
    A = [0.0, 0.0, 0.0, 0.0]  # the running hold's sum of dt R(psi), row-major
    vi = max([i for i, v in enumerate(velocities) if v[0] <= t] or [-1])
    u, v = (velocities[vi][1], velocities[vi][2]) if vi >= 0 else (0.0, 0.0)
    next_scan = t + scan_period_s

    def held(P, A):
        a, b, c, d = A
        s2 = sigma_v * sigma_v
        return [P[0] + s2 * (a * a + b * b), P[1] + s2 * (a * c + b * d),
                P[2] + s2 * (c * c + d * d)]

    for th, psi in headings:
        if th <= t:
            continue
        while vi + 1 < len(velocities) and velocities[vi + 1][0] <= th:
            vi += 1
            u, v = velocities[vi][1], velocities[vi][2]
            P, A = held(P, A), [0.0, 0.0, 0.0, 0.0]
        dt = th - t
        c, s = math.cos(psi), math.sin(psi)
        x += dt * (c * u - s * v)
        y += dt * (s * u + c * v)
        A = [A[0] + dt * c, A[1] - dt * s, A[2] + dt * s, A[3] + dt * c]
        jx, jy = dt * (-s * u - c * v), dt * (c * u - s * v)  # d(dp)/dpsi
        q = sigma_yaw * sigma_yaw
        P = [P[0] + q * jx * jx, P[1] + q * jx * jy, P[2] + q * jy * jy]
        t = th
        poses.append((t, x, y, psi))
        while next_scan <= t:
            C = held(P, A)
            scans.append((t, x, y, psi, C[0], C[1], 0.0, C[2], 0.0, q))
            next_scan += scan_period_s
    return poses, scans


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dataset")
    parser.add_argument("out")
    parser.add_argument("--seed", type=int, default=0, help="unused: the method is deterministic")
    parser.add_argument("--config", default="", help="SLAM config YAML (dead_reckoning sigmas)")
    parser.add_argument("--scan-period", type=float, default=13.8, help="seconds between scans")
    args = parser.parse_args()
    calibration = read_yaml_numbers(os.path.join(args.dataset, "calibration.yaml"))
    config = read_yaml_numbers(args.config)
    sigma_v = config.get("dead_reckoning.dvl_sigma_mps", 0.2)
    sigma_yaw = math.radians(config.get("dead_reckoning.heading_sigma_deg", 1.0))
    mti, dvl = find_one(args.dataset, "_MTi.log"), find_one(args.dataset, "_DVL.log")
    if mti is None or dvl is None:
        sys.exit("%s: no *_MTi.log or *_DVL.log" % args.dataset)
    headings = read_headings(mti, calibration)
    velocities = read_velocities(dvl, calibration)
    start = start_pose(args.dataset, headings, calibration)
    poses, scans = integrate(headings, velocities, start, sigma_v, sigma_yaw, args.scan_period)
    with open(os.path.join(args.out, "trajectory.tum"), "w") as f:
        f.write("# t x y z qx qy qz qw\n")
        for t, x, y, yaw in poses:
            f.write("%r %r %r 0 0 0 %r %r\n" % (t, x, y, math.sin(yaw / 2), math.cos(yaw / 2)))
    with open(os.path.join(args.out, "scans.csv"), "w") as f:
        f.write("t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,cov_yawyaw,points\n")
        for row in scans:
            f.write(",".join(repr(v) for v in row) + ",0\n")
    print("dead_reckoning.py: %d poses, %d scans (seed %d)" % (len(poses), len(scans), args.seed),
          file=sys.stderr)


if __name__ == "__main__":
    main()
