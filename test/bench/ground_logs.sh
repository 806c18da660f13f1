#!/usr/bin/env bash
# Simulated buildings as 2D benchmark logs: each ground scenario (config/scenarios/ground) written
# as a CARMEN log with its relations (uavslam simulate --carmen) for seeds 1..N (the scanner's and
# the wheels' noise), run with config/slam_2d_logs.yaml (uavslam run --carmen) and scored on its
# relations (uavslam eval --relations): the buildings the Freiburg logs do not show
# (docs/real-logs.md "Simulated buildings").
# Usage: test/bench/ground_logs.sh [--build-dir DIR] [--seeds N] [--set key=value ...] [scenario ...]
# Prints a Markdown table: per scenario the mean over the seeds of the all-relations error, the
# worst seed's, the largest single relation error, the short relations' mean, and the loops.
set -euo pipefail

repo="$(cd "$(dirname "$0")/../.." && pwd)"
build_dir="${repo}/build"
seeds=4
overrides=()
scenarios=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build_dir="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --set) overrides+=(--set "$2"); shift 2 ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    -*) echo "ground_logs.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) scenarios+=("$1"); shift ;;
  esac
done
[[ "${seeds}" =~ ^[1-9][0-9]*$ ]] || { echo "ground_logs.sh: --seeds '${seeds}' is not a positive count" >&2; exit 2; }
uavslam="${build_dir}/bin/uavslam"
[[ -x "${uavslam}" ]] || { echo "ground_logs.sh: no ${uavslam} (build first, or --build-dir)" >&2; exit 2; }
if [[ ${#scenarios[@]} -eq 0 ]]; then
  for f in "${repo}"/config/scenarios/ground/*.yaml; do scenarios+=("$(basename "${f}" .yaml)"); done
fi

work="$(mktemp -d)"
trap 'rm -rf "${work}"' EXIT
echo "| scenario | seeds | all relations: mean over seeds | worst seed | largest relation error | under 5 s | loops accepted / back to back / by the graph |"
echo "|---|---|---|---|---|---|---|"
for name in "${scenarios[@]}"; do
  scenario="${repo}/config/scenarios/ground/${name}.yaml"
  [[ -f "${scenario}" ]] || { echo "ground_logs.sh: no scenario ${scenario}" >&2; exit 2; }
  for seed in $(seq 1 "${seeds}"); do
    echo "running ${name}, seed ${seed} of ${seeds} ..." >&2
    dir="${work}/${name}_${seed}"
    "${uavslam}" simulate --quiet --scenario "${scenario}" --seed "${seed}" --out "${dir}/sim" \
      --carmen "${dir}/log.clf" > /dev/null
    "${uavslam}" run --quiet --carmen "${dir}/log.clf" --out "${dir}/run" \
      --config "${repo}/config/slam_2d_logs.yaml" "${overrides[@]}" > /dev/null
    "${uavslam}" eval --json --relations "${dir}/log.relations" \
      --estimate "${dir}/run/estimate.txt" > "${dir}/eval.json"
  done
  python3 - "${work}" "${name}" "${seeds}" <<'PY'
import json, sys
work, name, seeds = sys.argv[1], sys.argv[2], int(sys.argv[3])
alls, shorts, largest, loops = [], [], 0.0, [0, 0, 0]
for seed in range(1, seeds + 1):
    d = f"{work}/{name}_{seed}"
    e = json.load(open(f"{d}/eval.json"))
    alls.append(e["all"]["translation_m"]["mean"])
    shorts.append(e["short_span"]["translation_m"]["mean"])
    largest = max(largest, e["all"]["translation_m"]["max"])
    l = json.load(open(f"{d}/run/summary.json")).get("loops") or {}
    loops = [loops[0] + l.get("accepted", 0), loops[1] + l.get("rejected_back_to_back", 0),
             loops[2] + l.get("rejected_by_graph", 0)]
print(f"| {name} | {seeds} | {sum(alls) / seeds:.4f} m | {max(alls):.4f} m | {largest:.3f} m "
      f"| {sum(shorts) / seeds:.4f} m | {loops[0]} / {loops[1]} / {loops[2]} |")
PY
done
