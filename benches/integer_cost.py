#!/usr/bin/env python3
"""What reading a 16-bit counter costs a property, on the example programs with counters.

For each program below, writes properties of the same shapes twice, once over the
program's bits only and once reading its counter through a comparison atom:

  * implications `X => Y` between two bits, and `X => [C op k]`;
  * exclusions `X . Y = 0*`, and `X . [C op k] = 0*`;
  * invariants over the counter (`[C >= 0] = 1*`, `[C <= max] = 1*`, and the
    comparator's own `[C <= k] + [C > k] = 1*`), which have no counterpart without it.

checks them all with `ii-prove PROGRAM PROPS.ii --json --jobs 1` (best of `--runs`),
and prints, per program and per shape, the median and largest time per property as
ii-prove reports it, with and without the counter, and their ratio.

    benches/integer_cost.py [--runs N] [--timeout T]
"""

import argparse
import itertools
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BINARY = os.path.join(ROOT, "target", "release", "ii-prove")

# Each program: its file, its bits, its counter and the constants it compares it with.
PROGRAMS = [
    ("examples/parts.ld", ["Part", "Box_removed", "Conveyor", "Box_full"], "Cparts", [0, 9, 10]),
    ("examples/box.st", ["Part", "Empty", "Conveyor", "Full", "Lamp"], "Parts", [0, 9, 10]),
    ("tests/data/proves_programs/batch_counter.ld",
     ["Bottle", "Start", "Filler", "Batch_done"], "Cbottles", [0, 5, 6]),
    ("tests/data/proves_programs/bottle_counter_fbd.xml",
     ["Full", "Warn"], "Count", [0, 3, 6]),
]

OPS = ["<", "<=", ">=", "="]


def properties(bits, counter, constants):
    """`(shape, reads_counter, text)` for every property of the benchmark."""
    out = []
    atoms = [f"[{counter} {op} {k}]" for op in OPS for k in constants]
    for x, y in itertools.permutations(bits, 2):
        out.append(("implication", False, f"{x} => {y}"))
        out.append(("exclusion", False, f"{x} . {y} = 0*"))
    for x in bits:
        for a in atoms:
            out.append(("implication", True, f"{x} => {a}"))
            out.append(("exclusion", True, f"{x} . {a} = 0*"))
    out.append(("invariant", True, f"[{counter} >= 0] = 1*"))
    out.append(("invariant", True, f"[{counter} <= {max(constants)}] = 1*"))
    for k in constants:
        out.append(("invariant", True, f"[{counter} <= {k}] + [{counter} > {k}] = 1*"))
    return out


def run(program, props, timeout):
    with tempfile.NamedTemporaryFile("w", suffix=".ii", delete=False) as f:
        for i, (_, _, text) in enumerate(props):
            f.write(f"property p{i}: {text}\n")
        path = f.name
    try:
        out = subprocess.run([BINARY, program, path, "--json", "--jobs", "1",
                              "--timeout", str(timeout)], capture_output=True, text=True,
                             cwd=ROOT)
        if out.returncode not in (0, 1, 3):
            sys.exit(f"{program}: exit {out.returncode}\n{out.stderr}")
        report = json.loads(out.stdout)
    finally:
        os.unlink(path)
    return [(p["status"], p["time_ms"]) for p in report["properties"]]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--timeout", type=float, default=10)
    args = ap.parse_args()
    print("| program | shape | without the counter: n, median, max (ms) "
          "| reading the counter: n, median, max (ms) | ratio of medians | verdicts with it |")
    print("|---|---|---|---|---|---|")
    worst = 0.0
    for program, bits, counter, constants in PROGRAMS:
        props = properties(bits, counter, constants)
        best = None
        for _ in range(args.runs):
            got = run(program, props, args.timeout)
            best = got if best is None else [
                (s, min(t, b)) for (s, t), (_, b) in zip(got, best)]
        for shape in ["implication", "exclusion", "invariant"]:
            cells = []
            for reads in [False, True]:
                times = [t for (sh, r, _), (_, t) in zip(props, best) if sh == shape and r == reads]
                cells.append(times)
            verdicts = {}
            for (sh, r, _), (s, _) in zip(props, best):
                if sh == shape and r:
                    verdicts[s] = verdicts.get(s, 0) + 1
            fmt = lambda ts: (f"{len(ts)}, {statistics.median(ts):.1f}, {max(ts):.1f}"
                              if ts else "—")
            ratio = ""
            if cells[0] and cells[1]:
                r = statistics.median(cells[1]) / max(statistics.median(cells[0]), 0.01)
                worst = max(worst, r)
                ratio = f"{r:.1f}×"
            v = ", ".join(f"{n} {s}" for s, n in sorted(verdicts.items()))
            print(f"| `{os.path.basename(program)}` | {shape} | {fmt(cells[0])} "
                  f"| {fmt(cells[1])} | {ratio} | {v} |")
    print(f"\nlargest ratio of medians: {worst:.1f}×")


if __name__ == "__main__":
    sys.exit(main())
