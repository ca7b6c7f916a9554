//! Laws as data: the files of `theories/`, read into the kernel's axioms.
//!
//! The theory files are compiled into the binary, so `ii-prove` works from any
//! directory; [`standard`] reads them, and [`check_law`] validates one law
//! against the exact semantics (the test suite runs it on every law).

use crate::diag::{Diagnostic, Sources};
use crate::kernel::{Axiom, CYCLE, Cmp, Rel};
use crate::semantics::falsify::{self, Condition, Relation, SampleError, Witness};
use crate::syntax::{
    self, DelayComparison, Goal, Law, NoProgram, Relation as GoalRelation, SideCondition, Statement,
};
use crate::term::{Delay, Expr, Language, Symbol, Term, matches, root};

/// Matches a law's side against a whole ground term, extending `sigma` (the search and
/// the script checker find instances with it; the kernel re-checks every use).
pub fn match_side(
    law: &Axiom,
    side: &Expr,
    term: &Expr,
    sigma: &mut std::collections::BTreeMap<Symbol, Expr>,
) -> bool {
    let (top, at) = (&side[root(side)], &term[root(term)]);
    let variable = |s: &Symbol| law.signal_vars.contains(s) || law.delay_vars.contains(s);
    // Most tries fail at the root: there, without gathering the variables.
    if !matches!(top, Term::Name(s) if variable(s)) && !top.matches(at) {
        return false;
    }
    let vars: Vec<Symbol> = law.signal_vars.iter().chain(&law.delay_vars).cloned().collect();
    matches(side, root(side), &vars, &law.delay_vars, term, root(term), sigma)
}

/// The theory files shipped with the prover: path (as shown to users) and text.
pub const THEORY_FILES: &[(&str, &str)] = &[
    ("theories/boolean.ii", include_str!("../theories/boolean.ii")),
    ("theories/memory.ii", include_str!("../theories/memory.ii")),
    ("theories/timer.ii", include_str!("../theories/timer.ii")),
    ("theories/scan.ii", include_str!("../theories/scan.ii")),
];

/// A law with where it was written.
#[derive(Clone, Debug)]
pub struct LawEntry {
    /// The kernel's form of the law.
    pub axiom: Axiom,
    /// The file it comes from.
    pub file: String,
    /// Its line in that file.
    pub line: usize,
    /// The statement as written back by the printer.
    pub statement: Statement<Law>,
}

/// The laws of the theory files.
#[derive(Clone, Debug, Default)]
pub struct Theory {
    /// Every law, in file order.
    pub laws: Vec<LawEntry>,
}

impl Theory {
    /// The kernel axioms of every law.
    pub fn axioms(&self) -> Vec<Axiom> {
        self.laws.iter().map(|l| l.axiom.clone()).collect()
    }
    /// A law by name.
    pub fn get(&self, name: &str) -> Option<&LawEntry> {
        self.laws.iter().find(|l| l.axiom.name == name)
    }
}

/// A statement's relation as the kernel's.
pub(crate) fn relation(r: GoalRelation) -> Rel {
    match r {
        GoalRelation::Equals => Rel::Eq,
        GoalRelation::Implies => Rel::Implies,
    }
}

fn comparison(c: DelayComparison) -> Cmp {
    match c {
        DelayComparison::Ge => Cmp::Ge,
        DelayComparison::Gt => Cmp::Gt,
        DelayComparison::Le => Cmp::Le,
        DelayComparison::Lt => Cmp::Lt,
        DelayComparison::Eq => Cmp::Eq,
    }
}

/// The kernel axiom of a law statement.
pub fn axiom_of(statement: &Statement<Law>) -> Axiom {
    let law = &statement.value;
    let mut axiom = Axiom::ground(
        statement.name.clone(),
        law.goal.lhs_with_after(),
        relation(law.goal.relation),
        law.goal.rhs_with_after(),
    );
    axiom.signal_vars = law.signal_vars.clone();
    axiom.delay_vars = law.delay_vars.clone();
    for condition in &law.conditions {
        match condition {
            SideCondition::Delay { lhs, op, rhs } => {
                axiom.delay_conditions.push((lhs.clone(), comparison(*op), rhs.clone()))
            }
            SideCondition::Signal(goal) => axiom.signal_conditions.push((
                goal.lhs_with_after(),
                relation(goal.relation),
                goal.rhs_with_after(),
            )),
        }
    }
    axiom
}

/// Reads the laws of one theory text registered in `sources`.
pub fn read(sources: &Sources, file: usize) -> Result<Vec<LawEntry>, Vec<Diagnostic>> {
    let doc = syntax::parse_document(sources, file, &NoProgram)
        .map_err(|errors| errors.into_iter().map(Diagnostic::from).collect::<Vec<_>>())?;
    Ok(doc
        .laws
        .iter()
        .map(|statement| LawEntry {
            axiom: axiom_of(statement),
            file: sources.name(file).to_string(),
            line: sources.line_col(file, statement.span.start).0,
            statement: statement.clone(),
        })
        .collect())
}

/// The standard theory: every file of [`THEORY_FILES`]. The sources are added to `sources`
/// so that errors in them can be rendered.
pub fn standard(sources: &mut Sources) -> Result<Theory, Vec<Diagnostic>> {
    let mut theory = Theory::default();
    for (name, text) in THEORY_FILES {
        let file = sources.add(*name, *text);
        theory.laws.extend(read(sources, file)?);
    }
    Ok(theory)
}

/// The falsifier's relation for a kernel relation.
pub fn sample_relation(rel: Rel) -> Relation {
    match rel {
        Rel::Eq => Relation::Equal,
        Rel::Implies => Relation::Implies,
    }
}

/// The side conditions of a law as sampling conditions.
fn conditions(axiom: &Axiom) -> Vec<Condition> {
    use std::cmp::Ordering::{Equal, Greater, Less};
    let mut out: Vec<Condition> = axiom
        .delay_conditions
        .iter()
        .map(|(lhs, cmp, rhs)| Condition::Delay {
            lhs: lhs.clone(),
            accept: match cmp {
                Cmp::Ge => vec![Greater, Equal],
                Cmp::Gt => vec![Greater],
                Cmp::Le => vec![Less, Equal],
                Cmp::Lt => vec![Less],
                Cmp::Eq => vec![Equal],
            },
            rhs: rhs.clone(),
        })
        .collect();
    out.extend(axiom.signal_conditions.iter().map(|(lhs, rel, rhs)| Condition::Signal {
        lhs: lhs.clone(),
        rel: sample_relation(*rel),
        rhs: rhs.clone(),
    }));
    out
}

/// Checks a law on `cases` random exact assignments that satisfy its side conditions.
/// `Ok(n)`: it held on `n` samples; `Err`: a witness that it is false, or why it
/// could not be sampled.
pub fn check_law(axiom: &Axiom, cases: usize, seed: u64) -> Result<usize, LawFailure> {
    match falsify::falsify(
        &axiom.lhs,
        sample_relation(axiom.rel),
        &axiom.rhs,
        &conditions(axiom),
        cases,
        seed,
        None,
    ) {
        Ok(Ok(n)) => Ok(n),
        Ok(Err(witness)) => Err(LawFailure::Witness(witness)),
        Err(e) => Err(LawFailure::Sampling(e)),
    }
}

/// One random instance of a law on a scan run of a 1 s cycle: its two sides over the
/// signals `v0`, `v1`, … and their values scan by scan (`runs`; as exact step signals
/// in `env`).
#[derive(Clone, Debug)]
pub struct ScanInstance {
    /// The left side, instantiated.
    pub lhs: Expr,
    /// The right side, instantiated.
    pub rhs: Expr,
    /// Each signal's value at each scan.
    pub runs: std::collections::BTreeMap<String, Vec<bool>>,
    /// The same runs as exact signals constant on each scan, and the cycle.
    pub env: crate::semantics::Assignment,
}

impl ScanInstance {
    /// The number of scans.
    pub fn scans(&self) -> usize {
        self.runs.values().next().map_or(1, Vec::len)
    }

    /// The instant at which scan `k` (0-based) is read: inside the first scan, then at
    /// each scan's start (a step signal is right-continuous).
    pub fn instant(k: usize) -> crate::semantics::Time {
        use crate::semantics::Time;
        if k == 0 { Time::new(1.into(), 2.into()) } else { Time::from_integer(k.into()) }
    }
}

/// `cases` random instances of a law on scan runs: every signal metavariable is a random
/// run of a signal or of its complement (so that its value before the first scan is 0 or
/// 1), every delay one to four whole cycles (on scans a delay is a whole number of
/// cycles; `cycle` itself is one), and the side conditions hold at every scan (a run
/// that breaks a signal condition is mended by clearing the value that breaks it, or
/// drawn again).
pub fn scan_instances(axiom: &Axiom, cases: usize, seed: u64) -> Result<Vec<ScanInstance>, String> {
    use crate::semantics::{Assignment, Signal, Time, eval};
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let one = Time::from_integer(1.into());
    let on_a_side =
        |v: &Symbol| [&axiom.lhs, &axiom.rhs].iter().any(|e| e.as_ref().contains(&Term::Name(*v)));
    let cycle = Delay::new(one.clone()).map_err(|e| e.to_string())?;
    let (mut out, mut tries) = (Vec::new(), 0);
    while out.len() < cases {
        tries += 1;
        if tries > 20 * cases {
            return Err(format!("only {} of {tries} runs satisfy the side conditions", out.len()));
        }
        let scans = 1 + (next() % 12) as usize;
        let mut sigma = std::collections::BTreeMap::new();
        for v in axiom.delay_vars.iter().filter(|v| on_a_side(v) || v.as_str() != CYCLE) {
            let d = Delay::new(Time::from_integer((1 + next() % 4).into()))
                .map_err(|e| e.to_string())?;
            sigma.insert(*v, Expr::from(vec![Term::Delay(d)]));
        }
        axiom.bind_cycle(Some(&cycle), &mut sigma);
        if axiom.check_delay_conditions(&sigma).is_err() {
            continue;
        }
        let mut runs = std::collections::BTreeMap::new();
        let mut negated = Vec::new();
        for (i, v) in axiom.signal_vars.iter().enumerate() {
            let name = format!("v{i}");
            runs.insert(name.clone(), (0..scans).map(|_| next() % 2 == 1).collect::<Vec<bool>>());
            let term = crate::term::name(&name);
            negated.push(next() % 2 == 1);
            let term = if negated[i] { crate::term::not(&term) } else { term };
            sigma.insert(*v, term);
        }
        let side = |e: &Expr| crate::term::instantiate(e, &sigma).ok_or("an unbound variable");
        let conditions: Vec<(Expr, Rel, Expr)> = axiom
            .signal_conditions
            .iter()
            .map(|(l, rel, r)| Ok((side(l)?, *rel, side(r)?)))
            .collect::<Result<_, String>>()?;
        for _mend in 0..=8 {
            let mut env = Assignment::new(Time::from_integer(scans.into()));
            env.cycle = Some(one.clone());
            for (name, run) in &runs {
                let changes: Vec<(Time, bool)> = (1..scans)
                    .filter(|k| run[*k] != run[k - 1])
                    .map(|k| (Time::from_integer(k.into()), run[k]))
                    .collect();
                let signal = Signal::from_steps(env.horizon.clone(), run[0], &changes)
                    .map_err(|e| format!("{e:?}"))?;
                env.signals.insert(Symbol::from(name.as_str()), signal);
            }
            let mut broken = Vec::new();
            for (l, rel, r) in &conditions {
                let (a, b) = (
                    eval(l, &env).map_err(|e| e.to_string())?,
                    eval(r, &env).map_err(|e| e.to_string())?,
                );
                broken.extend((0..scans).filter(|k| {
                    let (x, y) = (
                        a.value_at(&ScanInstance::instant(*k)),
                        b.value_at(&ScanInstance::instant(*k)),
                    );
                    !(x == y || (*rel == Rel::Implies && !x))
                }));
            }
            if broken.is_empty() {
                let (lhs, rhs) = (side(&axiom.lhs)?, side(&axiom.rhs)?);
                out.push(ScanInstance { lhs, rhs, runs, env });
                break;
            }
            // Clear one signal's term at each broken scan (a condition `f·g = 0*`).
            for k in broken {
                let i = (next() as usize) % negated.len().max(1);
                if let Some(run) = runs.get_mut(&format!("v{i}")) {
                    run[k] = negated[i];
                }
            }
        }
    }
    Ok(out)
}

/// Checks a law on `cases` random scan runs ([`scan_instances`]; every law: those with
/// `pre` are about scans only, and the others must hold there too) by exact evaluation
/// at every scan. `Ok(n)`: it held on `n` runs; `Err(text)`: the run where it fails.
pub fn check_scan_law(axiom: &Axiom, cases: usize, seed: u64) -> Result<usize, String> {
    let instances = scan_instances(axiom, cases, seed)?;
    for inst in &instances {
        let (l, r) = (&inst.lhs, &inst.rhs);
        let a = crate::semantics::eval(l, &inst.env).map_err(|e| e.to_string())?;
        let b = crate::semantics::eval(r, &inst.env).map_err(|e| e.to_string())?;
        for k in 0..inst.scans() {
            let t = ScanInstance::instant(k);
            let (x, y) = (a.value_at(&t), b.value_at(&t));
            if !(x == y || (axiom.rel == Rel::Implies && !x)) {
                return Err(format!("`{l}` is {x} and `{r}` is {y} at scan {k} of {}", inst.env));
            }
        }
    }
    Ok(instances.len())
}

/// Why a law did not validate.
#[derive(Clone, Debug)]
pub enum LawFailure {
    /// Signals under which it is false.
    Witness(Box<Witness>),
    /// It could not be sampled.
    Sampling(SampleError),
}

/// A goal of a `.ii` file as a kernel relation with `after` folded in.
pub fn goal_parts(goal: &Goal) -> (crate::term::Expr, Rel, crate::term::Expr) {
    (goal.lhs_with_after(), relation(goal.relation), goal.rhs_with_after())
}
