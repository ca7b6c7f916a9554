//! An integer of a counterexample's run as a value track: the signals of its bits, its value at each instant and where it changes, for every renderer (text, VCD, WaveDrom, HTML).

use std::collections::BTreeSet;

use super::waveform;
use crate::program::{CompiledProgram, IntType, Program, bitvec};
use crate::semantics::{Assignment, Signal, Time};
use crate::term::Symbol;

/// A program integer whose every bit the run computed.
#[derive(Clone, Debug)]
pub struct IntegerTrack {
    /// Its name, as the report spells it.
    pub name: String,
    /// Its type (width and signedness).
    pub ty: IntType,
    /// Each bit's signal (least significant first), and whether the stored bit is
    /// flipped by the start value.
    bits: Vec<(Signal, bool)>,
}

impl IntegerTrack {
    /// The program's integers whose bits `env` holds, named by `named`.
    pub fn all(
        compiled: &CompiledProgram,
        env: &Assignment,
        named: &dyn Fn(&str) -> String,
    ) -> Vec<IntegerTrack> {
        compiled
            .integers
            .iter()
            .filter(|(x, _)| !elapsed_count(compiled, env, x))
            .filter_map(|(x, var)| {
                let bits = (0..var.ty.bits)
                    .map(|k| {
                        let s = env.signals.get(&Symbol::from(Program::int_bit(x, k).as_str()))?;
                        Some((s.clone(), var.start_bit(k)))
                    })
                    .collect::<Option<Vec<_>>>()?;
                Some(IntegerTrack { name: named(x), ty: var.ty, bits })
            })
            .collect()
    }

    /// The bits a counterexample's `env` lacks of the elapsed times (`T1_ET`, a TIME)
    /// it shows in part or whose hidden count of scans ([`elapsed_of`]) it has: a
    /// diagram draws the time, not the count, once they are added.
    pub fn elapsed_bits(compiled: &CompiledProgram, env: &Assignment) -> Vec<String> {
        let has = |x: &str, k: u32| has_bit(env, x, k);
        let mut out = Vec::new();
        for (x, var) in compiled.integers.iter().filter(|(_, v)| v.ty.time) {
            let counted = compiled.integers.iter().any(|(count, c)| {
                elapsed_of(count).as_deref() == Some(x.as_str())
                    && (0..c.ty.bits).all(|k| has(count, k))
            });
            if counted || (0..var.ty.bits).any(|k| has(x, k)) {
                out.extend(
                    (0..var.ty.bits).filter(|k| !has(x, *k)).map(|k| Program::int_bit(x, k)),
                );
            }
        }
        out
    }

    /// Whether `label` names one of this integer's bits (`X_b3`), which a diagram
    /// that draws the value does not draw.
    pub fn shows_bit(&self, label: &str) -> bool {
        label.strip_prefix(&format!("{}_b", self.name)).is_some_and(|k| k.parse::<u32>().is_ok())
    }

    fn value(&self, bit: impl Fn(&Signal) -> bool) -> i64 {
        let bits: Vec<bool> = self.bits.iter().map(|(s, flip)| bit(s) != *flip).collect();
        bitvec::value_of(&bits, self.ty)
    }

    /// The value at the instant `t`.
    pub fn value_at(&self, t: &Time) -> i64 {
        self.value(|s| s.value_at(t))
    }

    /// The value just after `t` (on the open interval that starts at `t`).
    pub fn value_after(&self, t: &Time) -> i64 {
        self.value(|s| super::export::value_after(s, t))
    }

    /// The end of the run.
    pub fn horizon(&self) -> Time {
        self.bits.first().map_or_else(|| Time::from_integer(0.into()), |(s, _)| s.horizon().clone())
    }

    /// The instants where some bit changes.
    pub fn breakpoints(&self) -> BTreeSet<Time> {
        self.bits.iter().flat_map(|(s, _)| s.breakpoints().iter().cloned()).collect()
    }

    /// A TIME's value (ns) in its units, as a duration literal without `T#` (`20ms`,
    /// `1m30s`); `None` for an integer of another type.
    pub fn time_text(&self, value: i64) -> Option<String> {
        self.ty.time.then(|| self.ty.show(value).replacen("T#", "", 1))
    }

    /// How many bits VCD writes the value in: a TIME in 64 (ns), another integer in
    /// its width.
    pub fn vcd_width(&self) -> u32 {
        if self.ty.time { 64 } else { self.ty.bits }
    }

    /// The value as the `bits`-wide two's-complement word (`0110…`, most significant
    /// first), as VCD writes a vector.
    pub fn word(&self, value: i64) -> String {
        (0..self.vcd_width()).rev().map(|k| if value >> k & 1 == 1 { '1' } else { '0' }).collect()
    }
}

/// Whether `env` holds bit `k` of the integer `x`.
fn has_bit(env: &Assignment, x: &str, k: u32) -> bool {
    env.signals.contains_key(&Symbol::from(Program::int_bit(x, k).as_str()))
}

/// Whether the integer `x` is a timer's hidden count of scans (`T1_ET_SCANS`; `T1_AGE`,
/// the scans since the start of one followed call by call) whose elapsed time (`T1_ET`,
/// a TIME) `env` holds whole: that is drawn instead.
fn elapsed_count(compiled: &CompiledProgram, env: &Assignment, x: &str) -> bool {
    let Some(et) = elapsed_of(x) else { return false };
    compiled
        .integers
        .get(&et)
        .is_some_and(|var| var.ty.time && (0..var.ty.bits).all(|k| has_bit(env, &et, k)))
}

/// The elapsed time (`T1_ET`) whose hidden count of scans the integer `x` would be:
/// `T1_ET_SCANS`, or `T1_AGE` (the scans since the start of a timer followed call by
/// call).
fn elapsed_of(x: &str) -> Option<String> {
    match (x.strip_suffix("_SCANS"), x.strip_suffix("_AGE")) {
        (Some(et), _) => Some(et.to_string()),
        (None, Some(inst)) => Some(format!("{inst}_ET")),
        (None, None) => None,
    }
}

/// `signals` drawn with a value row for each of `tracks` (`Cparts  0    1    2 …`).
pub fn draw(
    signals: &[(String, Signal)],
    tracks: &[IntegerTrack],
    mark: Option<&Time>,
    glyphs: waveform::Glyphs,
) -> Vec<String> {
    // A TIME in its units (`20ms`, as the property's `T#20ms`), each value over the
    // scans it holds.
    let text = |t: &IntegerTrack, v: i64| t.time_text(v).unwrap_or_else(|| t.ty.show(v));
    let readers: Vec<_> =
        tracks.iter().map(|t| move |time: &Time| Some(text(t, t.value_at(time)))).collect();
    let changes: Vec<Time> =
        tracks.iter().filter(|t| t.ty.time).flat_map(|t| t.breakpoints()).collect();
    let values: Vec<waveform::Track> = tracks
        .iter()
        .zip(&readers)
        .map(|(t, f)| (t.name.clone(), f as &dyn Fn(&Time) -> Option<String>))
        .collect();
    waveform::draw_with_changes(signals, &values, &changes, mark, glyphs)
}
