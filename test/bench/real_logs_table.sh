#!/usr/bin/env bash
# The Freiburg benchmark table of docs/real-logs.md: the heading modes and the back end on the
# three logs, each run once as it is and then under tiny heading perturbations (--heading-jitter),
# so a figure comes with its spread (the data README: matchers on these logs can be chaotic).
#
#   test/bench/real_logs_table.sh [--build-dir DIR] [--data DIR] [--jitter-runs N] [--out DIR]
#
#   --build-dir DIR    where uavslam was built (default: build)
#   --data DIR         the Freiburg logs and relations (default: ../shared/data/freiburg)
#   --jitter-runs N    perturbed runs per mode and log, seeds 1..N, 1e-6 rad (default 4)
#   --out DIR          keep every run's outputs here (default: a temporary folder)
#
# Mode rows (one config, config/slam_2d_logs.yaml, with the heading key overridden):
#   seed      icp.heading=source, icp.metric=point_to_point, no loop closure: the seed's
#             translation-only ICP with the odometry heading (and the odometry prior)
#   periodic  icp.heading=periodic_check, no loop closure: yaw checked every
#             icp.heading_check_every scans
#   no_loops  yaw in every scan, point-to-line, loop_closure.enabled=false: the front end alone
#   full      the config as shipped: the front end and the pose-graph back end
# Then the floor: each relation's two scans aligned to each other from the relation.
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="${repo_dir}/build"
data_dir="${repo_dir}/../shared/data/freiburg"
jitter_runs=4
out_dir=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build_dir="$2"; shift 2 ;;
    --data) data_dir="$2"; shift 2 ;;
    --jitter-runs) jitter_runs="$2"; shift 2 ;;
    --out) out_dir="$2"; shift 2 ;;
    -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
    *) echo "real_logs_table.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
uavslam="${build_dir}/bin/uavslam"
[[ -x "${uavslam}" ]] || { echo "real_logs_table.sh: ${uavslam} not built (make build)" >&2; exit 2; }
for log in intel fr079 aces; do
  [[ -f "${data_dir}/${log}.clf" ]] || { echo "real_logs_table.sh: ${data_dir}/${log}.clf missing" >&2; exit 2; }
done
if [[ -z "${out_dir}" ]]; then
  out_dir="$(mktemp -d)"
  trap 'rm -rf "${out_dir}"' EXIT
fi
mkdir -p "${out_dir}"
config="${repo_dir}/config/slam_2d_logs.yaml"

declare -A mode_sets=(
  [seed]="--set icp.heading=source --set icp.metric=point_to_point --set loop_closure.enabled=false"
  [periodic]="--set icp.heading=periodic_check --set loop_closure.enabled=false"
  [no_loops]="--set loop_closure.enabled=false"
  [full]=""
)

# One run: prints "all_m all_deg short_m short_deg front_s back_s loops searched".
run_once() {
  local log="$1" mode="$2" seed="$3"
  local dir="${out_dir}/${log}_${mode}_${seed}"
  local jitter=()
  [[ "${seed}" != 0 ]] && jitter=(--heading-jitter 1e-6 --jitter-seed "${seed}")
  # shellcheck disable=SC2086
  "${uavslam}" run --carmen "${data_dir}/${log}.clf" --out "${dir}" --config "${config}" --quiet \
    ${mode_sets[${mode}]} "${jitter[@]}" > "${dir}.log"
  "${uavslam}" eval --relations "${data_dir}/${log}.relations" --estimate "${dir}/estimate.txt" \
    --json > "${dir}/eval.json"
  python3 - "${dir}/eval.json" "${dir}/summary.json" <<'EOF'
import json, sys
e = json.load(open(sys.argv[1])); s = json.load(open(sys.argv[2]))
loops = s.get("loops", {})
print(e["all"]["translation_m"]["mean"], e["all"]["rotation_deg"]["mean"],
      e["short_span"]["translation_m"]["mean"], e["short_span"]["rotation_deg"]["mean"],
      s["wall_seconds"], loops.get("seconds", 0), loops.get("accepted", 0), loops.get("searched", 0))
EOF
}

echo "| mode | log | all relations (m, deg) | all, ${jitter_runs} perturbed runs: median [min, max] m | under 5 s (m, deg) | under 5 s perturbed: median [min, max] m | loops accepted / searched | front end, back end time |"
echo "|---|---|---|---|---|---|---|---|"
for mode in seed periodic no_loops full; do
  for log in intel fr079 aces; do
    echo "running ${mode} on ${log} ..." >&2
    read -r all_m all_deg short_m short_deg front back loops searched < <(run_once "${log}" "${mode}" 0)
    perturbed=()
    for seed in $(seq 1 "${jitter_runs}"); do perturbed+=("$(run_once "${log}" "${mode}" "${seed}")"); done
    printf '%s\n' "${perturbed[@]}" | python3 -c '
import sys
rows = [list(map(float, l.split())) for l in sys.stdin if l.strip()]
def spread(k):
    v = sorted(r[k] for r in rows)
    return "%.4f [%.4f, %.4f]" % (v[len(v) // 2], v[0], v[-1])
print("|%s|%s|%.4f, %.2f|%s|%.4f, %.2f|%s|%d / %d|%.1f s, %.1f s|" % ("'"${mode}"'", "'"${log}"'",
      '"${all_m}"', '"${all_deg}"', spread(0), '"${short_m}"', '"${short_deg}"', spread(2),
      '"${loops}"', '"${searched}"', '"${front}"', '"${back}"'))'
  done
done

# The floor: each relation's two scans aligned to each other by the same ICP, starting at the
# relation itself (uavslam eval --scans). No estimate that follows the scans does better.
echo
echo "| each relation's two scans aligned from the relation (eval --scans) | all relations (m, deg) | under 5 s (m, deg) |"
echo "|---|---|---|"
for log in intel fr079 aces; do
  "${uavslam}" eval --relations "${data_dir}/${log}.relations" --scans "${data_dir}/${log}.clf" \
    --config "${config}" --json > "${out_dir}/${log}_scan_pairs.json"
  python3 - "${out_dir}/${log}_scan_pairs.json" "${log}" <<'EOF2'
import json, sys
e = json.load(open(sys.argv[1]))
a, s = e["all"], e["short_span"]
print("|%s|%.4f, %.2f (%d not aligned)|%.4f, %.2f (%d not aligned)|" % (sys.argv[2],
      a["translation_m"]["mean"], a["rotation_deg"]["mean"], a["unmatched"],
      s["translation_m"]["mean"], s["rotation_deg"]["mean"], s["unmatched"]))
EOF2
done
