#!/usr/bin/python3
"""Plots of a `verifybench loop` report (DIR/loop.json):

  DIR/loop_trajectory_<solver>.png  ground truth, odometry, the pose graph with the solver's loops
                                    (plain and robust), accepted loop edges green when correct and
                                    red when false
  DIR/loop_pr.png                   precision-recall of every solver over the accept count K
                                    (and over alpha where the calibrated rule ran)

usage: plot_loop.py DIR [--out-dir OUT]
"""
import argparse
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    try:
        with open(path) as f:
            report = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"plot_loop.py: cannot read {path}: {e}")
    if report.get("kind") != "loop" or "trajectories" not in report:
        sys.exit(f"plot_loop.py: {path} is not a loop report (kind 'loop' with trajectories)")
    return report


def xy(points):
    return [p[0] for p in points], [p[1] for p in points]


def plot_trajectory(report, solver, out):
    traj = report["trajectories"]
    maps = report["maps"]
    fig, ax = plt.subplots(figsize=(7, 7))
    ax.plot(*xy(traj["truth"]), color="black", lw=1.2, label="ground truth")
    ax.plot(*xy(traj["odometry"]), color="tab:orange", lw=1, label="odometry (drift)")
    ax.plot(*xy(traj[solver]), color="tab:blue", lw=1, label="with loops")
    ax.plot(*xy(traj[solver + "+robust"]), color="tab:purple", lw=1, ls="--",
            label="with loops, robust")
    anchors = {m["index"]: m["position_truth"] for m in maps}
    shown = set()
    for c in report["closures"]:
        if c["solver"] != solver or not c["accepted"]:
            continue
        a, b = anchors[c["query"]], anchors[c["match"]]
        kind = "correct loop" if c["correct"] else "false loop"
        ax.plot([a[0], b[0]], [a[1], b[1]], color="tab:green" if c["correct"] else "tab:red",
                lw=1.5, label=None if kind in shown else kind)
        shown.add(kind)
    s = next(r for r in report["summary"] if r["solver"] == solver)
    ax.set_title(f"{solver} ({s['pipeline']}): P {fmt(s['precision'])} R {fmt(s['recall'])}, "
                 f"APE {s['ape_without_m']:.2f} -> {s['ape_with_m']:.2f} m "
                 f"(robust {s['ape_with_robust_m']:.2f} m)", fontsize=9)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, f"loop_trajectory_{solver}.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def fmt(v):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.2f}"


def plot_pr(report, out):
    fig, ax = plt.subplots(figsize=(6, 5))
    for solver, curves in report["curves"].items():
        for kind, style in (("count", "-"), ("alpha", ":")):
            pts = [(p["recall"], p["precision"]) for p in curves.get(kind, [])
                   if p["precision"] is not None and p["recall"] is not None]
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], style, marker=".",
                        label=f"{solver} ({'min inliers K' if kind == 'count' else 'alpha'})")
    ax.set_xlabel("recall")
    ax.set_ylabel("precision")
    ax.set_xlim(0, 1.02)
    ax.set_ylim(0, 1.02)
    ax.set_title(f"loop closures: {len(report['true_closures'])} true, "
                 f"{len(report['candidates'])} candidates", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, "loop_pr.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dir", help="folder holding loop.json")
    parser.add_argument("--out-dir", help="where the PNGs go (default: DIR)")
    args = parser.parse_args()
    report = load(os.path.join(args.dir, "loop.json"))
    out = args.out_dir or args.dir
    os.makedirs(out, exist_ok=True)
    for row in report["summary"]:
        print(plot_trajectory(report, row["solver"], out))
    print(plot_pr(report, out))


if __name__ == "__main__":
    main()
