"""The Python module against oracles: a brute-force maximum consistent set, the generator's known
motion and labels, the CLI on the same set, and bad input. Run by ctest (python_bindings) with
build/python on PYTHONPATH and VERIFYBENCH_CLI naming the CLI."""
import itertools
import json
import os
import subprocess

import numpy as np
import pytest

import verifybench as vb


def rotation_error_deg(Ra, Rb):
    c = (np.trace(Ra.T @ Rb) - 1) / 2 if Ra.shape[0] == 3 else np.trace(Ra.T @ Rb) / 2
    return np.degrees(np.arccos(np.clip(c, -1, 1)))


def brute_force_omega(src, dst, eps):
    """Largest set of correspondences pairwise consistent under Eq. (1), by enumeration."""
    n = len(src)
    ok = np.abs(np.linalg.norm(src[:, None] - src[None], axis=2) -
                np.linalg.norm(dst[:, None] - dst[None], axis=2)) < eps
    for size in range(n, 0, -1):
        for subset in itertools.combinations(range(n), size):
            if all(ok[a, b] for a, b in itertools.combinations(subset, 2)):
                return size
    return 0


@pytest.mark.parametrize("seed", range(6))
def test_clique_finds_the_brute_force_maximum(seed):
    rng = np.random.default_rng(seed)
    src = rng.uniform(0, 4, size=(13, 2))
    angle = rng.uniform(-np.pi, np.pi)
    R = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    dst = src @ R.T + [1.0, -2.0]
    dst[7:] = rng.uniform(0, 4, size=(6, 2))  # 6 outliers, some consistent by chance
    r = vb.solve("clique", src, dst, eps=0.3)
    assert r["status"] in ("ok", "rejected")
    assert len(r["inliers"]) == brute_force_omega(src, dst, 0.3)
    assert r["omega_upper_bound"] == len(r["inliers"])


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("solver", ["clique", "ransac", "lo-ransac", "jcbb"])
def test_solvers_recover_the_known_motion(dim, solver):
    s = vb.synthetic(n=300, outliers=0.8, noise=0.01, dim=dim, seed=5)
    r = vb.solve(solver, s["src"], s["dst"], eps=0.1)
    assert r["accepted"]
    assert r["T"].shape == (dim + 1, dim + 1)
    assert rotation_error_deg(r["T"][:dim, :dim], s["T"][:dim, :dim]) < 2.0
    assert np.linalg.norm(r["T"][:dim, dim] - s["T"][:dim, dim]) < 0.1
    inliers = r["inliers"]
    assert np.all(np.diff(inliers) > 0)
    assert s["labels"][inliers].mean() > 0.95
    assert len(inliers) >= 0.9 * s["labels"].sum()


def test_same_answer_as_the_cli(tmp_path):
    cli = os.environ.get("VERIFYBENCH_CLI")
    if not cli:
        pytest.skip("VERIFYBENCH_CLI not set")
    s = vb.synthetic(n=400, outliers=0.9, dim=3, seed=11)
    dump = tmp_path / "dump"
    dump.mkdir()
    np.savetxt(dump / "corr.txt", np.hstack([s["src"], s["dst"]]), fmt="%.17g")
    report = tmp_path / "r.json"
    subprocess.run([cli, "run", "--dump", str(dump), "--solvers", "clique,ransac", "--accept", "count",
                    "--quiet", "--out", str(report)], check=True, capture_output=True)
    rows = {row["solver"]: row for row in json.load(open(report))["results"]}
    for solver in ("clique", "ransac"):
        r = vb.solve(solver, s["src"], s["dst"], eps=0.1, seed=rows[solver]["solver_seed"])
        assert len(r["inliers"]) == rows[solver]["inliers"]
        assert np.allclose(r["T"].ravel(), rows[solver]["T_target_source"], atol=1e-9)
        assert r["accepted"] == rows[solver]["accepted"]


def test_calibrated_rule_accepts_a_loop_and_rejects_a_negative():
    pos = vb.synthetic(n=500, outliers=0.95, dim=3, seed=2)
    neg = vb.synthetic(n=500, dim=3, seed=2, negative=True)
    assert neg["T"] is None and neg["positive"] is False
    # eps 0.5 m: chance cliques of 7-10 in this 10 m cube (BENCHMARK section 14), over the paper's 5
    a = vb.solve("clique", pos["src"], pos["dst"], eps=0.5, accept="pvalue")
    b = vb.solve("clique", neg["src"], neg["dst"], eps=0.5, accept="pvalue")
    assert a["accepted"] and a["p_value"] < 0.001
    assert not b["accepted"] and b["p_value"] >= 0.001
    count = vb.solve("clique", neg["src"], neg["dst"], eps=0.5, accept="count")  # the paper's rule
    assert count["accepted"] and len(count["inliers"]) >= 5 and count["p_value"] is None
    assert count["p_value_range"] is None
    for r in (a, b):
        assert r["p_value_range"][0] <= r["p_value"] <= r["p_value_range"][1]
    # 25 inliers: below the 34 any screen of score bounds needs, so the null was solved; 250
    # inliers: the bounds of the permuted sets (near the chance cliques) decide it
    clear = vb.synthetic(n=500, outliers=0.5, dim=3, seed=2)
    c = vb.solve("clique", clear["src"], clear["dst"], eps=0.5, accept="pvalue")
    assert c["accepted"] and c["null_screened"]
    assert not a["null_screened"] and not b["null_screened"] and not count["null_screened"]


def test_pose_prior_gates_the_calibrated_rule():
    # The loop's own motion as prior (sigmas 2 deg, 0.5 m): accepted, d^2 = delta^T P^-1 delta by
    # hand from the returned T. Turned 90 deg about z and 20 m off: rejected under 'pvalue',
    # accepted without the gate and under the count rule.
    s = vb.synthetic(n=300, outliers=0.5, dim=3, seed=3)
    cov = np.diag([np.radians(2.0) ** 2] * 3 + [0.25] * 3)
    a = vb.solve("clique", s["src"], s["dst"], eps=0.1, accept="pvalue", prior_T=s["T"], prior_cov=cov)
    assert a["accepted"]
    E = a["T"] @ np.linalg.inv(s["T"])
    angle = np.arccos(np.clip((np.trace(E[:3, :3]) - 1) / 2, -1, 1))
    w = np.array([E[2, 1] - E[1, 2], E[0, 2] - E[2, 0], E[1, 0] - E[0, 1]])
    w = w * (angle / (2 * np.sin(angle))) if angle > 1e-12 else w / 2
    delta = np.concatenate([w, E[:3, 3]])
    assert abs(a["prior_d2"] - delta @ np.linalg.solve(cov, delta)) <= 1e-6 * max(1.0, a["prior_d2"])
    off = np.eye(4)
    off[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
    off[0, 3] = 20.0
    far = off @ s["T"]
    b = vb.solve("clique", s["src"], s["dst"], eps=0.1, accept="pvalue", prior_T=far, prior_cov=cov)
    assert not b["accepted"] and b["p_value"] < 0.001 and b["prior_d2"] > 400
    assert vb.solve("clique", s["src"], s["dst"], eps=0.1, accept="pvalue", prior_T=far,
                    prior_cov=cov, prior_gate=0.0)["accepted"]
    assert vb.solve("clique", s["src"], s["dst"], eps=0.1, accept="count", prior_T=far,
                    prior_cov=cov)["accepted"]
    assert vb.solve("clique", s["src"], s["dst"], eps=0.1)["prior_d2"] is None
    with pytest.raises(ValueError, match="come together"):
        vb.solve("clique", s["src"], s["dst"], prior_T=far)
    with pytest.raises(ValueError, match="prior_cov must be a 6 x 6"):
        vb.solve("clique", s["src"], s["dst"], prior_T=far, prior_cov=np.eye(3))
    with pytest.raises(ValueError, match="positive definite"):
        vb.solve("clique", s["src"], s["dst"], prior_T=far, prior_cov=-cov)
    with pytest.raises(ValueError, match="prior_T"):
        vb.solve("clique", s["src"], s["dst"], prior_T=2 * far, prior_cov=cov)


def test_runner_up_test_rejects_a_corridors_shifted_copies():
    # A repetitive negative: four shifted copies of the corridor and no true motion. The null
    # accepts one copy; the runner-up test (on by default without clouds, runner_up_alpha=0 turns
    # it off) finds the other copies, which together outweigh it, and rejects the pair.
    s = vb.synthetic(n=300, dim=3, seed=11, kind="repetitive", negative=True)
    plain = vb.solve("clique", s["src"], s["dst"], eps=0.1, runner_up_alpha=0)
    assert plain["accepted"] and plain["runner_up"] is None and not plain["runner_up_ambiguous"]
    assert plain["runner_up_rivals"] is None and plain["runner_up_support"] is None
    r = vb.solve("clique", s["src"], s["dst"], eps=0.1)
    assert not r["accepted"] and r["runner_up_ambiguous"]
    assert r["runner_up"] >= 0.6 * len(r["inliers"]) and r["runner_up_p"] < 0.001
    assert r["runner_up_separation"] > 10.0
    assert r["runner_up_rivals"] >= 1 and r["runner_up_support"] >= len(r["inliers"])
    assert len(r["inliers"]) + r["runner_up_support"] <= 300


def test_dense_check_refines_with_the_clouds_and_refutes_an_alias():
    # The clouds two scans would give: three orthogonal planes of a 20 m corner, the target's the
    # source's moved 1 m along x. 40 matches follow that motion among 40 drawn at random.
    if not any(r["keyword"] == "dense_overlap" for r in vb.settings()):
        pytest.skip("built without the front end (no dense check)")
    rng = np.random.default_rng(7)
    a, b = rng.uniform(0, 20, 3000), rng.uniform(0, 20, 3000)
    k = rng.integers(0, 3, 3000)
    cloud = np.where((k == 0)[:, None], np.c_[a, b, 0 * a],
                     np.where((k == 1)[:, None], np.c_[a, 0 * a, b], np.c_[0 * a, a, b]))
    shift = np.array([1.0, 0.0, 0.0])
    src = np.vstack([cloud[rng.choice(3000, 40, replace=False)], cloud[rng.choice(3000, 40)]])
    dst = np.vstack([src[:40] + shift, rng.uniform(0, 20, (40, 3))])
    plain = vb.solve("clique", src, dst, eps=0.2)
    assert plain["accepted"] and plain["dense_check"] is None
    kept = vb.solve("clique", src, dst, eps=0.2, source_cloud=cloud, target_cloud=cloud + shift)
    assert kept["accepted"] and kept["dense_check"]["overlap"] > 0.9
    # With clouds the dense check decides: the runner-up test is off unless asked.
    assert plain["runner_up"] is not None and kept["runner_up"] is None
    assert np.allclose(kept["dense_check"]["T_refined"][:3, 3], shift, atol=0.05)
    apart = vb.solve("clique", src, dst, eps=0.2, source_cloud=cloud,
                     target_cloud=cloud + [50.0, 0.0, 0.0])
    assert not apart["accepted"] and apart["status"] == "rejected"
    assert apart["dense_check"]["overlap"] < 0.1
    # Off: dense_overlap=0, or the count rule (the paper's).
    for keywords in ({"dense_overlap": 0.0}, {"accept": "count"}):
        r = vb.solve("clique", src, dst, eps=0.2, source_cloud=cloud,
                     target_cloud=cloud + [50.0, 0.0, 0.0], **keywords)
        assert r["accepted"] and r["dense_check"] is None, keywords
    with pytest.raises(ValueError, match="come together"):
        vb.solve("clique", src, dst, source_cloud=cloud)
    bad = cloud.copy()
    bad[5, 1] = np.nan
    with pytest.raises(ValueError, match=r"target_cloud\[5\] is not finite"):
        vb.solve("clique", src, dst, source_cloud=cloud, target_cloud=bad)


def test_generators_are_seeded():
    a = vb.synthetic(n=50, seed=3)
    b = vb.synthetic(n=50, seed=3)
    c = vb.synthetic(n=50, seed=4)
    assert np.array_equal(a["src"], b["src"]) and np.array_equal(a["dst"], b["dst"])
    assert not np.array_equal(a["src"], c["src"])
    assert set(vb.generators()) >= {"uniform", "repetitive"}
    assert "clique" in vb.solvers()


def test_bad_input_raises_value_error_naming_it(tmp_path):
    s = vb.synthetic(n=20, seed=1)
    with pytest.raises(ValueError, match="unknown solver 'nope'"):
        vb.solve("nope", s["src"], s["dst"])
    with pytest.raises(ValueError, match="must match"):
        vb.solve("clique", s["src"], s["dst"][:10])
    bad = s["dst"].copy()
    bad[4, 1] = np.nan
    with pytest.raises(ValueError, match=r"dst\[4, 1\]"):
        vb.solve("clique", s["src"], bad)
    with pytest.raises(ValueError, match="columns"):
        vb.solve("clique", np.zeros((5, 4)), np.zeros((5, 4)))
    with pytest.raises(ValueError, match="eps"):
        vb.solve("clique", s["src"], s["dst"], eps=-1.0)
    with pytest.raises(ValueError, match="accept"):
        vb.solve("clique", s["src"], s["dst"], accept="maybe")
    with pytest.raises(ValueError, match="max_null_draws"):
        vb.solve("clique", s["src"], s["dst"], accept="pvalue", max_null_draws=-1)
    (tmp_path / "corr.txt").write_text("0 0 0 1 1 1\n0 0 0 1 1 oops\n")
    with pytest.raises(vb.InputError, match="corr.txt:2"):
        vb.read_dump(str(tmp_path))


def test_dump_and_report_readers(tmp_path):
    cli = os.environ.get("VERIFYBENCH_CLI")
    if not cli:
        pytest.skip("VERIFYBENCH_CLI not set")
    s = vb.synthetic(n=60, outliers=0.5, dim=2, seed=9)
    (tmp_path / "d").mkdir()
    np.savetxt(tmp_path / "d" / "corr.txt", np.hstack([s["src"], s["dst"]]), fmt="%.17g")
    np.savetxt(tmp_path / "d" / "label.txt", s["labels"], fmt="%d")
    d = vb.read_dump(str(tmp_path / "d"))
    assert d["dim"] == 2 and np.array_equal(d["src"], s["src"]) and np.array_equal(d["labels"], s["labels"])
    report = tmp_path / "sweep.json"
    subprocess.run([cli, "sweep", "--solvers", "clique,ransac", "--n", "50", "--outliers", "0.5,0.9",
                    "--trials", "3", "--quiet", "--out", str(report)], check=True, capture_output=True)
    df = vb.load_report(str(report))
    assert len(df) == len(json.load(open(report))["results"]) == 2 * 2 * 3
    assert set(df["solver"]) == {"clique", "ransac"}
    assert df.attrs["context"]["seed"] == 1
    agg = vb.load_report(str(report), table="aggregates")
    assert len(agg) == 4 and (agg["trials"] == 3).all()
    (tmp_path / "x.json").write_text('{"hello": 1}')
    with pytest.raises(vb.InputError, match="schema_version"):
        vb.load_report(str(tmp_path / "x.json"))


def test_load_report_reads_a_loop_report(tmp_path):
    # A loop.json in the layout of reports/schema/loop.schema.json, written here: 3 closures of
    # 2 solvers, 2 summary rows, 4 maps.
    doc = {"schema_version": 1, "kind": "loop", "context": {"seed": 7}, "parameters": {"loop": {}},
           "maps": [{"frames": [0, 1]}, {"frames": [2]}, {"frames": [3]}, {"frames": [4]}],
           "true_closures": [[3, 0]], "candidates": [{"query": 3, "match": 0, "votes": 9}],
           "closures": [{"solver": "clique", "query": 3, "match": 0, "accepted": True, "correct": True},
                        {"solver": "ransac", "query": 3, "match": 0, "accepted": False, "correct": False},
                        {"solver": "ransac", "query": 3, "match": 1, "accepted": True, "correct": False}],
           "summary": [{"solver": "clique", "tp": 1, "fp": 0, "pose_graph": {"iterations": 4}},
                       {"solver": "ransac", "tp": 0, "fp": 1, "pose_graph": {"iterations": 5}}]}
    path = tmp_path / "loop.json"
    path.write_text(json.dumps(doc))
    closures = vb.load_report(str(path))
    assert len(closures) == 3 and list(closures["solver"]) == ["clique", "ransac", "ransac"]
    assert closures["accepted"].sum() == 2 and closures.attrs["kind"] == "loop"
    assert closures.attrs["context"]["seed"] == 7
    summary = vb.load_report(str(path), table="summary")
    assert list(summary["tp"]) == [1, 0] and list(summary["pose_graph.iterations"]) == [4, 5]
    assert len(vb.load_report(str(path), table="maps")) == 4
    with pytest.raises(ValueError, match="a loop has 'closures'"):
        vb.load_report(str(path), table="results")


def test_synthetic_takes_the_generators_shape_and_a_prior():
    # planar_motion: the true rotation's z axis is e_z; without it, tilted.
    flat = vb.synthetic(n=100, dim=3, seed=4, planar_motion=True)
    assert np.allclose(np.asarray(flat["T"])[:3, 2], [0, 0, 1], atol=1e-12)
    assert not np.allclose(np.asarray(vb.synthetic(n=100, dim=3, seed=4)["T"])[:3, 2], [0, 0, 1], atol=1e-3)
    # score_separation < 0: no scores; a separation of 5: inliers score higher on average by ~5.
    assert vb.synthetic(n=100, seed=4, score_separation=-1)["scores"] is None
    s = vb.synthetic(n=2000, outliers=0.5, seed=4, score_separation=5.0)
    labels, scores = np.asarray(s["labels"]).astype(bool), np.asarray(s["scores"])
    assert abs(scores[labels].mean() - scores[~labels].mean() - 5.0) < 0.2
    # A prior around the truth with the stated sigmas: present, near T, a 6 x 6 covariance with
    # (1 deg)^2 and (0.3 m)^2 on its diagonal.
    p = vb.synthetic(n=100, seed=4, prior_rot_deg=1.0, prior_trans=0.3)
    assert p["prior_T"] is not None and np.asarray(p["prior_cov"]).shape == (6, 6)
    diag = np.diag(np.asarray(p["prior_cov"]))
    assert np.allclose(sorted(diag), sorted([np.radians(1.0) ** 2] * 3 + [0.09] * 3))
    assert np.linalg.norm(np.asarray(p["prior_T"])[:3, 3] - np.asarray(p["T"])[:3, 3]) < 3.0
    assert vb.synthetic(n=100, seed=4)["prior_T"] is None
    with pytest.raises(ValueError, match="both > 0 or both 0"):
        vb.synthetic(prior_rot_deg=1.0)
    with pytest.raises(ValueError, match="group_ratio"):
        vb.synthetic(kind="rigid-group", group_ratio=-1.0)


def cli_defaults():
    """Each option's default as `verifybench sweep --help` and `run --help` (the dense check's
    options, in a build with the front end) print it: {"--eps": "0.1", ...}."""
    cli = os.environ.get("VERIFYBENCH_CLI")
    if not cli:
        pytest.skip("VERIFYBENCH_CLI is not set")
    text = "\n".join(subprocess.run([cli, command, "--help"], check=True, capture_output=True,
                                    text=True).stdout for command in ("sweep", "run"))
    out = {}
    for line in text.splitlines():
        words = line.split()
        if not words or not words[0].startswith("--"):
            continue
        out[words[0]] = line[line.rfind("(default ") + 9:-1] if line.endswith(")") and "(default " in line else ""
    return out


def test_every_setting_defaults_to_the_clis_and_reaches_solve():
    rows = vb.settings()
    defaults = cli_defaults()
    assert {r["keyword"] for r in rows} >= {"eps", "inlier_threshold", "accept", "alpha", "time_limit",
                                            "ransac_iterations", "mac_max_cliques", "jcbb_sigma",
                                            "gnc_max_iterations", "sc2_k1", "teaser_inlier_selection"}
    for r in rows:
        assert r["option"] in defaults, r["option"]
        shown = defaults[r["option"]]
        if r["kind"] == "flag":
            assert r["default"] is False and shown == "", r
        elif r["kind"] in ("text",) or isinstance(r["default"], str):
            assert shown == r["default"], r
        else:
            assert float(shown) == pytest.approx(float(r["default"]), rel=1e-5), r
    s = vb.synthetic(n=200, outliers=0.5, seed=3)
    # The CLI's default rule, and a family setting that used to raise a TypeError.
    r = vb.solve("ransac", s["src"], s["dst"], ransac_iterations=1000, seed=5)
    assert r["accept_rule"] == "pvalue"
    assert r["iterations"] == 1000
    c = vb.solve("clique", s["src"], s["dst"], accept="count", min_inliers=10**6)
    assert not c["accepted"] and c["accept_rule"] == "count"


def test_every_generator_setting_defaults_to_the_clis_and_is_in_the_stub():
    """synthetic()'s shape keywords are sweep's shape options (the same rows): same defaults as
    `sweep --help`, listed in the stub with those defaults, and each one reaches the generator (a
    changed value changes the drawn set of its kind)."""
    import ast
    rows = vb.generator_settings()
    defaults = cli_defaults()
    assert {r["keyword"] for r in rows} == {"planar_motion", "group_ratio", "grid_spacing", "overlap",
                                            "tail_dof", "anisotropy", "near_radius", "cell",
                                            "score_separation"}
    stub = ast.parse(open(os.path.join(os.path.dirname(vb.__file__), "_core.pyi")).read())
    synth = next(f for f in stub.body if isinstance(f, ast.FunctionDef) and f.name == "synthetic")
    stub_defaults = {a.arg: ast.literal_eval(d) for a, d in zip(synth.args.kwonlyargs, synth.args.kw_defaults)}
    for r in rows:
        shown = defaults[r["option"]]
        if r["kind"] == "flag":
            assert r["default"] is False and shown == "", r
        else:
            assert float(shown) == pytest.approx(r["default"]), r
        assert stub_defaults[r["keyword"]] == r["default"], r
    kinds = {"group_ratio": ("rigid-group", 0.8), "grid_spacing": ("repetitive", 1.0),
             "overlap": ("partial-overlap", 0.6), "tail_dof": ("heavy-tailed", 1.5),
             "anisotropy": ("anisotropic", 9.0), "near_radius": ("near-true", 3.0),
             "cell": ("bev-orb", 0.25), "score_separation": ("uniform", 3.0),
             "planar_motion": ("uniform", True)}
    for keyword, (kind, value) in kinds.items():
        dim = 2 if kind == "bev-orb" else 3
        a = vb.synthetic(n=200, outliers=0.6, kind=kind, dim=dim, seed=2)
        b = vb.synthetic(n=200, outliers=0.6, kind=kind, dim=dim, seed=2, **{keyword: value})
        changed = any(not np.array_equal(a[k], b[k]) for k in ("src", "dst", "T", "scores"))
        assert changed, keyword
    with pytest.raises(TypeError, match="did you mean 'group_ratio'"):
        vb.synthetic(group_ration=0.5)


def test_unknown_or_bad_settings_are_named_without_the_arrays():
    s = vb.synthetic(n=2000, outliers=0.5, seed=1)
    with pytest.raises(TypeError) as e:
        vb.solve("ransac", s["src"], s["dst"], ransac_iteration=10)
    assert "ransac_iteration" in str(e.value) and "ransac_iterations" in str(e.value)
    assert len(str(e.value)) < 300
    with pytest.raises(ValueError, match="ransac_iterations"):
        vb.solve("ransac", s["src"], s["dst"], ransac_iterations=0)
    with pytest.raises(TypeError, match="eps must be a number"):
        vb.solve("clique", s["src"], s["dst"], eps="big")
