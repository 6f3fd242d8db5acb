#!/usr/bin/python3
"""The peers table (issue #32): from the TSV of scripts/peers (graph n m peer omega solve_s wall_s
status [set known note]), one markdown row per graph: each solver's solve time in ms (the time after
reading the graph; ">L s" when it did not prove the maximum within the limit), the clique number,
the fastest peer that proved it, the ratio of `clique`'s time to that peer's, and whether `clique`
meets the done-when of issue #32 there: ratio <= 1.0, or, where the best peer needs < 10 ms, within
2 ms of it. Solvers named `clique` or `clique-*` are ours; every other name is a peer.

The omegas of every solver that proved its result (and the known omega of a DIMACS graph) must
agree: a disagreement is flagged in the row ("DISAGREE") and listed in a warning after the table
(and on stderr); such a graph never counts as met. A closing line counts the graphs, among those
some peer proved, on which `clique` meets the done-when.

usage: peers_table.py [--limit S] [--ours NAME] PEERS.tsv
"""
import argparse
import csv
import statistics
import sys

REQUIRED = ["graph", "n", "m", "peer", "omega", "solve_s", "wall_s", "status"]
FAST_S = 0.010    # below this best-peer time, the 2 ms rule applies
SLACK_S = 0.002


def fail(msg):
    print(f"peers_table: error: {msg}", file=sys.stderr)
    sys.exit(2)


def is_ours(name):
    return name == "clique" or name.startswith("clique-")


def ms(seconds):
    v = seconds * 1000.0
    if v < 10:
        return f"{v:.2f}"
    if v < 100:
        return f"{v:.1f}"
    return f"{v:.0f}"


def read(path):
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f, delimiter="\t")
            missing = [c for c in REQUIRED if c not in (reader.fieldnames or [])]
            if missing:
                fail(f"{path}: missing column(s) {', '.join(missing)}")
            rows = list(reader)
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    for i, r in enumerate(rows, start=2):
        if not (r["n"] or "").isdigit() or not (r["m"] or "").isdigit():
            fail(f"{path}:{i}: n and m must be integers (n {r['n']!r}, m {r['m']!r}: "
                 "columns out of order?)")
        try:
            r["solve"] = float(r["solve_s"]) if r["solve_s"] else None
            r["omega_v"] = int(r["omega"]) if r["omega"] else None
        except ValueError:
            fail(f"{path}:{i}: bad omega or solve_s ({r['omega']!r}, {r['solve_s']!r})")
        if r["status"] == "ok" and (r["solve"] is None or r["omega_v"] is None):
            fail(f"{path}:{i}: status ok without omega and solve_s")
    return rows


def merge(rows):
    """One result per (graph, solver): the median time when every repeat proved, else the first
    repeat that did not."""
    bad = [r for r in rows if r["status"] != "ok"]
    if bad:
        return bad[0]
    r = dict(rows[0])
    r["solve"] = statistics.median(x["solve"] for x in rows)
    return r


def main(argv):
    ap = argparse.ArgumentParser(prog="peers_table.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("tsv", metavar="PEERS.tsv")
    ap.add_argument("--limit", type=float, default=None, help="the time limit of the run [s]")
    ap.add_argument("--ours", default="clique", help="the solver compared with the peers")
    args = ap.parse_args(argv)
    rows = read(args.tsv)
    if not rows:
        fail(f"{args.tsv}: no rows")

    graphs, solvers, by = [], [], {}
    for r in rows:
        if r["graph"] not in by:
            graphs.append(r["graph"])
            by[r["graph"]] = {}
        if r["peer"] not in solvers:
            solvers.append(r["peer"])
        by[r["graph"]].setdefault(r["peer"], []).append(r)
    peers = [s for s in solvers if not is_ours(s)]
    ours = [s for s in solvers if is_ours(s)]
    ours.sort(key=lambda s: (s != args.ours, solvers.index(s)))
    columns = peers + ours
    limit = f">{args.limit:g} s" if args.limit else "not proved"

    head = ["graph", "set", "n", "m", "omega"] + columns + [
        "best peer", f"{args.ours} / best peer", "done-when"]
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    disagreements, counted, met, not_met, no_peer, no_peer_ours = [], 0, 0, [], 0, 0
    per_set = {}
    for g in graphs:
        res = {s: merge(v) for s, v in by[g].items()}
        first = next(iter(by[g].values()))[0]
        known = first.get("known") or ""
        proved = {s: r for s, r in res.items() if r["status"] == "ok"}
        omegas = {r["omega_v"] for r in proved.values()}
        if known:
            omegas.add(int(known))
        agree = len(omegas) <= 1
        consensus = next(iter(omegas)) if len(omegas) == 1 else None
        if not agree:
            detail = ", ".join(f"{s} {r['omega_v']}" for s, r in proved.items())
            disagreements.append(f"{g}: {detail}" + (f", known {known}" if known else ""))
        peer_ok = [(r["solve"], s) for s, r in proved.items() if not is_ours(s)]
        best = min(peer_ok) if peer_ok else None
        fastest = min((r["solve"] for r in proved.values()), default=None)
        cells = []
        for s in columns:
            r = res.get(s)
            if r is None:
                cells.append("")
            elif r["status"] == "ok":
                c = ms(r["solve"])
                if r["solve"] == fastest:
                    c = f"**{c}**"
                if not agree:
                    c += f" (omega {r['omega_v']})"
                cells.append(c)
            elif r["status"] == "timeout":
                cells.append(limit)
            else:
                cells.append(r["status"])
        mine = res.get(args.ours)
        mine_ok = mine is not None and mine["status"] == "ok"
        if best is None:
            ratio, verdict = "", "no peer proved" + (f" ({args.ours} did)" if mine_ok else "")
            no_peer += 1
            no_peer_ours += mine_ok
            best_cell = "none"
        else:
            best_s, best_name = best
            best_cell = f"{best_name} {ms(best_s)}"
            counted += 1
            st = per_set.setdefault(first.get("set") or "-", [0, 0])
            st[1] += 1
            if mine_ok:
                ratio = (f"{mine['solve'] / best_s:.2f}" if best_s > 0
                         else ("1.00" if mine["solve"] == 0 else "inf"))
                ok = mine["solve"] <= best_s
                slack = (not ok and best_s < FAST_S and mine["solve"] <= best_s + SLACK_S + 1e-12)
                if not agree:
                    verdict = "**no: omegas disagree**"
                elif ok:
                    verdict = "yes"
                elif slack:
                    verdict = "yes (within 2 ms)"
                else:
                    verdict = "no"
            else:
                ratio = (f">{args.limit / best_s:.2f}" if args.limit and best_s > 0 else "")
                verdict = "no" if mine is not None else f"no ({args.ours} not run)"
            if verdict.startswith("yes"):
                met += 1
                st[0] += 1
            else:
                not_met.append(g)
        omega_cell = (str(consensus) if consensus is not None
                      else ("?" if agree else "**DISAGREE " + "/".join(map(str, sorted(omegas))) + "**"))
        out.append("| " + " | ".join([g, first.get("set", "") or "", first["n"], first["m"], omega_cell]
                                     + cells + [best_cell, ratio, verdict]) + " |")

    print("\n".join(out))
    print()
    print(f"Times in ms: each solver's own time after reading the graph (peaty: its whole process on "
          f"the complement); {limit if args.limit else 'timeout'} = no proof within the limit; bold = "
          f"fastest proof of the row. done-when: {args.ours} no slower than the fastest peer (ratio "
          f"<= 1.0), or within 2 ms of it where that peer needs < 10 ms.")
    print()
    within = f" within {args.limit:g} s" if args.limit else ""
    line = (f"**{args.ours} meets the done-when on {met} of {counted} graphs that some peer proved"
            f"{within}**")
    if per_set:
        line += " (" + ", ".join(f"{k} {v[0]}/{v[1]}" for k, v in per_set.items()) + ")"
    line += f"; no peer proved {no_peer} graph(s)"
    if no_peer:
        line += f", {args.ours} proved {no_peer_ours} of them"
    print(line + ".")
    if not_met:
        print(f"Not met: {', '.join(not_met)}.")
    if disagreements:
        print()
        print(f"**WARNING: OMEGAS DISAGREE on {len(disagreements)} graph(s):**")
        for d in disagreements:
            print(f"- **{d}**")
            print(f"peers_table: WARNING: omegas disagree on {d}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
