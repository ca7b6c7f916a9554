//! Timing diagrams of exact signals, as people read them, in the terminal.
//!
//! Each piece of the common partition (an open interval or an instant) is a
//! column: intervals are several characters wide, instants one. A time axis
//! labels the breakpoints, and an optional marker points at an instant.

use std::collections::BTreeSet;

use crate::semantics::{Signal, Time, format_time};

/// Characters for the two levels and the marker.
#[derive(Clone, Copy, Debug)]
pub struct Glyphs {
    /// Drawn where the signal is 1.
    pub high: char,
    /// Drawn where the signal is 0.
    pub low: char,
    /// Marks the instant of interest.
    pub marker: char,
}

impl Glyphs {
    /// Block characters.
    pub const UNICODE: Glyphs = Glyphs { high: '█', low: '▁', marker: '▲' };
    /// Plain ASCII.
    pub const ASCII: Glyphs = Glyphs { high: '#', low: '_', marker: '^' };
}

const INTERVAL_WIDTH: usize = 5;

/// Draws the named signals over their common horizon; `mark` points at one instant.
pub fn draw(signals: &[(String, Signal)], mark: Option<&Time>, glyphs: Glyphs) -> Vec<String> {
    draw_full(signals, (&[], &[]), mark, glyphs, usize::MAX)
}

/// The value of an integer at an instant.
pub type Track<'a> = (String, &'a dyn Fn(&Time) -> Option<String>);

/// [`draw`], with a row per integer under the signals: its value written where it
/// changes (`Cparts  0    1         2 …`).
pub fn draw_with_values(
    signals: &[(String, Signal)],
    values: &[Track],
    mark: Option<&Time>,
    glyphs: Glyphs,
) -> Vec<String> {
    draw_full(signals, (values, &[]), mark, glyphs, usize::MAX)
}

/// At most this many columns of instants in a diagram: the instants where a value
/// changes are columns of their own only within it.
const VALUE_COLUMNS: usize = 16;

/// [`draw_with_values`], with a column for each of the instants `changes` too (where a
/// value changes: each value then written over the interval it holds), if the diagram
/// has at most [`VALUE_COLUMNS`] instants with them.
pub fn draw_with_changes(
    signals: &[(String, Signal)],
    values: &[Track],
    changes: &[Time],
    mark: Option<&Time>,
    glyphs: Glyphs,
) -> Vec<String> {
    draw_full(signals, (values, changes), mark, glyphs, usize::MAX)
}

/// [`draw`], at most `width` characters wide where the signals allow it: the earliest
/// pieces are left out (the axis then starts at a later breakpoint), never the mark.
pub fn draw_within(
    signals: &[(String, Signal)],
    mark: Option<&Time>,
    glyphs: Glyphs,
    width: usize,
) -> Vec<String> {
    draw_full(signals, (&[], &[]), mark, glyphs, width)
}

fn draw_full(
    signals: &[(String, Signal)],
    (values, changes): (&[Track], &[Time]),
    mark: Option<&Time>,
    glyphs: Glyphs,
    width: usize,
) -> Vec<String> {
    let Some((_, first)) = signals.first() else { return Vec::new() };
    let horizon = first.horizon().clone();
    let mut points: BTreeSet<Time> = BTreeSet::new();
    for (_, s) in signals {
        points.extend(s.breakpoints().iter().filter(|b| **b <= horizon).cloned());
    }
    if let Some(t) = mark {
        points.insert(t.clone());
    }
    points.insert(horizon.clone());
    let mut with_changes = points.clone();
    with_changes.extend(
        changes.iter().filter(|c| **c > Time::from_integer(0.into()) && **c <= horizon).cloned(),
    );
    if with_changes.len() <= VALUE_COLUMNS {
        points = with_changes;
    }
    let mut points: Vec<Time> = points.into_iter().collect();
    let name_width = signals
        .iter()
        .map(|(n, _)| n.chars().count())
        .chain(values.iter().map(|(n, _)| n.chars().count()))
        .max()
        .unwrap_or(0)
        .max(4);
    // Each breakpoint takes an interval and an instant; keep the last ones that fit,
    // and the mark.
    let fit = (width.saturating_sub(name_width + 1) / (INTERVAL_WIDTH + 1)).max(1);
    let keep = match mark.and_then(|t| points.iter().position(|p| p == t)) {
        Some(m) => fit.max(points.len() - m),
        None => fit,
    };
    let mut previous = Time::from_integer(0.into());
    if points.len() > keep {
        previous = points[points.len() - keep - 1].clone();
        points.drain(..points.len() - keep);
    }
    let mut rows = Vec::new();
    // Columns: (value sampler, width, is_point).
    let mut columns: Vec<(Time, bool)> = Vec::new(); // (sample instant, is_point)
    for p in &points {
        let middle = (&previous + p) / Time::from_integer(2.into());
        columns.push((middle, false));
        columns.push((p.clone(), true));
        previous = p.clone();
    }
    for (name, signal) in signals {
        let mut row = format!("{name:<name_width$} ");
        for (t, is_point) in &columns {
            let c = if signal.value_at(t) { glyphs.high } else { glyphs.low };
            let width = if *is_point { 1 } else { INTERVAL_WIDTH };
            row.extend(std::iter::repeat_n(c, width));
        }
        rows.push(row.trim_end().to_string());
    }
    for (name, value) in values {
        let mut row: Vec<char> = format!("{name:<name_width$} ").chars().collect();
        let mut last = None;
        for (t, is_point) in &columns {
            let width = if *is_point { 1 } else { INTERVAL_WIDTH };
            let start = row.len();
            row.extend(std::iter::repeat_n(' ', width));
            let v = value(t);
            if *is_point || v == last {
                continue;
            }
            last = v.clone();
            // Written where it changes, over the columns after it if it is long.
            let text = v.unwrap_or_else(|| "?".to_string());
            for (k, c) in text.chars().enumerate() {
                if start + k < row.len() {
                    row[start + k] = c;
                } else {
                    row.push(c);
                }
            }
        }
        rows.push(row.into_iter().collect::<String>().trim_end().to_string());
    }
    // Time axis: a label under each breakpoint column.
    let mut axis: Vec<char> = vec![' '; name_width + 1];
    let mut marker_row: Vec<char> = vec![' '; name_width + 1];
    let mut col = name_width + 1;
    axis[..4].copy_from_slice(&['t', 'i', 'm', 'e']);
    for (t, is_point) in &columns {
        let width = if *is_point { 1 } else { INTERVAL_WIDTH };
        if *is_point {
            let label = format_time(t);
            // A label that would touch the previous one is left out.
            if axis.len() < col {
                while axis.len() < col {
                    axis.push(' ');
                }
                axis.extend(label.chars());
            }
            while marker_row.len() < col {
                marker_row.push(' ');
            }
            if mark == Some(t) {
                marker_row.push(glyphs.marker);
            }
        }
        col += width;
    }
    rows.push(axis.into_iter().collect::<String>().trim_end().to_string());
    if mark.is_some() {
        rows.push(marker_row.into_iter().collect::<String>().trim_end().to_string());
    }
    rows
}
