//! The programs a file runs each scan, in order: the one `--pou` names, else every program instance of its configuration by task priority, else its one `PROGRAM`.

use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::{self, Ident, PouKind};

/// One program instance to run each scan: the program, its task, and the prefix its
/// local names take (`None`: its names are used as they are).
pub(super) struct Run<'u> {
    pub(super) pou: &'u ast::Pou,
    pub(super) task: Option<&'u ast::Task>,
    pub(super) instance: Option<&'u ast::Instance>,
}

/// The programs to run each scan, in order: `--pou`'s, else every program instance of the
/// configuration (by task priority, then declaration; instances without a task last),
/// else the file's one `PROGRAM`.
pub(super) fn pick<'u>(
    unit: &'u ast::Unit,
    pou: Option<&str>,
) -> Result<Vec<Run<'u>>, Vec<StError>> {
    let programs: Vec<&ast::Pou> =
        unit.pous.iter().filter(|p| p.kind == PouKind::Program).collect();
    let find =
        |name: &str| programs.iter().copied().find(|p| p.name.name.eq_ignore_ascii_case(name));
    let tasks: Vec<&ast::Task> = unit.configs.iter().flat_map(|c| &c.tasks).collect();
    let task_named =
        |t: &Ident| tasks.iter().copied().find(|k| k.name.name.eq_ignore_ascii_case(&t.name));
    let instances: Vec<&ast::Instance> = unit.configs.iter().flat_map(|c| &c.instances).collect();
    if let Some(name) = pou {
        return match find(name) {
            Some(p) => {
                let instance = instances
                    .iter()
                    .copied()
                    .find(|i| i.ty.name.eq_ignore_ascii_case(&p.name.name));
                let task = instance.and_then(|i| i.task.as_ref()).and_then(task_named);
                Ok(vec![Run { pou: p, task, instance: None }])
            }
            None => {
                let span = programs.first().map_or(Span::new(0, 0..0), |p| p.name.span);
                let mut e = StError::new(
                    span,
                    format!("no PROGRAM `{name}` in this file"),
                    "the programs are declared here",
                );
                if let Some(m) =
                    crate::diag::did_you_mean(name, programs.iter().map(|p| p.name.name.as_str()))
                {
                    e.notes.push(format!("did you mean `{m}`?"));
                }
                Err(vec![e])
            }
        };
    }
    if instances.is_empty() {
        return match programs.as_slice() {
            [one] => Ok(vec![Run { pou: one, task: None, instance: None }]),
            [] => Err(vec![StError::new(
                Span::new(0, 0..0),
                "no PROGRAM in this file",
                "a program to check is a `PROGRAM … END_PROGRAM`",
            )]),
            many => {
                let names: Vec<&str> = many.iter().map(|p| p.name.name.as_str()).collect();
                Err(vec![StError::new(
                    many[1].name.span,
                    format!(
                        "this file has {} programs ({}) and no configuration runs them: choose one with --pou",
                        many.len(),
                        names.join(", ")
                    ),
                    "a second program",
                )])
            }
        };
    }
    let mut runs = Vec::new();
    let mut errors = Vec::new();
    for i in &instances {
        let task = i.task.as_ref().and_then(task_named);
        if let (Some(t), None) = (&i.task, task) {
            errors.push(StError::new(
                t.span,
                format!("no task `{}` in this configuration", t.name),
                "not declared",
            ));
        }
        match find(&i.ty.name) {
            Some(p) => runs.push(Run { pou: p, task, instance: Some(*i) }),
            None => errors.push(StError::new(
                i.ty.span,
                format!("no PROGRAM `{}` in this file", i.ty.name),
                "this program type is not declared",
            )),
        }
    }
    // An event task runs its programs when its trigger rises, not every cycle.
    for r in &runs {
        if let Some(t) = r.task.filter(|t| t.single) {
            errors.push(StError::new(
                t.name.span,
                format!(
                    "the event task `{}` (SINGLE) runs `{}` when its trigger rises: event tasks are not modelled yet; choose a cyclic program with --pou",
                    t.name.name, r.pou.name.name
                ),
                "an event task",
            ));
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    // Higher priority (a smaller number) first, then declaration order; no task last.
    runs.sort_by_key(|r| r.task.map_or(i128::MAX, |t| t.priority));
    Ok(runs)
}
