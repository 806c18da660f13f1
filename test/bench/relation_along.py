#!/usr/bin/env python3
"""Whether an estimate (or the scans' own alignment, `uavslam eval --scans`) moves farther or less
far than the relations say, by the speed of the relation: the short relations of one or more
`uavslam eval --per-relation` files (columns relation_m, along_m), those at least --min-length
long, binned by their mean speed (relation_m / span_s). Per bin: the count, the median of along_m
(positive: the estimate moved farther) and the length ratio sum(relation_m + along_m) /
sum(relation_m). Then, over every short relation with a direction, the mean |along_m|, |across_m|
and translation error. A ratio apart from 1 that follows the speed is not a scale
(docs/real-logs.md)."""
import argparse
import csv
import statistics
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="+", help="uavslam eval --per-relation output")
    parser.add_argument("--max-span", type=float, default=5.0, help="s: the short relations")
    parser.add_argument("--min-length", type=float, default=0.1, help="m: shorter ones left out")
    parser.add_argument("--speeds", default="0.3,0.5", help="m/s: the bins' edges")
    args = parser.parse_args()
    edges = [float(v) for v in args.speeds.split(",")]
    for path in args.csv:
        rows = []
        short = []  # (along, across, translation) of every short relation with a direction
        with open(path) as f:
            for row in csv.DictReader(f):
                if "along_m" not in row:
                    sys.exit(f"{path}: no along_m column (uavslam eval --per-relation writes it)")
                span = abs(float(row["span_s"]))
                length = float(row["relation_m"])
                if span >= args.max_span or not row["along_m"]:
                    continue
                short.append((float(row["along_m"]), float(row["across_m"]),
                              float(row["translation_m"])))
                if length >= args.min_length:
                    rows.append((length / span, length, float(row["along_m"])))
        print(f"{path}: {len(rows)} relations under {args.max_span:g} s, at least "
              f"{args.min_length:g} m")
        bounds = [0.0] + edges + [float("inf")]
        for lo, hi in zip(bounds, bounds[1:]):
            part = [r for r in rows if lo <= r[0] < hi]
            if not part:
                continue
            ratio = sum(l + a for _, l, a in part) / sum(l for _, l, _ in part)
            label = f"{lo:g}-{hi:g} m/s" if hi != float("inf") else f">= {lo:g} m/s"
            print(f"  {label:>12}: {len(part):5d}, along median {statistics.median(a for _, _, a in part):+.4f} m, "
                  f"length ratio {ratio:.4f}")
        if rows:
            ratio = sum(l + a for _, l, a in rows) / sum(l for _, l, _ in rows)
            print(f"  {'all':>12}: {len(rows):5d}, along median {statistics.median(a for _, _, a in rows):+.4f} m, "
                  f"length ratio {ratio:.4f}")
        if short:
            print(f"  every short relation with a direction ({len(short)}): mean |along| "
                  f"{statistics.mean(abs(a) for a, _, _ in short):.4f} m, mean |across| "
                  f"{statistics.mean(abs(c) for _, c, _ in short):.4f} m, mean translation error "
                  f"{statistics.mean(t for _, _, t in short):.4f} m")


if __name__ == "__main__":
    main()
