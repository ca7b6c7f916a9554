//! Proof scripts: every file of `proofs/` checks; every file of `tests/data/scripts_reject/`
//! is rejected with a located error whose text and place its first two lines record
//! (`// error: FRAGMENT`, `// at: LINE:COL`).

use crate::common;

use std::path::Path;

use ii_prove::diag::Sources;
use ii_prove::report::Options;
use ii_prove::script::{self, Checker};
use ii_prove::syntax::{self, NoProgram};
use ii_prove::theory;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn every_proof_script_checks() {
    let files = common::files_with(&root().join("proofs"), "ii");
    assert!(files.len() >= 2, "found only {files:?}");
    for path in files {
        let run = script::check_files(&[path.display().to_string()], &Options::default());
        assert!(run.errors.is_empty(), "{}:\n{}", path.display(), run.errors.join("\n"));
        assert!(!run.claims.is_empty(), "{}: no claims", path.display());
        assert!(run.claims.iter().all(|c| c.ok), "{}", path.display());
        assert_eq!(run.exit_code(), 0);
    }
}

#[test]
fn the_water_proofs_cover_every_property() {
    let path = root().join("proofs/water_paper.ii").display().to_string();
    let run = script::check_files(&[path], &Options::default());
    for name in ["P1a", "P1b", "P2", "P3", "P4a", "P4b", "Fig9"] {
        assert!(run.claims.iter().any(|c| c.name == name && c.ok), "{name} missing");
    }
}

#[test]
fn every_rejected_script_gets_its_located_error() {
    let files = common::files_with(&root().join("tests/data/scripts_reject"), "ii");
    assert!(files.len() >= 5, "found only {files:?}");
    for path in files {
        let text = std::fs::read_to_string(&path).expect("readable");
        let mut lines = text.lines();
        let fragment = lines
            .next()
            .and_then(|l| l.strip_prefix("// error: "))
            .unwrap_or_else(|| panic!("{}: first line must be `// error: ...`", path.display()));
        let at = lines
            .next()
            .and_then(|l| l.strip_prefix("// at: "))
            .unwrap_or_else(|| panic!("{}: second line must be `// at: L:C`", path.display()));
        let shown = path.display().to_string();
        let run = script::check_files(std::slice::from_ref(&shown), &Options::default());
        assert_eq!(run.exit_code(), 2, "{shown} was accepted");
        let location = format!("{shown}:{at}");
        assert!(
            run.errors.iter().any(|e| e.contains(fragment) && e.contains(&location)),
            "{shown}: no error with `{fragment}` at {location}:\n{}",
            run.errors.join("\n")
        );
    }
}

/// Checks a script given as text; `Ok(names)` of the checked claims or the first error.
fn check_text(text: &str) -> Result<Vec<String>, String> {
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).map_err(|_| "theory".to_string())?;
    let file = sources.add("test.ii", text);
    let doc = syntax::parse_document(&sources, file, &NoProgram).map_err(|e| format!("{e:?}"))?;
    let (reports, errors) =
        script::check_document(&theory, &doc, None, "test.ii", Default::default());
    match errors.first() {
        Some(e) => Err(format!("{e:?}")),
        None => Ok(reports.into_iter().map(|r| r.name).collect()),
    }
}

#[test]
fn auto_proves_true_claims_and_fails_on_false_ones() {
    let ok = "input f\ntheorem T: 2s/f => f\nby auto\n";
    assert_eq!(check_text(ok), Ok(vec!["T".to_string()]));
    let bad = "input f\ntheorem T: f => 2s/f\nby auto\n";
    let err = check_text(bad).unwrap_err();
    assert!(err.contains("AutoFailed"), "{err}");
    let step = "input f, g\nassume E: f = g\ntheorem T: f . g = g\nproof\n  f . g\n  = g . g [E]\n  = g [auto]\nqed\n";
    assert_eq!(check_text(step), Ok(vec!["T".to_string()]));
}

#[test]
fn closings_by_meet_and_by_zero() {
    let meet = "input f\ntheorem T: 3s/f => f\nproof\n  3s/f . f\n  = 3s/f [ton_weaken]\nqed\n";
    assert_eq!(check_text(meet), Ok(vec!["T".to_string()]));
    let zero = "input f\ntheorem T: f => f\nproof\n  f . !f\n  = 0* [and_not]\nqed\n";
    assert_eq!(check_text(zero), Ok(vec!["T".to_string()]));
}

#[test]
fn an_implication_step_cannot_prove_an_equation_and_uncited_rules_are_not_used() {
    // `or_comm` is needed but not cited.
    let text = "input f, g\ntheorem T: f + g = g + f\nproof\n  f + g\n  = g + f [and_comm]\nqed\n";
    assert!(check_text(text).unwrap_err().contains("StepFailed"));
    let text = "input f, g\ntheorem T: f + g = g + f\nproof\n  f + g\n  = g + f [or_comm]\nqed\n";
    assert!(check_text(text).is_ok());
}

#[test]
fn the_checker_answers_single_rewrites() {
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).expect("theory");
    let checker = Checker::new(theory.axioms(), vec![]).expect("kernel");
    let term = ii_prove::term::sexp("(ton 5s f)");
    let (found, _) = checker.rewrites(&term, "ton_weaken", None, None);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].1, ii_prove::kernel::Rel::Implies);
}

/// Each line of two proof scripts dropped in turn (every third line in the test
/// command, to keep CI's time; `II_DAMAGE_STRIDE=1` drops every one): no panic.
#[test]
fn damaged_scripts_are_rejected_without_panicking() {
    let stride: usize =
        std::env::var("II_DAMAGE_STRIDE").ok().and_then(|v| v.parse().ok()).unwrap_or(3);
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).expect("theory");
    for name in ["proofs/derived_laws.ii", "proofs/water_paper.ii"] {
        let text = std::fs::read_to_string(root().join(name)).expect("readable");
        let lines: Vec<&str> = text.lines().collect();
        // Drop each line in turn; also swap two neighbouring step lines.
        for i in (0..lines.len()).step_by(stride.max(1)) {
            let mut damaged: Vec<&str> = lines.clone();
            damaged.remove(i);
            if i + 1 < damaged.len() && damaged[i].trim_start().starts_with('=') {
                damaged.swap(i, i + 1);
            }
            let file = sources.add(format!("{name} (damaged {i})"), damaged.join("\n"));
            if let Ok(doc) = syntax::parse_document(&sources, file, &NoProgram) {
                let _ = script::check_document(&theory, &doc, None, name, Default::default());
            }
        }
    }
}

#[test]
fn a_claim_may_not_take_a_hypothesis_name() {
    let text = "input f\nassume H: f = f\n";
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).expect("theory");
    let file = sources.add("t.ii", format!("{text}lemma and_comm: f = f\nby auto\n"));
    let doc = syntax::parse_document(&sources, file, &NoProgram).expect("parses");
    let (_, errors) = script::check_document(&theory, &doc, None, "t.ii", Default::default());
    assert_eq!(errors.len(), 1, "{errors:?}");
}
