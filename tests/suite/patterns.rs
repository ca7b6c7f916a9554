//! Each requirement pattern means the sentence of the README's catalogue: on random scan
//! runs, its compiled goal fails at some scan exactly when the sentence, evaluated
//! directly on the run's values, is broken by then.

use ii_prove::counterexample::scans_of;
use ii_prove::counterexample::unroll::{Concrete, Model, unroll};
use ii_prove::diag::Sources;
use ii_prove::semantics::Time;
use ii_prove::syntax::{self, Lookup, Relation, Scope};
use ii_prove::term::Delay;

/// The signals `a`, `b`, `c` of a program scanned every second.
struct Scans;

impl Scope for Scans {
    fn lookup(&self, name: &str) -> Lookup {
        match name {
            "a" | "b" | "c" => Lookup::Signal(name.into()),
            _ => Lookup::Unknown,
        }
    }
    fn names(&self) -> Vec<String> {
        vec!["a".into(), "b".into(), "c".into()]
    }
    fn scans(&self) -> bool {
        true
    }
    fn cycle(&self) -> Option<Delay> {
        Some(Delay::from_micros(1_000_000).unwrap())
    }
}

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// A run that holds each value for a random stretch (so delays are reached).
    fn run(&mut self, len: usize) -> Vec<bool> {
        let mut v = Vec::with_capacity(len);
        let mut cur = self.next() % 2 == 1;
        while v.len() < len {
            for _ in 0..1 + self.next() % 5 {
                v.push(cur);
            }
            cur = !cur;
        }
        v.truncate(len);
        v
    }
}

/// The first scan at which the pattern's compiled goal fails on the runs, if any.
fn goal_fails_at(text: &str, runs: &[Vec<bool>; 3]) -> Option<usize> {
    let mut sources = Sources::new();
    let file = sources.add("pattern.ii", format!("property P: {text}\n"));
    let doc = syntax::parse_properties(&sources, file, &Scans)
        .unwrap_or_else(|e| panic!("{text}: {e:?}"));
    let goal = &doc.properties[0].value;
    let (l, r) = (goal.lhs_with_after(), goal.rhs_with_after());
    let scans = runs[0].len();
    let cycle = Time::from_integer(1.into());
    let unrolled = unroll(
        &mut Concrete,
        &Model::default(),
        &[&l, &r],
        scans,
        &|d| scans_of(d, &cycle),
        &mut |_, name, k| match name {
            "a" => runs[0][k],
            "b" => runs[1][k],
            "c" => runs[2][k],
            other => panic!("unexpected signal {other}"),
        },
    )
    .expect("unrolls");
    (0..scans).find(|&k| {
        let (x, y) = (unrolled.extra[0][k], unrolled.extra[1][k]);
        match goal.relation {
            Relation::Equals => x != y,
            Relation::Implies => x && !y,
        }
    })
}

/// Does the sentence hold on the first `len` scans (`n` the duration in scans)?
fn sentence_holds(pattern: &str, n: usize, [a, b, c]: &[Vec<bool>; 3], len: usize) -> bool {
    let at = |v: &Vec<bool>, k: isize| k >= 0 && v[k as usize];
    let scans = 0..len as isize;
    match pattern {
        // "a is 1 at every scan"
        "always" => scans.clone().all(|k| at(a, k)),
        // "a is 1 at no scan"
        "never" => scans.clone().all(|k| !at(a, k)),
        // "if a at a scan and b at the next, then c at that next scan"
        "then" => scans.clone().all(|k| !(at(a, k - 1) && at(b, k)) || at(c, k)),
        // "every a is answered by a b at its scan or within n scans after it" (a scan whose
        // n scans are not all seen yet breaks nothing so far)
        "within" => scans.clone().all(|k| {
            !at(a, k) || k + n as isize >= len as isize || (k..=k + n as isize).any(|j| at(b, j))
        }),
        // "b only once more than n scans have passed since the last a"
        "not_before" => scans.clone().all(|j| !at(b, j) || (j - n as isize..=j).all(|k| !at(a, k))),
        // "a is never on for more than n scans in a row"
        "at_most" => scans.clone().all(|k| !(k - n as isize..=k).all(|j| at(a, j))),
        // "each stretch of a that has ended lasted at least n scans"
        "at_least" => scans.clone().all(|j| {
            if !at(a, j - 1) || at(a, j) {
                return true;
            }
            let mut start = j - 1;
            while at(a, start - 1) {
                start -= 1;
            }
            (j - start) as usize >= n
        }),
        other => panic!("no sentence for {other}"),
    }
}

#[test]
fn every_pattern_means_its_sentence_on_random_scan_runs() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let patterns = [
        ("always", "always a"),
        ("never", "never a"),
        ("then", "a then b => c"),
        ("within", "whenever a then b within {d}s"),
        ("not_before", "b not before {d}s after a"),
        ("at_most", "a at most {d}s"),
        ("at_least", "a at least {d}s once on"),
    ];
    let (mut violated, mut runs_of) = ([0usize; 7], [0usize; 7]);
    for case in 0..3_000 {
        let (i, (key, text)) = (case % patterns.len(), patterns[case % patterns.len()]);
        let n = 1 + (rng.next() % 4) as usize;
        let len = 1 + (rng.next() % 16) as usize;
        let runs = [rng.run(len), rng.run(len), rng.run(len)];
        let text = text.replace("{d}", &n.to_string());
        let fails = goal_fails_at(&text, &runs);
        for prefix in 1..=len {
            let by_goal = fails.is_some_and(|k| k < prefix);
            let by_sentence = !sentence_holds(key, n, &runs, prefix);
            assert_eq!(
                by_goal, by_sentence,
                "`{text}` on the first {prefix} scans of a = {:?}, b = {:?}, c = {:?}",
                runs[0], runs[1], runs[2]
            );
        }
        violated[i] += usize::from(fails.is_some());
        runs_of[i] += 1;
    }
    // Both verdicts occur for every pattern, so each comparison tested something.
    for (i, (key, _)) in patterns.iter().enumerate() {
        let (v, all) = (violated[i], runs_of[i]);
        assert!(v > 20 && v + 20 < all, "{key}: violated in {v} of {all} runs");
    }
}

#[test]
fn patterns_that_are_not_safety_properties_are_located_errors() {
    for (text, fragment, place) in [
        ("eventually a", "`eventually` states more than a safety property", "p.ii:1:13"),
        ("a until b", "`until` states more than a safety property", "p.ii:1:15"),
        ("reachable a", "an existence claim", "p.ii:1:13"),
    ] {
        let mut sources = Sources::new();
        let file = sources.add("p.ii", format!("property P: {text}\n"));
        let errors = syntax::parse_properties(&sources, file, &Scans).expect_err(text);
        let shown = ii_prove::diag::render_report(
            &errors[0],
            &sources,
            ii_prove::diag::RenderStyle { ascii: true },
        );
        assert!(shown.contains(fragment), "{text}: {shown}");
        assert!(shown.contains(place), "{text}: {shown}");
    }
    // Patterns that read the previous scan need a program.
    let mut sources = Sources::new();
    let file = sources.add("p.ii", "input a, b, c\nproperty P: a then b => c\n".to_string());
    let errors =
        syntax::parse_properties(&sources, file, &syntax::NoProgram).expect_err("no program");
    let shown = format!("{errors:?}");
    assert!(shown.contains("needs a program"), "{shown}");
}
