//! The `.ii` language: lexer, parser with spans, resolver and pretty-printer.
//!
//! [`parse_document`] reads a property, theory or proof file into a [`Document`]
//! of resolved goals (terms of [`crate::term`]); [`parse_expression`] and
//! [`parse_goal`] read what is typed at the REPL. Every problem is a
//! [`SyntaxError`] with a span; several are reported at once (the parser
//! recovers at the next statement keyword). [`print`](mod@print) writes terms, goals and
//! whole documents back, in the paper's notation or in ASCII.
//!
//! Pipeline: [`lexer`] (text → tokens) → [`parser`] (tokens → [`ast`]) →
//! [`resolve`] (names, `/` chains, durations → terms).
//!
//! # Grammar
//!
//! ```text
//! file      := statement*                       (each starts with its keyword; may span lines)
//! statement := "let" NAME "=" expr              abbreviation, expanded where used (define before use)
//!            | "input" NAME ("," NAME)*         free signals
//!            | "delay" NAME ("," NAME)*         delay metavariables (for laws)
//!            | "assume" NAME ":" goal
//!            | "property" NAME ":" goal
//!            | "law" NAME ":" expr ("=>" | "=") expr ["if" cond ("," cond)*]
//!            | "program" STRING                 names the ladder program
//!            | ("theorem" | "lemma") NAME ":" goal proof
//! proof     := "by" NAME ("," NAME)*            `by auto`, or one step citing these rules
//!            | "proof" expr step* "qed"         a calculation from the goal's left side
//! step      := ("=" | "=>") expr "[" NAME ("," NAME)* "]"
//! goal      := ["after" DURATION ":"] expr ("=>" | "=") expr
//! cond      := DURATION (">=" | ">" | "<=" | "<" | "=") DURATION  |  expr ("=>" | "=") expr
//! expr      := product (("+" | "∨" | "|") product)*
//! product   := chain (("." | "·" | "&" | "∧") chain)*
//! chain     := unary ("/" unary)*               exactly one operand is a signal
//! unary     := ("!" | "¬" | "~") unary | atom
//! atom      := NAME | DURATION | "0*" | "1*" | "0" | "1" | "(" expr ")"
//!            | ("SR" | "RS" | "max" | "min") "(" expr "," expr ")"
//! DURATION  := a duration literal, a declared `delay` variable (laws only),
//!              max(D, D), min(D, D), or a parenthesised sum (D + D + ...)
//! NAME      := [A-Za-z_][A-Za-z0-9_]* (not a keyword) | `any text but back quotes`
//! ```
//!
//! In a chain, durations left of the signal are on-delays applied outward
//! (`2s/5s/f` = `2s/(5s/f)`), durations right of it are off-delays
//! (`f/1s/2s` = `(f/1s)/2s`); both on one signal is an error. Keywords:
//! `let input delay assume property law program after if theorem lemma proof qed by`. `SR`, `RS`,
//! `max`, `min` are calls only when followed by `(`.
//!
//! Limits: parentheses and `!` nest at most 200 deep; a resolved term has at
//! most 100 000 nodes and depth 1 000 (a sum of more than 1 000 operands is
//! rejected); a duration's number has at most 200 characters. A `let` is
//! resolved where it is written, by the rules of properties (so a theory file's
//! `let` may use only `input`s), and may not reuse a program signal's name.

pub mod ast;
pub mod lexer;
pub mod parser;
pub mod pattern;
pub mod print;
pub mod resolve;

use crate::diag::{FileId, Report, Sources, Span};
use crate::term::{Delay, Expr, Id, Symbol, Term};

pub use ast::{ClaimKind, CmpOp, IntOperand, RuleRef};
pub use pattern::Pattern;
pub use print::{
    GoalKeyword, Notation, claim_to_string, delay_to_string, document_to_string,
    goal_statement_to_string, goal_to_string, law_to_string, step_to_string, term_to_string,
};

/// How the two sides of a goal are related.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Relation {
    /// `f => g`: whenever `f` is 1, `g` is 1.
    Implies,
    /// `f = g`: the signals agree at every instant.
    Equals,
}

/// A goal: `lhs => rhs` or `lhs = rhs`, possibly only `after` some delay.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Goal {
    /// Left side.
    pub lhs: Expr,
    /// The relation.
    pub relation: Relation,
    /// Right side.
    pub rhs: Expr,
    /// `after d:` — the goal holds from `d` on: `d/1* · lhs ⇒ rhs`, or
    /// `d/1* · lhs = d/1* · rhs` for an equality.
    pub after: Option<Delay>,
    /// The requirement pattern it was written as, if any (the goal is its II term).
    pub pattern: Option<Pattern>,
}

impl Goal {
    /// The left side with `after d` folded in: `d/1* · lhs`.
    pub fn lhs_with_after(&self) -> Expr {
        with_after(&self.lhs, self.after.as_ref())
    }

    /// The right side with `after d` folded in: `d/1* · rhs` for an equality (nothing is
    /// said before `d`), `rhs` itself for an implication (`d/1* · f ⇒ g` already says it).
    pub fn rhs_with_after(&self) -> Expr {
        match self.relation {
            Relation::Equals => with_after(&self.rhs, self.after.as_ref()),
            Relation::Implies => self.rhs.clone(),
        }
    }
}

/// `d/1* · side`, or `side` without a delay.
fn with_after(side: &Expr, after: Option<&Delay>) -> Expr {
    match after {
        None => side.clone(),
        Some(d) => {
            // Built directly (egg's `RecExpr::add` is linear in the term's size).
            let mut nodes: Vec<Term> = side.as_ref().to_vec();
            let top = Id::from(nodes.len().saturating_sub(1));
            let base = nodes.len();
            nodes.push(Term::Delay(d.clone()));
            nodes.push(Term::One);
            nodes.push(Term::Ton([Id::from(base), Id::from(base + 1)]));
            nodes.push(Term::And([Id::from(base + 2), top]));
            Expr::from(nodes)
        }
    }
}

/// A named statement (`assume`, `property`, `law`) and where it is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Statement<T> {
    /// Its name.
    pub name: String,
    /// Where the name is written.
    pub name_span: Span,
    /// The whole statement.
    pub span: Span,
    /// What it says.
    pub value: T,
}

/// A comparison between durations in a law's side condition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DelayComparison {
    /// `>=`
    Ge,
    /// `>`
    Gt,
    /// `<=`
    Le,
    /// `<`
    Lt,
    /// `=`
    Eq,
}

/// A side condition of a law (`if ...`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SideCondition {
    /// `d1 >= d2` and the like, between delay terms.
    Delay {
        /// Left side (a delay term).
        lhs: Expr,
        /// The comparison.
        op: DelayComparison,
        /// Right side (a delay term).
        rhs: Expr,
    },
    /// A signal goal that must hold (e.g. `s . r = 0*`).
    Signal(Goal),
}

/// A law of a theory: a goal over metavariables, with side conditions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Law {
    /// The equation or implication.
    pub goal: Goal,
    /// Conditions under which it holds.
    pub conditions: Vec<SideCondition>,
    /// The signal metavariables, in order of first use.
    pub signal_vars: Vec<Symbol>,
    /// The delay metavariables used, in order of first use.
    pub delay_vars: Vec<Symbol>,
}

/// A resolved `.ii` file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Document {
    /// The file it was read from.
    pub file: FileId,
    /// `program "path"`, if the file names its ladder program.
    pub program: Option<(String, Span)>,
    /// Free signals declared with `input`.
    pub inputs: Vec<(String, Span)>,
    /// Delay variables declared with `delay`.
    pub delays: Vec<(String, Span)>,
    /// `assume` statements, in file order.
    pub assumptions: Vec<Statement<Goal>>,
    /// `property` statements, in file order.
    pub properties: Vec<Statement<Goal>>,
    /// `law` statements, in file order.
    pub laws: Vec<Statement<Law>>,
    /// `theorem` and `lemma` statements of a proof script, in file order.
    pub claims: Vec<Statement<Claim>>,
}

/// A `theorem` or `lemma` of a proof script: a goal and its proof.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Claim {
    /// `theorem` or `lemma`.
    pub kind: ClaimKind,
    /// What it states.
    pub goal: Goal,
    /// How it is proved.
    pub proof: ScriptProof,
}

/// The proof of a claim.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ScriptProof {
    /// `by auto`: the full prover.
    Auto(Span),
    /// `by induction`: induction over scans (a script about a program), with an
    /// invariant the prover finds; it becomes the lemma `NAME_inv`.
    Induction(Span),
    /// `by r1, r2`: one step from the left side to the right side, with these rules.
    By(Vec<RuleRef>, Span),
    /// `proof START (= TERM [RULES])* qed`: a calculation.
    Calc {
        /// The starting term (the goal's left side, or `f·g`, `f·¬g` for `f ⇒ g`).
        start: Expr,
        /// Where it is written.
        start_span: Span,
        /// The steps.
        steps: Vec<CalcStep>,
        /// Where `qed` is.
        qed: Span,
    },
}

/// One step of a calculation: `= term [rules]` or `=> term [rules]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CalcStep {
    /// `=` or `=>`.
    pub relation: Relation,
    /// The term the step arrives at.
    pub term: Expr,
    /// Where the term is written.
    pub term_span: Span,
    /// The cited rules (`auto` runs the prover).
    pub rules: Vec<RuleRef>,
    /// The whole step, from its relation symbol to its `]`.
    pub span: Span,
}

/// The signals a program defines, for resolving names in property files.
pub trait Scope {
    /// Resolve a user-written name to the program's canonical signal name.
    fn lookup(&self, name: &str) -> Lookup;
    /// Every signal name of the program (for "did you mean" and for listing).
    fn names(&self) -> Vec<String>;
    /// The names of the program's own hypotheses (rung equations and recurrences), which
    /// an `assume` may not reuse.
    fn hypothesis_names(&self) -> Vec<String> {
        Vec::new()
    }
    /// Whether the names are a program's, run in scans (then `pre` may be used).
    fn scans(&self) -> bool {
        false
    }
    /// The program's scan cycle, when known: every duration written must then be a whole
    /// number of cycles (only those have one reading on scans).
    fn cycle(&self) -> Option<Delay> {
        None
    }
    /// The signal standing for the comparison atom `[a op b]` of the program's integers,
    /// or why there is none: (what is wrong, a hint).
    fn comparison(
        &self,
        _op: CmpOp,
        _a: &ast::IntOperand,
        _b: &ast::IntOperand,
    ) -> Result<String, (String, Option<String>)> {
        Err((
            "a comparison `[a op b]` reads a program's integers, and there is no program here"
                .into(),
            Some("load a program with integers (counters, MOVE, arithmetic)".into()),
        ))
    }
}

/// The answer of a [`Scope`] to a name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Lookup {
    /// The name denotes this signal (its canonical name).
    Signal(String),
    /// The name could denote any of these.
    Ambiguous(Vec<String>),
    /// No such signal.
    Unknown,
}

/// An empty scope: only `input`-declared names exist (free-signal mode, theory files).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoProgram;

impl Scope for NoProgram {
    fn lookup(&self, _name: &str) -> Lookup {
        Lookup::Unknown
    }
    fn names(&self) -> Vec<String> {
        Vec::new()
    }
}

/// No program, but signals that are scan runs: `pre` may be used. A `.ii` text that
/// describes a program's scans (what `ii-prove show` prints) reads back with this scope.
#[derive(Clone, Copy, Debug, Default)]
pub struct Scans;

impl Scope for Scans {
    fn lookup(&self, _name: &str) -> Lookup {
        Lookup::Unknown
    }
    fn names(&self) -> Vec<String> {
        Vec::new()
    }
    fn scans(&self) -> bool {
        true
    }
}

/// Reads a whole `.ii` file; names are resolved against `scope` and the file's `input`s.
pub fn parse_document(
    sources: &Sources,
    file: FileId,
    scope: &dyn Scope,
) -> Result<Document, Vec<SyntaxError>> {
    resolve::document(sources.text(file), file, scope)
}

/// Parses a property file or proof script: a document without `law` statements (a law
/// stated there would be neither proved nor used, so it is an error).
pub fn parse_properties(
    sources: &Sources,
    file: FileId,
    scope: &dyn Scope,
) -> Result<Document, Vec<SyntaxError>> {
    let doc = parse_document(sources, file, scope)?;
    let laws: Vec<SyntaxError> =
        doc.laws.iter().map(|l| SyntaxError::LawOutsideTheory { span: l.span }).collect();
    if laws.is_empty() { Ok(doc) } else { Err(laws) }
}

/// One expression (for the REPL), names checked against `scope` plus `inputs`.
pub fn parse_expression(
    sources: &Sources,
    file: FileId,
    scope: &dyn Scope,
    inputs: &[String],
) -> Result<Expr, Vec<SyntaxError>> {
    resolve::expression(sources.text(file), file, scope, inputs)
}

/// One statement or goal typed at a REPL, same rules.
///
/// Accepts `f => g`, `f = g`, `after D: f => g`, or a whole
/// `property NAME: ...` / `assume NAME: ...` statement (its goal is returned).
pub fn parse_goal(
    sources: &Sources,
    file: FileId,
    scope: &dyn Scope,
    inputs: &[String],
) -> Result<Goal, Vec<SyntaxError>> {
    resolve::goal(sources.text(file), file, scope, inputs)
}

/// The statement that declares a name (for [`SyntaxError::ShadowsSignal`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Declaration {
    /// `let NAME = …`
    Let,
    /// `input NAME, …`
    Input,
    /// `assume NAME: …`
    Assume,
}

/// A malformed `.ii` file, or one that refers to something that does not exist.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SyntaxError {
    /// A character that starts no token.
    UnexpectedChar {
        /// Where.
        span: Span,
        /// The character.
        found: char,
    },
    /// A `"` string without its closing quote on the same line.
    UnterminatedString {
        /// Where the string starts.
        span: Span,
    },
    /// A back-quoted name without its closing back quote on the same line.
    UnterminatedName {
        /// Where the name starts.
        span: Span,
    },
    /// ``` `` ```: a back-quoted name with nothing inside.
    EmptyName {
        /// Where.
        span: Span,
    },
    /// A duration that is zero, negative, malformed or too long.
    BadDuration {
        /// Where.
        span: Span,
        /// Why it is rejected.
        reason: String,
    },
    /// A number without a unit (`5` instead of `5s`).
    MissingUnit {
        /// Where.
        span: Span,
        /// The number as written.
        number: String,
    },
    /// A unit that does not exist (`5sec`).
    BadUnit {
        /// Where the unit is.
        span: Span,
        /// The unit as written.
        unit: String,
        /// The units that are allowed here.
        allowed: String,
    },
    /// A token the grammar does not allow here.
    UnexpectedToken {
        /// Where.
        span: Span,
        /// What was found.
        found: String,
        /// What would have been accepted.
        expected: Vec<String>,
    },
    /// A keyword used as a name.
    ReservedWord {
        /// Where.
        span: Span,
        /// The keyword.
        word: String,
    },
    /// `=>` or `=` inside an expression (they are only allowed at the top of a statement).
    RelationNotAtTop {
        /// Where the relation is.
        span: Span,
    },
    /// `>=`, `<` ... between signals, or `=>` between durations.
    BadRelation {
        /// Where the relation is.
        span: Span,
        /// Why it does not fit.
        reason: String,
    },
    /// Parentheses nested too deeply to be reasonable.
    TooDeep {
        /// Where.
        span: Span,
    },
    /// A comparison atom `[a op b]` that does not fit the program's integers.
    BadComparison {
        /// Where.
        span: Span,
        /// What is wrong.
        reason: String,
        /// A hint (`did you mean`, the type's range, …).
        help: Option<String>,
    },
    /// A name that is not a signal of the program, an input or an abbreviation.
    UnknownName {
        /// Where.
        span: Span,
        /// The name.
        name: String,
        /// A near miss, if any.
        suggestion: Option<String>,
        /// The names that would have been accepted.
        known: Vec<String>,
    },
    /// A name the program resolves to several signals.
    AmbiguousName {
        /// Where.
        span: Span,
        /// The name.
        name: String,
        /// The signals it could mean.
        candidates: Vec<String>,
    },
    /// A name defined twice.
    DuplicateName {
        /// The second definition.
        span: Span,
        /// The name.
        name: String,
        /// The first definition.
        first: Span,
    },
    /// A `let` or `input` whose name is already a signal of the program, or an
    /// `assume` named like one of the program's hypotheses.
    ShadowsSignal {
        /// Where the name is declared.
        span: Span,
        /// The name.
        name: String,
        /// What declares it.
        by: Declaration,
    },
    /// `5s/f/2s`: an on-delay and an off-delay on one atom.
    BothDelayKinds {
        /// The chain.
        span: Span,
    },
    /// `f/g`: no side of `/` is a duration.
    NoDuration {
        /// The chain.
        span: Span,
    },
    /// `!2s/f`: `!` binds tightest, so it negates the duration alone.
    NegatedDuration {
        /// The negated duration.
        span: Span,
    },
    /// `5s/2s`: no side of `/` is a signal.
    NoSignal {
        /// The chain.
        span: Span,
    },
    /// A duration where a signal is expected (`f . 5s`).
    DurationAsSignal {
        /// Where.
        span: Span,
    },
    /// A signal where a duration is expected (`max(f, 1s)`, `after f:`).
    SignalAsDuration {
        /// Where.
        span: Span,
    },
    /// A delay variable in a property or hypothesis (only laws may have them).
    DelayVariableOutsideLaw {
        /// Where.
        span: Span,
        /// The variable.
        name: String,
    },
    /// A delay metavariable of a law that no `delay` statement declares.
    UndeclaredDelay {
        /// Where.
        span: Span,
        /// The variable.
        name: String,
    },
    /// A term too large or too deep to handle (abbreviations expanding exponentially, say).
    TooLarge {
        /// Where.
        span: Span,
    },
    /// `after d:` with a delay variable (the `after` of a goal must be concrete).
    AfterNotConcrete {
        /// Where.
        span: Span,
    },
    /// A `law` in a property file or proof script (laws belong to theory files).
    LawOutsideTheory {
        /// The statement.
        span: Span,
    },
    /// A pattern that is not a safety property over scans (`eventually`, `until`, …).
    NotSafety {
        /// The word.
        span: Span,
        /// The word as written.
        word: String,
    },
    /// A requirement pattern where it has no meaning (why).
    BadPattern {
        /// The pattern.
        span: Span,
        /// Why it is refused here.
        reason: String,
    },
    /// In a program's context, a duration that is not a whole number of scan cycles.
    SubCycleDelay {
        /// Where.
        span: Span,
        /// The duration written.
        delay: Box<Delay>,
        /// The program's scan cycle.
        cycle: Box<Delay>,
    },
    /// `pre` in a goal about free signals: it is defined only for a program's scans.
    PreOutsideProgram {
        /// The `pre` term.
        span: Span,
    },
}

impl SyntaxError {
    /// Where the problem is.
    pub fn primary_span(&self) -> Span {
        use SyntaxError::*;
        match self {
            UnexpectedChar { span, .. }
            | UnterminatedString { span }
            | UnterminatedName { span }
            | EmptyName { span }
            | BadDuration { span, .. }
            | MissingUnit { span, .. }
            | BadUnit { span, .. }
            | UnexpectedToken { span, .. }
            | ReservedWord { span, .. }
            | RelationNotAtTop { span }
            | BadRelation { span, .. }
            | TooDeep { span }
            | UnknownName { span, .. }
            | BadComparison { span, .. }
            | AmbiguousName { span, .. }
            | DuplicateName { span, .. }
            | ShadowsSignal { span, .. }
            | BothDelayKinds { span }
            | NoDuration { span }
            | NegatedDuration { span }
            | NoSignal { span }
            | DurationAsSignal { span }
            | SignalAsDuration { span }
            | DelayVariableOutsideLaw { span, .. }
            | UndeclaredDelay { span, .. }
            | TooLarge { span }
            | AfterNotConcrete { span }
            | LawOutsideTheory { span }
            | SubCycleDelay { span, .. }
            | NotSafety { span, .. }
            | BadPattern { span, .. }
            | PreOutsideProgram { span } => *span,
        }
    }
}

/// `a`, `a or b`, `a, b or c`.
fn one_of(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

fn backquote_list(names: &[String], limit: usize) -> String {
    let mut shown: Vec<String> = names.iter().take(limit).map(|n| format!("`{n}`")).collect();
    if names.len() > limit {
        shown.push(format!("and {} more", names.len() - limit));
    }
    shown.join(", ")
}

impl Report for SyntaxError {
    fn span(&self) -> Option<Span> {
        Some(self.primary_span())
    }

    fn message(&self) -> String {
        use SyntaxError::*;
        match self {
            UnexpectedChar { found, .. } => format!("unexpected character `{found}`"),
            UnterminatedString { .. } => "unterminated string: expected a closing `\"`".into(),
            UnterminatedName { .. } => "unterminated quoted name: expected a closing back quote".into(),
            EmptyName { .. } => "empty quoted name".into(),
            BadDuration { reason, .. } => format!("bad duration: {reason}"),
            MissingUnit { number, .. } => {
                format!("`{number}` is a number without a unit: expected a unit (us, ms, s, min, h)")
            }
            BadUnit { unit, allowed, .. } => {
                format!("`{unit}` is not a unit of time (expected one of {allowed})")
            }
            UnexpectedToken { found, .. } => format!("unexpected {found}"),
            ReservedWord { word, .. } => format!("`{word}` is a reserved word, not a name"),
            RelationNotAtTop { .. } => {
                "`=>` and `=` are only allowed at the top of a statement, not inside an expression"
                    .into()
            }
            BadRelation { reason, .. } => reason.clone(),
            TooDeep { .. } => "expression nested too deeply".into(),
            UnknownName { name, .. } => format!("unknown signal `{name}`"),
            BadComparison { reason, .. } => reason.clone(),
            AmbiguousName { name, .. } => format!("ambiguous signal name `{name}`"),
            DuplicateName { name, .. } => format!("`{name}` is defined twice"),
            ShadowsSignal { name, by: Declaration::Let, .. } => {
                format!("`{name}` is already a signal of the program; an abbreviation needs another name")
            }
            ShadowsSignal { name, by: Declaration::Input, .. } => format!(
                "`{name}` is already a signal of the program; `input` would declare a new, unrelated signal"
            ),
            ShadowsSignal { name, by: Declaration::Assume, .. } => format!(
                "`{name}` already names one of the program's hypotheses; an `assume` needs another name"
            ),
            BothDelayKinds { .. } => {
                "an on-delay and an off-delay on the same signal: add parentheses, e.g. `(5s/f)/2s` or `5s/(f/2s)`".into()
            }
            NoDuration { .. } => {
                "exactly one side of `/` must be a duration, but neither is".into()
            }
            NegatedDuration { .. } => {
                "`!` applies to the duration alone here: `!` binds tighter than `/`".into()
            }
            NoSignal { .. } => {
                "exactly one side of `/` must be a duration, but both are: there is no signal to delay".into()
            }
            DurationAsSignal { .. } => "a duration is not a signal".into(),
            SignalAsDuration { .. } => "expected a duration, found a signal".into(),
            DelayVariableOutsideLaw { name, .. } => format!(
                "delay variable `{name}` outside a law: properties need concrete durations"
            ),
            UndeclaredDelay { name, .. } => {
                format!("`{name}` is not a declared delay variable")
            }
            AfterNotConcrete { .. } => "`after` needs a concrete duration".into(),
            LawOutsideTheory { .. } => {
                "a `law` belongs in a theory file, not in a property file or proof script".into()
            }
            TooLarge { .. } => "this term is too large or too deeply nested".into(),
            NotSafety { word, .. } => format!(
                "`{word}` states more than a safety property over scans: no finite run refutes it"
            ),
            BadPattern { reason, .. } => reason.clone(),
            SubCycleDelay { delay, cycle, .. } => format!(
                "{delay} is not a whole number of scan cycles: the program scans every {cycle}"
            ),
            PreOutsideProgram { .. } => "`pre` (the value one scan earlier) needs a program: \
                 free signals have no scans; give the program first (`ii-prove PROGRAM FILE.ii`) \
                 or a `program` header"
                .into(),
        }
    }

    fn label(&self) -> String {
        use SyntaxError::*;
        match self {
            UnexpectedToken { expected, .. } if !expected.is_empty() => {
                format!("expected {}", one_of(expected))
            }
            UnexpectedToken { .. } => "not expected here".into(),
            MissingUnit { .. } => "expected a unit after this number".into(),
            BadUnit { .. } => "unknown unit".into(),
            UnknownName { .. } => "not defined".into(),
            BadComparison { .. } => "in this comparison".into(),
            AmbiguousName { .. } => "ambiguous".into(),
            DuplicateName { .. } => "defined again here".into(),
            ShadowsSignal { by: Declaration::Assume, .. } => "name taken".into(),
            ShadowsSignal { .. } => "a signal of the program".into(),
            BothDelayKinds { .. } => "add parentheses".into(),
            NoDuration { .. } => "expected a duration on one side".into(),
            NegatedDuration { .. } => "a duration cannot be negated".into(),
            NoSignal { .. } => "expected a signal on one side".into(),
            DurationAsSignal { .. } => "expected a signal".into(),
            SignalAsDuration { .. } => "expected a duration".into(),
            DelayVariableOutsideLaw { .. } => "expected a concrete duration such as `5s`".into(),
            UndeclaredDelay { .. } => "not declared with `delay`".into(),
            RelationNotAtTop { .. } => "expected `)`".into(),
            ReservedWord { .. } => "expected a name".into(),
            UnterminatedString { .. } => "expected `\"` before the end of the line".into(),
            UnterminatedName { .. } => "expected a back quote before the end of the line".into(),
            AfterNotConcrete { .. } => "expected a concrete duration such as `5s`".into(),
            LawOutsideTheory { .. } => "expected `property`, `assume`, `theorem` or `lemma`".into(),
            PreOutsideProgram { .. } => "no program is loaded".into(),
            SubCycleDelay { .. } => "expected a whole number of cycles".into(),
            NotSafety { .. } => "not a safety property".into(),
            _ => String::new(),
        }
    }

    fn related(&self) -> Vec<(Span, String)> {
        match self {
            SyntaxError::DuplicateName { first, .. } => vec![(*first, "first defined here".into())],
            _ => Vec::new(),
        }
    }

    fn notes(&self) -> Vec<String> {
        use SyntaxError::*;
        match self {
            UnknownName { suggestion, known, .. } => {
                let mut notes = Vec::new();
                if let Some(s) = suggestion {
                    notes.push(format!("did you mean `{s}`?"));
                }
                if known.is_empty() {
                    notes.push(
                        "no signals are known here: declare free signals with `input NAME, ...`"
                            .into(),
                    );
                } else {
                    notes.push(format!("known signals: {}", backquote_list(known, 40)));
                    notes.push("declare a free signal with `input NAME`".into());
                }
                notes
            }
            AmbiguousName { candidates, .. } => {
                vec![format!("it could be any of {}", backquote_list(candidates, 40))]
            }
            BadComparison { help, .. } => help.iter().cloned().collect(),
            ShadowsSignal { name, by: Declaration::Input, .. } => vec![format!(
                "remove `{name}` from `input` to mean the program's signal; a free signal needs a name the program does not use"
            )],
            UndeclaredDelay { name, .. } => {
                vec![format!("declare it before the law: `delay {name}`")]
            }
            ReservedWord { word, .. } => vec![format!("write `` `{word}` `` to use it as a name")],
            NegatedDuration { .. } => vec![
                "the complement of a timer is written with parentheses: `!(2s/f)`; an on-delay of a complement is `2s/!f`".into(),
            ],
            UnexpectedChar { .. } => vec![
                "names with other characters can be written between back quotes: `Xpi@90`".into(),
            ],
            NotSafety { .. } => vec![
                "ii-prove checks safety properties: every violation shows in a finite run. \
                 A bounded form is one: `whenever a then b within 10s`, `f at most 30s`"
                    .into(),
            ],
            SubCycleDelay { delay, cycle, .. } => {
                let (below, above) = delay.nearest_whole_cycles(cycle);
                let cycles = |d: &Delay| {
                    let n = (d.seconds() / cycle.seconds()).to_integer();
                    let plural = if n == 1.into() { "" } else { "s" };
                    format!("{d} ({n} cycle{plural})")
                };
                let nearest = match below {
                    Some(b) => format!(
                        "the nearest whole multiples are {} and {}",
                        cycles(&b),
                        cycles(&above)
                    ),
                    None => format!("the shortest whole multiple is {}", cycles(&above)),
                };
                vec![
                    nearest,
                    "a timer counts whole scans, so a shorter or fractional delay has no single \
                     reading on the PLC (docs/semantics.md, \"Programs, scan by scan\")"
                        .into(),
                ]
            }
            _ => Vec::new(),
        }
    }
}
