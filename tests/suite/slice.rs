//! The LDmicro simulator of part of a program against the simulator of the whole: a slice ([`LdProgram::slice`]) and a part near a recorded run ([`LdProgram::slice_near`]) give the values of the names they watch, scan by scan, that the whole program's run gives, on random programs of contacts, coils and timers and random runs that differ from the recorded one in a few inputs.
//!
//! The programs are drawn from the rung grammar of `formats/ldmicro.md` (§4: contacts,
//! plain/negated/set/reset coils, TON/TOF/RTO timers, series and parallel), the only
//! elements slicing applies to; `II_SLICE_PROGRAMS=N` scales the number of programs.
#![warn(missing_docs)]

use crate::common::rng;
use rng::Rng;

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

use ii_prove::diag::Sources;
use ii_prove::ladder::{LdProgram, Simulator, read_ldmicro};

const INPUTS: &[&str] = &["Xa", "Xb", "Xc", "Xd", "Xe", "Xf"];
const BITS: &[&str] = &["Ra", "Rb", "Rc", "Yp", "Yq", "Yr", "Ys"];
const TIMERS: &[&str] = &["Ta", "Tb", "Tc"];

/// A random series item of at most `depth` levels: a contact, or a parallel whose
/// branches are contacts or series of items (a parallel never directly holds another).
fn circuit(rng: &mut Rng, depth: u32, out: &mut String) {
    let contact = |rng: &mut Rng, out: &mut String| {
        let name = if rng.chance(50) { rng.pick(INPUTS) } else { rng.pick(BITS) };
        out.push_str(&format!("CONTACTS {name} {}\n", u8::from(rng.chance(30))));
    };
    if depth == 0 || rng.chance(50) {
        contact(rng, out);
        return;
    }
    out.push_str("PARALLEL\n");
    for _ in 0..2 + rng.below(2) {
        if rng.chance(50) {
            contact(rng, out);
        } else {
            out.push_str("SERIES\n");
            for _ in 0..1 + rng.below(3) {
                circuit(rng, depth - 1, out);
            }
            out.push_str("END\n");
        }
    }
    out.push_str("END\n");
}

/// A random program of contacts, coils and timers on a 10 ms cycle.
fn program(rng: &mut Rng) -> String {
    let mut text = String::from("LDmicro0.2\nCYCLE=10000\nPROGRAM\n");
    for _ in 0..3 + rng.below(8) {
        text.push_str("RUNG\n");
        for _ in 0..1 + rng.below(3) {
            circuit(rng, 2, &mut text);
        }
        if rng.chance(40) {
            let kw = rng.pick(&["TON", "TOF", "RTO"]);
            text.push_str(&format!("{kw} {} {}\n", rng.pick(TIMERS), 10_000 * (1 + rng.below(4))));
        }
        // set, reset, negated or plain
        let kind = rng.below(4);
        let (negated, set, reset) = (kind == 1, kind == 2, kind == 3);
        text.push_str(&format!(
            "COIL {} {} {} {}\nEND\n",
            rng.pick(BITS),
            u8::from(negated),
            u8::from(set),
            u8::from(reset)
        ));
    }
    text
}

fn read(text: &str) -> LdProgram {
    let mut sources = Sources::new();
    let f = sources.add("slice.ld", text.to_string());
    read_ldmicro(&sources, f).unwrap_or_else(|e| panic!("{e:?}\n{text}"))
}

/// Random inputs for `scans` scans, each held for a few scans.
fn run(rng: &mut Rng, scans: usize) -> Vec<BTreeMap<String, bool>> {
    let mut now: BTreeMap<String, bool> = INPUTS.iter().map(|n| (n.to_string(), false)).collect();
    (0..scans)
        .map(|_| {
            for v in now.values_mut() {
                if rng.chance(25) {
                    *v = !*v;
                }
            }
            now.clone()
        })
        .collect()
}

/// The names `sim` gives, scan by scan, of `watched` on `inputs`.
fn values(
    mut sim: Simulator,
    inputs: &[BTreeMap<String, bool>],
    watched: &BTreeSet<String>,
) -> Vec<Vec<(String, bool, i64)>> {
    inputs
        .iter()
        .map(|step| {
            sim.step(step);
            watched.iter().map(|n| (n.clone(), sim.bit(n), sim.int(n))).collect()
        })
        .collect()
}

#[test]
fn a_part_near_a_recorded_run_gives_what_the_whole_program_gives() {
    let programs: u64 =
        std::env::var("II_SLICE_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(2_000);
    for seed in 0..programs {
        let mut rng = Rng::new(seed);
        let text = program(&mut rng);
        let p = read(&text);
        let scans = 2 + rng.below(20) as usize;
        let base = run(&mut rng, scans);
        // The run: the base run's inputs with a few of them changed.
        let changed: BTreeSet<String> =
            INPUTS.iter().filter(|_| rng.chance(20)).map(|n| n.to_string()).collect();
        let mut inputs = base.clone();
        let cut = 1 + rng.below(scans as u64) as usize;
        inputs.truncate(cut);
        for step in &mut inputs {
            for n in &changed {
                if rng.chance(50) {
                    step.insert(n.clone(), rng.chance(50));
                }
            }
        }
        let watched: BTreeSet<String> =
            BITS.iter().chain(TIMERS).filter(|_| rng.chance(40)).map(|n| n.to_string()).collect();
        // The record: a run of the rungs that can write the names watched and a few more.
        let recorded: BTreeSet<String> = BITS
            .iter()
            .chain(TIMERS)
            .filter(|n| watched.contains(**n) || rng.chance(30))
            .map(|n| n.to_string())
            .collect();
        let record = Arc::new(p.record(&recorded, &base).expect("contacts, coils and timers"));
        let whole = values(Simulator::new(&p), &inputs, &watched);
        let sliced = p.slice(&watched).expect("sliceable");
        assert_eq!(
            values(Simulator::new(&sliced), &inputs, &watched),
            whole,
            "slice, seed {seed}\n{text}"
        );
        let near = p.slice_near(&watched, &record, &changed, cut).expect("a part");
        assert_eq!(values(near, &inputs, &watched), whole, "near part, seed {seed}\n{text}");
    }
}

#[test]
fn a_part_near_a_recorded_run_replays_what_the_changed_inputs_do_not_reach() {
    // Two chains: Xa → Ra → Yp and Xb → Rb → Yq, with Yq also reading Ra. A run that
    // changes only Xb must still see Ra as the recorded run had it (Xa held at 1 there),
    // though the part does not run Ra's rung.
    let p = read(
        "LDmicro0.2\nCYCLE=10000\nPROGRAM\n\
         RUNG\nCONTACTS Xa 0\nCOIL Ra 0 0 0\nEND\n\
         RUNG\nCONTACTS Ra 0\nCOIL Yp 0 0 0\nEND\n\
         RUNG\nCONTACTS Xb 0\nCOIL Rb 0 0 0\nEND\n\
         RUNG\nCONTACTS Rb 0\nCONTACTS Ra 0\nCOIL Yq 0 0 0\nEND\n",
    );
    let on = |a: bool, b: bool| -> BTreeMap<String, bool> {
        [("Xa".to_string(), a), ("Xb".to_string(), b)].into_iter().collect()
    };
    let watched: BTreeSet<String> = ["Yq".to_string()].into_iter().collect();
    let record = Arc::new(p.record(&watched, &[on(true, false), on(true, false)]).expect("record"));
    let changed: BTreeSet<String> = ["Xb".to_string()].into_iter().collect();
    let mut near = p.slice_near(&watched, &record, &changed, 2).expect("a part");
    // Xa is left out of the step: the part reads Ra from the record, not from Xa.
    let only_b: BTreeMap<String, bool> = [("Xb".to_string(), true)].into_iter().collect();
    near.step(&only_b);
    assert!(near.bit("Yq"), "Ra replayed at 1, Rb run at 1");
    // Past the record, what is replayed is not exact.
    near.step(&only_b);
    near.step(&only_b);
    assert!(!near.is_known("Ra"));
    assert!(p.slice_near(&watched, &record, &changed, 3).is_none(), "longer than the record");
    // A part that would replay a rung the record does not hold is refused: Yp's rung
    // reads Ra, whose rung was recorded, but Yp's own rung was not.
    let yp: BTreeSet<String> = ["Yp".to_string()].into_iter().collect();
    let ra: BTreeSet<String> = ["Xa".to_string()].into_iter().collect();
    assert!(p.slice_near(&yp, &record, &BTreeSet::new(), 2).is_none(), "Yp is not recorded");
    // With Xa changed, both rungs run and nothing is replayed: no record needed.
    let mut both = p.slice_near(&yp, &record, &ra, 2).expect("nothing to replay");
    both.step(&on(false, true));
    assert!(!both.bit("Yp"), "Xa at 0 in this run, not the record's 1");
}
