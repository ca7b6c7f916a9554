//! Reports for tools and CI systems: JSON, JUnit XML, SARIF 2.1.0 and GitHub Actions
//! workflow commands, each rendered from a [`RunReport`].
//!
//! - **JUnit XML**: a `<testsuite>` per property file, a `<testcase>` per property
//!   (`file` and `line` attributes); a refuted property is a `<failure>` whose text is
//!   the counterexample, an unknown one is `<skipped>` with the reason in
//!   `<system-out>`, a property an interrupted run did not finish is an `<error>`, a
//!   vacuous proof is a `<failure>` under `--deny vacuous` and noted in `<system-out>`
//!   otherwise;
//!   warnings are the `<system-err>` of the first suite.
//! - **SARIF 2.1.0**: one run; a result per refuted (`error`) or unknown (`warning`)
//!   property, per vacuous proof and per warning, each with its file, line and column.
//! - **GitHub**: one line per property as in the text report, and a workflow command
//!   (`::error file=…,line=…,col=…,title=…::…`) for each refuted, unknown or vacuous
//!   property and each warning, which GitHub shows as an annotation at that line.

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesText, Event};
use serde_json::json;

use super::text::{Paint, render_property, summary_line};
use super::{Location, Options, PropertyReport, RunReport, Status, WarningReport};

/// The report formats of `--format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// For people: a line per property, proofs with `--trace`, a summary.
    Text,
    /// One JSON object (see the README for its fields).
    Json,
    /// JUnit XML: a test case per property.
    Junit,
    /// SARIF 2.1.0: a result per refuted or unknown property and per warning.
    Sarif,
    /// GitHub Actions workflow commands: an annotation per failure and warning.
    Github,
    /// One self-contained HTML page: summary, proofs, timing diagrams, the program.
    Html,
}

impl Format {
    /// Formats written line by line as results come (the others are one document).
    pub fn streams(self) -> bool {
        matches!(self, Format::Text | Format::Github)
    }
}

/// The whole report in `format`.
pub fn render(format: Format, report: &RunReport, opts: &Options) -> String {
    match format {
        Format::Text => super::render_text(report, opts),
        Format::Json => super::render_json(report),
        Format::Junit => junit(report, opts),
        Format::Sarif => sarif(report, opts),
        Format::Html => super::html::html(report),
        Format::Github => {
            let mut out: String = report.warnings.iter().map(github_warning).collect();
            let width = super::text::name_width(report.properties.iter().map(|p| p.name.as_str()));
            for p in &report.properties {
                out.push_str(&github_property(p, width, opts));
            }
            out.push_str(&summary_line(&report.summary, report.timers));
            out
        }
    }
}

/// A property's text lines (the verdict line, the reason, the counterexample), without colour.
fn plain(p: &PropertyReport, opts: &Options) -> String {
    render_property(p, 0, opts, Paint::default())
}

/// The verdict of a property as a CI system sees it: `None` when it passes.
fn failure(p: &PropertyReport, opts: &Options) -> Option<(&'static str, String)> {
    match p.status {
        Status::Refuted => Some(("refuted", format!("{} is refuted: {}", p.name, p.statement))),
        // The reason follows in each format's details (one copy of it).
        Status::Unknown => Some((
            "unknown",
            format!("{} is unknown (neither proved nor refuted): {}", p.name, p.statement),
        )),
        Status::Proved if p.vacuous => Some((
            "vacuous",
            format!(
                "{} holds only vacuously{}: {}",
                p.name,
                if opts.deny_vacuous { " (denied)" } else { "" },
                p.vacuity.as_deref().unwrap_or("")
            ),
        )),
        Status::Proved => None,
    }
}

// ----------------------------------------------------------------------------- JUnit

/// JUnit XML (the schema Jenkins, GitLab and most CI systems read).
pub fn junit(report: &RunReport, opts: &Options) -> String {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    let result = write_junit(&mut w, report, opts);
    debug_assert!(result.is_ok(), "writing to memory cannot fail");
    let mut out = String::from_utf8(w.into_inner()).unwrap_or_default();
    out.push('\n');
    out
}

fn seconds(ms: f64) -> String {
    format!("{:.3}", ms / 1e3)
}

fn write_junit(w: &mut Writer<Vec<u8>>, report: &RunReport, opts: &Options) -> std::io::Result<()> {
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    let props = &report.properties;
    let count = |f: &dyn Fn(&PropertyReport) -> bool| props.iter().filter(|p| f(p)).count();
    let failed = |p: &PropertyReport| {
        p.status == Status::Refuted
            || (p.status == Status::Proved && p.vacuous && opts.deny_vacuous)
    };
    let skipped = |p: &PropertyReport| p.status == Status::Unknown;
    let total_ms: f64 = props.iter().map(|p| p.time_ms).sum();
    // One suite per property file, in the order given.
    let mut files: Vec<&str> = Vec::new();
    let located = props.iter().map(|p| p.location.as_ref().map_or("", |l| l.file.as_str()));
    for file in located.chain(report.unchecked.iter().map(|u| u.location.file.as_str())) {
        if !files.contains(&file) {
            files.push(file);
        }
    }
    // An interrupted run: each property it did not finish is a test case in error.
    let unchecked_in = |file: &str| -> Vec<&super::Unchecked> {
        report.unchecked.iter().filter(|u| u.location.file == file).collect()
    };
    let errors = report.unchecked.len();
    let (tests, failures, skips) = (props.len() + errors, count(&failed), count(&skipped));
    w.create_element("testsuites")
        .with_attribute(("name", "ii-prove"))
        .with_attribute(("tests", tests.to_string().as_str()))
        .with_attribute(("failures", failures.to_string().as_str()))
        .with_attribute(("errors", errors.to_string().as_str()))
        .with_attribute(("skipped", skips.to_string().as_str()))
        .with_attribute(("time", seconds(total_ms).as_str()))
        .write_inner_content(|w| {
            for (i, file) in files.iter().enumerate() {
                let in_file: Vec<&PropertyReport> = props
                    .iter()
                    .filter(|p| p.location.as_ref().map_or("", |l| l.file.as_str()) == *file)
                    .collect();
                let not_run = unchecked_in(file);
                let ms: f64 = in_file.iter().map(|p| p.time_ms).sum();
                let suite_name = match &report.program {
                    Some(program) => format!("{program}: {file}"),
                    None => file.to_string(),
                };
                w.create_element("testsuite")
                    .with_attribute(("name", suite_name.as_str()))
                    .with_attribute(("tests", (in_file.len() + not_run.len()).to_string().as_str()))
                    .with_attribute((
                        "failures",
                        in_file.iter().filter(|p| failed(p)).count().to_string().as_str(),
                    ))
                    .with_attribute(("errors", not_run.len().to_string().as_str()))
                    .with_attribute((
                        "skipped",
                        in_file.iter().filter(|p| skipped(p)).count().to_string().as_str(),
                    ))
                    .with_attribute(("time", seconds(ms).as_str()))
                    .write_inner_content(|w| {
                        for p in &in_file {
                            write_testcase(w, p, file, opts)?;
                        }
                        for u in &not_run {
                            let line = u.location.line.to_string();
                            let message = format!(
                                "the run was interrupted (Ctrl-C) before {} was checked",
                                u.name
                            );
                            w.create_element("testcase")
                                .with_attribute(("name", u.name.as_str()))
                                .with_attribute(("classname", *file))
                                .with_attribute(("file", *file))
                                .with_attribute(("line", line.as_str()))
                                .with_attribute(("time", "0.000"))
                                .write_inner_content(|w| {
                                    w.create_element("error")
                                        .with_attribute(("type", "interrupted"))
                                        .with_attribute(("message", message.as_str()))
                                        .write_empty()?;
                                    Ok(())
                                })?;
                        }
                        if i == 0 && !report.warnings.is_empty() {
                            let text: String =
                                report.warnings.iter().map(|x| format!("warning: {x}\n")).collect();
                            w.create_element("system-err")
                                .write_text_content(BytesText::new(&text))?;
                        }
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

fn write_testcase(
    w: &mut Writer<Vec<u8>>,
    p: &PropertyReport,
    file: &str,
    opts: &Options,
) -> std::io::Result<()> {
    let line = p.location.as_ref().map_or(0, |l| l.line).to_string();
    let case = w
        .create_element("testcase")
        .with_attribute(("name", p.name.as_str()))
        .with_attribute(("classname", file))
        .with_attribute(("file", file))
        .with_attribute(("line", line.as_str()))
        .with_attribute(("time", seconds(p.time_ms).as_str()));
    let details = plain(p, opts);
    match (p.status, failure(p, opts)) {
        (Status::Refuted, Some((kind, message))) => case.write_inner_content(|w| {
            w.create_element("failure")
                .with_attribute(("type", kind))
                .with_attribute(("message", message.as_str()))
                .write_text_content(BytesText::new(&details))?;
            Ok(())
        })?,
        (Status::Unknown, Some((_, message))) => case.write_inner_content(|w| {
            w.create_element("skipped")
                .with_attribute(("message", message.as_str()))
                .write_empty()?;
            w.create_element("system-out").write_text_content(BytesText::new(&details))?;
            Ok(())
        })?,
        (Status::Proved, Some((kind, message))) => case.write_inner_content(|w| {
            if opts.deny_vacuous {
                w.create_element("failure")
                    .with_attribute(("type", kind))
                    .with_attribute(("message", message.as_str()))
                    .write_text_content(BytesText::new(&details))?;
            } else {
                w.create_element("system-out").write_text_content(BytesText::new(&message))?;
            }
            Ok(())
        })?,
        _ => case.write_empty()?,
    };
    Ok(())
}

// ----------------------------------------------------------------------------- SARIF

/// The rules of the SARIF report, by id.
const RULES: &[(&str, &str, &str)] = &[
    ("refuted", "The property is false: a confirmed counterexample violates it.", "error"),
    ("unknown", "The property was neither proved nor refuted within the limits.", "warning"),
    ("vacuous", "The property holds only vacuously: its hypotheses force it.", "warning"),
    (
        "correspondence",
        "A state correspondence of two compared programs, proved and cited by the outputs' proofs.",
        "note",
    ),
    ("input-warning", "The input has an element or assumption that weakens the proofs.", "warning"),
];

/// A SARIF artifact URI for a path as given on the command line: forward slashes,
/// spaces and `%` escaped; an absolute path becomes a `file://` URI.
fn uri(path: &str) -> String {
    let slashed = path.replace('\\', "/").replace('%', "%25").replace(' ', "%20");
    if slashed.starts_with('/') { format!("file://{slashed}") } else { slashed }
}

fn sarif_location(at: &Location) -> serde_json::Value {
    json!({
        "physicalLocation": {
            "artifactLocation": { "uri": uri(&at.file) },
            "region": { "startLine": at.line.max(1), "startColumn": at.column.max(1) }
        }
    })
}

/// SARIF 2.1.0 (GitHub code scanning, many editors and dashboards read it).
pub fn sarif(report: &RunReport, opts: &Options) -> String {
    let mut results = Vec::new();
    for p in &report.properties {
        let Some((rule, message)) = failure(p, opts) else { continue };
        let level = match rule {
            "refuted" => "error",
            "vacuous" if opts.deny_vacuous => "error",
            _ => "warning",
        };
        let mut result = json!({
            "ruleId": rule,
            "ruleIndex": RULES.iter().position(|r| r.0 == rule).unwrap_or(0),
            "level": level,
            "message": { "text": format!("{message}\n{}", plain(p, opts)) },
            "properties": { "property": p.name, "time_ms": p.time_ms },
        });
        if let Some(at) = &p.location {
            result["locations"] = json!([sarif_location(at)]);
        }
        results.push(result);
    }
    for c in &report.correspondences {
        results.push(json!({
            "ruleId": "correspondence",
            "ruleIndex": RULES.len() - 2,
            "level": "note",
            "message": { "text": format!("state correspondence {} proved: the outputs' proofs may cite it as `{}`", c.statement, c.name) },
            "properties": { "property": c.name, "time_ms": c.time_ms },
        }));
    }
    for w in &report.warnings {
        let mut result = json!({
            "ruleId": "input-warning",
            "ruleIndex": RULES.len() - 1,
            "level": "warning",
            "message": { "text": w.message },
        });
        if let Some(at) = &w.location {
            result["locations"] = json!([sarif_location(at)]);
        }
        results.push(result);
    }
    let rules: Vec<serde_json::Value> = RULES
        .iter()
        .map(|(id, text, level)| {
            json!({
                "id": id,
                "shortDescription": { "text": text },
                "defaultConfiguration": { "level": level }
            })
        })
        .collect();
    let mut artifacts: Vec<String> = report.files.iter().map(|f| uri(f)).collect();
    if let Some(program) = &report.program {
        artifacts.insert(0, uri(program));
    }
    let doc = json!({
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [{
            "tool": { "driver": {
                "name": "ii-prove",
                "version": env!("CARGO_PKG_VERSION"),
                "rules": rules,
            }},
            "artifacts": artifacts.iter().map(|a| json!({ "location": { "uri": a } })).collect::<Vec<_>>(),
            "invocations": [{ "executionSuccessful": !report.interrupted }],
            "results": results,
        }]
    });
    serde_json::to_string_pretty(&doc).unwrap_or_default() + "\n"
}

// ----------------------------------------------------------------------------- GitHub

/// Escapes the message of a workflow command.
fn escape_data(text: &str) -> String {
    text.replace('%', "%25").replace('\r', "%0D").replace('\n', "%0A")
}

/// Escapes a property (`file=`, `title=`) of a workflow command.
fn escape_property(text: &str) -> String {
    escape_data(text).replace(':', "%3A").replace(',', "%2C")
}

fn command(kind: &str, at: Option<&Location>, title: &str, message: &str) -> String {
    let mut props = Vec::new();
    if let Some(at) = at {
        props.push(format!("file={}", escape_property(&at.file)));
        props.push(format!("line={}", at.line));
        props.push(format!("col={}", at.column));
    }
    props.push(format!("title={}", escape_property(title)));
    format!("::{kind} {}::{}\n", props.join(","), escape_data(message))
}

/// A property's text line(s), then an annotation when it fails or is vacuous.
pub fn github_property(p: &PropertyReport, width: usize, opts: &Options) -> String {
    let mut out = render_property(p, width, opts, Paint::default());
    if let Some((kind, message)) = failure(p, opts) {
        let level = match kind {
            "refuted" => "error",
            "vacuous" if opts.deny_vacuous => "error",
            _ => "warning",
        };
        let mut detail: Vec<String> = match (&p.counterexample, &p.candidate) {
            (Some(c), _) => super::text::counterexample_lines(c),
            (None, Some(c)) => vec![super::text::candidate_line(c)],
            _ => Vec::new(),
        };
        if p.status == Status::Unknown
            && let Some(reason) = &p.reason
        {
            detail.splice(0..0, reason.lines().map(str::to_string));
        }
        if let Some(c) = p.counterexample.as_ref().or(p.candidate.as_ref()) {
            detail.extend(c.diagram.iter().cloned());
        }
        let detail: String = detail.iter().map(|l| format!("\n{l}")).collect();
        let title = format!("{} {kind}", p.name);
        out.push_str(&command(level, p.location.as_ref(), &title, &format!("{message}{detail}")));
    }
    out
}

/// A warning as an annotation.
pub fn github_warning(w: &WarningReport) -> String {
    command("warning", w.location.as_ref(), "ii-prove warning", &w.message)
}
