#!/usr/bin/python3
"""The instruction-count gate (issue #16): runs the fixed workloads of perf_workloads under
valgrind's callgrind, counting only each workload's measured call, and compares the counts with a
committed baseline. Counts, not times: they are the same on every run of the same binary (wall
time on a shared 2-core VM drifts by 30% within minutes).

  perf_gate.py --binary build/benchmarks/perf_workloads [--baseline benchmarks/perf_baseline.json]
               [--threshold 2] [--warn 0.5] [--workloads a,b] [--jobs J] [--out out/perf]
               [--trend FILE] [--update]

Exit status: 0 when no workload grew past --threshold percent; 1 when one did; 2 on an error (no
valgrind, a workload that failed, a workload missing from the baseline: each named).
Writes into --out: counts.json (this run), github-action-benchmark.json (the counts in
github-action-benchmark's customSmallerIsBetter format), callgrind.<workload>.out (for
callgrind_annotate), trend.png (the trend file drawn). Appends one row per workload to the trend
file (date, commit, kind, workload, instructions). --update rewrites the baseline with this run's
counts (workloads that could not run here keep their entry) and appends to the committed history
benchmarks/perf_trend.tsv.
"""
import argparse
import concurrent.futures
import datetime
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
HISTORY = os.path.join(HERE, "perf_trend.tsv")
TREND_HEADER = "date\tcommit\tkind\tworkload\tinstructions\n"


def fail(message, code=2):
    print(f"perf-gate: {message}", file=sys.stderr)
    sys.exit(code)


def write_atomic(path, text):
    """A temporary file beside the target, then a rename: never a half-written file."""
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    if os.path.islink(path) or (os.path.exists(path) and not os.path.isfile(path)):
        fail(f"{path}: not a regular file; refusing to replace it")
    fd, tmp = tempfile.mkstemp(prefix=".perf-gate.", dir=folder)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def git_commit():
    """The commit measured; "-dirty" when tracked files other than the gate's own records differ."""
    try:
        head = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short=12", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
        changed = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no", "--",
                                  ".", ":!benchmarks/perf_baseline.json", ":!benchmarks/perf_trend.tsv"],
                                 capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("-dirty" if changed else "")


def valgrind_version():
    try:
        out = subprocess.run(["valgrind", "--version"], capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        fail("valgrind not found (Debian package valgrind; scripts/install-deps installs it)")
    return out.stdout.strip()


def list_workloads(binary):
    try:
        out = subprocess.run([binary, "--list"], capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError) as e:
        fail(f"{binary} --list failed: {e}")
    rows = {}
    for line in out.stdout.splitlines():
        name, available, description = line.split("\t", 2)
        rows[name] = {"available": available, "description": description}
    return rows


def load_baseline(path):
    try:
        with open(path) as f:
            baseline = json.load(f)
    except FileNotFoundError:
        return None
    except (OSError, ValueError) as e:
        fail(f"{path}: cannot read the baseline: {e}")
    if not isinstance(baseline, dict) or not isinstance(baseline.get("workloads"), dict):
        fail(f"{path}: field 'workloads': expected an object of workload -> {{instructions: N}}")
    for name, entry in baseline["workloads"].items():
        n = entry.get("instructions") if isinstance(entry, dict) else None
        if not isinstance(n, int) or n <= 0:
            fail(f"{path}: workload '{name}', field 'instructions': expected a positive integer, "
                 f"got {n!r}")
    return baseline


def measure(binary, name, out_dir):
    """Instructions of the measured call of one workload, and its check string."""
    cg_out = os.path.join(out_dir, f"callgrind.{name}.out")
    cmd = ["valgrind", "--tool=callgrind", "--instr-atstart=no", "--collect-atstart=no",
           f"--callgrind-out-file={cg_out}", binary, name]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        tail = "\n".join(run.stderr.strip().splitlines()[-5:])
        return {"error": f"exit {run.returncode}: {tail}"}
    check = ""
    for line in run.stdout.splitlines():
        if line.startswith(name + " "):
            check = line.split("check=", 1)[1].split(" native_ms=")[0] if "check=" in line else ""
    totals = None
    with open(cg_out) as f:
        for line in f:
            if line.startswith("totals:"):
                totals = int(line.split()[1])
    if not totals:
        return {"error": f"{cg_out}: no 'totals:' line (did the measured region run?)"}
    return {"instructions": totals, "check": check}


def classify(now, base, threshold, warn):
    change = 100.0 * (now - base) / base
    if change > threshold:
        return change, "FAIL"
    if change > warn:
        return change, "warn"
    if change < -warn:
        return change, "better"
    return change, "ok"


def append_trend(path, date, commit, kind, counts):
    new = not os.path.exists(path)
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "a") as f:
        if new:
            f.write(TREND_HEADER)
        for name in sorted(counts):
            f.write(f"{date}\t{commit}\t{kind}\t{name}\t{counts[name]}\n")


def read_trend(path):
    rows = []
    if not os.path.exists(path):
        return rows
    with open(path) as f:
        for number, line in enumerate(f, 1):
            if number == 1 or not line.strip():
                continue
            fields = line.rstrip("\n").split("\t")
            if len(fields) != 5:
                fail(f"{path}:{number}: expected 5 tab-separated fields, got {len(fields)}")
            try:
                fields[4] = int(fields[4])
            except ValueError:
                fail(f"{path}:{number}: field 'instructions': not an integer: {fields[4]!r}")
            rows.append(fields)
    return rows


def draw_trend(rows, png):
    """One panel per workload: its count over the runs, relative to its first count."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("perf-gate: matplotlib absent, no trend plot", file=sys.stderr)
        return
    series = {}
    for date, commit, kind, name, count in rows:
        series.setdefault(name, []).append((date, commit, kind, count))
    if not series:
        return
    fig, ax = plt.subplots(figsize=(9, 5))
    for name, points in sorted(series.items()):
        first = points[0][3]
        ax.plot(range(len(points)), [100.0 * (p[3] - first) / first for p in points],
                marker="o", label=name)
    ax.axhline(0, color="grey", lw=0.8)
    ax.set_xlabel("run (oldest first; baseline updates and gate runs)")
    ax.set_ylabel("instructions vs first run [%]")
    ax.set_title("verifybench instruction counts (callgrind, measured region only)")
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", required=True, help="the perf_workloads executable")
    ap.add_argument("--baseline", default=os.path.join(HERE, "perf_baseline.json"))
    ap.add_argument("--threshold", type=float, default=2.0, help="fail past this growth [%%]")
    ap.add_argument("--warn", type=float, default=0.5, help="warn past this growth [%%]")
    ap.add_argument("--workloads", default="", help="comma-separated subset (default: all)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                    help="workloads measured at once (each at one thread; counts do not depend on it)")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "perf"))
    ap.add_argument("--trend", default=None, help="trend file to append to (default OUT/trend.tsv)")
    ap.add_argument("--update", action="store_true", help="rewrite the baseline with this run")
    args = ap.parse_args()
    if not (args.threshold > 0 and args.warn >= 0 and args.warn <= args.threshold):
        fail(f"--threshold {args.threshold} / --warn {args.warn}: need 0 <= warn <= threshold, threshold > 0")
    if args.jobs < 1:
        fail(f"--jobs {args.jobs}: expected an integer >= 1")
    if not os.access(args.binary, os.X_OK):
        fail(f"--binary {args.binary}: not an executable (build first: scripts/build)")
    version = valgrind_version()
    known = list_workloads(args.binary)
    wanted = [w for w in args.workloads.split(",") if w] or list(known)
    for name in wanted:
        if name not in known:
            fail(f"--workloads: unknown workload '{name}' (known: {', '.join(known)})")
    baseline = load_baseline(args.baseline)
    if baseline is None and not args.update:
        fail(f"{args.baseline}: no baseline (make one with --update)")
    base = baseline["workloads"] if baseline else {}
    if not args.update:
        missing = [n for n in wanted if known[n]["available"] == "yes" and n not in base]
        if missing:
            fail(f"{args.baseline}: no entry for workload(s) {', '.join(missing)} "
                 "(a new workload: record it with --update, in the commit that adds it)")
    runnable = [n for n in wanted if known[n]["available"] == "yes"]
    skipped = {n: known[n]["available"][4:] for n in wanted if n not in runnable}
    os.makedirs(args.out, exist_ok=True)
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(measure, args.binary, n, args.out): n for n in runnable}
        for future in concurrent.futures.as_completed(futures):
            results[futures[future]] = future.result()
    errors = {n: r["error"] for n, r in results.items() if "error" in r}
    for name, message in sorted(errors.items()):
        print(f"perf-gate: workload {name} failed: {message}", file=sys.stderr)

    worst = "ok"
    print(f"{'workload':32} {'baseline':>15} {'now':>15} {'change':>9}  status")
    for name in wanted:
        r = results.get(name, {})
        entry = base.get(name)
        if name in skipped:
            line = (f"{name:32} {entry['instructions'] if entry else '-':>15} {'-':>15} {'-':>9}  "
                    f"skipped ({skipped[name]})")
        elif "instructions" not in r:
            line = f"{name:32} {'-':>15} {'-':>15} {'-':>9}  ERROR"
        elif entry is None:
            line = f"{name:32} {'-':>15} {r['instructions']:>15} {'-':>9}  new"
        else:
            change, status = classify(r["instructions"], entry["instructions"], args.threshold, args.warn)
            if status == "FAIL":
                worst = "FAIL"
            elif status == "warn" and worst == "ok":
                worst = "warn"
            note = ""
            if entry.get("check") and r["check"] != entry["check"]:
                note = f"; result changed: {entry['check']} -> {r['check']}"
            line = (f"{name:32} {entry['instructions']:>15} {r['instructions']:>15} "
                    f"{change:>+8.2f}%  {status}{note}")
        print(line)
    for name in sorted(set(base) - set(known)):
        print(f"perf-gate: warning: baseline workload '{name}' is not in {args.binary} (removed?)",
              file=sys.stderr)

    counts = {n: r["instructions"] for n, r in results.items() if "instructions" in r}
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    commit = git_commit()
    run_json = {"schema_version": 1, "tool": "callgrind", "valgrind": version, "commit": commit,
                "date": date, "threshold_percent": args.threshold,
                "workloads": {n: {"instructions": counts[n], "check": results[n]["check"],
                                  "description": known[n]["description"]} for n in sorted(counts)}}
    write_atomic(os.path.join(args.out, "counts.json"), json.dumps(run_json, indent=2) + "\n")
    gab = [{"name": n, "unit": "instructions", "value": counts[n],
            "extra": f"callgrind, measured region only; check {results[n]['check']}"}
           for n in sorted(counts)]
    write_atomic(os.path.join(args.out, "github-action-benchmark.json"), json.dumps(gab, indent=2) + "\n")
    trend = args.trend or os.path.join(args.out, "trend.tsv")
    append_trend(trend, date, commit, "update" if args.update else "gate", counts)
    draw_trend(read_trend(trend), os.path.join(args.out, "trend.png"))

    if errors:
        sys.exit(2)
    if args.update:
        merged = dict(base)
        merged.update(run_json["workloads"])
        new_baseline = dict(run_json)
        new_baseline["workloads"] = dict(sorted(merged.items()))
        write_atomic(args.baseline, json.dumps(new_baseline, indent=2) + "\n")
        if os.path.abspath(trend) != os.path.abspath(HISTORY) and \
                os.path.abspath(args.baseline) == os.path.abspath(os.path.join(HERE, "perf_baseline.json")):
            append_trend(HISTORY, date, commit, "update", counts)
        print(f"perf-gate: baseline {args.baseline} updated ({len(counts)} workloads)")
        return
    if worst == "FAIL":
        print(f"perf-gate: FAIL: a workload grew by more than {args.threshold}% "
              "(if intended, run scripts/perf-gate --update and give the reason in the commit message)")
        sys.exit(1)
    print(f"perf-gate: pass ({len(counts)} workloads measured, {len(skipped)} skipped"
          f"{', warnings above' if worst == 'warn' else ''})")


if __name__ == "__main__":
    main()
