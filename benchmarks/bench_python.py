#!/usr/bin/python3
"""The Python binding's cost per call: wall time of verifybench.solve() seen from Python against
the C++ solve it wraps (the module's own `time_ms`, measured around solver->solve in C++), per
solver and n. The difference is the binding: argument parsing, the (n, dim) -> column-major copy,
validation, the result dict. Medians over --repeats calls after one warm-up call.

usage: PYTHONPATH=build/python /usr/bin/python3 benchmarks/bench_python.py [--repeats 200]
"""
import argparse
import statistics
import time

import verifybench as vb


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=200)
    args = ap.parse_args()
    print("| solver | n | Python call median us | C++ solve median us | binding us | binding share |")
    print("|---|---|---|---|---|---|")
    for solver in ("clique", "ransac"):
        for n in (10, 100, 1000, 10000):
            s = vb.synthetic(n=n, outliers=0.9, dim=3, seed=1)
            src, dst = s["src"], s["dst"]
            vb.solve(solver, src, dst, eps=0.1)
            outer, inner = [], []
            repeats = max(5, args.repeats // (1 + n // 1000))
            for _ in range(repeats):
                t0 = time.perf_counter()
                r = vb.solve(solver, src, dst, eps=0.1)
                outer.append((time.perf_counter() - t0) * 1e6)
                inner.append(r["time_ms"] * 1e3)
            o, i = statistics.median(outer), statistics.median(inner)
            print(f"| {solver} | {n} | {o:.1f} | {i:.1f} | {o - i:.1f} | {100 * (o - i) / o:.1f}% |")


if __name__ == "__main__":
    main()
