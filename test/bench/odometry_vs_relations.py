#!/usr/bin/env python3
"""Where a 2D log's short relations go wrong: for every relation under 5 s, the estimate's error
against it, the wheel odometry's error against it (the log's ODOM lines, interpolated at the two
stamps) and how far the estimate and the odometry are from each other. A large estimate error
where the estimate agrees with the odometry is a relation both disagree with; one where the
odometry agrees with the relation is the matcher's own (docs/real-logs.md).

usage: odometry_vs_relations.py LOG.clf LOG.relations ESTIMATE.txt [--rows N] [--large 0.1]
"""
import argparse
import csv
import bisect
import math
import sys


def odometry(log_path):
    """(ipc_timestamp, x, y, theta) of every ODOM line, by stamp."""
    rows = []
    with open(log_path, encoding="utf-8", errors="replace") as log:
        for line in log:
            f = line.split()
            if len(f) >= 8 and f[0] == "ODOM":
                rows.append((float(f[7]), float(f[1]), float(f[2]), float(f[3])))
    rows.sort()
    return rows


def interpolated(rows, stamps, t):
    i = bisect.bisect_left(stamps, t)
    if i <= 0 or i >= len(rows):
        return None
    a, b = rows[i - 1], rows[i]
    w = (t - a[0]) / (b[0] - a[0]) if b[0] > a[0] else 0.0
    turn = math.atan2(math.sin(b[3] - a[3]), math.cos(b[3] - a[3]))
    return (a[1] + w * (b[1] - a[1]), a[2] + w * (b[2] - a[2]), a[3] + w * turn)


def motion(p, q):
    """q seen from p: (dx, dy) in p's frame."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    c, s = math.cos(p[2]), math.sin(p[2])
    return (c * dx + s * dy, -s * dx + c * dy)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("log")
    parser.add_argument("relations")
    parser.add_argument("estimate")
    parser.add_argument("--rows", type=int, default=25, help="largest estimate errors listed")
    parser.add_argument("--large", type=float, default=0.1, help="m: an error counted as large")
    parser.add_argument("--scan-errors", metavar="CSV",
                        help="each relation's scan alignment error (uavslam eval --relations R "
                        "--scans LOG --per-relation CSV): the means also over the relations the "
                        "scans themselves put within --clean of the relation")
    parser.add_argument("--clean", type=float, default=0.01, help="m, with --scan-errors")
    a = parser.parse_args()
    odo = odometry(a.log)
    if not odo:
        sys.exit(f"{a.log}: no ODOM lines")
    stamps = [r[0] for r in odo]
    estimate = {}
    with open(a.estimate, encoding="utf-8") as f:
        for line in f:
            v = line.split()
            if len(v) >= 4:
                estimate[float(v[0])] = (float(v[1]), float(v[2]), float(v[3]))
    rows = []
    with open(a.relations, encoding="utf-8") as f:
        for line in f:
            v = line.split()
            if len(v) < 8:
                continue
            t1, t2 = float(v[0]), float(v[1])
            if t2 - t1 >= 5.0 or t1 not in estimate or t2 not in estimate:
                continue
            o1, o2 = interpolated(odo, stamps, t1), interpolated(odo, stamps, t2)
            if o1 is None or o2 is None:
                continue
            true = (float(v[2]), float(v[3]))
            by_odometry = motion(o1, o2)
            by_estimate = motion(estimate[t1], estimate[t2])
            rows.append((math.dist(by_estimate, true), math.dist(by_odometry, true),
                         math.dist(by_estimate, by_odometry), t1, t2, math.hypot(*true),
                         math.hypot(*by_odometry), math.hypot(*by_estimate)))
    if not rows:
        sys.exit("no short relation with an estimate and odometry at both ends")
    rows.sort(reverse=True)
    print("estimate_err odometry_err estimate_vs_odometry t1 t2 |relation| |odometry| |estimate|")
    for r in rows[: a.rows]:
        print(" ".join("%.3f" % x for x in r))
    large = [r for r in rows if r[0] > a.large]
    print("%d short relations: estimate %.4f m, odometry %.4f m mean error" %
          (len(rows), sum(r[0] for r in rows) / len(rows), sum(r[1] for r in rows) / len(rows)))
    print("%d with the estimate off by more than %.2f m: the estimate within 0.05 m of the "
          "odometry in %d, the odometry also off by more than %.2f m in %d" %
          (len(large), a.large, sum(1 for r in large if r[2] < 0.05), a.large,
           sum(1 for r in large if r[1] > a.large)))
    if a.scan_errors:
        by_scans = {}
        with open(a.scan_errors, encoding="utf-8") as f:
            for r in csv.DictReader(f):
                if r["translation_m"]:
                    by_scans[(round(float(r["t1"]), 6), round(float(r["t2"]), 6))] = float(
                        r["translation_m"])
        clean = [r for r in rows if by_scans.get((round(r[3], 6), round(r[4], 6)), 1e9) < a.clean]
        if clean:
            print("%d where the scans agree with the relation within %.3f m: estimate %.4f m, "
                  "odometry %.4f m mean error" %
                  (len(clean), a.clean, sum(r[0] for r in clean) / len(clean),
                   sum(r[1] for r in clean) / len(clean)))


if __name__ == "__main__":
    main()
