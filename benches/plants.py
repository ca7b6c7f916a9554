#!/usr/bin/env python3
"""Water plants of N units in two shapes, checked by ii-prove, NuSMV and ABC in the same run.

Each unit is the 10 rungs of examples/water.ld with its signals suffixed `_uK`. Every
unit has 7 properties: P1a, P1b, P2, P3, P4a, P4b and P5 (stoppage ⇒ no backflow).

`--shape chain` (the default): one demand chain. Only unit 1 reads the stoppage input
`XSP_fail`; unit K may demand only while unit K-1 demands (its rung L01 reads
`RDemand_u(K-1)` instead of `¬XSP_fail`), so "stoppage ⇒ unit K is off" needs the whole
chain u1…uK. Every property holds.

`--shape mesh`: independent demand chains of 5 units (units 5J-4 … 5J form chain J,
stopped by its own input `XSP_fail_cJ`; a chain's head reads `¬XSP_fail_cJ`, the others
the demand of the unit before them). One unit's timer fans out to all: every unit's
priority rung L02 also reads `YL2_pump_u1` (unit 1's timed pump; unit 1 itself reads the
previous scan's value, the others this scan's). Timers are read through contacts of
other units: an 11th rung per unit, `YAssist_uK := (YL1_pump_uS + YL1_up_uS) · XL_flow_uK`,
reads unit S = K-1 (earlier in the scan, the same chain) or, for a chain's head, S = K+1
(later in the scan: the previous scan's value). The 8th property
`P6_uK: SP_fail_cJ ⇒ ¬Assist_uK` holds where S = K-1 and is violated at a chain's head
(a fifth of the units): the stoppage arrives while unit K+1's line was up at the scan
before. A head alone in its chain (N not a multiple of 5) reads its own unit (S = K,
this scan) and P6 holds.

`--faulty` drops the interlock `¬RL1_Prod` from rung L04 of the last unit: its P2 is
false. `--ldmicro01` writes LDmicro0.1 files with a 1 s cycle (the shape of issue 30's
outside generator): a 0.1 timer counts P = delay/cycle - 1 scans, so with `--timers plc`
each unit's P1a and P1b are refuted (the pumps start one scan before 5s/L1_up holds);
with `--timers ideal` they hold. Without it: LDmicro0.2, a 10 ms cycle, P = 500 scans.

    benches/plants.py generate N DIR [--shape chain|mesh] [--faulty] [--ldmicro01]
        # DIR/plant.ld, DIR/plant.ii, DIR/plant.smv
    benches/plants.py run N... [--shape chain --shape mesh] [--ldmicro01] [--faulty]
        [--limit S] [--tools ii-plc,nusmv-df,abc-pdr,...] [--ii-prove PATH] [--nusmv PATH]

`run` generates each plant and checks every property with each tool and mode in the
same run (see benches/plant_peers.py): ii-prove (`--timers plc` and `--timers ideal`),
NuSMV 2.5.4 on the SMV model (`-df`, `-df -coi`, `-dynamic -df -coi`), ABC on the model
`ii-prove export --aiger` writes (`pdr -a`, `int -k -d`, `bmc3 -a`). Each tool's
verdicts are compared, property by property, with the expected ones above; a
disagreement is printed on standard error and makes the exit code 1. One table row per
(shape, N): wall time, user CPU time, peak memory and verdict counts per tool and mode.

The SMV model is one transition per scan (`init` is the first scan, previous values 0),
rungs in scan order: a bit written earlier in the scan is read at this scan, a later one
at the previous scan. Each timer is a word counter of the consecutive scans its input is
on, saturating at P + 1; the properties' `5s/x` are observer counters. Variable order:
the stoppage inputs first, then each unit's variables together (its inputs, its bits in
scan order, its counters), the order NuSMV's BDDs do best with on these plants.
"""

import argparse
import os
import sys

import plant_peers

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
CHAIN = 5  # units per demand chain of the mesh shape
SHAPES = ("chain", "mesh")


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


class Shape:
    """Where unit k's demand comes from, which stoppage input stops it, what else it reads."""

    def __init__(self, name, n):
        self.name, self.n = name, n

    def mesh(self):
        return self.name == "mesh"

    def head(self, k):
        return k == 1 if not self.mesh() else (k - 1) % CHAIN == 0

    def stop(self, k):
        """The stoppage input that stops unit k (LDmicro name)."""
        return "XSP_fail" if not self.mesh() else f"XSP_fail_c{(k - 1) // CHAIN + 1}"

    def stops(self):
        return sorted({self.stop(k) for k in range(1, self.n + 1)}, key=lambda s: (len(s), s))

    def assist_source(self, k):
        """The unit whose line YAssist_uk reads (mesh only)."""
        if not self.head(k):
            return k - 1
        return k + 1 if k < self.n else k

    def properties_per_unit(self):
        return 8 if self.mesh() else 7

    def rungs_per_unit(self):
        return 11 if self.mesh() else 10


def expected(shape, faulty, timers):
    """Each property's expected verdict (True: it holds) under `--timers plc|ideal`."""
    early = VERSION == "LDmicro0.1" and timers == "plc"
    out = {}
    for k in range(1, shape.n + 1):
        u = f"_u{k}"
        out |= {f"P1a{u}": not early, f"P1b{u}": not early, f"P2{u}": not (faulty and k == shape.n)}
        out |= {f"P{p}{u}": True for p in ["3", "4a", "4b", "5"]}
        if shape.mesh():
            out[f"P6{u}"] = shape.assist_source(k) <= k
    return out


def unit_rungs(shape, k, faulty):
    """The rungs of unit k (1-based) as LDmicro text."""
    u = f"_u{k}"
    demand_gate = f"CONTACTS {shape.stop(k)} 1" if shape.head(k) else f"CONTACTS RDemand_u{k - 1} 0"
    interlock = "" if faulty else f"\n    CONTACTS RL1_Prod{u} 1"
    fan_out = "\n        CONTACTS YL2_pump_u1 0" if shape.mesh() else ""
    rungs = [
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
        CONTACTS XL1_fail{u} 0{fan_out}
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
    if shape.mesh():
        s = f"_u{shape.assist_source(k)}"
        rungs.append(
            f"""RUNG
    PARALLEL
        CONTACTS YL1_pump{s} 0
        CONTACTS YL1_up{s} 0
    END
    CONTACTS XL_flow{u} 0
    COIL YAssist{u} 0 0 0
END"""
        )
    return rungs


def ladder(shape, faulty):
    rungs = []
    for k in range(1, shape.n + 1):
        rungs.extend(unit_rungs(shape, k, faulty and k == shape.n))
    return f"{VERSION}\nCYCLE={CYCLE_US}\n\nPROGRAM\n" + "\n".join(rungs) + "\n"


def properties(shape):
    n = shape.n
    out = [f"// {shape.properties_per_unit() * n} properties of a {shape.name} of {n} water units (benches/plants.py)."]
    for k in range(1, n + 1):
        u = f"_u{k}"
        stop = shape.stop(k)[1:]
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
            f"property P3{u}: {stop} => {off}",
            f"property P4a{u}: L1_fail{u} => !L1_pump{u} . !L1_up{u} . !L1_down{u}",
            f"property P4b{u}: L2_fail{u} => !L2_pump{u} . !L2_up{u} . !L2_down{u}",
            f"property P5{u}: {stop} => !Bf_valve{u}",
        ]
        if shape.mesh():
            out.append(f"property P6{u}: {stop} => !Assist{u}")
    return "\n".join(out) + "\n"


def smv(shape, faulty):
    """One NuSMV transition per scan; `init` is the first scan (previous values 0)."""
    decls, lines_init, lines_next, specs = [], [], [], []
    written = set()

    def r(name, mode):
        # A bit written earlier in the scan is read at this scan; a later one (or the
        # bit itself) at the previous scan; an input at this scan.
        if name in written or name.startswith("X"):
            return name if mode == "init" else f"next({name})"
        return "FALSE" if mode == "init" else name

    def rung(target, f):
        decls.append(f"  {target} : boolean;")
        lines_init.append(f"init({target}) := {f('init')};")
        lines_next.append(f"next({target}) := {f('next')};")
        written.add(target)

    def counter(c, of, cap):
        # Consecutive scans with `of` on, this one included, capped at `cap`.
        decls.append(f"  {c} : unsigned word[{BITS}];")
        lines_init.append(f"init({c}) := {of} ? {W}1 : {W}0;")
        lines_next.append(f"next({c}) := next({of}) ? ({c} < {cap} ? {c} + {W}1 : {cap}) : {W}0;")

    decls += [f"  {x} : boolean;" for x in shape.stops()]
    for k in range(1, shape.n + 1):
        u = f"_u{k}"
        decls += [f"  {x}{u} : boolean;" for x in ["XL_flow", "XH_flow", "XLine_swap", "XL1_fail", "XL2_fail"]]
        stop = shape.stop(k)
        drop = faulty and k == shape.n
        gate = (lambda m: f"!{r(stop, m)}") if shape.head(k) else (lambda m: r(f"RDemand_u{k - 1}", m))
        rung(f"RDemand{u}", lambda m: f"({r('XL_flow' + u, m)} | {r('XH_flow' + u, m)}) & {gate(m)}")
        fan = (lambda m: f" | {r('YL2_pump_u1', m)}") if shape.mesh() else (lambda m: "")
        rung(
            f"RPrio2{u}",
            lambda m: f"(({r('XLine_swap' + u, m)} & !{r('XL2_fail' + u, m)}) | {r('XL1_fail' + u, m)}{fan(m)})",
        )
        rung(
            f"RL1_Prod{u}",
            lambda m: f"(!{r('RPrio2' + u, m)} | {r('RL1_Prod' + u, m)}) & {r('RDemand' + u, m)} & !{r('XL1_fail' + u, m)} & !{r('RL2_Prod' + u, m)}",
        )
        interlock = (lambda m: "TRUE") if drop else (lambda m: f"!{r('RL1_Prod' + u, m)}")
        rung(
            f"RL2_Prod{u}",
            lambda m: f"({r('RPrio2' + u, m)} | {r('RL2_Prod' + u, m)}) & {r('RDemand' + u, m)} & !{r('XL2_fail' + u, m)} & {interlock(m)}",
        )
        for line in ["1", "2"]:
            prod = f"RL{line}_Prod{u}"
            rung(f"YL{line}_up{u}", lambda m, prod=prod: r(prod, m))
            c = f"cT{line}{u}"
            counter(c, prod, CAP)
            for coil in ["pump", "down"]:
                rung(f"YL{line}_{coil}{u}", lambda m, c=c: f"{c} >= {CAP}" if m == "init" else f"next({c}) >= {CAP}")
        rung(f"YOut_valve{u}", lambda m: f"({r('YL1_pump' + u, m)} | {r('YL2_pump' + u, m)})")
        rung(
            f"YBf_valve{u}",
            lambda m: f"({r('YL1_pump' + u, m)} | {r('YL2_pump' + u, m)}) & {r('XL_flow' + u, m)} & !{r('XH_flow' + u, m)}",
        )
        if shape.mesh():
            s = f"_u{shape.assist_source(k)}"
            rung(f"YAssist{u}", lambda m: f"({r('YL1_pump' + s, m)} | {r('YL1_up' + s, m)}) & {r('XL_flow' + u, m)}")
        # Observers of the properties' timers: 5s/L1_up, 5s/L2_up.
        for line in ["1", "2"]:
            counter(f"o{line}{u}", f"YL{line}_up{u}", OBS)
        off = " & ".join(
            f"!{s}{u}"
            for s in ["YL1_pump", "YL1_up", "YL1_down", "YL2_pump", "YL2_up", "YL2_down", "YOut_valve", "YBf_valve"]
        )
        specs += [
            f"INVARSPEC NAME P1a{u} := YL1_pump{u} -> o1{u} >= {OBS}",
            f"INVARSPEC NAME P1b{u} := YL2_pump{u} -> o2{u} >= {OBS}",
            f"INVARSPEC NAME P2{u} := !((YL1_up{u} | YL1_pump{u} | YL1_down{u}) & (YL2_up{u} | YL2_pump{u} | YL2_down{u}))",
            f"INVARSPEC NAME P3{u} := {stop} -> ({off})",
            f"INVARSPEC NAME P4a{u} := XL1_fail{u} -> (!YL1_pump{u} & !YL1_up{u} & !YL1_down{u})",
            f"INVARSPEC NAME P4b{u} := XL2_fail{u} -> (!YL2_pump{u} & !YL2_up{u} & !YL2_down{u})",
            f"INVARSPEC NAME P5{u} := {stop} -> !YBf_valve{u}",
        ]
        if shape.mesh():
            specs.append(f"INVARSPEC NAME P6{u} := {stop} -> !YAssist{u}")
    out = ["MODULE main", "VAR"] + decls
    out += ["ASSIGN"] + [f"  {line}" for line in lines_init + lines_next]
    out += specs
    return "\n".join(out) + "\n"


def generate(shape, directory, faulty):
    os.makedirs(directory, exist_ok=True)
    paths = {}
    for ext, text in [("ld", ladder(shape, faulty)), ("ii", properties(shape)), ("smv", smv(shape, faulty))]:
        paths[ext] = os.path.join(directory, f"plant.{ext}")
        with open(paths[ext], "w") as f:
            f.write(text)
    return paths


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    g = sub.add_parser("generate")
    g.add_argument("n", type=int)
    g.add_argument("dir")
    g.add_argument("--shape", choices=SHAPES, default="chain")
    g.add_argument("--faulty", action="store_true")
    g.add_argument("--ldmicro01", action="store_true")
    r = sub.add_parser("run")
    r.add_argument("n", type=int, nargs="+")
    r.add_argument("--shape", choices=SHAPES, action="append", help="repeatable; default: chain")
    r.add_argument("--faulty", action="store_true")
    r.add_argument("--ldmicro01", action="store_true")
    plant_peers.add_options(r)
    args = parser.parse_args()
    if args.ldmicro01:
        ldmicro01()
    if min([args.n] if args.command == "generate" else args.n) < 1:
        parser.error("N must be at least 1")
    if args.command == "generate":
        for path in generate(Shape(args.shape, args.n), args.dir, args.faulty).values():
            print(path)
        return 0
    return plant_peers.run(args, sys.modules[__name__])


if __name__ == "__main__":
    sys.exit(main())
