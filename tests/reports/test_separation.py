"""reports/separation.py: labels, ROC areas and the recall at no false accept against values worked
out by hand on a run report and a loop report written here."""
import json
import math
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPORTS = os.path.join(HERE, "..", "..", "reports")
sys.path.insert(0, REPORTS)
import separation  # noqa: E402


def run_row(solver, expected, success, inliers, p=None, lever=None, status="ok"):
    return {"solver": solver, "expected": expected, "success": success, "inliers": inliers,
            "n": 100, "p_value": p, "lever_arm": lever, "status": status}


def test_labels():
    assert separation.label(run_row("a", "positive", True, 10), loop=False) is True
    assert separation.label(run_row("a", "positive", False, 10), loop=False) is False  # wrong motion
    assert separation.label(run_row("a", "negative", None, 10), loop=False) is False
    assert separation.label(run_row("a", None, True, 10), loop=False) is None         # unknown
    assert separation.label(run_row("a", "positive", True, 10, status="error"), loop=False) is None
    assert separation.label(run_row("a", "positive", True, 0), loop=False) is None    # no inliers
    assert separation.label({"correct": True, "inliers": 3, "status": "ok"}, loop=True) is True
    assert separation.label({"correct": False, "inliers": 3, "status": "rejected"}, loop=True) is False


def test_separation_by_hand():
    # good 5, 7, 9 against bad 4, 7: pairs won 5>4; 7>4, 7=7 (half); 9>4, 9>7 -> 4.5 of 6
    area, recall = separation.separation([5, 7, 9], [4, 7])
    assert area == pytest.approx(4.5 / 6)
    assert recall == pytest.approx(1 / 3)  # only 9 is above every bad score
    assert separation.separation([1, 2], []) == (None, None)


def test_cli_on_written_reports(tmp_path):
    run = {"schema_version": 1, "kind": "run", "parameters": {}, "aggregates": [], "results": [
        run_row("a", "positive", True, 30, p=1e-9, lever=5.0),
        run_row("a", "positive", True, 20, p=1e-6, lever=1.0),
        run_row("a", "negative", None, 25, p=1e-4, lever=0.5),
        run_row("a", "positive", False, 8, p=None, lever=2.0),   # no p: left out of -log10 p only
    ]}
    loop = {"schema_version": 1, "kind": "loop", "summary": [], "closures": [
        {"solver": "a", "correct": True, "inliers": 12, "n": 50, "status": "ok", "prior_d2": 1.0},
        {"solver": "a", "correct": False, "inliers": 14, "n": 50, "status": "ok", "prior_d2": 40.0},
    ]}
    (tmp_path / "run.json").write_text(json.dumps(run))
    (tmp_path / "loop.json").write_text(json.dumps(loop))
    out = subprocess.run([sys.executable, os.path.join(REPORTS, "separation.py"),
                          str(tmp_path / "run.json"), str(tmp_path / "loop.json")],
                         capture_output=True, text=True, check=True).stdout
    lines = {l.split("|")[1].strip(): [c.strip() for c in l.split("|")[2:-1]]
             for l in out.splitlines() if l.startswith("| ") and not l.startswith("| statistic")}
    # inliers: good 30, 20, 12 against bad 25, 8, 14: wins 3 + 2 + 1 = 6 of 9; above 25: 30 only
    assert lines["inliers"] == ["3", "3", "0.667", "0.333"]
    # -log10 p: good 9, 6 against bad 4: both above
    assert lines["-log10 p"] == ["2", "1", "1.000", "1.000"]
    # lever arm: good 5, 1 against bad 0.5, 2: wins 2 + 1 = 3 of 4; above 2: 5 only
    assert lines["lever arm"] == ["2", "2", "0.750", "0.500"]
    # -prior d2: good -1 against bad -40
    assert lines["-prior d2"] == ["1", "1", "1.000", "1.000"]
    assert "dense overlap" not in lines


def test_refuses_reports_without_labelled_rows(tmp_path):
    (tmp_path / "r.json").write_text(json.dumps(
        {"schema_version": 1, "kind": "run", "parameters": {}, "aggregates": [],
         "results": [run_row("a", None, True, 10)]}))
    r = subprocess.run([sys.executable, os.path.join(REPORTS, "separation.py"), str(tmp_path / "r.json")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert "no labelled row" in r.stderr
