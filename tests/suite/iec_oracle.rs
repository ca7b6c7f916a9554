//! The IEC text front end against matiec, the editors' own compiler: random Structured Text (`common/st_gen.rs`), Instruction List (`common/il_gen.rs`) programs and sequential function charts (`common/sfc_gen.rs`, as text and as PLCopen `<SFC>` bodies, the latter turned into ST by Beremiz's generator) are compiled by `iec2c` and gcc and run scan by scan (`tools/oracle/run.py`); every BOOL variable and function-block output must have, at every scan, the value the scan-model simulator gives the lowered program — whose compiled equations `tests/suite/st.rs` and `tests/suite/il.rs` check against that simulator — and so must every integer the lowered program computes (`Program::integers`, `C1_CV`; a TIME in ns), its integer inputs driven with the same random values on both sides.
//!
//! Outside the test command (it needs the toolchain built by `tools/oracle/setup.sh DIR`):
//! `II_ORACLE=DIR cargo test --release --test suite iec_oracle:: -- --ignored`, with
//! `II_ST_PROGRAMS=N` / `II_IL_PROGRAMS=N` / `II_REAL_PROGRAMS=N` programs (500 by
//! default) from seed `II_ST_FIRST` / `II_IL_FIRST` / `II_REAL_FIRST` (0). The `REAL`
//! programs (`common/real_gen.rs`) compare every `REAL` variable as its bit pattern.

use crate::common;
use crate::common::il_gen;
use crate::common::real_gen;
use crate::common::rng;
use crate::common::sfc_gen;
use crate::common::st_gen;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use ii_prove::diag::Sources;
use ii_prove::ladder::TimerModel;
use ii_prove::program::{IntType, Program};
use serde_json::{Value, json};

const SCANS: usize = 120;

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// A random program to run.
struct Job {
    seed: u64,
    text: String,
    pou: String,
    inputs: Vec<String>,
    bits: Vec<String>,
    cycle_us: u64,
    /// Whether a bit may be unknown (read from a value ii-prove leaves unconstrained):
    /// not compared then. Otherwise it fails the job.
    partial: bool,
    /// Whether `text` is a PLCopen project (read by ii-prove's PLCopen front end, turned
    /// into ST by Beremiz's generator for matiec), else Structured Text.
    xml: bool,
}

/// What the scan-model simulator says of a job.
struct Expected {
    /// Per bit of the job, a string of `0`/`1` per scan.
    bits: Vec<String>,
    /// Per integer the lowered program computes, its value per scan (`None` where the
    /// simulator does not know it: derived from an unconstrained value).
    ints: Vec<(String, Vec<Option<i64>>)>,
    /// Per integer input of the lowered program, the value it was given per scan.
    int_inputs: Vec<(String, Vec<i64>)>,
    /// The `REAL`s among `ints`: two NaNs are the same value there (which NaN a sum or a
    /// product of two NaNs gives depends on the order the C compiler puts them in, and
    /// no IEC program can tell NaNs apart).
    reals: std::collections::BTreeSet<String>,
}

/// Whether the stored `REAL` `v` is a NaN.
fn is_nan(v: i64) -> bool {
    f32::from_bits(v as u32).is_nan()
}

/// Random values of an integer input for `scans` scans, each held for 1 to 12 scans:
/// small values mostly, and the type's ends (where wrapping and C's promotions show).
fn int_schedule(ty: IntType, seed: u64, scans: usize) -> Vec<i64> {
    let mut rng = rng::Rng::new(seed);
    let mut out = Vec::with_capacity(scans);
    while out.len() < scans {
        let v = match rng.below(10) {
            _ if ty.real => real_gen::real_value(&mut rng),
            0 => ty.min(),
            1 => ty.max(),
            2 => ty.wrap(rng.next() as i64),
            _ => ty.wrap(rng.below(41) as i64 - 20),
        };
        let hold = 1 + rng.below(12) as usize;
        out.extend(std::iter::repeat_n(v, hold.min(scans - out.len())));
    }
    out
}

/// The scan-model simulator's run of the job on these inputs (integer inputs drawn from
/// the seed).
fn ours(g: &Job, inputs: &[BTreeMap<String, bool>]) -> Result<Expected, String> {
    let mut sources = Sources::new();
    let lowered = if g.xml {
        use ii_prove::ladder::plcopen;
        let file = sources.add("random.xml", g.text.clone());
        let project = plcopen::read_plcopen(&sources, file).map_err(|e| format!("{e:?}"))?;
        // The statement order of the generator the oracle runs.
        let selection = crate::plcopen_oracle::selection();
        plcopen::st_program(&mut sources, &project, &selection)
            .ok_or("no text or chart body")?
            .map_err(|e| format!("{e:?}"))?
    } else {
        let file = sources.add("random.st", g.text.clone());
        let unit = ii_prove::iec::read(&sources, file).map_err(|e| format!("{e:?}"))?;
        ii_prove::iec::lower(&sources, &unit, None, None).map_err(|e| format!("{e:?}"))?
    };
    let integers = &lowered.program.integers;
    let int_inputs: Vec<(String, Vec<i64>)> = integers
        .iter()
        .enumerate()
        // A free value standing for what C leaves undefined has no member to drive.
        .filter(|(_, (n, v))| v.input && !lowered.program.undefined.contains(*n))
        .map(|(k, (n, v))| {
            (n.clone(), int_schedule(v.ty, g.seed ^ (0x1A7 + k as u64), inputs.len()))
        })
        .collect();
    let computed: Vec<&String> =
        integers.iter().filter(|(_, v)| !v.input).map(|(n, _)| n).collect();
    let mut sim = ii_prove::program::simulate::Simulator::new(&lowered.program, TimerModel::Plc);
    // Where C leaves a value undefined (a signed overflow), gcc's build may compute
    // anything: what it decides is not compared.
    sim.leave_undefined_unknown();
    let mut bits = vec![String::new(); g.bits.len()];
    let mut ints: Vec<(String, Vec<Option<i64>>)> =
        computed.iter().map(|n| ((*n).clone(), Vec::new())).collect();
    for (scan, step) in inputs.iter().enumerate() {
        // An integer input is driven as the outside world drives it: through its bits.
        let mut step = step.clone();
        for (n, values) in &int_inputs {
            for k in 0..integers[n].ty.bits {
                step.insert(Program::int_bit(n, k), values[scan] >> k & 1 == 1);
            }
        }
        sim.step(&step);
        for (k, b) in g.bits.iter().enumerate() {
            bits[k].push(match sim.is_known(b) {
                true if sim.bit(b) => '1',
                true => '0',
                // Unknown only where a value C leaves undefined decides it (or in a
                // partial job).
                false if g.partial || !lowered.program.undefined.is_empty() => '?',
                false => return Err(format!("{b} is unknown")),
            });
        }
        for (n, values) in &mut ints {
            values.push(if sim.is_known(n) { sim.int(n) } else { None });
        }
    }
    let reals = integers.iter().filter(|(_, v)| v.ty.real).map(|(n, _)| n.clone()).collect();
    Ok(Expected { bits, ints, int_inputs, reals })
}

#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn random_st_programs_run_as_matiec_runs_them() {
    let (first, n) = (env_u64("II_ST_FIRST", 0), env_u64("II_ST_PROGRAMS", 500));
    let jobs = (first..first + n).map(|seed| {
        let g = st_gen::program_with(seed, false);
        let (text, pou, inputs, bits, cycle_us) = (g.text, g.pou, g.inputs, g.bits, g.cycle_us);
        Job { seed, text, pou, inputs, bits, cycle_us, partial: false, xml: false }
    });
    against_matiec("ST", jobs.collect());
}

#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn random_real_programs_run_as_matiec_runs_them() {
    let (first, n) = (env_u64("II_REAL_FIRST", 0), env_u64("II_REAL_PROGRAMS", 500));
    let jobs = (first..first + n).map(|seed| {
        let g = real_gen::program(seed);
        let (text, pou, inputs, bits, cycle_us) = (g.text, g.pou, g.inputs, g.bits, g.cycle_us);
        Job { seed, text, pou, inputs, bits, cycle_us, partial: true, xml: false }
    });
    against_matiec("REAL", jobs.collect());
}

#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn random_sfc_charts_run_as_matiec_runs_them() {
    let (first, n) = (env_u64("II_SFC_FIRST", 0), env_u64("II_SFC_PROGRAMS", 500));
    let jobs = (first..first + n).map(|seed| {
        let g = sfc_gen::program(seed);
        let (text, pou, inputs, bits, cycle_us) = (g.text, g.pou, g.inputs, g.bits, g.cycle_us);
        Job { seed, text, pou, inputs, bits, cycle_us, partial: false, xml: false }
    });
    against_matiec("SFC", jobs.collect());
}

/// The same charts as PLCopen `<SFC>` bodies: ii-prove's reading of the XML against
/// Beremiz's generator's (the ST it writes, run by matiec).
#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn random_plcopen_charts_run_as_the_toolchain_runs_them() {
    let (first, n) = (env_u64("II_SFC_FIRST", 0), env_u64("II_SFC_PROGRAMS", 500));
    let jobs = (first..first + n).map(|seed| {
        let g = sfc_gen::project(seed);
        let (text, pou, inputs, bits, cycle_us) = (g.text, g.pou, g.inputs, g.bits, g.cycle_us);
        Job { seed, text, pou, inputs, bits, cycle_us, partial: false, xml: true }
    });
    against_matiec("PLCopen SFC", jobs.collect());
}

#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn random_il_programs_run_as_matiec_runs_them() {
    let (first, n) = (env_u64("II_IL_FIRST", 0), env_u64("II_IL_PROGRAMS", 500));
    let jobs = (first..first + n).map(|seed| {
        let g = il_gen::program_with(seed, true);
        let pou = "Random".to_string();
        let (text, inputs, bits, cycle_us) = (g.text, g.inputs, g.bits, g.cycle_us);
        Job { seed, text, pou, inputs, bits, cycle_us, partial: false, xml: false }
    });
    against_matiec("IL", jobs.collect());
}

/// Runs every job through matiec and compares its bits with the scan-model simulator's.
fn against_matiec(language: &str, programs: Vec<Job>) {
    let n = programs.len();
    let dir = PathBuf::from(std::env::var_os("II_ORACLE").expect("II_ORACLE=DIR"));
    assert!(dir.join("matiec/iec2c").is_file(), "{} has no matiec/iec2c", dir.display());
    let temp = tempfile::tempdir().expect("temporary directory");
    let work = common::oracle_work_dir(temp.path());
    let mut jobs = Vec::new();
    let mut failures = Vec::new();
    for g in programs {
        let seed = g.seed;
        let inputs = st_gen::schedule_of(&g.inputs, seed, SCANS);
        let expected = match ours(&g, &inputs) {
            Ok(x) => x,
            Err(e) => {
                failures.push(format!("seed {seed}: {e}\n{}", g.text));
                continue;
            }
        };
        let key = format!("{seed:06}");
        let trace =
            |n: &str| inputs.iter().map(|s| if s[n] { '1' } else { '0' }).collect::<String>();
        let mut drive: serde_json::Map<_, _> =
            g.inputs.iter().map(|n| (n.clone(), Value::from(trace(n)))).collect();
        for (n, values) in &expected.int_inputs {
            drive.insert(n.clone(), Value::from(values.clone()));
        }
        // Integers are optional: one the lowering made up (a function's local, a hidden
        // count) has no member in matiec's program; they are counted, not compared.
        let want: Vec<Value> = g
            .bits
            .iter()
            .map(|b| json!({"bit": b}))
            .chain(expected.ints.iter().map(|(n, _)| json!({"int": n, "optional": true})))
            .collect();
        let req = json!({
            "pou": g.pou,
            "cycle_ns": g.cycle_us * 1000,
            "scans": SCANS,
            "inputs": drive,
            "want": want,
        });
        let ext = if g.xml { "xml" } else { "st" };
        std::fs::write(work.join(format!("{key}.{ext}")), &g.text).expect("write");
        std::fs::write(work.join(format!("{key}.req.json")), req.to_string()).expect("write");
        jobs.push((key, seed, g, expected));
    }
    let status = std::process::Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/oracle/run.py"))
        .arg(&work)
        .env("ORACLE_MATIEC", dir.join("matiec"))
        // A PLCopen project goes through Beremiz's generator first.
        .env("ORACLE_BEREMIZ", dir.join("beremiz"))
        .env("ORACLE_PYTHON", dir.join("venv/bin/python"))
        .env("ORACLE_ORDER", if crate::plcopen_oracle::layout() { "layout" } else { "document" })
        .status()
        .expect("run.py");
    assert!(status.success(), "run.py failed");
    let (mut compared, mut refused, mut bit_scans) = (0u64, BTreeMap::<String, u64>::new(), 0u64);
    // Bit-scans not compared: unknown to ii-prove (a partial job's).
    let mut unknown_scans = 0u64;
    // Integer-scans compared, and the integers matiec's program has no member for.
    let (mut int_scans, mut absent) = (0u64, BTreeMap::<String, u64>::new());
    let (mut flow, mut ranged) = (0u64, 0u64);
    for (key, seed, g, expected) in jobs {
        let out = std::fs::read_to_string(work.join(format!("{key}.out.json"))).expect("an answer");
        let out: Value = serde_json::from_str(&out).expect("JSON");
        let stage = out["status"].as_str().unwrap_or("?");
        if stage != "ok" {
            *refused.entry(stage.to_string()).or_default() += 1;
            if refused[stage] == 1 {
                eprintln!("seed {seed}: {stage}: {}", out["message"].as_str().unwrap_or(""));
            }
            continue;
        }
        compared += 1;
        // Programs with a jump or a loop counted before the scan.
        let words = ["EXIT;", "CONTINUE;", "RETURN;", "WHILE ", "REPEAT\n", "RET", "JMP"];
        flow += u64::from(words.iter().any(|w| g.text.contains(w)));
        ranged += u64::from(g.text.contains("END_TYPE"));
        let traces: &[Value] = out["trace"].as_array().map_or(&[], Vec::as_slice);
        let mut differs = None;
        for (k, bit) in g.bits.iter().enumerate() {
            let theirs = traces.get(k).and_then(Value::as_str).unwrap_or("");
            bit_scans += expected.bits[k].chars().filter(|c| *c != '?').count() as u64;
            unknown_scans += expected.bits[k].chars().filter(|c| *c == '?').count() as u64;
            let differ = |(a, b): (char, char)| a != b && b != '?';
            let lengths = theirs.len() != expected.bits[k].len();
            if lengths || theirs.chars().zip(expected.bits[k].chars()).any(differ) {
                let at = theirs.chars().zip(expected.bits[k].chars()).position(differ).unwrap_or(0);
                differs = Some(format!(
                    "{bit} differs from scan {at}:\n  matiec {theirs}\n  ours   {}",
                    expected.bits[k]
                ));
                break;
            }
        }
        for (k, (name, ours)) in expected.ints.iter().enumerate() {
            if differs.is_some() {
                break;
            }
            let Some(theirs) = traces.get(g.bits.len() + k).and_then(Value::as_array) else {
                *absent.entry(name.clone()).or_default() += 1;
                continue;
            };
            let theirs: Vec<Option<i64>> = theirs.iter().map(Value::as_i64).collect();
            for (scan, (a, b)) in theirs.iter().zip(ours).enumerate() {
                let Some(b) = b else { continue };
                int_scans += 1;
                let both_nan = expected.reals.contains(name) && is_nan(*b) && a.is_some_and(is_nan);
                if *a != Some(*b) && !both_nan {
                    let show = |v: &[Option<i64>]| {
                        let v = &v[scan.saturating_sub(3)..(scan + 3).min(v.len())];
                        v.iter()
                            .map(|x| x.map_or("?".into(), |x| x.to_string()))
                            .collect::<Vec<_>>()
                            .join(" ")
                    };
                    differs = Some(format!(
                        "{name} differs at scan {scan} (scans {}..):\n  matiec {}\n  ours   {}",
                        scan.saturating_sub(3),
                        show(&theirs),
                        show(ours)
                    ));
                    break;
                }
            }
        }
        if let Some(d) = differs {
            let given: Vec<String> =
                expected.int_inputs.iter().map(|(n, v)| format!("  {n} = {v:?}")).collect();
            failures.push(format!("seed {seed}: {d}\n{}\n{}", given.join("\n"), g.text));
        }
    }
    eprintln!(
        "random {language} programs against matiec: {n} generated, {compared} run by the toolchain ({refused:?} refused; {flow} with EXIT, CONTINUE, RETURN, WHILE, REPEAT or a jump; {ranged} with a subrange type), {bit_scans} bit-scans ({unknown_scans} more unknown to ii-prove) and {int_scans} integer-scans compared; {} disagreements",
        failures.len()
    );
    if !absent.is_empty() {
        let some: Vec<_> = absent.iter().take(8).collect();
        eprintln!(
            "integers of the lowered programs with no member in matiec's ({} names, e.g. {some:?}): not compared",
            absent.len()
        );
    }
    assert!(
        failures.is_empty(),
        "{}",
        failures.iter().take(3).cloned().collect::<Vec<_>>().join("\n\n")
    );
    assert!(compared > 0, "the toolchain ran no program");
}

/// Runs one request through `run.py` in a fresh work directory: its answer.
fn run_one(dir: &Path, name: &str, text: &str, req: &Value) -> Value {
    let work = tempfile::tempdir().expect("temporary directory");
    std::fs::write(work.path().join(format!("{name}.st")), text).expect("write");
    std::fs::write(work.path().join(format!("{name}.req.json")), req.to_string()).expect("write");
    let status = std::process::Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/oracle/run.py"))
        .arg(work.path())
        .env("ORACLE_MATIEC", dir.join("matiec"))
        .status()
        .expect("run.py");
    assert!(status.success(), "run.py failed");
    let answer = std::fs::read_to_string(work.path().join(format!("{name}.out.json")));
    serde_json::from_str(&answer.expect("an answer")).expect("JSON")
}

/// The oracle reads integers: counters' `CV`, a TON's `ET` in ns, integer variables of
/// every width, with integer inputs driven per scan — checked against values worked out
/// here from matiec's library (`lib/counter.txt`, `lib/timer.txt`) and C's arithmetic
/// as matiec generates it: `+`, `/`, comparisons in C `int` after promotion (so
/// `(A + B) / 2` of two INTs does not wrap at 16 bits, nor does `W1 - W2 > 0` of two
/// UINTs), wrapping only where the result is stored; `MOD` by 0 is 0.
#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn integers_are_read_from_matiec_runs() {
    let dir = PathBuf::from(std::env::var_os("II_ORACLE").expect("II_ORACLE=DIR"));
    let text = "PROGRAM Main
  VAR_INPUT
    Up : BOOL; Rst : BOOL;
    A : INT; B : INT; W1 : UINT; W2 : UINT; S : SINT;
  END_VAR
  VAR
    C1 : CTU; D1 : CTD; T1 : TON;
    N : INT := 5; Half : INT; Big : BOOL; R : INT; UGt : BOOL;
    SS : SINT; SGt : BOOL; Byt : BYTE; U : UDINT; M : DINT;
  END_VAR
  C1(CU := Up, R := Rst, PV := 3);
  D1(CD := Up, LD := Rst, PV := 2);
  T1(IN := Up, PT := T#50ms);
  N := N + A;
  Half := (A + B) / 2;
  Big := A + B > 100;
  R := A MOD B;
  UGt := W1 - W2 > 0;
  SS := S + S;
  SGt := S + S > 100;
  Byt := INT_TO_BYTE(A);
  U := UINT_TO_UDINT(W1) - 1;
  M := INT_TO_DINT(A) * 1000;
END_PROGRAM
CONFIGURATION Cfg
  RESOURCE Res ON PLC
    TASK Tk(INTERVAL := T#20ms, PRIORITY := 0);
    PROGRAM Inst WITH Tk : Main;
  END_RESOURCE
END_CONFIGURATION
";
    let scans = 40;
    let mut rng = rng::Rng::new(7);
    let mut held = |lo: i64, hi: i64, edges: &[i64]| -> Vec<i64> {
        let mut v = Vec::new();
        while v.len() < scans {
            let x = if rng.chance(30) {
                *rng.pick(edges)
            } else {
                lo + rng.below((hi - lo + 1) as u64) as i64
            };
            v.extend(std::iter::repeat_n(x, 1 + rng.below(4) as usize));
        }
        v.truncate(scans);
        v
    };
    let up = held(0, 1, &[1]);
    let rst: Vec<i64> = (0..scans).map(|k| i64::from(k % 17 == 16)).collect();
    let a = held(-300, 300, &[i16::MIN.into(), i16::MAX.into(), 20_000, -7]);
    let b = held(-5, 5, &[0, 20_000, 2, -2]);
    let w1 = held(0, 6, &[0, 65_535]);
    let w2 = held(0, 6, &[0, 1]);
    let s = held(-100, 100, &[i8::MIN.into(), i8::MAX.into(), 100, 60]);
    let bits = |v: &[i64]| v.iter().map(|x| if *x == 1 { '1' } else { '0' }).collect::<String>();
    let ints = ["C1_CV", "D1_CV", "T1_ET", "N", "Half", "R", "SS", "Byt", "U", "M"];
    let flags = ["C1_Q", "D1_Q", "T1_Q", "Big", "UGt", "SGt"];
    let req = json!({
        "pou": "Main",
        "cycle_ns": 20_000_000u64,
        "scans": scans,
        "inputs": {"Up": bits(&up), "Rst": bits(&rst), "A": a, "B": b, "W1": w1, "W2": w2, "S": s},
        "want": flags.iter().map(|n| json!({"bit": n}))
            .chain(ints.iter().map(|n| json!({"int": n})))
            .chain([json!({"int": "Nowhere", "optional": true})])
            .collect::<Vec<_>>(),
    });
    let answer = run_one(&dir, "ints", text, &req);
    assert_eq!(answer["status"], "ok", "{answer}");
    let trace = answer["trace"].as_array().expect("traces");
    assert_eq!(trace.len(), flags.len() + ints.len() + 1);
    assert!(trace[flags.len() + ints.len()].is_null(), "{answer}");
    // The reference, scan by scan.
    let mut want_bits: Vec<String> = vec![String::new(); flags.len()];
    let mut want_ints: Vec<Vec<i64>> = vec![Vec::new(); ints.len()];
    let (mut c1, mut d1, mut n) = (0i64, 0i64, 5i64);
    let (mut last_up, mut t_state, mut t_start, mut t_et, mut t_q) = (false, 0, 0i64, 0i64, false);
    for k in 0..scans {
        let now = k as i64 * 20_000_000;
        let (u, r) = (up[k] == 1, rst[k] == 1);
        let rising = u && !last_up;
        last_up = u;
        if r {
            c1 = 0;
        } else if rising && c1 < 3 {
            c1 += 1;
        }
        if r {
            d1 = 2;
        } else if rising && d1 > 0 {
            d1 -= 1;
        }
        // TON (lib/timer.txt): PREV_IN is the last scan's IN, as `last_up` was.
        if t_state == 0 && rising {
            (t_state, t_q, t_start) = (1, false, now);
        } else if !u {
            (t_et, t_q, t_state) = (0, false, 0);
        } else if t_state == 1 {
            if t_start + 50_000_000 <= now {
                (t_state, t_q, t_et) = (2, true, 50_000_000);
            } else {
                t_et = now - t_start;
            }
        }
        n = i64::from((n + a[k]) as i16);
        let half = i64::from(((a[k] + b[k]) / 2) as i16);
        let rem = if b[k] == 0 { 0 } else { a[k] % b[k] };
        let ss = i64::from((2 * s[k]) as i8);
        let byt = i64::from(a[k] as u8);
        let ud = i64::from((w1[k] as u32).wrapping_sub(1));
        let m = i64::from((a[k] as i32).wrapping_mul(1000));
        let flag = [c1 >= 3, d1 <= 0, t_q, a[k] + b[k] > 100, w1[k] - w2[k] > 0, 2 * s[k] > 100];
        for (j, f) in flag.iter().enumerate() {
            want_bits[j].push(if *f { '1' } else { '0' });
        }
        for (j, v) in [c1, d1, t_et, n, half, rem, ss, byt, ud, m].into_iter().enumerate() {
            want_ints[j].push(v);
        }
    }
    for (j, name) in flags.iter().enumerate() {
        assert_eq!(trace[j].as_str(), Some(want_bits[j].as_str()), "{name}");
    }
    for (j, name) in ints.iter().enumerate() {
        let got: Vec<i64> = trace[flags.len() + j]
            .as_array()
            .expect("an integer trace")
            .iter()
            .filter_map(Value::as_i64)
            .collect();
        assert_eq!(got, want_ints[j], "{name}");
    }
    eprintln!(
        "{} integers and {} bits over {scans} scans read from matiec as worked out",
        ints.len(),
        flags.len()
    );
}

/// The value of a counterexample signal (`--json`) at `t`, in seconds.
fn sample(signal: &Value, t: f64) -> Option<bool> {
    let bps: Vec<f64> = signal["breakpoints"]
        .as_array()?
        .iter()
        .filter_map(|b| b.as_str().and_then(|s| s.parse().ok()))
        .collect();
    let at = |key: &str, k: usize| {
        signal[key].as_array().and_then(|a| a.get(k)).and_then(Value::as_bool)
    };
    for (k, bp) in bps.iter().enumerate() {
        if (bp - t).abs() < 1e-9 {
            return at("points", k);
        }
        if t < *bp {
            return at("intervals", k);
        }
    }
    None
}

/// The faulty water plants' counterexamples, replayed on the program as matiec builds
/// it: at every scan up to the violation, every program bit the counterexample shows has
/// the value matiec's run gives it.
#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn counterexamples_of_the_faulty_text_plants_replay_on_matiec() {
    let dir = PathBuf::from(std::env::var_os("II_ORACLE").expect("II_ORACLE=DIR"));
    let inputs = ["L_flow", "H_flow", "Line_swap", "L1_fail", "L2_fail", "SP_fail"];
    for program in ["examples/water_faulty.st", "examples/water_faulty.il"] {
        let out = common::ii_prove(&[program, "examples/water.ii", "--only", "P2", "--json"]);
        let report: Value = serde_json::from_str(&common::text(&out.stdout)).expect("JSON");
        let cex = &report["properties"][0]["counterexample"];
        let signals = cex["signals"].as_array().expect("a counterexample");
        let violated: f64 = cex["time"].as_str().and_then(|t| t.parse().ok()).expect("its time");
        let cycle = 0.01;
        let scans = (violated / cycle).round() as usize + 1;
        let named = |n: &str| signals.iter().find(|s| s["name"] == n);
        let trace = |s: &Value| -> String {
            (0..scans)
                .map(|k| if sample(s, k as f64 * cycle).unwrap_or(false) { '1' } else { '0' })
                .collect()
        };
        let mut drive = serde_json::Map::new();
        for i in inputs {
            let t = named(i).map_or("0".repeat(scans), trace);
            drive.insert(i.to_string(), Value::from(t));
        }
        let shown: Vec<&Value> = signals
            .iter()
            .filter(|s| {
                let n = s["name"].as_str().unwrap_or("");
                !inputs.contains(&n) && !n.starts_with("lhs") && !n.starts_with("rhs")
            })
            .collect();
        let req = json!({
            "pou": "Water",
            "cycle_ns": 10_000_000u64,
            "scans": scans,
            "inputs": drive,
            "want": shown.iter().map(|s| json!({"bit": s["name"]})).collect::<Vec<_>>(),
        });
        let text = std::fs::read_to_string(program).expect("read");
        let answer = run_one(&dir, "water", &text, &req);
        assert_eq!(answer["status"], "ok", "{program}: {answer}");
        let traces = answer["trace"].as_array().expect("traces");
        for (s, theirs) in shown.iter().zip(traces) {
            assert_eq!(theirs.as_str(), Some(trace(s).as_str()), "{program}: {}", s["name"]);
        }
        eprintln!(
            "{program}: the counterexample's {} program bits over {scans} scans are matiec's",
            shown.len()
        );
    }
}

/// `STRING_TO_BOOL` and `STRING_TO_<integer>` of random string literals (signs, digits,
/// `2#`/`8#`/`16#` bodies, separators, letters, `$` escapes): the value matiec's run
/// gives each, compared with the lowered program's (the literal read by
/// `iec::literal`). A literal the lowering leaves not computed (C's overflow) is counted,
/// not compared.
#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn string_literals_convert_as_matiec_converts_them() {
    let dir = PathBuf::from(std::env::var_os("II_ORACLE").expect("II_ORACLE=DIR"));
    let rounds = env_u64("II_STRING_ROUNDS", 4);
    let types = ["BOOL", "SINT", "INT", "DINT", "USINT", "UINT", "UDINT", "BYTE", "WORD", "DWORD"];
    let (mut compared, mut skipped) = (0, 0);
    for round in 0..rounds {
        let mut rng = rng::Rng::new(0x5781 + round);
        let pieces = [
            "0", "1", "7", "9", "12", "-", "+", ".", "_", " ", ",", "a", "F", "g", "x", "2#", "8#",
            "16#", "$$", "$'", "$N", "$T", "$41", "TRUE", "true", "e", "99999", "65535",
        ];
        let (mut decls, mut body, mut want) = (String::new(), String::new(), Vec::new());
        for k in 0..60 {
            let mut s = String::new();
            if rng.chance(40) {
                s.push_str(rng.pick::<&str>(&["2#", "8#", "16#", "-", ""]));
            }
            for _ in 0..rng.below(9) {
                s.push_str(rng.pick::<&str>(&pieces));
            }
            let ty = *rng.pick(&types);
            decls.push_str(&format!("    V{k} : {ty};\n"));
            body.push_str(&format!("  V{k} := STRING_TO_{ty}('{s}');\n"));
            want.push((format!("V{k}"), ty == "BOOL", s));
        }
        let text = format!(
            "PROGRAM Main\n  VAR\n{decls}  END_VAR\n{body}END_PROGRAM\nCONFIGURATION Cfg\n  \
             RESOURCE Res ON PLC\n    TASK Tk(INTERVAL := T#20ms, PRIORITY := 0);\n    \
             PROGRAM Inst WITH Tk : Main;\n  END_RESOURCE\nEND_CONFIGURATION\n"
        );
        let mut sources = Sources::new();
        let file = sources.add("strings.st", text.clone());
        let unit = ii_prove::iec::read(&sources, file).expect("reads");
        let lowered = ii_prove::iec::lower(&sources, &unit, None, None).expect("lowers");
        let mut sim =
            ii_prove::program::simulate::Simulator::new(&lowered.program, TimerModel::Plc);
        sim.step(&BTreeMap::new());
        let req = json!({
            "pou": "Main",
            "cycle_ns": 20_000_000u64,
            "scans": 1,
            "inputs": {},
            "want": want.iter().map(|(n, bit, _)| if *bit { json!({"bit": n}) } else { json!({"int": n}) })
                .collect::<Vec<_>>(),
        });
        let answer = run_one(&dir, "strings", &text, &req);
        assert_eq!(answer["status"], "ok", "{answer}");
        let trace = answer["trace"].as_array().expect("traces");
        for ((n, bit, s), got) in want.iter().zip(trace) {
            let computed = match bit {
                true => sim.is_known(n),
                false => lowered.program.integers.contains_key(n),
            };
            if !computed {
                skipped += 1;
                continue;
            }
            let theirs = match bit {
                true => got.as_str().map(|b| i64::from(b == "1")),
                false => got.as_array().and_then(|v| v.first()).and_then(Value::as_i64),
            };
            let ours = if *bit { Some(i64::from(sim.bit(n))) } else { sim.int(n) };
            assert_eq!(theirs, ours, "{n} := STRING_TO_…('{s}')");
            compared += 1;
        }
    }
    eprintln!(
        "{compared} conversions of string literals as matiec computes them, {skipped} not computed"
    );
    assert!(compared > 0);
}

/// The Structured Text and Instruction List programs of the test data and the examples
/// (each file whose single `PROGRAM` ii-prove lowers), run on random inputs: every
/// declared bit and computed integer as matiec's run gives it, as for the random
/// programs. Hand-written programs reach what the generators do not draw (`VAR_TEMP`
/// of every type, square roots of readings, nested function blocks).
#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn programs_of_the_test_data_run_as_matiec_runs_them() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["tests/data/proves_programs", "tests/data/refutes_programs", "examples"] {
        for ext in ["st", "il"] {
            files.extend(common::files_with(&root.join(dir), ext));
        }
    }
    files.sort();
    let mut jobs = Vec::new();
    for (seed, file) in files.iter().enumerate() {
        let text = std::fs::read_to_string(file).expect("read");
        // The program's type: the one POU declared `PROGRAM Name` (a configuration's
        // `PROGRAM inst WITH task : Name` names an instance).
        let pous: Vec<&str> = text
            .lines()
            .filter(|l| !l.contains(" WITH ") && !l.contains(':'))
            .filter_map(|l| l.strip_prefix("PROGRAM "))
            .map(str::trim)
            .collect();
        let [pou] = pous[..] else { continue };
        // A file without a configuration runs as the only program of one.
        let mut text = text.clone();
        if !text.contains("CONFIGURATION") {
            text += &format!(
                "\nCONFIGURATION Cfg\n  RESOURCE Res ON PLC\n    TASK Tk(INTERVAL := T#20ms, \
                 PRIORITY := 0);\n    PROGRAM Inst WITH Tk : {pou};\n  END_RESOURCE\n\
                 END_CONFIGURATION\n"
            );
        }
        let mut sources = Sources::new();
        let id = sources.add("program.st", text.clone());
        let Ok(unit) = ii_prove::iec::read(&sources, id) else { continue };
        let Ok(lowered) = ii_prove::iec::lower(&sources, &unit, None, None) else { continue };
        let p = &lowered.program;
        let int_bits: std::collections::BTreeSet<String> = p
            .integers
            .iter()
            .flat_map(|(n, v)| (0..v.ty.bits).map(|k| Program::int_bit(n, k)))
            .collect();
        let own = |n: &&String| !p.hidden.contains(*n) && !int_bits.contains(*n);
        let inputs: Vec<String> =
            p.signals.iter().filter(own).filter(|n| p.inputs.contains(n)).cloned().collect();
        let bits: Vec<String> =
            p.signals.iter().filter(own).filter(|n| !p.inputs.contains(n)).cloned().collect();
        eprintln!("{}: {pou}, {} inputs, {} bits", file.display(), inputs.len(), bits.len());
        let (pou, cycle_us, seed) = (pou.to_string(), p.cycle_us, seed as u64);
        jobs.push(Job { seed, text, pou, inputs, bits, cycle_us, partial: true, xml: false });
    }
    against_matiec("test data", jobs);
}
