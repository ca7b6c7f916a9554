//! The pretty-printer: terms, goals, statements and documents back to `.ii` text.
//!
//! Output parses back to the same tree ([`crate::term::same`]): parentheses are
//! minimal but faithful (the parser is left-associative, so `f·(g·h)` keeps its
//! parentheses and `(f·g)·h` prints flat), names that are not plain
//! identifiers are back-quoted, and long terms break at width 100.

use num_bigint::BigInt;
use num_rational::BigRational;
use pretty::RcDoc;

use super::lexer::Keyword;
use super::{
    Claim, ClaimKind, DelayComparison, Document, Goal, Law, Relation, RuleRef, ScriptProof,
    SideCondition, Statement,
};
use crate::term::{Delay, Expr, Id, Term, format_decimal, root};

/// Which symbols to print.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Notation {
    /// The paper's notation: `·`, `+`, `¬`, `⇒`.
    #[default]
    Paper,
    /// Plain ASCII: `.`, `+`, `!`, `=>`.
    Ascii,
}

/// Which keyword a goal statement is printed with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GoalKeyword {
    /// `assume NAME: ...`
    Assume,
    /// `property NAME: ...`
    Property,
}

/// The line width long terms are broken at.
pub const WIDTH: usize = 100;

type Doc = RcDoc<'static, ()>;

struct Symbols {
    and: &'static str,
    not: &'static str,
    implies: &'static str,
    ge: &'static str,
    le: &'static str,
}

fn symbols(n: Notation) -> Symbols {
    match n {
        Notation::Paper => Symbols { and: "·", not: "¬", implies: "⇒", ge: "≥", le: "≤" },
        Notation::Ascii => Symbols { and: ".", not: "!", implies: "=>", ge: ">=", le: "<=" },
    }
}

/// Writes a delay so that it parses back exactly (`5s`, `250ms`, `1.5s`).
pub fn delay_to_string(delay: &Delay) -> String {
    let seconds = delay.seconds();
    // A whole number of seconds (at least 1) is its digits.
    use num_traits::Signed;
    if seconds.is_integer() && seconds.numer().is_positive() {
        return format!("{}s", seconds.numer());
    }
    let thousand = BigRational::from_integer(BigInt::from(1000));
    let one = BigRational::from_integer(BigInt::from(1));
    let millis = seconds * &thousand;
    if seconds < &one && millis.is_integer() {
        return format!("{}ms", millis.to_integer());
    }
    match format_decimal(seconds) {
        Some(text) => format!("{text}s"),
        None => format!("{seconds}s"),
    }
}

/// Writes a name, back-quoted unless it is a plain identifier that is not a keyword.
pub fn name_to_string(name: &str) -> String {
    // A comparison atom's signal is its own notation.
    if name.starts_with('[') && name.ends_with(']') && !name.contains('`') {
        return name.to_string();
    }
    let mut chars = name.chars();
    let plain = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && Keyword::from_text(name).is_none();
    if plain { name.to_string() } else { format!("`{name}`") }
}

struct Printer<'a> {
    expr: &'a Expr,
    sym: Symbols,
}

fn text(s: impl Into<String>) -> Doc {
    RcDoc::text(s.into())
}

fn parens(doc: Doc) -> Doc {
    text("(").append(doc.nest(1)).append(text(")"))
}

impl Printer<'_> {
    fn prec(&self, id: Id) -> u8 {
        match &self.expr[id] {
            Term::Or(_) => 1,
            Term::And(_) => 2,
            Term::Ton(_) | Term::Tof(_) => 3,
            Term::Not(_) | Term::Pre(_) => 4,
            _ => 5,
        }
    }

    /// Collects the operands of a left-nested chain of one binary operator.
    fn spine(&self, id: Id, is_op: fn(&Term) -> Option<[Id; 2]>) -> Vec<Id> {
        let mut right = Vec::new();
        let mut cur = id;
        while let Some([l, r]) = is_op(&self.expr[cur]) {
            right.push(r);
            cur = l;
        }
        right.push(cur);
        right.reverse();
        right
    }

    fn infix(&self, ops: Vec<Id>, symbol: &'static str, min: u8) -> Doc {
        let mut iter = ops.into_iter();
        let mut doc = match iter.next() {
            Some(first) => self.signal(first, min),
            None => RcDoc::nil(),
        };
        for op in iter {
            doc = doc
                .append(RcDoc::line())
                .append(text(symbol))
                .append(text(" "))
                .append(self.signal(op, min));
        }
        doc.group().nest(2)
    }

    /// A signal term, in parentheses if its precedence is below `min`.
    fn signal(&self, id: Id, min: u8) -> Doc {
        let doc = match &self.expr[id] {
            Term::Zero => text("0*"),
            Term::One => text("1*"),
            Term::Name(n) => text(name_to_string(n.as_str())),
            Term::Or(_) => self.infix(
                self.spine(id, |t| match t {
                    Term::Or(c) => Some(*c),
                    _ => None,
                }),
                "+",
                2,
            ),
            Term::And(_) => self.infix(
                self.spine(id, |t| match t {
                    Term::And(c) => Some(*c),
                    _ => None,
                }),
                self.sym.and,
                3,
            ),
            Term::Not(x) => text(self.sym.not).append(self.signal(*x, 4)),
            Term::Pre(x) => text("pre ").append(self.signal(*x, 4)),
            Term::Ton([d, f]) => {
                let inner = if matches!(self.expr[*f], Term::Ton(_)) { 3 } else { 4 };
                self.delay_operand(*d).append(text("/")).append(self.signal(*f, inner))
            }
            Term::Tof([f, d]) => {
                let inner = if matches!(self.expr[*f], Term::Tof(_)) { 3 } else { 4 };
                self.signal(*f, inner).append(text("/")).append(self.delay_operand(*d))
            }
            Term::Sr([s, r]) | Term::Rs([s, r]) => {
                let f = if matches!(self.expr[id], Term::Sr(_)) { "SR(" } else { "RS(" };
                text(f)
                    .append(
                        self.signal(*s, 1)
                            .append(text(","))
                            .append(RcDoc::line())
                            .append(self.signal(*r, 1))
                            .group()
                            .nest(3),
                    )
                    .append(text(")"))
            }
            Term::Delay(_) | Term::DMax(_) | Term::DMin(_) | Term::DAdd(_) => {
                self.delay_operand(id)
            }
        };
        if self.prec(id) < min { parens(doc) } else { doc }
    }

    /// A delay where a single operand is expected (a `/` operand): sums in parentheses.
    fn delay_operand(&self, id: Id) -> Doc {
        match &self.expr[id] {
            Term::DAdd(_) => parens(self.delay_top(id)),
            Term::Delay(d) => text(delay_to_string(d)),
            Term::Name(n) => text(name_to_string(n.as_str())),
            Term::DMax([a, b]) | Term::DMin([a, b]) => {
                let f = if matches!(self.expr[id], Term::DMax(_)) { "max(" } else { "min(" };
                text(f)
                    .append(self.delay_top(*a))
                    .append(text(", "))
                    .append(self.delay_top(*b))
                    .append(text(")"))
            }
            _ => parens(self.signal(id, 0)),
        }
    }

    /// A delay at the top of a comparison or a `max` argument: sums need no parentheses.
    fn delay_top(&self, id: Id) -> Doc {
        match &self.expr[id] {
            Term::DAdd(_) => {
                let ops = self.spine(id, |t| match t {
                    Term::DAdd(c) => Some(*c),
                    _ => None,
                });
                RcDoc::intersperse(ops.into_iter().map(|op| self.delay_operand(op)), text(" + "))
            }
            _ => self.delay_operand(id),
        }
    }
}

fn render(doc: Doc) -> String {
    doc.pretty(WIDTH).to_string()
}

fn term_doc(expr: &Expr, notation: Notation) -> Doc {
    if expr.as_ref().is_empty() {
        return RcDoc::nil();
    }
    let printer = Printer { expr, sym: symbols(notation) };
    printer.signal(root(expr), 0)
}

fn delay_doc(expr: &Expr, notation: Notation) -> Doc {
    if expr.as_ref().is_empty() {
        return RcDoc::nil();
    }
    let printer = Printer { expr, sym: symbols(notation) };
    printer.delay_top(root(expr))
}

/// Writes a signal term.
pub fn term_to_string(expr: &Expr, notation: Notation) -> String {
    // A lone name, the most printed term (every signal of a counterexample), needs no
    // layout.
    if let [Term::Name(n)] = expr.as_ref() {
        return name_to_string(n.as_str());
    }
    render(term_doc(expr, notation))
}

fn goal_doc(goal: &Goal, notation: Notation) -> Doc {
    let body = relation_doc(&goal.lhs, goal.relation, &goal.rhs, notation);
    match &goal.after {
        Some(d) => text(format!("after {}: ", delay_to_string(d))).append(body),
        None => body,
    }
}

/// `lhs ⇒ rhs` or `lhs = rhs`, broken after `lhs` where it does not fit.
fn relation_doc(lhs: &Expr, relation: Relation, rhs: &Expr, notation: Notation) -> Doc {
    let rel = match relation {
        Relation::Implies => symbols(notation).implies,
        Relation::Equals => "=",
    };
    term_doc(lhs, notation)
        .append(
            RcDoc::line()
                .append(text(rel))
                .append(text(" "))
                .append(term_doc(rhs, notation))
                .nest(2),
        )
        .group()
}

/// Writes `assume NAME: lhs = rhs` (or `⇒`) at the end of `out`: what
/// [`goal_statement_to_string`] writes for the assumption of that goal, without building it.
pub fn push_assumption(
    out: &mut String,
    name: &str,
    lhs: &Expr,
    relation: Relation,
    rhs: &Expr,
    notation: Notation,
) {
    use std::fmt::Write;
    let doc = named("assume", name, relation_doc(lhs, relation, rhs, notation));
    let _ = write!(out, "{}", doc.pretty(WIDTH));
}

/// Writes a goal: `f ⇒ g`, `f = g`, `after 5s: f ⇒ g`.
pub fn goal_to_string(goal: &Goal, notation: Notation) -> String {
    render(goal_doc(goal, notation))
}

fn named(keyword: &str, name: &str, body: Doc) -> Doc {
    text(format!("{keyword} {}: ", name_to_string(name))).append(body.nest(2))
}

/// Writes `assume NAME: goal` or `property NAME: goal`.
pub fn goal_statement_to_string(
    keyword: GoalKeyword,
    statement: &Statement<Goal>,
    notation: Notation,
) -> String {
    render(goal_statement_doc(keyword, statement, notation))
}

fn goal_statement_doc(
    keyword: GoalKeyword,
    statement: &Statement<Goal>,
    notation: Notation,
) -> Doc {
    let keyword = match keyword {
        GoalKeyword::Assume => "assume",
        GoalKeyword::Property => "property",
    };
    named(keyword, &statement.name, goal_doc(&statement.value, notation))
}

fn condition_doc(c: &SideCondition, notation: Notation) -> Doc {
    match c {
        SideCondition::Signal(goal) => goal_doc(goal, notation),
        SideCondition::Delay { lhs, op, rhs } => {
            let sym = symbols(notation);
            let op = match op {
                DelayComparison::Ge => sym.ge,
                DelayComparison::Gt => ">",
                DelayComparison::Le => sym.le,
                DelayComparison::Lt => "<",
                DelayComparison::Eq => "=",
            };
            delay_doc(lhs, notation)
                .append(text(format!(" {op} ")))
                .append(delay_doc(rhs, notation))
        }
    }
}

fn law_doc(statement: &Statement<Law>, notation: Notation) -> Doc {
    let law = &statement.value;
    let mut body = goal_doc(&law.goal, notation);
    if !law.conditions.is_empty() {
        let conditions = RcDoc::intersperse(
            law.conditions.iter().map(|c| condition_doc(c, notation)),
            text(",").append(RcDoc::line()),
        );
        body = body
            .append(RcDoc::line().append(text("if ")).append(conditions.nest(3)).nest(2))
            .group();
    }
    named("law", &statement.name, body)
}

/// Writes `law NAME: lhs = rhs if cond, ...`.
pub fn law_to_string(statement: &Statement<Law>, notation: Notation) -> String {
    render(law_doc(statement, notation))
}

fn rules_to_string(rules: &[RuleRef]) -> String {
    let names: Vec<String> = rules.iter().map(|r| name_to_string(&r.name)).collect();
    names.join(", ")
}

/// Writes one step of a calculation: `  = term   [r1, r2]` (`⇒`/` =>` for an implication),
/// the term at column 4 like the calculation's first line.
pub fn step_to_string(
    relation: Relation,
    term: &Expr,
    rules: &[RuleRef],
    notation: Notation,
) -> String {
    let rel = match relation {
        Relation::Implies => symbols(notation).implies,
        Relation::Equals => "=",
    };
    let indent = if rel.chars().count() == 1 { "  " } else { " " };
    let term = term_to_string(term, notation).replace('\n', "\n      ");
    format!("{indent}{rel} {term}   [{}]", rules_to_string(rules))
}

/// Writes `theorem NAME: goal` (or `lemma`) and its proof: `by auto`, `by r1, r2`, or
/// `proof`, the calculation one step a line, `qed`.
pub fn claim_to_string(statement: &Statement<Claim>, notation: Notation) -> String {
    let claim = &statement.value;
    let keyword = match claim.kind {
        ClaimKind::Theorem => "theorem",
        ClaimKind::Lemma => "lemma",
    };
    let mut out = render(named(keyword, &statement.name, goal_doc(&claim.goal, notation)));
    out.push('\n');
    match &claim.proof {
        ScriptProof::Auto(_) => out.push_str("by auto\n"),
        ScriptProof::Induction(_) => out.push_str("by induction\n"),
        ScriptProof::By(rules, _) => out.push_str(&format!("by {}\n", rules_to_string(rules))),
        ScriptProof::Calc { start, steps, .. } => {
            out.push_str("proof\n");
            let start = term_to_string(start, notation).replace('\n', "\n      ");
            out.push_str(&format!("    {start}\n"));
            for step in steps {
                out.push_str(&step_to_string(step.relation, &step.term, &step.rules, notation));
                out.push('\n');
            }
            out.push_str("qed\n");
        }
    }
    out
}

fn names_line(keyword: &str, names: &[(String, crate::diag::Span)]) -> String {
    let list: Vec<String> = names.iter().map(|(n, _)| name_to_string(n)).collect();
    format!("{keyword} {}\n", list.join(", "))
}

/// Writes a whole document: `program`, `input`, `delay`, then the statements.
///
/// Abbreviations (`let`) are already expanded, so they do not appear.
pub fn document_to_string(doc: &Document, notation: Notation) -> String {
    let mut out = String::new();
    if let Some((path, _)) = &doc.program {
        let escaped = path.replace('\\', "\\\\").replace('"', "\\\"");
        out.push_str(&format!("program \"{escaped}\"\n"));
    }
    if !doc.inputs.is_empty() {
        out.push_str(&names_line("input", &doc.inputs));
    }
    if !doc.delays.is_empty() {
        out.push_str(&names_line("delay", &doc.delays));
    }
    for s in &doc.assumptions {
        out.push_str(&goal_statement_to_string(GoalKeyword::Assume, s, notation));
        out.push('\n');
    }
    for s in &doc.properties {
        out.push_str(&goal_statement_to_string(GoalKeyword::Property, s, notation));
        out.push('\n');
    }
    for s in &doc.laws {
        out.push_str(&law_to_string(s, notation));
        out.push('\n');
    }
    for s in &doc.claims {
        out.push('\n');
        out.push_str(&claim_to_string(s, notation));
    }
    out
}

/// A duration in µs as an IEC literal (`T#2s`, `T#1500ms`, `T#250us`), in the
/// largest of these units that divides it.
pub fn duration(us: u64) -> String {
    if us.is_multiple_of(1_000_000) {
        format!("T#{}s", us / 1_000_000)
    } else if us.is_multiple_of(1_000) {
        format!("T#{}ms", us / 1_000)
    } else {
        format!("T#{us}us")
    }
}

/// A signed duration in ns as an IEC literal (`T#-5s`, `T#1399999999ns`).
pub fn signed_duration_ns(ns: i64) -> String {
    let a = ns.unsigned_abs();
    let text = if a.is_multiple_of(1_000) { duration(a / 1_000) } else { format!("T#{a}ns") };
    if ns < 0 { text.replacen("T#", "T#-", 1) } else { text }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::term::sexp;

    #[test]
    fn minimal_faithful_parentheses() {
        let p = |s: &str| term_to_string(&sexp(s), Notation::Paper);
        let a = |s: &str| term_to_string(&sexp(s), Notation::Ascii);
        assert_eq!(p("(& (& f g) h)"), "f · g · h");
        assert_eq!(p("(& f (& g h))"), "f · (g · h)");
        assert_eq!(p("(+ f (& g h))"), "f + g · h");
        assert_eq!(p("(& (+ f g) h)"), "(f + g) · h");
        assert_eq!(a("(tof (! f) 5s)"), "!f/5s");
        assert_eq!(a("(! (ton 5s f))"), "!(5s/f)");
        assert_eq!(a("(ton 2s (ton 5s f))"), "2s/5s/f");
        assert_eq!(a("(tof (tof f 1s) 2s)"), "f/1s/2s");
        assert_eq!(a("(tof (ton 1s f) 2s)"), "(1s/f)/2s");
        assert_eq!(a("(ton 1s (tof f 2s))"), "1s/(f/2s)");
        assert_eq!(a("(ton (dadd d (dmax e 1s)) f)"), "(d + max(e, 1s))/f");
        assert_eq!(a("(sr s (rs 0* 1*))"), "SR(s, RS(0*, 1*))");
        assert_eq!(a("(& law Xpi@90)"), "`law` . `Xpi@90`");
    }

    #[test]
    fn delays_print_back() {
        assert_eq!(delay_to_string(&"0.25s".parse().unwrap()), "250ms");
        assert_eq!(delay_to_string(&"90s".parse().unwrap()), "90s");
        assert_eq!(delay_to_string(&"1.5s".parse().unwrap()), "1.5s");
        assert_eq!(delay_to_string(&"3us".parse().unwrap()), "0.000003s");
    }

    #[test]
    fn long_terms_break_lines() {
        let names: Vec<String> = (0..40).map(|i| format!("signal_{i}")).collect();
        let s = format!("(+ {} {})", names[0], names[1]);
        let mut e = s;
        for n in &names[2..] {
            e = format!("(+ {e} {n})");
        }
        let text = term_to_string(&sexp(&e), Notation::Paper);
        assert!(text.lines().count() > 1);
        assert!(text.lines().all(|l| l.chars().count() <= WIDTH));
    }
}
