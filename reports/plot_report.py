#!/usr/bin/python3
"""Robustness curves from a verifybench sweep report.

usage: plot_report.py REPORT.json [REPORT.json ...] [--out-dir DIR] [--name STEM]

Writes DIR/<stem>_success.png (success rate vs outlier ratio) and DIR/<stem>_time.png (median
time vs outlier ratio, log scale, with the p90 as a dashed line), one panel per dimension and one
curve per solver and n. Several reports (e.g. sweeps at different n) are drawn together; the stem
is the first report's unless --name gives one. Runs on Debian's /usr/bin/python3 with python3-matplotlib.
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def fail(msg):
    print(f"plot_report: error: {msg}", file=sys.stderr)
    sys.exit(2)


def load(path):
    try:
        with open(path) as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        fail(f"{path}: {e}")
    if doc.get("schema_version") != 1:
        fail(f"{path}: schema_version {doc.get('schema_version')!r} is not 1")
    aggs = doc.get("aggregates")
    if not isinstance(aggs, list):
        fail(f"{path}: no 'aggregates' list")
    points = [a for a in aggs if a.get("outlier_ratio") is not None]
    if not points:
        fail(f"{path}: no sweep points (aggregates with an outlier_ratio)")
    for a in points:
        for key in ("solver", "dim", "n", "success_rate", "median_time_ms", "p90_time_ms"):
            if key not in a:
                fail(f"{path}: aggregate {a.get('solver')!r} lacks field {key!r}")
    return doc, points


def curves(points):
    """{dim: {(solver, n): [(ratio, aggregate), ...]}} sorted by ratio."""
    out = {}
    for a in points:
        out.setdefault(a["dim"], {}).setdefault((a["solver"], a["n"]), []).append((a["outlier_ratio"], a))
    for per_dim in out.values():
        for series in per_dim.values():
            series.sort(key=lambda p: p[0])
    return out


def title(doc, dim):
    sweep = doc.get("parameters", {}).get("sweep", {})
    eps = doc.get("parameters", {}).get("eps")
    generator = sweep.get("generator", "uniform")
    return (f"{generator}, {dim}D, noise {sweep.get('noise')}, eps {eps}, "
            f"{sweep.get('trials')} trials/point")



def plot(doc, points, out_dir, stem):
    by_dim = curves(points)
    dims = sorted(by_dim)
    # One colour per solver, one marker per n, so that curves stay apart when there are many.
    solvers = sorted({a["solver"] for a in points})
    sizes = sorted({a["n"] for a in points})
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    if len(solvers) > len(cycle):  # 20 distinct colours before any repeats
        cycle = [matplotlib.colormaps["tab20"](i) for i in range(20)]
    colour = {s: cycle[i % len(cycle)] for i, s in enumerate(solvers)}
    marker = {n: "osD^vP*X"[i % 8] for i, n in enumerate(sizes)}
    paths = []
    for kind in ("success", "time"):
        fig, axes = plt.subplots(1, len(dims), figsize=(7.5 * len(dims), 4.8), squeeze=False)
        for ax, dim in zip(axes[0], dims):
            for (solver, n), series in sorted(by_dim[dim].items()):
                x = [r for r, _ in series]
                label = f"{solver} (n={n})"
                style = {"color": colour[solver], "marker": marker[n]}
                if kind == "success":
                    ax.plot(x, [a["success_rate"] for _, a in series], label=label, **style)
                else:
                    ax.plot(x, [a["median_time_ms"] for _, a in series], label=label, **style)
                    ax.plot(x, [a["p90_time_ms"] for _, a in series], linestyle="--",
                            color=colour[solver], alpha=0.5)
            ax.set_xlabel("outlier ratio")
            if kind == "success":
                ax.set_ylabel("success rate")
                ax.set_ylim(-0.03, 1.03)
            else:
                ax.set_ylabel("time per solve [ms] (solid: median, dashed: p90)")
                ax.set_yscale("log")
            ax.set_title(title(doc, dim))
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        fig.tight_layout()
        path = os.path.join(out_dir, f"{stem}_{kind}.png")
        tmp = path + ".tmp.png"
        fig.savefig(tmp, dpi=110)
        plt.close(fig)
        os.replace(tmp, path)  # never leave half a PNG under the final name
        paths.append(path)
    return paths


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reports", nargs="+")
    parser.add_argument("--out-dir", default=None, help="default: the first report's folder")
    parser.add_argument("--name", default=None, help="file name stem of the PNGs")
    args = parser.parse_args()
    doc, points = load(args.reports[0])
    for path in args.reports[1:]:
        points += load(path)[1]
    out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.reports[0]))
    if not os.path.isdir(out_dir):
        fail(f"{out_dir}: output folder does not exist")
    stem = args.name or os.path.splitext(os.path.basename(args.reports[0]))[0]
    for path in plot(doc, points, out_dir, stem):
        print(path)


if __name__ == "__main__":
    main()
