#!/usr/bin/env python3
"""How much of the matches' horizontal error is shared by the matches around them, and over what
distance flown: over the scans of `uavslam simulate`'s scans.csv that were matched and saw every
direction (outcome accepted, degenerate 0), the structure function of the error e (x and y against
true_x, true_y), as the spread it implies,
    s(d) = sqrt(E[(e(at l + d) - e(at l))^2] / 2)    per axis, l the distance flown
For independent errors s(d) is their spread at every d; for a part the matches share, s grows
with d from the independent part alone (the smallest d) to the whole spread, as the shared part
changes. Sets motion.match_error_sigma and _distance (docs/algorithm.md)."""
import argparse
import bisect
import csv
import math
import sys

DISTANCES = [0.01, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0]  # m flown


def matched_errors(path):
    """(distance flown, x error, y error) of each scan that saw every direction."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"shared_error.py: {path}: cannot read the scans ({e})")
    flown, last, out = 0.0, None, []
    for line, r in enumerate(rows, start=2):
        try:
            if r["outcome"] != "accepted":
                continue
            truth = (float(r["true_x"]), float(r["true_y"]), float(r["true_z"]))
            if last is not None:
                flown += math.dist(truth, last)
            last = truth
            if r["degenerate"] == "0":
                out.append((flown, float(r["x"]) - truth[0], float(r["y"]) - truth[1]))
        except (KeyError, ValueError) as e:
            sys.exit(f"shared_error.py: {path}: line {line}: not a scans.csv row ({e})")
    return out


def spread_at(errors, d):
    """s(d) above, over the pairs d to 1.5 d apart; None without such a pair."""
    flown = [e[0] for e in errors]
    total, pairs = 0.0, 0
    for l, ex, ey in errors:
        j = bisect.bisect_left(flown, l + d)
        if j < len(errors) and flown[j] < l + 1.5 * d:
            total += ((errors[j][1] - ex) ** 2 + (errors[j][2] - ey) ** 2) / 2.0
            pairs += 1
    return math.sqrt(total / pairs / 2.0) if pairs else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="+", help="scans.csv of uavslam simulate")
    args = parser.parse_args()
    print("| scans.csv | matched scans | rms error | " +
          " | ".join(f"s({d:g} m)" for d in DISTANCES) + " |")
    print("|---|---|---|" + "---|" * len(DISTANCES))
    for path in args.csv:
        errors = matched_errors(path)
        if len(errors) < 2:
            sys.exit(f"shared_error.py: {path}: fewer than two scans that saw every direction")
        rms = math.sqrt(sum(ex * ex + ey * ey for _, ex, ey in errors) / len(errors) / 2.0)
        cells = []
        for d in DISTANCES:
            s = spread_at(errors, d)
            cells.append("-" if s is None else f"{s * 1000:.1f} mm")
        print(f"| {path} | {len(errors)} | {rms * 1000:.1f} mm | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
