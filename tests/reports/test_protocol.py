"""reports/decisions.py --protocol: the registration recall, the errors of the registered pairs,
the inlier scores and the times against values worked out by hand on a report written here."""
import json
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPORTS = os.path.join(HERE, "..", "..", "reports")
sys.path.insert(0, REPORTS)
import decisions  # noqa: E402


def row(solver, rot, trans, status="ok", expected=None, prec=None, rec=None, f1=None, ms=10.0, cal=None):
    return {"solver": solver, "status": status, "expected": expected, "rotation_error_deg": rot,
            "translation_error": trans, "inlier_precision": prec, "inlier_recall": rec,
            "inlier_f1": f1, "time_ms": ms, "calibration_ms": cal, "dim": 3}


ROWS = [
    # a: 2 of 4 registered under 3DMatch (15 deg, 0.30 m); the 0.29 m one fails KITTI's 5 deg
    row("a", 1.0, 0.10, prec=1.0, rec=0.5, f1=2 / 3, ms=10.0, cal=90.0),
    row("a", 6.0, 0.29, prec=0.5, rec=0.5, f1=0.5, ms=20.0),
    row("a", 16.0, 0.01, prec=0.0, rec=0.0, f1=0.0, ms=30.0),   # rotation too large
    row("a", None, None, status="error", ms=None),               # an error is a failure
    row("a", 0.1, 0.01, expected="negative"),                    # negatives are left out
    # b: 1 of 1, no labels
    row("b", 2.0, 0.50, ms=5.0),                                 # 0.5 m: fails 3DMatch, meets KITTI
]


def test_scores_against_hand_values():
    a = [r for r in ROWS if r["solver"] == "a" and r["expected"] != "negative"]
    g = decisions.registration_scores(a, 15.0, 0.30)
    assert g["pairs"] == 4 and g["registered"] == 2
    assert g["recall"] == pytest.approx(0.5)
    assert g["rotation_error_deg"] == pytest.approx(3.5)         # (1 + 6) / 2
    assert g["translation_error"] == pytest.approx(0.195)        # (0.10 + 0.29) / 2
    assert g["inlier_precision"] == pytest.approx(0.5)           # (1 + 0.5 + 0) / 3
    assert g["inlier_f1"] == pytest.approx((2 / 3 + 0.5) / 3)
    assert g["time_ms_mean"] == pytest.approx(20.0)              # the error row has no time
    assert g["total_ms_mean"] == pytest.approx((100.0 + 20.0 + 30.0) / 3)
    kitti = decisions.registration_scores(a, *decisions.PROTOCOLS["kitti"])
    assert kitti["registered"] == 1 and kitti["recall"] == pytest.approx(0.25)


def test_protocol_names_and_bad_values():
    assert decisions.parse_protocol("3dmatch") == (15.0, 0.30)
    assert decisions.parse_protocol("kitti") == (5.0, 0.60)
    assert decisions.parse_protocol("10,0.2") == (10.0, 0.2)
    for bad in ("3DMatchX", "10", "0,0.3", "10,nan", "200,1"):
        with pytest.raises(ValueError):
            decisions.parse_protocol(bad)


def test_cli_table(tmp_path):
    doc = {"schema_version": 1, "parameters": {}, "aggregates": [], "results": ROWS}
    path = tmp_path / "r.json"
    path.write_text(json.dumps(doc))
    out = subprocess.run([sys.executable, os.path.join(REPORTS, "decisions.py"), str(path),
                          "--protocol", "kitti"], capture_output=True, text=True, check=True).stdout
    lines = {l.split("|")[1].strip(): [c.strip() for c in l.split("|")[1:-1]]
             for l in out.splitlines() if l.startswith("| a ") or l.startswith("| b ")}
    assert lines["a"][1:4] == ["4", "1", "0.250"]
    assert lines["b"][1:4] == ["1", "1", "1.000"]
    assert lines["b"][5] == "50.0"  # cm
    bad = subprocess.run([sys.executable, os.path.join(REPORTS, "decisions.py"), str(path),
                          "--protocol", "nope"], capture_output=True, text=True)
    assert bad.returncode == 2 and "--protocol" in bad.stderr


def test_matrix_by_outlier_ratio():
    rows = [dict(row("a", 1.0, 0.1, ms=4.0), outlier_ratio=0.5), dict(row("a", 30.0, 0.1, ms=6.0), outlier_ratio=0.5),
            dict(row("a", 1.0, 0.1, ms=8.0), outlier_ratio=0.9)]
    text = decisions.registration_matrix(rows, 15.0, 0.30)
    assert "| 50% | 90% |" in text
    assert "| a | 0.50 (5) | 1.00 (8) |" in text
    assert decisions.registration_matrix(rows[:2], 15.0, 0.30) is None
