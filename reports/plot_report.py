#!/usr/bin/python3
"""Plots of verifybench reports, as PNG and PDF.

Sweep reports: DIR/<stem>_success.{png,pdf} (success rate vs outlier ratio, 95% Wilson intervals,
and the false accept rate of the negative twins where the sweep drew them) and DIR/<stem>_time.
{png,pdf} (median time per solve, quartile band): a grid with one row per generator (per report
where two reports share a generator and a curve) and one column per dimension, shared axes, one
curve per (solver, n). Each panel's title names the accept rule, the figure's the success
criterion. Time axes are linear unless the medians span more than 100x (then log, and the axis
says so).
Dump reports (`verifybench run`): DIR/<stem>_dump.{png,pdf}: time per solve (median, quartiles;
linear unless the span exceeds 100x) and selected inliers per solver, one row per dump.
DIMACS reports: DIR/<stem>_dimacs.{png,pdf}: search time per graph and algorithm (log scale when
the times span more than 100x); hatched bars did not prove optimality.
The stem is the first report's file name unless --name gives one; DIR (--out-dir) is created.

From Python, build_sweep(reports, "success"|"time"), build_dump(reports) and build_dimacs(reports)
return the matplotlib Figure without saving it.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_io  # noqa: E402
from plot_style import (LINESTYLES, MARKERS, OFFSET_PT, PANEL_H, PANEL_W,  # noqa: E402
                        accept_rule_text, colours, count_threshold, log_axis, nudge, save_figure,
                        time_scale)

TOOL = "plot_report"


def fail(msg):
    report_io.fail(TOOL, msg)


# ---------------------------------------------------------------------------------------------
# Sweeps

def sweep_series(reports):
    """{(row, dim): {"doc", "generator", "curves": {(solver, n): [points]}, "fa": {...}}}, and the
    row order. A row is a generator; reports that share a generator and a (dim, solver, n) curve
    get a row each."""
    panels, rows_order, claimed = {}, [], {}
    for k, doc in enumerate(reports):
        rows = report_io.results_frame(doc)
        if "outlier_ratio" not in rows.columns:
            continue
        rows = rows[rows["outlier_ratio"].notna()]
        if rows.empty:
            continue
        generator = doc["parameters"]["sweep"].get("generator", "uniform")
        curves = {(d, s, n) for d, s, n in zip(rows["dim"], rows["solver"], rows["n"])}
        row = generator
        if claimed.get(generator, set()) & curves:
            row = f"{generator} (report {k + 1})"
        claimed.setdefault(row, set()).update(curves)
        if row not in rows_order:
            rows_order.append(row)
        if "expected" in rows.columns:  # negative twins (--negatives): their false accept rate
            negative = rows["expected"] == "negative"
            for (dim, solver, n, ratio), g in rows[negative].groupby(["dim", "solver", "n",
                                                                       "outlier_ratio"]):
                panel = panels.setdefault((row, dim), {"doc": doc, "generator": generator,
                                                       "curves": {}, "fa": {}})
                panel["fa"].setdefault((solver, n), []).append(
                    {"ratio": ratio, "fa": g["accepted"].astype(bool).mean()})
            rows = rows[~negative]
        for (dim, solver, n, ratio), g in rows.groupby(["dim", "solver", "n", "outlier_ratio"]):
            panel = panels.setdefault((row, dim), {"doc": doc, "generator": generator,
                                                   "curves": {}, "fa": {}})
            judged = g["success"].dropna()
            lo, hi = report_io.wilson_interval(judged.astype(bool).sum(), len(judged))
            times = g["time_ms"]
            panel["curves"].setdefault((solver, n), []).append({
                "ratio": ratio,
                "success": judged.astype(bool).mean() if len(judged) else float("nan"),
                "lo": lo, "hi": hi,
                "median": times.median(), "q1": times.quantile(0.25), "q3": times.quantile(0.75)})
    return panels, rows_order


def grid(nrows, ncols, extra_w=2.9, extra_h=0.7, **kw):
    fig, axes = plt.subplots(nrows, ncols, figsize=(PANEL_W * ncols + extra_w,
                                                    PANEL_H * nrows + extra_h),
                             squeeze=False, **kw)
    return fig, axes


def build_sweep(reports, kind):
    """The success ('success') or time ('time') figure of sweep reports: a grid of panels, rows =
    generators, columns = dimensions."""
    if kind not in ("success", "time"):
        raise ValueError(f"kind must be 'success' or 'time', not {kind!r}")
    panels, row_keys = sweep_series(reports)
    if not panels:
        fail("no sweep points (rows with an outlier_ratio) in the sweep reports")
    dims = sorted({d for _, d in panels})
    solvers = sorted({s for p in panels.values() for s, _ in list(p["curves"]) + list(p["fa"])})
    sizes = sorted({n for p in panels.values() for _, n in p["curves"]})
    colour = colours(solvers)
    marker = {s: MARKERS[i % len(MARKERS)] for i, s in enumerate(solvers)}
    style = {n: LINESTYLES[i % len(LINESTYLES)] for i, n in enumerate(sizes)}
    has_fa = any(p["fa"] for p in panels.values())
    scale = "linear"
    if kind == "time":
        scale = time_scale([pt["median"] for p in panels.values() for c in p["curves"].values()
                            for pt in c])
    criteria = {report_io.success_criterion(p["doc"]) for p in panels.values()}
    legend_below = len(dims) == 1  # one column: the legend goes under the grid, not beside it
    n_entries = len({(s, n) for p in panels.values() for s, n in p["curves"]}) + (
        len({(s, n) for p in panels.values() for s, n in p["fa"]}) if kind == "success" else 0) + 1
    fig, axes = grid(len(row_keys), len(dims), sharex=True, sharey=True,
                     extra_w=0.9 if legend_below else 2.9,
                     extra_h=0.7 + (0.1 + 0.15 * n_entries if legend_below else 0.0))
    handles = {}
    for r, row in enumerate(row_keys):
        first = True
        for c, dim in enumerate(dims):
            ax = axes[r][c]
            panel = panels.get((row, dim))
            if panel is None:
                ax.set_axis_off()
                continue
            doc = panel["doc"]
            for (solver, n), pts in sorted(panel["curves"].items()):
                pts = sorted(pts, key=lambda p: p["ratio"])
                x = [p["ratio"] for p in pts]
                tr = nudge(fig, ax, solvers.index(solver), len(solvers), vertical=kind == "success")
                kw = {"color": colour[solver], "marker": marker[solver], "linestyle": style[n],
                      "markersize": 4.5, "transform": tr}
                label = f"{solver} (n={n})"
                if kind == "success":
                    y = [p["success"] for p in pts]
                    err = [[p["success"] - p["lo"] for p in pts], [p["hi"] - p["success"] for p in pts]]
                    ax.errorbar(x, y, yerr=err, fmt="none", ecolor=colour[solver], capsize=2,
                                elinewidth=0.8, transform=tr, alpha=0.8)
                    label += ": success rate, 95% Wilson interval"
                else:
                    y = [p["median"] for p in pts]
                    ax.fill_between(x, [p["q1"] for p in pts], [p["q3"] for p in pts],
                                    color=colour[solver], alpha=0.18, linewidth=0, transform=tr)
                    label += ": median, quartile band"
                (line,) = ax.plot(x, y, label=label, **kw)
                line.set_gid(f"{kind}:{solver}:{n}")
                handles.setdefault(label, line)
            if kind == "success":
                for (solver, n), pts in sorted(panel["fa"].items()):
                    pts = sorted(pts, key=lambda p: p["ratio"])
                    label = f"{solver} (n={n}): false accepts of negative twins"
                    (line,) = ax.plot([p["ratio"] for p in pts], [p["fa"] for p in pts],
                                      color=colour[solver], marker="x", linestyle=":",
                                      markersize=5, label=label,
                                      transform=nudge(fig, ax, solvers.index(solver), len(solvers)))
                    line.set_gid(f"false_accepts:{solver}:{n}")
                    handles.setdefault(label, line)
                ax.set_ylim(-0.04, 1.04)
            elif scale == "log":
                log_axis("y", ax)
            else:
                ax.set_ylim(bottom=0)
            ax.grid(True, which="both", alpha=0.3)
            sweep = doc["parameters"]["sweep"]
            ns = sorted({n for _, n in panel["curves"]})
            title = (f"{row}, {dim}D: n {', '.join(map(str, ns))}, noise {sweep.get('noise')}, "
                     f"eps {doc['parameters'].get('eps')}, {sweep.get('trials')} trials/point\n"
                     f"{accept_rule_text(doc['parameters'], dim)}")
            if len(criteria) > 1:
                title += f"\n{report_io.success_criterion(doc)}"
            ax.set_title(title, fontsize=8)
            if first:  # one y label per row, on its first panel
                if kind == "success":
                    ylabel = "success rate" + (" / false accept rate" if has_fa else "")
                else:
                    ylabel = "time per solve [ms]" + (", log scale" if scale == "log" else "")
                ax.set_ylabel(f"{panel['generator']}\n{ylabel}", fontsize=9)
                ax.tick_params(labelleft=True)
                first = False
            else:
                ax.tick_params(labelleft=False)
            # x labels on the lowest panel of each column
            lower = [rr for rr in range(r + 1, len(row_keys)) if (row_keys[rr], dim) in panels]
            if not lower:
                ax.set_xlabel("outlier ratio")
                ax.tick_params(labelbottom=True)
    note = (f"solvers drawn {OFFSET_PT:g} pt apart"
            + (" (x and y)" if kind == "success" else " (x)") + " so equal curves stay visible")
    entries = (list(handles.values()) + [Line2D([], [], linestyle="none")],
               list(handles.keys()) + [note])
    if legend_below:
        bottom = [axes[r][0] for r in range(len(row_keys)) if axes[r][0].axison][-1]
        bottom.legend(*entries, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2),
                      borderaxespad=0.0)
    else:  # right of the top-right panel
        top_right = next(axes[0][c] for c in reversed(range(len(dims))) if axes[0][c].axison)
        top_right.legend(*entries, fontsize=7, loc="upper left", bbox_to_anchor=(1.03, 1.0),
                         borderaxespad=0.0)
    head = ("success rate vs outlier ratio" if kind == "success"
            else "time per solve vs outlier ratio (positive sets)")
    fig.suptitle(head + ("\n" + criteria.pop() if len(criteria) == 1 else ""), fontsize=9)
    fig.tight_layout()
    return fig


def plot_sweeps(reports, out_dir, stem):
    paths = []
    for kind in ("success", "time"):
        paths += save_figure(build_sweep(reports, kind), os.path.join(out_dir, f"{stem}_{kind}"))
    return paths


# ---------------------------------------------------------------------------------------------
# Dumps

def dump_stats(rows):
    """Per solver: median and quartiles of time_ms, median inliers, max true inliers, success rate,
    accepted count and trials (rows of one dump)."""
    return rows.groupby("solver", sort=False).agg(
        median=("time_ms", "median"),
        q1=("time_ms", lambda t: t.quantile(0.25)),
        q3=("time_ms", lambda t: t.quantile(0.75)),
        inliers=("inliers", "median"),
        true_inliers=("true_inliers", "max"),
        accepted=("accepted", lambda a: int(a.astype(bool).sum())),
        trials=("time_ms", "size"),
        success=("success", lambda s: s.dropna().astype(bool).mean()
                 if s.notna().any() else float("nan")))


def build_dump(reports):
    """Time per solve and selected inliers per solver: one row per dump, shared axes per column."""
    import pandas as pd
    frames = []
    for doc in reports:
        f = report_io.results_frame(doc)
        if not f.empty:
            f["_doc"] = [doc] * len(f)
            frames.append(f)
    if not frames:
        fail("the dump reports hold no rows")
    rows = pd.concat(frames, ignore_index=True)
    datasets = list(dict.fromkeys(rows["dataset"]))
    solvers = list(dict.fromkeys(rows["solver"]))
    colour = colours(solvers)
    stats = {d: dump_stats(rows[rows["dataset"] == d]).reindex(solvers) for d in datasets}
    scale = time_scale([m for s in stats.values() for m in s["median"]])
    row_h = max(1.6, 0.75 + 0.38 * len(solvers))
    fig, axes = plt.subplots(len(datasets), 2, figsize=(2 * PANEL_W + 0.6, row_h * len(datasets) + 0.8),
                             squeeze=False, sharex="col")
    y = list(range(len(solvers)))
    # the inlier panels' annotations stand in a column right of every bar and line
    marks = [v for st in stats.values() for v in list(st["inliers"]) + list(st["true_inliers"])
             if v == v]
    marks += [count_threshold(d.get("parameters", {}), int(dm)) for d, dm in zip(rows["_doc"], rows["dim"])
              if d.get("parameters", {}).get("accept_rule") == "count"]
    right = 1.03 * max(marks + [1])
    for r, ((ax_t, ax_i), dataset) in enumerate(zip(axes, datasets)):
        s = stats[dataset]
        doc = rows[rows["dataset"] == dataset]["_doc"].iloc[0]
        params = doc.get("parameters", {})
        dim = int(rows[rows["dataset"] == dataset]["dim"].iloc[0])
        bars = ax_t.barh(y, s["median"].fillna(0), color=[colour[x] for x in solvers],
                         xerr=[(s["median"] - s["q1"]).fillna(0), (s["q3"] - s["median"]).fillna(0)],
                         capsize=3, height=0.6)
        for solver, bar in zip(solvers, bars):
            bar.set_gid(f"time:{solver}")
        ax_t.set_yticks(y, solvers, fontsize=8)
        ax_t.invert_yaxis()
        for k, (m, q3) in enumerate(zip(s["median"], s["q3"])):
            if m == m:  # the median's value, right of the upper quartile's whisker
                ax_t.text(max(m, q3), k, f"  {m:.3g} ms", va="center", ha="left", fontsize=7)
        if scale == "log":
            log_axis("x", ax_t)
        else:
            ax_t.set_xlim(left=0)
        ax_t.grid(True, which="both", axis="x", alpha=0.3)
        name = os.path.basename(str(dataset).rstrip("/"))
        n = rows[rows["dataset"] == dataset]["n"].iloc[0]
        ax_t.set_title(f"{name}: n {n}, eps {params.get('eps')}, {int(s['trials'].max())} trials; "
                       f"{accept_rule_text(params, dim)}", fontsize=8)
        inl = ax_i.barh(y, s["inliers"].fillna(0), color=[colour[x] for x in solvers], height=0.6)
        for solver, bar in zip(solvers, inl):
            bar.set_gid(f"inliers:{solver}")
        ax_i.set_yticks(y, [""] * len(solvers))
        ax_i.invert_yaxis()
        truth = s["true_inliers"].dropna()
        if len(truth):
            ax_i.axvline(truth.iloc[0], color="k", linestyle="--", linewidth=0.9,
                         label=f"true inliers ({int(truth.iloc[0])})")
        if params.get("accept_rule") == "count":
            k = count_threshold(params, dim)
            ax_i.axvline(k, color="tab:red", linestyle=":", linewidth=1.2,
                         label=f"accept threshold K = {k}")
        ax_i.set_xlim(0, right * 1.6)
        for k, (_, st) in enumerate(s.iterrows()):
            if st["trials"] != st["trials"]:  # a solver without rows on this dump
                continue
            text = f"accepted {int(st['accepted'])}/{int(st['trials'])}"
            if st["success"] == st["success"]:  # not NaN
                text += f", success {st['success']:.2f}"
            ax_i.text(right, k, text, va="center", fontsize=7)
        if ax_i.get_legend_handles_labels()[0]:
            ax_i.legend(fontsize=7, loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=2,
                        borderaxespad=0.2)
        ax_i.grid(True, axis="x", alpha=0.3)
        if r == len(datasets) - 1:
            ax_t.set_xlabel("time per solve [ms] (bar: median, whiskers: quartiles)"
                            + (", log scale" if scale == "log" else ""))
            ax_i.set_xlabel("selected inliers (median)")
    fig.suptitle(report_io.success_criterion(reports[0]), fontsize=9)
    fig.tight_layout()
    return fig


def plot_dumps(reports, out_dir, stem):
    return save_figure(build_dump(reports), os.path.join(out_dir, f"{stem}_dump"))


# ---------------------------------------------------------------------------------------------
# DIMACS

def build_dimacs(reports):
    import pandas as pd
    rows = pd.concat([report_io.results_frame(d) for d in reports], ignore_index=True)
    if rows.empty:
        fail("the DIMACS reports hold no rows")
    rows["graph_name"] = rows["graph"].map(lambda p: os.path.splitext(os.path.basename(p))[0])
    graphs = sorted(rows["graph_name"].unique())
    algorithms = sorted(rows["algorithm"].unique())
    colour = colours(algorithms)
    width = 0.8 / len(algorithms)
    scale = time_scale([max(t, 1e-3) for t in rows["time_ms"]])
    fig, ax = plt.subplots(figsize=(max(PANEL_W + 2.5, 0.6 * len(graphs) * max(1, len(algorithms) / 2)),
                                    PANEL_H + 1.2))
    for k, algorithm in enumerate(algorithms):
        g = rows[rows["algorithm"] == algorithm].set_index("graph_name")
        for i, graph in enumerate(graphs):
            if graph not in g.index:
                continue
            r = g.loc[[graph]].iloc[0]
            bar = ax.bar(i + (k - (len(algorithms) - 1) / 2) * width, max(r["time_ms"], 1e-3), width,
                         color=colour[algorithm], hatch=None if r["status"] == "ok" else "//",
                         edgecolor="k" if r["status"] != "ok" else None, linewidth=0.4,
                         label=algorithm if i == 0 else None)
            bar.patches[0].set_gid(f"dimacs:{algorithm}:{graph}")
    ax.set_xticks(range(len(graphs)), graphs, rotation=60, ha="right", fontsize=8)
    ax.set_ylabel("search time [ms] (hatched: not proven optimal)"
                  + (", log scale" if scale == "log" else ""))
    if scale == "log":
        log_axis("y", ax)
    ax.grid(True, which="both", axis="y", alpha=0.3)
    limit = reports[0].get("parameters", {}).get("time_limit_s")
    ax.set_title(f"maximum clique on DIMACS graphs, time limit {limit} s", fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    return fig


def plot_dimacs(reports, out_dir, stem):
    return save_figure(build_dimacs(reports), os.path.join(out_dir, f"{stem}_dimacs"))


def plot_loops(doc, out_dir, prefix):
    """A loop report's figures (plot_loop.py): PREFIX_trajectory_SOLVER per solver and PREFIX_pr."""
    import plot_loop
    if "trajectories" not in doc:
        fail("a loop report without its 'trajectories'")
    paths = []
    for row in doc["summary"]:
        paths += save_figure(plot_loop.build_trajectory(doc, row["solver"]),
                             os.path.join(out_dir, f"{prefix}_trajectory_{row['solver']}"))
    return paths + save_figure(plot_loop.build_pr(doc), os.path.join(out_dir, f"{prefix}_pr"))


def main():
    parser = argparse.ArgumentParser(prog="plot_report.py", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("reports", nargs="+", metavar="REPORT.json")
    parser.add_argument("--out-dir", default=None, help="default: the first report's folder")
    parser.add_argument("--name", default=None, help="file name stem of the plots")
    args = parser.parse_args()
    reports = [report_io.load_report(TOOL, p, loop=True) for p in args.reports]
    kinds = {report_io.report_kind(d) for d in reports}
    if len(kinds) != 1:
        fail(f"the reports mix kinds ({', '.join(sorted(kinds))}); plot each kind on its own")
    out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.reports[0]))
    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as e:
        fail(f"{out_dir}: {e}")
    stem = args.name or os.path.splitext(os.path.basename(args.reports[0]))[0]
    kind = kinds.pop()
    if kind == "loop":  # plot_loop.py's figures, one set per report
        paths = []
        for path, doc in zip(args.reports, reports):
            prefix = args.name or "loop"
            if len(reports) > 1:
                prefix += "_" + os.path.basename(os.path.dirname(os.path.abspath(path)))
            paths += plot_loops(doc, out_dir, prefix)
        for path in paths:
            print(path)
        return
    plot = {"sweep": plot_sweeps, "run": plot_dumps, "dimacs": plot_dimacs}[kind]
    for path in plot(reports, out_dir, stem):
        print(path)


if __name__ == "__main__":
    main()
