//! Selection: which POU of a project is checked (`--pou`, the configuration's task), at
//! which cycle, and with which start values (`--cold-start`) and statement order
//! (`--order`); the POU's body is checked in `check.rs`, its operands resolved in
//! `operand.rs`, tool-dependent constructs refused in `refusals.rs`, its statements
//! ordered in `order.rs`, and the result is the `PlcProgram` of `program.rs`.

use super::*;
use crate::diag::{Span, did_you_mean};

mod check;
mod operand;
mod order;
mod program;
mod refusals;

pub use order::ORDER_CHOICE;
pub(in crate::ladder::plcopen) use order::geometric;

pub use check::hmi_base;
pub use program::{
    Operand, OrderRule, PlcProgram, Source, Std, bool_literal, bool_of_int_literal,
    is_known_library_block, is_true, unconnected,
};

/// What the user asks for: which POU, which cycle.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Selection {
    /// `--pou NAME`.
    pub pou: Option<String>,
    /// `--cycle`, in µs.
    pub cycle_us: Option<u64>,
    /// `--cold-start`: retained variables start at their declared initial values, as
    /// after a cold restart (by default they start with any value, as after a warm one).
    pub cold_start: bool,
    /// `--order`: which editor's statement order, when positions and document order
    /// differ (by default such a file is refused if the two orders compile differently).
    pub order: Option<StatementOrder>,
    /// The timer instances (upper case) whose elapsed time `ET` the properties name
    /// (`[T1.ET < T#2s]`, `[T1_ET < T#2s]`): the IEC text front end computes it as if
    /// the program read it.
    pub elapsed: std::collections::BTreeSet<String>,
}

/// The statement order of LD/FBD bodies whose positions and document order differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StatementOrder {
    /// By position, rows top to bottom, each left to right (Beremiz before its 2022
    /// Python 3 port, the OpenPLC editor built on it).
    Layout,
    /// Document order (Beremiz since 2022).
    Document,
}

/// The cycle used when neither the task nor the command line gives one (Beremiz's default task interval is 20 ms... the OpenPLC runtime's default tick).
pub const DEFAULT_CYCLE_US: u64 = 20_000;

/// The refusal of a configuration whose tasks run several graphical programs: at the
/// task whose interval differs from the first's (running each at its own rate is not
/// modelled), else at the configuration (programs composed in one cycle are not).
fn several_programs<'p>(
    several: &[&'p Pou],
    task_of: &dyn Fn(&Pou) -> Option<&'p Task>,
) -> PlcError {
    let names: Vec<&str> = several.iter().map(|p| p.name.as_str()).collect();
    let choose = format!("choose one with --pou (candidates: {})", names.join(", "));
    let interval = |p: &Pou| -> Option<(u64, Span)> {
        let (text, span) = task_of(p)?.interval.as_ref()?;
        let us = parse_duration(text).or_else(|| parse_duration(&format!("T#{}", text.trim())))?;
        Some((us, *span))
    };
    let first = interval(several[0]);
    let other = several[1..].iter().find_map(|p| match (interval(p), first) {
        (Some((us, span)), Some((f, _))) if us != f => Some((p, us, span)),
        _ => None,
    });
    if let (Some((p, us, span)), Some((f, _))) = (other, first) {
        let ms = |us: u64| format!("{} ms", us as f64 / 1000.0);
        return PlcError::Unsupported {
            span,
            what: format!(
                "a configuration whose tasks run at different intervals (`{}` every {}, `{}` every {})",
                several[0].name,
                ms(f),
                p.name,
                ms(us)
            ),
            reason: format!("running each program at its own rate is not modelled yet; {choose}"),
        };
    }
    PlcError::Unsupported {
        span: task_of(several[1])
            .and_then(|t| t.instances.first())
            .map_or(several[1].span, |i| i.2),
        what: format!(
            "a configuration running {} graphical programs ({})",
            names.len(),
            names.join(", ")
        ),
        reason: format!("composing LD/FBD programs in one cycle is not modelled yet; {choose}"),
    }
}

/// A program run by an event task (`single`) runs when the trigger rises, not every
/// cycle: refused at the task, saying so.
pub(super) fn event_task(pou: &Pou, task: Option<&Task>) -> Result<(), Vec<PlcError>> {
    match task.and_then(|t| t.single.map(|s| (t, s))) {
        Some((t, span)) => Err(vec![PlcError::Unsupported {
            span,
            what: format!("the event task `{}` running `{}`", t.name, pou.name),
            reason: "a program an event triggers runs on some cycles only, which is not modelled yet; choose a cyclic program with --pou".into(),
        }]),
        None => Ok(()),
    }
}

/// Picks the program to check: `--pou`, else the POU the configuration's task runs, else the only program.
pub(super) fn pick<'p>(
    project: &'p Project,
    sel: &Selection,
) -> Result<(&'p Pou, Option<&'p Task>), Vec<PlcError>> {
    let programs: Vec<&Pou> = project.pous.iter().filter(|p| p.kind == PouKind::Program).collect();
    let candidates = |kind: &str, name: &str, pous: &[&Pou]| PlcError::Unknown {
        span: project.span,
        kind: kind.into(),
        name: name.into(),
        candidates: match did_you_mean(name, pous.iter().map(|p| p.name.as_str())) {
            Some(near) => vec![near.to_string()],
            None => pous.iter().map(|p| p.name.clone()).collect(),
        },
        ambiguous: false,
    };
    let task_of = |pou: &Pou| {
        project
            .tasks
            .iter()
            .find(|t| t.instances.iter().any(|(_, ty, _)| ty.eq_ignore_ascii_case(&pou.name)))
    };
    if let Some(want) = &sel.pou {
        let found: Vec<&Pou> =
            project.pous.iter().filter(|p| p.name.eq_ignore_ascii_case(want)).collect();
        return match found.as_slice() {
            [p] => Ok((p, task_of(p))),
            [] => Err(vec![candidates("POU (--pou)", want, &programs)]),
            many => Err(vec![PlcError::Unknown {
                span: project.span,
                kind: "POU (--pou)".into(),
                name: want.clone(),
                candidates: many.iter().map(|p| p.name.clone()).collect(),
                ambiguous: true,
            }]),
        };
    }
    let run: Vec<&Pou> = programs.iter().copied().filter(|p| task_of(p).is_some()).collect();
    match (run.as_slice(), programs.as_slice()) {
        ([p], _) => Ok((p, task_of(p))),
        ([], [p]) => Ok((p, None)),
        ([], []) => {
            let graphical: Vec<&Pou> = project
                .pous
                .iter()
                .filter(|p| p.body.as_ref().is_some_and(|b| matches!(b.lang, Lang::Ld | Lang::Fbd)))
                .collect();
            Err(vec![if graphical.is_empty() {
                PlcError::Unsupported {
                    span: project.span,
                    what: "a project without a program POU".into(),
                    reason: "there is nothing to scan, and no POU has an LD or FBD body".into(),
                }
            } else {
                PlcError::Unsupported {
                    span: project.span,
                    what: "a project without a program POU".into(),
                    reason: format!(
                        "choose the function block to check with --pou (candidates: {})",
                        graphical.iter().map(|p| p.name.as_str()).collect::<Vec<_>>().join(", ")
                    ),
                }
            }])
        }
        (several, _) if !several.is_empty() => Err(vec![several_programs(several, &task_of)]),
        (_, all) => Err(vec![PlcError::Unknown {
            span: project.span,
            kind: "program to check: no task runs one and there are several; choose one with --pou, e.g. --pou".into(),
            name: all[0].name.clone(),
            candidates: all.iter().map(|p| p.name.clone()).collect(),
            ambiguous: true,
        }]),
    }
}

/// Checks the chosen POU and resolves it into a [`PlcProgram`].
pub fn select(project: &Project, sel: &Selection) -> Result<PlcProgram, Vec<PlcError>> {
    let (pou, task) = pick(project, sel)?;
    event_task(pou, task)?;
    if !pou.errors.is_empty() {
        return Err(pou.errors.clone());
    }
    let mut warnings = Vec::new();
    let mut errors = Vec::new();
    if pou.body.is_none() {
        return Err(vec![PlcError::Unsupported {
            span: pou.span,
            what: format!("POU `{}` without a body", pou.name),
            reason: "there is nothing to scan".into(),
        }]);
    }
    // The cycle: --cycle, else the task interval, else the default.
    let cycle_us = match (sel.cycle_us, task.and_then(|t| t.interval.as_ref())) {
        (Some(c), _) => c,
        // `T#20ms`, 1.0's `00:00:00.020000`, or a bare `20ms`.
        (None, Some((text, span))) => {
            match parse_duration(text).or_else(|| parse_duration(&format!("T#{}", text.trim()))) {
                Some(c) if c > 0 => c,
                _ => {
                    errors.push(PlcError::Malformed {
                        span: *span,
                        what: format!("task interval `{text}`"),
                        expected: "a positive duration such as `T#20ms` (or give --cycle)".into(),
                    });
                    DEFAULT_CYCLE_US
                }
            }
        }
        (None, None) => {
            warnings.push(PlcError::Note {
                span: pou.span,
                message: format!(
                    "no task with an interval runs `{}`: the scan cycle is taken to be {} ms \
                     (give --cycle to choose it)",
                    pou.name,
                    DEFAULT_CYCLE_US / 1000
                ),
            });
            DEFAULT_CYCLE_US
        }
    };
    if !errors.is_empty() {
        return Err(errors);
    }
    let mut program = check::check_pou(project, pou, cycle_us, 0)?;
    if let Some(choice) = sel.order {
        program.choose_order(choice);
    }
    warnings.append(&mut program.warnings);
    program.start_retained(sel.cold_start, &mut warnings);
    program.warnings = warnings;
    Ok(program)
}

impl PlcProgram {
    /// After a cold restart (`cold`) a retained variable starts at its declared value;
    /// otherwise with any value. Either way a note says which, at the variable.
    fn start_retained(&mut self, cold: bool, warnings: &mut Vec<PlcError>) {
        let retained: Vec<(String, String)> = self
            .starts
            .iter()
            .filter_map(|(x, s)| s.as_ref().map(|s| (x.clone(), s.clone())))
            .collect();
        for (x, start) in retained {
            let Some(v) = self.vars.values().find(|v| v.name == x) else { continue };
            let declared = v.init.as_deref().is_some_and(is_true);
            let message = if cold {
                format!(
                    "`{x}` is retained; with --cold-start it starts at its declared value \
                     ({})",
                    if declared { "TRUE" } else { "FALSE" }
                )
            } else {
                format!(
                    "`{x}` is retained: after a warm restart it starts with the value it had, \
                     so it may be TRUE or FALSE at the first scan (`{start}`); --cold-start \
                     starts it at its declared value"
                )
            };
            warnings.push(PlcError::Note { span: v.span, message });
            if cold {
                self.inputs.remove(&start);
                if declared {
                    self.starts.insert(x, None);
                } else {
                    self.starts.remove(&x);
                }
            }
        }
    }
}
