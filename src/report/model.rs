//! The report's data, which every renderer reads (text, JSON, JUnit, SARIF, GitHub,
//! HTML) and which is serialized as the JSON report: each property's verdict, trace and
//! counterexample, the warnings, the summary and its exit status.

use serde::Serialize;

use super::tracks;
use crate::diag::Sources;

/// The verdict on one property.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// The kernel checked a proof.
    Proved,
    /// A counterexample, confirmed by exact evaluation.
    Refuted,
    /// Neither within the limits.
    Unknown,
}

/// A step of a checked proof, in the JSON output.
#[derive(Clone, Debug, Serialize)]
pub struct StepReport {
    /// The law, hypothesis or lemma cited (`case`, `delay arithmetic` otherwise).
    pub rule: String,
    /// `law`, `hypothesis`, `lemma`, `case` or `delay-arithmetic`.
    pub kind: String,
    /// The whole term after the step.
    pub term: String,
}

/// A proof in the JSON output.
#[derive(Clone, Debug, Serialize)]
pub struct TraceReport {
    /// `saturation` or `case-split`.
    pub method: String,
    /// The printed calculation, line by line (a line may hold a term broken over
    /// several); an induction's lemmas folded unless `--trace-all`.
    pub lines: Vec<String>,
    /// The names of the lemmas the kernel checked with the proof, each one.
    pub lemmas: Vec<String>,
    /// The length of the calculation (its lines, as the paper's proofs are counted).
    pub length: usize,
    /// Every kernel-checked step.
    pub steps: Vec<StepReport>,
    /// The hypotheses the proof depends on.
    pub hypotheses: Vec<String>,
    /// The laws the proof depends on.
    pub laws: Vec<String>,
}

/// One signal of a counterexample: its exact pieces.
#[derive(Clone, Debug, Serialize)]
pub struct SignalReport {
    /// The signal's name.
    pub name: String,
    /// Breakpoints `b1 … bn` (exact, as decimals or fractions).
    pub breakpoints: Vec<String>,
    /// The value on each open interval `(b(i−1), b(i))`.
    pub intervals: Vec<bool>,
    /// The value at each breakpoint.
    pub points: Vec<bool>,
}

impl SignalReport {
    /// Signal `s`, reported as `name`.
    pub fn of(name: String, s: &crate::semantics::Signal) -> SignalReport {
        SignalReport {
            name,
            breakpoints: s.breakpoints().iter().map(crate::semantics::format_time).collect(),
            intervals: s.open_values().to_vec(),
            points: s.point_values().to_vec(),
        }
    }
}

/// A counterexample in the JSON output.
#[derive(Clone, Debug, Serialize)]
pub struct CounterexampleReport {
    /// The instant where the property fails.
    pub time: String,
    /// The left side's value there.
    pub lhs: bool,
    /// The right side's value there.
    pub rhs: bool,
    /// The signals.
    pub signals: Vec<SignalReport>,
    /// The timing diagram as text lines.
    pub diagram: Vec<String>,
    /// The violating scan (1-based) of a program counterexample.
    pub scan: Option<usize>,
    /// The first scan at which LDmicro's scan simulator shows the violation.
    pub simulator_scan: Option<usize>,
    /// What confirmed it: `exact evaluation`, `scan simulator`.
    pub confirmed_by: Vec<String>,
    /// What a possible counterexample that is not a run is (the induction step's state).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    /// The program's integers the run computed, with their value at each scan.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub integers: Vec<IntegerReport>,
    /// The integers drawn as value tracks (for `--vcd`, `--wavedrom`, `--html`).
    #[serde(skip)]
    pub tracks: Vec<tracks::IntegerTrack>,
    /// The signals shown in the diagram, with their exact pieces (for `--vcd`, `--wavedrom`).
    #[serde(skip)]
    pub shown: Vec<(String, crate::semantics::Signal)>,
    /// The instant marked in the diagram.
    #[serde(skip)]
    pub mark: Option<crate::semantics::Time>,
}

/// An integer of a counterexample's run.
#[derive(Clone, Debug, Serialize)]
pub struct IntegerReport {
    /// Its name, as the report spells it.
    pub name: String,
    /// Its value at the end of each scan, from the first (a TIME's in ns).
    pub values: Vec<i64>,
    /// `"TIME"` for a duration (its values in ns, a timer's elapsed time `T1_ET`);
    /// absent for an integer.
    #[serde(rename = "type", skip_serializing_if = "Option::is_none")]
    pub ty: Option<&'static str>,
}

/// Where something is written: a file as named on the command line, 1-based line and
/// column.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Location {
    /// The file.
    pub file: String,
    /// The line, from 1.
    pub line: usize,
    /// The column (in characters), from 1.
    pub column: usize,
}

impl Location {
    /// The start of `span`.
    pub fn of(sources: &Sources, span: crate::diag::Span) -> Location {
        let (line, column) = sources.line_col(span.file, span.start);
        Location { file: sources.name(span.file).to_string(), line, column }
    }
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.column)
    }
}

/// A warning about the input: an element the algebra cannot express, contradictory
/// assumptions.
#[derive(Clone, Debug, Serialize)]
pub struct WarningReport {
    /// What it says, without the location.
    pub message: String,
    /// Where: the element in the program, the first assumption in a property file.
    pub location: Option<Location>,
}

impl std::fmt::Display for WarningReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.location {
            Some(at) => write!(f, "{at}: {}", self.message),
            None => write!(f, "{}", self.message),
        }
    }
}

/// The result for one property.
#[derive(Clone, Debug, Serialize)]
pub struct PropertyReport {
    /// Its name.
    pub name: String,
    /// Where its statement starts in its property file.
    pub location: Option<Location>,
    /// The statement as printed.
    pub statement: String,
    /// The verdict.
    pub status: Status,
    /// Why it is unknown (or how it was refuted).
    pub reason: Option<String>,
    /// Wall-clock time in milliseconds.
    pub time_ms: f64,
    /// The checked proof (boxed, as the counterexamples: a run keeps every report).
    pub trace: Option<Box<TraceReport>>,
    /// The counterexample (only for `refuted`: confirmed).
    pub counterexample: Option<Box<CounterexampleReport>>,
    /// For `unknown`: a counterexample that only the exact evaluation confirms.
    pub candidate: Option<Box<CounterexampleReport>>,
    /// For `proved`: the property holds only vacuously (see `vacuity`).
    pub vacuous: bool,
    /// Why the property holds vacuously: inconsistent hypotheses, or a signal it reads
    /// forced to a constant.
    pub vacuity: Option<String>,
}

impl PropertyReport {
    /// The report without its proof and runs: what a summary and an exit status read.
    pub fn outline(self) -> PropertyReport {
        PropertyReport { trace: None, counterexample: None, candidate: None, ..self }
    }
}

/// Counts of verdicts.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Summary {
    /// Proved properties.
    pub proved: usize,
    /// Refuted properties.
    pub refuted: usize,
    /// Unknown properties.
    pub unknown: usize,
    /// Proved properties that hold only vacuously (counted among `proved` too).
    pub vacuous: usize,
}

impl Summary {
    /// The counts of `properties`.
    pub fn of(properties: &[PropertyReport]) -> Summary {
        let mut summary = Summary::default();
        properties.iter().for_each(|p| summary.count(p));
        summary
    }

    /// Counts one more property.
    pub fn count(&mut self, p: &PropertyReport) {
        match p.status {
            Status::Proved => self.proved += 1,
            Status::Refuted => self.refuted += 1,
            Status::Unknown => self.unknown += 1,
        }
        self.vacuous += usize::from(p.vacuous);
    }

    /// How many properties were counted.
    pub fn total(&self) -> usize {
        self.proved + self.refuted + self.unknown
    }

    /// Does the run fail: something refuted or unknown, or (when denied) vacuous?
    pub fn fails(&self, deny_vacuous: bool) -> bool {
        self.refuted + self.unknown > 0 || (deny_vacuous && self.vacuous > 0)
    }
}

/// Everything a run found.
#[derive(Clone, Debug, Serialize)]
pub struct RunReport {
    /// The ladder program, if there is one.
    pub program: Option<String>,
    /// The property files.
    pub files: Vec<String>,
    /// How the program's timers were compiled (`plc` or `ideal`); null without a program.
    pub timers: Option<&'static str>,
    /// `equiv`: the state correspondences `X = X'` proved before the outputs, which
    /// their proofs may cite (`state_X`); not verdicts of their own.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub correspondences: Vec<PropertyReport>,
    /// Per property.
    pub properties: Vec<PropertyReport>,
    /// Warnings (unconstrained elements and the like). After the results, so that a
    /// document written as the run goes ([`stream`]) has them all.
    pub warnings: Vec<WarningReport>,
    /// Totals.
    pub summary: Summary,
    /// The run was interrupted (Ctrl-C): `properties` are those finished before.
    pub interrupted: bool,
    /// When interrupted: the properties it did not finish, in file order.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub unchecked: Vec<Unchecked>,
    /// The program's compiled equations, as the HTML report's appendix shows them.
    #[serde(skip)]
    pub equations: Vec<EquationLine>,
}

/// One compiled equation of the program, as printed, and where it comes from.
#[derive(Clone, Debug)]
pub struct EquationLine {
    /// Its name (`L06a`), as proofs cite it.
    pub name: String,
    /// `L1_pump = 5s/L1_Prod`.
    pub text: String,
    /// The rung or element it is compiled from.
    pub location: Location,
}

/// A property an interrupted run did not finish.
#[derive(Clone, Debug, Serialize)]
pub struct Unchecked {
    /// Its name.
    pub name: String,
    /// Where it is written.
    pub location: Location,
}

impl RunReport {
    /// 0 when every property is proved, 1 otherwise.
    pub fn exit_code(&self) -> i32 {
        i32::from(self.summary.fails(false))
    }
}
