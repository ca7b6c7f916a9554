#!/usr/bin/env python3
"""How long each kind of verdict takes on random properties of a program.

Writes random safety properties over a program's signals (the names `ii-prove show`
declares), checks them all with `ii-prove PROGRAM PROPS.ii --json`, and prints, per
verdict (proved, refuted, unknown), how many there were and the median, 90th
percentile and largest time per property as ii-prove reports it. The properties are
implications and exclusions between literals, with on-delays, off-delays and
previous-scan reads of the program's own delays, so some need induction over scans
and some need timer reasoning the prover may not have.

    benches/verdict_times.py PROGRAM [--count N] [--seed S] [--timeout T] [--jobs J]
                             [--keep FILE]

`--keep FILE` writes the generated properties there (to rerun one by hand).
"""

import argparse
import json
import os
import random
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BINARY = os.path.join(ROOT, "target", "release", "ii-prove")


def signals_and_delays(program):
    """The signals `show` declares, and the delays its timers use."""
    out = subprocess.run([BINARY, "show", "--ascii", program], capture_output=True,
                         text=True, check=True).stdout
    names = []
    for line in out.splitlines():
        if line.startswith("input "):
            names += [n.strip() for n in line[len("input "):].split(",")]
    delays = sorted(set(re.findall(r"effective delay ([0-9.]+(?:ms|s|us))", out))) or ["1s"]
    return names, delays


def literal(rng, names):
    name = rng.choice(names)
    return f"!{name}" if rng.random() < 0.3 else name


def operand(rng, names, delays):
    """A literal, a conjunction of two, or a delayed or previous-scan one."""
    r = rng.random()
    if r < 0.45:
        return literal(rng, names)
    if r < 0.65:
        return f"{literal(rng, names)} . {literal(rng, names)}"
    if r < 0.8:
        return f"{rng.choice(delays)}/({literal(rng, names)})"
    if r < 0.9:
        return f"({literal(rng, names)})/{rng.choice(delays)}"
    return f"pre {literal(rng, names)}"


def properties(rng, names, delays, count):
    """Exclusions `a . b = 0*` and implications from a conjunction of one to three
    operands to a disjunction of one to three: strong premises and weak conclusions,
    so that a fair share holds."""
    lines = []
    for i in range(count):
        if rng.random() < 0.25:
            a, b = operand(rng, names, delays), operand(rng, names, delays)
            lines.append(f"property R{i}: ({a}) . ({b}) = 0*")
        else:
            lhs = " . ".join(f"({operand(rng, names, delays)})"
                             for _ in range(rng.randint(1, 3)))
            rhs = " + ".join(f"({operand(rng, names, delays)})"
                             for _ in range(rng.randint(1, 3)))
            lines.append(f"property R{i}: {lhs} => {rhs}")
    return "\n".join(lines) + "\n"


def summary(times):
    if not times:
        return "      -"
    times = sorted(times)
    p90 = times[min(len(times) - 1, int(0.9 * len(times)))]
    return (f"median {statistics.median(times) / 1e3:7.3f} s   p90 {p90 / 1e3:7.3f} s   "
            f"max {times[-1] / 1e3:7.3f} s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("program")
    ap.add_argument("--count", type=int, default=100)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", default="10s")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--keep")
    args = ap.parse_args()
    if not os.path.exists(BINARY):
        sys.exit("build first: cargo build --release")
    names, delays = signals_and_delays(args.program)
    text = properties(random.Random(args.seed), names, delays, args.count)
    with tempfile.TemporaryDirectory() as tmp:
        props = args.keep or os.path.join(tmp, "props.ii")
        with open(props, "w") as f:
            f.write(text)
        run = subprocess.run([BINARY, args.program, props, "--json", "--quiet", "--jobs",
                              str(args.jobs), "--timeout", args.timeout],
                             capture_output=True, text=True)
        if run.returncode not in (0, 1):
            sys.exit(run.stderr)
        report = json.loads(run.stdout)
    by_status = {}
    for p in report["properties"]:
        by_status.setdefault(p["status"], []).append(p["time_ms"])
    print(f"{args.program}: {args.count} random properties (seed {args.seed}, "
          f"--timeout {args.timeout}, --jobs {args.jobs})")
    for status in ("proved", "refuted", "unknown"):
        times = by_status.get(status, [])
        print(f"  {status:8} {len(times):4}   {summary(times)}")


if __name__ == "__main__":
    main()
