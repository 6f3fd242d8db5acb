#!/usr/bin/python3
"""Plots of verifybench reports, as PNG and PDF.

Sweep reports: DIR/<stem>_success.{png,pdf} (success rate vs outlier ratio, 95% Wilson intervals)
and DIR/<stem>_time.{png,pdf} (median time per solve, log scale, quartile band), one panel per
(generator, dimension), one curve per (solver, n). Several sweeps (other n, other generators) are
drawn together; each panel is titled from its own report.
Dump reports (`verifybench run`): DIR/<stem>_dump.{png,pdf}: time per solve (median, quartiles)
and inliers per solver, for each dump.
DIMACS reports: DIR/<stem>_dimacs.{png,pdf}: search time per graph and algorithm (log scale);
hatched bars did not prove optimality.
The stem is the first report's file name unless --name gives one; DIR (--out-dir) is created.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_io  # noqa: E402

TOOL = "plot_report"
MARKERS = "osD^vP*X"
LINESTYLES = ["-", "--", "-.", ":"]


def fail(msg):
    report_io.fail(TOOL, msg)


def colours(names):
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    if len(names) > len(cycle):  # 20 distinct colours before any repeats
        cycle = [matplotlib.colormaps["tab20"](i) for i in range(20)]
    return {s: cycle[i % len(cycle)] for i, s in enumerate(sorted(names))}


def save(fig, out_dir, stem, suffix):
    """Writes PNG and PDF through temporary names, so no half-written plot has the final name."""
    paths = []
    for ext in ("png", "pdf"):
        path = os.path.join(out_dir, f"{stem}_{suffix}.{ext}")
        tmp = f"{path}.tmp.{ext}"
        fig.savefig(tmp, dpi=110)
        os.replace(tmp, path)
        paths.append(path)
    plt.close(fig)
    return paths


def log_axis(ax):
    """Log scale labelled at 1, 2 and 5 of every decade, not only at the decades."""
    ax.set_yscale("log")
    plain = FuncFormatter(lambda v, _: f"{v:g}")
    ax.yaxis.set_major_locator(LogLocator(base=10))
    ax.yaxis.set_major_formatter(plain)
    ax.yaxis.set_minor_locator(LogLocator(base=10, subs=(2, 5)))
    ax.yaxis.set_minor_formatter(plain)
    ax.tick_params(axis="y", which="minor", labelsize=7)
    ax.grid(True, which="both", alpha=0.3)


def sweep_series(reports):
    """{(generator, dim): {"doc": first report, "curves": {(solver, n): DataFrame by ratio}}}."""
    panels = {}
    for doc in reports:
        rows = report_io.results_frame(doc)
        rows = rows[rows["outlier_ratio"].notna()]
        if rows.empty:
            continue
        generator = doc["parameters"]["sweep"].get("generator", "uniform")
        if "expected" in rows.columns:  # negative twins (--negatives): their false accept rate
            negative = rows["expected"] == "negative"
            for (dim, solver, n, ratio), g in rows[negative].groupby(["dim", "solver", "n",
                                                                       "outlier_ratio"]):
                panel = panels.setdefault((generator, dim), {"doc": doc, "curves": {}, "fa": {}})
                panel.setdefault("fa", {}).setdefault((solver, n), []).append(
                    {"ratio": ratio, "fa": g["accepted"].astype(bool).mean()})
            rows = rows[~negative]
        for (dim, solver, n, ratio), g in rows.groupby(["dim", "solver", "n", "outlier_ratio"]):
            panel = panels.setdefault((generator, dim), {"doc": doc, "curves": {}})
            judged = g["success"].dropna()
            lo, hi = report_io.wilson_interval(judged.astype(bool).sum(), len(judged))
            times = g["time_ms"]
            panel["curves"].setdefault((solver, n), []).append({
                "ratio": ratio,
                "success": judged.astype(bool).mean() if len(judged) else float("nan"),
                "lo": lo, "hi": hi,
                "median": times.median(), "q1": times.quantile(0.25), "q3": times.quantile(0.75)})
    return panels


def plot_sweeps(reports, out_dir, stem):
    panels = sweep_series(reports)
    if not panels:
        fail("no sweep points (rows with an outlier_ratio) in the sweep reports")
    keys = sorted(panels)
    solvers = sorted({s for p in panels.values() for s, _ in p["curves"]})
    sizes = sorted({n for p in panels.values() for _, n in p["curves"]})
    colour = colours(solvers)
    marker = {n: MARKERS[i % len(MARKERS)] for i, n in enumerate(sizes)}
    # Curves that coincide (two solvers at 100%) stay visible: each solver is shifted slightly
    # along x and drawn in its own line style.
    ratios = sorted({pt["ratio"] for p in panels.values() for c in p["curves"].values() for pt in c})
    step = min((b - a for a, b in zip(ratios, ratios[1:])), default=0.05)
    offset = {s: (i - (len(solvers) - 1) / 2) * step * 0.12 for i, s in enumerate(solvers)}
    style = {s: LINESTYLES[i % len(LINESTYLES)] for i, s in enumerate(solvers)}
    paths = []
    for kind in ("success", "time"):
        fig, axes = plt.subplots(1, len(keys), figsize=(7.5 * len(keys), 5.0), squeeze=False)
        for ax, key in zip(axes[0], keys):
            generator, dim = key
            doc = panels[key]["doc"]
            for (solver, n), pts in sorted(panels[key]["curves"].items()):
                pts = sorted(pts, key=lambda p: p["ratio"])
                x = [p["ratio"] + offset[solver] for p in pts]
                kw = {"color": colour[solver], "marker": marker[n], "linestyle": style[solver],
                      "label": f"{solver} (n={n})", "markersize": 4}
                if kind == "success":
                    y = [p["success"] for p in pts]
                    err = [[p["success"] - p["lo"] for p in pts], [p["hi"] - p["success"] for p in pts]]
                    ax.errorbar(x, y, yerr=err, capsize=2, elinewidth=0.8, **kw)
                else:
                    ax.plot(x, [p["median"] for p in pts], **kw)
                    ax.fill_between(x, [p["q1"] for p in pts], [p["q3"] for p in pts],
                                    color=colour[solver], alpha=0.15, linewidth=0)
            for (solver, n), pts in sorted(panels[key].get("fa", {}).items()):
                if kind != "success":
                    break
                pts = sorted(pts, key=lambda p: p["ratio"])
                ax.plot([p["ratio"] + offset.get(solver, 0) for p in pts], [p["fa"] for p in pts],
                        color=colour.get(solver, "k"), marker="x", linestyle=":", markersize=4,
                        label=f"{solver} (n={n}): false accepts of negatives")
            ax.set_xlabel("outlier ratio")
            if kind == "success":
                ax.set_ylabel("success rate (bars: 95% Wilson interval); dotted: false accepts")
                ax.set_ylim(-0.03, 1.03)
                ax.grid(True, alpha=0.3)
            else:
                ax.set_ylabel("time per solve [ms] (line: median, band: quartiles)")
                log_axis(ax)
            sweep = doc["parameters"]["sweep"]
            ax.set_title(f"{generator}, {dim}D, noise {sweep.get('noise')}, eps "
                         f"{doc['parameters'].get('eps')}, {sweep.get('trials')} trials/point",
                         fontsize=9)
            ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        fig.suptitle(report_io.success_criterion(reports[0]), fontsize=9)
        fig.tight_layout()
        paths += save(fig, out_dir, stem, kind)
    return paths


def plot_dumps(reports, out_dir, stem):
    import pandas as pd
    rows = pd.concat([report_io.results_frame(d) for d in reports], ignore_index=True)
    if rows.empty:
        fail("the dump reports hold no rows")
    datasets = sorted(rows["dataset"].unique())
    colour = colours(rows["solver"].unique())
    fig, axes = plt.subplots(len(datasets), 2, figsize=(12, 1.2 + 0.45 * rows["solver"].nunique()
                                                        * len(datasets)), squeeze=False)
    for (ax_t, ax_i), dataset in zip(axes, datasets):
        g = rows[rows["dataset"] == dataset]
        stats = g.groupby("solver").agg(median=("time_ms", "median"),
                                        q1=("time_ms", lambda t: t.quantile(0.25)),
                                        q3=("time_ms", lambda t: t.quantile(0.75)),
                                        inliers=("inliers", "median"),
                                        true_inliers=("true_inliers", "max"),
                                        success=("success", lambda s: s.dropna().astype(bool).mean()
                                                 if s.notna().any() else float("nan")))
        stats = stats.sort_values("median")
        y = range(len(stats))
        ax_t.barh(y, stats["median"], xerr=[stats["median"] - stats["q1"], stats["q3"] - stats["median"]],
                  color=[colour[s] for s in stats.index], capsize=2)
        ax_t.set_yticks(list(y), stats.index, fontsize=8)
        ax_t.set_xscale("log")
        ax_t.set_xlabel("time per solve [ms] (median, quartiles)")
        ax_t.set_title(os.path.basename(str(dataset).rstrip("/")), fontsize=9)
        ax_t.grid(True, which="both", axis="x", alpha=0.3)
        ax_i.barh(y, stats["inliers"], color=[colour[s] for s in stats.index])
        ax_i.set_yticks(list(y), [""] * len(stats))
        truth = stats["true_inliers"].dropna()
        if len(truth):
            ax_i.axvline(truth.iloc[0], color="k", linestyle="--", linewidth=0.8, label="true inliers")
            ax_i.legend(fontsize=7)
        for k, (_, s) in enumerate(stats.iterrows()):
            if s["success"] == s["success"]:  # not NaN
                ax_i.text(s["inliers"], k, f"  success {s['success']:.2f}", va="center", fontsize=7)
        ax_i.set_xlabel("selected inliers (median)")
    fig.suptitle(report_io.success_criterion(reports[0]), fontsize=9)
    fig.tight_layout()
    return save(fig, out_dir, stem, "dump")


def plot_dimacs(reports, out_dir, stem):
    import pandas as pd
    rows = pd.concat([report_io.results_frame(d) for d in reports], ignore_index=True)
    if rows.empty:
        fail("the DIMACS reports hold no rows")
    rows["graph_name"] = rows["graph"].map(lambda p: os.path.splitext(os.path.basename(p))[0])
    graphs = sorted(rows["graph_name"].unique())
    algorithms = sorted(rows["algorithm"].unique())
    colour = colours(algorithms)
    width = 0.8 / len(algorithms)
    fig, ax = plt.subplots(figsize=(max(8, 0.6 * len(graphs) * max(1, len(algorithms) / 2)), 5))
    for k, algorithm in enumerate(algorithms):
        g = rows[rows["algorithm"] == algorithm].set_index("graph_name")
        for i, graph in enumerate(graphs):
            if graph not in g.index:
                continue
            r = g.loc[[graph]].iloc[0]
            ax.bar(i + (k - (len(algorithms) - 1) / 2) * width, max(r["time_ms"], 1e-3), width,
                   color=colour[algorithm], hatch=None if r["status"] == "ok" else "//",
                   edgecolor="k" if r["status"] != "ok" else None, linewidth=0.4,
                   label=algorithm if i == 0 else None)
    ax.set_xticks(range(len(graphs)), graphs, rotation=60, ha="right", fontsize=8)
    ax.set_ylabel("search time [ms] (hatched: not proven optimal)")
    log_axis(ax)
    limit = reports[0].get("parameters", {}).get("time_limit_s")
    ax.set_title(f"maximum clique on DIMACS graphs, time limit {limit} s", fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    return save(fig, out_dir, stem, "dimacs")


def main():
    parser = argparse.ArgumentParser(prog="plot_report.py", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("reports", nargs="+", metavar="REPORT.json")
    parser.add_argument("--out-dir", default=None, help="default: the first report's folder")
    parser.add_argument("--name", default=None, help="file name stem of the plots")
    args = parser.parse_args()
    reports = [report_io.load_report(TOOL, p) for p in args.reports]
    kinds = {report_io.report_kind(d) for d in reports}
    if len(kinds) != 1:
        fail(f"the reports mix kinds ({', '.join(sorted(kinds))}); plot each kind on its own")
    out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.reports[0]))
    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as e:
        fail(f"{out_dir}: {e}")
    stem = args.name or os.path.splitext(os.path.basename(args.reports[0]))[0]
    plot = {"sweep": plot_sweeps, "run": plot_dumps, "dimacs": plot_dimacs}[kinds.pop()]
    for path in plot(reports, out_dir, stem):
        print(path)


if __name__ == "__main__":
    main()
