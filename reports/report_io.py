"""Shared by the report scripts (Debian's /usr/bin/python3 with python3-pandas and python3-scipy):
one-line errors, report loading, reports as pandas DataFrames, interval estimates.

    import report_io
    doc = report_io.load_report("mytool", "sweep.json")
    rows = report_io.results_frame(doc)        # one row per trial (solver x set)
    aggs = report_io.aggregates_frame(doc)     # the report's own summaries
"""
import json
import sys


def fail(tool, msg):
    """Prints `tool: error: msg` on stderr and exits 2, as the C++ tools do."""
    print(f"{tool}: error: {msg}", file=sys.stderr)
    sys.exit(2)


def load_report(tool, path, loop=False):
    """The parsed schema_version 1 report at `path`; anything else ends the script with a message.
    loop=True also takes a loop report (`verifybench loop`'s loop.json: kind 'loop', a 'summary'
    list of one row per solver); the other tools refuse it by name."""
    try:
        with open(path) as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        fail(tool, f"{path}: {e}")
    if not isinstance(doc, dict) or doc.get("schema_version") != 1:
        fail(tool, f"{path}: not a schema_version 1 verifybench report")
    if doc.get("kind") == "loop":
        if not loop:
            fail(tool, f"{path}: a loop report (verifybench loop); {tool} reads sweep, run and "
                       "dimacs reports (summarize.py and plot_report.py read loop reports)")
        if not isinstance(doc.get("summary"), list):
            fail(tool, f"{path}: a loop report without its 'summary' list")
        return doc
    if not isinstance(doc.get("results"), list) or not isinstance(doc.get("aggregates"), list):
        fail(tool, f"{path}: no 'results' and 'aggregates' lists")
    return doc


def parser(tool, doc):
    """An argparse parser for a report script: its docstring as --help, REPORT.json... positional."""
    import argparse
    p = argparse.ArgumentParser(prog=f"{tool}.py", description=doc,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("reports", nargs="+", metavar="REPORT.json")
    return p


def report_kind(doc):
    """'sweep' (synthetic robustness sweep), 'run' (solvers on a dump), 'dimacs' or 'loop'."""
    if doc.get("kind") == "loop":
        return "loop"
    parameters = doc.get("parameters", {})
    if parameters.get("mode") == "dimacs":
        return "dimacs"
    if "sweep" in parameters:
        return "sweep"
    return "run"


def results_frame(doc):
    """The report's rows as a DataFrame (lists such as T_target_source or clique kept as objects)."""
    import pandas as pd
    return pd.DataFrame(doc["results"])


def aggregates_frame(doc):
    import pandas as pd
    return pd.DataFrame(doc["aggregates"])


def wilson_interval(successes, trials, confidence=0.95):
    """Wilson score interval of a success rate (scipy's binomtest); (nan, nan) without trials."""
    if trials <= 0:
        return float("nan"), float("nan")
    from scipy.stats import binomtest
    ci = binomtest(int(successes), int(trials)).proportion_ci(confidence_level=confidence,
                                                              method="wilson")
    return ci.low, ci.high


def success_criterion(doc):
    """The success rule of a report in words, for plot titles."""
    c = doc.get("parameters", {}).get("success_criteria", {})
    if not c:
        return ""
    text = (f"success: rotation error < {c.get('max_rotation_error_deg')} deg and translation error "
            f"< {c.get('max_translation_error')} m")
    return text + (", pair accepted" if c.get("requires_accepted") else "")


def fmt(value, spec):
    """`value` formatted with `spec`, or "-" for a missing (null) value."""
    return "-" if value is None else format(value, spec)
