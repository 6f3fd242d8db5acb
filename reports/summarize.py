#!/usr/bin/python3
"""Tables of the aggregates of verifybench reports, as markdown or CSV.

One row per aggregate (solver x setting): dataset, dim, n, outlier ratio, solver, trials, success
rate, accept rate, median and p90 time, median inliers and median errors. Columns come from the
reports only; nothing is recomputed. --format csv writes every aggregate field, one row each, with
the report's path in a first column (pandas: read_csv).
A loop report (loop.json) gives one row per solver: the paper's Table I (TP, FP, FN, precision,
recall, F1) and Table II (APE rmse without loops, with them, with them under the robust kernel).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_io  # noqa: E402
from report_io import fmt  # noqa: E402

TOOL = "summarize"


def main(argv):
    parser = report_io.parser(TOOL, __doc__)
    parser.add_argument("--format", choices=("md", "csv"), default="md",
                        help="markdown table (default) or CSV of every aggregate field")
    args = parser.parse_args(argv)
    docs = [(path, report_io.load_report(TOOL, path, loop=True)) for path in args.reports]
    kinds = {report_io.report_kind(doc) == "loop" for _, doc in docs}
    if len(kinds) > 1:
        report_io.fail(TOOL, "the reports mix loop reports with others; summarize each kind on its own")
    if kinds == {True}:
        loop_table(docs, args.format)
        return
    if args.format == "csv":
        import pandas as pd
        frames = []
        for path, doc in docs:
            f = report_io.aggregates_frame(doc)
            if "decisions" in f.columns:  # nested counts -> decisions_tp, decisions_fp, ...
                nested = pd.json_normalize(f.pop("decisions").tolist()).add_prefix("decisions_")
                f = pd.concat([f, nested], axis=1)
            f.insert(0, "report", path)
            frames.append(f)
        pd.concat(frames, ignore_index=True).to_csv(sys.stdout, index=False)
        return
    aggs = [a for _, doc in docs for a in doc["aggregates"]]
    if aggs and "solver" not in aggs[0]:  # a DIMACS report: one row per algorithm
        print("| algorithm | graphs | proven | correct (proved) | found, unproved | wrong | total ms | median ms |")
        print("|---|---|---|---|---|---|---|---|")
        for a in aggs:
            print(f"| {a.get('algorithm')} | {a.get('graphs')} | {a.get('proven')} | {a.get('correct')} "
                  f"| {a.get('found_unproved', '-')} | {a.get('wrong', '-')} "
                  f"| {fmt(a.get('total_time_ms'), '.2f')} | {fmt(a.get('median_time_ms'), '.2f')} |")
        return
    print("| dataset | dim | n | outliers | solver | expected | trials | success | accepted | median ms "
          "| p90 ms | median inliers | median rot err (deg) | median trans err |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for a in aggs:
        print(f"| {a['dataset'].split('/')[-1]} | {a['dim']} | {a['n']} | {fmt(a['outlier_ratio'], '.2f')} "
              f"| {a['solver']} | {a.get('expected') or '-'} | {a['trials']} | {fmt(a['success_rate'], '.2f')} "
              f"| {fmt(a['accept_rate'], '.2f')} | {fmt(a['median_time_ms'], '.2f')} "
              f"| {fmt(a['p90_time_ms'], '.2f')} | {fmt(a['median_inliers'], '.0f')} "
              f"| {fmt(a['median_rotation_error_deg'], '.3f')} | {fmt(a['median_translation_error'], '.4f')} |")


LOOP_COLUMNS = [("pipeline", "pipeline", None), ("solver", "solver", None),
                ("accepted", "closures_accepted", None), ("TP", "tp", None), ("FP", "fp", None),
                ("FN", "fn", None), ("precision", "precision", ".3f"), ("recall", "recall", ".3f"),
                ("F1", "f1", ".3f"), ("APE without loops [m]", "ape_without_m", ".2f"),
                ("APE with loops [m]", "ape_with_m", ".2f"),
                ("APE with loops, robust [m]", "ape_with_robust_m", ".2f")]


def loop_table(docs, form):
    """One row per solver of each loop report (its 'summary'), as the report wrote it."""
    if form == "csv":
        import pandas as pd
        frames = []
        for path, doc in docs:
            f = pd.json_normalize(doc["summary"])
            f.insert(0, "report", path)
            frames.append(f)
        pd.concat(frames, ignore_index=True).to_csv(sys.stdout, index=False)
        return
    print("| report | " + " | ".join(name for name, _, _ in LOOP_COLUMNS) + " |")
    print("|---" * (len(LOOP_COLUMNS) + 1) + "|")
    for path, doc in docs:
        for s in doc["summary"]:
            cells = [str(s.get(key, "-")) if spec is None else fmt(s.get(key), spec)
                     for _, key, spec in LOOP_COLUMNS]
            print(f"| {path} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
