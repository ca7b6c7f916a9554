"""Runs PLCopen programs on the editors' own toolchain, scan by scan, and records what they do.

Usage: run.py WORK_DIR  (environment: ORACLE_BEREMIZ, ORACLE_MATIEC, ORACLE_PYTHON, and
ORACLE_ORDER=layout to restore the generator's Python 2 position order, see gen_st.py)

For every request `K.req.json` in WORK_DIR (written by the oracle tests), with a PLCopen
project `K.xml` or Structured Text `K.st`:

  1. Beremiz's PLCGenerator.py turns a project into ST (`gen_st.py`, one process; a
     `K.st` without a `K.xml` is used as it is);
  2. matiec's `iec2c` turns the ST into C;
  3. a harness (written here from matiec's generated headers) is compiled with gcc and
     run: `config_init__()`, then per scan the requested inputs are written, the
     runtime clock `__CURRENT_TIME` set to scan x cycle, and `config_run__(scan)`
     called; after each scan the requested values are printed.

The request names what to drive and what to read, in the prover's names:
  {"pou": "main", "cycle_ns": N, "scans": S,
   "inputs": {"In0": "0110...",                 # a BOOL: its value per scan
              "N": [3, -7, 12, ...]},           # an integer: its value per scan
   "starts": {"B1": 1, "N": 40, ...},           # written after init (warm restart)
   "want": [{"bit": "TON0_Q"},                  # a BOOL variable or FB member, by flat name
            {"int": "C1_CV"},                   # an integer one (SINT ... ULINT, BYTE ...
                                                # LWORD; TIME in microseconds: `T1_ET`;
                                                # a REAL as its 32-bit pattern)
            {"int": "F_X", "optional": true},   # null in the answer if there is no such
                                                # member (any want may say so)
            {"edge": [path, localId, field, rank]}]}  # the edge detector Beremiz made
                                                # for element localId of the POU
                                                # instance at path (FB instance
                                                # names), field Q or M
A flat name is the C member path joined by `_` (matiec upper-cases identifiers), so
`TON0.Q` is `TON0_Q` and `UF0.TON1.Q` is `UF0_TON1_Q`, the prover's names for them. An
integer input's value is converted to the member's C type as C assignment does (so it
wraps into an unsigned type); a REAL input's value is its 32-bit pattern.

The answer `K.out.json` is {"status": "ok", "trace": ["0101", [0, 1, 1, 2], ...]} (per
want in order: a bit's string, one character per scan; an integer's list, one number per
scan; null for an optional want not found) or {"status": "<stage>", "message": ...}
when a stage refused the program or a name could not be found.
"""
import concurrent.futures
import json
import os
import re
import subprocess
import sys

BEREMIZ = os.environ.get("ORACLE_BEREMIZ", "")
MATIEC = os.environ.get("ORACLE_MATIEC", "")
PYTHON = os.environ.get("ORACLE_PYTHON", sys.executable)
HERE = os.path.dirname(os.path.abspath(__file__))

STRUCT = re.compile(r"typedef struct \{(.*?)\}\s*(\w+);", re.S)
DERIVED = re.compile(r"__DECLARE_DERIVED_TYPE\((\w+),\s*(\w+)\)")
FIELD = re.compile(r"__DECLARE_(VAR|LOCATED|EXTERNAL)\((\w+),(\w+)\)|^\s*(\w+)\s+(\w+);", re.M)


def structs(*headers):
    """Struct name -> [(kind, type, field)] from matiec's C headers; a field of a derived
    type (a subrange, `__DECLARE_DERIVED_TYPE(LEVEL_T,INT)`) has its base type."""
    out = {}
    texts = [open(h, encoding="utf-8", errors="replace").read() for h in headers]
    derived = {name: base for text in texts for name, base in DERIVED.findall(text)}
    for text in texts:
        for body, name in STRUCT.findall(text):
            fields = []
            for m in FIELD.finditer(body):
                if m.group(1):
                    fields.append((m.group(1), derived.get(m.group(2), m.group(2)), m.group(3)))
                elif m.group(4) not in ("return", "typedef"):
                    fields.append(("FB", m.group(4), m.group(5)))
            out[name] = fields
    return out


# matiec's C types of the integers `{"int": ...}` reads (iec_types.h), and TIME.
INTEGERS = {"SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT",
            "BYTE", "WORD", "DWORD", "LWORD"}
UNSIGNED64 = {"ULINT", "LWORD"}


def leaves(types, ty, path=()):
    """Every scalar member reachable from a struct: flat name -> (path, kind, C type)."""
    out = {}
    for kind, fty, name in types.get(ty, []):
        p = path + (name,)
        if kind == "FB":
            out.update(leaves(types, fty, p))
        else:
            out["_".join(p).upper()] = (p, kind, fty)
    return out


def access(base, path, kind):
    member = base + "." + ".".join(path) + ".value"
    return "(*(%s))" % member if kind in ("LOCATED", "EXTERNAL") else "(%s)" % member


def struct_at(types, ty, path):
    """The struct type at an instance path, and the path as C spells it."""
    spelled = []
    for name in path:
        fields = {f.upper(): (t, f) for k, t, f in types.get(ty, []) if k == "FB"}
        ty, field = fields.get(name.upper(), (None, None))
        if ty is None:
            return None, None
        spelled.append(field)
    return ty, tuple(spelled)


def harness(req, types, prog_type, instance, trigs):
    flat = leaves(types, prog_type)

    def member(name, allowed, what):
        hit = flat.get(name.upper())
        if hit is None or hit[2] not in allowed:
            raise LookupError("no %s member `%s` in %s" % (what, name, prog_type))
        return access(instance, hit[0], hit[1]), hit[2]

    def bit(name):
        return member(name, {"BOOL"}, "BOOL")[0]

    def integer(name):
        """A C expression of type long long (unsigned for ULINT, LWORD), and its printf."""
        c, ty = member(name, INTEGERS | {"TIME", "REAL"}, "integer")
        if ty == "REAL":
            return "real_bits(%s)" % c, "%lld"
        if ty == "TIME":
            return "((long long)%s.tv_sec * 1000000000LL + %s.tv_nsec)" % (c, c), "%lld"
        if ty in UNSIGNED64:
            return "((unsigned long long)%s)" % c, "%llu"
        return "((long long)%s)" % c, "%lld"

    def edge(path, local_id, field, rank):
        ty, path = struct_at(types, prog_type, path)
        if ty is None:
            raise LookupError("no instance path %s" % path)
        found = sorted((int(info[4]) if info[1] == "block" else 0, inst.split("@")[0])
                       for inst, info in trigs.items()
                       # the debug map also lists each detector's output (`F_TRIG2.Q`)
                       if "." not in inst.split("@")[0]
                       and info[0].split("::")[-1].upper() == ty.upper() and info[2] == str(local_id))
        if rank >= len(found):
            raise LookupError("no edge detector %d of element %s of %s" % (rank, local_id, ty))
        return access(instance, tuple(path) + (found[rank][1], field), "VAR")

    # Per want: None (optional, not found), or ("bit", C) or ("int", C, printf format).
    reads = []
    for w in req["want"]:
        try:
            if "bit" in w:
                reads.append(("bit", bit(w["bit"])))
            elif "int" in w:
                reads.append(("int",) + integer(w["int"]))
            else:
                reads.append(("bit", edge(*w["edge"])))
        except LookupError:
            if not w.get("optional"):
                raise
            reads.append(None)
    scans = req["scans"]
    inputs = list(req["inputs"].items())
    lines = [
        '#include "iec_std_lib.h"',
        "#define __LOCATED_VAR(type, name, ...) type __##name; type *name = &__##name;",
        '#include "LOCATED_VARIABLES.h"',
        "#undef __LOCATED_VAR",
        '#include "POUS.h"',
        "#include <stdio.h>",
        "#include <string.h>",
        "static long long real_bits(REAL x) { unsigned u; memcpy(&u, &x, 4); return u; }",
        "static REAL real_of(long long v) { unsigned u = (unsigned)v; REAL x; memcpy(&x, &u, 4); return x; }",
        "TIME __CURRENT_TIME;",
        "BOOL __DEBUG;",
        "extern unsigned long long common_ticktime__;",
        "extern %s %s;" % (prog_type, instance),
        "void config_init__(void);",
        "void config_run__(unsigned long tick);",
        "int main(void) {",
    ]
    for j, (name, v) in enumerate(inputs):
        if isinstance(v, str):
            lines.append('  static const char in%d[] = "%s";' % (j, v))
        else:
            lines.append("  static const long long in%d[] = {%s};" % (j, ", ".join("%dLL" % x for x in v) or "0"))
    lines.append("  config_init__();")

    def scalar(name):
        return member(name, INTEGERS | {"BOOL"}, "BOOL or integer")[0]

    def driven(name):
        """A C assignment of `v` (a C expression of the value given) to input `name`."""
        c, ty = member(name, INTEGERS | {"BOOL", "REAL"}, "BOOL, integer or REAL")
        return (lambda v: "%s = real_of(%s);" % (c, v)) if ty == "REAL" else (lambda v: "%s = %s;" % (c, v))

    for name, v in req.get("starts", {}).items():
        lines.append("  %s = %d;" % (scalar(name), v))
    lines.append("  for (unsigned long k = 0; k < %d; k++) {" % scans)
    for j, (name, v) in enumerate(inputs):
        if isinstance(v, str):
            lines.append("    %s = in%d[k] == '1';" % (bit(name), j))
        else:
            lines.append("    " + driven(name)("in%d[k]" % j))
    lines += [
        "    __CURRENT_TIME.tv_sec = (k * %dULL) / 1000000000ULL;" % req["cycle_ns"],
        "    __CURRENT_TIME.tv_nsec = (k * %dULL) %% 1000000000ULL;" % req["cycle_ns"],
        "    config_run__(k);",
    ]
    # One line per scan, `@@` and one token per want found: 0/1 for a bit, a number for an
    # integer. The marker (on a line of its own) sets the rows apart from what the program
    # prints itself (a pragma's `printf`).
    lines.append('    fputs("\\n@@", stdout);')
    for r in reads:
        if r is None:
            continue
        if r[0] == "bit":
            lines.append('    printf(" %%c", %s ? \'1\' : \'0\');' % r[1])
        else:
            lines.append('    printf(" %s", %s);' % (r[2], r[1]))
    lines += ['    putchar(\'\\n\');', "  }", "  return 0;", "}"]
    return "\n".join(lines) + "\n", reads


def build_and_run(work, k):
    req = json.load(open(os.path.join(work, k + ".req.json")))
    cdir = os.path.join(work, k + ".c")
    os.makedirs(cdir, exist_ok=True)
    r = subprocess.run([os.path.join(MATIEC, "iec2c"), "-I", os.path.join(MATIEC, "lib"), "-T", cdir,
                        os.path.join(work, k + ".st")], capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        return {"status": "iec2c", "message": (r.stdout + r.stderr)[-2000:]}
    types = structs(os.path.join(cdir, "POUS.h"), os.path.join(MATIEC, "lib", "C", "iec_std_FB.h"))
    resources = [f for f in os.listdir(cdir) if f.endswith(".c") and f not in ("POUS.c", "main.c", "all.c")]
    instances = []
    for f in resources:
        for ty, name in re.findall(r"^(\w+) (\w+__\w+);", open(os.path.join(cdir, f)).read(), re.M):
            if ty.upper() == req["pou"].upper():
                instances.append((ty, name))
    if len(instances) != 1:
        return {"status": "map", "message": "%d instances of %s" % (len(instances), req["pou"])}
    prog_type, instance = instances[0]
    trigs = json.load(open(os.path.join(work, k + ".json")))
    try:
        main, reads = harness(req, types, prog_type, instance, trigs)
    except LookupError as e:
        return {"status": "map", "message": str(e)}
    open(os.path.join(cdir, "main.c"), "w").write(main)
    # iec2c appends the names of some globals, with no newline, to the list of located
    # variables; only the `__LOCATED_VAR(...)` entries are declarations.
    located = os.path.join(cdir, "LOCATED_VARIABLES.h")
    if os.path.exists(located):
        text = open(located).read().replace(")", ")\n")
        entries = [l for l in text.splitlines() if l.startswith("__LOCATED_VAR(")]
        open(located, "w").write("".join(e + "\n" for e in entries))
    exe = os.path.join(cdir, "run")
    # One translation unit: the standard library's headers are read once, not per file.
    unity = os.path.join(cdir, "all.c")
    open(unity, "w").write("".join('#include "%s"\n' % f for f in sorted(resources) + ["main.c"]))
    r = subprocess.run(["gcc", "-O0", "-w", "-I", cdir, "-I", os.path.join(MATIEC, "lib", "C"), "-o", exe,
                        unity, "-lm"], capture_output=True, text=True, timeout=300)
    if r.returncode != 0:
        return {"status": "gcc", "message": r.stderr[-2000:]}
    r = subprocess.run([exe], capture_output=True, text=True, timeout=60)
    if r.returncode != 0:
        return {"status": "run", "message": "exit %d %s" % (r.returncode, r.stderr[-500:])}
    rows = [line[2:].split() for line in r.stdout.splitlines() if line.startswith("@@")]
    if len(rows) != req["scans"]:
        return {"status": "run", "message": "%d scans printed of %d" % (len(rows), req["scans"])}
    trace, column = [], 0
    for read in reads:
        if read is None:
            trace.append(None)
            continue
        values = [row[column] for row in rows]
        column += 1
        trace.append("".join(values) if read[0] == "bit" else [int(v) for v in values])
    return {"status": "ok", "trace": trace}


def main():
    work = os.path.abspath(sys.argv[1])
    jobs = sorted(f[:-len(".req.json")] for f in os.listdir(work) if f.endswith(".req.json"))
    # A job with a `K.xml` is a PLCopen project (Beremiz makes its ST); one with only a
    # `K.st` is Structured Text already, run by matiec as it is.
    projects = [k for k in jobs if os.path.exists(os.path.join(work, k + ".xml"))]
    feed = "".join("%s %s %s\n" % tuple(os.path.join(work, k + ext) for ext in (".xml", ".st", ".json"))
                   for k in projects)
    verdicts = {}
    if projects:
        gen = subprocess.run([PYTHON, os.path.join(HERE, "gen_st.py"), BEREMIZ], input=feed,
                             capture_output=True, text=True)
        answers = gen.stdout.splitlines()
        if len(answers) != len(projects):
            sys.exit("gen_st.py answered %d of %d jobs:\n%s" % (len(answers), len(projects), gen.stderr[-3000:]))
        verdicts = dict(zip(projects, answers))
    for k in jobs:
        if k not in verdicts:
            json.dump({}, open(os.path.join(work, k + ".json"), "w"))
            verdicts[k] = "ok"

    def one(item):
        k, verdict = item
        if verdict != "ok":
            out = {"status": "beremiz", "message": verdict}
        else:
            try:
                out = build_and_run(work, k)
            except subprocess.TimeoutExpired as e:
                out = {"status": "timeout", "message": str(e)}
        json.dump(out, open(os.path.join(work, k + ".out.json"), "w"))

    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        list(pool.map(one, ((k, verdicts[k]) for k in jobs)))


if __name__ == "__main__":
    main()
