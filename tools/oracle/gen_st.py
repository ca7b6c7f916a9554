"""Turns PLCopen projects into Structured Text with Beremiz's own generator (PLCGenerator.py).

Usage: gen_st.py BEREMIZ_DIR < jobs, one job per line: `IN.xml OUT.st OUT.json`.
For each job it writes the ST program Beremiz would hand to matiec, and a JSON map
of the edge detectors the generator made: instance name -> [POU, element kind,
localId, extra...] (from the generator's own debug annotations). One line per job
on stdout: `ok`, or `error: ...` (the generator refused or crashed).

Beremiz's editor stores at least one point on every wire; the generator reads the
last one, so a wire without points gets one at (-1, -1), which matches no pin.
"""
import builtins
import json
import os
import sys
import tempfile
import traceback

beremiz = os.path.abspath(sys.argv[1])
sys.path.insert(0, beremiz)
os.chdir(beremiz)
import fake_wx  # noqa: E402,F401  Beremiz's stand-in for wx, as its command line uses
builtins.__dict__.setdefault("_", lambda s: s)


def py2_order(x):
    """Python 2's order of the generator's mixed path lists (None first, then by type
    name: list < str < tuple)."""
    if x is None:
        return (-1,)
    if isinstance(x, list):
        return (0, [py2_order(e) for e in x])
    if isinstance(x, tuple):
        return (2, [py2_order(e) for e in x])
    return (1, x)


# FactorizePaths sorts lists of strings, lists and tuples, which Python 3 refuses; the
# generator was written for Python 2's order, which is restored here. The order only
# changes the order of the operands of an OR.
import types  # noqa: E402
source = open(os.path.join(beremiz, "PLCGenerator.py"), encoding="utf-8").read()
assert source.count("factorized_paths.sort()") == 1
# Since its Python 3 port the generator's position comparator returns `eq(x, y)`, which
# never says "less", so statements keep document order. ORACLE_ORDER=layout restores
# the Python 2 comparison (`cmp`), the order by position of earlier Beremiz and OpenPLC.
if os.environ.get("ORACLE_ORDER") == "layout":
    assert source.count("return eq(ax, bx)") == 1 and source.count("return eq(ay, by)") == 1
    source = source.replace("return eq(ax, bx)", "return (ax > bx) - (ax < bx)")
    source = source.replace("return eq(ay, by)", "return (ay > by) - (ay < by)")
generator = types.ModuleType("PLCGenerator")
generator.__file__ = os.path.join(beremiz, "PLCGenerator.py")
generator.py2_order = py2_order
sys.modules["PLCGenerator"] = generator
exec(compile(source.replace("factorized_paths.sort()", "factorized_paths.sort(key=py2_order)"),
             generator.__file__, "exec"), generator.__dict__)
import ProjectController  # noqa: E402,F401  imports the editor modules in Beremiz's order
from PLCControler import PLCControler  # noqa: E402
from lxml import etree  # noqa: E402

NS = "{http://www.plcopen.org/xml/tc6_0201}"


def with_wire_points(src):
    """The project as Beremiz's editor would have saved it: every pin with a relative
    position, every wire ending at the pin it comes from (the generator reads both)."""
    tree = etree.parse(src)
    pins = {}
    for obj in tree.iter():
        local = obj.get("localId")
        if local is None or not isinstance(obj.tag, str):
            continue
        pos = obj.find(NS + "position")
        ox, oy = (int(float(pos.get("x"))), int(float(pos.get("y")))) if pos is not None else (0, 0)
        outs = [v for v in obj.iter(NS + "connectionPointOut")]
        for i, point in enumerate(outs):
            rel = point.find(NS + "relPosition")
            if rel is None:
                rel = etree.Element(NS + "relPosition", x="1000", y=str(10 * i))
                point.insert(0, rel)
            owner = point.getparent()
            name = owner.get("formalParameter") if owner is not None else None
            at = (ox + int(float(rel.get("x"))), oy + int(float(rel.get("y"))))
            pins.setdefault(local, []).append((name, at))
        for point in obj.iter(NS + "connectionPointIn"):
            if point.find(NS + "relPosition") is None:
                point.insert(0, etree.Element(NS + "relPosition", x="0", y="0"))
    for conn in tree.iter(NS + "connection"):
        if conn.find(NS + "position") is None:
            outs = pins.get(conn.get("refLocalId"), [])
            wanted = conn.get("formalParameter")
            ends = [at for name, at in outs if wanted is None or name == wanted]
            x, y = ends[0] if len(ends) == 1 else (-1, -1)
            conn.insert(0, etree.Element(NS + "position", x=str(x), y=str(y)))
    out = tempfile.NamedTemporaryFile("wb", suffix=".xml", delete=False)
    tree.write(out, xml_declaration=True, encoding="utf-8")
    out.close()
    return out.name


def svghmi_types():
    """The ST of Beremiz's SVGHMI library (the `HMI_*` types), as Beremiz writes it ahead
    of a project's own (`POULibrary.GetSTCode`, `GetLibrariesSTCode`) when the SVGHMI
    extension is loaded."""
    lib = PLCControler()
    lib.OpenXMLFile(os.path.join(beremiz, "svghmi", "pous.xml"))
    text, errors, _warnings = lib.GenerateProgram(noconfig=True)
    assert not errors, errors
    return text + "\n"


def job(src, st, mapping):
    fixed = with_wire_points(src)
    try:
        c = PLCControler()
        err = c.OpenXMLFile(fixed)
        if c.Project is None:
            return "error: load: %s" % str(err).replace("\n", " ")
        text, errors, _warnings = c.GenerateProgram(st)
        if errors:
            return "error: " + " | ".join(str(e) for e in errors).replace("\n", " ")
        # A project that names the SVGHMI types builds with that library's ST first.
        if "HMI_" in text:
            with open(st, "w", encoding="utf-8") as f:
                f.write(svghmi_types() + text)
        trigs = {}
        for chunk, info in c.ProgramChunks:
            if (chunk.startswith("R_TRIG") or chunk.startswith("F_TRIG")) and info and info[-1] in ("rising", "falling"):
                trigs[chunk + "@" + str(info[0])] = [str(x) for x in info]
        with open(mapping, "w") as f:
            json.dump(trigs, f)
        return "ok"
    finally:
        os.unlink(fixed)


for line in sys.stdin:
    parts = line.split()
    if len(parts) != 3:
        continue
    try:
        result = job(*parts)
    except Exception as e:  # the generator crashed on this file
        traceback.print_exc()
        result = "error: crash: %s: %s" % (type(e).__name__, str(e).replace("\n", " "))
    print(result, flush=True)
