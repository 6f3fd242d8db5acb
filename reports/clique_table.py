#!/usr/bin/python3
"""One table of every clique algorithm on every corpus graph, from `verifybench run` reports whose
solvers are clique-<algorithm> (scripts/corpus-cliques): per graph, n, the clique number (the
largest clique any algorithm found, with "proved" when one proved it), and for each algorithm the
median graph + search time in ms when it proved the maximum, else ">LIMIT s (found/upper bound)".
A last line counts the graphs each algorithm proved and the median time over the graphs all of
them proved.

usage: clique_table.py [--manifest MANIFEST.tsv] [--limit S] REPORT.json...
"""
import argparse
import csv
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_io  # noqa: E402


def main(argv):
    ap = argparse.ArgumentParser(prog="clique_table.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("reports", nargs="+", metavar="REPORT.json")
    ap.add_argument("--manifest", help="corpus MANIFEST.tsv: the graphs' expected decision")
    ap.add_argument("--limit", type=float, default=None, help="the per-search limit [s], for the table")
    args = ap.parse_args(argv)
    expected = {}
    if args.manifest:
        try:
            with open(args.manifest) as f:
                for row in csv.DictReader(f, delimiter="\t"):
                    expected[row["name"]] = row.get("expected", "")
        except (OSError, KeyError) as e:
            report_io.fail("clique_table", f"{args.manifest}: {e}")
    graphs, algorithms = [], []
    for path in args.reports:
        doc = report_io.load_report("clique_table", path)
        name = os.path.splitext(os.path.basename(path))[0]
        cells = {}
        for r in doc["results"]:
            if not r["solver"].startswith("clique-"):
                continue
            algorithm = r["solver"][len("clique-"):]
            if algorithm not in algorithms:
                algorithms.append(algorithm)
            cells.setdefault(algorithm, []).append(r)
        if cells:
            n = doc["results"][0]["n"]
            graphs.append((name, n, cells))
    limit = f">{args.limit:g} s" if args.limit else "limit"
    print("| graph | expected | n | omega | " + " | ".join(algorithms) + " |")
    print("|---|---|---|---|" + "---|" * len(algorithms))
    proved_count = {a: 0 for a in algorithms}
    all_proved_times = {a: [] for a in algorithms}
    for name, n, cells in sorted(graphs, key=lambda g: g[1]):
        best = max(r["inliers"] for rows in cells.values() for r in rows)
        proved_by = []
        row_text, times = [], {}
        for a in algorithms:
            rows = cells.get(a, [])
            if not rows:
                row_text.append("-")
                continue
            r = rows[0]
            proved = r["status"] != "error" and r["omega_upper_bound"] == r["inliers"]
            if r["status"] == "error":
                row_text.append("error")
            elif proved:
                t = statistics.median(x["graph_ms"] + x["search_ms"] for x in rows)
                times[a] = t
                proved_by.append(a)
                proved_count[a] += 1
                row_text.append(f"{t:.0f}" if t >= 10 else f"{t:.1f}")
            else:
                ub = r["omega_upper_bound"]
                row_text.append(f"{limit} ({r['inliers']}/{ub if ub is not None else '?'})")
        if times:
            fastest = min(times.values())
            row_text = [f"**{c}**" if a in times and times[a] == fastest else c
                        for a, c in zip(algorithms, row_text)]
        if len(proved_by) == len(algorithms):
            for a in algorithms:
                all_proved_times[a].append(times[a])
        omega = f"{best}" + ("" if proved_by else " (unproved)")
        print(f"| {name} | {expected.get(name, '')} | {n} | {omega} | " + " | ".join(row_text) + " |")
    common = len(next(iter(all_proved_times.values()), []))
    print("| **proved** | | | | " + " | ".join(f"{proved_count[a]} of {len(graphs)}" for a in algorithms) + " |")
    print(f"| **median ms, the {common} graphs all proved** | | | | " +
          " | ".join(f"{statistics.median(all_proved_times[a]):.0f}" if all_proved_times[a] else "-"
                     for a in algorithms) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
