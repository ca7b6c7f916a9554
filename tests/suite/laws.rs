//! Every law of `theories/` holds under the exact semantics, in continuous time and on
//! scan runs with whole-cycle delays; false laws are rejected with a witness.

use std::path::Path;

use ii_prove::counterexample::scans_of;
use ii_prove::counterexample::unroll::{Concrete, Model, unroll};
use ii_prove::diag::Sources;
use ii_prove::kernel::{Axiom, Rel};
use ii_prove::semantics::Time;
use ii_prove::semantics::falsify::violation;
use ii_prove::semantics::{eval, random::exhaustive_boolean};
use ii_prove::term::{Term, mentions_pre};
use ii_prove::theory::{self, LawFailure, sample_relation};

const CASES: usize = 1_000;

fn is_boolean(axiom: &Axiom) -> bool {
    let boolean = |e: &ii_prove::term::Expr| {
        e.as_ref().iter().all(|n| {
            matches!(
                n,
                Term::Zero | Term::One | Term::And(_) | Term::Or(_) | Term::Not(_) | Term::Name(_)
            )
        })
    };
    boolean(&axiom.lhs) && boolean(&axiom.rhs)
}

#[test]
fn every_law_holds_on_random_exact_signals() {
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).expect("the theory files parse");
    assert!(theory.laws.len() >= 60, "the registry has {} laws", theory.laws.len());
    let mut failures = Vec::new();
    for (i, law) in theory.laws.iter().enumerate() {
        if mentions_pre(&law.axiom.lhs) || mentions_pre(&law.axiom.rhs) {
            // A law about scans: on random scan runs instead.
            match theory::check_scan_law(&law.axiom, CASES, i as u64 + 1) {
                Ok(n) => assert!(n >= CASES),
                Err(why) => {
                    failures.push(format!("{} ({}:{}): {why}", law.axiom.name, law.file, law.line))
                }
            }
            continue;
        }
        match theory::check_law(&law.axiom, CASES, i as u64 + 1) {
            Ok(n) => assert!(n >= CASES, "{} checked on only {n} samples", law.axiom.name),
            Err(LawFailure::Witness(w)) => failures.push(format!(
                "{} ({}:{}) fails at t = {} on {}",
                law.axiom.name, law.file, law.line, w.time, w.assignment
            )),
            Err(LawFailure::Sampling(e)) => {
                failures.push(format!("{}: cannot sample: {e:?}", law.axiom.name))
            }
        }
    }
    assert!(failures.is_empty(), "laws that do not hold:\n{}", failures.join("\n"));
}

/// On a program's scans every delay is a whole number of cycles. Every law, timer and
/// memory laws included, holds there under both of the project's readings of a scan
/// run: the exact evaluator at each scan's instant (`theory::check_scan_law`) and the
/// counterexample unroller, which counts scans (`d/f` is on from the (d/δ+1)-th
/// consecutive scan of `f`); and the two readings agree on every side of every instance.
#[test]
fn every_law_holds_on_scan_runs_with_whole_cycle_delays() {
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).expect("the theory files parse");
    let mut failures = Vec::new();
    for (i, law) in theory.laws.iter().enumerate() {
        let place = format!("{} ({}:{})", law.axiom.name, law.file, law.line);
        if let Err(why) = theory::check_scan_law(&law.axiom, CASES, i as u64 + 101) {
            failures.push(format!("{place}, exact evaluation: {why}"));
        }
        if let Err(why) = counting_scans(&law.axiom, CASES, i as u64 + 101) {
            failures.push(format!("{place}, counting scans: {why}"));
        }
    }
    assert!(failures.is_empty(), "laws that fail on scans:\n{}", failures.join("\n"));
}

/// The instances [`theory::check_scan_law`] evaluates exactly, read by the unroller
/// (counting scans), which must satisfy the law and agree with the exact reading.
fn counting_scans(axiom: &Axiom, cases: usize, seed: u64) -> Result<(), String> {
    let cycle = Time::from_integer(1.into());
    for inst in theory::scan_instances(axiom, cases, seed)? {
        let (l, r, runs) = (&inst.lhs, &inst.rhs, &inst.runs);
        let unrolled = unroll(
            &mut Concrete,
            &Model::default(),
            &[l, r],
            inst.scans(),
            &|d| scans_of(d, &cycle),
            &mut |_, name, k| runs.get(name).is_some_and(|v| v[k]),
        )?;
        let (a, b) = (eval(l, &inst.env).unwrap(), eval(r, &inst.env).unwrap());
        for k in 0..inst.scans() {
            let (x, y) = (unrolled.extra[0][k], unrolled.extra[1][k]);
            if !(x == y || (axiom.rel == Rel::Implies && !x)) {
                return Err(format!("`{l}` is {x} and `{r}` is {y} at scan {k} of {runs:?}"));
            }
            let t = theory::ScanInstance::instant(k);
            if (a.value_at(&t), b.value_at(&t)) != (x, y) {
                return Err(format!(
                    "the readings of `{l}` / `{r}` differ at scan {k} of {runs:?}"
                ));
            }
        }
    }
    Ok(())
}

#[test]
fn boolean_laws_hold_on_every_constant_assignment() {
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).expect("the theory files parse");
    let mut checked = 0;
    for law in theory.laws.iter().filter(|l| is_boolean(&l.axiom)) {
        for env in exhaustive_boolean(&law.axiom.signal_vars) {
            let (l, r) = (eval(&law.axiom.lhs, &env).unwrap(), eval(&law.axiom.rhs, &env).unwrap());
            assert!(
                violation(&l, sample_relation(law.axiom.rel), &r).is_none(),
                "{} fails on {env}",
                law.axiom.name
            );
        }
        checked += 1;
    }
    assert!(checked >= 25, "only {checked} Boolean laws");
}

#[test]
fn the_papers_false_forms_are_rejected_with_a_witness() {
    let mut rejected = 0;
    for law in laws_in_folder("tests/data/false_laws") {
        match theory::check_law(&law.axiom, CASES, 7) {
            Err(LawFailure::Witness(w)) => {
                // The witness is confirmed by exact evaluation.
                let l = eval(&law.axiom.lhs, &w.assignment).unwrap();
                let r = eval(&law.axiom.rhs, &w.assignment).unwrap();
                assert_eq!((l.value_at(&w.time), r.value_at(&w.time)), (w.lhs, w.rhs));
                match law.axiom.rel {
                    Rel::Eq => assert_ne!(w.lhs, w.rhs),
                    Rel::Implies => assert!(w.lhs && !w.rhs),
                }
                rejected += 1;
            }
            other => panic!("{} was not rejected: {other:?}", law.axiom.name),
        }
    }
    assert!(rejected >= 8);
}

#[test]
fn false_laws_about_scans_are_rejected_on_scan_runs() {
    let mut rejected = 0;
    for law in laws_in_folder("tests/data/false_scan_laws") {
        let result = theory::check_scan_law(&law.axiom, CASES, 7);
        assert!(result.is_err(), "{} was not rejected: {result:?}", law.axiom.name);
        rejected += 1;
    }
    assert!(rejected >= 3);
}

/// The laws of every theory file in `folder` (relative to the crate), each file non-empty.
fn laws_in_folder(folder: &str) -> Vec<theory::LawEntry> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(folder);
    let mut all = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("the folder exists") {
        let path = entry.unwrap().path();
        let mut sources = Sources::new();
        let file = sources.add(path.display().to_string(), std::fs::read_to_string(&path).unwrap());
        let laws = theory::read(&sources, file).expect("false laws still parse");
        assert!(!laws.is_empty(), "{} has no law", path.display());
        all.extend(laws);
    }
    all
}

#[test]
fn every_law_is_restated_as_a_property_that_the_cli_proves() {
    // tests/suite/verdicts.rs proves these files; here we check they cover the whole registry.
    // The laws of `pre` are about scans: tests/data/proves_programs/scan_laws.ii restates
    // them for a program.
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).expect("the theory files parse");
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/proves");
    let mut stated = String::new();
    for file in ["theory_laws.ii", "theory_laws_disjoint.ii", "../proves_programs/scan_laws.ii"] {
        stated.push_str(&std::fs::read_to_string(dir.join(file)).unwrap());
    }
    for law in &theory.laws {
        let line = format!("property {}:", law.axiom.name);
        assert!(stated.contains(&line), "{} is not restated as a property", law.axiom.name);
    }
}
