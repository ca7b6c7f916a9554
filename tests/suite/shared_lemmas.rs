//! Shared lemmas: what a literal forces far along a chain is proved once per program and
//! cited by every property; the proofs are the same alone, in any order and at any
//! `--jobs`, and a broken link is still refuted.

use crate::common;

use std::path::PathBuf;

use common::{ii_prove, text};

/// A chain of `n` units: unit 1 demands unless `XStop`; unit i demands only while unit
/// i−1 does and its own permit is on; each unit's output follows its demand. With
/// `broken`, that unit ignores the previous one.
fn chain(n: usize, broken: Option<usize>) -> String {
    let mut rungs = vec!["RUNG\n    CONTACTS XStop 1\n    COIL RD1 0 0 0\nEND".to_string()];
    for i in 2..=n {
        let gate =
            if broken == Some(i) { String::new() } else { format!("    CONTACTS RD{} 0\n", i - 1) };
        rungs.push(format!("RUNG\n{gate}    CONTACTS XPermit{i} 0\n    COIL RD{i} 0 0 0\nEND"));
    }
    for i in 1..=n {
        rungs.push(format!("RUNG\n    CONTACTS RD{i} 0\n    COIL YOut{i} 0 0 0\nEND"));
    }
    format!("LDmicro0.2\nCYCLE=10000\n\nPROGRAM\n{}\n", rungs.join("\n"))
}

fn properties(units: impl Iterator<Item = usize>) -> String {
    units.map(|i| format!("property Off{i}: Stop => !Out{i}\n")).collect()
}

fn write(dir: &str, name: &str, content: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ii-prove-lemmas-{}-{dir}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, content).unwrap();
    path
}

/// Each property's trace (its lines after the verdict line, times removed), by name.
fn traces(args: &[&str]) -> std::collections::BTreeMap<String, String> {
    let out = ii_prove(args);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}{}", text(&out.stderr));
    let mut by_name = std::collections::BTreeMap::new();
    let mut current: Option<(String, String)> = None;
    for line in stdout.lines() {
        let mut words = line.split_whitespace();
        if let (Some(name), Some("proved")) = (words.next(), words.next()) {
            by_name.extend(current.take());
            current = Some((name.to_string(), String::new()));
        } else if line.contains(" proved, ") {
            break;
        } else if let Some((_, body)) = current.as_mut() {
            body.push_str(line);
            body.push('\n');
        }
    }
    by_name.extend(current);
    by_name
}

#[test]
fn a_far_literal_is_a_lemma_and_every_order_gives_the_same_proofs() {
    let n = 40;
    let ld = write("order", "chain.ld", &chain(n, None));
    let forward = write("order", "forward.ii", &properties(1..=n));
    let backward = write("order", "backward.ii", &properties((1..=n).rev()));
    let alone = write("order", "alone.ii", &properties(std::iter::once(n)));
    let ld = ld.to_str().unwrap();
    let run = |props: &PathBuf, jobs: &str| {
        traces(&[ld, props.to_str().unwrap(), "--trace", "--jobs", jobs])
    };
    let reference = run(&forward, "1");
    assert_eq!(reference.len(), n);
    let last = &reference[&format!("Off{n}")];
    // The last unit's proof cites what `Stop` forces at the end of the chain, as one
    // lemma with its hypotheses folded, not a case per link.
    let lemma = format!("where Stop ⇒ ¬RD{n}   [forced through L01, L02, …, L{n} ({n} hypotheses)");
    assert!(last.contains(&lemma), "{last}");
    assert!(last.lines().count() < 8, "a short proof, not one line per link:\n{last}");
    // The first units are near the stoppage: their proofs cite no lemma.
    assert!(!reference["Off1"].contains("where"), "{}", reference["Off1"]);
    assert_eq!(run(&backward, "1"), reference);
    assert_eq!(run(&forward, "2"), reference);
    assert_eq!(run(&backward, "2"), reference);
    assert_eq!(run(&alone, "1")[&format!("Off{n}")], *last);
}

#[test]
fn a_broken_link_is_refuted_beyond_it_and_proved_before_it() {
    let n = 30;
    let ld = write("broken", "chain.ld", &chain(n, Some(20)));
    let props = write("broken", "props.ii", &properties(1..=n));
    let out = ii_prove(&[ld.to_str().unwrap(), props.to_str().unwrap(), "--jobs", "1"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    for i in 1..=n {
        let line = stdout
            .lines()
            .find(|l| l.split_whitespace().next() == Some(&format!("Off{i}")))
            .unwrap();
        let want = if i < 20 { "proved" } else { "refuted" };
        assert_eq!(line.split_whitespace().nth(1), Some(want), "{line}");
    }
}
