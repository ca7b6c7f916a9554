//! The HTML report (`--format html`, `--html FILE`): one self-contained page a person opens from a CI artifact.
//!
//! No script and no network: the styles are inline, the timing diagrams inline SVG. The
//! page has a summary table (verdict, time, location, each a link to its property); per
//! property its statement, and the proof as its trace (every cited equation a link to the
//! appendix), or the counterexample as a timing diagram with the violation marked and a
//! table of the values, or the unknown's reason and possible counterexample; then the
//! appendix: the program's compiled equations with the rung each comes from. The markup
//! is well-formed XML (every element closed, every attribute quoted), so tools and tests
//! read it with an XML parser.

use std::collections::BTreeSet;
use std::fmt::Write;

use super::export::value_after as after;
use super::text::{candidate_line, counterexample_lines, summary_line};
use super::{CounterexampleReport, PropertyReport, RunReport, Status};
use crate::semantics::{Time, format_time};

/// Text for HTML: `<`, `>`, `&`, `"` and `'` escaped.
fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '&' => out.push_str("&amp;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// An `id` for a name: letters, digits, `_` and `-` kept, anything else as `.XX`.
fn anchor(prefix: &str, name: &str) -> String {
    let mut out = String::from(prefix);
    for c in name.chars() {
        if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
            out.push(c);
        } else {
            let _ = write!(out, ".{:X}", u32::from(c));
        }
    }
    out
}

fn verdict(p: &PropertyReport) -> &'static str {
    match p.status {
        Status::Proved if p.vacuous => "vacuous",
        Status::Proved => "proved",
        Status::Refuted => "refuted",
        Status::Unknown => "unknown",
    }
}

const STYLE: &str = "
body { font: 15px/1.45 system-ui, sans-serif; margin: 2em auto; max-width: 70em; color: #1b1b1b; padding: 0 1em; }
h1 { font-size: 1.5em; margin-bottom: 0.2em; }
h2 { font-size: 1.15em; margin: 0 0 0.4em; }
code, pre { font: 13px/1.4 ui-monospace, SFMono-Regular, Menlo, monospace; }
pre { background: #f6f6f4; padding: 0.6em 0.8em; overflow-x: auto; border-radius: 4px; }
table { border-collapse: collapse; margin: 0.5em 0 1em; }
th, td { border-bottom: 1px solid #ddd; padding: 0.25em 0.7em; text-align: left; vertical-align: top; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.verdict { font-weight: 600; padding: 0.05em 0.5em; border-radius: 3px; }
.proved .verdict, .verdict.proved { background: #dff3e1; color: #135c1f; }
.refuted .verdict, .verdict.refuted { background: #fbe0e0; color: #8a1414; }
.unknown .verdict, .verdict.unknown, .vacuous .verdict, .verdict.vacuous { background: #fff2cc; color: #6b4d00; }
section.property { border: 1px solid #ddd; border-left-width: 5px; border-radius: 4px; padding: 0.8em 1em; margin: 1em 0; }
section.proved { border-left-color: #2e9c45; }
section.refuted { border-left-color: #c62828; }
section.unknown, section.vacuous { border-left-color: #d9a400; }
.where { color: #666; font-size: 0.9em; }
.reason { white-space: pre-line; }
.warning { color: #6b4d00; }
svg.diagram text { font: 12px ui-monospace, monospace; fill: #1b1b1b; }
svg.diagram .wave { fill: none; stroke: #1f5fa8; stroke-width: 1.6; }
svg.diagram .event { stroke: #1f5fa8; stroke-width: 1.6; }
svg.diagram .grid { stroke: #e4e4e4; stroke-width: 1; }
svg.diagram line.mark { stroke: #c62828; stroke-width: 1.5; stroke-dasharray: 4 3; }
svg.diagram text.mark { fill: #c62828; }
table.values td { font: 12px ui-monospace, monospace; text-align: center; vertical-align: middle; padding: 0.1em 0.35em; }
table.values td.one { background: #dde8f5; }
a { color: #1f5fa8; }
@media print {
  body { max-width: none; margin: 0; font-size: 11pt; }
  section.property { break-inside: avoid; }
  pre { white-space: pre-wrap; }
  a { color: inherit; text-decoration: none; }
}
";

/// The whole page.
pub fn html(report: &RunReport) -> String {
    let equations: BTreeSet<&str> = report.equations.iter().map(|e| e.name.as_str()).collect();
    let mut out = String::new();
    let title = match &report.program {
        Some(p) => format!("ii-prove: {p}"),
        None => format!("ii-prove: {}", report.files.join(", ")),
    };
    out.push_str(
        "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n<head>\n",
    );
    out.push_str("<meta charset=\"utf-8\"/>\n");
    let _ = writeln!(out, "<title>{}</title>", esc(&title));
    let _ = writeln!(out, "<style>{STYLE}</style>\n</head>\n<body>");
    let _ = writeln!(out, "<h1>{}</h1>", esc(&title));
    out.push_str("<p class=\"where\">");
    if let Some(p) = &report.program {
        let _ = write!(out, "program <code>{}</code>; ", esc(p));
    }
    let files: Vec<String> =
        report.files.iter().map(|f| format!("<code>{}</code>", esc(f))).collect();
    let _ = write!(out, "properties {}", files.join(", "));
    if let Some(t) = report.timers {
        let _ = write!(out, "; timers {}", esc(t));
    }
    out.push_str("</p>\n");
    let _ = writeln!(
        out,
        "<p id=\"summary-line\"><strong>{}</strong></p>",
        esc(summary_line(&report.summary, report.timers).trim())
    );
    if report.interrupted {
        out.push_str("<p class=\"warning\">The run was interrupted: the properties below are those finished before.</p>\n");
    }
    summary_table(&mut out, report);
    if !report.warnings.is_empty() {
        out.push_str("<h2>Warnings</h2>\n<ul class=\"warnings\">\n");
        for w in &report.warnings {
            let _ = writeln!(out, "<li class=\"warning\">{}</li>", esc(&w.to_string()));
        }
        out.push_str("</ul>\n");
    }
    for p in &report.properties {
        property(&mut out, p, &equations);
    }
    appendix(&mut out, report);
    out.push_str("</body>\n</html>\n");
    out
}

fn summary_table(out: &mut String, report: &RunReport) {
    out.push_str("<table id=\"summary\">\n<thead><tr><th>property</th><th>verdict</th><th>time</th><th>where</th></tr></thead>\n<tbody>\n");
    for p in &report.properties {
        let v = verdict(p);
        let at = p.location.as_ref().map(|l| l.to_string()).unwrap_or_default();
        let _ = writeln!(
            out,
            "<tr data-verdict=\"{v}\"><td><a href=\"#{}\">{}</a></td><td><span class=\"verdict {v}\">{v}</span></td><td class=\"num\">{:.1} ms</td><td><code>{}</code></td></tr>",
            anchor("p-", &p.name),
            esc(&p.name),
            p.time_ms,
            esc(&at)
        );
    }
    for u in &report.unchecked {
        let _ = writeln!(
            out,
            "<tr data-verdict=\"interrupted\"><td>{}</td><td><span class=\"verdict unknown\">not checked</span></td><td></td><td><code>{}</code></td></tr>",
            esc(&u.name),
            esc(&u.location.to_string())
        );
    }
    out.push_str("</tbody>\n</table>\n");
}

fn property(out: &mut String, p: &PropertyReport, equations: &BTreeSet<&str>) {
    let v = verdict(p);
    let _ = writeln!(out, "<section class=\"property {v}\" id=\"{}\">", anchor("p-", &p.name));
    let _ = writeln!(out, "<h2>{} <span class=\"verdict\">{v}</span></h2>", esc(&p.name));
    let _ = writeln!(out, "<p class=\"statement\"><code>{}</code></p>", esc(&p.statement));
    if let Some(at) = &p.location {
        let _ =
            writeln!(out, "<p class=\"where\">{} · {:.1} ms</p>", esc(&at.to_string()), p.time_ms);
    }
    if let Some(why) = &p.vacuity {
        let _ = writeln!(out, "<p class=\"warning\">vacuous: {}</p>", esc(why));
    }
    if let Some(t) = &p.trace {
        out.push_str("<pre class=\"trace\">");
        for line in &t.lines {
            out.push_str(&linked(line, equations));
            out.push('\n');
        }
        out.push_str("</pre>\n");
    }
    if let Some(reason) = &p.reason
        && p.status == Status::Unknown
    {
        let _ = writeln!(out, "<p class=\"reason\">{}</p>", esc(reason));
    }
    if let Some(c) = &p.counterexample {
        for line in counterexample_lines(c) {
            let _ = writeln!(out, "<p class=\"counterexample\">{}</p>", esc(&line));
        }
        diagram(out, c);
    }
    if let Some(c) = &p.candidate {
        let _ = writeln!(out, "<p class=\"candidate\">{}</p>", esc(&candidate_line(c)));
        diagram(out, c);
    }
    out.push_str("</section>\n");
}

/// A trace line, escaped, with every name of a program equation a link to it.
fn linked(line: &str, equations: &BTreeSet<&str>) -> String {
    let mut out = String::new();
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        if equations.contains(word.as_str()) {
            let _ = write!(out, "<a href=\"#{}\">{}</a>", anchor("eq-", word), esc(word));
        } else {
            out.push_str(&esc(word));
        }
        word.clear();
    };
    for c in line.chars() {
        if c.is_alphanumeric() || c == '_' {
            word.push(c);
        } else {
            flush(&mut word, &mut out);
            out.push_str(&esc(&c.to_string()));
        }
    }
    flush(&mut word, &mut out);
    out
}

/// A track's label: a long side of the property (`lhs: (a + b) · …`) by its side only
/// (the statement is printed above; the track's title has it whole).
fn label(name: &str) -> String {
    match name.split_once(": ") {
        Some((side @ ("lhs" | "rhs"), _)) if name.chars().count() > 24 => side.to_string(),
        _ => name.chars().take(40).collect(),
    }
}

fn float(t: &Time) -> f64 {
    use num_traits::ToPrimitive;
    t.to_f64().unwrap_or(0.0)
}

/// The counterexample as an SVG timing diagram (a track per signal, the violation
/// marked), then a table of the values on each piece of the time axis.
fn diagram(out: &mut String, c: &CounterexampleReport) {
    let Some((_, first)) = c.shown.first() else { return };
    let horizon = first.horizon().clone();
    let h = float(&horizon).max(f64::MIN_POSITIVE);
    let names = c.shown.iter().map(|(n, _)| n).chain(c.tracks.iter().map(|t| &t.name));
    let label_w = 14.0 + 7.4 * names.map(|n| label(n).chars().count()).max().unwrap_or(4) as f64;
    let (plot_w, row_h, top) = (560.0, 28.0, 22.0);
    let rows = c.shown.len() + c.tracks.len();
    let width = label_w + plot_w + 20.0;
    let height = top + row_h * rows as f64 + 26.0;
    let x = |t: f64| label_w + plot_w * (t / h);
    let _ = writeln!(
        out,
        "<svg class=\"diagram\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" viewBox=\"0 0 {width:.0} {height:.0}\" role=\"img\">"
    );
    let _ = writeln!(out, "<title>counterexample at t = {} s</title>", esc(&c.time));
    // The breakpoints: grid lines and time labels.
    let mut points: BTreeSet<Time> = BTreeSet::new();
    for (_, s) in &c.shown {
        points.extend(s.breakpoints().iter().cloned());
    }
    for t in &c.tracks {
        points.extend(t.breakpoints());
    }
    points.insert(horizon.clone());
    let bottom = top + row_h * rows as f64;
    let _ = writeln!(
        out,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">0</text>",
        x(0.0),
        bottom + 16.0
    );
    let mut last_label = x(0.0);
    for p in &points {
        let px = x(float(p));
        let _ = writeln!(
            out,
            "<line class=\"grid\" x1=\"{px:.1}\" y1=\"{top:.1}\" x2=\"{px:.1}\" y2=\"{bottom:.1}\"/>"
        );
        if px - last_label > 34.0 {
            let _ = writeln!(
                out,
                "<text x=\"{px:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
                bottom + 16.0,
                esc(&format_time(p))
            );
            last_label = px;
        }
    }
    for (row, (name, s)) in c.shown.iter().enumerate() {
        let y0 = top + row_h * row as f64;
        let (hi, lo) = (y0 + 5.0, y0 + row_h - 7.0);
        let _ = writeln!(out, "<g class=\"track\" data-signal=\"{}\">", esc(name));
        let _ = writeln!(out, "<title>{}</title>", esc(name));
        let _ = writeln!(out, "<text x=\"4\" y=\"{:.1}\">{}</text>", lo - 2.0, esc(&label(name)));
        // A step line over the open pieces, a spike at an isolated instant.
        let mut path = String::new();
        let mut t = Time::from_integer(0.into());
        let mut events = Vec::new();
        loop {
            let v = after(s, &t);
            let y = if v { hi } else { lo };
            let next = s
                .breakpoints()
                .iter()
                .find(|b| **b > t)
                .cloned()
                .unwrap_or_else(|| horizon.clone());
            if path.is_empty() {
                let _ = write!(path, "M{:.1},{y:.1}", x(float(&t)));
            } else {
                let _ = write!(path, " L{:.1},{y:.1}", x(float(&t)));
            }
            let _ = write!(path, " L{:.1},{y:.1}", x(float(&next)));
            if next >= horizon {
                break;
            }
            let at = s.value_at(&next);
            if at != v && at != after(s, &next) {
                events.push((x(float(&next)), if at { hi } else { lo }, y));
            }
            t = next;
        }
        let _ = writeln!(out, "<path class=\"wave\" d=\"{path}\"/>");
        for (ex, ey, from) in events {
            let _ = writeln!(
                out,
                "<line class=\"event\" x1=\"{ex:.1}\" y1=\"{from:.1}\" x2=\"{ex:.1}\" y2=\"{ey:.1}\"/>"
            );
        }
        out.push_str("</g>\n");
    }
    // An integer is a bus: its value written in each piece where it is constant, a
    // cross where it changes.
    for (row, t) in c.tracks.iter().enumerate() {
        let y0 = top + row_h * (c.shown.len() + row) as f64;
        let (hi, lo) = (y0 + 5.0, y0 + row_h - 7.0);
        let mid = (hi + lo) / 2.0;
        let _ = writeln!(out, "<g class=\"track\" data-integer=\"{}\">", esc(&t.name));
        let _ = writeln!(out, "<title>{}</title>", esc(&t.name));
        let _ =
            writeln!(out, "<text x=\"4\" y=\"{:.1}\">{}</text>", lo - 2.0, esc(&label(&t.name)));
        let mut starts = vec![Time::from_integer(0.into())];
        starts.extend(t.breakpoints().into_iter().filter(|b| *b < horizon));
        let mut pieces: Vec<(f64, f64, i64)> = Vec::new();
        for (k, s) in starts.iter().enumerate() {
            let end = starts.get(k + 1).unwrap_or(&horizon);
            let v = t.value_after(s);
            match pieces.last_mut() {
                Some(last) if last.2 == v => last.1 = x(float(end)),
                _ => pieces.push((x(float(s)), x(float(end)), v)),
            }
        }
        let last = pieces.len().saturating_sub(1);
        for (k, (x0, x1, v)) in pieces.iter().enumerate() {
            // A hexagon, its ends pointed where the value changes.
            let bevel = 3.0_f64.min((x1 - x0) / 4.0);
            let (a, b) = (if k == 0 { 0.0 } else { bevel }, if k == last { 0.0 } else { bevel });
            let _ = writeln!(
                out,
                "<path class=\"wave\" d=\"M{x0:.1},{mid:.1} L{:.1},{hi:.1} L{:.1},{hi:.1} L{x1:.1},{mid:.1} L{:.1},{lo:.1} L{:.1},{lo:.1} Z\"/>",
                x0 + a,
                x1 - b,
                x1 - b,
                x0 + a
            );
            let text = t.time_text(*v).unwrap_or_else(|| v.to_string());
            if x1 - x0 > 7.4 * text.len() as f64 + 6.0 {
                let _ = writeln!(
                    out,
                    "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{text}</text>",
                    (x0 + x1) / 2.0,
                    mid + 4.0
                );
            }
        }
        out.push_str("</g>\n");
    }
    if let Some(m) = &c.mark {
        let mx = x(float(m));
        let _ = writeln!(
            out,
            "<line class=\"mark\" x1=\"{mx:.1}\" y1=\"{:.1}\" x2=\"{mx:.1}\" y2=\"{bottom:.1}\"/>",
            top - 6.0
        );
        let scan = c.scan.map(|k| format!(" (scan {k})")).unwrap_or_default();
        let _ = writeln!(
            out,
            "<text class=\"mark\" x=\"{mx:.1}\" y=\"{:.1}\" text-anchor=\"middle\">t = {} s{}</text>",
            top - 9.0,
            esc(&c.time),
            esc(&scan)
        );
    }
    out.push_str("</svg>\n");
    values(out, c, &points);
}

/// The values of each signal on each piece of the time axis (at most 40 columns).
fn values(out: &mut String, c: &CounterexampleReport, points: &BTreeSet<Time>) {
    let mut starts = vec![Time::from_integer(0.into())];
    starts.extend(points.iter().filter(|p| **p < c.shown[0].1.horizon().clone()).cloned());
    starts.dedup();
    if starts.len() > 40 {
        return;
    }
    out.push_str("<table class=\"values\">\n<thead><tr><th>from t =</th>");
    for t in &starts {
        let _ = write!(out, "<th>{}</th>", esc(&format_time(t)));
    }
    out.push_str("</tr></thead>\n<tbody>\n");
    for (name, s) in &c.shown {
        let _ = write!(out, "<tr><th title=\"{}\">{}</th>", esc(name), esc(&label(name)));
        for t in &starts {
            let v = after(s, t);
            let _ = write!(
                out,
                "<td class=\"{}\">{}</td>",
                if v { "one" } else { "zero" },
                u8::from(v)
            );
        }
        out.push_str("</tr>\n");
    }
    for t in &c.tracks {
        let _ = write!(out, "<tr><th title=\"{}\">{}</th>", esc(&t.name), esc(&label(&t.name)));
        for s in &starts {
            let v = t.value_after(s);
            let _ = write!(
                out,
                "<td class=\"int\">{}</td>",
                t.time_text(v).unwrap_or_else(|| v.to_string())
            );
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody>\n</table>\n");
}

fn appendix(out: &mut String, report: &RunReport) {
    if report.equations.is_empty() {
        return;
    }
    out.push_str("<section id=\"program\">\n<h2>The compiled program</h2>\n");
    out.push_str("<p class=\"where\">Every equation the proofs cite, with the rung (or element) it is compiled from.</p>\n");
    out.push_str(
        "<table>\n<thead><tr><th>name</th><th>equation</th><th>from</th></tr></thead>\n<tbody>\n",
    );
    for e in &report.equations {
        let _ = writeln!(
            out,
            "<tr id=\"{}\"><td><code>{}</code></td><td><code>{}</code></td><td><code>{}</code></td></tr>",
            anchor("eq-", &e.name),
            esc(&e.name),
            esc(&e.text),
            esc(&e.location.to_string())
        );
    }
    out.push_str("</tbody>\n</table>\n</section>\n");
}
