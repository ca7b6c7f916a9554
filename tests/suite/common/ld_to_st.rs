//! An LDmicro program ported to an IEC 61131-3 Structured Text PROGRAM by an engineer's rules, written from the LDmicro format note (power flow, coils, timer scan arithmetic) and IEC ST, never from the front ends' lowering: the independent second program of the LD → ST equivalence tests.
//!
//! The subset is what the random tests generate: rungs of contacts in series and in
//! parallel (branches of contacts, or `SERIES` of contacts), TON/TOF timers in a rung's
//! series, and coils (plain, negated, set, reset). Names keep their spelling: `X…`
//! inputs become `VAR_INPUT`, `Y…` outputs `VAR_OUTPUT`, `R…` relays `VAR`, timers
//! `TON`/`TOF` instances; the cycle becomes the task's interval.
#![allow(dead_code)]

use std::collections::BTreeMap;

/// What a name is declared as.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    Input,
    Output,
    Relay,
    On,
    Off,
}

struct Port<'a> {
    lines: std::iter::Peekable<std::vec::IntoIter<&'a str>>,
    cycle_us: u64,
    /// LDmicro's timer count adjust when the element has none (format note §6.3).
    adjust: i64,
    names: BTreeMap<String, Kind>,
    body: Vec<String>,
}

/// `a AND b`, with `TRUE` (an unconditional rung start) left out.
fn and(a: &str, b: &str) -> String {
    match (a, b) {
        ("TRUE", x) | (x, "TRUE") => x.to_string(),
        _ => format!("{a} AND {b}"),
    }
}

impl<'a> Port<'a> {
    fn declare(&mut self, name: &str, kind: Kind) -> Result<(), String> {
        let kind = match (kind, name.chars().next()) {
            (Kind::On | Kind::Off, _) => kind,
            (_, Some('X')) => Kind::Input,
            (_, Some('Y')) => Kind::Output,
            (_, Some('R')) => Kind::Relay,
            _ => return Err(format!("`{name}`: not an X, Y or R bit")),
        };
        if let Some(old) = self.names.insert(name.to_string(), kind)
            && old != kind
        {
            return Err(format!("`{name}` used as two kinds"));
        }
        Ok(())
    }

    fn next(&mut self) -> Result<Vec<&'a str>, String> {
        let line = self.lines.next().ok_or("unexpected end of file")?;
        Ok(line.split_whitespace().collect())
    }

    /// A series from power `power` up to its `END`: the power at its end. Elements with
    /// effects (timers, coils) only at the rung's top level (`top`).
    fn series(&mut self, power: String, top: bool) -> Result<String, String> {
        let mut power = power;
        loop {
            let words = self.next()?;
            match words.as_slice() {
                ["END"] => return Ok(power),
                ["PARALLEL"] => {
                    // Each branch starts from the power before the group (§6.2); branches
                    // of contacts only, so `p AND (b1 OR b2)` is the group's output.
                    let mut branches = Vec::new();
                    loop {
                        let words = self.next()?;
                        match words.as_slice() {
                            ["END"] => break,
                            ["SERIES"] => branches.push(self.series("TRUE".into(), false)?),
                            leaf => branches.push(self.contact(leaf, "TRUE")?),
                        }
                    }
                    power = and(&power, &format!("({})", branches.join(" OR ")));
                }
                ["SERIES"] => return Err("SERIES at a rung's top level".into()),
                [timer @ ("TON" | "TOF"), name, delay, rest @ ..] if top => {
                    let kind = if *timer == "TON" { Kind::On } else { Kind::Off };
                    self.declare(name, kind)?;
                    let delay: u64 = delay.parse().map_err(|_| format!("delay `{delay}`"))?;
                    let adjust = match rest {
                        [] => self.adjust,
                        [a] => a.parse().map_err(|_| format!("adjust `{a}`"))?,
                        _ => return Err(format!("{timer}: too many fields")),
                    };
                    // The LDmicro output rises on the (P+1)-th scan with the input (TON),
                    // falls on the (P+1)-th without it (TOF), P = delay/cycle + adjust; an
                    // IEC timer whose elapsed time grows by one cycle a scan from 0 at
                    // the edge does the same with PT = P cycles.
                    let scans = (delay / self.cycle_us) as i64 + adjust;
                    let pt_us = scans.max(0) as u64 * self.cycle_us;
                    if !pt_us.is_multiple_of(1000) {
                        return Err(format!("{name}: {pt_us} µs is not whole milliseconds"));
                    }
                    let pt = pt_us / 1000;
                    self.body.push(format!("  {name}(IN := {power}, PT := T#{pt}ms);"));
                    power = format!("{name}.Q");
                }
                ["COIL", name, neg, set, reset] if top => {
                    self.declare(name, Kind::Relay)?;
                    // Flags checked in the order neg, set, reset (format note, COIL).
                    let stmt = match (*neg, *set, *reset) {
                        ("1", _, _) => format!("  {name} := NOT ({power});"),
                        (_, "1", _) => format!("  IF {power} THEN {name} := TRUE; END_IF;"),
                        (_, _, "1") => format!("  IF {power} THEN {name} := FALSE; END_IF;"),
                        _ => format!("  {name} := {power};"),
                    };
                    self.body.push(stmt);
                }
                leaf => power = self.contact(leaf, &power)?,
            }
        }
    }

    /// A contact after power `power`: the power after it.
    fn contact(&mut self, words: &[&str], power: &str) -> Result<String, String> {
        let ["CONTACTS", name, neg] = words else {
            return Err(format!("not ported: `{}`", words.join(" ")));
        };
        self.declare(name, Kind::Relay)?;
        let lit = if *neg == "1" { format!("NOT {name}") } else { name.to_string() };
        Ok(and(power, &lit))
    }
}

/// The Structured Text PROGRAM `name` doing what the LDmicro program `ld` does, scan by
/// scan, with its configuration (one cyclic task at the program's cycle); an error for
/// what the subset does not have.
pub fn port(ld: &str, name: &str) -> Result<String, String> {
    let mut lines = ld.lines().map(str::trim).filter(|l| !l.is_empty());
    let header = lines.next().ok_or("empty file")?;
    let adjust = match header {
        "LDmicro0.1" => -1,
        h if h.starts_with("LDmicro") => 0,
        h => return Err(format!("not an LDmicro file: `{h}`")),
    };
    let mut cycle_us = None;
    for line in lines.by_ref() {
        if let Some(c) = line.strip_prefix("CYCLE=") {
            cycle_us = Some(c.parse::<u64>().map_err(|_| format!("cycle `{c}`"))?);
        }
        if line == "PROGRAM" {
            break;
        }
    }
    let cycle_us = cycle_us.ok_or("no CYCLE=")?;
    if !cycle_us.is_multiple_of(1000) {
        return Err(format!("cycle {cycle_us} µs is not whole milliseconds"));
    }
    let rest: Vec<&str> = lines.collect();
    let mut p = Port {
        lines: rest.into_iter().peekable(),
        cycle_us,
        adjust,
        names: BTreeMap::new(),
        body: Vec::new(),
    };
    let mut rung = 0;
    while p.lines.peek().is_some() {
        match p.next()?.as_slice() {
            ["RUNG", ..] => {}
            other => return Err(format!("expected RUNG, found `{}`", other.join(" "))),
        }
        rung += 1;
        if p.lines.peek().is_some_and(|l| l.starts_with("COMMENT")) {
            p.lines.next();
            p.next()?;
            continue;
        }
        p.body.push(format!("  (* rung {rung} *)"));
        // A rung starts powered (no master relay in the subset).
        p.series("TRUE".into(), true)?;
    }
    let section = |kind: Kind, head: &str, ty: &str| -> String {
        let names: Vec<&String> =
            p.names.iter().filter(|(_, k)| **k == kind).map(|x| x.0).collect();
        if names.is_empty() {
            return String::new();
        }
        let decls: String = names.iter().map(|n| format!("    {n} : {ty};\n")).collect();
        format!("  {head}\n{decls}  END_VAR\n")
    };
    let mut text = format!("PROGRAM {name}\n");
    text += &section(Kind::Input, "VAR_INPUT", "BOOL");
    text += &section(Kind::Output, "VAR_OUTPUT", "BOOL");
    text += &section(Kind::Relay, "VAR", "BOOL");
    text += &section(Kind::On, "VAR", "TON");
    text += &section(Kind::Off, "VAR", "TOF");
    text += &p.body.join("\n");
    text += &format!(
        "\nEND_PROGRAM\n\nCONFIGURATION Plant\n  RESOURCE Controller ON PLC\n    TASK Cyclic (INTERVAL := T#{}ms, PRIORITY := 1);\n    PROGRAM Main WITH Cyclic : {name};\n  END_RESOURCE\nEND_CONFIGURATION\n",
        cycle_us / 1000
    );
    Ok(text)
}
