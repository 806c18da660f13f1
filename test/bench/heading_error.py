#!/usr/bin/env python3
"""The heading's error over a stretch of each flight: for each `uavslam simulate` output directory
(estimate.tum and groundtruth.tum), the mean of wrap(yaw_estimate - yaw_truth) over the poses
stamped in [--from, --to), in mrad; then the mean and rms over the directories. A mean apart from
0 over many noise seeds is a bias, not noise (docs/algorithm.md)."""
import argparse
import math
import os
import sys


def yaws(path):
    out = {}
    try:
        with open(path) as f:
            for number, line in enumerate(f, 1):
                if line.startswith("#") or not line.strip():
                    continue
                fields = line.split()
                if len(fields) != 8:
                    sys.exit(f"heading_error.py: {path}:{number}: {len(fields)} fields, a TUM line has 8")
                t, qx, qy, qz, qw = float(fields[0]), *map(float, fields[4:8])
                out[round(t, 4)] = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
    except OSError as e:
        sys.exit(f"heading_error.py: {path}: {e.strerror}")
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dirs", nargs="+", help="uavslam simulate --out directories")
    parser.add_argument("--from", dest="start", type=float, default=10.0, help="s (default 10)")
    parser.add_argument("--to", dest="end", type=float, default=20.0, help="s (default 20)")
    args = parser.parse_args()
    means = []
    for d in args.dirs:
        estimate = yaws(os.path.join(d, "estimate.tum"))
        truth = yaws(os.path.join(d, "groundtruth.tum"))
        errors = [(estimate[t] - truth[t] + math.pi) % (2 * math.pi) - math.pi
                  for t in estimate if t in truth and args.start <= t < args.end]
        if not errors:
            sys.exit(f"heading_error.py: {d}: no pose in [{args.start}, {args.end}) s")
        means.append(1000 * sum(errors) / len(errors))
        print(f"{d}: {means[-1]:+.2f} mrad")
    rms = math.sqrt(sum(m * m for m in means) / len(means))
    print(f"{len(means)} flights: mean {sum(means) / len(means):+.2f} mrad, rms {rms:.2f} mrad")


if __name__ == "__main__":
    main()
