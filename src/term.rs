//! Signal terms of the II algebra: the one term type of the crate (an egg language).
//!
//! A term is an [`Expr`] (an egg `RecExpr<Term>`) whose root is its last node.
//! Delays are exact positive rationals of seconds ([`Delay`]); there is no
//! floating point anywhere. The kernel depends on this module and on nothing
//! else, so everything here is small and obviously correct.

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

pub use egg::{Id, Language, RecExpr, Symbol};

/// A positive, exact duration in seconds whose decimal expansion is finite.
///
/// Every duration a user can write (`5s`, `0.1s`, `250ms`, `T#1m30s`) and every
/// sum, maximum or minimum of such durations is a finite decimal, so the
/// printer can always write a delay back in the `.ii` syntax.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Delay(BigRational);

/// Why a duration was rejected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DelayError {
    /// Zero or negative: `0s` is not a delay.
    NotPositive,
    /// Not a finite decimal number of seconds (for example one third of a second).
    NotDecimal,
    /// The text is not a duration literal.
    Malformed(String),
}

impl fmt::Display for DelayError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DelayError::NotPositive => write!(f, "a delay must be positive (0s is not a delay)"),
            DelayError::NotDecimal => {
                write!(f, "a delay must be a finite decimal number of seconds")
            }
            DelayError::Malformed(why) => write!(f, "{why}"),
        }
    }
}

impl std::error::Error for DelayError {}

/// The units a duration may carry, with their length in seconds as a fraction.
pub const UNITS: &[(&str, i64, i64)] = &[
    ("us", 1, 1_000_000),
    ("ms", 1, 1_000),
    ("s", 1, 1),
    ("min", 60, 1),
    ("m", 60, 1),
    ("h", 3_600, 1),
    ("d", 86_400, 1),
];

impl Delay {
    /// A delay of `seconds`, if it is positive and a finite decimal.
    pub fn new(seconds: BigRational) -> Result<Delay, DelayError> {
        if !seconds.is_positive() {
            return Err(DelayError::NotPositive);
        }
        let mut den = seconds.denom().clone();
        for p in [2u32, 5] {
            let p = BigInt::from(p);
            while (&den % &p).is_zero() {
                den /= &p;
            }
        }
        if !den.is_one() {
            return Err(DelayError::NotDecimal);
        }
        Ok(Delay(seconds))
    }

    /// A delay of a whole number of microseconds (LDmicro stores timers this way).
    pub fn from_micros(us: u64) -> Result<Delay, DelayError> {
        Delay::new(BigRational::new(BigInt::from(us), BigInt::from(1_000_000)))
    }

    /// The delay in seconds, exactly.
    pub fn seconds(&self) -> &BigRational {
        &self.0
    }

    /// The larger of two delays.
    pub fn dmax(&self, other: &Delay) -> Delay {
        if self >= other { self.clone() } else { other.clone() }
    }

    /// The smaller of two delays.
    pub fn dmin(&self, other: &Delay) -> Delay {
        if self <= other { self.clone() } else { other.clone() }
    }

    /// The sum of two delays (still positive and decimal).
    pub fn dadd(&self, other: &Delay) -> Delay {
        Delay(&self.0 + &other.0)
    }

    /// Is this delay a whole number of `cycle`s? On a program's scans only such delays
    /// have one reading (`shared/spec/semantics.md`, "Programs, scan by scan").
    pub fn is_whole_cycles(&self, cycle: &Delay) -> bool {
        (&self.0 / &cycle.0).is_integer()
    }

    /// The whole multiples of `cycle` nearest this delay: the largest below it (none when
    /// it is shorter than one cycle) and the smallest above it.
    pub fn nearest_whole_cycles(&self, cycle: &Delay) -> (Option<Delay>, Delay) {
        let n = (&self.0 / &cycle.0).floor();
        let below = Delay::new(&n * &cycle.0).ok();
        let above = Delay((n + BigRational::one()) * &cycle.0);
        (below, above)
    }
}

/// Every delay literal of `e` is a whole number of `cycle`s (then so is every delay its
/// arithmetic computes); the first that is not, otherwise.
pub fn sub_cycle_delay(e: &Expr, cycle: &Delay) -> Option<Delay> {
    e.as_ref().iter().find_map(|node| match node {
        Term::Delay(d) if !d.is_whole_cycles(cycle) => Some(d.clone()),
        _ => None,
    })
}

/// Parses a decimal number (`5`, `0.25`, `1.`) into an exact rational.
pub fn parse_decimal(text: &str) -> Option<BigRational> {
    let (int, frac) = match text.split_once('.') {
        Some((i, f)) => (i, f),
        None => (text, ""),
    };
    if int.is_empty() && frac.is_empty() {
        return None;
    }
    let all_digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
    if !all_digits(int) || !all_digits(frac) {
        return None;
    }
    let digits = format!("{int}{frac}");
    let numer: BigInt = if digits.is_empty() { BigInt::zero() } else { digits.parse().ok()? };
    let denom = num_traits::pow(BigInt::from(10), frac.len());
    Some(BigRational::new(numer, denom))
}

/// Writes a finite-decimal rational in plain decimal notation (`5`, `0.25`).
pub fn format_decimal(value: &BigRational) -> Option<String> {
    let negative = value.is_negative();
    let value = value.abs();
    let mut scale = 0usize;
    let mut scaled = value.clone();
    while !scaled.is_integer() {
        scaled *= BigRational::from_integer(BigInt::from(10));
        scale += 1;
        if scale > 4096 {
            return None;
        }
    }
    let digits = scaled.to_integer().to_string();
    let body = if scale == 0 {
        digits
    } else {
        let padded = format!("{digits:0>width$}", width = scale + 1);
        let (i, f) = padded.split_at(padded.len() - scale);
        format!("{i}.{f}")
    };
    Some(if negative { format!("-{body}") } else { body })
}

impl FromStr for Delay {
    type Err = DelayError;

    /// Reads `<decimal><unit>` with a unit of [`UNITS`], e.g. `5s`, `0.5s`, `250ms`.
    fn from_str(text: &str) -> Result<Delay, DelayError> {
        let split = text
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .ok_or_else(|| DelayError::Malformed(format!("`{text}` has no unit")))?;
        let (number, unit) = text.split_at(split);
        let value = parse_decimal(number)
            .ok_or_else(|| DelayError::Malformed(format!("`{number}` is not a number")))?;
        let (_, num, den) = UNITS
            .iter()
            .find(|(name, _, _)| *name == unit)
            .ok_or_else(|| DelayError::Malformed(format!("`{unit}` is not a unit of time")))?;
        Delay::new(value * BigRational::new(BigInt::from(*num), BigInt::from(*den)))
    }
}

impl fmt::Display for Delay {
    /// Writes the delay in seconds (`5s`, `0.25s`); it parses back with `FromStr`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = format_decimal(&self.0).ok_or(fmt::Error)?;
        write!(f, "{text}s")
    }
}

egg::define_language! {
    /// One node of a signal term.
    ///
    /// `Ton` is `d/f` with children `[d, f]`; `Tof` is `f/d` with children
    /// `[f, d]`, in the order they are written. `Pre` is `pre f`, the value of `f`
    /// one scan earlier (programs only: `shared/spec/semantics.md`, "Programs, scan by scan"). `DMax`, `DMin` and `DAdd` are
    /// delay arithmetic, used by laws such as `d1/(d2/f) = (d1+d2)/f`.
    #[allow(missing_docs)]
    pub enum Term {
        "0*" = Zero,
        "1*" = One,
        "&" = And([Id; 2]),
        "+" = Or([Id; 2]),
        "!" = Not(Id),
        "pre" = Pre(Id),
        "ton" = Ton([Id; 2]),
        "tof" = Tof([Id; 2]),
        "sr" = Sr([Id; 2]),
        "rs" = Rs([Id; 2]),
        "dmax" = DMax([Id; 2]),
        "dmin" = DMin([Id; 2]),
        "dadd" = DAdd([Id; 2]),
        Delay(Delay),
        Name(Symbol),
    }
}

/// A whole term; its root is the last node.
pub type Expr = RecExpr<Term>;

/// The root of a non-empty term.
pub fn root(expr: &Expr) -> Id {
    Id::from(expr.as_ref().len() - 1)
}

/// Is this node a delay (a literal or delay arithmetic) rather than a signal?
pub fn is_delay_node(node: &Term) -> bool {
    matches!(node, Term::Delay(_) | Term::DMax(_) | Term::DMin(_) | Term::DAdd(_))
}

/// Is this node a timer, a memory or a previous-scan value (an atom of the Boolean
/// skeleton whose value is not a function of the present instant)?
pub fn is_temporal_node(node: &Term) -> bool {
    matches!(node, Term::Ton(_) | Term::Tof(_) | Term::Sr(_) | Term::Rs(_) | Term::Pre(_))
}

/// Does the term mention `pre` anywhere?
pub fn mentions_pre(expr: &Expr) -> bool {
    expr.as_ref().iter().any(|t| matches!(t, Term::Pre(_)))
}

/// Copies the subterm rooted at `id` of `expr` into `out`, returning its new id.
pub fn copy_into(expr: &Expr, id: Id, out: &mut Expr) -> Id {
    let node = expr[id].clone().map_children(|child| copy_into(expr, child, out));
    out.add(node)
}

/// The subterm of `expr` rooted at `id`, as a term of its own.
pub fn subterm(expr: &Expr, id: Id) -> Expr {
    let mut out = Expr::default();
    copy_into(expr, id, &mut out);
    out
}

/// Structural equality of the trees at `a` in `x` and `b` in `y`
/// (independent of node order and sharing inside the two vectors).
pub fn same_tree(x: &Expr, a: Id, y: &Expr, b: Id) -> bool {
    let (m, n) = (&x[a], &y[b]);
    m.matches(n) && m.children().iter().zip(n.children()).all(|(&c, &d)| same_tree(x, c, y, d))
}

/// A hash of the tree at `id` in `expr` that depends on the tree alone (operators,
/// names, shape; a delay literal only as a delay): equal trees ([`same_tree`]) hash
/// alike wherever their nodes sit, so an index can find a subterm without copying it.
pub fn tree_hash(expr: &Expr, id: Id) -> u64 {
    fn mix(h: u64, word: u64) -> u64 {
        (h.rotate_left(5) ^ word).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95)
    }
    let node = &expr[id];
    let tag: u64 = match node {
        Term::Zero => 1,
        Term::One => 2,
        Term::And(_) => 3,
        Term::Or(_) => 4,
        Term::Not(_) => 5,
        Term::Pre(_) => 6,
        Term::Ton(_) => 7,
        Term::Tof(_) => 8,
        Term::Sr(_) => 9,
        Term::Rs(_) => 10,
        Term::DMax(_) => 11,
        Term::DMin(_) => 12,
        Term::DAdd(_) => 13,
        Term::Delay(_) => 14,
        Term::Name(s) => 15 | u64::from(std::num::NonZeroU32::from(*s).get()) << 8,
    };
    node.children().iter().fold(mix(0, tag), |h, &c| mix(h, tree_hash(expr, c)))
}

/// Structural equality of two whole terms.
pub fn same(x: &Expr, y: &Expr) -> bool {
    same_tree(x, root(x), y, root(y))
}

/// Builds terms node by node; a thin convenience over [`Expr::add`].
#[derive(Default, Debug, Clone)]
pub struct Builder {
    /// The term under construction.
    pub expr: Expr,
}

impl Builder {
    /// Adds a node and returns its id.
    pub fn add(&mut self, node: Term) -> Id {
        self.expr.add(node)
    }
    /// A named signal.
    pub fn name(&mut self, name: &str) -> Id {
        self.add(Term::Name(Symbol::from(name)))
    }
    /// A delay literal.
    pub fn delay(&mut self, delay: Delay) -> Id {
        self.add(Term::Delay(delay))
    }
    /// `0*`.
    pub fn zero(&mut self) -> Id {
        self.add(Term::Zero)
    }
    /// `1*`.
    pub fn one(&mut self) -> Id {
        self.add(Term::One)
    }
    /// `a · b`.
    pub fn and(&mut self, a: Id, b: Id) -> Id {
        self.add(Term::And([a, b]))
    }
    /// `a + b`.
    pub fn or(&mut self, a: Id, b: Id) -> Id {
        self.add(Term::Or([a, b]))
    }
    /// `¬a`.
    pub fn not(&mut self, a: Id) -> Id {
        self.add(Term::Not(a))
    }
    /// `pre a`.
    pub fn pre(&mut self, a: Id) -> Id {
        self.add(Term::Pre(a))
    }
    /// `d/f`.
    pub fn ton(&mut self, d: Id, f: Id) -> Id {
        self.add(Term::Ton([d, f]))
    }
    /// `f/d`.
    pub fn tof(&mut self, f: Id, d: Id) -> Id {
        self.add(Term::Tof([f, d]))
    }
    /// `SR(s, r)`.
    pub fn sr(&mut self, s: Id, r: Id) -> Id {
        self.add(Term::Sr([s, r]))
    }
    /// `RS(s, r)`.
    pub fn rs(&mut self, s: Id, r: Id) -> Id {
        self.add(Term::Rs([s, r]))
    }
    /// Copies a whole term in and returns the id of its root.
    pub fn term(&mut self, expr: &Expr) -> Id {
        copy_into(expr, root(expr), &mut self.expr)
    }
    /// Finishes the term (its root is the last node added).
    pub fn finish(self) -> Expr {
        self.expr
    }
}

/// First-order matching of a pattern (a law side; `vars` are its variables, `delay_vars`
/// those standing for delays) against the ground subterm at `t`, extending `sigma`.
pub fn matches(
    pat: &Expr,
    p: Id,
    vars: &[Symbol],
    delay_vars: &[Symbol],
    term: &Expr,
    t: Id,
    sigma: &mut BTreeMap<Symbol, Expr>,
) -> bool {
    if let Term::Name(v) = &pat[p]
        && vars.contains(v)
    {
        let wants_delay = delay_vars.contains(v);
        if wants_delay != is_delay_node(&term[t]) {
            return false;
        }
        return match sigma.get(v) {
            Some(bound) => same_tree(bound, root(bound), term, t),
            None => {
                sigma.insert(*v, subterm(term, t));
                true
            }
        };
    }
    let (m, n) = (&pat[p], &term[t]);
    m.matches(n)
        && m.children()
            .iter()
            .zip(n.children())
            .all(|(&c, &d)| matches(pat, c, vars, delay_vars, term, d, sigma))
}

/// A law side with its variables replaced (variables must all be bound).
pub fn instantiate(pat: &Expr, sigma: &BTreeMap<Symbol, Expr>) -> Option<Expr> {
    fn go(pat: &Expr, p: Id, sigma: &BTreeMap<Symbol, Expr>, out: &mut Expr) -> Option<Id> {
        if let Term::Name(v) = &pat[p]
            && let Some(value) = sigma.get(v)
        {
            return Some(copy_into(value, root(value), out));
        }
        let mut failed = false;
        let node = pat[p].clone().map_children(|c| {
            go(pat, c, sigma, out).unwrap_or_else(|| {
                failed = true;
                c
            })
        });
        if failed { None } else { Some(out.add(node)) }
    }
    let mut out = Expr::default();
    go(pat, root(pat), sigma, &mut out).map(|_| out)
}

/// The value of a ground delay expression built from literals, `max`, `min` and `+`.
pub fn fold_delay(e: &Expr, id: Id) -> Option<Delay> {
    match &e[id] {
        Term::Delay(d) => Some(d.clone()),
        Term::DMax([a, b]) => Some(fold_delay(e, *a)?.dmax(&fold_delay(e, *b)?)),
        Term::DMin([a, b]) => Some(fold_delay(e, *a)?.dmin(&fold_delay(e, *b)?)),
        Term::DAdd([a, b]) => Some(fold_delay(e, *a)?.dadd(&fold_delay(e, *b)?)),
        _ => None,
    }
}

/// Each node's value before the first scan (`shared/spec/semantics.md`, "Programs, scan
/// by scan"): names, timers and memories 0, the Boolean operators applied, `pre f` the
/// value of `f`.
pub fn initial_values(e: &Expr) -> Vec<bool> {
    let mut init: Vec<bool> = Vec::with_capacity(e.as_ref().len());
    for node in e.as_ref() {
        let at = |c: &Id| init[usize::from(*c)];
        let v = match node {
            Term::One => true,
            Term::Not(a) => !at(a),
            Term::And([a, b]) => at(a) && at(b),
            Term::Or([a, b]) => at(a) || at(b),
            Term::Pre(a) => at(a),
            _ => false,
        };
        init.push(v);
    }
    init
}

/// The value of `e` before the first scan.
pub fn initially(e: &Expr) -> bool {
    initial_values(e)[usize::from(root(e))]
}

/// `e` at the first scan: every `pre f` replaced by the value `f` has before it
/// (names, timers and memories 0).
pub fn at_first_scan(e: &Expr) -> Expr {
    let init = initial_values(e);
    let mut out = Expr::default();
    let mut ids: Vec<Id> = Vec::with_capacity(e.as_ref().len());
    for (i, node) in e.as_ref().iter().enumerate() {
        let node = match node {
            Term::Pre(_) if init[i] => Term::One,
            Term::Pre(_) => Term::Zero,
            n => n.clone().map_children(|c| ids[usize::from(c)]),
        };
        ids.push(out.add(node));
    }
    subterm(&out, root(&out))
}

/// The constant `1*` or `0*` as a whole term.
pub fn constant(value: bool) -> Expr {
    Expr::from(vec![if value { Term::One } else { Term::Zero }])
}

/// A signal name as a whole term.
pub fn name(name: &str) -> Expr {
    Expr::from(vec![Term::Name(Symbol::from(name))])
}

fn pair(a: &Expr, b: &Expr, op: fn([Id; 2]) -> Term) -> Expr {
    let mut out = Expr::default();
    let (x, y) = (copy_into(a, root(a), &mut out), copy_into(b, root(b), &mut out));
    out.add(op([x, y]));
    out
}

/// `a · b` as a whole term.
pub fn and(a: &Expr, b: &Expr) -> Expr {
    pair(a, b, Term::And)
}

/// `a + b` as a whole term.
pub fn or(a: &Expr, b: &Expr) -> Expr {
    pair(a, b, Term::Or)
}

/// `¬a` as a whole term.
pub fn not(a: &Expr) -> Expr {
    // One node more than `a`, allocated once (kept terms are not twice their size).
    let mut nodes = Vec::with_capacity(a.as_ref().len() + 1);
    nodes.extend_from_slice(a.as_ref());
    nodes.push(Term::Not(root(a)));
    Expr::from(nodes)
}

/// `a · ¬b` as a whole term.
pub fn and_not(a: &Expr, b: &Expr) -> Expr {
    and(a, &not(b))
}

/// Parses an egg s-expression such as `(& a (ton 5s b))`; for tests and internal use.
pub fn sexp(text: &str) -> Expr {
    text.parse().unwrap_or_else(|e| panic!("bad internal s-expression {text:?}: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delays_parse_exactly_and_print_back() {
        let tenth: Delay = "0.1s".parse().unwrap();
        assert_eq!(tenth.seconds(), &BigRational::new(BigInt::from(1), BigInt::from(10)));
        assert_eq!(tenth.to_string(), "0.1s");
        let ms: Delay = "250ms".parse().unwrap();
        assert_eq!(ms.to_string(), "0.25s");
        assert_eq!("1.25min".parse::<Delay>().unwrap().to_string(), "75s");
        assert_eq!("2h".parse::<Delay>().unwrap().to_string(), "7200s");
        assert_eq!("0s".parse::<Delay>(), Err(DelayError::NotPositive));
        assert!(matches!("5".parse::<Delay>(), Err(DelayError::Malformed(_))));
        assert!(matches!("5parsec".parse::<Delay>(), Err(DelayError::Malformed(_))));
        let third = BigRational::new(BigInt::from(1), BigInt::from(3));
        assert_eq!(Delay::new(third), Err(DelayError::NotDecimal));
    }

    #[test]
    fn delay_arithmetic_is_exact() {
        let a: Delay = "0.3s".parse().unwrap();
        let b: Delay = "0.7s".parse().unwrap();
        assert_eq!(a.dadd(&b).to_string(), "1s");
        assert_eq!(a.dmax(&b), b);
        assert_eq!(a.dmin(&b), a);
        assert_eq!(Delay::from_micros(1_500_000).unwrap().to_string(), "1.5s");
    }

    #[test]
    fn sexp_round_trip_and_structural_equality() {
        let t = sexp("(& (ton 5s L1_Prod) (! (sr a (tof b 0.5s))))");
        let again: Expr = t.to_string().parse().unwrap();
        assert!(same(&t, &again));
        let mut b = Builder::default();
        let x = b.name("a");
        let y = b.name("b");
        let _ = b.and(x, y);
        assert!(same(&b.finish(), &sexp("(& a b)")));
        assert!(!same(&sexp("(& a b)"), &sexp("(& b a)")));
    }

    #[test]
    fn an_instance_is_a_tree_the_same_as_its_copy() {
        // A value with a shared node, and a pattern naming it twice.
        let mut b = Builder::default();
        let _stray = b.name("c");
        let x = b.name("a");
        let n = b.not(x);
        let _ = b.and(n, n);
        let value = b.finish();
        let mut sigma = BTreeMap::new();
        sigma.insert(Symbol::from("f"), value);
        sigma.insert(Symbol::from("d"), sexp("5s"));
        let instance = instantiate(&sexp("(+ (ton d f) (! f))"), &sigma).unwrap();
        assert!(same(&instance, &sexp("(+ (ton 5s (& (! a) (! a))) (! (& (! a) (! a))))")));
        assert_eq!(subterm(&instance, root(&instance)).as_ref(), instance.as_ref());
    }

    #[test]
    fn equal_trees_hash_alike_wherever_their_nodes_sit() {
        // `5s/a · ¬5s/a` with the timer shared and a node the root does not reach.
        let mut b = Builder::default();
        let _stray = b.name("c");
        let x = b.name("a");
        let d = b.delay("5s".parse().unwrap());
        let t = b.ton(d, x);
        let n = b.not(t);
        let _ = b.and(t, n);
        let shared = b.finish();
        let tree = sexp("(& (ton 5s a) (! (ton 5s a)))");
        assert_ne!(shared.as_ref(), tree.as_ref());
        assert!(same(&shared, &tree));
        assert_eq!(tree_hash(&shared, root(&shared)), tree_hash(&tree, root(&tree)));
        let Term::And([_, m]) = tree[root(&tree)] else { panic!("an `·` at the root") };
        assert_eq!(tree_hash(&shared, n), tree_hash(&tree, m));
        // Different trees: operator, name, order of children.
        let hash = |t: &str| {
            let e = sexp(t);
            tree_hash(&e, root(&e))
        };
        let all = [
            "(& a b)",
            "(& b a)",
            "(+ a b)",
            "(ton 5s a)",
            "(tof a 5s)",
            "(sr a b)",
            "(rs a b)",
            "(pre a)",
            "(! a)",
            "a",
            "b",
        ];
        for (i, x) in all.iter().enumerate() {
            for y in &all[i + 1..] {
                assert_ne!(hash(x), hash(y), "{x} and {y}");
            }
        }
    }
}
