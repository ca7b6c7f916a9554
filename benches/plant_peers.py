"""The tools `plants.py run` checks each plant with, and how their verdicts are read.

Each tool and mode runs as one process under a wall-clock limit (`--limit`); its wall
time, user CPU time and peak resident memory come from `wait4`. Verdicts are read per
property and compared with the generator's expected ones:

- ii-prove `--timers plc` and `--timers ideal`: its text report, a line per property
  (`NAME  proved|refuted|unknown`).
- NuSMV 2.5.4 `-df`, `-df -coi`, `-dynamic -df -coi`: `-- invariant … is true|false`
  per INVARSPEC, in the model's order (NuSMV prints the expression, not the name).
- ABC on `ii-prove export --aiger` (timed on its own, `--timers plc`): `pdr -a` checks
  every output (`print_status -s` lists each output's status: 1 proved, 0 disproved,
  -1 undecided); `int -k -d` runs interpolation on each output separately, dropping the
  disproved ones (`Output K proved SAT`; the others are proved unless the summary
  counts them unsolved, which it does not name); `bmc3 -a -F FRAMES` looks for
  counterexamples of every output up to FRAMES scans (it disproves, never proves).
  Output K is the property of the K-th `o` line of the AIGER symbol table.
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TOOLS = {
    "ii-plc": "ii-prove --timers plc",
    "ii-ideal": "ii-prove --timers ideal",
    "nusmv-df": "NuSMV -df",
    "nusmv-df-coi": "NuSMV -df -coi",
    "nusmv-dyn": "NuSMV -dynamic -df -coi",
    "abc-pdr": "ABC pdr -a",
    "abc-int": "ABC int -k -d",
    "abc-bmc": "ABC bmc3 -a",
}


def add_options(parser):
    parser.add_argument("--ii-prove", help="the ii-prove binary (default: $II_PROVE, else ROOT/target/release/ii-prove)")
    parser.add_argument("--nusmv", help="the NuSMV binary (default: built by benches/peers/build_nusmv.sh)")
    parser.add_argument("--abc", default="berkeley-abc", help="the ABC binary (Debian: berkeley-abc)")
    parser.add_argument("--no-nusmv", action="store_true", help="leave NuSMV out")
    parser.add_argument(
        "--tools", default=",".join(TOOLS), help=f"comma-separated, from: {', '.join(TOOLS)} (default: all)"
    )
    parser.add_argument("--timeout", type=float, default=10.0, help="ii-prove's --timeout per property")
    parser.add_argument("--limit", type=float, default=600.0, help="wall-clock limit per tool run, in seconds")
    parser.add_argument("--bmc-frames", type=int, default=20, help="bmc3's depth, in scans")


class Outcome:
    """One tool run: its resources and each property's verdict (True holds, False fails, None unknown)."""

    def __init__(self, wall, user, mib, killed, verdicts, note=""):
        self.wall, self.user, self.mib, self.killed = wall, user, mib, killed
        self.verdicts, self.note = verdicts, note

    def counts(self):
        values = list(self.verdicts.values())
        return values.count(True), values.count(False)


def timed(cmd, limit):
    """Wall time, user CPU, peak RSS (MiB), whether it was killed at `limit`, exit code, stdout."""
    start = time.perf_counter()
    with tempfile.TemporaryFile("w+") as out:
        p = subprocess.Popen(cmd, stdout=out, stderr=subprocess.DEVNULL, text=True)
        killed = False
        while True:
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() - start > limit:
                p.kill()
                _, status, usage = os.wait4(p.pid, 0)
                killed = True
                break
            time.sleep(0.005)
        wall = time.perf_counter() - start
        out.seek(0)
        code = None if killed else os.waitstatus_to_exitcode(status)
        return wall, usage.ru_utime, usage.ru_maxrss / 1024, killed, code, out.read()


def ii_prove(binary, paths, timers, args):
    wall, user, mib, killed, code, out = timed(
        [binary, paths["ld"], paths["ii"], "--timers", timers, "--timeout", str(args.timeout)], args.limit
    )
    verdicts = {}
    for name, status in re.findall(r"^([A-Za-z_]\S*)\s+(proved|refuted|unknown)\b", out, re.M):
        verdicts[name] = {"proved": True, "refuted": False, "unknown": None}[status]
    note = "" if killed or code in (0, 1) else f"exit {code}"
    return Outcome(wall, user, mib, killed, verdicts, note)


def spec_names(smv_path):
    with open(smv_path) as f:
        return re.findall(r"^INVARSPEC NAME (\S+) :=", f.read(), re.M)


def nusmv(binary, paths, flags, args):
    wall, user, mib, killed, code, out = timed([binary, *flags, paths["smv"]], args.limit)
    results = re.findall(r"^-- invariant .* is (true|false)\s*$", out, re.M)
    names = spec_names(paths["smv"])
    verdicts = {name: results[i] == "true" for i, name in enumerate(names) if i < len(results)}
    note = "" if killed or code == 0 else f"exit {code}"
    return Outcome(wall, user, mib, killed, verdicts, note)


def aiger_outputs(path):
    """The output names of a binary AIGER file's symbol table, in output order."""
    with open(path, "rb") as f:
        data = f.read()
    found = dict(re.findall(rb"\no(\d+) ([^\n]+)", data))
    return [found[str(i).encode()].decode() for i in range(len(found))]


def abc(binary, aig, mode, args):
    names = aiger_outputs(aig)
    limit = max(1, int(args.limit * 0.9))  # ABC reports what it has before it is killed
    script = {
        "abc-pdr": f"read {aig}; pdr -a -T {limit}; print_status -s",
        "abc-int": f"read {aig}; int -k -d",
        "abc-bmc": f"read {aig}; bmc3 -a -F {args.bmc_frames} -T {limit}",
    }[mode]
    wall, user, mib, killed, code, out = timed([binary, "-c", script], args.limit)
    verdicts, note = {}, "" if killed or code == 0 else f"exit {code}"
    if mode == "abc-pdr":
        status = re.search(r"^((?:\d+=-?\d+\s+)+)$", out, re.M)
        for index, value in re.findall(r"(\d+)=(-?\d+)", status.group(1) if status else ""):
            verdicts[names[int(index)]] = {"1": True, "0": False}.get(value)
    elif mode == "abc-int":
        failed = {int(k) for k in re.findall(r"Output\s+(\d+) proved SAT", out)}
        left = re.search(r"Interpolation left (\d+) \(out of (\d+)\) outputs unsolved", out)
        for i, name in enumerate(names):
            if i in failed:
                verdicts[name] = False
            elif left and left.group(1) == "0":
                verdicts[name] = True
        if left and left.group(1) != "0":
            note = f"{left.group(1)} unsolved"
    else:
        for k in re.findall(r"Output\s+(\d+) was asserted", out):
            verdicts[names[int(k)]] = False
        note = f"no failure of the others in {args.bmc_frames} scans" if not killed else ""
    return Outcome(wall, user, mib, killed, verdicts, note)


def cell(o, limit, expected_total):
    """`wall (user CPU, MiB) proved/disproved/unknown`."""
    held, failed = o.counts()
    total = len(o.verdicts)
    time_part = f"> {limit:.0f} s killed" if o.killed else f"{o.wall:.2f} s"
    text = f"{time_part} ({o.user:.2f} u, {o.mib:.0f} MiB) {held}/{failed}"
    if total - held - failed:
        text += f"/{total - held - failed}?"
    if o.killed:
        text += f" of {expected_total} before the kill"
    return text + (f", {o.note}" if o.note else "")


def compare(label, outcome, want, bounded=False):
    """Properties where `outcome` contradicts `want`; a missing or unknown verdict is no contradiction."""
    wrong = [n for n, v in outcome.verdicts.items() if v is not None and n in want and v != want[n]]
    unknown_names = [n for n, v in outcome.verdicts.items() if n not in want]
    missing = [] if bounded or outcome.killed else [n for n in want if n not in outcome.verdicts]
    problems = [f"{n}: {'holds' if want[n] else 'fails'} expected, {label} says the opposite" for n in wrong]
    problems += [f"{n}: not a property of the plant" for n in unknown_names]
    if missing and not outcome.note:
        problems.append(f"{len(missing)} properties without a verdict, e.g. {missing[0]}")
    return problems


def peers(args):
    binary = args.ii_prove or os.environ.get("II_PROVE") or os.path.join(ROOT, "target", "release", "ii-prove")
    if not os.path.exists(binary):
        sys.exit(f"no ii-prove binary at {binary}: build it or pass --ii-prove PATH")
    tools = [t.strip() for t in args.tools.split(",") if t.strip()]
    for t in tools:
        if t not in TOOLS:
            sys.exit(f"unknown tool {t!r}; known: {', '.join(TOOLS)}")
    if args.no_nusmv:
        tools = [t for t in tools if not t.startswith("nusmv")]
    smv_binary = None
    if any(t.startswith("nusmv") for t in tools):
        smv_binary = args.nusmv or subprocess.run(
            [os.path.join(ROOT, "benches", "peers", "build_nusmv.sh")], stdout=subprocess.PIPE, text=True, check=True
        ).stdout.strip()
    abc_binary = shutil.which(args.abc) if any(t.startswith("abc") for t in tools) else None
    if any(t.startswith("abc") for t in tools) and not abc_binary:
        print(f"no ABC binary {args.abc!r} (apt-get install berkeley-abc): ABC left out", file=sys.stderr)
        tools = [t for t in tools if not t.startswith("abc")]
    return binary, smv_binary, abc_binary, tools


def run(args, plants):
    binary, smv_binary, abc_binary, tools = peers(args)
    shapes = args.shape or ["chain"]
    head = ["shape", "N units (rungs, properties)", "expected holds/fails"]
    head += [TOOLS[t] for t in tools if t.startswith("ii")]
    if any(t.startswith("abc") for t in tools):
        head.append("AIGER export")
    head += [TOOLS[t] for t in tools if not t.startswith("ii")]
    print("Cells: wall time (user CPU time, peak memory) proved/disproved[/unknown?]; ‼ marks a disagreement.")
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head), flush=True)
    disagreements = 0
    for shape_name in shapes:
        for n in args.n:
            shape = plants.Shape(shape_name, n)
            with tempfile.TemporaryDirectory() as d:
                paths = plants.generate(shape, d, args.faulty)
                row = [shape_name, f"{n} ({shape.rungs_per_unit() * n}, {shape.properties_per_unit() * n})"]
                plc = plants.expected(shape, args.faulty, "plc")
                row.append(f"{sum(plc.values())}/{len(plc) - sum(plc.values())}")
                cells, export = {}, None
                for t in tools:
                    want = plc
                    if t.startswith("ii"):
                        timers = t.split("-")[1]
                        want = plants.expected(shape, args.faulty, timers)
                        o = ii_prove(binary, paths, timers, args)
                    elif t.startswith("nusmv"):
                        flags = {"nusmv-df": ["-df"], "nusmv-df-coi": ["-df", "-coi"]}.get(t, ["-dynamic", "-df", "-coi"])
                        o = nusmv(smv_binary, paths, flags, args)
                    else:
                        if export is None:
                            aig = os.path.join(d, "plant.aig")
                            cmd = [binary, "export", "--aiger", aig, paths["ld"], paths["ii"]]
                            export = Outcome(*timed(cmd, args.limit)[:4], {})
                        o = abc(abc_binary, os.path.join(d, "plant.aig"), t, args)
                    problems = compare(TOOLS[t], o, want, bounded=(t == "abc-bmc"))
                    for p in problems:
                        print(f"DISAGREEMENT ({shape_name}, N = {n}, {TOOLS[t]}): {p}", file=sys.stderr, flush=True)
                    disagreements += len(problems)
                    cells[t] = cell(o, args.limit, len(want)) + (" ‼" if problems else "")
                row += [cells[t] for t in tools if t.startswith("ii")]
                if export is not None:
                    row.append(f"{export.wall:.2f} s ({export.user:.2f} u, {export.mib:.0f} MiB)")
                row += [cells[t] for t in tools if not t.startswith("ii")]
                print("| " + " | ".join(row) + " |", flush=True)
    if disagreements:
        print(f"{disagreements} DISAGREEMENTS with the expected verdicts (above, on standard error)", file=sys.stderr)
        return 1
    return 0
