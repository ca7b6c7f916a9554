//! Benchmarks of the prover on synthetic goals of growing size and on the paper's water plant.
//!
//! Every benched goal is first proved once outside the timing loop and asserted
//! `Proved`: timing a failure would be meaningless. Sizes are the number of
//! generated equations; `II_BENCH_MAX_N` (default 10000) caps them for quick runs.
//! Results and their reading are in `benches/RESULTS.md`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};

use ii_prove::diag::Sources;
use ii_prove::kernel::{Axiom, Rel};
use ii_prove::prover::{self, Budget, Context, Obligation, Outcome};
use ii_prove::report;
use ii_prove::syntax::{self, NoProgram};
use ii_prove::term::{Builder, Delay, Expr, Id, Symbol, Term};
use ii_prove::theory;

const WATER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/proves/water_paper.ii");

/// Sizes (equations) of the synthetic families whose goal has a small cone.
const SIZES: &[usize] = &[10, 100, 1_000, 10_000];

/// Sizes of the families whose goal needs the whole program (its cone is every
/// equation). Capped: at 1,000 equations none of them is proved within 60 s (the
/// case split stops at the time limit; see `benches/RESULTS.md`), so 30 and 300
/// are measured instead to show the growth.
const WHOLE_CONE_SIZES: &[usize] = &[10, 30, 100, 300];

fn upto(sizes: &[usize]) -> Vec<usize> {
    let max = std::env::var("II_BENCH_MAX_N").ok().and_then(|v| v.parse().ok()).unwrap_or(10_000);
    sizes.iter().copied().filter(|&n| n <= max).collect()
}

fn sizes() -> Vec<usize> {
    upto(SIZES)
}

fn whole_cone_sizes() -> Vec<usize> {
    std::env::var("II_BENCH_WHOLE_CONE")
        .ok()
        .map(|v| v.split(',').filter_map(|n| n.parse().ok()).collect())
        .unwrap_or_else(|| upto(WHOLE_CONE_SIZES))
}

fn laws() -> Vec<Axiom> {
    let mut sources = Sources::new();
    theory::standard(&mut sources).expect("the shipped theories parse").axioms()
}

fn delay(text: &str) -> Delay {
    text.parse().expect("a valid delay")
}

/// A small term built with a closure over a [`Builder`].
fn term(build: impl FnOnce(&mut Builder) -> Id) -> Expr {
    let mut b = Builder::default();
    build(&mut b);
    b.finish()
}

fn name(n: &str) -> Expr {
    term(|b| b.name(n))
}

fn eq(label: String, lhs: Expr, rhs: Expr) -> Axiom {
    Axiom::ground(label, lhs, Rel::Eq, rhs)
}

/// The goal `a · b = 0*`.
fn exclusive(a: &str, b: &str) -> Obligation {
    Obligation {
        lhs: term(|t| {
            let (x, y) = (t.name(a), t.name(b));
            t.and(x, y)
        }),
        rel: Rel::Eq,
        rhs: term(|t| t.zero()),
    }
}

fn implies(a: &str, b: &str) -> Obligation {
    Obligation { lhs: name(a), rel: Rel::Implies, rhs: name(b) }
}

/// `n` equations `p1 = 5s/p0`, `p2 = p1 · a2`, `p3 = p2 · SR(s3, r3)`,
/// `p4 = p3 · (c4/2s + ¬b4)`, … (the four forms in turn). Each `p(i)` implies `p(i−1)`.
fn chain(p: &str, n: usize, out: &mut Vec<Axiom>) {
    let five = delay("5s");
    let two = delay("2s");
    for i in 1..=n {
        let prev = format!("{p}{}", i - 1);
        let rhs = term(|b| {
            let x = b.name(&prev);
            match i % 4 {
                1 => {
                    let d = b.delay(five.clone());
                    b.ton(d, x)
                }
                2 => {
                    let a = b.name(&format!("{p}a{i}"));
                    b.and(x, a)
                }
                3 => {
                    let s = b.name(&format!("{p}s{i}"));
                    let r = b.name(&format!("{p}r{i}"));
                    let m = b.sr(s, r);
                    b.and(x, m)
                }
                _ => {
                    let c = b.name(&format!("{p}c{i}"));
                    let d = b.delay(two.clone());
                    let off = b.tof(c, d);
                    let nb = b.name(&format!("{p}b{i}"));
                    let nb = b.not(nb);
                    let or = b.or(off, nb);
                    b.and(x, or)
                }
            }
        });
        out.push(eq(format!("{p}{i}"), name(&format!("{p}{i}")), rhs));
    }
}

/// A balanced fan-in of `n` equations over nodes `t1 … tn` (node `i` has children
/// `2i`, `2i+1`; the children beyond `n` are inputs): `t = u · v` and `t = 2s/u + v`
/// on alternate levels, every input excluded by an emergency stop `e` (`tj · e = 0*`).
fn tree(n: usize) -> Vec<Axiom> {
    let two = delay("2s");
    let mut out = Vec::new();
    for i in 1..=n {
        let level = usize::BITS - 1 - i.leading_zeros();
        let rhs = term(|b| {
            let u = b.name(&format!("t{}", 2 * i));
            let v = b.name(&format!("t{}", 2 * i + 1));
            if level % 2 == 0 {
                b.and(u, v)
            } else {
                let d = b.delay(two.clone());
                let late = b.ton(d, u);
                b.or(late, v)
            }
        });
        out.push(eq(format!("T{i}"), name(&format!("t{i}")), rhs));
    }
    for j in n + 1..=2 * n + 1 {
        let lhs = term(|b| {
            let (x, e) = (b.name(&format!("t{j}")), b.name("e"));
            b.and(x, e)
        });
        out.push(eq(format!("E{j}"), lhs, term(|b| b.zero())));
    }
    out
}

/// The water plant's file, parsed: its hypotheses and its properties as obligations.
fn water() -> (Vec<Axiom>, Vec<(String, Obligation)>) {
    let mut sources = Sources::new();
    let file = report::read_source(&mut sources, WATER).expect("the water plant file");
    let doc = syntax::parse_document(&sources, file, &NoProgram).expect("the water plant parses");
    let goals =
        doc.properties.iter().map(|s| (s.name.clone(), report::obligation(&s.value))).collect();
    (report::assumptions(&doc), goals)
}

/// `e` with every signal name `x` not in `keep` renamed `x_k`.
fn rename(e: &Expr, k: usize, keep: &[&str]) -> Expr {
    let nodes: Vec<Term> = e
        .as_ref()
        .iter()
        .map(|node| match node {
            Term::Name(s) if !keep.contains(&s.as_str()) => {
                Term::Name(Symbol::from(format!("{s}_{k}")))
            }
            other => other.clone(),
        })
        .collect();
    Expr::from(nodes)
}

/// `n` copies of the water plant's H1–H10 (so `n` = 10 copies is 100 equations), each
/// copy's signals renamed `x_k` except those in `keep` (shared by every copy).
fn water_copies(n: usize, keep: &[&str]) -> (Vec<Axiom>, Obligation) {
    let (hyps, goals) = water();
    let mut out = Vec::with_capacity(n * hyps.len());
    for k in 0..n {
        for h in &hyps {
            let (lhs, rhs) = (rename(&h.lhs, k, keep), rename(&h.rhs, k, keep));
            out.push(Axiom::ground(format!("{}_{k}", h.name), lhs, h.rel, rhs));
        }
    }
    let p2 = &goals.iter().find(|(n, _)| n == "P2").expect("P2 in the water file").1;
    let goal =
        Obligation { lhs: rename(&p2.lhs, 0, keep), rel: p2.rel, rhs: rename(&p2.rhs, 0, keep) };
    (out, goal)
}

/// Proves once outside the timing loop and reports how; `None` unless proved.
fn prove_once(label: &str, ctx: &Context, goal: &Obligation, budget: Budget) -> Option<Duration> {
    let started = Instant::now();
    let outcome = prover::prove(ctx, goal, budget);
    let elapsed = started.elapsed();
    let cone = prover::cone_of_influence(ctx.hypotheses(), &[&goal.lhs, &goal.rhs]).len();
    match outcome {
        Outcome::Proved(p) => {
            eprintln!(
                "{label}: proved by {:?} in {elapsed:.2?} ({} hypotheses, cone {cone}, {} cases)",
                p.method,
                ctx.hypotheses().len(),
                prover::case_leaves(&p),
            );
            Some(elapsed)
        }
        Outcome::Unknown { reason, .. } => {
            eprintln!("{label}: NOT PROVED in {elapsed:.2?} (cone {cone}): {reason}");
            None
        }
    }
}

/// The budget of every synthetic goal: the default's node limit, but time and cases
/// large enough that the largest sizes are limited by the algorithm, not the budget.
/// `II_BENCH_SECS` overrides the time.
fn budget() -> Budget {
    let secs = std::env::var("II_BENCH_SECS").ok().and_then(|v| v.parse().ok()).unwrap_or(60);
    Budget { time: Duration::from_secs(secs), cases: 1_000_000, ..Budget::default() }
}

/// A single proof longer than this is reported once, not sampled by criterion
/// (ten samples would take minutes).
const SAMPLED: Duration = Duration::from_secs(3);

fn bench_goal(group: &mut Group<'_>, family: &str, n: usize, hyps: Vec<Axiom>, goal: Obligation) {
    let label = format!("{family}/{n}");
    if std::env::var("II_BENCH_ONLY").is_ok_and(|only| !label.contains(&only)) {
        return;
    }
    let started = Instant::now();
    let ctx = Context::new(laws(), hyps).expect("the kernel accepts the hypotheses");
    eprintln!("{label}: context built in {:.2?}", started.elapsed());
    match prove_once(&label, &ctx, &goal, budget()) {
        None if n <= 100 => panic!("{label}: every family must be proved at size 100"),
        None => eprintln!("{label}: not benched (not proved within the budget)"),
        Some(t) if t > SAMPLED => eprintln!("{label}: not sampled (one proof took {t:.2?})"),
        Some(_) => {
            group.bench_with_input(BenchmarkId::from_parameter(n), &goal, |b, goal| {
                b.iter(|| black_box(prover::prove(&ctx, goal, budget())))
            });
        }
    }
}

type Group<'a> = criterion::BenchmarkGroup<'a, criterion::measurement::WallTime>;

fn configure<'a>(c: &'a mut Criterion, name: &str) -> Group<'a> {
    let mut group = c.benchmark_group(name);
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    group
}

/// `pN ⇒ p0` over one chain of `n` equations: the cone is the whole chain.
fn chain_end(c: &mut Criterion) {
    let mut group = configure(c, "chain_end");
    for n in whole_cone_sizes() {
        let mut hyps = Vec::new();
        chain("p", n, &mut hyps);
        bench_goal(&mut group, "chain_end", n, hyps, implies(&format!("p{n}"), "p0"));
    }
    group.finish();
}

/// `p4 ⇒ p0` over the same chains: the cone is 4 equations whatever `n`.
fn chain_start(c: &mut Criterion) {
    let mut group = configure(c, "chain_start");
    for n in sizes() {
        let mut hyps = Vec::new();
        chain("p", n, &mut hyps);
        bench_goal(&mut group, "chain_start", n, hyps, implies("p4", "p0"));
    }
    group.finish();
}

/// Two chains of `n/2` equations with `p0 · q0 = 0*`; goal `p(n/2) · q(n/2) = 0*`.
fn interlock(c: &mut Criterion) {
    let mut group = configure(c, "interlock");
    for n in whole_cone_sizes() {
        let mut hyps = Vec::new();
        chain("p", n / 2, &mut hyps);
        chain("q", n / 2, &mut hyps);
        hyps.push(eq("interlock".into(), exclusive_lhs("p0", "q0"), term(|b| b.zero())));
        let top = format!("{}", n / 2);
        bench_goal(
            &mut group,
            "interlock",
            n,
            hyps,
            exclusive(&format!("p{top}"), &format!("q{top}")),
        );
    }
    group.finish();
}

fn exclusive_lhs(a: &str, b: &str) -> Expr {
    exclusive(a, b).lhs
}

/// Goal `t1 · e = 0*` at the root of a fan-in of `n` equations.
fn fan_in(c: &mut Criterion) {
    let mut group = configure(c, "tree");
    for n in whole_cone_sizes() {
        bench_goal(&mut group, "tree", n, tree(n), exclusive("t1", "e"));
    }
    group.finish();
}

/// P2 of copy 0 among `n/10` copies of H1–H10 with every signal renamed per copy.
fn water_private(c: &mut Criterion) {
    let mut group = configure(c, "water_private");
    for n in sizes() {
        let (hyps, goal) = water_copies(n / 10, &[]);
        bench_goal(&mut group, "water_private", n, hyps, goal);
    }
    group.finish();
}

/// The same, but the sensors `L_flow`, `H_flow`, `SP_fail` are shared by every copy.
fn water_shared(c: &mut Criterion) {
    let mut group = configure(c, "water_shared");
    for n in sizes() {
        let (hyps, goal) = water_copies(n / 10, &["L_flow", "H_flow", "SP_fail"]);
        bench_goal(&mut group, "water_shared", n, hyps, goal);
    }
    group.finish();
}

/// The paper's properties one by one, all P1–P4 together, and the whole session from the file.
fn water_paper(c: &mut Criterion) {
    let mut group = configure(c, "water_paper");
    let (hyps, goals) = water();
    let ctx = Context::new(laws(), hyps).expect("the kernel accepts H1-H10");
    let p1_p4: Vec<&(String, Obligation)> =
        goals.iter().filter(|(n, _)| n.starts_with('P')).collect();
    assert_eq!(p1_p4.len(), 6, "P1a, P1b, P2, P3, P4a, P4b");
    for (label, goal) in &p1_p4 {
        let once = prove_once(label, &ctx, goal, Budget::default());
        assert!(once.is_some(), "{label} must be proved");
        group.bench_with_input(BenchmarkId::new("property", label), goal, |b, goal| {
            b.iter(|| black_box(prover::prove(&ctx, goal, Budget::default())))
        });
    }
    group.bench_function("P1-P4", |b| {
        b.iter(|| {
            for (_, goal) in &p1_p4 {
                black_box(prover::prove(&ctx, goal, Budget::default()));
            }
        })
    });
    let paths = vec![WATER.to_string()];
    let opts = report::Options::default();
    let run = report::run_free(&paths, &opts).expect("the water plant file loads");
    assert_eq!(run.summary.proved, run.properties.len(), "every water property proved");
    group.bench_function("file_end_to_end", |b| {
        b.iter(|| black_box(report::run_free(&paths, &opts).expect("loads")))
    });
    group.finish();
}

criterion_group!(
    benches,
    water_paper,
    chain_start,
    chain_end,
    interlock,
    fan_in,
    water_private,
    water_shared
);
criterion_main!(benches);
