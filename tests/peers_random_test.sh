#!/usr/bin/env bash
# ctest: scripts/peers's random set with no peer (--peers ''): the G(n, p) graph it makes is a
# simple graph in DIMACS form (the header's n and m agree with its edge lines, 1 <= i < j <= n, no
# pair twice), its edge count lies within 5 standard deviations of Binomial(n(n-1)/2, p), the same
# seed makes the same file in another run, and two algorithms of ours prove the same omega on it.
# usage: peers_random_test.sh SOURCE_DIR DIR_OF_VERIFYBENCH WORK_DIR
set -uo pipefail
src=$1 bin=$2 out=$3
py=/usr/bin/python3
rm -rf "$out"; mkdir -p "$out"
fail=0
graph=gnp200_0.7_s1
for run in a b; do
  VERIFYBENCH_BUILD_DIR=$bin bash "$src/scripts/peers" "$out/$run" --no-corpus --no-3dmatch \
    --no-dimacs --only "^$graph\$" --peers '' --algorithms auto,bbmc --limit 60 \
    > "$out/$run.log" 2>&1 || { echo "FAIL: scripts/peers ($run)"; cat "$out/$run.log"; fail=1; }
done
f=$out/a/graphs/$graph.clq
cmp -s "$f" "$out/b/graphs/$graph.clq" || { echo "FAIL: the same seed made different graphs"; fail=1; }
$py - "$f" 0.7 "$out/a/peers.tsv" <<'PY' || fail=1
import math, sys
path, p, tsv = sys.argv[1], float(sys.argv[2]), sys.argv[3]
lines = [l.split() for l in open(path) if l.strip()]
bad = []
if lines[0][:2] != ["p", "edge"]:
    bad.append(f"header {lines[0]}")
n, m = int(lines[0][2]), int(lines[0][3])
edges = [(int(a), int(b)) for tag, a, b in lines[1:] if tag == "e"]
if len(edges) != len(lines) - 1 or len(edges) != m:
    bad.append(f"{len(edges)} edge lines, header says {m}")
if any(not (1 <= a < b <= n) for a, b in edges):
    bad.append("an edge outside 1 <= i < j <= n")
if len(set(edges)) != len(edges):
    bad.append("a pair twice")
pairs = n * (n - 1) // 2
sd = math.sqrt(pairs * p * (1 - p))
if abs(m - pairs * p) > 5 * sd:
    bad.append(f"{m} edges, Binomial({pairs}, {p}) has mean {pairs * p:.0f}, sd {sd:.1f}")
rows = [l.rstrip("\n").split("\t") for l in open(tsv)][1:]
omegas = {r[3]: r[4] for r in rows if r[7] == "ok"}
if sorted(omegas) != ["clique", "clique-bbmc"] or len(set(omegas.values())) != 1:
    bad.append(f"proved omegas {omegas}")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
[ $fail = 0 ] && echo "peers_random: ok"
exit $fail
