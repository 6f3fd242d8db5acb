#!/usr/bin/env bash
# ctest: reports/peers_table.py on a small TSV in the layout of scripts/peers (no peer needed): the
# ratio of clique's time to the best peer's, the done-when verdicts (ratio <= 1.0, or within 2 ms
# where the best peer needs < 10 ms), the flagged omega disagreements and the closing count, all
# against values worked out by hand.
set -euo pipefail
src=$1 out=$2
py=/usr/bin/python3
rm -rf "$out" && mkdir -p "$out"
tab=$'\t'
{
  echo "graph${tab}n${tab}m${tab}peer${tab}omega${tab}solve_s${tab}wall_s${tab}status${tab}set${tab}known${tab}note"
  while read -r g peer omega solve status known; do
    [ "$omega" = - ] && omega=""; [ "$solve" = - ] && solve=""; [ "$known" = - ] && known=""
    echo "$g${tab}100${tab}200${tab}$peer${tab}$omega${tab}$solve${tab}1.0${tab}$status${tab}test${tab}$known${tab}"
  done <<'ROWS'
g1 pmc 12 0.020 ok 12
g1 lmc 12 0.010 ok 12
g1 clique 12 0.005 ok 12
g1 clique-bbmcx 12 0.001 ok 12
g2 pmc 7 0.004 ok -
g2 clique 7 0.005 ok -
g3 pmc 7 0.004 ok -
g3 clique 7 0.007 ok -
g4 momc 30 2.0 ok -
g4 pmc 30 3.0 ok -
g4 clique 30 3.0 ok -
g5 pmc - - timeout -
g5 lmc - - timeout -
g5 clique 40 1.0 ok -
g6 pmc 12 0.002 ok -
g6 clique 11 0.001 ok -
g7 pmc 9 1.0 ok -
g7 clique - - timeout -
g8 pmc 5 0.1 ok 6
g8 clique 5 0.05 ok 6
ROWS
} > "$out/peers.tsv"

$py "$src/reports/peers_table.py" --limit 10 "$out/peers.tsv" > "$out/peers.md" 2> "$out/err"
cat "$out/peers.md"
# column COLUMN GRAPH: the cell of that graph's row under that header
column() {
  awk -F'|' -v col="$1" -v g="$2" '
    function trim(s) { gsub(/^ +| +$/, "", s); return s }
    NR == 1 { for (i = 2; i < NF; i++) if (trim($i) == col) c = i }
    c && trim($2) == g { print trim($c); exit }' "$out/peers.md"
}
fail=0
expect() {  # COLUMN GRAPH VALUE
  local got; got=$(column "$1" "$2")
  [ "$got" = "$3" ] || { echo "FAIL: $2 '$1': expected '$3', got '$got'"; fail=1; }
}
# Ratios by hand: g1 0.005 / 0.010 (lmc; clique-bbmcx is ours, not a peer), g2 0.005 / 0.004,
# g3 0.007 / 0.004, g4 3.0 / 2.0 (momc), g6 0.001 / 0.002, g7 a timeout: > 10 / 1.0, g8 0.05 / 0.1.
expect "clique / best peer" g1 0.50
expect "clique / best peer" g2 1.25
expect "clique / best peer" g3 1.75
expect "clique / best peer" g4 1.50
expect "clique / best peer" g5 ""
expect "clique / best peer" g6 0.50
expect "clique / best peer" g7 ">10.00"
expect "clique / best peer" g8 0.50
expect "best peer" g1 "lmc 10.0"
expect "best peer" g4 "momc 2000"
expect "best peer" g5 none
# g2: 1 ms behind a 4 ms peer (the 2 ms rule); g3: 3 ms behind it.
expect done-when g1 yes
expect done-when g2 "yes (within 2 ms)"
expect done-when g3 no
expect done-when g4 no
expect done-when g5 "no peer proved (clique did)"
expect done-when g6 "**no: omegas disagree**"
expect done-when g7 no
expect done-when g8 "**no: omegas disagree**"
expect omega g1 12
expect omega g6 "**DISAGREE 11/12**"
expect omega g8 "**DISAGREE 5/6**"
expect clique g7 ">10 s"
expect clique-bbmcx g1 "**1.00**"
grep -qF "**clique meets the done-when on 2 of 7 graphs that some peer proved within 10 s** (test 2/7); no peer proved 1 graph(s), clique proved 1 of them." "$out/peers.md" ||
  { echo "FAIL: closing line"; fail=1; }
grep -qF "**WARNING: OMEGAS DISAGREE on 2 graph(s):**" "$out/peers.md" || { echo "FAIL: no warning"; fail=1; }
grep -q "omegas disagree on g6" "$out/err" || { echo "FAIL: no warning on stderr"; fail=1; }
# Bad input: one line naming the file, exit 2.
printf 'graph\tpeer\n' > "$out/bad.tsv"
rc=0; $py "$src/reports/peers_table.py" "$out/bad.tsv" 2> "$out/err2" >/dev/null || rc=$?
[ $rc = 2 ] && grep -q "bad.tsv: missing column" "$out/err2" || { echo "FAIL: bad TSV (rc $rc)"; cat "$out/err2"; fail=1; }
# A row whose columns are out of order (the peer's name first, as scripts/peers once wrote peaty's
# refusal): the file and line, exit 2.
{ printf 'graph\tn\tm\tpeer\tomega\tsolve_s\twall_s\tstatus\tset\tknown\tnote\n'
  printf 'peaty\tg1\t100\t200\t\t\t\terror\ttest\t\tnot built\n'; } > "$out/shifted.tsv"
rc=0; $py "$src/reports/peers_table.py" "$out/shifted.tsv" 2> "$out/err3" >/dev/null || rc=$?
[ $rc = 2 ] && grep -q "shifted.tsv:2: n and m must be integers" "$out/err3" ||
  { echo "FAIL: shifted row (rc $rc)"; cat "$out/err3"; fail=1; }
[ $fail = 0 ] && echo "peers_table: ok"
exit $fail
