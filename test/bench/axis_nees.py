#!/usr/bin/env python3
"""Per axis, how the error of `uavslam simulate`'s poses compares with the covariance they report:
over the accepted scans of one or more scans.csv files (columns x, y, z, true_x, true_y, true_z,
sigma_x, sigma_y, sigma_z, nees), the rms error, the rms sigma and the mean of e^2 / sigma^2 of
each axis (1 where the covariance is honest along it), beside the flight's NEES mean. It says
which axis makes a flight's NEES too high or too low (docs/algorithm.md)."""
import argparse
import csv
import math
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="+", help="scans.csv of uavslam simulate")
    args = parser.parse_args()
    for path in args.csv:
        try:
            with open(path, newline="") as f:
                rows = [r for r in csv.DictReader(f) if r["outcome"] == "accepted" and r["nees"]]
        except (OSError, KeyError) as e:
            sys.exit(f"axis_nees.py: {path}: cannot read the scans ({e})")
        if not rows:
            sys.exit(f"axis_nees.py: {path}: no accepted scan with a NEES")
        nees = sum(float(r["nees"]) for r in rows) / len(rows)
        print(f"{path}: {len(rows)} scans, NEES mean {nees:.2f}")
        for axis in "xyz":
            errors = [(float(r[axis]) - float(r["true_" + axis])) ** 2 for r in rows]
            sigmas = [float(r["sigma_" + axis]) ** 2 for r in rows]
            ratio = sum(e / max(s, 1e-12) for e, s in zip(errors, sigmas)) / len(rows)
            print(f"  {axis}: rms error {math.sqrt(sum(errors) / len(rows)):.4f} m, "
                  f"rms sigma {math.sqrt(sum(sigmas) / len(rows)):.4f} m, "
                  f"mean e^2/sigma^2 {ratio:.2f}")


if __name__ == "__main__":
    main()
