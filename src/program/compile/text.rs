//! The compiled program as `.ii` text (what `show` prints): its signals grouped by kind, its timers, its warnings and one `assume` per hypothesis.

use super::{CompiledProgram, SignalKind, TimerModel};
use crate::syntax::print::{Notation, delay_to_string, name_to_string, push_assumption};

type KindFilter = fn(&SignalKind) -> bool;

/// The compiled program as `.ii` text: a header comment, `input` lines declaring
/// every signal, the warnings as `//` comments naming their rung, and one
/// `assume` per hypothesis. It parses back with
/// [`parse_document`](crate::syntax::parse_document) and
/// [`NoProgram`](crate::syntax::NoProgram) to the same hypotheses.
pub fn program_to_ii(compiled: &CompiledProgram, notation: Notation) -> String {
    let mut out = String::new();
    out.push_str(&format!(
        "// Compiled from {} program by ii-prove (timers: {}).\n",
        compiled.language,
        match compiled.timers {
            TimerModel::Plc => "plc, the scans the runtime counts",
            TimerModel::Ideal => "ideal, the delays as written",
        }
    ));
    let count =
        |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    out.push_str(&format!(
        "// {}, {}, {}. `pre X` is X's value at the previous scan (0 before the\n",
        count(compiled.hypotheses.len(), "hypothesis", "hypotheses"),
        count(compiled.signals.len(), "signal", "signals"),
        count(compiled.warnings.len(), "warning", "warnings")
    ));
    out.push_str("// first); with it this text describes scans, and reads back with a program.\n");
    let groups: [(&str, KindFilter); 10] = [
        ("inputs", |k| *k == SignalKind::Input),
        ("outputs", |k| *k == SignalKind::Output),
        ("relays", |k| *k == SignalKind::Relay),
        ("edge memories (the input of a one-shot or toggle coil)", |k| {
            matches!(k, SignalKind::EdgeMemory { .. })
        }),
        (
            "timers' state between calls (the input the last call gave; how the run of one called at several places stands)",
            |k| matches!(k, SignalKind::HeldInput { .. }),
        ),
        ("peripheral reads (free: what the world outside the scan answers)", |k| {
            matches!(k, SignalKind::Fresh { peripheral: true, .. })
        }),
        ("fresh outputs of unsupported elements (unconstrained)", |k| {
            matches!(k, SignalKind::Fresh { peripheral: false, .. })
        }),
        ("bits no coil writes (always 0*)", |k| *k == SignalKind::Unwritten),
        ("integers, as bits (X_b0 the least significant; stored xor the start value)", |k| {
            matches!(k, SignalKind::IntBit { .. })
        }),
        ("intermediate values of integer computations", |k| {
            matches!(k, SignalKind::Intermediate { .. })
        }),
    ];
    for (title, pick) in groups {
        let names: Vec<String> = compiled
            .signals
            .iter()
            .filter(|(_, k)| pick(k))
            .map(|(n, _)| name_to_string(n))
            .collect();
        if names.is_empty() {
            continue;
        }
        out.push_str(&format!("\n// {title}\n"));
        for chunk in names.chunks(8) {
            out.push_str(&format!("input {}\n", chunk.join(", ")));
        }
    }
    if !compiled.timer_info.is_empty() {
        out.push_str(&format!("\n// timers (--timers {})\n", compiled.timers.as_str()));
        for t in &compiled.timer_info {
            let effective = match &t.effective {
                Some(d) => delay_to_string(d),
                None => "none: the output follows the input".into(),
            };
            out.push_str(&format!(
                "// {} {}: {} {} {} µs, adjust {}: P = {} scan{}; effective delay {}\n",
                compiled.block_noun,
                t.rung,
                t.keyword,
                t.name,
                t.delay_us,
                t.adjust,
                t.scans,
                if t.scans == 1 { "" } else { "s" },
                effective
            ));
        }
    }
    if !compiled.warnings.is_empty() {
        out.push_str("\n// warnings\n");
        for w in &compiled.warnings {
            let text = format!("{}: {}: {}", w.rung_label(), w.element, w.message);
            let text: String = text.chars().map(|c| if c.is_control() { ' ' } else { c }).collect();
            out.push_str(&format!("// warning: {text}\n"));
        }
    }
    out.push('\n');
    for h in &compiled.hypotheses {
        push_assumption(&mut out, &h.name, &h.lhs, h.relation(), &h.rhs, notation);
        out.push('\n');
    }
    out
}
