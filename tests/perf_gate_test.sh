#!/usr/bin/env bash
# ctest: the instruction-count gate can fail. One cheap workload, measured into a scratch baseline
# (never the committed one); then the gate against that baseline made 10% cheaper must exit 1 with
# a FAIL row, against it made 10% dearer must pass, against a baseline without the workload must
# exit 2 naming it; a second measurement must equal the first (callgrind counts are exact), and
# the github-action-benchmark file must carry the same count. Skips (77) without valgrind.
set -euo pipefail
src=$1 binary=$2 out=$3
py=/usr/bin/python3
command -v valgrind >/dev/null || { echo "valgrind absent: skipped"; exit 77; }
rm -rf "$out" && mkdir -p "$out"
w=lo_ransac_n1000
gate() { $py "$src/benchmarks/perf_gate.py" --binary "$binary" --workloads $w --jobs 1 \
           --out "$out/run" --trend "$out/trend.tsv" "$@"; }
gate --baseline "$out/base.json" --update >"$out/update.log"
count=$($py -c "import json,sys; print(json.load(open(sys.argv[1]))['workloads'][sys.argv[2]]['instructions'])" \
        "$out/base.json" $w)
[ "$count" -gt 1000000 ] || { echo "implausible count $count"; exit 1; }
# Same binary, same count.
gate --baseline "$out/base.json" >"$out/same.log"
grep -Eq "^$w +$count +$count +\+0\.00%  ok" "$out/same.log" || { cat "$out/same.log"; exit 1; }
$py - "$out/run/github-action-benchmark.json" $w "$count" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))
assert rows == [r for r in rows if set(r) >= {"name", "unit", "value"}], rows
assert [(r["name"], r["value"], r["unit"]) for r in rows] == [(sys.argv[2], int(sys.argv[3]), "instructions")], rows
PY
scaled() {  # baseline with the count multiplied by $1
  $py - "$out/base.json" "$1" "$out/scaled.json" <<'PY'
import json, sys
b = json.load(open(sys.argv[1]))
for e in b["workloads"].values():
    e["instructions"] = int(round(e["instructions"] * float(sys.argv[2])))
json.dump(b, open(sys.argv[3], "w"))
PY
}
scaled 0.9
if gate --baseline "$out/scaled.json" >"$out/cheaper.log" 2>&1; then
  echo "a 10% cheaper baseline passed"; cat "$out/cheaper.log"; exit 1
else
  [ $? -eq 1 ] || { echo "expected exit 1"; cat "$out/cheaper.log"; exit 1; }
fi
grep -Eq "^$w .*\+11\.1[0-9]%  FAIL" "$out/cheaper.log" || { cat "$out/cheaper.log"; exit 1; }
scaled 1.1
gate --baseline "$out/scaled.json" >"$out/dearer.log" 2>&1 || { cat "$out/dearer.log"; exit 1; }
grep -Eq "^$w .*-9\.0[0-9]%  better" "$out/dearer.log" || { cat "$out/dearer.log"; exit 1; }
# 1% growth: under the 2% threshold, past the 0.5% warning.
scaled 0.99
gate --baseline "$out/scaled.json" >"$out/warn.log" 2>&1 || { cat "$out/warn.log"; exit 1; }
grep -Eq "^$w .*  warn" "$out/warn.log" || { cat "$out/warn.log"; exit 1; }
echo '{"workloads": {}}' > "$out/empty.json"
set +e
gate --baseline "$out/empty.json" >"$out/missing.log" 2>&1
code=$?
set -e
[ $code -eq 2 ] || { echo "missing workload: exit $code, expected 2"; cat "$out/missing.log"; exit 1; }
grep -q "no entry for workload(s) $w" "$out/missing.log" || { cat "$out/missing.log"; exit 1; }
# The trend file holds one row per measurement (update, same, cheaper, dearer, warn).
[ "$(grep -c "	$w	" "$out/trend.tsv")" -eq 5 ] || { cat "$out/trend.tsv"; exit 1; }
echo "perf gate test: ok ($w: $count instructions)"
