#!/usr/bin/env bash
# ctest: reports made by the CLI through the report scripts. Sweeps give success and time plots
# (PNG and PDF), a DIMACS report its own plot, two generators two panels; the tables hold the
# rows; malformed input is one line naming the file, never a traceback. Here only the files'
# headers are checked: what the figures draw (curves against the reports' data, panels, titles,
# operating points, pixels) is tested in tests/plots (ctest plot_figures).
set -euo pipefail
src=$1 out=$2
py=/usr/bin/python3
rm -rf "$out" && mkdir -p "$out"
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || { echo "not a PNG: $1"; exit 1; }; }
is_pdf() { [ "$(head -c 5 "$1")" = "%PDF-" ] || { echo "not a PDF: $1"; exit 1; }; }
"$VERIFYBENCH" sweep --dim 2,3 --n 60 --outliers 0.5,0.9 --trials 2 --quiet --out "$out/r.json" >/dev/null
"$VERIFYBENCH" sweep --generator repetitive --dim 3 --n 60 --outliers 0.5,0.9 --trials 2 --quiet \
  --out "$out/rep.json" >/dev/null
# The output folder is created when missing.
$py "$src/reports/plot_report.py" "$out/r.json" "$out/rep.json" --out-dir "$out/plots" >"$out/paths"
for kind in success time; do is_png "$out/plots/r_$kind.png"; is_pdf "$out/plots/r_$kind.pdf"; done
grep -c . "$out/paths" | grep -qx 4 || { echo "expected 4 plot paths:"; cat "$out/paths"; exit 1; }
# A DIMACS report gets its own plot.
printf 'p edge 4 6\ne 1 2\ne 1 3\ne 1 4\ne 2 3\ne 2 4\ne 3 4\n' > "$out/k4.clq"
"$VERIFYBENCH" dimacs "$out/k4.clq" --algorithms bbmc,greedy --quiet --out "$out/d.json" >/dev/null
$py "$src/reports/plot_report.py" "$out/d.json" --out-dir "$out/plots" >/dev/null
is_png "$out/plots/d_dimacs.png"; is_pdf "$out/plots/d_dimacs.pdf"
$py "$src/reports/summarize.py" "$out/d.json" > "$out/d.md"
grep -q '^| bbmc | 1 | 1 | ' "$out/d.md" ||
  { echo "summarize lost the DIMACS row"; exit 1; }
# Mixed kinds are refused with a message.
if $py "$src/reports/plot_report.py" "$out/r.json" "$out/d.json" 2>"$out/err"; then
  echo "mixed report kinds accepted"; exit 1
fi
grep -q "mix kinds" "$out/err" || { cat "$out/err"; exit 1; }
# A malformed report must fail with a message, not a traceback.
echo '{"schema_version": 1}' > "$out/bad.json"
if $py "$src/reports/plot_report.py" "$out/bad.json" --out-dir "$out" 2>"$out/err"; then
  echo "malformed report accepted"; exit 1
fi
grep -q "bad.json" "$out/err" && ! grep -q Traceback "$out/err" ||
  { echo "error does not name the file:"; cat "$out/err"; exit 1; }
# The table scripts on the same report: one row per solver and a cell per ratio, or per trial row.
$py "$src/reports/robustness_table.py" "$out/r.json" > "$out/rob.md"
grep -q '^| clique | ' "$out/rob.md" && grep -q '^| ransac | ' "$out/rob.md" &&
  grep -q 'uniform, 3D, n = 60' "$out/rob.md" || { echo "robustness table:"; cat "$out/rob.md"; exit 1; }
$py "$src/reports/summarize.py" "$out/r.json" > "$out/summary.md"
grep -q '| synthetic | 2 | 60 | 0.90 | clique |' "$out/summary.md" || { echo "summarize lost a row"; exit 1; }
# CSV: a header and one line per aggregate (2 dims x 2 ratios x 2 solvers), read back by pandas.
$py "$src/reports/summarize.py" --format csv "$out/r.json" > "$out/summary.csv"
$py -c "import pandas as pd, sys; f = pd.read_csv(sys.argv[1]); assert len(f) == 8, len(f); \
assert {'report', 'solver', 'success_rate'} <= set(f.columns), list(f.columns)" "$out/summary.csv"
if $py "$src/reports/real_table.py" "$out/missing.json" 2>"$out/err"; then
  echo "missing report accepted"; exit 1
fi
grep -q "real_table: error: .*missing.json" "$out/err" || { cat "$out/err"; exit 1; }
# Accept decisions: a sweep with negative twins scored per solver and rule, with its ROC / PR plot.
"$VERIFYBENCH" sweep --dim 3 --n 60 --outliers 0.5 --trials 3 --negatives --quiet \
  --out "$out/neg.json" >/dev/null
$py "$src/reports/decisions.py" "$out/neg.json" --rows --plot "$out/plots/decisions.png" > "$out/dec.md"
grep -q '^| clique | p < 0.001 | ' "$out/dec.md" && grep -q '^| clique | count >= 5/10 | ' "$out/dec.md" ||
  { echo "decisions table:"; cat "$out/dec.md"; exit 1; }
is_png "$out/plots/decisions.png"
# With pose priors (positives only: a negative twin has no motion to draw one around), --rows
# shows each row's prior_d2 as the report holds it, and "-" where there is none.
"$VERIFYBENCH" sweep --dim 3 --n 60 --outliers 0.5 --trials 2 --negatives --prior-rot-deg 1 \
  --prior-trans 0.3 --quiet --out "$out/negp.json" >/dev/null
$py "$src/reports/decisions.py" "$out/negp.json" --rows > "$out/decp.md"
$py - "$out/negp.json" "$out/decp.md" <<'PY' || { echo "decisions --rows lost prior_d2"; cat "$out/decp.md"; exit 1; }
import json, sys
rows = json.load(open(sys.argv[1]))["results"]
lines = [l.split("|") for l in open(sys.argv[2]) if l.startswith("| ") and " prior d^2 " not in l
         and ("| positive |" in l or "| negative |" in l)]
assert len(lines) == len(rows) > 0, (len(lines), len(rows))
shown = sorted(c[9].strip() for c in lines)
want = sorted("-" if r["prior_d2"] is None else format(r["prior_d2"], ".3g") for r in rows)
assert shown == want, (shown, want)
assert "-" in shown and any(s != "-" for s in shown), shown
PY
# The runner-up test's cell: a repetitive corridor's negatives (shifted copies, no true motion)
# are rejected as aliases (the test is on by default without clouds), "(alias)" with the
# runner-up's score and p; without the test, "-".
"$VERIFYBENCH" sweep --dim 3 --n 200 --outliers 0.5 --trials 2 --negatives --generator repetitive \
  --solvers clique --quiet --out "$out/alias.json" >/dev/null
$py "$src/reports/decisions.py" "$out/alias.json" --rows > "$out/alias.md"
$py - "$out/alias.json" "$out/alias.md" <<'PY' || { echo "decisions --rows runner-up"; cat "$out/alias.md"; exit 1; }
import json, sys
rows = json.load(open(sys.argv[1]))["results"]
neg = [r for r in rows if r["expected"] == "negative"]
assert neg and all(r["runner_up_ambiguous"] and not r["accepted"] for r in neg), neg
cells = [l.split("|")[10].strip() for l in open(sys.argv[2]) if "| negative |" in l]
assert len(cells) == len(neg) and all(c.endswith("(alias)") and "rivals" in c for c in cells), cells
PY
# The dense check's cell (a build with the front end: `run --dense-overlap`): two dumps with the same matches (40 consistent with a 1 m shift among 40
# drawn at random) and kept clouds: in one the target cloud is the source's under the shift
# (overlap near 1, kept), in the other it lies 50 m away (the rule accepts the matches, the
# clouds refute them: "(refuted)"); a dump without clouds shows "-".
if "$VERIFYBENCH" run --help | grep -q -- "--dense-overlap"; then
$py - "$out" <<'PY'
import json, os, random, struct, sys
random.seed(7)
out = sys.argv[1]
cloud = []
for _ in range(3000):  # three orthogonal planes of a 20 m corner
    a, b, k = random.uniform(0, 20), random.uniform(0, 20), random.randrange(3)
    cloud.append([(a, b, 0.0), (a, 0.0, b), (0.0, a, b)][k])
pairs = [(p, (p[0] + 1.0, p[1], p[2])) for p in random.sample(cloud, 40)]
pairs += [(random.choice(cloud), tuple(random.uniform(0, 20) for _ in range(3))) for _ in range(40)]
def write(name, target, keep):
    d = os.path.join(out, name)
    os.makedirs(d)
    meta = {"format": "verifybench-dump", "version": 1, "dim": 3, "count": len(pairs),
            "columns": ["xs", "ys", "zs", "xt", "yt", "zt"], "T_target_source": None,
            "label_threshold": None, "provenance": {}}
    if keep:
        for side, pts in (("source", cloud), ("target", target)):
            with open(os.path.join(d, side + "_cloud.bin"), "wb") as f:
                for p in pts:
                    f.write(struct.pack("<4f", p[0], p[1], p[2], 0.0))
        meta["clouds"] = {"source": "source_cloud.bin", "target": "target_cloud.bin",
                          "points": [len(cloud), len(target)], "voxel_m": 0}
    json.dump(meta, open(os.path.join(d, "dump.json"), "w"))
    with open(os.path.join(d, "matches.tsv"), "w") as f:
        f.write("xs\tys\tzs\txt\tyt\tzt\n")
        for m, q in pairs:
            f.write("\t".join(f"{v:.9g}" for v in (*m, *q)) + "\n")
write("kept", [(p[0] + 1.0, p[1], p[2]) for p in cloud], True)
write("apart", [(p[0] + 50.0, p[1], p[2]) for p in cloud], True)
write("bare", [], False)
PY
for d in kept apart bare; do
  expected=negative; [ $d = kept ] && expected=positive
  "$VERIFYBENCH" run --dump "$out/$d" --solvers clique --eps 0.2 --expected $expected --quiet \
    --out "$out/dense_$d.json" >/dev/null
done
$py "$src/reports/decisions.py" "$out/dense_kept.json" "$out/dense_apart.json" "$out/dense_bare.json" \
  --rows > "$out/dense.md"
$py - "$out/dense.md" <<'PY' || { echo "decisions --rows dense check"; cat "$out/dense.md"; exit 1; }
import sys
cells = {l.split("|")[1].strip(): (l.split("|")[11].strip(), l.split("|")[12].strip())
         for l in open(sys.argv[1]) if l.startswith("| ") and ("| positive |" in l or "| negative |" in l)}
kept, apart, bare = cells["kept"], cells["apart"], cells["bare"]
assert float(kept[0]) > 0.9 and kept[1] == "accept", kept
assert apart[0].endswith("(refuted)") and float(apart[0].split()[0]) < 0.1 and apart[1] == "reject", apart
assert bare == ("-", "accept"), bare
PY
fi
if $py "$src/reports/decisions.py" "$out/d.json" 2>"$out/err"; then
  echo "a report without expected decisions was scored"; exit 1
fi
grep -q "decisions: error: no rows with an expected decision" "$out/err" || { cat "$out/err"; exit 1; }
# Every script answers --help.
for s in plot_report summarize robustness_table real_table check_schema decisions; do
  $py "$src/reports/$s.py" --help > "$out/help"
  grep -q "usage: $s.py" "$out/help" || { echo "$s.py --help"; exit 1; }
done
# A dump report: solvers on a small text dump with a known motion (a shift of 1 m along x).
mkdir -p "$out/dump"
for i in 0 1 2 3 4 5 6 7 8 9; do echo "$i $((i * i % 7)) $((i % 3)) $((i + 1)) $((i * i % 7)) $((i % 3))"; done > "$out/dump/corr.txt"
printf '1 0 0 1\n0 1 0 0\n0 0 1 0\n0 0 0 1\n' > "$out/dump/GTmat.txt"
"$VERIFYBENCH" run --dump "$out/dump" --solvers clique,ransac --trials 2 --quiet --out "$out/run.json" >/dev/null
$py "$src/reports/plot_report.py" "$out/run.json" --out-dir "$out/plots" >/dev/null
is_png "$out/plots/run_dump.png"; is_pdf "$out/plots/run_dump.pdf"
# Every kind of report the CLI writes conforms to the checked-in schema, and a broken one does not.
$py "$src/reports/check_schema.py" "$out/r.json" "$out/rep.json" "$out/d.json" "$out/run.json" \
  "$out/neg.json" >"$out/schema"
$py -c "import json, sys; d = json.load(open(sys.argv[1])); d['results'][0]['status'] = 'fine'; \
json.dump(d, open(sys.argv[2], 'w'))" "$out/run.json" "$out/broken.json"
if $py "$src/reports/check_schema.py" "$out/broken.json" >"$out/schema"; then
  echo "a report with status 'fine' passed the schema"; exit 1
fi
# The clique table: the dump's 10 rows are one shift, so its clique number is 10, and both exact
# algorithms prove it.
"$VERIFYBENCH" run --dump "$out/dump" --solvers clique-bbmc,clique-bbmcx --accept count --quiet \
  --out "$out/cliques.json" >/dev/null
$py "$src/reports/clique_table.py" --limit 5 "$out/cliques.json" >"$out/cliques.md"
grep -Eq '^\| cliques \|  \| 10 \| 10 \| (\*\*)?[0-9.]+(\*\*)? \| (\*\*)?[0-9.]+(\*\*)? \|$' "$out/cliques.md" ||
  { cat "$out/cliques.md"; exit 1; }
grep -q '^| \*\*proved\*\* | | | | 1 of 1 | 1 of 1 |' "$out/cliques.md" || { cat "$out/cliques.md"; exit 1; }
echo "plot_report: ok"
