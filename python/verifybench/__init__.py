"""verifybench from Python: geometric verification solvers on numpy arrays.

    import verifybench as vb
    s = vb.synthetic(n=1000, outliers=0.9, dim=3, seed=1)
    r = vb.solve("clique", s["src"], s["dst"], eps=0.1)
    r["inliers"], r["T"], r["accepted"]
    df = vb.load_report("out/sweep.json")        # one row per result, as pandas

The compiled part (_core) is built by the project's CMake into build/python/verifybench: put
build/python on PYTHONPATH, or install the package (`cmake --install build`, or
`pip install --no-build-isolation .` from the source tree); use Debian's /usr/bin/python3.
"""
import json

from ._core import (InputError, __version__, generator_settings, generators,  # noqa: F401
                    git_commit, read_dump, settings, solve, solvers, synthetic)

__all__ = ["InputError", "__version__", "generator_settings", "generators", "git_commit",
           "load_report", "read_dump", "settings", "solve", "solvers", "synthetic"]


LOOP_TABLES = ("closures", "summary", "maps", "candidates", "true_closures")
REPORT_TABLES = ("results", "aggregates", "decisions")


def load_report(path, table=None):
    """A verifybench JSON report as a pandas DataFrame: sweep, run, dimacs and merge reports
    (table "results", the default: one row per solver and set; "aggregates"; "decisions"), and
    loop.json (table "closures", the default: one row per solver and candidate pair; "summary":
    one row per solver; "maps"; "candidates"; "true_closures"). The report's context and
    parameters are kept in DataFrame.attrs, with its kind ("loop" or "report").
    """
    import pandas as pd

    with open(path) as f:
        report = json.load(f)
    if not isinstance(report, dict) or report.get("schema_version") != 1:
        raise InputError(f"{path}: field 'schema_version': not a verifybench report (version 1)")
    kind = "loop" if report.get("kind") == "loop" else "report"
    tables = LOOP_TABLES if kind == "loop" else REPORT_TABLES
    table = tables[0] if table is None else table
    if table not in tables:
        raise ValueError(f"table {table!r}: a {kind} has " + ", ".join(repr(t) for t in tables))
    rows = report.get(table, [])
    if not isinstance(rows, list):
        raise InputError(f"{path}: field {table!r}: not a list")
    frame = pd.json_normalize(rows) if rows else pd.DataFrame()
    frame.attrs["kind"] = kind
    frame.attrs["context"] = report.get("context", {})
    frame.attrs["parameters"] = report.get("parameters", {})
    return frame
