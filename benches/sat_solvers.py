#!/usr/bin/env python3
"""Times other SAT solvers on exactly the queries an ii-prove run made, beside varisat.

ii-prove records every SAT query of a run when `II_PROVE_SAT_TRACE` names a directory
(src/sat_trace.rs: clauses, solves under assumptions, varisat's answer and time). This
script replays each recorded solver instance, incrementally and in the same order, in
the solvers of PySAT (`pip install python-sat`: CaDiCaL 1.5.3, Glucose 4, MiniSat 2.2,
...), checks that every answer agrees with varisat's, and prints the solve time per
kind of query (bmc: bounded model checking of a refutation; bounded: vacuity and the
bounded search of an unknown; split: the prover's case splits; refute: propositional
refutations with a DRAT proof), summed over the run.

Only the solve calls are timed, for every solver alike (loading clauses through Python
is not comparable with varisat's in-process loading, so it is left out for all).

    II_PROVE_SAT_TRACE=DIR ii-prove PROGRAM PROPERTIES
    benches/sat_solvers.py DIR [--solver cd15 --solver g4 ...]
"""
import argparse
import collections
import os
import sys
import time

try:
    from pysat.solvers import Solver
except ImportError:
    sys.exit("needs PySAT: pip install python-sat")

DEFAULT = ["cadical195", "cadical153", "glucose4", "minisat22"]


def parse(path):
    """The kind and the events of one trace: ('c', clause) or ('s', assumptions, answer, secs)."""
    kind, events, pending = "?", [], None
    with open(path) as f:
        for line in f:
            if line.startswith("c kind "):
                kind = line.split()[2]
            elif line.startswith("a "):
                pending = [int(x) for x in line.split()[1:-1]]
            elif line.startswith("r "):
                _, answer, secs = line.split()
                events.append(("s", pending or [], answer, float(secs)))
                pending = None
            elif line.strip():
                events.append(("c", [int(x) for x in line.split()[:-1]]))
    return kind, events


def replay(name, events):
    """Solve time (s) of solver `name` over the events, and the answers that disagree."""
    total, wrong = 0.0, 0
    with Solver(name=name) as s:
        for e in events:
            if e[0] == "c":
                s.add_clause(e[1])
            else:
                start = time.perf_counter()
                sat = s.solve(assumptions=e[1])
                total += time.perf_counter() - start
                if e[2] in ("sat", "unsat") and sat != (e[2] == "sat"):
                    wrong += 1
    return total, wrong


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--solver", action="append", help=f"PySAT solver names (default: {' '.join(DEFAULT)})")
    args = ap.parse_args()
    solvers = args.solver or DEFAULT
    files = sorted(os.path.join(args.dir, f) for f in os.listdir(args.dir) if f.endswith(".trace"))
    if not files:
        sys.exit(f"no .trace file in {args.dir}")
    times = collections.defaultdict(float)  # (kind, solver) -> seconds
    counts = collections.Counter()  # kind -> solves
    clauses = collections.Counter()  # kind -> clauses
    wrong = 0
    for path in files:
        kind, events = parse(path)
        solves = [e for e in events if e[0] == "s"]
        counts[kind] += len(solves)
        clauses[kind] += len(events) - len(solves)
        times[(kind, "varisat")] += sum(e[3] for e in solves)
        for name in solvers:
            t, w = replay(name, events)
            times[(kind, name)] += t
            wrong += w
    names = ["varisat"] + solvers
    print(f"{len(files)} solver instances from {args.dir}")
    print(f"{'kind':8} {'solves':>7} {'clauses':>9} " + " ".join(f"{n:>10}" for n in names))
    for kind in sorted(counts):
        row = " ".join(f"{times[(kind, n)]:10.4f}" for n in names)
        print(f"{kind:8} {counts[kind]:7d} {clauses[kind]:9d} {row}")
    row = " ".join(f"{sum(times[(k, n)] for k in counts):10.4f}" for n in names)
    print(f"{'total':8} {sum(counts.values()):7d} {sum(clauses.values()):9d} {row}")
    print("(seconds spent in solve calls, summed)")
    if wrong:
        print(f"DISAGREEMENT: {wrong} answers differ from varisat's", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
