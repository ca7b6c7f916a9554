//! Exact evaluation of a term on an assignment of signals (and delay metavariables).
//!
//! A node's kind (signal or delay) is given by its position: the root and the
//! arguments of `·`, `+`, `¬`, `SR`, `RS` and the signal argument of a timer
//! are signals; the delay argument of a timer and the arguments of delay
//! arithmetic are delays. A `Name` in a delay position is a delay
//! metavariable, looked up in [`Assignment::delays`]. Terms are DAGs: every
//! node is evaluated at most once per kind, without recursion.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;

use num_traits::Signed;

use super::signal::{Signal, Time, format_time};
use crate::term::{Delay, Expr, Id, Language, Symbol, Term, initial_values};

/// Values for the free names of a term, on a common horizon.
#[derive(Clone, PartialEq, Eq)]
pub struct Assignment {
    /// The horizon `H`: every signal is defined on `(0, H]`.
    pub horizon: Time,
    /// The signal of each signal name.
    pub signals: BTreeMap<Symbol, Signal>,
    /// The delay of each delay metavariable.
    pub delays: BTreeMap<Symbol, Delay>,
    /// The scan cycle, for `pre` (signals of a program's scans); `None` for free signals.
    pub cycle: Option<Time>,
}

impl Assignment {
    /// An assignment with no names, on `(0, horizon]`.
    pub fn new(horizon: Time) -> Assignment {
        Assignment { horizon, signals: BTreeMap::new(), delays: BTreeMap::new(), cycle: None }
    }
}

impl fmt::Display for Assignment {
    /// One name a line: `a = (0,1):0 @1:1 (1,2]:0`, `d = 0.5s`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "horizon {}", format_time(&self.horizon))?;
        for (name, delay) in &self.delays {
            write!(f, "\n{name} = {delay}")?;
        }
        for (name, signal) in &self.signals {
            write!(f, "\n{name} = {signal}")?;
        }
        Ok(())
    }
}

impl fmt::Debug for Assignment {
    /// Compact and exact: `Assignment { horizon: 4, d = 1s, a = (0,1):0 @1:1 (1,4]:1 }`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Assignment {{ horizon: {}", format_time(&self.horizon))?;
        for (name, delay) in &self.delays {
            write!(f, ", {name} = {delay}")?;
        }
        for (name, signal) in &self.signals {
            write!(f, ", {name} = {signal}")?;
        }
        write!(f, " }}")
    }
}

/// Why a term could not be evaluated.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EvalError {
    /// A signal name with no signal in the assignment.
    UnboundSignal(Symbol),
    /// A delay metavariable with no delay in the assignment.
    UnboundDelay(Symbol),
    /// A delay (a literal or delay arithmetic) where a signal is expected.
    DelayWhereSignalExpected(String),
    /// A signal where a delay is expected.
    SignalWhereDelayExpected(String),
    /// The assignment's horizon is not positive.
    NonPositiveHorizon,
    /// A signal the term reads has another horizon than the assignment.
    HorizonMismatch(Symbol),
    /// `pre` with no scan cycle (free signals have no scans).
    PreWithoutCycle,
    /// The term is empty, or a node refers to a child that does not precede it.
    Malformed(String),
}

impl fmt::Display for EvalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EvalError::UnboundSignal(n) => write!(f, "the signal `{n}` has no value"),
            EvalError::UnboundDelay(n) => write!(f, "the delay `{n}` has no value"),
            EvalError::DelayWhereSignalExpected(t) => {
                write!(f, "`{t}` is a delay where a signal is expected")
            }
            EvalError::SignalWhereDelayExpected(t) => {
                write!(f, "`{t}` is a signal where a delay is expected")
            }
            EvalError::NonPositiveHorizon => write!(f, "the horizon must be positive"),
            EvalError::PreWithoutCycle => write!(f, "`pre` needs a scan cycle"),
            EvalError::HorizonMismatch(n) => {
                write!(f, "the signal `{n}` is not given on the assignment's horizon")
            }
            EvalError::Malformed(why) => write!(f, "malformed term: {why}"),
        }
    }
}

impl std::error::Error for EvalError {}

/// What a node is used as.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Signal,
    Delay,
}

/// The kinds each node of `expr` is needed as, when `top` is needed as `kind`.
/// Checks that every reachable child precedes its parent.
fn demands(expr: &Expr, top: Id, kind: Kind) -> Result<(Vec<bool>, Vec<bool>), EvalError> {
    let nodes = expr.as_ref();
    let top = usize::from(top);
    if top >= nodes.len() {
        return Err(EvalError::Malformed(format!(
            "node {top} is not in a term of {} nodes",
            nodes.len()
        )));
    }
    let mut sig = vec![false; top + 1];
    let mut del = vec![false; top + 1];
    match kind {
        Kind::Signal => sig[top] = true,
        Kind::Delay => del[top] = true,
    }
    for i in (0..=top).rev() {
        if !sig[i] && !del[i] {
            continue;
        }
        let node = &nodes[i];
        for &child in node.children() {
            if usize::from(child) >= i {
                return Err(EvalError::Malformed(format!(
                    "node {i} refers to node {} that does not precede it",
                    usize::from(child)
                )));
            }
        }
        if sig[i] {
            match node {
                Term::Ton([d, f]) | Term::Tof([f, d]) => {
                    del[usize::from(*d)] = true;
                    sig[usize::from(*f)] = true;
                }
                Term::DMax(_) | Term::DMin(_) | Term::DAdd(_) | Term::Delay(_) => {
                    return Err(EvalError::DelayWhereSignalExpected(describe(expr, i)));
                }
                _ => {
                    for &c in node.children() {
                        sig[usize::from(c)] = true;
                    }
                }
            }
        }
        if del[i] {
            match node {
                Term::DMax(_) | Term::DMin(_) | Term::DAdd(_) => {
                    for &c in node.children() {
                        del[usize::from(c)] = true;
                    }
                }
                Term::Delay(_) | Term::Name(_) => {}
                _ => return Err(EvalError::SignalWhereDelayExpected(describe(expr, i))),
            }
        }
    }
    Ok((sig, del))
}

/// A short rendering of node `i` for error messages (bounded; never panics).
fn describe(expr: &Expr, i: usize) -> String {
    let mut out = String::new();
    render(expr, i, &mut out);
    if out.chars().count() > 60 {
        let cut: String = out.chars().take(57).collect();
        format!("{cut}...")
    } else {
        out
    }
}

fn render(expr: &Expr, i: usize, out: &mut String) {
    if out.len() > 60 {
        return;
    }
    let Some(node) = expr.as_ref().get(i) else {
        out.push('?');
        return;
    };
    let children = node.children();
    if children.is_empty() {
        out.push_str(&node.to_string());
        return;
    }
    out.push('(');
    out.push_str(&node.to_string());
    for &c in children {
        out.push(' ');
        let c = usize::from(c);
        if c < i {
            render(expr, c, out);
        } else {
            out.push('?');
        }
    }
    out.push(')');
}

fn check_env(env: &Assignment) -> Result<(), EvalError> {
    if !env.horizon.is_positive() {
        return Err(EvalError::NonPositiveHorizon);
    }
    Ok(())
}

/// The signal and the delay value of each node (`None` where not needed).
type Values = (Vec<Option<Signal>>, Vec<Option<Delay>>);

/// Evaluates the node `top` of `expr` as `kind`; returns (signals, delays) per node.
fn evaluate(expr: &Expr, top: Id, kind: Kind, env: &Assignment) -> Result<Values, EvalError> {
    let (need_sig, need_del) = demands(expr, top, kind)?;
    let nodes = expr.as_ref();
    let n = need_sig.len();
    let mut sig: Vec<Option<Signal>> = vec![None; n];
    let mut del: Vec<Option<Delay>> = vec![None; n];
    let init = if nodes.iter().any(|t| matches!(t, Term::Pre(_))) {
        initial_values(expr)
    } else {
        Vec::new()
    };
    let missing = || EvalError::Malformed("a child was not evaluated".to_string());
    for i in 0..n {
        let node = &nodes[i];
        if need_del[i] {
            let get = |c: &Id| del[usize::from(*c)].clone().ok_or_else(missing);
            let value = match node {
                Term::Delay(d) => d.clone(),
                Term::Name(name) => {
                    env.delays.get(name).cloned().ok_or(EvalError::UnboundDelay(*name))?
                }
                Term::DMax([a, b]) => get(a)?.dmax(&get(b)?),
                Term::DMin([a, b]) => get(a)?.dmin(&get(b)?),
                Term::DAdd([a, b]) => get(a)?.dadd(&get(b)?),
                _ => return Err(EvalError::SignalWhereDelayExpected(describe(expr, i))),
            };
            del[i] = Some(value);
        }
        if need_sig[i] {
            let s = |c: &Id| sig[usize::from(*c)].as_ref().ok_or_else(missing);
            let d = |c: &Id| del[usize::from(*c)].as_ref().ok_or_else(missing);
            let value = match node {
                Term::Zero => Signal::constant(env.horizon.clone(), false),
                Term::One => Signal::constant(env.horizon.clone(), true),
                Term::And([a, b]) => s(a)?.and(s(b)?),
                Term::Or([a, b]) => s(a)?.or(s(b)?),
                Term::Not(a) => s(a)?.not(),
                Term::Pre(a) => {
                    let cycle = env.cycle.as_ref().ok_or(EvalError::PreWithoutCycle)?;
                    s(a)?.delayed(cycle, init[usize::from(*a)])
                }
                Term::Ton([dd, f]) => s(f)?.ton(d(dd)?),
                Term::Tof([f, dd]) => s(f)?.tof(d(dd)?),
                Term::Sr([a, b]) => Signal::sr(s(a)?, s(b)?),
                Term::Rs([a, b]) => Signal::rs(s(a)?, s(b)?),
                Term::Name(name) => {
                    let signal = env.signals.get(name).ok_or(EvalError::UnboundSignal(*name))?;
                    if *signal.horizon() != env.horizon {
                        return Err(EvalError::HorizonMismatch(*name));
                    }
                    signal.clone()
                }
                Term::DMax(_) | Term::DMin(_) | Term::DAdd(_) | Term::Delay(_) => {
                    return Err(EvalError::DelayWhereSignalExpected(describe(expr, i)));
                }
            };
            sig[i] = Some(value);
        }
    }
    Ok((sig, del))
}

/// The signal denoted by the root of `expr` under `env`.
pub fn eval(expr: &Expr, env: &Assignment) -> Result<Signal, EvalError> {
    let len = expr.as_ref().len();
    if len == 0 {
        return Err(EvalError::Malformed("the term is empty".to_string()));
    }
    eval_signal(expr, Id::from(len - 1), env)
}

/// The signal denoted by the subterm of `expr` rooted at `id` under `env`.
pub fn eval_signal(expr: &Expr, id: Id, env: &Assignment) -> Result<Signal, EvalError> {
    check_env(env)?;
    let (mut sig, _) = evaluate(expr, id, Kind::Signal, env)?;
    sig.get_mut(usize::from(id))
        .and_then(Option::take)
        .ok_or_else(|| EvalError::Malformed("the root was not evaluated".to_string()))
}

/// The delay denoted by the subterm of `expr` rooted at `id` under `env`: a
/// literal, a delay metavariable bound in `env.delays`, or delay arithmetic.
pub fn eval_delay(expr: &Expr, id: Id, env: &Assignment) -> Result<Delay, EvalError> {
    let (_, mut del) = evaluate(expr, id, Kind::Delay, env)?;
    del.get_mut(usize::from(id))
        .and_then(Option::take)
        .ok_or_else(|| EvalError::Malformed("the root was not evaluated".to_string()))
}

/// The free names of the term rooted at the root of `expr`: signal names and
/// delay metavariables (by position), for building assignments.
pub fn free_names(expr: &Expr) -> Result<(BTreeSet<Symbol>, BTreeSet<Symbol>), EvalError> {
    let len = expr.as_ref().len();
    if len == 0 {
        return Err(EvalError::Malformed("the term is empty".to_string()));
    }
    let (sig, del) = demands(expr, Id::from(len - 1), Kind::Signal)?;
    let mut signals = BTreeSet::new();
    let mut delays = BTreeSet::new();
    for (i, node) in expr.as_ref().iter().enumerate().take(sig.len()) {
        if let Term::Name(name) = node {
            if sig[i] {
                signals.insert(*name);
            }
            if del[i] {
                delays.insert(*name);
            }
        }
    }
    Ok((signals, delays))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::term::sexp;
    use num_bigint::BigInt;

    fn int(n: i64) -> Time {
        Time::from_integer(BigInt::from(n))
    }

    fn env() -> Assignment {
        let mut env = Assignment::new(int(10));
        env.signals.insert(
            Symbol::from("a"),
            Signal::from_steps(int(10), false, &[(int(1), true), (int(6), false)]).unwrap(),
        );
        env.signals.insert(Symbol::from("b"), Signal::constant(int(10), true));
        env.delays.insert(Symbol::from("d"), "2s".parse::<Delay>().unwrap());
        env
    }

    #[test]
    fn evaluates_names_and_metavariables() {
        let e = env();
        let v = eval(&sexp("(& a (ton d b))"), &e).unwrap();
        let want = Signal::from_steps(int(10), false, &[(int(2), true), (int(6), false)]).unwrap();
        assert_eq!(v, want);
        let d = sexp("(dadd d (dmax 1s 0.5s))");
        assert_eq!(eval_delay(&d, crate::term::root(&d), &e).unwrap().to_string(), "3s");
    }

    #[test]
    fn reports_errors() {
        let e = env();
        assert_eq!(eval(&sexp("(& a c)"), &e), Err(EvalError::UnboundSignal(Symbol::from("c"))));
        assert_eq!(eval(&sexp("(ton k a)"), &e), Err(EvalError::UnboundDelay(Symbol::from("k"))));
        assert!(matches!(eval(&sexp("(& a 1s)"), &e), Err(EvalError::DelayWhereSignalExpected(_))));
        assert!(matches!(
            eval(&sexp("(ton (& a b) a)"), &e),
            Err(EvalError::SignalWhereDelayExpected(_))
        ));
        assert!(matches!(eval(&Expr::default(), &e), Err(EvalError::Malformed(_))));
        let mut bad = e.clone();
        bad.horizon = int(5);
        assert_eq!(eval(&sexp("a"), &bad), Err(EvalError::HorizonMismatch(Symbol::from("a"))));
        bad.horizon = int(0);
        assert_eq!(eval(&sexp("0*"), &bad), Err(EvalError::NonPositiveHorizon));
        for err in [EvalError::UnboundSignal(Symbol::from("x")), EvalError::Malformed("m".into())] {
            assert!(!err.to_string().is_empty());
        }
    }

    #[test]
    fn malformed_children_are_errors_not_panics() {
        let nodes = vec![Term::Not(Id::from(0))];
        let expr: Expr = nodes.into();
        assert!(matches!(eval(&expr, &env()), Err(EvalError::Malformed(_))));
        let nodes = vec![Term::Not(Id::from(7)), Term::One];
        let expr: Expr = nodes.into();
        assert!(matches!(eval_signal(&expr, Id::from(0), &env()), Err(EvalError::Malformed(_))));
        assert!(matches!(eval_delay(&expr, Id::from(9), &env()), Err(EvalError::Malformed(_))));
    }

    #[test]
    fn unreachable_nodes_are_not_evaluated_and_names_are_found() {
        // `zz` is unbound but not reachable from the root.
        let mut b = crate::term::Builder::default();
        let _ = b.name("zz");
        let a = b.name("a");
        let d = b.name("d");
        let t = b.ton(d, a);
        let _ = b.and(t, a);
        let expr = b.finish();
        assert!(eval(&expr, &env()).is_ok());
        let (s, d) = free_names(&expr).unwrap();
        assert_eq!(s.into_iter().collect::<Vec<_>>(), vec![Symbol::from("a")]);
        assert_eq!(d.into_iter().collect::<Vec<_>>(), vec![Symbol::from("d")]);
    }

    #[test]
    fn deep_terms_do_not_overflow_the_stack() {
        // Built as a vector: egg's `RecExpr::add` is quadratic in debug builds.
        let mut nodes = vec![Term::Name(Symbol::from("a"))];
        for i in 0..20_001 {
            nodes.push(Term::Not(Id::from(i)));
        }
        let expr: Expr = nodes.into();
        let e = env();
        assert_eq!(eval(&expr, &e).unwrap(), e.signals[&Symbol::from("a")].not());
        // A shared subterm used as a signal and as a delay is an error, not a panic.
        let mut b = crate::term::Builder::default();
        let d = b.delay("1s".parse().unwrap());
        let _ = b.ton(d, d);
        assert!(matches!(eval(&b.finish(), &e), Err(EvalError::DelayWhereSignalExpected(_))));
    }
}
