//! The text report for people: one line per property (verdict, time, statement, where
//! it is written), proofs and counterexamples when asked, a summary; in colour when
//! asked.

use anstyle::{AnsiColor, Style};

use super::{
    CounterexampleReport, Options, PropertyReport, RunReport, Status, Summary, WarningReport,
};

/// Colours for the text report (none when `enabled` is false).
#[derive(Clone, Copy, Debug, Default)]
pub struct Paint {
    /// Whether to emit ANSI colour codes.
    pub enabled: bool,
}

impl Paint {
    fn paint(self, style: Style, text: &str) -> String {
        if self.enabled {
            format!("{}{text}{}", style.render(), style.render_reset())
        } else {
            text.into()
        }
    }

    /// A verdict word, padded to `width` before colouring (so columns stay aligned).
    pub fn status(self, status: Status, width: usize) -> String {
        let (word, color) = match status {
            Status::Proved => ("proved", AnsiColor::Green),
            Status::Refuted => ("refuted", AnsiColor::Red),
            Status::Unknown => ("unknown", AnsiColor::Yellow),
        };
        self.paint(Style::new().fg_color(Some(color.into())).bold(), &format!("{word:<width$}"))
    }

    /// `warning:` in yellow.
    pub fn warning(self) -> String {
        self.paint(Style::new().fg_color(Some(AnsiColor::Yellow.into())).bold(), "warning:")
    }

    /// `error:` in red.
    pub fn error(self) -> String {
        self.paint(Style::new().fg_color(Some(AnsiColor::Red.into())).bold(), "error:")
    }
}

/// The text report: warnings, one line per property, proofs and counterexamples when
/// asked, a summary.
pub fn render_text(report: &RunReport, opts: &Options) -> String {
    let paint = Paint::default();
    let mut out: String = report.warnings.iter().map(|w| render_warning(w, paint)).collect();
    let width = name_width(report.properties.iter().map(|p| p.name.as_str()));
    for p in &report.properties {
        out.push_str(&render_property(p, width, opts, paint));
    }
    out.push_str(&summary_line(&report.summary, report.timers));
    out
}

/// The width of the name column.
pub fn name_width<'a>(names: impl IntoIterator<Item = &'a str>) -> usize {
    names.into_iter().map(|n| n.chars().count()).max().unwrap_or(0)
}

/// `warning: FILE:LINE:COL: message`.
pub fn render_warning(w: &WarningReport, paint: Paint) -> String {
    format!("{} {w}\n", paint.warning())
}

/// A state correspondence of `equiv` (under a heading when it is the `first`): its
/// name, statement and proof method, the proof's lines under `--trace`.
pub fn render_correspondence(report: &PropertyReport, first: bool, opts: &Options) -> String {
    let mut out = String::new();
    if first {
        out.push_str("state correspondences (proved first; the outputs' proofs may cite them):\n");
    }
    let how = report.trace.as_ref().map_or(String::new(), |t| {
        format!(
            "   proved by {} ({} line{})",
            t.method,
            t.length,
            if t.length == 1 { "" } else { "s" }
        )
    });
    out.push_str(&format!("  {}   {}{how}\n", report.name, report.statement));
    if opts.trace
        && let Some(t) = &report.trace
    {
        for l in &t.lines {
            out.push_str(&format!("      {l}\n"));
        }
    }
    out
}

/// One property: its line (name, verdict, time, statement, location), the reason, the
/// proof when `--trace`, a vacuity warning, the counterexample.
pub fn render_property(p: &PropertyReport, width: usize, opts: &Options, paint: Paint) -> String {
    let mut out = String::new();
    let at = p.location.as_ref().map(|l| format!("   ({l})")).unwrap_or_default();
    out.push_str(&format!(
        "{:<width$}  {} {:>9.1} ms   {}{at}\n",
        p.name,
        paint.status(p.status, 8),
        p.time_ms,
        p.statement
    ));
    if let Some(reason) = &p.reason {
        out.push_str(&reason_text(reason, &format!("{:<width$}  ", "")));
    }
    if opts.trace
        && let Some(t) = &p.trace
    {
        for line in &t.lines {
            out.push_str(&format!("{line}\n"));
        }
    }
    if let Some(why) = &p.vacuity {
        out.push_str(&format!("{:<width$}  {} vacuous: {why}\n", "", paint.warning()));
    }
    if let Some(c) = &p.counterexample {
        for line in counterexample_lines(c).iter().chain(&c.diagram) {
            out.push_str(&format!("    {line}\n"));
        }
    }
    if let Some(c) = &p.candidate {
        out.push_str(&candidate_text(c, "    "));
    }
    out
}

/// What a confirmed counterexample shows, before its diagram: where the property
/// fails, the two sides there, what confirmed it.
pub fn counterexample_lines(c: &CounterexampleReport) -> Vec<String> {
    let at = match c.scan {
        Some(k) => format!("at t = {} s (scan {k})", c.time),
        None => format!("at t = {}", c.time),
    };
    let mut lines = vec![format!(
        "counterexample: {at} the left side is {} and the right side is {}",
        c.lhs as u8, c.rhs as u8
    )];
    if let Some(k) = c.simulator_scan {
        lines.push(format!(
            "confirmed by exact evaluation and by the scan simulator (violated at scan {k})"
        ));
    }
    lines
}

/// `reason: ` and the reason's first line, its other lines aligned under it, each
/// after `indent`.
pub fn reason_text(reason: &str, indent: &str) -> String {
    let mut out = String::new();
    for (i, line) in reason.lines().enumerate() {
        let head = if i == 0 { "reason: " } else { "        " };
        out.push_str(&format!("{indent}{head}{line}\n"));
    }
    out
}

/// The first line of an unconfirmed counterexample.
pub fn candidate_line(c: &CounterexampleReport) -> String {
    match &c.title {
        Some(title) => title.clone(),
        None => format!(
            "possible counterexample (exact evaluation only, not confirmed by the scan simulator): at t = {} s",
            c.time
        ),
    }
}

/// An unconfirmed counterexample, said to be one, with its diagram, indented by `indent`.
pub fn candidate_text(c: &CounterexampleReport, indent: &str) -> String {
    let mut out = format!("{indent}{}\n", candidate_line(c));
    for line in &c.diagram {
        out.push_str(&format!("    {line}\n"));
    }
    out
}

/// `N proved, N refuted, N unknown`, with `(N vacuous)` after the proved count when
/// some proof is vacuous, and `(--timers plc)` for a program.
pub fn summary_line(s: &Summary, timers: Option<&str>) -> String {
    let vacuous = if s.vacuous > 0 { format!(" ({} vacuous)", s.vacuous) } else { String::new() };
    let timers = timers.map(|t| format!(" (--timers {t})")).unwrap_or_default();
    format!("{} proved{vacuous}, {} refuted, {} unknown{timers}\n", s.proved, s.refuted, s.unknown)
}
