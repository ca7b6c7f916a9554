//! The PLCopen front end against the editors' own toolchain: every hypothesis the compiler derives must hold on runs of the C code that Beremiz's generator and matiec make from the same file.
//!
//! The reference shares no code or reading with the project: Beremiz's
//! `PLCGenerator.py` turns the LD/FBD project into Structured Text, matiec's `iec2c`
//! turns that into C, and `tools/oracle/run.py` compiles the C with a harness that
//! drives the declared inputs scan by scan, advances the runtime clock one cycle per
//! scan and prints the values the hypotheses read (variables, function block members,
//! the edge detectors Beremiz made, found through its own debug annotations). The
//! hypotheses are then evaluated on those values by `common/scan_eval.rs`.
//!
//! The toolchain must be built first (`tools/oracle/setup.sh DIR`, a few minutes), so
//! these tests are ignored by default:
//!
//! ```text
//! II_ORACLE=DIR cargo test --release --test suite plcopen_oracle:: -- --ignored --nocapture
//! ```
//!
//! `II_ORACLE_PROGRAMS=N` sets the number of random programs (1000 by default),
//! `II_ORACLE_FIRST=S` the first seed, `II_ORACLE_KEEP=DIR` keeps the generated files. A program a stage of the toolchain refuses is
//! counted by stage, not checked; a disagreement fails the test with the seed, the
//! XML and the compiled equations.

use crate::common;
use crate::common::plcopen_diff;
use crate::common::scan_eval;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use ii_prove::ladder::plcopen::{Edge, ObjKind, PlcProgram, Selection, StatementOrder, Ty};
use plcopen_diff::{Figures, Prepared, check_run, input_schedule, prepare, random_program};
use scan_eval::Src;
use serde_json::{Value, json};

const SCANS: usize = 160;

/// Where the value of one hypothesis input comes from in a toolchain run.
enum Want {
    /// A member of the program instance, by flat name (`TON0_Q`, `UF0_OUT0`).
    Member(String),
    /// The edge detector Beremiz made for an element: instance path, localId, field,
    /// and for a block the rank of the pin among its edge pins (document order).
    Edge(Vec<String>, u64, &'static str, usize),
    /// A pulse timer's `DONE` (timed out, `IN` still high): its `STATE` member, by flat
    /// name (`TP1_STATE`), is 2.
    Done(String),
    /// A value the run is given: an input's (a latch, a retained variable's start).
    Given(String),
    /// `STARTED`: 1 from the end of the first scan on.
    Started,
    /// A name the hypotheses define themselves (a timer's or edge detector's input held
    /// between the calls that run it, an intermediate value): read FALSE here, its
    /// equation sets it, as in the differential test.
    Defined(String),
}

/// The programs of `p`'s instance tree with their instance-name paths.
fn tree<'a>(p: &'a PlcProgram, path: Vec<String>, out: &mut Vec<(Vec<String>, &'a PlcProgram)>) {
    out.push((path.clone(), p));
    for (k, child) in &p.subs {
        if let Some(ObjKind::Block { instance: Some(inst), .. }) = p.obj(*k).map(|o| &o.kind) {
            let mut sub = path.clone();
            sub.push(inst.clone());
            tree(child, sub, out);
        }
    }
}

/// The program at a path of block indices, with the instance names along it.
fn at_path<'a>(p: &'a PlcProgram, path: &[usize]) -> Option<(Vec<String>, &'a PlcProgram)> {
    let mut names = Vec::new();
    let mut prog = p;
    for k in path {
        let Some(ObjKind::Block { instance: Some(inst), .. }) = prog.obj(*k).map(|o| &o.kind)
        else {
            return None;
        };
        names.push(inst.clone());
        prog = prog.subs.get(k)?;
    }
    Some((names, prog))
}

/// Whether `pin` of an element is an edge detector, and its rank among the element's.
fn edge_rank(kind: &ObjKind, pin: &str) -> Option<usize> {
    match kind {
        ObjKind::Contact { .. } | ObjKind::InVar { .. } | ObjKind::Coil { .. } => Some(0),
        ObjKind::Block { inputs, .. } => inputs
            .iter()
            .filter(|i| i.edge != Edge::None)
            .position(|i| i.name.eq_ignore_ascii_case(pin)),
        _ => None,
    }
}

/// Why a program is not compared: its hypotheses read integers, which this oracle's
/// reading of the toolchain's run does not cover yet (the PLCopen simulator checks them:
/// `tests/suite/plcopen_differential.rs`).
const READS_INTEGERS: &str = "the hypotheses read integers";

/// What to read from the toolchain's run for each value the hypotheses read.
fn wants(p: &Prepared) -> Result<Vec<Want>, String> {
    let plc = &p.plc;
    let mut programs = Vec::new();
    tree(plc, Vec::new(), &mut programs);
    let mut out = Vec::new();
    for src in &p.known {
        let want = match src {
            Src::Bit(n) if plc.started.as_deref() == Some(n) => Want::Started,
            Src::Bit(n) if plc.inputs.contains(n) => Want::Given(n.clone()),
            Src::Bit(n) => {
                // A hidden edge bit (`_TRIG7`) is the Q of the edge detector Beremiz made;
                // a pulse timer's hidden `DONE`, a state of the instance.
                let edge = programs.iter().find_map(|(path, prog)| {
                    prog.hidden.iter().find(|(_, h)| *h == n).and_then(|((k, pin), _)| {
                        let o = prog.obj(*k)?;
                        if let ObjKind::Block { type_name, instance: Some(inst), .. } = &o.kind
                            && type_name.eq_ignore_ascii_case("TP")
                            && pin == "DONE"
                        {
                            let mut flat = path.clone();
                            flat.extend([inst.clone(), "STATE".into()]);
                            return Some(Want::Done(flat.join("_")));
                        }
                        let rank = edge_rank(&o.kind, pin)?;
                        Some(Want::Edge(path.clone(), o.id, "Q", rank))
                    })
                });
                edge.unwrap_or_else(|| Want::Member(n.clone()))
            }
            Src::IntBit { .. } => return Err(READS_INTEGERS.into()),
            Src::Defined(n) | Src::PreDefined(n) => Want::Defined(n.clone()),
            Src::Edge(k) => {
                let (path, owner, pin) = &p.lowered.edges[p.edge_of[k]];
                let (names, prog) = at_path(plc, path).ok_or("an edge detector's path")?;
                let o = prog.obj(*owner).ok_or("an edge detector's element")?;
                match (&o.kind, pin.as_str()) {
                    // An edge detector's own memory, a pulse timer's `PREV_IN`, a
                    // counter's detector of an input (`CU_T.M`): members of the instance.
                    (ObjKind::Block { instance: Some(inst), .. }, pin)
                        if pin == "M" || pin == "TP_IN" || pin.ends_with("_T") =>
                    {
                        let mut flat = names.clone();
                        flat.push(inst.clone());
                        match pin {
                            "M" => flat.push("M".into()),
                            "TP_IN" => flat.push("PREV_IN".into()),
                            _ => flat.extend([pin.to_string(), "M".into()]),
                        }
                        Want::Member(flat.join("_"))
                    }
                    (kind, pin) => Want::Edge(names, o.id, "M", edge_rank(kind, pin).unwrap_or(0)),
                }
            }
        };
        out.push(want);
    }
    Ok(out)
}

/// Whether `name` is declared with a type other than BOOL somewhere in `p`'s tree (a
/// global is declared where it is used as external).
fn number(p: &PlcProgram, name: &str) -> bool {
    let mut programs = Vec::new();
    tree(p, Vec::new(), &mut programs);
    programs.iter().any(|(_, q)| {
        q.vars.get(&name.to_ascii_uppercase()).is_some_and(|v| !matches!(v.ty, Ty::Bool))
    })
}

/// The request `run.py` reads, and the wants in its order.
fn request(
    p: &Prepared,
    schedule: &[BTreeMap<String, bool>],
) -> Result<(Value, Vec<Want>), String> {
    let wants = wants(p)?;
    let plc = &p.plc;
    let bits = |name: &str| -> String {
        schedule
            .iter()
            .map(|s| if s.get(name).copied().unwrap_or(false) { '1' } else { '0' })
            .collect()
    };
    let mut inputs = serde_json::Map::new();
    for n in &plc.inputs {
        // A latched input is the variable the outside world writes; a start input is
        // not written each scan but once, as the retained variable's start value.
        if plc.starts.values().any(|s| s.as_deref() == Some(n)) {
            continue;
        }
        let var = plc.latches.iter().find(|(_, l)| *l == n).map_or(n.as_str(), |(x, _)| x);
        // A number the outside world writes stays at its initial value: the model reads
        // none as a bit (one it did read would be asked for, and fail to map, as a BOOL).
        let read = wants.iter().any(|w| matches!(w, Want::Given(g) if g == n));
        if !read && number(plc, var) {
            continue;
        }
        inputs.insert(var.to_string(), bits(n).into());
    }
    let mut starts = serde_json::Map::new();
    for (x, s) in &plc.starts {
        if let Some(s) = s {
            starts.insert(x.clone(), u8::from(schedule[0].get(s).copied().unwrap_or(false)).into());
        }
    }
    let want: Vec<Value> = wants
        .iter()
        .filter_map(|w| match w {
            Want::Member(n) => Some(json!({ "bit": n })),
            Want::Done(n) => Some(json!({ "int": n })),
            Want::Edge(path, id, field, rank) => Some(json!({ "edge": [path, id, field, rank] })),
            Want::Given(_) | Want::Started | Want::Defined(_) => None,
        })
        .collect();
    let req = json!({
        "pou": plc.pou.name,
        "cycle_ns": plc.cycle_us * 1000,
        "scans": SCANS,
        "inputs": inputs,
        "starts": starts,
        "want": want,
    });
    Ok((req, wants))
}

/// `II_ORACLE_ORDER=layout` checks the statement order by position against Beremiz's
/// generator with its Python 2 position comparator restored; by default, document
/// order against the generator as it is (since 2022 its comparator compares nothing).
pub(crate) fn layout() -> bool {
    std::env::var("II_ORACLE_ORDER").is_ok_and(|o| o == "layout")
}

pub(crate) fn selection() -> Selection {
    let order = if layout() { StatementOrder::Layout } else { StatementOrder::Document };
    Selection { order: Some(order), ..Selection::default() }
}

fn oracle_dir() -> PathBuf {
    let dir = std::env::var_os("II_ORACLE")
        .map(PathBuf::from)
        .expect("II_ORACLE=DIR, the toolchain built by tools/oracle/setup.sh DIR");
    assert!(dir.join("matiec/iec2c").is_file(), "{} has no matiec/iec2c", dir.display());
    dir
}

/// Figures of the toolchain's side.
#[derive(Default, Debug)]
struct Toolchain {
    /// Programs the toolchain refused or a name it did not have, by stage.
    refused: BTreeMap<String, u64>,
    /// One message per stage.
    examples: BTreeMap<String, String>,
    /// Programs not compared because their hypotheses read integers.
    integers: u64,
}

/// Runs every program through the toolchain and checks the hypotheses on its runs.
fn run(programs: Vec<(u64, String, bool)>, fig: &mut Figures, tc: &mut Toolchain) {
    let dir = oracle_dir();
    // `II_ORACLE_KEEP=DIR` keeps the generated ST, C and runs there.
    let temp = tempfile::tempdir().expect("temporary directory");
    let work = common::oracle_work_dir(temp.path());
    let mut jobs = Vec::new();
    for (seed, xml, must_load) in programs {
        let Some(p) = prepare(&xml, seed, fig, must_load, &selection()) else { continue };
        let schedule = input_schedule(&p.plc, seed, SCANS);
        let (req, wants) = match request(&p, &schedule) {
            Ok(x) => x,
            Err(e) if e == READS_INTEGERS => {
                tc.integers += 1;
                continue;
            }
            Err(e) => {
                fig.failures.push(format!("seed {seed}: no reading of {e}\n{xml}"));
                continue;
            }
        };
        let key = format!("{seed:06}");
        std::fs::write(work.as_path().join(format!("{key}.xml")), &xml).expect("write");
        std::fs::write(work.as_path().join(format!("{key}.req.json")), req.to_string())
            .expect("write");
        jobs.push((key, seed, xml, p, schedule, wants));
    }
    let python = |name: &str| dir.join(name);
    let status = std::process::Command::new(python("venv/bin/python"))
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/oracle/run.py"))
        .arg(work.as_path())
        .env("ORACLE_BEREMIZ", dir.join("beremiz"))
        .env("ORACLE_MATIEC", dir.join("matiec"))
        .env("ORACLE_PYTHON", python("venv/bin/python"))
        .env("ORACLE_ORDER", if layout() { "layout" } else { "document" })
        .status()
        .expect("run.py");
    assert!(status.success(), "run.py failed");
    for (key, seed, xml, mut p, schedule, wants) in jobs {
        let out = std::fs::read_to_string(work.as_path().join(format!("{key}.out.json")))
            .expect("run.py answers every job");
        let out: Value = serde_json::from_str(&out).expect("JSON");
        let stage = out["status"].as_str().unwrap_or("?").to_string();
        if stage != "ok" {
            *tc.refused.entry(stage.clone()).or_default() += 1;
            tc.examples.entry(stage).or_insert_with(|| {
                format!("seed {seed}: {}", out["message"].as_str().unwrap_or(""))
            });
            continue;
        }
        // A bit's trace as its characters; an integer's (a `STATE`) as one character per
        // scan, `1` where it is 2.
        let trace = |t: &Value| match t.as_array() {
            Some(v) => v.iter().map(|x| if x.as_i64() == Some(2) { b'1' } else { b'0' }).collect(),
            None => t.as_str().unwrap_or("").as_bytes().to_vec(),
        };
        let traces: Vec<Vec<u8>> =
            out["trace"].as_array().map(|a| a.iter().map(trace).collect()).unwrap_or_default();
        check_run(&mut p, seed, &xml, SCANS, fig, |scan| {
            let mut next = traces.iter();
            let mut values = Vec::with_capacity(wants.len());
            let mut shown = Vec::new();
            for w in &wants {
                let (name, v) = match w {
                    Want::Given(n) => (n.clone(), schedule[scan].get(n).copied().unwrap_or(false)),
                    Want::Started => ("STARTED".to_string(), true),
                    Want::Defined(n) => (n.clone(), false),
                    Want::Member(n) | Want::Done(n) => {
                        let t = next.next().ok_or("a missing trace")?;
                        (n.clone(), *t.get(scan).ok_or("a short trace")? == b'1')
                    }
                    Want::Edge(path, id, field, _) => {
                        let t = next.next().ok_or("a missing trace")?;
                        let name = format!("{}edge{id}.{field}", path.join("."));
                        (name, *t.get(scan).ok_or("a short trace")? == b'1')
                    }
                };
                shown.push(format!("{name}={}", u8::from(v)));
                values.push(v);
            }
            Ok((values, shown.join(" ")))
        });
    }
}

fn report(what: &str, fig: &Figures, tc: &Toolchain) {
    eprintln!(
        "oracle on {what}: {} programs loaded ({} refused by ii-prove, {} not compared: {READS_INTEGERS}), toolchain refusals {:?}, {} scans, {} hypotheses checked ({} skipped), {} timer hypotheses fired",
        fig.programs,
        fig.refused,
        tc.integers,
        tc.refused,
        fig.scans,
        fig.checked,
        fig.skipped,
        fig.timer_fired
    );
    for (stage, e) in &tc.examples {
        eprintln!("  first {stage} refusal: {}", e.chars().take(400).collect::<String>());
    }
}

#[test]
#[ignore = "needs the toolchain: tools/oracle/setup.sh DIR, then II_ORACLE=DIR … -- --ignored"]
fn random_programs_agree_with_the_toolchain() {
    let n: u64 =
        std::env::var("II_ORACLE_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(1000);
    let first: u64 =
        std::env::var("II_ORACLE_FIRST").ok().and_then(|v| v.parse().ok()).unwrap_or(0);
    let programs = (first..first + n).map(|s| (s, random_program(s), true)).collect();
    let (mut fig, mut tc) = (Figures::default(), Toolchain::default());
    run(programs, &mut fig, &mut tc);
    report("random programs", &fig, &tc);
    assert!(
        fig.failures.is_empty(),
        "{}",
        fig.failures.iter().take(3).cloned().collect::<Vec<_>>().join("\n\n")
    );
    let refused: u64 = tc.refused.values().sum();
    assert!(refused * 10 <= fig.programs, "the toolchain refused more than a tenth: {refused}");
}

#[test]
#[ignore = "needs the toolchain: tools/oracle/setup.sh DIR, then II_ORACLE=DIR … -- --ignored"]
fn examples_and_corpus_agree_with_the_toolchain() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = common::files_with(&root.join("examples"), "xml");
    files.extend(common::files_with(&root.join("tests/data/plcopen/corpus"), "xml"));
    if let Some(shared) = std::env::var_os("II_ORACLE_CORPUS") {
        files.extend(common::files_with(Path::new(&shared), "xml"));
    }
    // The same file in two folders is checked once.
    let mut seen = std::collections::BTreeSet::new();
    let programs = files
        .iter()
        .filter_map(|f| std::fs::read_to_string(f).ok())
        .filter(|t| seen.insert(t.clone()))
        .enumerate()
        .map(|(k, t)| (k as u64, t, false))
        .collect();
    let (mut fig, mut tc) = (Figures::default(), Toolchain::default());
    run(programs, &mut fig, &mut tc);
    report("files", &fig, &tc);
    assert!(
        fig.failures.is_empty(),
        "{}",
        fig.failures.iter().take(3).cloned().collect::<Vec<_>>().join("\n\n")
    );
}
