//! Counterexamples as files: Value Change Dump (`--vcd`, opens in GTKWave) and WaveDrom JSON (`--wavedrom`); where the files a run writes go (`--html` too).
//!
//! Both take the signals a counterexample's diagram shows. VCD times are the exact
//! rational instants scaled to the coarsest timescale (`1 s`, `1 ms`, … `1 fs`) that
//! makes them all integers; an instant that is not a whole number of femtoseconds is
//! rounded (and a `$comment` says so). WaveDrom has a group per property, one column
//! per piece of the partition of its time axis (an interval, or an isolated instant
//! where some signal has an event) with a labelled time lane, and the violation's
//! instant is named in the head. In VCD an
//! event (a value at one instant only) is a zero-width glitch: two changes at one time.
#![warn(missing_docs)]

use std::collections::BTreeSet;

use num_traits::ToPrimitive;

use super::tracks::IntegerTrack;
use super::{CounterexampleReport, RunReport};
use crate::semantics::{Signal, Time, format_time};

/// The counterexamples of a run, with the property names.
fn counterexamples(report: &RunReport) -> Vec<(&str, &CounterexampleReport)> {
    report
        .properties
        .iter()
        .filter_map(|p| p.counterexample.as_deref().map(|c| (p.name.as_str(), c)))
        .collect()
}

fn vcd_identifier(mut i: usize) -> String {
    let mut out = String::new();
    loop {
        out.push(char::from(b'!' + (i % 94) as u8));
        i /= 94;
        if i == 0 {
            return out;
        }
    }
}

fn vcd_name(name: &str) -> String {
    let name = match name.split_once(": ") {
        Some((side @ ("lhs" | "rhs"), _)) => side,
        _ => name,
    };
    name.chars().map(|c| if c.is_ascii_graphic() { c } else { '_' }).collect()
}

/// Every counterexample of the run as one VCD file, one scope per property (all
/// starting at time 0). `None` when there is no counterexample.
pub fn vcd(report: &RunReport) -> Option<String> {
    let cexs = counterexamples(report);
    if cexs.is_empty() {
        return None;
    }
    let mut times: BTreeSet<Time> = BTreeSet::new();
    for (_, c) in &cexs {
        for (_, s) in &c.shown {
            times.extend(s.breakpoints().iter().cloned());
        }
        for t in &c.tracks {
            times.extend(t.breakpoints());
        }
    }
    let units = [("s", 1i64), ("ms", 1_000), ("us", 1_000_000), ("ns", 1_000_000_000)];
    let mut chosen = None;
    for (unit, scale) in units {
        if times.iter().all(|t| (t * Time::from_integer(scale.into())).is_integer()) {
            chosen = Some((unit, Time::from_integer(scale.into()), false));
            break;
        }
    }
    let (unit, scale, rounded) =
        chosen.unwrap_or(("fs", Time::from_integer(1_000_000_000_000_000i64.into()), true));
    let tick = |t: &Time| (t * &scale).round().to_integer().to_u64().unwrap_or(u64::MAX);
    let mut out = String::new();
    out.push_str("$date ii-prove counterexample $end\n");
    out.push_str("$version ii-prove $end\n");
    if rounded {
        out.push_str("$comment some instants are not whole femtoseconds and are rounded $end\n");
    }
    out.push_str(&format!("$timescale 1{unit} $end\n"));
    let mut ids = Vec::new();
    let mut words: Vec<(String, &IntegerTrack)> = Vec::new();
    let mut n = 0;
    for (name, c) in &cexs {
        out.push_str(&format!("$scope module {} $end\n", vcd_name(name)));
        out.push_str(&format!(
            "$comment violated at t = {} s{} $end\n",
            c.time,
            c.simulator_scan
                .map(|k| format!(", scan {k} in the scan simulator"))
                .unwrap_or_default()
        ));
        for (label, s) in &c.shown {
            let id = vcd_identifier(n);
            n += 1;
            out.push_str(&format!("$var wire 1 {id} {} $end\n", vcd_name(label)));
            ids.push((id, s));
        }
        // An integer is a vector of its width, its value in two's complement.
        for t in &c.tracks {
            let id = vcd_identifier(n);
            n += 1;
            out.push_str(&format!("$var wire {} {id} {} $end\n", t.vcd_width(), vcd_name(&t.name)));
            if t.ty.time {
                out.push_str(&format!("$comment {} is a TIME in ns $end\n", vcd_name(&t.name)));
            }
            words.push((id, t));
        }
        out.push_str("$upscope $end\n");
    }
    out.push_str("$enddefinitions $end\n");
    // Value changes: every piece boundary, with the value on the piece that follows.
    let mut events: BTreeSet<Time> = BTreeSet::new();
    events.insert(Time::from_integer(0.into()));
    for (_, s) in &ids {
        events.extend(s.breakpoints().iter().cloned());
    }
    for (_, t) in &words {
        events.extend(t.breakpoints());
    }
    let mut last: Vec<Option<bool>> = vec![None; ids.len()];
    let mut last_word: Vec<Option<i64>> = vec![None; words.len()];
    let mut end = 0u64;
    for t in &events {
        let mut lines = String::new();
        for (i, (id, s)) in ids.iter().enumerate() {
            if t >= s.horizon() {
                continue;
            }
            let after = value_after(s, t);
            // An isolated instant (an event) is a zero-width glitch: its value, then the
            // value after it, at the same time stamp.
            let at = s.value_at(t);
            if t > &Time::from_integer(0.into()) && at != after && last[i] != Some(at) {
                lines.push_str(&format!("{}{id}\n", u8::from(at)));
                last[i] = Some(at);
            }
            if last[i] != Some(after) {
                lines.push_str(&format!("{}{id}\n", u8::from(after)));
                last[i] = Some(after);
            }
        }
        for (i, (id, w)) in words.iter().enumerate() {
            if t >= &w.horizon() {
                continue;
            }
            let (at, after) = (w.value_at(t), w.value_after(t));
            if t > &Time::from_integer(0.into()) && at != after && last_word[i] != Some(at) {
                lines.push_str(&format!("b{} {id}\n", w.word(at)));
                last_word[i] = Some(at);
            }
            if last_word[i] != Some(after) {
                lines.push_str(&format!("b{} {id}\n", w.word(after)));
                last_word[i] = Some(after);
            }
        }
        end = end.max(tick(t));
        if !lines.is_empty() {
            out.push_str(&format!("#{}\n{lines}", tick(t)));
        }
    }
    out.push_str(&format!("#{end}\n"));
    Some(out)
}

/// The value just after `t` (on the open interval that starts at `t`).
pub(super) fn value_after(s: &Signal, t: &Time) -> bool {
    let next =
        s.breakpoints().iter().find(|b| *b > t).cloned().unwrap_or_else(|| s.horizon().clone());
    s.value_at(&((t + &next) / Time::from_integer(2.into())))
}

/// Every counterexample as WaveDrom JSON (`{"signal": [...], "head": ..., "foot": ...}`):
/// one group per property (`["P2", lane, ...]`, a group being WaveDrom's array whose
/// first element is its name), each with its signals and a last lane `t (s)` whose
/// labels are the instants where its columns start; the head names each violation's
/// instant; `hscale` is wide enough for the longest label and for the head.
pub fn wavedrom(report: &RunReport) -> Option<String> {
    let cexs = counterexamples(report);
    if cexs.is_empty() {
        return None;
    }
    let mut groups = Vec::new();
    let mut longest = 0;
    let mut widest = 0;
    let mut heads = Vec::new();
    for (name, c) in &cexs {
        let Some((_, first)) = c.shown.first() else { continue };
        let horizon = first.horizon().clone();
        let mut points: BTreeSet<Time> = BTreeSet::new();
        for (_, s) in &c.shown {
            points.extend(s.breakpoints().iter().cloned());
        }
        for t in &c.tracks {
            points.extend(t.breakpoints());
        }
        // Columns: the open interval before each breakpoint, then the breakpoint itself
        // when some signal has an event there.
        let mut columns: Vec<Time> = Vec::new();
        let mut previous = Time::from_integer(0.into());
        for p in &points {
            columns.push((&previous + p) / Time::from_integer(2.into()));
            let event = c.shown.iter().any(|(_, s)| {
                let v = s.value_at(p);
                v != s.left_limit(p) && (p == &horizon || v != value_after(s, p))
            }) || c.tracks.iter().any(|t| {
                let v = t.value_at(p);
                v != t.value_at(&((&previous + p) / Time::from_integer(2.into())))
                    && (p == &horizon || v != t.value_after(p))
            });
            if event && p != &horizon {
                columns.push(p.clone());
            }
            previous = p.clone();
        }
        let mut group = vec![serde_json::json!(name)];
        for (label, s) in &c.shown {
            let mut wave = String::new();
            let mut last = None;
            for t in &columns {
                let v = s.value_at(t);
                wave.push(if last == Some(v) {
                    '.'
                } else if v {
                    '1'
                } else {
                    '0'
                });
                last = Some(v);
            }
            // A long side (`lhs: (a + b) · …`) is named by its side only: the renderer
            // does not widen the name column for it.
            let label = match label.split_once(": ") {
                Some((side @ ("lhs" | "rhs"), _)) if label.chars().count() > 24 => side,
                _ => label.as_str(),
            };
            group.push(serde_json::json!({ "name": label, "wave": wave }));
        }
        // An integer is a data lane: a new value opens a `=` cell labelled with it.
        for t in &c.tracks {
            let (mut wave, mut data, mut last) = (String::new(), Vec::new(), None);
            for col in &columns {
                let v = t.value_at(col);
                if last == Some(v) {
                    wave.push('.');
                } else {
                    wave.push('=');
                    data.push(t.time_text(v).unwrap_or_else(|| v.to_string()));
                }
                last = Some(v);
            }
            group.push(serde_json::json!({ "name": t.name, "wave": wave, "data": data }));
        }
        // Where each column starts: the instant itself for an event, else the
        // breakpoint before the interval.
        let mut starts = Vec::new();
        let mut previous = Time::from_integer(0.into());
        for t in &columns {
            if points.contains(t) {
                starts.push(format_time(t));
            } else {
                starts.push(format_time(&previous));
                if let Some(p) = points.iter().find(|p| *p > t) {
                    previous = p.clone();
                }
            }
        }
        longest = starts.iter().map(String::len).fold(longest, usize::max);
        widest = widest.max(starts.len());
        let time_wave = "=".repeat(starts.len());
        group.push(serde_json::json!({ "name": "t (s)", "wave": time_wave, "data": starts }));
        groups.push(serde_json::Value::Array(group));
        heads.push(format!("{name}: violated at t = {} s", c.time));
    }
    // A column is 40 px wide at hscale 1, a character about 7 px: room for the longest
    // time label in its column, and for the head above the widest group's columns.
    let head = heads.join("; ");
    let for_labels = (longest * 7 + 8).div_ceil(40);
    let for_head = (head.chars().count() * 7).div_ceil(40 * widest.max(1));
    let hscale = for_labels.max(for_head).max(1);
    let doc = serde_json::json!({
        "signal": groups,
        "head": { "text": head },
        "config": { "hscale": hscale },
    });
    serde_json::to_string_pretty(&doc).ok()
}

/// The files a run writes beside its report: `-` is standard output.
#[derive(Clone, Copy, Debug, Default)]
pub struct Outputs<'a> {
    /// `--vcd`.
    pub vcd: Option<&'a str>,
    /// `--wavedrom`.
    pub wavedrom: Option<&'a str>,
    /// `--html`.
    pub html: Option<&'a str>,
}

impl Outputs<'_> {
    fn named(&self) -> [(&'static str, Option<&str>); 3] {
        [("--vcd", self.vcd), ("--wavedrom", self.wavedrom), ("--html", self.html)]
    }

    /// Whether any file is asked for.
    pub fn any(&self) -> bool {
        self.named().iter().any(|(_, p)| p.is_some())
    }

    /// Whether one of them goes to standard output (the report then goes to standard error).
    pub fn to_stdout(&self) -> bool {
        self.named().iter().any(|(_, p)| *p == Some("-"))
    }
}

/// Refuses, before any proof runs, an output path that cannot be written: its folder
/// is missing or not writable, or it names a folder. `-` (standard output) is fine,
/// but only for one of them.
pub fn check_outputs(outputs: &Outputs) -> Result<(), super::InputError> {
    let error = |text: String| super::InputError { rendered: format!("error: {text}\n") };
    let dashes: Vec<&str> =
        outputs.named().iter().filter(|(_, p)| *p == Some("-")).map(|(f, _)| *f).collect();
    if dashes.len() > 1 {
        return Err(error(format!(
            "only one of {} can write to standard output (`-`)",
            dashes.join(" and ")
        )));
    }
    for path in outputs.named().into_iter().filter_map(|(_, p)| p).filter(|p| *p != "-") {
        let target = std::path::Path::new(path);
        if target.is_dir() {
            return Err(error(format!("cannot write {path}: it is a directory")));
        }
        // Probe the folder with the temporary name the file is later written under.
        let probe = format!("{path}.tmp-ii-prove");
        std::fs::OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(true)
            .open(&probe)
            .and_then(|_| std::fs::remove_file(&probe))
            .map_err(|e| error(format!("cannot write {path}: {e}")))?;
    }
    Ok(())
}

/// Writes the requested files after a successful run: each is rendered first, then
/// written whole (to a temporary name, then renamed), so nothing is half written;
/// `-` writes to standard output. A run without a counterexample writes no waveform
/// file and says so on standard error; the HTML report is always written.
pub fn write_files(report: &RunReport, outputs: &Outputs) -> Result<(), super::InputError> {
    let mut files = Vec::new();
    for (path, render) in
        [(outputs.vcd, vcd as fn(&RunReport) -> Option<String>), (outputs.wavedrom, wavedrom)]
    {
        let Some(path) = path else { continue };
        match render(report) {
            Some(text) => files.push((path, text)),
            None => super::console::err(&format!("note: no counterexample to write to {path}\n")),
        }
    }
    if let Some(path) = outputs.html {
        files.push((path, super::html::html(report)));
    }
    for (path, text) in files {
        write_whole(path, text.as_bytes())?;
    }
    Ok(())
}

/// Writes `bytes` to `path` whole (to a temporary name, then renamed), so nothing is
/// half written; `-` writes to standard output.
pub fn write_whole(path: &str, bytes: &[u8]) -> Result<(), super::InputError> {
    if path == "-" {
        if let Ok(text) = std::str::from_utf8(bytes) {
            super::console::out(text);
            return Ok(());
        }
        use std::io::Write as _;
        let mut out = std::io::stdout().lock();
        return out.write_all(bytes).and_then(|()| out.flush()).map_err(|e| super::InputError {
            rendered: format!("error: cannot write to standard output: {e}\n"),
        });
    }
    let tmp = format!("{path}.tmp-ii-prove");
    std::fs::write(&tmp, bytes).and_then(|_| std::fs::rename(&tmp, path)).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        super::InputError { rendered: format!("error: cannot write {path}: {e}\n") }
    })
}
