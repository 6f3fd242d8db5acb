#!/usr/bin/python3
"""What the plot scripts share (plot_report.py, plot_loop.py, decisions.py): panel sizes, markers,
colours, the accept rule in words, log axes, the small offsets that keep equal curves apart, and a
figure writer that never leaves a half-written file under the final name."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator  # noqa: E402
from matplotlib.transforms import ScaledTranslation  # noqa: E402

MARKERS = "osD^vP*X"
LINESTYLES = ["-", "--", "-.", ":"]
PANEL_W, PANEL_H = 4.5, 3.4  # inches per panel
LOG_SPAN = 100.0  # a time axis turns logarithmic only beyond this max / min ratio
OFFSET_PT = 2.0  # curves of different solvers are drawn this many points apart
DPI = 110


def colours(names):
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    if len(names) > len(cycle):  # 20 distinct colours before any repeats
        cycle = [matplotlib.colormaps["tab20"](i) for i in range(20)]
    return {s: cycle[i % len(cycle)] for i, s in enumerate(sorted(names))}


def accept_rule_text(parameters, dim=None):
    """The accept rule a report ran with, in words: 'accept: p < 0.001 (permutation null)' or
    'accept: inliers >= 5'. `dim` picks the count rule's default threshold (5 in 3D, 10 in 2D);
    without it both are named."""
    rule = parameters.get("accept_rule")
    if rule == "pvalue":
        return f"accept: p < {parameters.get('alpha')} (the pair's permutation null)"
    if rule == "count":
        k = parameters.get("min_inliers") or 0
        if k:
            return f"accept: inliers >= {k}"
        k2, k3 = parameters.get("accept_threshold_2d", 10), parameters.get("accept_threshold_3d", 5)
        if dim in (2, 3):
            return f"accept: inliers >= {k2 if dim == 2 else k3}"
        return f"accept: inliers >= {k3} (3D) / {k2} (2D)"
    return f"accept rule: {rule}" if rule else "accept rule: not recorded"


def count_threshold(parameters, dim):
    """K of the count rule at `dim` as the report ran it."""
    k = parameters.get("min_inliers") or 0
    return k or parameters.get(f"accept_threshold_{dim}d", 10 if dim == 2 else 5)


def time_scale(values):
    """'log' when the positive values span more than LOG_SPAN (max / min), else 'linear'."""
    v = [x for x in values if x is not None and x == x and x > 0]
    if len(v) < 2:
        return "linear"
    return "log" if max(v) / min(v) > LOG_SPAN else "linear"


def log_axis(axis, ax):
    """Log scale labelled at 1, 2 and 5 of every decade, not only at the decades. `axis`: 'x'|'y'."""
    getattr(ax, f"set_{axis}scale")("log")
    plain = FuncFormatter(lambda v, _: f"{v:g}")
    a = ax.xaxis if axis == "x" else ax.yaxis
    a.set_major_locator(LogLocator(base=10))
    a.set_major_formatter(plain)
    a.set_minor_locator(LogLocator(base=10, subs=(2, 5)))
    a.set_minor_formatter(plain)
    ax.tick_params(axis=axis, which="minor", labelsize=7)


def nudge(fig, ax, k, count, points=OFFSET_PT, vertical=True):
    """A data transform shifted by a few points for the k-th of `count` curves, so curves with
    equal values stay visible side by side; the line's data stay the report's values."""
    d = (k - (count - 1) / 2) * points / 72.0
    return ax.transData + ScaledTranslation(d, d if vertical else 0.0, fig.dpi_scale_trans)


def save_figure(fig, base, exts=("png", "pdf")):
    """Writes base.<ext> for each ext through a temporary name, so no half-written plot has the
    final name; closes the figure. Returns the paths."""
    paths = []
    for ext in exts:
        path = f"{base}.{ext}"
        tmp = f"{path}.tmp.{ext}"
        fig.savefig(tmp, dpi=DPI)
        os.replace(tmp, path)
        paths.append(path)
    plt.close(fig)
    return paths
