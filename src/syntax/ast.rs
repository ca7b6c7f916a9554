//! The syntax tree of a `.ii` file as written, with spans; the resolver turns it into terms.

use crate::diag::Span;
use crate::term::Delay;

/// An expression as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ast {
    /// What it is.
    pub kind: AstKind,
    /// Where it is.
    pub span: Span,
}

/// The built-in functions written as calls.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func {
    /// `SR(s, r)`.
    Sr,
    /// `RS(s, r)`.
    Rs,
    /// `max(d, d)`.
    Max,
    /// `min(d, d)`.
    Min,
}

impl Func {
    /// The function a name denotes when it is followed by `(`.
    pub fn from_name(name: &str) -> Option<Func> {
        match name {
            "SR" => Some(Func::Sr),
            "RS" => Some(Func::Rs),
            "max" => Some(Func::Max),
            "min" => Some(Func::Min),
            _ => None,
        }
    }
}

/// The forms of an expression.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AstKind {
    /// A name (plain or back-quoted).
    Name(String),
    /// A duration literal.
    Duration(Delay),
    /// `0*`.
    Zero,
    /// `1*`.
    One,
    /// `!a`.
    Not(Box<Ast>),
    /// `pre a`.
    Pre(Box<Ast>),
    /// `a + b + ...` (left-associative), at least two operands.
    Or(Vec<Ast>),
    /// `a . b . ...` (left-associative), at least two operands.
    And(Vec<Ast>),
    /// `a / b / ...`, at least two operands; the resolver sorts out which are durations.
    Chain(Vec<Ast>),
    /// `(a)`.
    Paren(Box<Ast>),
    /// `SR(a, b)`, `RS(a, b)`, `max(a, b)`, `min(a, b)`.
    Call(Func, Box<Ast>, Box<Ast>),
    /// `[a op b]`: a comparison of a program's integers, a signal.
    Compare(CmpOp, IntOperand, IntOperand),
    /// Text the lexer rejected (already reported).
    Error,
}

/// A comparison operator of integers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CmpOp {
    /// `=`
    Eq,
    /// `<>`
    Ne,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
}

impl CmpOp {
    /// The operator as the `.ii` language writes it.
    pub fn symbol(self) -> &'static str {
        match self {
            CmpOp::Eq => "=",
            CmpOp::Ne => "<>",
            CmpOp::Lt => "<",
            CmpOp::Le => "<=",
            CmpOp::Gt => ">",
            CmpOp::Ge => ">=",
        }
    }

    /// Whether `a op b`.
    pub fn holds(self, a: i64, b: i64) -> bool {
        self.compares(a, b)
    }

    /// Whether `a op b` in a partial order (for floats: IEEE's, where a NaN is
    /// unordered: every comparison with it false but `<>`).
    pub fn compares<T: PartialOrd>(self, a: T, b: T) -> bool {
        match self {
            CmpOp::Eq => a == b,
            CmpOp::Ne => a != b,
            CmpOp::Lt => a < b,
            CmpOp::Le => a <= b,
            CmpOp::Gt => a > b,
            CmpOp::Ge => a >= b,
        }
    }
}

/// A side of a comparison atom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum IntOperand {
    /// An integer variable of the program.
    Var(String),
    /// A literal.
    Int(i64),
    /// A duration (`T#2500ms`), in ns: compared with a `TIME` of the program.
    Time(i64),
}

impl std::fmt::Display for IntOperand {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            IntOperand::Var(v) => write!(f, "{v}"),
            IntOperand::Int(k) => write!(f, "{k}"),
            IntOperand::Time(us) => write!(f, "{}", super::print::signed_duration_ns(*us)),
        }
    }
}

/// A relation between two expressions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RelOp {
    /// `=>`.
    Implies,
    /// `=`.
    Equals,
    /// `>=`.
    Ge,
    /// `>`.
    Gt,
    /// `<=`.
    Le,
    /// `<`.
    Lt,
}

/// A requirement pattern as written: a property in the words a control engineer uses,
/// which the resolver compiles to a goal (the catalogue is in the README).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AstPattern {
    /// `always f`: `f = 1*`.
    Always(Ast),
    /// `never f`: `f = 0*`.
    Never(Ast),
    /// `reachable f`: some run makes `f` 1 at some scan (an existence claim).
    Reachable(Ast),
    /// `a then b => c`: if `a` at a scan and `b` at the next, then `c` there.
    Then {
        /// `a`, at the earlier scan.
        first: Ast,
        /// `b`, at the later scan.
        next: Ast,
        /// `c`, at the later scan.
        then: Ast,
    },
    /// `whenever a then b within d`: `b` at the scan of `a` or within `d` after it.
    Within {
        /// `a`.
        trigger: Ast,
        /// `b`.
        response: Ast,
        /// `d`.
        delay: Ast,
    },
    /// `b not before d after a`: `b` only once more than `d` has passed since the last `a`.
    NotBefore {
        /// `b`.
        response: Ast,
        /// `d`.
        delay: Ast,
        /// `a`.
        trigger: Ast,
    },
    /// `f at most d`: `f` is never on for longer than `d` at a stretch.
    AtMost {
        /// `f`.
        signal: Ast,
        /// `d`.
        delay: Ast,
    },
    /// `f at least d once on`: once `f` turns on it stays on for at least `d`.
    AtLeast {
        /// `f`.
        signal: Ast,
        /// `d`.
        delay: Ast,
    },
}

/// `[after D:] lhs op rhs` as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AstGoal {
    /// The `after` duration, if any.
    pub after: Option<Ast>,
    /// Left side.
    pub lhs: Ast,
    /// The relation.
    pub op: RelOp,
    /// Where the relation symbol is.
    pub op_span: Span,
    /// Right side.
    pub rhs: Ast,
    /// The whole goal.
    pub span: Span,
    /// A requirement pattern: then it says what the goal is, and `lhs`, `op` and `rhs`
    /// are placeholders.
    pub pattern: Option<Box<AstPattern>>,
}

/// Which named statement.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NamedKind {
    /// `assume`.
    Assume,
    /// `property`.
    Property,
    /// `law`.
    Law,
}

/// One statement as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AstStatement {
    /// `let NAME = expr`.
    Let {
        /// The abbreviation.
        name: (String, Span),
        /// What it stands for.
        value: Ast,
        /// The whole statement.
        span: Span,
    },
    /// `input NAME, ...`.
    Input(Vec<(String, Span)>),
    /// `delay NAME, ...`.
    Delay(Vec<(String, Span)>),
    /// `assume`, `property` or `law`.
    Named {
        /// Which one.
        kind: NamedKind,
        /// Its name.
        name: (String, Span),
        /// The goal.
        goal: Box<AstGoal>,
        /// The side conditions (`law` only).
        conditions: Vec<AstGoal>,
        /// The whole statement.
        span: Span,
    },
    /// `program "path"`.
    Program(String, Span),
    /// `theorem NAME: goal proof ... qed` or `lemma NAME: goal by auto` (proof scripts).
    Claim {
        /// `theorem` or `lemma`.
        kind: ClaimKind,
        /// Its name.
        name: (String, Span),
        /// What it states.
        goal: Box<AstGoal>,
        /// How it is proved.
        proof: AstProof,
        /// The whole statement.
        span: Span,
    },
}

/// `theorem` or `lemma` (a lemma is meant to be cited later; both may be).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ClaimKind {
    /// `theorem`.
    Theorem,
    /// `lemma`.
    Lemma,
}

/// A rule cited in a proof step: a law, hypothesis or lemma name, or `auto`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RuleRef {
    /// The name as written.
    pub name: String,
    /// Where it is written.
    pub span: Span,
}

/// One step `= term [rules]` or `=> term [rules]` of a calculation, as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AstStep {
    /// `=` or `=>`.
    pub op: RelOp,
    /// Where the relation symbol is.
    pub op_span: Span,
    /// The term the step arrives at.
    pub term: Ast,
    /// The cited rules.
    pub rules: Vec<RuleRef>,
    /// The whole step.
    pub span: Span,
}

/// The proof of a claim, as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AstProof {
    /// `by auto`.
    Auto(Span),
    /// `by induction`: induction over scans, with an invariant the prover finds.
    Induction(Span),
    /// `by r1, r2`: one step from the left side to the right side with these rules.
    By(Vec<RuleRef>, Span),
    /// `proof start (= term [rules])* qed`.
    Calc {
        /// The starting term.
        start: Ast,
        /// The steps.
        steps: Vec<AstStep>,
        /// Where `qed` is.
        qed: Span,
    },
}
