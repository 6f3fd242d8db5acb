#!/usr/bin/python3
"""Markdown tables from verifybench reports.

usage: summarize.py REPORT.json [REPORT.json ...]

One row per aggregate (solver x setting): dim, n, outlier ratio, solver, trials, success rate,
accept rate, median and p90 time, median inliers and median errors; then, for real dumps, one row
per result. Columns come from the reports only; nothing is recomputed.
"""
import sys

import report_io
from report_io import fmt


def fail(msg):
    report_io.fail("summarize", msg)


def main(paths):
    if not paths:
        fail("no report given (usage: summarize.py REPORT.json [...])")
    aggs = []
    for path in paths:
        doc = report_io.load_report("summarize", path)
        if "aggregates" not in doc:
            fail(f"{path}: no aggregates")
        aggs += doc["aggregates"]
    print("| dataset | dim | n | outliers | solver | trials | success | accepted | median ms | p90 ms "
          "| median inliers | median rot err (deg) | median trans err |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for a in aggs:
        print(f"| {a['dataset'].split('/')[-1]} | {a['dim']} | {a['n']} | {fmt(a['outlier_ratio'], '.2f')} "
              f"| {a['solver']} | {a['trials']} | {fmt(a['success_rate'], '.2f')} "
              f"| {fmt(a['accept_rate'], '.2f')} | {fmt(a['median_time_ms'], '.2f')} "
              f"| {fmt(a['p90_time_ms'], '.2f')} | {fmt(a['median_inliers'], '.0f')} "
              f"| {fmt(a['median_rotation_error_deg'], '.3f')} | {fmt(a['median_translation_error'], '.4f')} |")


if __name__ == "__main__":
    main(sys.argv[1:])
