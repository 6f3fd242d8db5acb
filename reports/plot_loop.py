#!/usr/bin/python3
"""Plots of a `verifybench loop` report (DIR/loop.json), as PNG and PDF:

  DIR/loop_trajectory_<solver>.{png,pdf}  ground truth, odometry, the pose graph with the solver's
                                    loops (plain and robust), and on top of them every accepted
                                    loop edge between the two maps' true anchors, green when
                                    correct and red when false: drawn as an arc with a dot at each
                                    end and a minimum drawn size, so a closure between maps at the
                                    same place (a revisit) stays visible
  DIR/loop_pr.{png,pdf}             precision-recall of every solver over the accept count K (and
                                    over alpha where the calibrated rule ran), each solver's
                                    operating point (the rule as run) marked

Titles name the accept rule and what makes a closure correct.

usage: plot_loop.py DIR [--out-dir OUT]

From Python, build_trajectory(report, solver) and build_pr(report) return the matplotlib Figure.
"""
import argparse
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_style as common  # noqa: E402

MIN_EDGE = 0.03  # the smallest drawn loop edge, as a fraction of the trajectory's extent
EDGE_COLOUR = {True: "tab:green", False: "tab:red"}


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


def fmt(v):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.2f}"


def loop_dim(report):
    pipeline = report.get("parameters", {}).get("loop", {}).get("frontend", {}).get("pipeline")
    if pipeline is None and report.get("summary"):
        pipeline = report["summary"][0].get("pipeline")
    return 2 if pipeline == "2d" else 3


def correct_text(report):
    """What makes an accepted closure correct, from the report's loop parameters."""
    loop = report.get("parameters", {}).get("loop", {})
    g = lambda key: f"{loop[key]:g}" if isinstance(loop.get(key), (int, float)) else "?"  # noqa: E731
    return (f"correct: a true pair (maps >= {g('min_map_gap')} apart, anchors <= "
            f"{g('gt_max_distance_m')} m apart, overlap > {g('gt_overlap')}), translation error "
            f"<= {g('pose_tolerance_m')} m")


def edge_path(a, b, min_len, centre):
    """Points of the drawn loop edge from a to b: a cubic arc bulging away from `centre` (the
    trajectory's middle), at least `min_len` high, so an edge along the path or between two
    coincident anchors (a revisit) leaves the trajectory and stays visible."""
    a, b = np.asarray(a[:2], float), np.asarray(b[:2], float)
    d = b - a
    length = float(np.hypot(*d))
    t = d / length if length > 1e-9 else np.array([1.0, 0.0])
    n = np.array([-t[1], t[0]])
    mid = 0.5 * (a + b)
    if np.dot(n, mid - centre) < 0:
        n = -n
    h = max(0.3 * length, min_len)
    w = 0.6 * h if length < min_len else 0.0  # a short edge opens into a loop
    c1, c2 = a + n * h - t * w, b + n * h + t * w
    s = np.linspace(0.0, 1.0, 40)[:, None]
    pts = ((1 - s) ** 3) * a + 3 * ((1 - s) ** 2) * s * c1 + 3 * (1 - s) * s ** 2 * c2 + s ** 3 * b
    return pts[:, 0], pts[:, 1]


def build_trajectory(report, solver):
    traj = report["trajectories"]
    maps = report["maps"]
    fig, ax = plt.subplots(figsize=(7.2, 7.4))
    ax.plot(*xy(traj["truth"]), color="black", lw=1.2, label="ground truth", zorder=2)
    ax.plot(*xy(traj["odometry"]), color="tab:orange", lw=1, label="odometry (drift)", zorder=2)
    ax.plot(*xy(traj[solver]), color="tab:blue", lw=1, label="with loops", zorder=2)
    ax.plot(*xy(traj[solver + "+robust"]), color="tab:purple", lw=1, ls="--",
            label="with loops, robust", zorder=2)
    truth = np.asarray([p[:2] for p in traj["truth"]], float)
    extent = float(max(np.ptp(truth[:, 0]), np.ptp(truth[:, 1]), 1.0))
    centre = 0.5 * (truth.min(axis=0) + truth.max(axis=0))
    anchors = {m["index"]: m["position_truth"] for m in maps}
    accepted = [c for c in report["closures"] if c["solver"] == solver and c["accepted"]]
    counts = {True: 0, False: 0}
    # false edges last, so they are on top
    for c in sorted(accepted, key=lambda c: bool(c["correct"]), reverse=True):
        a, b = anchors[c["query"]], anchors[c["match"]]
        ok = bool(c["correct"])
        counts[ok] += 1
        colour = EDGE_COLOUR[ok]
        z = 5 if ok else 6
        (arc,) = ax.plot(*edge_path(a, b, MIN_EDGE * extent, centre), color=colour, lw=1.8,
                         zorder=z, solid_capstyle="round")
        arc.set_gid(f"edge:{'correct' if ok else 'false'}:{c['query']}:{c['match']}")
        (ends,) = ax.plot([a[0], b[0]], [a[1], b[1]], "o", color=colour, ms=5, mec="k", mew=0.5,
                          zorder=z + 0.5)
        ends.set_gid(f"ends:{'correct' if ok else 'false'}:{c['query']}:{c['match']}")
    handles, labels = ax.get_legend_handles_labels()
    for ok in (True, False):
        handles.append(Line2D([], [], color=EDGE_COLOUR[ok], lw=1.8, marker="o", ms=5, mec="k",
                              mew=0.5))
        labels.append(f"{'correct' if ok else 'false'} loop ({counts[ok]} of {len(accepted)} "
                      "accepted)")
    handles.append(Line2D([], [], linestyle="none"))
    labels.append(f"loop edges: arcs between the maps' true anchors\n(dots), at least "
                  f"{MIN_EDGE * extent:.0f} m high")
    s = next(r for r in report["summary"] if r["solver"] == solver)
    ax.set_title(f"{solver} ({s['pipeline']}): P {fmt(s['precision'])} R {fmt(s['recall'])}, "
                 f"APE {s['ape_without_m']:.2f} -> {s['ape_with_m']:.2f} m "
                 f"(robust {s['ape_with_robust_m']:.2f} m)\n"
                 f"{common.accept_rule_text(report.get('parameters', {}), loop_dim(report))}\n"
                 f"{correct_text(report)}", fontsize=8)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(handles, labels, fontsize=7, loc="best", framealpha=0.85)
    fig.tight_layout()
    return fig


def build_pr(report):
    """Precision-recall over K (and alpha), one curve per solver and rule, the operating points
    (each solver's summary under the rule as run) marked."""
    fig, ax = plt.subplots(figsize=(common.PANEL_W + 2.6, common.PANEL_H + 1.0))
    solvers = list(report["curves"])
    params = report.get("parameters", {})
    markers = "o^v<>"
    for k, solver in enumerate(solvers):
        curves = report["curves"][solver]
        colour = f"C{k}"
        tr = common.nudge(fig, ax, k, len(solvers))
        for kind, style in (("count", "-"), ("alpha", ":")):
            pts = [(p["recall"], p["precision"]) for p in curves.get(kind, [])
                   if p["precision"] is not None and p["recall"] is not None]
            if pts:
                (line,) = ax.plot([p[0] for p in pts], [p[1] for p in pts], style, color=colour,
                                  marker=markers[k % len(markers)], ms=3.5, transform=tr,
                                  label=f"{solver}: over {'K (inliers >= K)' if kind == 'count' else 'alpha'}")
                line.set_gid(f"pr:{kind}:{solver}")
        s = next((r for r in report["summary"] if r["solver"] == solver), None)
        if s and s.get("precision") is not None and s.get("recall") is not None:
            (op,) = ax.plot([s["recall"]], [s["precision"]], "*", color=colour, ms=14, mec="k",
                            mew=0.8, zorder=5, transform=tr,
                            label=f"{solver}: as run (P {fmt(s['precision'])}, R {fmt(s['recall'])})")
            op.set_gid(f"operating:{solver}")
    ax.set_xlabel("recall")
    ax.set_ylabel("precision")
    ax.set_xlim(-0.02, 1.02)
    ax.set_ylim(-0.02, 1.04)
    ax.grid(alpha=0.3)
    ax.set_title(f"loop closures: {len(report['true_closures'])} true, "
                 f"{len(report['candidates'])} candidates; as run: "
                 f"{common.accept_rule_text(params, loop_dim(report))}\n{correct_text(report)}",
                 fontsize=7.5)
    handles, labels = ax.get_legend_handles_labels()
    handles.append(Line2D([], [], linestyle="none"))
    labels.append(f"star: the operating point\nsolvers drawn {common.OFFSET_PT:g} pt apart\n"
                  "so equal curves stay visible")
    ax.legend(handles, labels, fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0),
              borderaxespad=0.0)
    fig.tight_layout()
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dir", help="folder holding loop.json")
    parser.add_argument("--out-dir", help="where the plots go (default: DIR)")
    args = parser.parse_args()
    report = load(os.path.join(args.dir, "loop.json"))
    out = args.out_dir or args.dir
    os.makedirs(out, exist_ok=True)
    for row in report["summary"]:
        for path in common.save_figure(build_trajectory(report, row["solver"]),
                                       os.path.join(out, f"loop_trajectory_{row['solver']}")):
            print(path)
    for path in common.save_figure(build_pr(report), os.path.join(out, "loop_pr")):
        print(path)


if __name__ == "__main__":
    main()
