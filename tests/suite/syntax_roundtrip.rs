//! Parse → print → parse is the identity, for every `.ii` file of the repository
//! and for random terms, in both notations.

use crate::common;

use std::path::Path;

use ii_prove::diag::Sources;
use ii_prove::syntax::{
    Claim, Document, Goal, Lookup, NoProgram, Notation, RuleRef, Scope, ScriptProof, SideCondition,
    document_to_string, parse_document, parse_expression, term_to_string,
};
use ii_prove::term::{Builder, Delay, Expr, Id, Term, same};
use num_bigint::BigInt;
use num_rational::BigRational;
use proptest::prelude::*;

/// Every name is a signal of the program (files may name a ladder program we do not
/// load), except the file's own `input`s.
struct AnyName(Vec<String>);

impl AnyName {
    fn for_text(text: &str) -> AnyName {
        let inputs = text
            .lines()
            .filter_map(|l| l.trim().strip_prefix("input "))
            .flat_map(|rest| rest.split('/').next().unwrap_or("").split(','))
            .map(|n| n.trim().to_string())
            .collect();
        AnyName(inputs)
    }
}

impl Scope for AnyName {
    fn lookup(&self, name: &str) -> Lookup {
        if self.0.iter().any(|n| n == name) {
            return Lookup::Unknown;
        }
        Lookup::Signal(name.to_string())
    }
    fn names(&self) -> Vec<String> {
        Vec::new()
    }
    fn scans(&self) -> bool {
        true
    }
    /// A cycle every duration of the repository's files is a whole number of (1 µs), so
    /// that patterns which need one resolve.
    fn cycle(&self) -> Option<ii_prove::term::Delay> {
        ii_prove::term::Delay::from_micros(1).ok()
    }
    /// Every comparison names its own signal, as written.
    fn comparison(
        &self,
        op: ii_prove::syntax::CmpOp,
        a: &ii_prove::syntax::IntOperand,
        b: &ii_prove::syntax::IntOperand,
    ) -> Result<String, (String, Option<String>)> {
        Ok(format!("[{a} {} {b}]", op.symbol()))
    }
}

fn same_goal(a: &Goal, b: &Goal) -> bool {
    same(&a.lhs, &b.lhs) && same(&a.rhs, &b.rhs) && a.relation == b.relation && a.after == b.after
}

fn same_condition(a: &SideCondition, b: &SideCondition) -> bool {
    match (a, b) {
        (
            SideCondition::Delay { lhs, op, rhs },
            SideCondition::Delay { lhs: l2, op: o2, rhs: r2 },
        ) => same(lhs, l2) && op == o2 && same(rhs, r2),
        (SideCondition::Signal(x), SideCondition::Signal(y)) => same_goal(x, y),
        _ => false,
    }
}

fn same_claim(a: &Claim, b: &Claim) -> bool {
    let rules = |r: &[RuleRef]| r.iter().map(|x| x.name.clone()).collect::<Vec<_>>();
    let proofs = match (&a.proof, &b.proof) {
        (ScriptProof::Auto(_), ScriptProof::Auto(_)) => true,
        (ScriptProof::Induction(_), ScriptProof::Induction(_)) => true,
        (ScriptProof::By(x, _), ScriptProof::By(y, _)) => rules(x) == rules(y),
        (
            ScriptProof::Calc { start: s1, steps: v1, .. },
            ScriptProof::Calc { start: s2, steps: v2, .. },
        ) => {
            same(s1, s2)
                && v1.len() == v2.len()
                && v1.iter().zip(v2).all(|(x, y)| {
                    x.relation == y.relation
                        && same(&x.term, &y.term)
                        && rules(&x.rules) == rules(&y.rules)
                })
        }
        _ => false,
    };
    a.kind == b.kind && same_goal(&a.goal, &b.goal) && proofs
}

fn same_document(a: &Document, b: &Document) -> Result<(), String> {
    let names = |v: &[(String, _)]| v.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    if a.program.as_ref().map(|p| &p.0) != b.program.as_ref().map(|p| &p.0) {
        return Err("program differs".into());
    }
    if names(&a.inputs) != names(&b.inputs) || names(&a.delays) != names(&b.delays) {
        return Err("declarations differ".into());
    }
    for (x, y) in [(&a.assumptions, &b.assumptions), (&a.properties, &b.properties)] {
        if x.len() != y.len() {
            return Err("statement count differs".into());
        }
        for (s, t) in x.iter().zip(y) {
            if s.name != t.name || !same_goal(&s.value, &t.value) {
                return Err(format!("statement `{}` differs", s.name));
            }
        }
    }
    if a.claims.len() != b.claims.len() {
        return Err("claim count differs".into());
    }
    for (s, t) in a.claims.iter().zip(&b.claims) {
        if !same_claim(&s.value, &t.value) || s.name != t.name {
            return Err(format!("claim `{}` differs", s.name));
        }
    }
    if a.laws.len() != b.laws.len() {
        return Err("law count differs".into());
    }
    for (s, t) in a.laws.iter().zip(&b.laws) {
        let (l, m) = (&s.value, &t.value);
        let conditions = l.conditions.len() == m.conditions.len()
            && l.conditions.iter().zip(&m.conditions).all(|(c, d)| same_condition(c, d));
        if s.name != t.name
            || !same_goal(&l.goal, &m.goal)
            || !conditions
            || l.signal_vars != m.signal_vars
            || l.delay_vars != m.delay_vars
        {
            return Err(format!("law `{}` differs", s.name));
        }
    }
    Ok(())
}

#[test]
fn every_repository_file_round_trips() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["theories", "examples", "proofs", "tests/data"] {
        files.extend(common::files_with(&root.join(dir), "ii"));
    }
    // The parse-error cases are malformed on purpose.
    files.retain(|p| !p.starts_with(root.join("tests/data/parse_err")));
    files.sort();
    assert!(files.len() >= 3, "found only {files:?}");
    for path in files {
        let text = std::fs::read_to_string(&path).expect("readable");
        let mut sources = Sources::new();
        let file = sources.add(path.display().to_string(), text);
        // Files about free signals resolve without a program; the others against a
        // scope in which every name is a program signal.
        let any_name = AnyName::for_text(sources.text(file));
        let scope: &dyn Scope = match parse_document(&sources, file, &NoProgram) {
            Ok(_) => &NoProgram,
            Err(_) => &any_name,
        };
        let doc = parse_document(&sources, file, scope)
            .unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
        for notation in [Notation::Paper, Notation::Ascii] {
            let printed = document_to_string(&doc, notation);
            let again_file = sources.add(format!("{} (printed)", path.display()), printed.clone());
            let again = parse_document(&sources, again_file, scope).unwrap_or_else(|e| {
                panic!("{}: printed text fails: {e:?}\n{printed}", path.display())
            });
            if let Err(why) = same_document(&doc, &again) {
                panic!("{}: {why}\n{printed}", path.display());
            }
        }
    }
}

// ---- random terms ----

#[derive(Clone, Debug)]
enum D {
    Lit(Delay),
    Var(&'static str),
    Max(Box<D>, Box<D>),
    Min(Box<D>, Box<D>),
    Add(Box<D>, Box<D>),
}

impl D {
    fn has_var(&self) -> bool {
        match self {
            D::Lit(_) => false,
            D::Var(_) => true,
            D::Max(a, b) | D::Min(a, b) | D::Add(a, b) => a.has_var() || b.has_var(),
        }
    }
    fn build(&self, b: &mut Builder) -> Id {
        match self {
            D::Lit(d) => b.delay(d.clone()),
            D::Var(v) => b.name(v),
            D::Max(x, y) | D::Min(x, y) | D::Add(x, y) => {
                let (x, y) = (x.build(b), y.build(b));
                b.add(match self {
                    D::Max(..) => Term::DMax([x, y]),
                    D::Min(..) => Term::DMin([x, y]),
                    _ => Term::DAdd([x, y]),
                })
            }
        }
    }
}

#[derive(Clone, Debug)]
enum T {
    Name(&'static str),
    Zero,
    One,
    Not(Box<T>),
    And(Box<T>, Box<T>),
    Or(Box<T>, Box<T>),
    Sr(Box<T>, Box<T>),
    Rs(Box<T>, Box<T>),
    Ton(D, Box<T>),
    Tof(Box<T>, D),
}

impl T {
    fn has_var(&self) -> bool {
        match self {
            T::Name(_) | T::Zero | T::One => false,
            T::Not(x) => x.has_var(),
            T::And(x, y) | T::Or(x, y) | T::Sr(x, y) | T::Rs(x, y) => x.has_var() || y.has_var(),
            T::Ton(d, x) | T::Tof(x, d) => d.has_var() || x.has_var(),
        }
    }
    fn build(&self, b: &mut Builder) -> Id {
        match self {
            T::Name(n) => b.name(n),
            T::Zero => b.zero(),
            T::One => b.one(),
            T::Not(x) => {
                let x = x.build(b);
                b.not(x)
            }
            T::And(x, y) | T::Or(x, y) | T::Sr(x, y) | T::Rs(x, y) => {
                let (x, y) = (x.build(b), y.build(b));
                b.add(match self {
                    T::And(..) => Term::And([x, y]),
                    T::Or(..) => Term::Or([x, y]),
                    T::Sr(..) => Term::Sr([x, y]),
                    _ => Term::Rs([x, y]),
                })
            }
            T::Ton(d, x) => {
                let d = d.build(b);
                let x = x.build(b);
                b.ton(d, x)
            }
            T::Tof(x, d) => {
                let x = x.build(b);
                let d = d.build(b);
                b.tof(x, d)
            }
        }
    }
    fn expr(&self) -> Expr {
        let mut b = Builder::default();
        self.build(&mut b);
        b.finish()
    }
}

const NAMES: &[&str] = &["a", "b", "L1_pump", "Xpi@90", "law", "_x", "T", "max", "SR", "pre_Q"];

fn delay_literal() -> impl Strategy<Value = Delay> {
    (1u64..2_000_000, 0u32..8).prop_map(|(n, scale)| {
        let value =
            BigRational::new(BigInt::from(n), num_traits::pow(BigInt::from(10), scale as usize));
        Delay::new(value).expect("positive decimal")
    })
}

fn delay_term() -> impl Strategy<Value = D> {
    let leaf = prop_oneof![
        delay_literal().prop_map(D::Lit),
        prop_oneof![Just("d1"), Just("d2")].prop_map(D::Var),
    ];
    leaf.prop_recursive(3, 8, 2, |inner| {
        (inner.clone(), inner, 0u8..3).prop_map(|(x, y, op)| {
            // Arithmetic on literals alone is folded by the parser: keep a variable in.
            let x = if x.has_var() || y.has_var() { x } else { D::Var("d1") };
            let (x, y) = (Box::new(x), Box::new(y));
            match op {
                0 => D::Max(x, y),
                1 => D::Min(x, y),
                _ => D::Add(x, y),
            }
        })
    })
}

fn delay_any() -> impl Strategy<Value = D> {
    prop_oneof![
        3 => delay_literal().prop_map(D::Lit),
        1 => delay_term(),
    ]
}

fn signal_term() -> impl Strategy<Value = T> {
    let leaf = prop_oneof![
        4 => prop::sample::select(NAMES).prop_map(T::Name),
        1 => Just(T::Zero),
        1 => Just(T::One),
    ];
    leaf.prop_recursive(6, 48, 2, |inner| {
        prop_oneof![
            inner.clone().prop_map(|x| T::Not(Box::new(x))),
            (inner.clone(), inner.clone()).prop_map(|(x, y)| T::And(Box::new(x), Box::new(y))),
            (inner.clone(), inner.clone()).prop_map(|(x, y)| T::Or(Box::new(x), Box::new(y))),
            (inner.clone(), inner.clone()).prop_map(|(x, y)| T::Sr(Box::new(x), Box::new(y))),
            (inner.clone(), inner.clone()).prop_map(|(x, y)| T::Rs(Box::new(x), Box::new(y))),
            (delay_any(), inner.clone()).prop_map(|(d, x)| T::Ton(d, Box::new(x))),
            (inner, delay_any()).prop_map(|(x, d)| T::Tof(Box::new(x), d)),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn random_terms_print_and_parse_back(t in signal_term()) {
        let expr = t.expr();
        for notation in [Notation::Paper, Notation::Ascii] {
            let printed = term_to_string(&expr, notation);
            // As a law: signal names are metavariables, `d1`, `d2` declared delays.
            let mut sources = Sources::new();
            let text = format!("delay d1, d2\nlaw t: {printed} = 0*\n");
            let file = sources.add("law.ii", text.clone());
            let doc = parse_document(&sources, file, &NoProgram);
            prop_assert!(doc.is_ok(), "{text}\n{:?}", doc.err());
            let doc = doc.unwrap();
            prop_assert!(same(&doc.laws[0].value.goal.lhs, &expr), "{text}");
            // Without delay variables, also as a REPL expression over inputs.
            if !t.has_var() {
                let file = sources.add("repl", printed.clone());
                let inputs: Vec<String> = NAMES.iter().map(|s| s.to_string()).collect();
                let again = parse_expression(&sources, file, &NoProgram, &inputs);
                prop_assert!(again.is_ok(), "{printed}\n{:?}", again.err());
                prop_assert!(same(&again.unwrap(), &expr), "{printed}");
            }
        }
    }
}
