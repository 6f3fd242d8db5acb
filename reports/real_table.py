#!/usr/bin/python3
"""Per-pair tables from `verifybench run` reports on real dumps.

For each report (one dump): a header with the dump's match count, labelled inliers and the
extraction counts when the dump has provenance, then one row per solver: accepted (of the trials),
median inliers, median rotation / translation error against the ground truth, median time.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_io  # noqa: E402
from report_io import fmt  # noqa: E402


def fail(msg):
    report_io.fail("real_table", msg)


def med(values):
    """Median of the non-null values (pandas), None when there are none."""
    import pandas as pd
    m = pd.Series([v for v in values if v is not None], dtype=float).median()
    return None if pd.isna(m) else m


def main(argv):
    paths = report_io.parser("real_table", __doc__).parse_args(argv).reports
    for path in paths:
        doc = report_io.load_report("real_table", path)
        run = doc.get("parameters", {}).get("run", {})
        rows = doc.get("results", [])
        if not rows:
            continue
        prov = run.get("dump_provenance") or {}
        counts = prov.get("counts", {})
        head = rows[0]
        line = f"\n**{run.get('dump', path).split('/')[-1]}**: {head['n']} matches"
        if head.get("true_inliers") is not None:
            line += f", {head['true_inliers']} labelled inliers"
            if run.get("label_threshold") is not None:
                line += f" (ground-truth residual < {run['label_threshold']:g} m)"
        if counts:
            s, t = counts.get("source", {}), counts.get("target", {})
            line += (f"; keypoints {s.get('keypoints', 0):.0f} / {t.get('keypoints', 0):.0f}, "
                     f"descriptors {s.get('descriptors', 0):.0f} / {t.get('descriptors', 0):.0f}")
        pipe = prov.get("pipeline", {}).get("name")
        if pipe:
            line += f"; {pipe}"
        if run.get("prior_sigma_trans"):
            line += (f"; **pose prior** {run.get('prior_sigma_rot_deg', 0):g} deg / "
                     f"{run['prior_sigma_trans']:g} m per axis")
        print(line + "\n")
        print("| solver | accepted | inliers | precision | rot. err [deg] | trans. err [m] | time [ms] |")
        print("|---|---|---|---|---|---|---|")
        by = {}
        for r in rows:
            by.setdefault(r["solver"], []).append(r)
        for solver, rs in by.items():
            acc = sum(1 for r in rs if r["accepted"])
            print(f"| {solver} | {acc}/{len(rs)} | {fmt(med([r['inliers'] for r in rs]), '.0f')} | "
                  f"{fmt(med([r.get('inlier_precision') for r in rs]), '.2f')} | "
                  f"{fmt(med([r.get('rotation_error_deg') for r in rs]), '.2f')} | "
                  f"{fmt(med([r.get('translation_error') for r in rs]), '.2f')} | "
                  f"{fmt(med([r['time_ms'] for r in rs]), '.3g')} |")


if __name__ == "__main__":
    main(sys.argv[1:])
