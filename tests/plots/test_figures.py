"""The report figures' content (issues #29 item 5, #33 item 4): small reports made by the CLI
(VERIFYBENCH names the binary), the figures built by reports/*.py's build_* functions, and what
they draw checked against the reports' data read here straight from the JSON: the curves' x and y,
the panels' count and layout, titles naming the accept rule and the success criterion, the
operating points, the time axes' scale, the loop edges; and pixels: every panel has
curve-coloured pixels once drawn, and a figure whose curves are removed fails that check.

    VERIFYBENCH=build/verifybench /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/plots
"""
import copy
import json
import math
import os
import statistics
import struct
import subprocess
import sys

import pytest

REPORTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "reports")
sys.path.insert(0, os.path.abspath(REPORTS))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import to_rgb  # noqa: E402

import decisions  # noqa: E402
import plot_loop  # noqa: E402
import plot_report  # noqa: E402

VB = os.environ.get("VERIFYBENCH")
if not VB or not os.access(VB, os.X_OK):
    pytest.skip("VERIFYBENCH (the verifybench binary) is not set or not executable; ctest sets it",
                allow_module_level=True)

PY = "/usr/bin/python3"


# ---------------------------------------------------------------------------------------------
# Reports, made once per session

def cli(*args):
    r = subprocess.run([VB, *args, "--quiet"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, f"verifybench {' '.join(args)}: {r.stderr}"


def block_poses(path):
    """A 220 m x 140 m block driven twice (KITTI poses), as scripts/loop draws it."""
    W, H, rows = 220.0, 140.0, []
    for _ in range(2):
        s = 0.0
        while s < 2 * (W + H):
            if s < W:
                x, y, yaw = s, 0.0, 0.0
            elif s < W + H:
                x, y, yaw = W, s - W, math.pi / 2
            elif s < 2 * W + H:
                x, y, yaw = W - (s - W - H), H, math.pi
            else:
                x, y, yaw = 0.0, H - (s - 2 * W - H), -math.pi / 2
            c, n = math.cos(yaw), math.sin(yaw)
            rows.append(f"{c} {-n} 0 {x} {n} {c} 0 {y} 0 0 1 0")
            s += 1.0
    with open(path, "w") as f:
        f.write("\n".join(rows) + "\n")


@pytest.fixture(scope="session")
def out(tmp_path_factory):
    return tmp_path_factory.mktemp("plots")


@pytest.fixture(scope="session")
def paths(out):
    p = {k: str(out / f"{k}.json") for k in ("uniform", "repetitive", "count", "run", "dimacs")}
    sweep = ["sweep", "--solvers", "clique,ransac", "--dim", "2,3", "--n", "60", "--outliers",
             "0.5,0.9", "--seed", "1"]
    cli(*sweep, "--trials", "2", "--negatives", "--out", p["uniform"])
    cli(*sweep, "--generator", "repetitive", "--trials", "2", "--negatives", "--out", p["repetitive"])
    cli(*sweep, "--trials", "2", "--accept", "count", "--out", p["count"])
    dump = out / "dump"
    dump.mkdir()
    (dump / "corr.txt").write_text("".join(
        f"{i} {i * i % 7} {i % 3} {i + 1} {i * i % 7} {i % 3}\n" for i in range(10)))
    (dump / "GTmat.txt").write_text("1 0 0 1\n0 1 0 0\n0 0 1 0\n0 0 0 1\n")
    cli("run", "--dump", str(dump), "--solvers", "clique,ransac", "--trials", "3", "--out", p["run"])
    (out / "k4.clq").write_text("p edge 4 6\ne 1 2\ne 1 3\ne 1 4\ne 2 3\ne 2 4\ne 3 4\n")
    (out / "c5.clq").write_text("p edge 5 10\n" + "".join(
        f"e {a} {b}\n" for a in range(1, 6) for b in range(a + 1, 6)))
    cli("dimacs", str(out / "k4.clq"), str(out / "c5.clq"), "--algorithms", "bbmc,greedy",
        "--out", p["dimacs"])
    return p


@pytest.fixture(scope="session")
def docs(paths):
    return {k: json.load(open(v)) for k, v in paths.items()}


@pytest.fixture(scope="session")
def loop_dir(out):
    """A loop report on the drawn block (about 5 s); skipped when the build has no loop stage or
    cannot ray-cast (the core-only sanitizer build of .ci/run)."""
    block_poses(out / "block.txt")
    r = subprocess.run([VB, "loop", "--trajectory", str(out / "block.txt"), "--pipeline", "2d",
                        "--solvers", "clique,ransac", "--accept", "count", "--scan-spacing", "4",
                        "--lidar-columns", "512", "--threads", "2", "--quiet", "--out",
                        str(out / "loop")], capture_output=True, text=True, timeout=300)
    if r.returncode != 0 and ("Embree" in r.stderr or "without the loop stage" in r.stderr):
        pytest.skip(f"this build cannot run the loop: {r.stderr.strip()}")
    assert r.returncode == 0, r.stderr
    return out / "loop"


@pytest.fixture(scope="session")
def loop_doc(loop_dir):
    return json.load(open(loop_dir / "loop.json"))


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


# ---------------------------------------------------------------------------------------------
# Helpers

def panels(fig):
    """The figure's visible main axes (no insets, no hidden grid cells)."""
    return [ax for ax in fig.axes if ax.axison and ax.get_gid() != "roc_zoom"
            and not any(ax in a.child_axes for a in fig.axes)]


def line(ax, gid):
    found = [ln for ln in ax.lines if ln.get_gid() == gid]
    assert len(found) == 1, (gid, [ln.get_gid() for ln in ax.lines])
    return found[0]


def suptitle(fig):
    if hasattr(fig, "get_suptitle"):  # matplotlib >= 3.8
        return fig.get_suptitle()
    return fig._suptitle.get_text() if fig._suptitle is not None else ""


def title_of(ax):
    return ax.get_title()


def rendered(fig):
    fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba())[:, :, :3].astype(int)


def axes_pixels(fig, ax, image=None):
    """The RGB pixels inside ax's frame (2 px in from the spines), legends hidden."""
    legends = [a.get_legend() for a in fig.axes if a.get_legend() is not None]
    for lg in legends:
        lg.set_visible(False)
    try:
        image = rendered(fig) if image is None else image
        box = ax.get_window_extent()
    finally:
        for lg in legends:
            lg.set_visible(True)
    h = image.shape[0]
    x0, x1 = int(math.ceil(box.x0)) + 2, int(math.floor(box.x1)) - 2
    y0, y1 = h - int(math.floor(box.y1)) + 2, h - int(math.ceil(box.y0)) - 2
    return image[y0:y1, x0:x1]


def coloured_pixels(pixels):
    """How many pixels have a colour (chroma >= 60): curves, bars and markers; not the white
    background, the grey grid, nor black text and spines."""
    return int(((pixels.max(axis=2) - pixels.min(axis=2)) >= 60).sum())


def pixels_near(pixels, colour, tol=40):
    rgb = np.array(to_rgb(colour)) * 255
    return int((np.abs(pixels - rgb).max(axis=2) <= tol).sum())


def assert_drawn(fig, minimum=150):
    """Every panel of the figure, drawn, holds at least `minimum` curve-coloured pixels."""
    legends = [a.get_legend() for a in fig.axes if a.get_legend() is not None]
    for lg in legends:
        lg.set_visible(False)
    try:
        image = rendered(fig)
    finally:
        for lg in legends:
            lg.set_visible(True)
    for ax in panels(fig):
        n = coloured_pixels(axes_pixels(fig, ax, image))
        assert n >= minimum, f"panel {title_of(ax)!r}: {n} coloured pixels, want >= {minimum}"


def blank(fig):
    """The figure with every curve, band, bar and marker removed: axes, labels, titles kept."""
    for ax in fig.axes:
        for artist in list(ax.lines) + list(ax.collections) + list(ax.patches):
            artist.remove()
    return fig


def aggregates(doc):
    """{(solver, dim, n, ratio, expected): aggregate} of a sweep report."""
    return {(a["solver"], a["dim"], a["n"], a["outlier_ratio"], a.get("expected") or "positive"): a
            for a in doc["aggregates"]}


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", path
    return struct.unpack(">II", head[16:24])


def panel_key(ax):
    """(generator, dim) from a sweep panel's title, 'uniform, 3D: ...'."""
    head = title_of(ax).split(":")[0]
    generator, dim = head.rsplit(", ", 1)
    return generator, int(dim.rstrip("D"))


# ---------------------------------------------------------------------------------------------
# Sweeps

def test_sweep_success_curves_are_the_reports_aggregates(docs):
    reports = [docs["uniform"], docs["repetitive"]]
    fig = plot_report.build_sweep(reports, "success")
    axs = panels(fig)
    generators = {d["parameters"]["sweep"]["generator"] for d in reports}
    dims = {dim for d in reports for dim in d["parameters"]["sweep"]["dims"]}
    assert len(axs) == len(generators) * len(dims) == 4
    assert {panel_key(ax) for ax in axs} == {(g, d) for g in generators for d in dims}
    for doc in reports:
        sweep = doc["parameters"]["sweep"]
        agg = aggregates(doc)
        for ax in axs:
            generator, dim = panel_key(ax)
            if generator != sweep["generator"]:
                continue
            for solver in sweep["solvers"]:
                ln = line(ax, f"success:{solver}:{sweep['n']}")
                assert list(ln.get_xdata()) == pytest.approx(sorted(sweep["outlier_ratios"]))
                want = [agg[(solver, dim, sweep["n"], r, "positive")]["success_rate"]
                        for r in sorted(sweep["outlier_ratios"])]
                assert list(ln.get_ydata()) == pytest.approx(want)
                fa = line(ax, f"false_accepts:{solver}:{sweep['n']}")
                want = [agg[(solver, dim, sweep["n"], r, "negative")]["accept_rate"]
                        for r in sorted(sweep["outlier_ratios"])]
                assert list(fa.get_ydata()) == pytest.approx(want)
            assert f"accept: p < {doc['parameters']['alpha']}" in title_of(ax)
    c = docs["uniform"]["parameters"]["success_criteria"]
    head = suptitle(fig)
    assert f"rotation error < {c['max_rotation_error_deg']} deg" in head
    assert f"translation error < {c['max_translation_error']} m" in head
    assert_drawn(fig)


def test_sweep_grid_shares_axes_and_labels_once_per_row(docs):
    fig = plot_report.build_sweep([docs["uniform"], docs["repetitive"]], "success")
    axs = panels(fig)
    rows = {}
    for ax in axs:
        rows.setdefault(panel_key(ax)[0], []).append(ax)
    for generator, row in rows.items():
        labelled = [ax for ax in row if ax.get_ylabel()]
        assert len(labelled) == 1, (generator, [ax.get_ylabel() for ax in row])
        assert generator in labelled[0].get_ylabel() and "success rate" in labelled[0].get_ylabel()
    for ax in axs[1:]:
        assert axs[0].get_shared_y_axes().joined(axs[0], ax)
        assert axs[0].get_shared_x_axes().joined(axs[0], ax)
    assert sum(ax.get_xlabel() == "outlier ratio" for ax in axs) == 2  # the bottom row's
    w, h = fig.get_size_inches()
    assert w <= 4.5 * 2 + 3.5 and h <= 3.5 * 2 + 1.0 and w / h < 2.5, (w, h)
    # Both solvers' colours show in every panel, even where their curves are equal (offsets).
    image = rendered(fig)
    colour = plot_report.colours(["clique", "ransac"])
    for ax in axs:
        px = axes_pixels(fig, ax, image)
        for solver, c in colour.items():
            assert pixels_near(px, c) >= 40, (title_of(ax), solver, pixels_near(px, c))


def test_sweep_titles_name_the_count_rule(docs):
    doc = docs["count"]
    fig = plot_report.build_sweep([doc], "success")
    axs = panels(fig)
    assert len(axs) == 2
    p = doc["parameters"]
    for ax in axs:
        _, dim = panel_key(ax)
        k = p["min_inliers"] or p[f"accept_threshold_{dim}d"]
        assert f"accept: inliers >= {k}" in title_of(ax)
        assert "p <" not in title_of(ax)
    assert_drawn(fig)


def test_sweep_time_medians_and_scale(docs):
    doc = docs["uniform"]
    sweep = doc["parameters"]["sweep"]
    agg = aggregates(doc)
    fig = plot_report.build_sweep([doc], "time")
    medians = [a["median_time_ms"] for k, a in agg.items() if k[4] == "positive"]
    log = max(medians) / min(medians) > 100
    for ax in panels(fig):
        _, dim = panel_key(ax)
        for solver in sweep["solvers"]:
            ln = line(ax, f"time:{solver}:{sweep['n']}")
            want = [agg[(solver, dim, sweep["n"], r, "positive")]["median_time_ms"]
                    for r in sorted(sweep["outlier_ratios"])]
            assert list(ln.get_ydata()) == pytest.approx(want)
        assert ax.get_yscale() == ("log" if log else "linear")
    labels = [ax.get_ylabel() for ax in panels(fig) if ax.get_ylabel()]
    assert len(labels) == 1 and ("log scale" in labels[0]) == log
    assert_drawn(fig)


def with_times(doc, times):
    """A copy of `doc` whose rows take time_ms from times(row)."""
    doc = copy.deepcopy(doc)
    for r in doc["results"]:
        r["time_ms"] = times(r)
    return doc


def test_time_axis_is_linear_unless_the_span_exceeds_100x(docs):
    small = with_times(docs["uniform"], lambda r: 17.0 if r["solver"] == "clique" else 115.0)
    fig = plot_report.build_sweep([small], "time")
    for ax in panels(fig):
        assert ax.get_yscale() == "linear" and ax.get_ylim()[0] == 0
    assert not any("log" in ax.get_ylabel() for ax in panels(fig))
    large = with_times(docs["uniform"], lambda r: 0.02 if r["solver"] == "clique" else 9.0)
    fig = plot_report.build_sweep([large], "time")
    assert all(ax.get_yscale() == "log" for ax in panels(fig))
    assert any("log scale" in ax.get_ylabel() for ax in panels(fig))


# ---------------------------------------------------------------------------------------------
# Dumps and DIMACS

def bar(ax, gid):
    found = [p for p in ax.patches if p.get_gid() == gid]
    assert len(found) == 1, (gid, [p.get_gid() for p in ax.patches])
    return found[0]


def test_dump_bars_are_the_rows_medians(docs):
    doc = docs["run"]
    fig = plot_report.build_dump([doc])
    ax_t, ax_i = panels(fig)
    solvers = list(dict.fromkeys(r["solver"] for r in doc["results"]))
    times = {s: [r["time_ms"] for r in doc["results"] if r["solver"] == s] for s in solvers}
    for s in solvers:
        assert bar(ax_t, f"time:{s}").get_width() == pytest.approx(statistics.median(times[s]))
        assert bar(ax_i, f"inliers:{s}").get_width() == pytest.approx(
            statistics.median(r["inliers"] for r in doc["results"] if r["solver"] == s))
    meds = [statistics.median(t) for t in times.values()]
    assert ax_t.get_xscale() == ("log" if max(meds) / min(meds) > 100 else "linear")
    assert f"accept: p < {doc['parameters']['alpha']}" in title_of(ax_t)
    assert "translation error" in suptitle(fig)
    assert_drawn(fig, minimum=100)


def test_dump_times_are_drawn_to_scale(docs):
    """17 vs 115 ms must look like 17 vs 115, not 1:30 (#33): linear from 0, bars in proportion."""
    doc = with_times(docs["run"], lambda r: 17.0 if r["solver"] == "clique" else 115.0)
    fig = plot_report.build_dump([doc])
    ax_t = panels(fig)[0]
    assert ax_t.get_xscale() == "linear" and ax_t.get_xlim()[0] == 0
    fig.canvas.draw()
    widths = {s: bar(ax_t, f"time:{s}").get_window_extent().width for s in ("clique", "ransac")}
    assert widths["ransac"] / widths["clique"] == pytest.approx(115 / 17, rel=0.05)


def test_dump_count_rule_draws_its_threshold(docs):
    doc = copy.deepcopy(docs["run"])
    doc["parameters"]["accept_rule"] = "count"
    fig = plot_report.build_dump([doc])
    ax_t, ax_i = panels(fig)
    k = doc["parameters"]["min_inliers"] or doc["parameters"]["accept_threshold_3d"]
    assert f"accept: inliers >= {k}" in title_of(ax_t)
    assert any(ln.get_label() == f"accept threshold K = {k}" and list(ln.get_xdata()) == [k, k]
               for ln in ax_i.lines)


def test_dimacs_bars_are_the_rows_times(docs):
    doc = docs["dimacs"]
    fig = plot_report.build_dimacs([doc])
    (ax,) = panels(fig)
    for r in doc["results"]:
        graph = os.path.splitext(os.path.basename(r["graph"]))[0]
        assert bar(ax, f"dimacs:{r['algorithm']}:{graph}").get_height() == pytest.approx(
            max(r["time_ms"], 1e-3))
    t = [max(r["time_ms"], 1e-3) for r in doc["results"]]
    assert ax.get_yscale() == ("log" if max(t) / min(t) > 100 else "linear")
    assert ("log scale" in ax.get_ylabel()) == (ax.get_yscale() == "log")
    assert_drawn(fig, minimum=20)


# ---------------------------------------------------------------------------------------------
# Accept decisions

def test_decisions_operating_points_sit_at_the_reports_counts(docs, paths):
    doc = docs["uniform"]
    rows, errors, _ = decisions.load_rows([paths["uniform"]])
    assert errors == 0
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    fig = decisions.build_decisions(rows, solvers)
    roc, pr = panels(fig)
    block = {d["solver"]: d for d in doc["decisions"]}
    for s in solvers:
        d = block[s]
        fpr, tpr = d["fp"] / (d["fp"] + d["tn"]), d["tp"] / (d["tp"] + d["fn"])
        op = line(roc, f"roc:operating:pvalue:{s}")
        assert (op.get_xdata()[0], op.get_ydata()[0]) == pytest.approx((fpr, tpr))
        op = line(pr, f"pr:operating:pvalue:{s}")
        assert (op.get_xdata()[0], op.get_ydata()[0]) == pytest.approx((d["recall"], d["precision"]))
        # The count rule at K = 5 (3D) / 10 (2D), counted here from the rows of the JSON.
        p = doc["parameters"]
        mine = [r for r in doc["results"] if r["solver"] == s]
        acc = [(r["expected"] == "positive", r["inliers"] >= p[f"accept_threshold_{r['dim']}d"])
               for r in mine]
        tp = sum(e and a for e, a in acc)
        fp = sum(a and not e for e, a in acc)
        pos = sum(e for e, _ in acc)
        op = line(roc, f"roc:operating:count:{s}")
        assert (op.get_xdata()[0], op.get_ydata()[0]) == pytest.approx(
            (fp / (len(acc) - pos), tp / pos))
    head = suptitle(fig)
    assert f"alpha = {doc['parameters']['alpha']:g}" in head
    assert "5 (3D)" in head and "10 (2D)" in head
    assert roc.get_xlabel().startswith("false accept rate") and pr.get_xlabel() == "recall"
    assert_drawn(fig)
    # One dimension (one K): each operating point lies on its rule's curve.
    for dim in (2, 3):
        mine = [r for r in rows if r["dim"] == dim]
        fig = decisions.build_decisions(mine, solvers)
        roc, pr = panels(fig)
        for s in solvers:
            for rule, curve in (("count", "count"), ("pvalue", "alpha")):
                op, c = line(roc, f"roc:operating:{rule}:{s}"), line(roc, f"roc:{curve}:{s}")
                if rule == "pvalue":  # the rows' decisions: p < alpha and a motion's points
                    continue
                assert any(x == pytest.approx(op.get_xdata()[0]) and y == pytest.approx(
                    op.get_ydata()[0]) for x, y in zip(c.get_xdata(), c.get_ydata())), (dim, s)
        assert f"K = {10 if dim == 2 else 5} ({dim}D)" in suptitle(fig)


# ---------------------------------------------------------------------------------------------
# Loop closure

def test_loop_edges_are_all_drawn_and_visible(loop_doc):
    anchors = {m["index"]: m["position_truth"] for m in loop_doc["maps"]}
    truth = np.asarray(loop_doc["trajectories"]["truth"])[:, :2]
    for s in loop_doc["summary"]:
        solver = s["solver"]
        fig = plot_loop.build_trajectory(loop_doc, solver)
        (ax,) = panels(fig)
        fig.canvas.draw()
        accepted = [c for c in loop_doc["closures"] if c["solver"] == solver and c["accepted"]]
        assert accepted
        top = max(ln.get_zorder() for ln in ax.lines if not (ln.get_gid() or "").startswith(
            ("edge:", "ends:")))
        for c in accepted:
            kind = "correct" if c["correct"] else "false"
            arc = line(ax, f"edge:{kind}:{c['query']}:{c['match']}")
            ends = line(ax, f"ends:{kind}:{c['query']}:{c['match']}")
            a, b = anchors[c["query"]], anchors[c["match"]]
            assert list(ends.get_xdata()) == pytest.approx([a[0], b[0]])
            assert list(ends.get_ydata()) == pytest.approx([a[1], b[1]])
            assert to_rgb(arc.get_color()) == to_rgb("tab:green" if c["correct"] else "tab:red")
            assert arc.get_zorder() > top and ends.get_zorder() > top
            # drawn at least 12 px away from its ends, even when both anchors coincide
            pts = ax.transData.transform(np.column_stack([arc.get_xdata(), arc.get_ydata()]))
            ends_px = ax.transData.transform([a[:2], b[:2]])
            reach = max(min(np.hypot(*(p - e)) for e in ends_px) for p in pts)
            assert reach >= 12, (c["query"], c["match"], reach)
        n_edges = sum((ln.get_gid() or "").startswith("edge:") for ln in ax.lines)
        assert n_edges == len(accepted) == s["closures_accepted"]
        p = loop_doc["parameters"]
        k = p["min_inliers"] or p["accept_threshold_2d"]
        assert f"accept: inliers >= {k}" in title_of(ax)
        assert f"translation error <= {p['loop']['pose_tolerance_m']:g} m" in title_of(ax)
        assert ax.get_lines()[0].get_xdata() == pytest.approx(truth[:, 0])
        assert_drawn(fig)


def test_loop_pr_marks_the_operating_point(loop_doc):
    fig = plot_loop.build_pr(loop_doc)
    (ax,) = panels(fig)
    for s in loop_doc["summary"]:
        op = line(ax, f"operating:{s['solver']}")
        assert (op.get_xdata()[0], op.get_ydata()[0]) == pytest.approx((s["recall"], s["precision"]))
        pts = [p for p in loop_doc["curves"][s["solver"]]["count"]
               if p["precision"] is not None and p["recall"] is not None]
        curve = line(ax, f"pr:count:{s['solver']}")
        assert list(curve.get_xdata()) == pytest.approx([p["recall"] for p in pts])
        assert list(curve.get_ydata()) == pytest.approx([p["precision"] for p in pts])
    assert "accept: inliers >= " in title_of(ax)
    assert_drawn(fig)


# ---------------------------------------------------------------------------------------------
# The checks can fail, and the CLIs still write their files

def test_a_blank_figure_fails_the_pixel_check(docs):
    fig = plot_report.build_sweep([docs["uniform"]], "success")
    assert_drawn(fig)
    with pytest.raises(AssertionError, match="coloured pixels"):
        assert_drawn(blank(fig))
    fig = plot_report.build_dump([docs["run"]])
    with pytest.raises(AssertionError, match="coloured pixels"):
        assert_drawn(blank(fig))


def test_clis_write_png_and_pdf(paths, out, loop_dir):
    def run(*args):
        r = subprocess.run([PY, *args], capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stderr
        return r.stdout.split()

    plots = out / "cli"
    written = run(os.path.join(REPORTS, "plot_report.py"), paths["uniform"], "--out-dir", str(plots))
    assert written == [str(plots / f"uniform_{k}.{e}") for k in ("success", "time")
                       for e in ("png", "pdf")]
    w, h = png_size(plots / "uniform_success.png")
    assert w < 1400 and w / h < 3.5, (w, h)  # 2 panels of 4.5 in and a legend, not a strip
    for p in written:
        if p.endswith(".pdf"):
            assert open(p, "rb").read(5) == b"%PDF-"
    written = run(os.path.join(REPORTS, "plot_loop.py"), str(loop_dir), "--out-dir", str(plots))
    want = [str(plots / f"loop_trajectory_{s}.{e}") for s in ("clique", "ransac")
            for e in ("png", "pdf")] + [str(plots / f"loop_pr.{e}") for e in ("png", "pdf")]
    assert written == want
    lines = subprocess.run([PY, os.path.join(REPORTS, "decisions.py"), paths["uniform"], "--plot",
                            str(plots / "dec.png")], capture_output=True, text=True).stdout
    assert lines.rstrip().endswith(f"plot: {plots / 'dec.png'}")
    png_size(plots / "dec.png")


def test_report_tools_read_a_loop_report(out, loop_dir, loop_doc):
    """plot_report.py draws plot_loop.py's figures from loop.json; summarize.py prints one row per
    solver whose TP / FP are the accepted closures counted here from the report's closure rows."""
    def run(*args):
        return subprocess.run([PY, *args], capture_output=True, text=True, timeout=120)

    plots = out / "from_plot_report"
    r = run(os.path.join(REPORTS, "plot_report.py"), str(loop_dir / "loop.json"), "--out-dir", str(plots))
    assert r.returncode == 0, r.stderr
    solvers = [s["solver"] for s in loop_doc["summary"]]
    assert r.stdout.split() == [str(plots / f"loop_trajectory_{s}.{e}") for s in solvers
                                for e in ("png", "pdf")] + [str(plots / f"loop_pr.{e}") for e in ("png", "pdf")]
    r = run(os.path.join(REPORTS, "summarize.py"), str(loop_dir / "loop.json"))
    assert r.returncode == 0, r.stderr
    header, _, *rows = r.stdout.splitlines()
    names = [c.strip() for c in header.strip("|").split("|")]
    assert len(rows) == len(solvers)
    for line in rows:
        cells = dict(zip(names, (c.strip() for c in line.strip("|").split("|"))))
        mine = [c for c in loop_doc["closures"] if c["solver"] == cells["solver"] and c["accepted"]]
        assert int(cells["TP"]) == sum(c["correct"] for c in mine), cells
        assert int(cells["FP"]) == sum(not c["correct"] for c in mine), cells
    r = run(os.path.join(REPORTS, "decisions.py"), str(loop_dir / "loop.json"))
    assert r.returncode == 2 and "a loop report" in r.stderr, r.stderr
