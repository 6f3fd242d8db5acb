#!/usr/bin/python3
"""How well each statistic in the report rows separates good verifications from bad ones (issue #31,
item 1: measure before choosing an accept test). Reads `verifybench run` / `sweep` reports (rows
with an expected decision) and `verifybench loop` reports (every candidate row).

A row is good when accepting it would be right: in a loop report a correct closure (a true closure
whose motion is within the run's pose tolerance), in a run report a positive pair whose fitted
motion meets the report's success criterion. Every other row is bad: a negative pair, a positive
pair fitted with a wrong motion, a candidate that is no closure or a closure fitted wrongly. Error
rows and rows without inliers are left out.

The statistics, each oriented so that higher means more likely good (a row without one, e.g. no
p-value under the count rule, is left out of that statistic only):
    inliers          the solver's inlier count (the paper's count rule)
    -log10 p         the calibrated rule's p-value (pvalue rule rows)
    inlier ratio     inliers / n
    distinct         min(distinct source, distinct target points) among the inliers
    lever arm        the inlier set's spread (core/metrics.hpp: in 3D the root of its covariance's two
                     smallest eigenvalues, summed; in 2D the RMS distance to the centroid) [m]
    -prior d2        minus d^2 of the motion under the set's pose prior (sets with a prior)
    dense overlap    the loop's dense check: the maps' overlap after ICP (runs with it on)

Per statistic and solver: the good and bad rows it sees, the ROC area (Mann-Whitney: the chance a
good row scores above a bad one, ties counted half), and the share of good rows scoring above every
bad one (the recall a threshold keeps at no false accept; "-" without a bad row).

    /usr/bin/python3 reports/separation.py REPORT.json... [--per-report]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_io  # noqa: E402

TOOL = "separation"


def _p(row):
    p = row.get("p_value")
    if p is None:
        return None
    return -math.log10(max(p, 1e-300))


def _ratio(row):
    n = row.get("n")
    return row["inliers"] / n if n else None


def _neg(key):
    def get(row):
        v = row.get(key)
        return None if v is None else -v
    return get


def _dense(row):
    d = row.get("dense_check")
    return d.get("overlap") if isinstance(d, dict) else None


STATISTICS = [
    ("inliers", lambda r: r.get("inliers")),
    ("-log10 p", _p),
    ("inlier ratio", _ratio),
    ("distinct", lambda r: r.get("distinct_inliers")),
    ("lever arm", lambda r: r.get("lever_arm")),
    ("-prior d2", _neg("prior_d2")),
    ("dense overlap", _dense),
]


def label(row, loop):
    """True (good), False (bad) or None (left out) for one row."""
    if row.get("status") == "error" or not row.get("inliers"):
        return None
    if loop:
        return bool(row.get("correct"))
    expected = row.get("expected")
    if expected == "negative":
        return False
    if expected == "positive":
        return row.get("success") is True
    return None


def load(paths):
    """(source, solver, good, row) for every labelled row of the reports."""
    out = []
    for path in paths:
        doc = report_io.load_report(TOOL, path, loop=True)
        loop = doc.get("kind") == "loop"
        rows = doc["closures"] if loop else doc["results"]
        for row in rows:
            good = label(row, loop)
            if good is not None:
                out.append((path, row.get("solver", "?"), good, row))
    return out


def separation(good, bad):
    """(ROC area, share of `good` above max(`bad`)) of two lists of scores; None where undefined."""
    if not good or not bad:
        return None, None
    wins = 0.0
    for g in good:
        for b in bad:
            wins += 1.0 if g > b else 0.5 if g == b else 0.0
    top = max(bad)
    return wins / (len(good) * len(bad)), sum(1 for g in good if g > top) / len(good)


def table(rows):
    """Markdown lines: one row per statistic with any value."""
    lines = ["| statistic | good | bad | ROC area | recall at no false accept |",
             "|---|---|---|---|---|"]
    for name, get in STATISTICS:
        good = [v for ok, r in rows if ok for v in [get(r)] if v is not None and math.isfinite(v)]
        bad = [v for ok, r in rows if not ok for v in [get(r)] if v is not None and math.isfinite(v)]
        if not good and not bad:
            continue
        area, recall = separation(good, bad)
        lines.append(f"| {name} | {len(good)} | {len(bad)} | {report_io.fmt(area, '.3f')} | "
                     f"{report_io.fmt(recall, '.3f')} |")
    return lines


def main(argv):
    p = report_io.parser(TOOL, __doc__)
    p.add_argument("--per-report", action="store_true", help="one table per report and solver")
    args = p.parse_args(argv)
    data = load(args.reports)
    if not data:
        report_io.fail(TOOL, "no labelled row in the reports (run rows need an expected decision)")
    groups = {}
    for source, solver, good, row in data:
        key = (source if args.per_report else "all reports", solver)
        groups.setdefault(key, []).append((good, row))
    for (source, solver), rows in sorted(groups.items()):
        print(f"## {solver}, {source}\n")
        print("\n".join(table(rows)))
        print()


if __name__ == "__main__":
    main(sys.argv[1:])
