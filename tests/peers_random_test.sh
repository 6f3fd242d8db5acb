#!/usr/bin/env bash
# ctest: scripts/peers's random set with no peer (--peers ''): the G(n, p) graph it makes is a
# simple graph in DIMACS form (the header's n and m agree with its edge lines, 1 <= i < j <= n, no
# pair twice), its edge count lies within 5 standard deviations of Binomial(n(n-1)/2, p), the same
# seed makes the same file in another run, and two algorithms of ours prove the same omega on it.
# Then the graphs it makes beyond G(n, p), against what they must be: hamming6-2 and johnson8-4-4
# with DIMACS's published edge counts (1,824 and 1,855) and omega (32 and 14), hamming8-4 edge for
# edge the file of ../shared/data/dimacs (where it is there); the p_hat kind's degrees spread
# more than twice G(n, p)'s at its density; the planted clique is a clique, and omega its size.
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

# The other kinds, made by scripts/peers (hamming8-4 through its generator, as a DIMACS family).
VERIFYBENCH_BUILD_DIR=$bin bash "$src/scripts/peers" "$out/k" --no-corpus --no-3dmatch \
  --only '^(hamming6-2|johnson8-4-4|phat500-1_s1|planted200_0.9_k60_s1)$' --peers '' \
  --algorithms auto,bbmc --limit 60 > "$out/k.log" 2>&1 ||
  { echo "FAIL: scripts/peers (other kinds)"; cat "$out/k.log"; fail=1; }
$py - "$out/k" "$src/../shared/data/dimacs/hamming8-4.clq" "$src/scripts/peers" <<'PY' || fail=1
import math, os, random, subprocess, sys
out, shared_h84, script = sys.argv[1:4]
bad = []
def read(path):
    lines = [l.split() for l in open(path) if l.strip() and l[0] in "pe"]  # no comment lines
    n = int(lines[0][2])
    edges = {(min(int(a), int(b)), max(int(a), int(b))) for tag, a, b in lines[1:] if tag == "e"}
    if len(edges) != int(lines[0][3]) or any(not (1 <= a < b <= n) for a, b in edges):
        bad.append(f"{path}: not a simple graph in DIMACS form")
    return n, edges
rows = [l.rstrip("\n").split("\t") for l in open(f"{out}/peers.tsv")][1:]
proved = {}
for r in rows:
    if r[7] == "ok":
        proved.setdefault(r[0], {})[r[3]] = int(r[4])
def omega_is(g, w):
    got = proved.get(g, {})
    if sorted(got) != ["clique", "clique-bbmc"] or set(got.values()) != {w}:
        bad.append(f"{g}: proved omegas {got}, expected {w}")
for g, m, w in (("hamming6-2", 1824, 32), ("johnson8-4-4", 1855, 14)):
    n, e = read(f"{out}/graphs/{g}.clq")
    if len(e) != m:
        bad.append(f"{g}: {len(e)} edges, DIMACS's has {m}")
    omega_is(g, w)
n, e = read(f"{out}/graphs/phat500-1_s1.clq")
deg = [0] * (n + 1)
for a, b in e:
    deg[a] += 1; deg[b] += 1
mean = sum(deg[1:]) / n
sd = math.sqrt(sum((d - mean) ** 2 for d in deg[1:]) / n)
p = mean / (n - 1)
if not sd > 2 * math.sqrt((n - 1) * p * (1 - p)):
    bad.append(f"phat500-1_s1: degree sd {sd:.1f}, G(n, {p:.2f})'s {math.sqrt((n - 1) * p * (1 - p)):.1f}")
n, e = read(f"{out}/graphs/planted200_0.9_k60_s1.clq")
K = random.Random(1).sample(range(1, n + 1), 60)
if any((min(a, b), max(a, b)) not in e for i, a in enumerate(K) for b in K[i + 1:]):
    bad.append("planted200_0.9_k60_s1: the planted vertices are no clique")
omega_is("planted200_0.9_k60_s1", 60)
if os.path.exists(shared_h84):
    # scripts/peers's make_graph on its own: the hamming family at b = 8, d = 4.
    h84 = f"{out}/h84.clq"
    subprocess.run(["bash", "-c", 'source <(sed -n "/^make_graph() {/,/^}/p" "$0"); make_graph "$@"',
                    script, "hamming", "8", "4", h84], check=True)
    if read(h84)[1] != read(shared_h84)[1]:
        bad.append("hamming8-4: not the DIMACS file's edges")
else:
    print(f"skip: {shared_h84} not found (hamming8-4 against DIMACS's file)")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
[ $fail = 0 ] && echo "peers_random: ok"
exit $fail
