#!/usr/bin/env bash
# ctest: the sharding engines for real. `parallel`: scripts/parallel-sweep on this machine;
# `slurm`: a one-node Slurm cluster started here (scripts/slurm-local: Debian's slurmctld, slurmd
# and munge) running scripts/slurm-sweep's job array and its dependent merge job. Either way the
# merged report must equal the unsharded run row for row, apart from times. Skips (77) without
# GNU parallel, or without root / slurm-wlm / munge for the Slurm case.
set -euo pipefail
mode=$1 src=$2 out=$3
export VERIFYBENCH=$4
py=/usr/bin/python3
args=(sweep --solvers clique,ransac --dim 2,3 --n 120 --outliers 0.5,0.9 --trials 3 --negatives)
rm -rf "$out" && mkdir -p "$out"
case $mode in
  parallel)
    command -v parallel >/dev/null || { echo "GNU parallel absent: skipped"; exit 77; }
    "$src/scripts/parallel-sweep" --shards 4 --jobs 2 --out "$out/sharded" -- "${args[@]}" >/dev/null ;;
  slurm)
    [ "$(id -u)" -eq 0 ] || { echo "not root: skipped (slurmd must run as root)"; exit 77; }
    for b in slurmctld slurmd sbatch munged; do
      command -v $b >/dev/null || { echo "$b absent: skipped"; exit 77; }
    done
    trap '"$src/scripts/slurm-local" stop "$out/cluster"' EXIT
    "$src/scripts/slurm-local" start "$out/cluster"
    export SLURM_CONF=$out/cluster/slurm.conf
    timeout 240 "$src/scripts/slurm-sweep" --shards 3 --out "$out/sharded" --wait -- "${args[@]}" >/dev/null
    [ -f "$out/sharded/merged.json" ] || { cat "$out/sharded"/*.log; exit 1; }
    grep -q -- '--array=1-3' "$out/sharded/shards.sbatch"
    # A failing shard cancels the merge (afterok) and --wait says so.
    if timeout 120 "$src/scripts/slurm-sweep" --shards 2 --out "$out/failing" --wait -- \
        run --dump "$out/no-such-dump" >"$out/failing.log" 2>&1; then
      echo "a failed shard went unnoticed"; cat "$out/failing.log"; exit 1
    fi
    grep -q "merge job .* ended" "$out/failing.log" || { cat "$out/failing.log"; exit 1; }
    [ ! -f "$out/failing/merged.json" ] ;;
  *) echo "usage: cluster_test.sh parallel|slurm SRC OUT VERIFYBENCH"; exit 2 ;;
esac
"$VERIFYBENCH" "${args[@]}" --quiet --out "$out/whole.json" >/dev/null
# A shard's report and the merged one conform to the report schema.
$py "$src/reports/check_schema.py" "$out/sharded/shard_1.json" "$out/sharded/merged.json" >/dev/null
$py - "$out/whole.json" "$out/sharded/merged.json" <<'PY'
import json, sys
times = {"time_ms", "graph_ms", "search_ms", "fit_ms", "calibration_ms", "median_time_ms",
         "p90_time_ms", "median_calibration_ms"}
strip = lambda rows: [{k: v for k, v in r.items() if k not in times} for r in rows]
whole, merged = (json.load(open(p)) for p in sys.argv[1:3])
assert len(whole["results"]) == 2 * 2 * 3 * 2 * 2, len(whole["results"])
assert strip(whole["results"]) == strip(merged["results"]), "rows differ"
assert strip(whole["aggregates"]) == strip(merged["aggregates"]), "aggregates differ"
assert whole["decisions"] == merged["decisions"], "decisions differ"
print(f"{sys.argv[2]}: {len(merged['results'])} rows, equal to the unsharded run apart from times")
PY
