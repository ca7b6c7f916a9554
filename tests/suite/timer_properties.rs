//! Random LDmicro programs with timers and random properties about time: none that fails on the scan simulator is proved, and the share of those that hold which are proved is measured.
//!
//! A property's truth is judged by the ladder simulator (`src/ladder/simulate.rs`,
//! written from the format's description, not from the compiler), on random runs with
//! inputs held for random stretches, independently of the prover. `II_TIMER_PROGRAMS=N`
//! runs `N` programs (8 by default); the figures are printed.

use crate::common::rng;

use std::collections::BTreeMap;
use std::time::Duration;

use ii_prove::diag::Sources;
use ii_prove::ladder::{Simulator, read_ldmicro};
use ii_prove::report::{self, Options, Status};
use rng::Rng;

const INPUTS: [&str; 3] = ["XA", "XB", "XC"];
const RELAYS: [&str; 3] = ["RP", "RQ", "RS"];

/// A program of three rungs, each writing one relay from one or two contacts through an
/// optional TON or TOF of one to four 100 ms cycles.
fn program(rng: &mut Rng) -> String {
    let mut text = String::from("LDmicro0.2\nCYCLE=100000\nPROGRAM\n");
    let names: Vec<&str> = INPUTS.iter().chain(RELAYS.iter()).copied().collect();
    for (i, coil) in RELAYS.iter().enumerate() {
        text.push_str("RUNG\n");
        for _ in 0..1 + rng.below(2) {
            let negated = u8::from(rng.chance(30));
            text.push_str(&format!("    CONTACTS {} {negated} 0\n", rng.pick(&names)));
        }
        match rng.below(3) {
            0 => text.push_str(&format!("    TON Tn{i} {}\n", 100_000 * (1 + rng.below(4)))),
            1 => text.push_str(&format!("    TOF Tf{i} {}\n", 100_000 * (1 + rng.below(4)))),
            _ => {}
        }
        text.push_str(&format!("    COIL {coil} 0 0 0 0\nEND\n"));
    }
    text
}

/// A run: each signal's value per scan.
type Run = BTreeMap<String, Vec<bool>>;

/// A property: its `.ii` text and its meaning on a run.
struct Property {
    text: String,
    holds: Box<dyn Fn(&Run) -> bool>,
}

/// A property over the relays and the inputs the program reads.
fn property(rng: &mut Rng, ld: &str) -> Property {
    let names: Vec<&str> =
        INPUTS.iter().chain(RELAYS.iter()).copied().filter(|n| ld.contains(n)).collect();
    let (a, b) = (rng.pick(&RELAYS).to_string(), rng.pick(&names).to_string());
    let p = 1 + rng.below(6) as usize;
    let ms = 100 * p;
    match rng.below(3) {
        0 => Property {
            text: format!("{a} => {b}"),
            holds: Box::new(move |run| run[&a].iter().zip(&run[&b]).all(|(x, y)| !x || *y)),
        },
        // `d/f = 0*`: never `p + 1` consecutive scans of `a`.
        1 => Property {
            text: format!("{a} at most {ms}ms"),
            holds: Box::new(move |run| run[&a].windows(p + 1).all(|w| w.iter().any(|x| !x))),
        },
        // `a ⇒ d/b`: when `a`, `b` has been on for the last `p + 1` scans.
        _ => Property {
            text: format!("{a} => {ms}ms/{b}"),
            holds: Box::new(move |run| {
                (0..run[&a].len())
                    .all(|k| !run[&a][k] || (k >= p && run[&b][k - p..=k].iter().all(|x| *x)))
            }),
        },
    }
}

/// Each signal's value at each scan of one random run of `scans` scans.
fn simulate(ld: &str, rng: &mut Rng, scans: usize) -> BTreeMap<String, Vec<bool>> {
    let mut sources = Sources::new();
    let file = sources.add("random.ld", ld.to_string());
    let program = read_ldmicro(&sources, file).expect("a generated program reads");
    let mut sim = Simulator::new(&program);
    let mut run: BTreeMap<String, Vec<bool>> = BTreeMap::new();
    let mut inputs = rng::HeldInputs::new(&INPUTS, 50, 8);
    for _ in 0..scans {
        sim.step(inputs.next(rng));
        for n in INPUTS.iter().chain(RELAYS.iter()) {
            run.entry(n.to_string()).or_default().push(sim.bit(n));
        }
    }
    run
}

#[test]
fn no_failing_timer_property_is_proved_and_most_that_hold_are() {
    let programs: u64 =
        std::env::var("II_TIMER_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(8);
    let dir = std::env::temp_dir().join(format!("ii_timer_properties_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let opts = Options { timeout: Duration::from_secs(10), ..Options::default() };
    let (mut hold, mut proved, mut fail) = (0, 0, 0);
    for seed in 0..programs {
        let mut rng = Rng::new(seed ^ 0x71_3E);
        let ld = program(&mut rng);
        let props: Vec<Property> = (0..4).map(|_| property(&mut rng, &ld)).collect();
        let runs: Vec<_> = (0..200).map(|_| simulate(&ld, &mut rng, 40)).collect();
        let (ld_path, ii_path) = (dir.join(format!("p{seed}.ld")), dir.join(format!("p{seed}.ii")));
        std::fs::write(&ld_path, &ld).unwrap();
        let ii: String =
            props.iter().enumerate().map(|(i, p)| format!("property p{i}: {}\n", p.text)).collect();
        std::fs::write(&ii_path, &ii).unwrap();
        let run = report::run_program(
            &ld_path.display().to_string(),
            &[ii_path.display().to_string()],
            &opts,
        )
        .unwrap_or_else(|e| panic!("seed {seed}: {}", e.rendered));
        for (p, verdict) in props.iter().zip(&run.properties) {
            let holds = runs.iter().all(|r| (p.holds)(r));
            let is_proved = verdict.status == Status::Proved;
            assert!(holds || !is_proved, "seed {seed}: `{}` is proved and fails:\n{ld}", p.text);
            if holds {
                hold += 1;
                proved += usize::from(is_proved);
            } else {
                fail += 1;
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    println!(
        "{programs} programs: {proved} of {hold} properties that hold are proved; {fail} fail, none proved"
    );
    assert!(hold > 0);
    assert!(100 * proved >= 95 * hold, "only {proved} of {hold} properties that hold are proved");
}
