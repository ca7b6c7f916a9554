#!/usr/bin/env python3
"""Chained water plants of N units, checked by ii-prove and by NuSMV side by side.

Each unit is the 10 rungs of examples/water.ld with its signals suffixed `_uK`. The units
are coupled by a demand chain: only unit 1 reads the stoppage input `XSP_fail`; unit K
may demand only while unit K-1 demands (its rung L01 reads `RDemand_u(K-1)` instead of
`¬XSP_fail`), so "stoppage ⇒ unit K is off" needs the whole chain u1…uK. Every unit has
7 properties: P1a, P1b, P2, P3, P4a, P4b and P5 (stoppage ⇒ no backflow). The faulty
variant drops the interlock `¬RL1_Prod` from rung L04 of the last unit: exactly its P2 is
false.

    benches/plants.py generate N DIR [--faulty]   # DIR/plant.ld, DIR/plant.ii, DIR/plant.smv
    benches/plants.py run N...  [--nusmv PATH] [--no-nusmv] [--faulty] [--timeout S]

`--ldmicro01` writes the same plants as LDmicro0.1 files with a 1 s cycle (the shape of
issue 30's outside generator): a 0.1 timer counts P = delay/cycle - 1 scans, so with the
default `--timers plc` each unit's P1a and P1b are refuted (the pumps start one scan
before 5s/L1_up holds) and every other property is proved.

`run` times `ii-prove plant.ld plant.ii` (every property, one process, wall clock and peak
memory) and `NuSMV -dynamic -df -coi plant.smv` (every INVARSPEC by BDD on its cone of influence, with PLCverif's settings) in
the same run, checks that the verdicts are what they must be, and prints one table row per
N with the ratio. The SMV model is one transition per scan, rungs in scan order, each timer
a counter of the scans the runtime counts (P = 500 for 5 s at 10 ms, LDmicro0.2).
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CYCLE_US = 10_000
DELAY_US = 5_000_000
P = DELAY_US // CYCLE_US  # LDmicro0.2, no adjust field: P = floor(delay / cycle) + 0
# Timer counters as machine words (NuSMV's BDDs handle them far better than integer
# ranges): consecutive scans with the input on, saturating at P + 1.
BITS = (P + 1).bit_length()
W = f"0ud{BITS}_"
CAP = f"{W}{P + 1}"
# The properties' `5s/x` (on from the (N+1)-th scan of x): the same count for 0.2.
OBS = CAP
VERSION = "LDmicro0.2"


def ldmicro01():
    """Switch to LDmicro0.1 with a 1 s cycle: the program's timers fire one scan before 5s/x."""
    global CYCLE_US, P, BITS, W, CAP, OBS, VERSION
    CYCLE_US = 1_000_000
    n = DELAY_US // CYCLE_US
    P = n - 1  # LDmicro0.1: P = delay / cycle - 1
    BITS = (n + 1).bit_length()
    W = f"0ud{BITS}_"
    CAP = f"{W}{P + 1}"
    OBS = f"{W}{n + 1}"
    VERSION = "LDmicro0.1"


def unit_rungs(k, faulty):
    """The 10 rungs of unit k (1-based) as LDmicro text."""
    u = f"_u{k}"
    demand_gate = "CONTACTS XSP_fail 1" if k == 1 else f"CONTACTS RDemand_u{k - 1} 0"
    interlock = "" if faulty else f"\n    CONTACTS RL1_Prod{u} 1"
    return [
        f"""RUNG
    PARALLEL
        CONTACTS XL_flow{u} 0
        CONTACTS XH_flow{u} 0
    END
    {demand_gate}
    COIL RDemand{u} 0 0 0
END""",
        f"""RUNG
    PARALLEL
        SERIES
            CONTACTS XLine_swap{u} 0
            CONTACTS XL2_fail{u} 1
        END
        CONTACTS XL1_fail{u} 0
    END
    COIL RPrio2{u} 0 0 0
END""",
        f"""RUNG
    PARALLEL
        CONTACTS RPrio2{u} 1
        CONTACTS RL1_Prod{u} 0
    END
    CONTACTS RDemand{u} 0
    CONTACTS XL1_fail{u} 1
    CONTACTS RL2_Prod{u} 1
    COIL RL1_Prod{u} 0 0 0
END""",
        f"""RUNG
    PARALLEL
        CONTACTS RPrio2{u} 0
        CONTACTS RL2_Prod{u} 0
    END
    CONTACTS RDemand{u} 0
    CONTACTS XL2_fail{u} 1{interlock}
    COIL RL2_Prod{u} 0 0 0
END""",
        f"""RUNG
    CONTACTS RL1_Prod{u} 0
    COIL YL1_up{u} 0 0 0
END""",
        f"""RUNG
    CONTACTS RL1_Prod{u} 0
    TON TT1{u} {DELAY_US}
    PARALLEL
        COIL YL1_pump{u} 0 0 0
        COIL YL1_down{u} 0 0 0
    END
END""",
        f"""RUNG
    CONTACTS RL2_Prod{u} 0
    COIL YL2_up{u} 0 0 0
END""",
        f"""RUNG
    CONTACTS RL2_Prod{u} 0
    TON TT2{u} {DELAY_US}
    PARALLEL
        COIL YL2_pump{u} 0 0 0
        COIL YL2_down{u} 0 0 0
    END
END""",
        f"""RUNG
    PARALLEL
        CONTACTS YL1_pump{u} 0
        CONTACTS YL2_pump{u} 0
    END
    COIL YOut_valve{u} 0 0 0
END""",
        f"""RUNG
    PARALLEL
        CONTACTS YL1_pump{u} 0
        CONTACTS YL2_pump{u} 0
    END
    CONTACTS XL_flow{u} 0
    CONTACTS XH_flow{u} 1
    COIL YBf_valve{u} 0 0 0
END""",
    ]


def ladder(n, faulty):
    rungs = []
    for k in range(1, n + 1):
        rungs.extend(unit_rungs(k, faulty and k == n))
    return f"{VERSION}\nCYCLE={CYCLE_US}\n\nPROGRAM\n" + "\n".join(rungs) + "\n"


def properties(n):
    out = [f"// {7 * n} properties of a chain of {n} water units (benches/plants.py)."]
    for k in range(1, n + 1):
        u = f"_u{k}"
        l1 = f"L1_up{u} + L1_pump{u} + L1_down{u}"
        l2 = f"L2_up{u} + L2_pump{u} + L2_down{u}"
        off = " . ".join(
            f"!{s}{u}"
            for s in ["L1_pump", "L1_up", "L1_down", "L2_pump", "L2_up", "L2_down", "Out_valve", "Bf_valve"]
        )
        out += [
            f"property P1a{u}: L1_pump{u} => 5s/L1_up{u}",
            f"property P1b{u}: L2_pump{u} => 5s/L2_up{u}",
            f"property P2{u}: ({l1}) . ({l2}) = 0*",
            f"property P3{u}: SP_fail => {off}",
            f"property P4a{u}: L1_fail{u} => !L1_pump{u} . !L1_up{u} . !L1_down{u}",
            f"property P4b{u}: L2_fail{u} => !L2_pump{u} . !L2_up{u} . !L2_down{u}",
            f"property P5{u}: SP_fail => !Bf_valve{u}",
        ]
    return "\n".join(out) + "\n"


def smv(n, faulty):
    """One NuSMV transition per scan; `init` is the first scan (previous values 0)."""
    inputs, bits, lines_init, lines_next, counters, specs = [], [], [], [], [], []

    def rd(name, written, mode):
        # A bit written earlier in the scan is read at this scan; a later one (or the
        # bit itself) at the previous scan; an input at this scan.
        if name in written or name.startswith("X"):
            return name if mode == "init" else f"next({name})"
        return "FALSE" if mode == "init" else name

    inputs.append("XSP_fail")
    for k in range(1, n + 1):
        u = f"_u{k}"
        for x in ["XL_flow", "XH_flow", "XLine_swap", "XL1_fail", "XL2_fail"]:
            inputs.append(x + u)
        drop = faulty and k == n

        def rung(target, f):
            bits.append(target)
            lines_init.append(f"init({target}) := {f('init')};")
            lines_next.append(f"next({target}) := {f('next')};")

        w = set(bits)
        # L01 .. L10 in scan order; `w` grows as coils are written.

        def r(name, mode):
            return rd(name, w, mode)

        gate = (lambda m: f"!{r('XSP_fail', m)}") if k == 1 else (lambda m: r(f"RDemand_u{k - 1}", m))
        rung(f"RDemand{u}", lambda m: f"({r('XL_flow' + u, m)} | {r('XH_flow' + u, m)}) & {gate(m)}")
        w.add(f"RDemand{u}")
        rung(f"RPrio2{u}", lambda m: f"(({r('XLine_swap' + u, m)} & !{r('XL2_fail' + u, m)}) | {r('XL1_fail' + u, m)})")
        w.add(f"RPrio2{u}")
        rung(
            f"RL1_Prod{u}",
            lambda m: f"(!{r('RPrio2' + u, m)} | {r('RL1_Prod' + u, m)}) & {r('RDemand' + u, m)} & !{r('XL1_fail' + u, m)} & !{r('RL2_Prod' + u, m)}",
        )
        w.add(f"RL1_Prod{u}")
        interlock = (lambda m: "TRUE") if drop else (lambda m: f"!{r('RL1_Prod' + u, m)}")
        rung(
            f"RL2_Prod{u}",
            lambda m: f"({r('RPrio2' + u, m)} | {r('RL2_Prod' + u, m)}) & {r('RDemand' + u, m)} & !{r('XL2_fail' + u, m)} & {interlock(m)}",
        )
        w.add(f"RL2_Prod{u}")
        for line in ["1", "2"]:
            prod = f"RL{line}_Prod{u}"
            rung(f"YL{line}_up{u}", lambda m, prod=prod: r(prod, m))
            w.add(f"YL{line}_up{u}")
            c = f"cT{line}{u}"
            counters.append(c)
            # Consecutive scans with the timer's input on, this one included, capped at P+1.
            lines_init.append(f"init({c}) := {prod} ? {W}1 : {W}0;")
            lines_next.append(f"next({c}) := next({prod}) ? ({c} < {CAP} ? {c} + {W}1 : {CAP}) : {W}0;")
            for coil in ["pump", "down"]:
                rung(f"YL{line}_{coil}{u}", lambda m, c=c: f"{c} >= {CAP}" if m == "init" else f"next({c}) >= {CAP}")
                w.add(f"YL{line}_{coil}{u}")
        rung(f"YOut_valve{u}", lambda m: f"({r('YL1_pump' + u, m)} | {r('YL2_pump' + u, m)})")
        w.add(f"YOut_valve{u}")
        rung(
            f"YBf_valve{u}",
            lambda m: f"({r('YL1_pump' + u, m)} | {r('YL2_pump' + u, m)}) & {r('XL_flow' + u, m)} & !{r('XH_flow' + u, m)}",
        )
        w.add(f"YBf_valve{u}")
        # Observers of the properties' timers: 5s/L1_up, 5s/L2_up.
        for line in ["1", "2"]:
            o = f"o{line}{u}"
            counters.append(o)
            lines_init.append(f"init({o}) := YL{line}_up{u} ? {W}1 : {W}0;")
            lines_next.append(f"next({o}) := next(YL{line}_up{u}) ? ({o} < {OBS} ? {o} + {W}1 : {OBS}) : {W}0;")
        off = " & ".join(
            f"!{s}{u}"
            for s in ["YL1_pump", "YL1_up", "YL1_down", "YL2_pump", "YL2_up", "YL2_down", "YOut_valve", "YBf_valve"]
        )
        specs += [
            f"INVARSPEC NAME P1a{u} := YL1_pump{u} -> o1{u} >= {OBS}",
            f"INVARSPEC NAME P1b{u} := YL2_pump{u} -> o2{u} >= {OBS}",
            f"INVARSPEC NAME P2{u} := !((YL1_up{u} | YL1_pump{u} | YL1_down{u}) & (YL2_up{u} | YL2_pump{u} | YL2_down{u}))",
            f"INVARSPEC NAME P3{u} := XSP_fail -> ({off})",
            f"INVARSPEC NAME P4a{u} := XL1_fail{u} -> (!YL1_pump{u} & !YL1_up{u} & !YL1_down{u})",
            f"INVARSPEC NAME P4b{u} := XL2_fail{u} -> (!YL2_pump{u} & !YL2_up{u} & !YL2_down{u})",
            f"INVARSPEC NAME P5{u} := XSP_fail -> !YBf_valve{u}",
        ]
    out = ["MODULE main", "VAR"]
    out += [f"  {x} : boolean;" for x in inputs + bits]
    out += [f"  {c} : unsigned word[{BITS}];" for c in counters]
    out += ["ASSIGN"] + [f"  {line}" for line in lines_init + lines_next]
    out += specs
    return "\n".join(out) + "\n"


def generate(n, directory, faulty):
    os.makedirs(directory, exist_ok=True)
    paths = {}
    for ext, text in [("ld", ladder(n, faulty)), ("ii", properties(n)), ("smv", smv(n, faulty))]:
        paths[ext] = os.path.join(directory, f"plant.{ext}")
        with open(paths[ext], "w") as f:
            f.write(text)
    return paths


def timed(cmd, timeout):
    """Wall time, peak RSS (MiB) of the child, exit code and stdout of `cmd` (None on timeout)."""
    start = time.perf_counter()
    with tempfile.TemporaryFile("w+") as out:
        p = subprocess.Popen(cmd, stdout=out, stderr=subprocess.DEVNULL, text=True)
        while True:
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() - start > timeout:
                p.kill()
                os.wait4(p.pid, 0)
                return time.perf_counter() - start, None, None, ""
            time.sleep(0.002)
        wall = time.perf_counter() - start
        out.seek(0)
        return wall, usage.ru_maxrss / 1024, os.waitstatus_to_exitcode(status), out.read()


def run(args):
    binary = os.environ.get("II_PROVE") or os.path.join(ROOT, "target", "release", "ii-prove")
    if not os.path.exists(binary):
        subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    nusmv = None
    if not args.no_nusmv:
        nusmv = args.nusmv or subprocess.run(
            [os.path.join(ROOT, "benches", "peers", "build_nusmv.sh")], stdout=subprocess.PIPE, text=True, check=True
        ).stdout.strip()
    print(f"| N units (rungs, properties) | ii-prove | verdicts | NuSMV -dynamic -df -coi | verdicts | ratio |")
    print("|---|---|---|---|---|---|")
    for n in args.n:
        with tempfile.TemporaryDirectory() as d:
            paths = generate(n, d, args.faulty)
            wall, mem, code, out = timed([binary, paths["ld"], paths["ii"], "--timeout", str(args.timeout)], args.limit)
            summary = re.search(r"(\d+) proved, (\d+) refuted, (\d+) unknown", out or "")
            verdict = "timeout" if code is None else (summary.group(0) if summary else f"exit {code}")
            if summary and args.ldmicro01:
                refuted = sorted(re.findall(r"^(\S+)\s+refuted", out, re.M))
                want = sorted(f"P1{s}_u{k}" for k in range(1, n + 1) for s in "ab")
                assert (summary.group(1), refuted) == (str(5 * n), want), f"N={n}: {verdict}"
            elif summary and not args.faulty:
                assert summary.group(1) == str(7 * n), f"N={n}: {verdict}"
            if summary and args.faulty:
                refuted = re.findall(r"^(\S+)\s+refuted", out, re.M)
                assert refuted == [f"P2_u{n}"], f"N={n}: refuted {refuted}"
            ours = f"{wall:.3f} s, {mem:.0f} MiB" if mem is not None else f"> {args.limit} s"
            theirs, their_verdict, ratio = "—", "—", "—"
            if nusmv:
                nwall, nmem, ncode, nout = timed([nusmv, "-dynamic", "-df", "-coi", paths["smv"]], args.limit)
                if ncode is None:
                    theirs, their_verdict = f"> {args.limit} s (killed)", "no verdict"
                    ratio = f"> {args.limit / wall:.1f}×"
                else:
                    true = len(re.findall(r"-- invariant .* is true", nout))
                    false = len(re.findall(r"-- invariant .* is false", nout))
                    theirs, their_verdict = f"{nwall:.3f} s, {nmem:.0f} MiB", f"{true} true, {false} false"
                    ratio = f"{nwall / wall:.2f}× faster" if wall < nwall else f"{wall / nwall:.2f}× slower"
            print(f"| {n} ({10 * n}, {7 * n}) | {ours} | {verdict} | {theirs} | {their_verdict} | {ratio} |", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    g = sub.add_parser("generate")
    g.add_argument("n", type=int)
    g.add_argument("dir")
    g.add_argument("--faulty", action="store_true")
    g.add_argument("--ldmicro01", action="store_true")
    r = sub.add_parser("run")
    r.add_argument("n", type=int, nargs="+")
    r.add_argument("--nusmv")
    r.add_argument("--no-nusmv", action="store_true")
    r.add_argument("--faulty", action="store_true")
    r.add_argument("--ldmicro01", action="store_true")
    r.add_argument("--timeout", type=float, default=10.0, help="ii-prove's --timeout per property")
    r.add_argument("--limit", type=float, default=600.0, help="wall-clock limit per tool run")
    args = parser.parse_args()
    if args.ldmicro01:
        ldmicro01()
    if args.command == "generate":
        for path in generate(args.n, args.dir, args.faulty).values():
            print(path)
    else:
        run(args)


if __name__ == "__main__":
    sys.exit(main())
