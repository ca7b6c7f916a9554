//! Random LDmicro programs with counters, comparisons and arithmetic, and random properties over their integers: none that fails is proved, and the share of those that hold which are proved is measured.
//!
//! A property's truth is judged by the ladder simulator (`src/ladder/simulate.rs`,
//! written from the format's description, not from the compiler), on random runs with
//! inputs held for random stretches, independently of the prover. A property refuted by
//! the prover is counted as failing only when its counterexample was confirmed by that
//! simulator (the report says so); any other refutation fails the test. A property no run
//! violates and the prover does not refute counts as holding, so a property that fails
//! only on runs longer than the random ones counts against the figure, never for it.
//! `II_INT_PROGRAMS=N` runs `N` programs (8 by default); the figures are printed;
//! `II_INT_KEEP=DIR` keeps the generated files in `DIR`. Every property no run violates
//! and the prover leaves unknown is printed.

use crate::common::rng;

use std::collections::BTreeMap;
use std::time::Duration;

use ii_prove::diag::Sources;
use ii_prove::ladder::{Simulator, read_ldmicro};
use ii_prove::report::{self, Options, Status};
use rng::Rng;

const INPUTS: [&str; 3] = ["XA", "XB", "XC"];
const RELAYS: [&str; 3] = ["RP", "RQ", "RS"];

/// What a generated program holds: its text, its integers and its relays' meaning.
struct Program {
    text: String,
    /// Counters and variables, each with the bound a property may compare it to.
    ints: Vec<(String, i64)>,
}

/// A counter of one kind on a contact, its reset, an arithmetic copy of it, and three
/// relays written from comparisons of the integers, contacts and each other.
fn program(rng: &mut Rng) -> Program {
    let mut text = String::from("LDmicro0.2\nCYCLE=10000\nPROGRAM\n");
    let contact = |rng: &mut Rng, names: &[&str]| {
        format!("    CONTACTS {} {} 0\n", rng.pick(names), u8::from(rng.chance(25)))
    };
    let max = 2 + rng.below(5) as i64;
    let counter = ["CTU", "CTD", "CTC"][rng.below(3) as usize];
    let kind = ["/", "\\", "/", "-"][rng.below(4) as usize];
    let init = if counter == "CTD" { max + 1 + rng.below(3) as i64 } else { 0 };
    text.push_str("RUNG\n");
    text.push_str(&contact(rng, &INPUTS));
    text.push_str(&format!("    {counter} Cn {max} {init} {kind}\nEND\n"));
    text.push_str("RUNG\n");
    text.push_str(&contact(rng, &INPUTS));
    text.push_str("    RES Cn\nEND\n");
    let mut ints = vec![("Cn".to_string(), max.max(init))];
    // A variable computed from the count, on a condition or every scan.
    let (op, k) = (rng.below(3), 1 + rng.below(3) as i64);
    text.push_str("RUNG\n");
    if rng.chance(50) {
        text.push_str(&contact(rng, &INPUTS));
    }
    match op {
        0 => text.push_str("    MOVE Vd Cn\nEND\n"),
        1 => text.push_str(&format!("    ADD Vd Cn {k}\nEND\n")),
        _ => text.push_str(&format!("    SUB Vd Cn {k}\nEND\n")),
    }
    ints.push(("Vd".to_string(), max.max(init) + k));
    let names: Vec<&str> = INPUTS.iter().chain(RELAYS.iter()).copied().collect();
    for relay in RELAYS {
        text.push_str("RUNG\n");
        let (var, bound) = rng.pick(&ints).clone();
        let cmp = ["GEQ", "GRT", "LES", "LEQ", "EQU", "NEQ"][rng.below(6) as usize];
        text.push_str(&format!("    {cmp} {var} {}\n", rng.below(bound as u64 + 2)));
        if rng.chance(50) {
            text.push_str(&contact(rng, &names));
        }
        text.push_str(&format!("    COIL {relay} 0 0 0\nEND\n"));
    }
    Program { text, ints }
}

/// A run: each bit's and each integer's value per scan.
#[derive(Default)]
struct Run {
    bits: BTreeMap<String, Vec<bool>>,
    ints: BTreeMap<String, Vec<i64>>,
}

/// A property: its `.ii` text and its meaning on a run.
struct Property {
    text: String,
    holds: Box<dyn Fn(&Run) -> bool>,
}

/// The comparison `op` of the `.ii` language, applied.
fn compare(op: &str, a: i64, b: i64) -> bool {
    match op {
        "=" => a == b,
        "<>" => a != b,
        "<" => a < b,
        "<=" => a <= b,
        ">" => a > b,
        _ => a >= b,
    }
}

/// A property over the integers, the relays and the inputs: an invariant bound on an
/// integer, a relay that implies a comparison, or a comparison that implies a relay.
fn property(rng: &mut Rng, p: &Program) -> Property {
    let (var, bound) = rng.pick(&p.ints).clone();
    let op = ["=", "<>", "<", "<=", ">", ">="][rng.below(6) as usize];
    let k = rng.below(bound as u64 + 3) as i64 - 1;
    let atom = format!("[{var} {op} {k}]");
    let at = move |run: &Run, i: usize| compare(op, run.ints[&var][i], k);
    let bit = rng.pick(&RELAYS).to_string();
    match rng.below(3) {
        0 => Property {
            text: format!("{atom} = 1*"),
            holds: Box::new(move |run| (0..run.bits[RELAYS[0]].len()).all(|i| at(run, i))),
        },
        1 => Property {
            text: format!("{bit} => {atom}"),
            holds: Box::new(move |run| {
                (0..run.bits[&bit].len()).all(|i| !run.bits[&bit][i] || at(run, i))
            }),
        },
        _ => Property {
            text: format!("{atom} => {bit}"),
            holds: Box::new(move |run| {
                (0..run.bits[&bit].len()).all(|i| !at(run, i) || run.bits[&bit][i])
            }),
        },
    }
}

/// Each signal's and integer's value at each scan of one random run of `scans` scans.
fn simulate(p: &Program, rng: &mut Rng, scans: usize) -> Run {
    let mut sources = Sources::new();
    let file = sources.add("random.ld", p.text.clone());
    let program = read_ldmicro(&sources, file).expect("a generated program reads");
    let mut sim = Simulator::new(&program);
    let mut run = Run::default();
    let mut inputs = rng::HeldInputs::new(&INPUTS, 35, 6);
    for _ in 0..scans {
        sim.step(inputs.next(rng));
        for n in INPUTS.iter().chain(RELAYS.iter()) {
            run.bits.entry(n.to_string()).or_default().push(sim.bit(n));
        }
        for (n, _) in &p.ints {
            run.ints.entry(n.clone()).or_default().push(sim.int(n));
        }
    }
    run
}

#[test]
fn no_failing_integer_property_is_proved_and_most_that_hold_are() {
    let programs: u64 =
        std::env::var("II_INT_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(8);
    // `II_INT_KEEP=DIR` keeps the programs and properties there.
    let keep = std::env::var("II_INT_KEEP").ok();
    let dir = keep.clone().map(std::path::PathBuf::from).unwrap_or_else(|| {
        std::env::temp_dir().join(format!("ii_int_properties_{}", std::process::id()))
    });
    std::fs::create_dir_all(&dir).unwrap();
    let opts = Options { timeout: Duration::from_secs(10), ..Options::default() };
    let (mut hold, mut proved, mut fail, mut refuted) = (0, 0, 0, 0);
    let mut unproved = Vec::new();
    for seed in 0..programs {
        let mut rng = Rng::new(seed ^ 0x1A7E);
        let p = program(&mut rng);
        let props: Vec<Property> = (0..5).map(|_| property(&mut rng, &p)).collect();
        let runs: Vec<Run> = (0..200).map(|_| simulate(&p, &mut rng, 60)).collect();
        let (ld_path, ii_path) = (dir.join(format!("p{seed}.ld")), dir.join(format!("p{seed}.ii")));
        std::fs::write(&ld_path, &p.text).unwrap();
        let ii: String =
            props.iter().enumerate().map(|(i, q)| format!("property p{i}: {}\n", q.text)).collect();
        std::fs::write(&ii_path, &ii).unwrap();
        let run = report::run_program(
            &ld_path.display().to_string(),
            &[ii_path.display().to_string()],
            &opts,
        )
        .unwrap_or_else(|e| panic!("seed {seed}: {}\n{}", e.rendered, p.text));
        for (q, verdict) in props.iter().zip(&run.properties) {
            let seen_to_hold = runs.iter().all(|r| (q.holds)(r));
            let status = verdict.status;
            assert!(
                seen_to_hold || status != Status::Proved,
                "seed {seed}: `{}` is proved and fails:\n{}",
                q.text,
                p.text
            );
            if status == Status::Refuted {
                let confirmed = verdict
                    .counterexample
                    .as_ref()
                    .is_some_and(|c| c.confirmed_by.iter().any(|by| by.contains("simulator")));
                assert!(confirmed, "seed {seed}: `{}` refuted without confirmation", q.text);
                refuted += usize::from(seen_to_hold);
                fail += 1;
            } else if seen_to_hold {
                hold += 1;
                if status == Status::Proved {
                    proved += 1;
                } else {
                    unproved.push(format!("seed {seed}: {}", q.text));
                }
            } else {
                fail += 1;
            }
        }
    }
    if keep.is_none() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    println!(
        "{programs} programs: {proved} of {hold} properties that hold are proved; {fail} fail \
         ({refuted} of them only on the prover's confirmed counterexample), none proved"
    );
    for u in &unproved {
        println!("  not proved: {u}");
    }
    assert!(hold > 0);
    // The bar is 95 % (measured: 53 of 54 at 30 programs, 217 of 222 at 100); the
    // floor leaves room for one or two more unknowns in a small sample.
    assert!(10 * proved >= 9 * hold, "only {proved} of {hold} properties that hold are proved");
}
