#!/usr/bin/python3
"""Tables of the aggregates of verifybench reports, as markdown or CSV.

One row per aggregate (solver x setting): dataset, dim, n, outlier ratio, solver, trials, success
rate, accept rate, median and p90 time, median inliers and median errors. Columns come from the
reports only; nothing is recomputed. --format csv writes every aggregate field, one row each, with
the report's path in a first column (pandas: read_csv).
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
    docs = [(path, report_io.load_report(TOOL, path)) for path in args.reports]
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


if __name__ == "__main__":
    main(sys.argv[1:])
