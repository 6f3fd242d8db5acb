#!/usr/bin/python3
"""Scores accept decisions over one or more reports (issue #13): per solver, TP / FP / TN / FN,
precision, recall and F1 under the calibrated rule the reports ran with (accepted, p < alpha) and
under the paper's fixed count (inliers >= K; K = 5 in 3D, 10 in 2D unless --count), with the
median solve and calibration times. Only rows with an expected decision (positive / negative)
count; error rows are left out and counted apart.

    /usr/bin/python3 reports/decisions.py out/acceptance/*.json [--count K] [--rows]
        [--plot decisions.png]
    /usr/bin/python3 reports/decisions.py REPORT.json... --protocol 3dmatch|kitti|ROT_DEG,TRANS_M

--protocol scores the fitted motions instead, as registration papers do (3DMatch: Zeng et al.,
CVPR 2017, as reported by TEASER++, SC2-PCR, MAC, TurboReg): over every row with a true motion
(negatives left out; error rows count as failures), per solver, the registration recall (rotation
error < 15 deg and translation error < 0.30 m; KITTI: 5 deg and 0.60 m; or the two given), the mean
rotation and translation error of the registered pairs, the mean inlier precision, recall and F1
against the labels (rows with labels), and the mean and median time per pair (solve, and solve plus
calibration). A pair counts as registered by its motion alone, accepted or not.

--rows prints one line per (dump, solver): expected, inliers, the null's mean and threshold,
p-value, its range, d^2 of the fitted motion under the set's pose prior (`prior_d2`; "-" without
one; the calibrated rule rejects beyond the prior gate), the runner-up test's score and p where
it ran (by default on sets without clouds; `--runner-up-alpha`), with its rivals' count and
inliers together where it found any ("(alias)" where they outweigh the accepted motion and the
pair was rejected) and both decisions. The curve
over alpha keeps a pair the runner-up test rejected rejected at every alpha; the test ran only on
pairs accepted at the reports' alpha, so points at a larger alpha include pairs it never saw. `uncertain` counts the calibrated decisions whose p range
(the p that the null's draws cannot tell apart) holds alpha: other draws may reverse them. --plot draws ROC and precision-recall curves per solver: the
calibrated rule over alpha (a sweep of the p-value threshold) and the count rule over K.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_io  # noqa: E402

TOOL = "decisions"


def scores(decisions):
    """(tp, fp, tn, fn, precision, recall, f1) of a list of (expected, accepted) pairs."""
    tp = sum(e and a for e, a in decisions)
    fp = sum((not e) and a for e, a in decisions)
    tn = sum((not e) and (not a) for e, a in decisions)
    fn = sum(e and (not a) for e, a in decisions)
    precision = tp / (tp + fp) if tp + fp else None
    recall = tp / (tp + fn) if tp + fn else None
    f1 = 2 * tp / (2 * tp + fp + fn) if tp + fp + fn else None
    return tp, fp, tn, fn, precision, recall, f1


def median(values):
    v = sorted(x for x in values if x is not None)
    if not v:
        return None
    m = len(v) // 2
    return v[m] if len(v) % 2 else 0.5 * (v[m - 1] + v[m])


def load_rows(paths):
    rows, errors, alphas = [], 0, set()
    for path in paths:
        doc = report_io.load_report(TOOL, path)
        alpha = doc.get("parameters", {}).get("alpha")
        alphas.add(alpha)
        for r in doc["results"]:
            if "solver" not in r or r.get("expected") not in ("positive", "negative"):
                continue
            if r["status"] == "error":
                errors += 1
                continue
            r["_name"] = os.path.basename(r["dataset"].rstrip("/")) if r["dataset"] else "?"
            r["_alpha"] = alpha
            rows.append(r)
    return rows, errors, alphas


def runner_up_text(row):
    """The runner-up test's row cell: its score and p, then "rivals K: S" where K motions holding S
    inliers together competed with the accepted one, "(alias)" where they rejected the pair; "-"
    where it did not run."""
    if row.get("runner_up") is None:
        return "-"
    rivals = row.get("runner_up_rivals") or 0
    family = f", rivals {rivals}: {row.get('runner_up_support')}" if rivals else ""
    alias = " (alias)" if row.get("runner_up_ambiguous") else ""
    return f"{row['runner_up']} ({report_io.fmt(row.get('runner_up_p'), '.2g')}){family}{alias}"


def dense_text(row):
    """The dense check's row cell: the clouds' overlap after ICP, "(refuted)" where it rejected the
    pair; "-" where it did not run (no clouds, or a pair the rule rejected)."""
    check = row.get("dense_check")
    if not check:
        return "-"
    return f"{check['overlap']:.3f}{' (refuted)' if dense_refuted(row) else ''}"


def dense_refuted(row):
    """True when the dense check rejected a pair the accept rule had accepted. The check runs only
    on the pairs accepted at the run's alpha, so past that alpha the curve over alpha counts pairs
    it never saw as the rule alone decides them."""
    return bool(row.get("dense_check")) and not row["accepted"] and \
        row.get("message", "").startswith("dense check")


def uncertain(row):
    """True when the row's p range (draws cannot tell its ends apart) holds alpha: other draws
    may reverse the decision."""
    rng, alpha = row.get("p_value_range"), row.get("_alpha")
    return bool(rng) and alpha is not None and rng[0] < alpha <= rng[1]


PROTOCOLS = {"3dmatch": (15.0, 0.30), "kitti": (5.0, 0.60)}


def parse_protocol(text):
    """(max rotation error [deg], max translation error [m]) of a protocol name or 'DEG,M'."""
    if text in PROTOCOLS:
        return PROTOCOLS[text]
    try:
        rot, trans = (float(v) for v in text.split(","))
    except ValueError:
        raise ValueError(f"--protocol: {text!r} is not 3dmatch, kitti or ROT_DEG,TRANS_M") from None
    if not (0 < rot <= 180 and 0 < trans < math.inf):
        raise ValueError(f"--protocol: {text!r}: need 0 < ROT_DEG <= 180 and 0 < TRANS_M")
    return rot, trans


def load_registration_rows(paths):
    """Every solver row of the reports that has a true motion (expected positive or unlabelled;
    negatives have none to register): rows with errors, and error rows, which count as failures."""
    rows = []
    for path in paths:
        doc = report_io.load_report(TOOL, path)
        for r in doc["results"]:
            if "solver" not in r or r.get("expected") == "negative":
                continue
            if r.get("rotation_error_deg") is None and r["status"] != "error":
                continue  # no ground truth motion
            rows.append(r)
    return rows


def mean(values):
    v = [x for x in values if x is not None]
    return sum(v) / len(v) if v else None


def registration_scores(rows, max_rot_deg, max_trans):
    """The 3DMatch protocol's figures of one solver's rows (load_registration_rows): a dict of
    pairs, registered, recall, mean rotation error [deg] and translation error [m] of the
    registered, mean inlier precision / recall / F1, mean and median solve time and solve plus
    calibration time [ms]."""
    ok = [r for r in rows if r["status"] != "error" and r.get("rotation_error_deg") is not None
          and r["rotation_error_deg"] < max_rot_deg and r["translation_error"] < max_trans]
    total = [r["time_ms"] + (r.get("calibration_ms") or 0.0) for r in rows if r.get("time_ms") is not None]
    return {
        "pairs": len(rows),
        "registered": len(ok),
        "recall": len(ok) / len(rows) if rows else None,
        "rotation_error_deg": mean(r["rotation_error_deg"] for r in ok),
        "translation_error": mean(r["translation_error"] for r in ok),
        "inlier_precision": mean(r.get("inlier_precision") for r in rows),
        "inlier_recall": mean(r.get("inlier_recall") for r in rows),
        "inlier_f1": mean(r.get("inlier_f1") for r in rows),
        "time_ms_mean": mean(r.get("time_ms") for r in rows),
        "time_ms_median": median(r.get("time_ms") for r in rows),
        "total_ms_mean": mean(total),
    }


def registration_table(rows, max_rot_deg, max_trans):
    """The protocol's table (markdown), one line per solver in the rows' order."""
    lines = [f"registration: rotation error < {max_rot_deg:g} deg and translation error < "
             f"{max_trans:g} m; errors of the registered pairs; inlier scores of every pair",
             "",
             "| solver | pairs | registered | recall | RE deg | TE cm | inlier P | inlier R | "
             "inlier F1 | solve ms mean | solve ms median | with calibration ms mean |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in dict.fromkeys(r["solver"] for r in rows):
        g = registration_scores([r for r in rows if r["solver"] == s], max_rot_deg, max_trans)
        te = g["translation_error"]
        lines.append(
            f"| {s} | {g['pairs']} | {g['registered']} | {report_io.fmt(g['recall'], '.3f')} | "
            f"{report_io.fmt(g['rotation_error_deg'], '.2f')} | "
            f"{report_io.fmt(None if te is None else 100 * te, '.1f')} | "
            f"{report_io.fmt(g['inlier_precision'], '.3f')} | {report_io.fmt(g['inlier_recall'], '.3f')} | "
            f"{report_io.fmt(g['inlier_f1'], '.3f')} | {report_io.fmt(g['time_ms_mean'], '.1f')} | "
            f"{report_io.fmt(g['time_ms_median'], '.1f')} | {report_io.fmt(g['total_ms_mean'], '.1f')} |")
    return "\n".join(lines)


def registration_matrix(rows, max_rot_deg, max_trans):
    """Registration recall and median solve time per solver (rows) and outlier ratio (columns),
    markdown; None when the rows hold fewer than two outlier ratios."""
    ratios = sorted({r.get("outlier_ratio") for r in rows if r.get("outlier_ratio") is not None})
    if len(ratios) < 2:
        return None
    head = " | ".join(f"{100 * x:g}%" for x in ratios)
    lines = [f"registration recall by outlier ratio (median solve ms)", "",
             f"| solver | {head} |", "|---|" + "---|" * len(ratios)]
    for s in dict.fromkeys(r["solver"] for r in rows):
        cells = []
        for x in ratios:
            mine = [r for r in rows if r["solver"] == s and r.get("outlier_ratio") == x]
            g = registration_scores(mine, max_rot_deg, max_trans)
            cells.append(f"{report_io.fmt(g['recall'], '.2f')} ({report_io.fmt(g['time_ms_median'], '.3g')})")
        lines.append(f"| {s} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def count_threshold(row, count):
    return count if count else (10 if row["dim"] == 2 else 5)


def main():
    p = report_io.parser(TOOL, __doc__)
    p.add_argument("--count", type=int, default=0, help="K of the count rule (0: 5 in 3D, 10 in 2D)")
    p.add_argument("--rows", action="store_true", help="one line per dump and solver")
    p.add_argument("--plot", metavar="PNG", help="ROC and precision-recall curves")
    p.add_argument("--protocol", metavar="NAME",
                   help="registration recall instead: 3dmatch (15 deg, 0.30 m), kitti (5 deg, 0.60 m) "
                        "or ROT_DEG,TRANS_M")
    args = p.parse_args()
    if args.protocol:
        try:
            max_rot, max_trans = parse_protocol(args.protocol)
        except ValueError as e:
            report_io.fail(TOOL, str(e))
        reg = load_registration_rows(args.reports)
        if not reg:
            report_io.fail(TOOL, "no rows with a true motion in the reports")
        matrix = registration_matrix(reg, max_rot, max_trans)
        if matrix:
            print(matrix + "\n")
        print(registration_table(reg, max_rot, max_trans))
        return
    rows, errors, alphas = load_rows(args.reports)
    if not rows:
        report_io.fail(TOOL, "no rows with an expected decision in the reports")
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    if args.rows:
        print("| dump | expected | solver | inliers | null mean | threshold | p | p range | prior d^2 | "
              "runner-up (p) | dense overlap | pvalue | count |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            count_ok = r["inliers"] >= count_threshold(r, args.count)
            p_text = report_io.fmt(r.get("p_value"), ".2g")
            rng = r.get("p_value_range")
            rng_text = (f"{rng[0]:.2g} - {rng[1]:.2g}{' (holds alpha)' if uncertain(r) else ''}"
                        if rng else "-")
            print(f"| {r['_name']} | {r['expected']} | {r['solver']} | {r['inliers']} | "
                  f"{report_io.fmt(r.get('null_mean'), '.1f')} | "
                  f"{report_io.fmt(r.get('null_threshold'), 'd')} | {p_text} | {rng_text} | "
                  f"{report_io.fmt(r.get('prior_d2'), '.3g')} | {runner_up_text(r)} | {dense_text(r)} | "
                  f"{'accept' if r['accepted'] else 'reject'} | "
                  f"{'accept' if count_ok else 'reject'} |")
        print()
    alpha_text = ", ".join(str(a) for a in sorted(a for a in alphas if a is not None)) or "?"
    print(f"| solver | rule | TP | FP | TN | FN | precision | recall | F1 | median solve ms | "
          f"median calibration ms | calibration / solve | uncertain |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for s in solvers:
        mine = [r for r in rows if r["solver"] == s]
        solve = median(r["time_ms"] for r in mine)
        cal = median(r.get("calibration_ms") for r in mine)
        pv = [r for r in mine if r.get("accept_rule") == "pvalue"]
        rules = []
        if pv:
            rules.append((f"p < {alpha_text}", [(r["expected"] == "positive", r["accepted"]) for r in pv]))
        rules.append((f"count >= {args.count or '5/10'}",
                      [(r["expected"] == "positive", r["inliers"] >= count_threshold(r, args.count))
                       for r in mine]))
        for name, decided in rules:
            tp, fp, tn, fn, prec, rec, f1 = scores(decided)
            ratio = cal / solve if (cal is not None and solve) and name.startswith("p") else None
            print(f"| {s} | {name} | {tp} | {fp} | {tn} | {fn} | {report_io.fmt(prec, '.3f')} | "
                  f"{report_io.fmt(rec, '.3f')} | {report_io.fmt(f1, '.3f')} | "
                  f"{report_io.fmt(solve, '.1f')} | "
                  f"{report_io.fmt(cal if name.startswith('p') else None, '.1f')} | "
                  f"{report_io.fmt(ratio, '.1f')} | "
                  f"{sum(map(uncertain, pv)) if name.startswith('p') else '-'} |")
    if errors:
        print(f"\n{errors} error rows left out")
    if args.plot:
        plot(rows, solvers, args.plot, args.count)


def curve(rows, accept):
    """(fpr, tpr, precision, recall) of one decision function."""
    decided = [(r["expected"] == "positive", accept(r)) for r in rows]
    tp, fp, tn, fn, prec, rec, _ = scores(decided)
    fpr = fp / (fp + tn) if fp + tn else float("nan")
    tpr = tp / (tp + fn) if tp + fn else float("nan")
    return fpr, tpr, (prec if prec is not None else 1.0), (rec if rec is not None else float("nan"))


def op_text(op):
    """An operating point's rates for a legend: ' (FAR 0.00, TAR 0.91, P 1.00)'."""
    fpr, tpr, prec, _ = op
    f = lambda v: "-" if v != v else f"{v:.2f}"  # noqa: E731
    return f" (FAR {f(fpr)}, TAR {f(tpr)}, P {f(prec)})"


def build_decisions(rows, solvers, count=0):
    """The ROC and precision-recall figure of `rows` (load_rows), per solver: the calibrated rule
    over alpha and the count rule over K, with each rule's operating point as the reports ran it
    (the rows' own decisions at the reports' alpha; inliers >= K at `count`, 0: 5 in 3D, 10 in
    2D) marked. Returns the matplotlib Figure."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    import plot_style as style
    fig, (roc, pr) = plt.subplots(1, 2, figsize=(2 * style.PANEL_W + 3.2, style.PANEL_H + 1.3),
                                  sharex=True, sharey=True)
    alphas = [10.0 ** e for e in range(-16, 0)]
    markers = "o^v<>"  # not the operating points' star and diamond
    run_alphas = sorted({r["_alpha"] for r in rows if r.get("_alpha") is not None})
    alpha_text = ", ".join(f"{a:g}" for a in run_alphas) or "?"
    dims = sorted({r["dim"] for r in rows})
    k_text = " / ".join(f"{count_threshold({'dim': d}, count)} ({d}D)" for d in dims)

    drawn = []  # the ROC's curves, drawn again in its zoom

    def draw(k, xs, ys, fmt, gid, label, **kw):
        drawn.append((k, xs, fmt, gid, kw))
        for ax, (x, y) in ((roc, xs), (pr, ys)):
            tr = style.nudge(fig, ax, k, len(solvers))
            (line,) = ax.plot(x, y, fmt, transform=tr, label=label if ax is pr else None, **kw)
            line.set_gid(f"{'roc' if ax is roc else 'pr'}:{gid}")

    for k, s in enumerate(solvers):
        mine = [r for r in rows if r["solver"] == s]
        colour, marker = f"C{k}", markers[k % len(markers)]
        counts = sorted(set(r["inliers"] for r in mine) | {0})
        cnt = [curve(mine, lambda r, c=c: r["inliers"] >= c) for c in counts]
        draw(k, ([c[0] for c in cnt], [c[1] for c in cnt]), ([c[3] for c in cnt], [c[2] for c in cnt]),
             "--", f"count:{s}", f"{s}: count rule over K", color=colour, lw=1.2)
        pv = [r for r in mine if r.get("p_value") is not None]
        if pv:
            cal = [curve(pv, lambda r, a=a: r["p_value"] < a and r["inliers"] >= 3
                         and not r.get("runner_up_ambiguous") and not dense_refuted(r))
                   for a in alphas]
            draw(k, ([c[0] for c in cal], [c[1] for c in cal]), ([c[3] for c in cal], [c[2] for c in cal]),
                 "-", f"alpha:{s}", f"{s}: p < alpha, alpha 1e-16..0.1", color=colour, lw=1.2,
                 marker=marker, ms=3.5)
        # Operating points: the decisions as the reports made them.
        calibrated = [r for r in mine if r.get("accept_rule") == "pvalue"]
        if calibrated:
            op = curve(calibrated, lambda r: bool(r["accepted"]))
            draw(k, ([op[0]], [op[1]]), ([op[3]], [op[2]]), "*", f"operating:pvalue:{s}",
                 f"{s}: as run, p < {alpha_text}{op_text(op)}", color=colour, ms=14, mec="k", mew=0.8, zorder=5)
        op = curve(mine, lambda r: r["inliers"] >= count_threshold(r, count))
        draw(k, ([op[0]], [op[1]]), ([op[3]], [op[2]]), "D", f"operating:count:{s}",
             f"{s}: inliers >= {k_text}{op_text(op)}", color=colour, ms=7.5, mec="k", mew=0.8, zorder=5)
    positives = sum(r["expected"] == "positive" for r in rows)
    roc.set_xlabel("false accept rate (negatives accepted)")
    roc.set_ylabel("true accept rate (positives accepted)")
    roc.set_title("ROC of the accept decision", fontsize=9)
    pr.set_xlabel("recall")
    pr.set_ylabel("precision")
    pr.tick_params(labelleft=True)
    pr.set_title("precision-recall of the accept decision", fontsize=9)
    for ax in (roc, pr):
        ax.grid(alpha=0.3)
        ax.set_xlim(-0.03, 1.03)
        ax.set_ylim(-0.03, 1.03)
    # Operating points near a false accept rate of 0 crowd the ROC's corner: a zoom shows them.
    ops = [(xs[0][0], xs[1][0]) for _, xs, _, gid, _ in drawn if gid.startswith("operating:")]
    ops = [(x, y) for x, y in ops if x == x and y == y]
    if ops and max(x for x, _ in ops) <= 0.1:
        zoom = roc.inset_axes([0.36, 0.1, 0.6, 0.55])
        zoom.set_gid("roc_zoom")
        for k, xs, fmt, gid, kw in drawn:
            (line,) = zoom.plot(*xs, fmt, transform=style.nudge(fig, zoom, k, len(solvers)), **kw)
            line.set_gid(f"zoom:{gid}")
        right = max(0.05, 1.5 * max(x for x, _ in ops))
        bottom = max(-0.02, min(y for _, y in ops) - 0.15)
        zoom.set_xlim(-0.1 * right, right)
        zoom.set_ylim(bottom, 1.0 + 0.1 * (1.0 - bottom))
        zoom.tick_params(labelsize=7)
        zoom.grid(alpha=0.3)
        zoom.set_title("zoom", fontsize=7, pad=2)
        roc.indicate_inset_zoom(zoom, edgecolor="0.4")
    handles, labels = pr.get_legend_handles_labels()
    handles.append(Line2D([], [], linestyle="none"))
    labels.append(f"star / diamond: operating points;\nsolvers drawn {style.OFFSET_PT:g} pt apart "
                  "so equal curves stay visible")
    pr.legend(handles, labels, fontsize=7, loc="upper left", bbox_to_anchor=(1.03, 1.0),
              borderaxespad=0.0)
    fig.suptitle(f"accept decisions on {positives} positive sets and {len(rows) - positives} "
                 f"negative twins (positive: the sides share the true motion)\n"
                 f"calibrated rule: accept when p < alpha (the reports ran alpha = {alpha_text}); "
                 f"count rule: accept when inliers >= K (K = {k_text})", fontsize=9)
    fig.tight_layout()
    return fig


def plot(rows, solvers, path, count=0):
    import matplotlib.pyplot as plt
    fig = build_decisions(rows, solvers, count)
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, path)
    plt.close(fig)
    print(f"\nplot: {path}")


if __name__ == "__main__":
    main()
