//! The text report for people: one line per property, proofs and counterexamples when
//! asked, a summary.

use super::{Options, RunReport, Status};

/// The text report: one line per property, proofs and counterexamples when asked, a summary.
pub fn render_text(report: &RunReport, opts: &Options) -> String {
    let mut out = String::new();
    for w in &report.warnings {
        out.push_str(&format!("warning: {w}\n"));
    }
    let width = report.properties.iter().map(|p| p.name.chars().count()).max().unwrap_or(0);
    for p in &report.properties {
        let status = match p.status {
            Status::Proved => "proved",
            Status::Refuted => "refuted",
            Status::Unknown => "unknown",
        };
        out.push_str(&format!(
            "{:<width$}  {status:<8} {:>9.1} ms   {}\n",
            p.name, p.time_ms, p.statement
        ));
        if let Some(reason) = &p.reason {
            out.push_str(&format!("{:<width$}  reason: {reason}\n", ""));
        }
        if opts.trace
            && let Some(t) = &p.trace
        {
            for line in &t.lines {
                out.push_str(&format!("{line}\n"));
            }
        }
        if let Some(why) = &p.vacuity {
            out.push_str(&format!("{:<width$}  warning: vacuous: {why}\n", ""));
        }
        if let Some(c) = &p.counterexample {
            let at = match c.scan {
                Some(k) => format!("at t = {} s (scan {k})", c.time),
                None => format!("at t = {}", c.time),
            };
            out.push_str(&format!(
                "    counterexample: {at} the left side is {} and the right side is {}\n",
                c.lhs as u8, c.rhs as u8
            ));
            if let Some(k) = c.simulator_scan {
                out.push_str(&format!(
                    "    confirmed by exact evaluation and by the scan simulator (violated at scan {k})\n"
                ));
            }
            for line in &c.diagram {
                out.push_str(&format!("    {line}\n"));
            }
        }
        if let Some(c) = &p.candidate {
            out.push_str(&format!(
                "    possible counterexample (exact evaluation only, not confirmed by the scan simulator): at t = {} s\n",
                c.time
            ));
            for line in &c.diagram {
                out.push_str(&format!("    {line}\n"));
            }
        }
    }
    let s = &report.summary;
    out.push_str(&format!("{} proved, {} refuted, {} unknown\n", s.proved, s.refuted, s.unknown));
    out
}
