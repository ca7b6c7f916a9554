//! The random PLCopen generator's `REAL` networks: REAL variables and literals (zeros of both signs, a value past 2^24), integers and BOOLs converted to REAL, comparisons (extensible), ADD and MUL (extensible), SUB, DIV (by ±0.0 too), MIN/MAX/LIMIT/ABS/MOVE/SEL/MUX of REALs, REAL_TO_BOOL, REAL_TO_* of the integer types and back, some under a wired EN.

use std::fmt::Write as _;

use std::collections::BTreeMap;

use super::Rng;
use super::{Gen, SINT_VAR};

/// A REAL input, and a REAL the program writes (starting at 1.5).
pub(super) const REAL_VARS: [&str; 2] = ["R0", "R1"];

/// A wire's source: a block's id and output pin, or a variable object's id.
type Src = (u64, Option<&'static str>);

const REAL_OPERANDS: &[&str] = &[
    "R0",
    "R0",
    "R1",
    "2.5",
    "-0.5",
    "0.0",
    "-0.0",
    "1.0E3",
    "REAL#80.5",
    "16_777_217.0",
    "-2.5",
    "3.0E9",
    "-1.0E19",
];

#[rustfmt::skip]
const REAL_BLOCKS: &[&str] = &[
    "GT", "GE", "EQ", "NE", "LT", "LE", "MIN", "MAX", "LIMIT", "ABS", "MOVE", "SEL", "MUX",
    "INT_TO_REAL", "SINT_TO_REAL", "UDINT_TO_REAL", "BOOL_TO_REAL", "REAL_TO_BOOL",
    "REAL_TO_REAL", "DIV", "DIV", "MUL", "MUL", "ADD", "ADD", "SUB", "SUB", "REAL_TO_INT",
    "REAL_TO_SINT", "REAL_TO_DINT", "REAL_TO_USINT", "REAL_TO_UINT", "REAL_TO_UDINT",
    "REAL_TO_BYTE", "REAL_TO_WORD", "REAL_TO_DWORD",
];

/// Sometimes a new value of the REAL input `n` (its bits `{n}_b{k}` in `current`): the
/// hard values mostly (zeros, the literals, NaN, infinities, a subnormal), sometimes any
/// pattern.
pub(super) fn drive(rng: &mut Rng, n: &str, current: &mut BTreeMap<String, bool>) {
    if !rng.chance(30) {
        return;
    }
    let hard = [0.0, -0.0, 2.5, -0.5, 1000.0, 80.5, 16_777_216.0, 1.5, f32::NAN];
    let more = [f32::INFINITY, f32::NEG_INFINITY, 1e-40, -3.0, 7.0, 0.5, -2.5, 3e9, 1e19, -1e19];
    let x: u32 = match rng.below(4) {
        0 => rng.below(1 << 32) as u32,
        1 => more[rng.below(more.len() as u64) as usize].to_bits(),
        _ => hard[rng.below(hard.len() as u64) as usize].to_bits(),
    };
    for k in 0..32 {
        current.insert(format!("{n}_b{k}"), x >> k & 1 == 1);
    }
}

impl Gen {
    /// A block `ty` with these input pins (name, source, modifier), `EN` wired when
    /// given (and then an `ENO`): its id.
    fn real_block(&mut self, ty: &str, pins: &[(&str, Src, &str)], en: Option<Src>) -> u64 {
        let mut ins = String::new();
        let mut outs = String::new();
        if let Some(src) = en {
            write!(ins, r#"<variable formalParameter="EN">{}</variable>"#, Gen::conn(&[src]))
                .unwrap();
            outs.push_str(r#"<variable formalParameter="ENO"><connectionPointOut/></variable>"#);
        }
        for (pin, src, m) in pins {
            let c = Gen::conn(&[*src]);
            write!(ins, r#"<variable formalParameter="{pin}"{m}>{c}</variable>"#).unwrap();
        }
        outs.push_str(r#"<variable formalParameter="OUT"><connectionPointOut/></variable>"#);
        let id = self.nid();
        let (p, o) = (self.pos(200), self.order(true));
        writeln!(
            self.body,
            r#"<block localId="{id}" typeName="{ty}"{o}>{p}<inputVariables>{ins}</inputVariables><inOutVariables/><outputVariables>{outs}</outputVariables></block>"#
        )
        .unwrap();
        id
    }

    /// An FBD network over REALs: REAL operands and conversions into REAL, blocks over
    /// them, a REAL result into `R1` and a Boolean one into a bit.
    pub(super) fn real_network(&mut self) {
        let (mut reals, mut bools) = self.network_operands(REAL_OPERANDS);
        for _ in 0..1 + self.rng.below(4) {
            let ty = *self.rng.pick(REAL_BLOCKS);
            let real = |g: &mut Gen, reals: &[Src]| *g.rng.pick(reals);
            let en = if self.rng.chance(25) { Some(*self.rng.pick(&bools)) } else { None };
            let (id, gives_real) = match ty {
                "INT_TO_REAL" | "SINT_TO_REAL" | "UDINT_TO_REAL" => {
                    let n = *self.rng.pick(&["N0", "N1", "N2"]);
                    let mut src =
                        (self.in_var(if ty == "SINT_TO_REAL" { SINT_VAR } else { n }, true), None);
                    if ty == "UDINT_TO_REAL" {
                        // A negative INT is a UDINT past 2^24: rounded.
                        src = (
                            self.real_block("INT_TO_UDINT", &[("IN", src, "")], None),
                            Some("OUT"),
                        );
                    }
                    (self.real_block(ty, &[("IN", src, "")], en), true)
                }
                "BOOL_TO_REAL" => {
                    let m = if self.rng.chance(40) { r#" negated="true""# } else { "" };
                    let src = *self.rng.pick(&bools);
                    (self.real_block(ty, &[("IN", src, m)], en), true)
                }
                "REAL_TO_BOOL" | "REAL_TO_REAL" | "ABS" | "MOVE" => {
                    let src = real(self, &reals);
                    (self.real_block(ty, &[("IN", src, "")], en), ty != "REAL_TO_BOOL")
                }
                // To an integer and back: `REAL_TO_*` (rounded, ties to even; a free
                // value where C leaves it undefined), then `*_TO_REAL`.
                t if t.starts_with("REAL_TO_") => {
                    let src = real(self, &reals);
                    let to = (self.real_block(t, &[("IN", src, "")], en), Some("OUT"));
                    let back = format!("{}_TO_REAL", &t["REAL_TO_".len()..]);
                    (self.real_block(&back, &[("IN", to, "")], en), true)
                }
                "LIMIT" => {
                    let pins: Vec<(&str, Src, &str)> =
                        ["MN", "IN", "MX"].iter().map(|p| (*p, real(self, &reals), "")).collect();
                    (self.real_block(ty, &pins, en), true)
                }
                "DIV" | "SUB" => {
                    // A divisor ±0.0 sometimes (matiec's DIV gives 0.0, ENO FALSE).
                    let d = if self.rng.chance(25) {
                        let zero = *self.rng.pick(&["0.0", "-0.0"]);
                        (self.in_var(zero, true), None)
                    } else {
                        real(self, &reals)
                    };
                    let pins = [("IN1", real(self, &reals), ""), ("IN2", d, "")];
                    (self.real_block(ty, &pins, en), true)
                }
                "SEL" => {
                    let g = *self.rng.pick(&bools);
                    let pins = [
                        ("G", g, ""),
                        ("IN0", real(self, &reals), ""),
                        ("IN1", real(self, &reals), ""),
                    ];
                    (self.real_block(ty, &pins, en), true)
                }
                "MUX" => {
                    let k = *self.rng.pick(&["0", "1", "2", "-1", "N0"]);
                    let k = (self.in_var(k, true), None);
                    let pins = [
                        ("K", k, ""),
                        ("IN0", real(self, &reals), ""),
                        ("IN1", real(self, &reals), ""),
                    ];
                    (self.real_block(ty, &pins, en), true)
                }
                _ => {
                    let names: &[&str] =
                        if self.rng.chance(25) { &["IN1", "IN2", "IN3"] } else { &["IN1", "IN2"] };
                    let pins: Vec<(&str, Src, &str)> =
                        names.iter().map(|p| (*p, real(self, &reals), "")).collect();
                    (self.real_block(ty, &pins, en), matches!(ty, "MIN" | "MAX" | "MUL" | "ADD"))
                }
            };
            if gives_real {
                reals.push((id, Some("OUT")));
            } else {
                bools.push((id, Some("OUT")));
            }
            if en.is_some() && self.rng.chance(40) {
                bools.push((id, Some("ENO")));
            }
        }
        let targets = [
            (*self.rng.pick(&reals), REAL_VARS[1]),
            (*self.rng.pick(&bools), *self.rng.pick(self.bits)),
        ];
        for (src, target) in targets {
            self.out_var(src, target);
        }
        self.y += 100;
    }
}
