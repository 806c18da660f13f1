#!/usr/bin/env bash
# Monte Carlo over the sensors' noise: each scenario flown with seeds 1..N (uavslam simulate --seed),
# one table row per scenario: ATE horizontal RMSE (m) mean, median and worst over the seeds, the
# vertical RMSE's mean, the mean NEES, and the mean of each flight's median NEES (a flight's mean
# can hide a too-sure stretch behind a too-cautious one; the median says where most scans stand). One seed's figure says little where the estimate is chaotic (a corridor, where one
# keyframe decides the rest of the flight); the spread over seeds is what a change must improve.
# --accel-bias-sigma S: each seed's flight with an accelerometer bias drawn from N(0, S^2) per body
# axis (seeded by the seed; the scenario's imu.accel_bias replaced), e.g. the config's own prior
# (motion.initial_bias_sigma), which the scenarios' bias-free IMUs never draw.
# --sweep-seconds S: the scanner's sweep replaced (lidar.sweep_seconds; 0: every beam at the
# stamp, as the scenarios were flown before they swept).
# Usage: test/bench/monte_carlo.sh [--build-dir DIR] [--seeds N] [--config FILE]
#                                  [--set key=value ...] [--accel-bias-sigma S]
#                                  [--sweep-seconds S] [scenario ...]
# (default: seeds 8, config/slam.yaml, the scenarios corridor and plain_corridor)
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="${repo_dir}/build"
seeds=8
config="${repo_dir}/config/slam.yaml"
overrides=()
scenarios=()
bias_sigma=
sweep=
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build_dir="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --config) config="$2"; shift 2 ;;
    --set) overrides+=(--set "$2"); shift 2 ;;
    --accel-bias-sigma) bias_sigma="$2"; shift 2 ;;
    --sweep-seconds) sweep="$2"; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    -*) echo "monte_carlo.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) scenarios+=("$1"); shift ;;
  esac
done
[[ ${#scenarios[@]} -gt 0 ]] || scenarios=(corridor plain_corridor)
[[ "${seeds}" =~ ^[1-9][0-9]*$ ]] || { echo "monte_carlo.sh: --seeds '${seeds}' is not a positive count" >&2; exit 2; }
[[ -z "${bias_sigma}" || "${bias_sigma}" =~ ^[0-9]*\.?[0-9]+$ ]] || { echo "monte_carlo.sh: --accel-bias-sigma '${bias_sigma}' is not a number >= 0" >&2; exit 2; }
[[ -z "${sweep}" || "${sweep}" =~ ^[0-9]*\.?[0-9]+$ ]] || { echo "monte_carlo.sh: --sweep-seconds '${sweep}' is not a number >= 0" >&2; exit 2; }
uavslam="${build_dir}/bin/uavslam"
[[ -x "${uavslam}" ]] || { echo "monte_carlo.sh: ${uavslam} not built (make build)" >&2; exit 2; }
out_dir="$(mktemp -d)"
trap 'rm -rf "${out_dir}"' EXIT

echo "| scenario | seeds | ATE horizontal mean | median | worst | ATE vertical mean | NEES mean | NEES median |"
echo "|---|---|---|---|---|---|---|---|"
for scenario in "${scenarios[@]}"; do
  file="${repo_dir}/config/scenarios/${scenario}.yaml"
  [[ -f "${file}" ]] || { echo "monte_carlo.sh: no scenario ${file}" >&2; exit 2; }
  for seed in $(seq 1 "${seeds}"); do
    echo "running ${scenario}, seed ${seed} of ${seeds} ..." >&2
    flown="${file}"
    if [[ -n "${bias_sigma}" || -n "${sweep}" ]]; then
      mkdir -p "${out_dir}/scenarios"
      flown="${out_dir}/scenarios/${scenario}-${seed}.yaml"
      python3 - "${file}" "${flown}" "${seed}" "${bias_sigma}" "${sweep}" <<'PY'
import random, re, sys
source, target, seed, sigma, sweep = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5]
lines = open(source).readlines()

def replace_in(section, key, value):
    global lines
    lines = [l for l in lines if not re.match(r"\s+%s:" % key, l)]
    at = next((i for i, l in enumerate(lines) if re.match(section + ":", l)), None)
    if at is None:
        sys.exit(f"monte_carlo.sh: {source} has no {section}: section for {key}")
    lines.insert(at + 1, "  %s: %s\n" % (key, value))

if sigma:
    draw = random.Random(seed)
    bias = [draw.gauss(0.0, float(sigma)) for _ in range(3)]
    replace_in("imu", "accel_bias", "[%.6f, %.6f, %.6f]" % tuple(bias))
if sweep:
    replace_in("lidar", "sweep_seconds", sweep)
open(target, "w").writelines(lines)
PY
    fi
    "${uavslam}" simulate --quiet --scenario "${flown}" --config "${config}" --seed "${seed}" \
      --out "${out_dir}/${scenario}/${seed}" "${overrides[@]}" > /dev/null
  done
  python3 - "${out_dir}/${scenario}" "${scenario}" <<'PY'
import csv, json, pathlib, statistics, sys
runs = [json.load(open(p)) for p in sorted(pathlib.Path(sys.argv[1]).glob("*/summary.json"))]
ate = [r["trajectory_errors"]["ate_horizontal_rmse_m"] for r in runs]
vertical = [r["trajectory_errors"]["ate_vertical_rmse_m"] for r in runs]
nees = [r["consistency"]["nees_mean"] for r in runs if "consistency" in r]
nees_text = "%.1f" % statistics.mean(nees) if nees else "-"
medians = []
for scans in sorted(pathlib.Path(sys.argv[1]).glob("*/scans.csv")):
    values = [float(row["nees"]) for row in csv.DictReader(open(scans)) if row.get("nees")]
    if values:
        medians.append(statistics.median(values))
median_text = "%.1f" % statistics.mean(medians) if medians else "-"
print("| %s | %d | %.3f m | %.3f m | %.3f m | %.3f m | %s | %s |" % (sys.argv[2], len(ate),
      statistics.mean(ate), statistics.median(ate), max(ate), statistics.mean(vertical), nees_text,
      median_text))
PY
done
