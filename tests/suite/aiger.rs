//! The AIGER export against the scan simulator (always) and against ABC's verdicts (when ABC is installed).
//!
//! The AIGER files are read here by a small reader and evaluator written from the
//! AIGER format description (ASCII `aag` and binary `aig`, version 1): literals `2v + s`,
//! latches starting at 0, and-gates, the symbol table. A run of the exported graph on
//! random inputs must agree, scan by scan, with the front end's own scan simulator: each
//! exported signal (`signal X` outputs) with the simulator's bit, and each property's
//! output with the property evaluated on the simulator's run by the test evaluator of
//! `common/scan_eval.rs` (written from `shared/spec/semantics.md`), gated by the
//! assumptions. With ABC on the PATH (`berkeley-abc` or `abc`), each property of the
//! water plant (correct and faulty) exported alone must get ABC `pdr`'s verdict equal to
//! ii-prove's: proved ↔ "Property proved", refuted ↔ a counterexample.
#![warn(missing_docs)]

use crate::common;
use crate::common::rng;
use crate::common::scan_eval;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use ii_prove::diag::Sources;
use ii_prove::kernel::Rel;
use ii_prove::ladder::{CompileOptions, HypothesisKind, SignalKind};
use ii_prove::report::{self, Options};
use rng::Rng;
use scan_eval::{Hyp, Known, Src, TimerStats};

/// An AIGER netlist as the format describes it.
#[derive(Debug, PartialEq, Eq)]
struct Net {
    max_var: u32,
    inputs: Vec<u32>,
    /// (literal, next-state literal).
    latches: Vec<(u32, u32)>,
    outputs: Vec<u32>,
    /// (lhs, rhs0, rhs1).
    ands: Vec<(u32, u32, u32)>,
    /// `i`, `l`, `o` symbols by position.
    symbols: BTreeMap<(char, usize), String>,
}

fn numbers(line: &str) -> Vec<u32> {
    line.split_whitespace().map(|w| w.parse().expect("a number")).collect()
}

/// Reads an ASCII (`aag`) or binary (`aig`) AIGER file.
fn read_aiger(bytes: &[u8]) -> Net {
    let mut pos = 0;
    let line = |pos: &mut usize| -> String {
        let end = bytes[*pos..].iter().position(|b| *b == b'\n').map_or(bytes.len(), |e| *pos + e);
        let text = String::from_utf8(bytes[*pos..end].to_vec()).expect("ASCII");
        *pos = (end + 1).min(bytes.len());
        text
    };
    let header = line(&mut pos);
    let mut words = header.split_whitespace();
    let kind = words.next().expect("a header");
    let h: Vec<u32> = words.map(|w| w.parse().expect("a number")).collect();
    assert_eq!(h.len(), 5, "header `{header}`: M I L O A");
    let (m, i, l, o, a) = (h[0], h[1], h[2], h[3], h[4]);
    assert_eq!(m, i + l + a, "M = I + L + A");
    let binary = match kind {
        "aag" => false,
        "aig" => true,
        other => panic!("not AIGER: {other}"),
    };
    let inputs: Vec<u32> =
        (0..i).map(|k| if binary { 2 * (k + 1) } else { numbers(&line(&mut pos))[0] }).collect();
    let latches: Vec<(u32, u32)> = (0..l)
        .map(|k| {
            let n = numbers(&line(&mut pos));
            if binary {
                assert_eq!(n.len(), 1);
                (2 * (i + k + 1), n[0])
            } else {
                assert_eq!(n.len(), 2, "a latch without a reset value");
                (n[0], n[1])
            }
        })
        .collect();
    let outputs: Vec<u32> = (0..o).map(|_| numbers(&line(&mut pos))[0]).collect();
    let mut ands = Vec::new();
    for k in 0..a {
        if binary {
            let mut delta = || {
                let (mut x, mut shift) = (0u32, 0);
                loop {
                    let b = bytes[pos];
                    pos += 1;
                    x |= u32::from(b & 0x7f) << shift;
                    if b & 0x80 == 0 {
                        return x;
                    }
                    shift += 7;
                }
            };
            let lhs = 2 * (i + l + k + 1);
            let r0 = lhs - delta();
            let r1 = r0 - delta();
            ands.push((lhs, r0, r1));
        } else {
            let n = numbers(&line(&mut pos));
            ands.push((n[0], n[1], n[2]));
        }
    }
    let mut symbols = BTreeMap::new();
    while pos < bytes.len() {
        let text = line(&mut pos);
        if text == "c" {
            break;
        }
        let (kind, rest) = text.split_at(1);
        let (index, name) = rest.split_once(' ').expect("`i0 name`");
        symbols.insert((kind.chars().next().unwrap(), index.parse().unwrap()), name.to_string());
    }
    Net { max_var: m, inputs, latches, outputs, ands, symbols }
}

impl Net {
    fn named(&self, kind: char, k: usize) -> &str {
        self.symbols.get(&(kind, k)).map_or("", String::as_str)
    }

    /// One step: input values → (output values), updating `state` (one bool a latch).
    fn step(&self, state: &mut [bool], inputs: &[bool]) -> Vec<bool> {
        let mut v = vec![false; self.max_var as usize + 1];
        let mut defined = vec![false; self.max_var as usize + 1];
        defined[0] = true;
        let set = |v: &mut Vec<bool>, d: &mut Vec<bool>, lit: u32, x: bool| {
            assert_eq!(lit & 1, 0, "a defined literal is even");
            assert!(!d[(lit / 2) as usize], "variable {} defined twice", lit / 2);
            v[(lit / 2) as usize] = x;
            d[(lit / 2) as usize] = true;
        };
        for (lit, x) in self.inputs.iter().zip(inputs) {
            set(&mut v, &mut defined, *lit, *x);
        }
        for ((lit, _), x) in self.latches.iter().zip(state.iter()) {
            set(&mut v, &mut defined, *lit, *x);
        }
        let get = |v: &Vec<bool>, d: &Vec<bool>, lit: u32| {
            assert!(d[(lit / 2) as usize], "literal {lit} read before it is defined");
            v[(lit / 2) as usize] ^ (lit & 1 == 1)
        };
        for (lhs, r0, r1) in &self.ands {
            let x = get(&v, &defined, *r0) && get(&v, &defined, *r1);
            set(&mut v, &mut defined, *lhs, x);
        }
        for (s, (_, next)) in state.iter_mut().zip(&self.latches) {
            *s = get(&v, &defined, *next);
        }
        self.outputs.iter().map(|o| get(&v, &defined, *o)).collect()
    }
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A temporary folder of this test binary.
fn temp_dir(label: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ii-aiger-{label}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The exported model of `program` with the properties of `props` (selected by `only`),
/// with one output per exported signal; ASCII and binary must describe the same net.
fn export(program: &Path, props: &Path, only: &[String]) -> Result<Net, String> {
    let opts = Options { only: only.to_vec(), ..Options::default() };
    let paths = [props.display().to_string()];
    let program = program.display().to_string();
    let ascii = report::aiger::export_aiger(&program, &paths, &opts, false, true)
        .map_err(|e| e.rendered)?;
    let binary =
        report::aiger::export_aiger(&program, &paths, &opts, true, true).map_err(|e| e.rendered)?;
    let net = read_aiger(&ascii.bytes);
    assert_eq!(net, read_aiger(&binary.bytes), "{program}: aag and aig differ");
    Ok(net)
}

/// What one comparison counted.
#[derive(Default, Debug)]
struct Compared {
    scans: u64,
    signal_checks: u64,
    property_checks: u64,
    violations: u64,
}

/// Runs the exported net and the program's simulator side by side on random inputs.
fn compare(program: &Path, props: &Path, only: &[String], runs: u64, scans: usize) -> Compared {
    let label = program.display().to_string();
    let net = export(program, props, only).unwrap_or_else(|e| panic!("{label}: {e}"));
    let mut sources = Sources::new();
    let loaded =
        report::load_program(&mut sources, &label, &CompileOptions::default()).expect("loads");
    let file = report::read_source(&mut sources, &props.display().to_string()).expect("reads");
    let doc = ii_prove::syntax::parse_properties(&sources, file, &loaded.compiled).expect("parses");
    // The comparison atoms the properties use, defined as the export defines them.
    let with_atoms = loaded.compiled.with_atoms();
    let compiled = &with_atoms;
    let loose = scan_eval::loose_names(compiled);
    let hyp = |name: &str, lhs, rel, rhs, known: &mut Known| {
        let h = ii_prove::ladder::Hypothesis {
            name: name.to_string(),
            rung: 0,
            span: doc
                .properties
                .first()
                .map(|s| s.span)
                .unwrap_or(ii_prove::diag::Span::new(file, 0..0)),
            kind: HypothesisKind::Equation,
            lhs,
            rel,
            rhs,
        };
        Hyp::new(&h, compiled, compiled.cycle_us, known, &loose)
    };
    let mut known = Known::default();
    let assumed: Vec<Hyp> = report::assumptions(&doc)
        .into_iter()
        .map(|a| hyp(&a.name, a.lhs, a.rel, a.rhs, &mut known))
        .collect();
    // Per output: the property it stands for, or the signal.
    enum Out {
        Property(Hyp),
        Signal(String),
    }
    let mut outs = Vec::new();
    for k in 0..net.outputs.len() {
        let name = net.named('o', k).to_string();
        if let Some(signal) = name.strip_prefix("signal ") {
            outs.push(Out::Signal(signal.to_string()));
            continue;
        }
        let s = doc.properties.iter().find(|s| s.name == name).expect("a property of the file");
        let goal = report::obligation(&s.value);
        outs.push(Out::Property(hyp(&name, goal.lhs, goal.rel, goal.rhs, &mut known)));
    }
    let inputs: Vec<String> =
        (0..net.inputs.len()).map(|k| net.named('i', k).to_string()).collect();
    let mut figures = Compared::default();
    let mut rng = Rng::new(0x5eed ^ label.len() as u64);
    for run in 0..runs {
        let mut sim = loaded.reference.simulator();
        let mut carry = scan_eval::Carry::new(&known);
        let mut state = vec![false; net.latches.len()];
        let mut hyp_states: Vec<Vec<u32>> = assumed
            .iter()
            .chain(outs.iter().filter_map(|o| match o {
                Out::Property(h) => Some(h),
                Out::Signal(_) => None,
            }))
            .map(|h| h.states.iter().next().expect("a start state").clone())
            .collect();
        let mut held = true;
        let mut values: Vec<bool> = vec![false; inputs.len()];
        let mut hold = vec![0usize; inputs.len()];
        let mut vals = Vec::new();
        let mut stats = TimerStats::default();
        for scan in 0..scans {
            for (k, v) in values.iter_mut().enumerate() {
                if hold[k] == 0 {
                    *v = rng.chance(50);
                    hold[k] = match rng.below(4) {
                        0 => 1,
                        1 => 1 + rng.below(8) as usize,
                        2 => 20 + rng.below(100) as usize,
                        _ => 200 + rng.below(700) as usize,
                    };
                }
                hold[k] -= 1;
            }
            let map: BTreeMap<String, bool> =
                inputs.iter().cloned().zip(values.iter().copied()).collect();
            sim.step(&map);
            let out = net.step(&mut state, &values);
            let mut now: Vec<bool> = known
                .iter()
                .map(|src| match src {
                    // A comparison atom: the comparison of the simulator's integers.
                    Src::Defined(n) => compiled.atom_value(n, &|x| sim.int(x)).unwrap_or(false),
                    _ => src.read(&|n| sim.bit(n), &|k| sim.edge_memory(k), &|n| sim.int(n)),
                })
                .collect();
            carry.fill(&mut now);
            let mut next_state = 0;
            for h in &assumed {
                let (l, r) = h.step(&mut hyp_states[next_state], &now, 0, &mut vals, &mut stats);
                held &= if h.rel == Rel::Eq { l == r } else { !l || r };
                next_state += 1;
            }
            for (k, o) in outs.iter().enumerate() {
                let want = match o {
                    Out::Property(h) => {
                        let (l, r) =
                            h.step(&mut hyp_states[next_state], &now, 0, &mut vals, &mut stats);
                        next_state += 1;
                        figures.property_checks += 1;
                        held && if h.rel == Rel::Eq { l != r } else { l && !r }
                    }
                    Out::Signal(name) => {
                        let value = match compiled.signals.get(name) {
                            Some(SignalKind::EdgeMemory { index, .. }) => sim.edge_memory(*index),
                            Some(SignalKind::IntBit { of, bit, start, .. }) => {
                                sim.int(of).map(|v| (v >> bit & 1 == 1) != *start)
                            }
                            // Named parts of a computation: their equations define them.
                            Some(SignalKind::Intermediate { .. } | SignalKind::Atom) => None,
                            _ => sim.is_known(name).then(|| sim.bit(name)),
                        };
                        let Some(value) = value else { continue };
                        figures.signal_checks += 1;
                        value
                    }
                };
                figures.violations += u64::from(want && matches!(o, Out::Property(_)));
                assert_eq!(
                    out[k],
                    want,
                    "{label}, run {run}, scan {scan}: output {k} `{}` is {} in the AIGER model, {} by the simulator",
                    net.named('o', k),
                    out[k],
                    want
                );
            }
            carry.keep(&now);
            figures.scans += 1;
        }
    }
    figures
}

/// A property file with one property `S => pre S` per output or relay `S` of the
/// program (so every equation is in the exported cone), and the properties whose cone
/// the export accepts (no unconstrained element).
fn generated_properties(program: &Path, dir: &Path) -> (PathBuf, Vec<String>) {
    let mut sources = Sources::new();
    let loaded = report::load_program(
        &mut sources,
        &program.display().to_string(),
        &CompileOptions::default(),
    )
    .expect("loads");
    let names: Vec<&String> = loaded
        .compiled
        .signals
        .iter()
        .filter(|(n, k)| {
            matches!(k, SignalKind::Output | SignalKind::Relay)
                && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        })
        .map(|(n, _)| n)
        .collect();
    let text: String = names
        .iter()
        .enumerate()
        .map(|(k, n)| format!("property gen{k}end: {n} => pre {n}\n"))
        .collect();
    let stem = program.file_stem().unwrap().to_string_lossy();
    let path = dir.join(format!("{stem}.ii"));
    std::fs::write(&path, text).unwrap();
    let accepted = (0..names.len())
        .map(|k| format!("gen{k}end"))
        .filter(|name| export(program, &path, std::slice::from_ref(name)).is_ok())
        .collect();
    (path, accepted)
}

/// The programs with property files of the test data: each program of
/// `tests/data/refutes_programs` with its `.ii` (assumptions among them), and the
/// vacuity cases (assumptions that force a constant or contradict the program).
fn data_cases() -> Vec<(String, String)> {
    let mut cases = Vec::new();
    for ld in common::files_with(&root().join("tests/data/refutes_programs"), "ld") {
        let ii = ld.with_extension("ii");
        if ii.exists() {
            let rel = |p: &Path| p.strip_prefix(root()).unwrap().display().to_string();
            cases.push((rel(&ld), rel(&ii)));
        }
    }
    for ii in ["forces_constant", "contradicts_program"] {
        cases.push((
            "tests/data/refutes_programs/traffic_greens_overlap.ld".into(),
            format!("tests/data/vacuity/{ii}.ii"),
        ));
    }
    cases
}

#[test]
fn data_case_models_run_as_the_simulator() {
    let mut assumed = 0;
    for (program, props) in data_cases() {
        let text = std::fs::read_to_string(root().join(&props)).unwrap();
        assumed += usize::from(text.lines().any(|l| l.starts_with("assume")));
        let f = compare(&root().join(&program), &root().join(&props), &[], 3, 1500);
        eprintln!("{program} {props}: {f:?}");
        assert!(f.property_checks > 0);
    }
    assert!(assumed >= 3, "only {assumed} cases with assumptions");
}

#[test]
fn the_water_plant_model_runs_as_the_simulator() {
    for program in ["examples/water.ld", "examples/water_faulty.ld"] {
        let f = compare(&root().join(program), &root().join("examples/water.ii"), &[], 8, 3000);
        eprintln!("{program}: {f:?}");
        assert!(f.signal_checks > 0 && f.property_checks > 0);
        if program.contains("faulty") {
            assert!(f.violations > 0, "the faulty plant's P2 fails on some random run");
        }
    }
}

#[test]
fn the_parts_counter_model_runs_as_the_simulator() {
    // Comparison atoms over the counter's bits: the model defines each one.
    for program in ["examples/parts.ld", "examples/parts_faulty.ld"] {
        let f = compare(&root().join(program), &root().join("examples/parts.ii"), &[], 8, 2000);
        eprintln!("{program}: {f:?}");
        assert!(f.signal_checks > 0 && f.property_checks > 0);
        // Random inputs rarely count ten parts before a box is removed: the faulty
        // program's violation is ABC's and the prover's to find (`abc_agrees_with_ii_prove`).
        assert!(program.contains("faulty") || f.violations == 0, "{program}: {f:?}");
    }
}

#[test]
fn examples_and_corpus_models_run_as_the_simulator() {
    let dir = temp_dir("corpus");
    let corpus = root().join("tests/data/ldmicro/corpus");
    let mut programs: Vec<PathBuf> = ["conveyor.ld", "traffic.ld", "press.ld", "early_timer.ld"]
        .iter()
        .map(|p| root().join("examples").join(p))
        .collect();
    for p in [
        "LDmicro__LDmicro/misc-ops.ld",
        "LDmicro__LDmicro/ctc_osr.ld",
        "LDmicro__LDmicro/test-pwm.ld",
        "LDmicro__LDmicro/traffic.ld",
        "pridolfi__example_ldmicro/ladder.ld",
    ] {
        let path = corpus.join(p);
        if path.exists() {
            programs.push(path);
        } else {
            eprintln!("skipped {}: not found", path.display());
        }
    }
    let mut exported = 0;
    for program in &programs {
        let (props, accepted) = generated_properties(program, &dir);
        if accepted.is_empty() {
            eprintln!("{}: every property reads an unconstrained element", program.display());
            continue;
        }
        let f = compare(program, &props, &accepted, 4, 1500);
        eprintln!("{} ({} properties): {f:?}", program.display(), accepted.len());
        assert!(f.signal_checks > 0);
        exported += 1;
    }
    assert!(exported >= 4, "only {exported} programs exported");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_command_line_writes_the_model_or_nothing() {
    let dir = temp_dir("cli");
    let out = dir.join("water.aag");
    let o = out.display().to_string();
    let run =
        common::ii_prove(&["export", "examples/water.ld", "examples/water.ii", "--aiger", &o]);
    assert!(run.status.success(), "{}", common::text(&run.stderr));
    let net = read_aiger(&std::fs::read(&out).unwrap());
    assert_eq!(net.outputs.len(), 12);
    assert_eq!(net.named('o', 2), "P2");
    // Two properties of one name (an ST `#ASSERT` and a property of water.ii): the
    // second output is renamed.
    let run =
        common::ii_prove(&["export", "examples/water.st", "examples/water.ii", "--aiger", "-"]);
    let st = read_aiger(&run.stdout);
    let names: Vec<&str> = (0..st.outputs.len()).map(|k| st.named('o', k)).collect();
    assert!(names.contains(&"backflow_needs_out_valve_2"), "{names:?}");
    // To standard output, the same model.
    let run =
        common::ii_prove(&["export", "examples/water.ld", "examples/water.ii", "--aiger", "-"]);
    assert_eq!(read_aiger(&run.stdout), net);
    // An unconstrained element in a property's cone (a comparison of a quotient, which
    // ii-prove does not compute): a located error, exit 2, no file.
    let bad = dir.join("quotient.ii");
    std::fs::write(&bad, "property p: Done => Done\n").unwrap();
    let refused = dir.join("refused.aig");
    let r = refused.display().to_string();
    let program = "tests/data/unknown_programs/quotient_never_done.ld";
    if root().join(program).exists() {
        let run = common::ii_prove(&["export", program, &bad.display().to_string(), "--aiger", &r]);
        let err = common::text(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{err}");
        assert!(err.contains("cannot export to AIGER") && err.contains(".ld:"), "{err}");
        assert!(!refused.exists() && !Path::new(&format!("{r}.tmp-ii-prove")).exists());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The ABC binary, if one is installed.
fn abc() -> Option<&'static str> {
    ["berkeley-abc", "abc"].into_iter().find(|b| {
        std::process::Command::new(b)
            .args(["-c", "quit"])
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// ABC's verdict on the single property of `aig` with `command` (`pdr`, `int`) within
/// `limit` seconds, and its wall time in ms: `proved`, `refuted`, `n/a` when the command
/// does not take a model without latches (`int`), or `timeout`. (`int` does not take a
/// model without inputs either: it stops on an assertion, so it is not asked.)
fn abc_verdict(abc: &str, aig: &Path, command: &str, limit: u64) -> (String, u128) {
    let start = Instant::now();
    let out_path = aig.with_extension(format!("{command}.out"));
    let mut child = std::process::Command::new(abc)
        .args(["-c", &format!("read {}; {command}", aig.display())])
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("ABC runs");
    loop {
        if child.try_wait().expect("ABC waits").is_some() {
            break;
        }
        if start.elapsed().as_secs() >= limit {
            let _ = child.kill();
            let _ = child.wait();
            return ("timeout".into(), start.elapsed().as_millis());
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let ms = start.elapsed().as_millis();
    let text = std::fs::read_to_string(&out_path).unwrap_or_default();
    let verdict = if text.contains("Property proved") || text.contains("UNSATISFIABLE") {
        "proved"
    } else if text.contains("was asserted in frame") {
        "refuted"
    } else if text.contains("Does not work for combinational networks") {
        "n/a"
    } else {
        panic!("ABC `{command}` on {}: no verdict:\n{text}", aig.display())
    };
    (verdict.to_string(), ms)
}

#[test]
fn abc_agrees_with_ii_prove() {
    let Some(abc) = abc() else {
        eprintln!("skipped: ABC (`berkeley-abc` or `abc`) is not installed");
        return;
    };
    let dir = temp_dir("abc");
    let mut table = String::new();
    let mut cases: Vec<(String, String)> = ["examples/water.ld", "examples/water_faulty.ld"]
        .iter()
        .map(|p| (p.to_string(), "examples/water.ii".to_string()))
        .collect();
    for p in ["examples/parts.ld", "examples/parts_faulty.ld"] {
        cases.push((p.to_string(), "examples/parts.ii".to_string()));
    }
    cases.extend(data_cases());
    let (mut agreed, mut refuted) = (0, 0);
    for (program, props) in &cases {
        let text = std::fs::read_to_string(root().join(props)).unwrap();
        let verdicts: Vec<(String, String)> = common::verdicts(&[program, props])
            .into_iter()
            .filter(|(name, _)| text.contains(&format!("property {name}:")))
            .collect();
        assert!(!verdicts.is_empty(), "{program} {props}: no verdict");
        for (name, verdict) in verdicts {
            let aig = dir.join(format!("{name}.aig"));
            let a = aig.display().to_string();
            let run = common::ii_prove(&["export", program, props, "--only", &name, "--aiger", &a]);
            assert!(run.status.success(), "{}", common::text(&run.stderr));
            let net = read_aiger(&std::fs::read(&aig).unwrap());
            if net.outputs.len() != 1 {
                eprintln!("{program} {name}: `--only {name}` selects more than one property");
                continue;
            }
            let (pdr, pdr_ms) = abc_verdict(abc, &aig, "pdr", 60);
            // ABC's `int` stops on an assertion for a model without primary inputs.
            let (int, int_ms) = match net.inputs.is_empty() {
                true => ("n/a".to_string(), 0),
                false => abc_verdict(abc, &aig, "int", 5),
            };
            table.push_str(&format!(
                "{program} {name}: ii-prove {verdict}, pdr {pdr} ({pdr_ms} ms), int {int} ({int_ms} ms)\n"
            ));
            assert!(
                int == pdr || int == "n/a" || int == "timeout",
                "{program} {name}: ABC pdr says {pdr}, int {int}"
            );
            if verdict != "unknown" {
                assert_eq!(pdr, verdict, "{program} {name}: ABC says {pdr}, ii-prove {verdict}");
                agreed += 1;
                refuted += usize::from(verdict == "refuted");
            }
        }
    }
    // The other front ends, whole files (the ST and IL programs' own `#ASSERT`s first,
    // one of them named as a property of water.ii): `pdr -a` counts per output.
    for program in [
        "examples/water.st",
        "examples/water_faulty.st",
        "examples/water_faulty.il",
        "examples/water_fbd.xml",
        "examples/water_ld_faulty.xml",
    ] {
        let verdicts = common::verdicts(&[program, "examples/water.ii"]);
        let count = |v: &str| verdicts.iter().filter(|(_, x)| x == v).count();
        let aig = dir.join("whole.aig");
        let a = aig.display().to_string();
        let run = common::ii_prove(&["export", program, "examples/water.ii", "--aiger", &a]);
        assert!(run.status.success(), "{}", common::text(&run.stderr));
        let out = std::process::Command::new(abc)
            .args(["-c", &format!("read {a}; pdr -a")])
            .output()
            .expect("ABC runs");
        let text = common::text(&out.stdout);
        let want = format!(
            "All = {}. Proved = {}. Disproved = {}.",
            verdicts.len(),
            count("proved"),
            count("refuted")
        );
        table.push_str(&format!("{program}: ii-prove and ABC pdr -a: {want}\n"));
        assert!(text.contains(&want), "{program}: ii-prove {want}, ABC:\n{text}");
    }
    eprint!("{table}");
    assert!(agreed >= 24 && refuted >= 10, "{agreed} verdicts compared, {refuted} refuted");
    let _ = std::fs::remove_dir_all(&dir);
}
