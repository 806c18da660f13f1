#!/usr/bin/env bash
# The NEES of a simulated flight over time: one row per window of the flight, the mean and median
# NEES of the accepted scans in it (uavslam simulate's scans.csv). A flight's NEES mean hides where
# the covariance is too sure and where too cautious; a consistent covariance gives 3 throughout.
# Usage: test/bench/nees_profile.sh [--build-dir DIR] [--config FILE] [--window S] [--seed N]
#                                   [--set key=value ...] scenario ...
# (default: config/slam.yaml, windows of 4 s, the scenario's own seed)
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="${repo_dir}/build"
config="${repo_dir}/config/slam.yaml"
window=4
seed=()
overrides=()
scenarios=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build_dir="$2"; shift 2 ;;
    --config) config="$2"; shift 2 ;;
    --window) window="$2"; shift 2 ;;
    --seed) seed=(--seed "$2"); shift 2 ;;
    --set) overrides+=(--set "$2"); shift 2 ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
    -*) echo "nees_profile.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) scenarios+=("$1"); shift ;;
  esac
done
[[ ${#scenarios[@]} -gt 0 ]] || { echo "nees_profile.sh: name a scenario (see --help)" >&2; exit 2; }
[[ "${window}" =~ ^[0-9]+([.][0-9]+)?$ ]] && [[ "${window}" != 0 ]] ||
  { echo "nees_profile.sh: --window '${window}' is not a positive number of seconds" >&2; exit 2; }
uavslam="${build_dir}/bin/uavslam"
[[ -x "${uavslam}" ]] || { echo "nees_profile.sh: ${uavslam} not built (make build)" >&2; exit 2; }
out_dir="$(mktemp -d)"
trap 'rm -rf "${out_dir}"' EXIT

for scenario in "${scenarios[@]}"; do
  file="${repo_dir}/config/scenarios/${scenario}.yaml"
  [[ -f "${file}" ]] || { echo "nees_profile.sh: no scenario ${file}" >&2; exit 2; }
  "${uavslam}" simulate --quiet --scenario "${file}" --config "${config}" "${seed[@]}" \
    --out "${out_dir}/${scenario}" "${overrides[@]}" > /dev/null
  python3 - "${out_dir}/${scenario}/scans.csv" "${scenario}" "${window}" <<'PY'
import csv, statistics, sys
path, scenario, window = sys.argv[1], sys.argv[2], float(sys.argv[3])
windows = {}
for row in csv.DictReader(open(path)):
    if row["nees"] and row["outcome"] == "accepted":
        windows.setdefault(int(float(row["stamp"]) // window), []).append(float(row["nees"]))
print("| %s: window (s) | scans | NEES mean | NEES median |" % scenario)
print("|---|---|---|---|")
for k in sorted(windows):
    v = windows[k]
    print("| %g-%g | %d | %.1f | %.1f |" % (k * window, (k + 1) * window, len(v),
                                          statistics.mean(v), statistics.median(v)))
print()
PY
done
