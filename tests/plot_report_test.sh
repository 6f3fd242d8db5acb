#!/usr/bin/env bash
# ctest: a small sweep report through reports/plot_report.py must give two PNG files, and
# through the table scripts the rows it holds.
set -euo pipefail
src=$1 out=$2
rm -rf "$out" && mkdir -p "$out"
"$VERIFYBENCH" sweep --dim 2,3 --n 60 --outliers 0.5,0.9 --trials 2 --quiet --out "$out/r.json" >/dev/null
/usr/bin/python3 "$src/reports/plot_report.py" "$out/r.json" --out-dir "$out"
for f in "$out/r_success.png" "$out/r_time.png"; do
  [ "$(head -c 8 "$f" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || { echo "not a PNG: $f"; exit 1; }
done
# A malformed report must fail with a message, not a traceback.
echo '{"schema_version": 1}' > "$out/bad.json"
if /usr/bin/python3 "$src/reports/plot_report.py" "$out/bad.json" --out-dir "$out" 2>"$out/err"; then
  echo "malformed report accepted"; exit 1
fi
grep -q "bad.json" "$out/err" || { echo "error does not name the file:"; cat "$out/err"; exit 1; }
# The table scripts on the same report: one row per solver and a cell per ratio, or per trial row.
/usr/bin/python3 "$src/reports/robustness_table.py" "$out/r.json" > "$out/rob.md"
grep -q '^| clique | ' "$out/rob.md" && grep -q '^| ransac | ' "$out/rob.md" &&
  grep -q 'uniform, 3D, n = 60' "$out/rob.md" || { echo "robustness table:"; cat "$out/rob.md"; exit 1; }
/usr/bin/python3 "$src/reports/summarize.py" "$out/r.json" > "$out/summary.md"
grep -q '| synthetic | 2 | 60 | 0.90 | clique |' "$out/summary.md" || { echo "summarize lost a row"; exit 1; }
if /usr/bin/python3 "$src/reports/real_table.py" "$out/missing.json" 2>"$out/err"; then
  echo "missing report accepted"; exit 1
fi
grep -q "real_table: error: .*missing.json" "$out/err" || { cat "$out/err"; exit 1; }
echo "plot_report: ok"
