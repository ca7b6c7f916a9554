#!/usr/bin/env python3
"""Times `ii-prove equiv` on the pairs of Sülflow & Drechsler's table: a combinational
pair of about 60 IL lines (8 outputs, sums of products against their De Morgan forms)
and a sequential pair of about 800 IL lines with 70 state variables (seal-in latches
against set/reset latches, each unit gated by the previous one).

    python3 benches/equiv.py [BINARY] [DIR]

writes the four programs to DIR (default: a temporary folder), runs each comparison
three times and prints the line counts, the verdicts and the best wall time."""

import os
import subprocess
import sys
import tempfile
import time

HEADER = "PROGRAM {name}\n  VAR_INPUT\n{inputs}  END_VAR\n  VAR_OUTPUT\n{outputs}  END_VAR\n"
FOOTER = """END_PROGRAM

CONFIGURATION Plant
  RESOURCE Controller ON PLC
    TASK Cyclic (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM Main WITH Cyclic : {name};
  END_RESOURCE
END_CONFIGURATION
"""


def declare(names):
    return "".join(f"    {n} : BOOL;\n" for n in names)


def combinational():
    n = 8
    ins = [f"I{k}" for k in range(n + 3)]
    outs = [f"Q{k}" for k in range(n)]
    a, b = [], []
    for k in range(n):
        x, y, z, w = ins[k], ins[k + 1], ins[k + 2], ins[k + 3 if k + 3 < len(ins) else 0]
        # Q := x·y + ¬z·w, and ¬(¬(x·y) · ¬(¬z·w)) by De Morgan.
        a += [f"  LD {x}", f"  AND {y}", f"  OR( {z}", "  NOT", f"  AND {w}", "  )", f"  ST {outs[k]}"]
        b += [f"  LDN {x}", f"  ORN {y}", f"  AND( {z}", f"  ORN {w}", "  )", "  NOT", f"  ST {outs[k]}"]
    return ins, outs, a, b


def sequential():
    n = 70
    starts = [f"Start{k}" for k in range(n)]
    stops = [f"Stop{k}" for k in range(n)]
    outs = [f"Out{k}" for k in range(n)]
    a, b = [], []
    for k in range(n):
        run, prev = f"Run{k}", f"Run{k - 1}" if k else "Enable"
        # Seal-in: Run := (Start + Run) · ¬Stop; Out := Run · previous unit's Run · ¬Stop.
        a += [f"  (* unit {k} *)", f"  LD {starts[k]}", f"  OR {run}", f"  ANDN {stops[k]}",
              f"  ST {run}", f"  LD {run}", f"  AND {prev}", f"  ANDN {stops[k]}",
              f"  ST {outs[k]}"]
        # Set, then reset (the stop wins, as in the seal-in).
        b += [f"  (* unit {k} *)", f"  LD {starts[k]}", f"  S {run}", f"  LD {stops[k]}",
              f"  R {run}", f"  LD {prev}", f"  AND {run}", f"  ANDN {stops[k]}",
              f"  ST {outs[k]}"]
    return starts + stops + ["Enable"], outs, a, b


def program(name, ins, outs, body, state):
    local = f"  VAR\n{declare(state)}  END_VAR\n" if state else ""
    head = HEADER.format(name=name, inputs=declare(ins), outputs=declare(outs)) + local
    return head + "\n".join(body) + "\n" + FOOTER.format(name=name)


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "target/release/ii-prove"
    folder = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp()
    cases = {
        "combinational": (combinational(), []),
        "sequential": (sequential(), [f"Run{k}" for k in range(70)]),
    }
    for label, ((ins, outs, a, b), state) in cases.items():
        paths = []
        for side, body in (("a", a), ("b", b)):
            path = os.path.join(folder, f"{label}_{side}.il")
            with open(path, "w") as f:
                f.write(program(f"{label.capitalize()}{side.upper()}", ins, outs, body, state))
            paths.append(path)
        lines = [sum(1 for _ in open(p)) for p in paths]
        best, out = None, None
        for _ in range(3):
            start = time.perf_counter()
            out = subprocess.run([binary, "equiv", *paths, "-q"], capture_output=True, text=True)
            took = time.perf_counter() - start
            best = took if best is None else min(best, took)
        summary = out.stdout.strip().splitlines()[-1] if out.stdout.strip() else out.stderr
        print(f"{label}: {lines[0]} and {lines[1]} lines, {len(state)} state variables "
              f"each: {summary}; best of 3: {best:.3f} s (exit {out.returncode})")


if __name__ == "__main__":
    main()
