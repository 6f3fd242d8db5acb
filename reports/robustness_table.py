#!/usr/bin/python3
"""Compact robustness tables from verifybench sweep reports.

For each (generator, dimension, n, pose prior) found in the reports' aggregates, one markdown table: a row per
solver, a column per outlier ratio, each cell "success rate / median time in ms" (success as the
report defines it; "-" when the point has no ground truth), then "FA x" when the sweep drew
negative twins (--negatives): the rate at which they were falsely accepted. Nothing is
recomputed.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_io  # noqa: E402


def fail(msg):
    report_io.fail("robustness_table", msg)


def main(argv):
    paths = report_io.parser("robustness_table", __doc__).parse_args(argv).reports
    groups, negatives = {}, {}
    for path in paths:
        doc = report_io.load_report("robustness_table", path)
        sweep = doc.get("parameters", {}).get("sweep", {})
        prior = ""
        if sweep.get("prior_sigma_trans"):
            prior = (f", pose prior {sweep.get('prior_sigma_rot_deg', 0):g} deg / "
                     f"{sweep['prior_sigma_trans']:g} m")
        for a in doc.get("aggregates", []):
            if a.get("outlier_ratio") is None:
                continue
            key = (a.get("generator") or "uniform", a["dim"], a["n"], prior)
            cells = groups.setdefault(key, {}).setdefault(a["solver"], {})
            if a.get("expected") == "negative":
                negatives.setdefault(key, {}).setdefault(a["solver"], {})[a["outlier_ratio"]] = a
            else:
                cells[a["outlier_ratio"]] = a
    if not groups:
        fail("no sweep aggregates in the reports")
    for (gen, dim, n, prior), by_solver in groups.items():
        ratios = sorted({r for cells in by_solver.values() for r in cells})
        print(f"\n**{gen}, {dim}D, n = {n}{prior}** (success / median ms)\n")
        print("| solver | " + " | ".join(f"{r:g}" for r in ratios) + " |")
        print("|---|" + "---|" * len(ratios))
        for solver, cells in by_solver.items():
            row = []
            for r in ratios:
                a = cells.get(r)
                if a is None:
                    row.append("")
                    continue
                s = a.get("success_rate")
                t = a.get("median_time_ms")
                limited = " (T)" if a.get("time_limited") else ""
                neg = negatives.get((gen, dim, n, prior), {}).get(solver, {}).get(r)
                fa = f", FA {neg['accept_rate']:.2f}" if neg else ""
                row.append(("-" if s is None else f"{s:.2f}") + " / " +
                           ("-" if t is None else f"{t:.3g}") + limited + fa)
            print(f"| {solver} | " + " | ".join(row) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
