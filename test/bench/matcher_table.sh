#!/usr/bin/env bash
# Runs bench_matcher once (JSON to a file, progress on stderr) and prints the Markdown tables of
# test/bench/README.md: (a) the matcher per scan, (b) the nearest-neighbour search with recall,
# (c) adding a keyframe.
#
#   test/bench/matcher_table.sh [--build-dir DIR] [--min-time SECONDS] [--json FILE]
#                               [--from-json FILE] [-- extra bench_matcher flags]
#
#   --build-dir DIR    where bench_matcher was built (default: build; the binary is
#                      DIR/test/bench/bench_matcher)
#   --min-time S       --benchmark_min_time per benchmark (default 0.5: the full run takes
#                      about two minutes on two cores)
#   --json FILE        keep the JSON results in FILE (default: a temporary file)
#   --from-json FILE   do not run: print the tables of an earlier run's JSON
#   -- ...             passed on to bench_matcher (e.g. --benchmark_filter=BM_MatchScan)
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="${repo_dir}/build"
min_time="0.5"
json=""
from_json=""
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build_dir="$2"; shift 2 ;;
    --min-time) min_time="$2"; shift 2 ;;
    --json) json="$2"; shift 2 ;;
    --from-json) from_json="$2"; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,17p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown argument: $1 (try --help)" >&2; exit 2 ;;
  esac
done

elapsed=""
if [[ -n "${from_json}" ]]; then
  json="${from_json}"
else
  bench="${build_dir}/test/bench/bench_matcher"
  if [[ ! -x "${bench}" ]]; then
    echo "no ${bench}: build it first (cmake --build ${build_dir} --target bench_matcher)" >&2
    exit 1
  fi
  if [[ -z "${json}" ]]; then
    json="$(mktemp --suffix=.json)"
    trap 'rm -f "${json}"' EXIT
  fi
  start=$(date +%s)
  # Console progress goes to stderr so that stdout holds only the tables.
  "${bench}" --benchmark_min_time="${min_time}" --benchmark_format=console \
    --benchmark_out="${json}" --benchmark_out_format=json "${extra[@]}" >&2
  elapsed=$(( $(date +%s) - start ))
fi

python3 - "${json}" "${elapsed}" <<'PY'
import collections
import json
import re
import sys

path, elapsed = sys.argv[1], sys.argv[2]
with open(path) as f:
    data = json.load(f)

TO_US = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}

# name without Google Benchmark's suffixes -> its runs (several with --benchmark_repetitions)
runs = collections.OrderedDict()
for b in data["benchmarks"]:
    if b.get("run_type") == "aggregate" or b.get("error_occurred"):
        continue
    name = re.sub(r"/(manual_time|real_time|iterations:\d+|repeats:\d+|min_time:[\d.]+)", "",
                  b["name"])
    runs.setdefault(name, []).append(b)


def mean(values):
    return sum(values) / len(values)


def time_us(bs):  # mean over repetitions
    return mean([b["real_time"] * TO_US[b["time_unit"]] for b in bs])


def counter(bs, key, combine=max):
    values = [b[key] for b in bs if key in b]
    return combine(values) if values else float("nan")


def size_label(n):
    n = int(n)
    if n >= 1000000 and n % 1000000 == 0:
        return f"{n // 1000000}M"
    if n >= 1000 and n % 1000 == 0:
        return f"{n // 1000}k"
    return str(n)


def fmt(x, digits=0):
    if x != x:  # NaN
        return "–"
    return f"{x:,.{digits}f}"


def parse(prefix, fields):
    rows = []
    for name, bs in runs.items():
        parts = name.split("/")
        if parts[0] == prefix and len(parts) == fields + 1:
            rows.append((parts[1:], bs))
    return rows


def order(items):  # first-seen order
    seen = []
    for item in items:
        if item not in seen:
            seen.append(item)
    return seen


ctx = data.get("context", {})
print(f"Run: {ctx.get('date', '?')}, {ctx.get('num_cpus', '?')} CPUs at "
      f"{ctx.get('mhz_per_cpu', '?')} MHz, one thread"
      + (f", {elapsed} s wall time" if elapsed else "") + ".")

# (a) the matcher per scan
matcher = parse("BM_MatchScan", 3)
if matcher:
    print("\n#### (a) ScanMatcher::match per scan (SlamConfig defaults, start 5 cm off the truth)\n")
    print("| index | scan points | map points | mean µs | p50 µs | p99 µs | max µs | samples | "
          "accepted | position error mm |")
    print("|---|--:|--:|--:|--:|--:|--:|--:|:-:|--:|")
    indexes = order([p[0] for p, _ in matcher])
    for p, bs in sorted(matcher, key=lambda r: (indexes.index(r[0][0]), int(r[0][1]),
                                                 int(r[0][2]))):
        accepted = counter(bs, "accepted", min)
        print(f"| {p[0]} | {p[1]} | {size_label(p[2])} | {fmt(time_us(bs))} | "
              f"{fmt(counter(bs, 'p50_us'))} | {fmt(counter(bs, 'p99_us'))} | "
              f"{fmt(counter(bs, 'max_us'))} | {fmt(counter(bs, 'samples', min))} | "
              f"{'yes' if accepted == 1 else 'no'} | {fmt(counter(bs, 'pos_err_mm'), 1)} |")
    print("\nTarget: p99 ≤ 1 ms per scan at 216 points and a 100k-point map:")
    for p, bs in matcher:
        if p[1] == "216" and p[2] == "100000":
            p99 = counter(bs, "p99_us")
            verdict = "meets it" if p99 <= 1000.0 else f"misses it ({p99 / 1000.0:.2f}x the target)"
            print(f"- {p[0]}: p99 {fmt(p99)} µs: {verdict}")

# (b) the nearest-neighbour search
nn = parse("BM_NearestNeighbour", 2)
if nn:
    sizes = sorted({int(p[1]) for p, _ in nn})
    cells = {(p[0], int(p[1])): bs for p, bs in nn}
    print("\n#### (b) One find_nearest of a 216-point scan: µs per search, recall vs brute force\n")
    print("| index | " + " | ".join(f"{size_label(s)}: µs | {size_label(s)}: recall"
                                    for s in sizes) + " |")
    print("|---|" + "--:|--:|" * len(sizes))
    for index in order([p[0] for p, _ in nn]):
        row = [index]
        for s in sizes:
            bs = cells.get((index, s))
            if bs is None:
                row += ["–", "–"]
            else:
                row += [fmt(time_us(bs)), fmt(counter(bs, "recall", min), 3)]
        print("| " + " | ".join(row) + " |")
    print("\nIndex build time (the whole map, ms): "
          + "; ".join(f"{index}: " + ", ".join(
              f"{size_label(s)} {fmt(counter(cells[(index, s)], 'build_ms'))}"
              for s in sizes if (index, s) in cells)
              for index in order([p[0] for p, _ in nn]) if index.startswith(("flann_c32", "exact"))))

# (c) adding a keyframe
add = parse("BM_AddKeyframe", 2)
if add:
    print("\n#### (c) Adding one 216-point keyframe to the map (which grows by one keyframe each)\n")
    print("| index | map points at start | mean µs | p50 µs | p99 µs | max µs | keyframes |")
    print("|---|--:|--:|--:|--:|--:|--:|")
    for p, bs in add:
        print(f"| {p[0]} | {size_label(p[1])} | {fmt(time_us(bs))} | "
              f"{fmt(counter(bs, 'p50_us'))} | {fmt(counter(bs, 'p99_us'))} | "
              f"{fmt(counter(bs, 'max_us'))} | {fmt(counter(bs, 'samples', min))} |")
PY
