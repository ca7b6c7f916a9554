//! Located errors of proof scripts: a step that cannot be justified, a chain that misses its goal.

use crate::diag::{Report, Span};

/// A step the cited rules do not justify.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FailedStep {
    /// The step (its relation symbol to its `]`).
    pub span: Span,
    /// The step's number in the calculation (1-based).
    pub index: usize,
    /// The term before the step.
    pub from: String,
    /// `=` or `⇒`.
    pub relation: String,
    /// The term after the step.
    pub to: String,
    /// Why: what was tried, or the kernel's objection.
    pub reason: String,
    /// What each cited rule states.
    pub cited: Vec<String>,
}

/// Why a claim of a proof script was not accepted. Terms are already printed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ScriptError {
    /// A cited rule that is no law, hypothesis or earlier claim.
    UnknownRule {
        /// Where it is cited.
        span: Span,
        /// The name as written.
        name: String,
        /// A near miss among the laws, hypotheses and lemmas.
        suggestion: Option<String>,
        /// The name is a claim of this file that did not check (or comes later).
        unproved_claim: bool,
    },
    /// A step the cited rules do not justify.
    StepFailed(Box<FailedStep>),
    /// The calculation does not start from the goal's left side.
    WrongStart {
        /// The starting term.
        span: Span,
        /// It as printed.
        found: String,
        /// What it should be.
        expected: String,
    },
    /// The calculation ends before the goal's right side.
    StopsShort {
        /// The last step (or the start, if there is none).
        span: Span,
        /// Where the chain ends.
        reached: String,
        /// The goal's right side.
        expected: String,
    },
    /// An equation proved by a chain with an implication step.
    OnlyImplication {
        /// The `=>` step.
        span: Span,
        /// The goal as printed.
        goal: String,
    },
    /// `by auto` (or `[auto]`, or `by induction`) did not find a proof within its limits.
    AutoFailed {
        /// Where `auto` (or `induction`) is.
        span: Span,
        /// `auto` or `induction`.
        method: &'static str,
        /// What it had to prove.
        goal: String,
        /// The prover's reason.
        reason: String,
    },
    /// The kernel rejected the assembled certificate (a bug of the checker, reported honestly).
    Kernel {
        /// The claim's name.
        span: Span,
        /// The claim.
        name: String,
        /// The kernel's error.
        error: String,
    },
    /// The program or the hypotheses could not be loaded into the kernel.
    BadContext {
        /// Where (the program header or the first statement).
        span: Span,
        /// Why.
        reason: String,
    },
}

impl Report for ScriptError {
    fn span(&self) -> Option<Span> {
        Some(match self {
            ScriptError::StepFailed(step) => step.span,
            ScriptError::UnknownRule { span, .. }
            | ScriptError::WrongStart { span, .. }
            | ScriptError::StopsShort { span, .. }
            | ScriptError::OnlyImplication { span, .. }
            | ScriptError::AutoFailed { span, .. }
            | ScriptError::Kernel { span, .. }
            | ScriptError::BadContext { span, .. } => *span,
        })
    }

    fn message(&self) -> String {
        match self {
            ScriptError::UnknownRule { name, unproved_claim: true, .. } => {
                format!("`{name}` is a claim that has not been proved before this step")
            }
            ScriptError::UnknownRule { name, .. } => {
                format!("unknown rule `{name}`: no law, hypothesis or lemma has this name")
            }
            ScriptError::StepFailed(s) => {
                format!("step {} does not follow: {} {} {}", s.index, s.from, s.relation, s.to)
            }
            ScriptError::WrongStart { found, expected, .. } => {
                format!(
                    "the calculation starts from {found}, not from the goal's left side {expected}"
                )
            }
            ScriptError::StopsShort { reached, expected, .. } => {
                format!(
                    "the calculation stops at {reached}, short of the goal's right side {expected}"
                )
            }
            ScriptError::OnlyImplication { goal, .. } => {
                format!(
                    "this step holds only as an implication (`⇒`), not as an equation (goal: {goal})"
                )
            }
            ScriptError::AutoFailed { goal, method, .. } => {
                format!("`{method}` found no proof of {goal}")
            }
            ScriptError::Kernel { name, error, .. } => {
                format!("the kernel rejects the proof of `{name}`: {error}")
            }
            ScriptError::BadContext { reason, .. } => reason.clone(),
        }
    }

    fn label(&self) -> String {
        match self {
            ScriptError::UnknownRule { .. } => "not defined".into(),
            ScriptError::StepFailed(step) => step.reason.clone(),
            ScriptError::WrongStart { .. } => "expected the goal's left side here".into(),
            ScriptError::StopsShort { .. } => "the chain ends here".into(),
            ScriptError::OnlyImplication { .. } => "an implication step".into(),
            ScriptError::AutoFailed { .. } => "no proof found".into(),
            ScriptError::Kernel { .. } => "rejected".into(),
            ScriptError::BadContext { .. } => String::new(),
        }
    }

    fn notes(&self) -> Vec<String> {
        match self {
            ScriptError::UnknownRule { suggestion: Some(s), .. } => {
                vec![format!("did you mean `{s}`?")]
            }
            ScriptError::UnknownRule { unproved_claim: false, .. } => {
                vec!["`ii-prove axioms` lists the laws; hypotheses are rung names and `assume` names".into()]
            }
            ScriptError::StepFailed(step) => step.cited.clone(),
            ScriptError::WrongStart { .. } => vec![
                "for `f => g` a calculation may also start from `f . g` (and end at `f`) or from `f . !g` (and end at `0*`)".into(),
            ],
            ScriptError::StopsShort { expected, .. } => {
                vec![format!("add a step `= {expected} [...]`, or finish with `[auto]`")]
            }
            ScriptError::OnlyImplication { .. } => vec![
                "write the step with `=>`; a goal `f = g`, or a chain that starts from `f . g` or `f . !g`, needs `=` steps throughout".into(),
            ],
            ScriptError::AutoFailed { reason, .. } => vec![reason.clone()],
            _ => Vec::new(),
        }
    }
}
