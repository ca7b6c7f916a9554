//! Random PLCopen LD/FBD programs and the check that a compiled program's hypotheses hold on scan runs; shared by the simulator and toolchain differential tests.
#![allow(dead_code)]

use super::rng::Rng;
use super::scan_eval::*;

use std::collections::BTreeMap;
use std::fmt::Write as _;

use ii_prove::diag::Sources;
use ii_prove::ladder::plcopen::{
    Lowered, PlcError, PlcProgram, PlcSimulator, Selection, lower, prepare_text_blocks,
    read_plcopen, select,
};
use ii_prove::ladder::{CompiledProgram, SignalKind};
use ii_prove::program::{BoolExpr, compile, walk};
use ii_prove::term::Term;

// ---------------------------------------------------------------- program generator

#[path = "plcopen_conv.rs"]
mod conv;
#[path = "plcopen_real.rs"]
mod real;
#[path = "plcopen_time.rs"]
mod time;

const INPUTS: &[&str] = &["In0", "In1", "In2", "In3"];
const BITS: &[&str] = &["B0", "B1", "B2", "Q0", "Q1"];
/// Declared, never written: stays FALSE.
const GHOST: &str = "G0";
const PRESETS: &[&str] = &["T#0ms", "T#10ms", "T#15ms", "T#20ms", "T#35ms", "T#50ms"];
const FBS: &[&str] = &["TON", "TOF", "TP", "SR", "RS", "R_TRIG", "F_TRIG", "CTU"];
const FUNCTIONS: &[&str] = &["AND", "OR", "XOR", "NOT", "SEL", "MOVE", "GT"];

/// Integer variables of the main program: an input, two the program writes, a SINT.
const INT_INPUT: &str = "N0";
const INT_VARS: &[&str] = &["N1", "N2"];
const SINT_VAR: &str = "S0";
const INT_OPERANDS: &[&str] = &["N0", "N1", "N2", "0", "1", "3", "-2", "7", "100", "32767"];
const INT_BLOCKS: &[&str] = &[
    "ADD",
    "SUB",
    "MUL",
    "DIV",
    "MOD",
    "MIN",
    "MAX",
    "LIMIT",
    "ABS",
    "MOVE",
    "SEL",
    "GT",
    "GE",
    "EQ",
    "NE",
    "LT",
    "LE",
    "CTU",
    "CTD",
    "CTUD",
    "CTU",
    "SINT_TO_INT",
    "BOOL_TO_INT",
    "INT_TO_BOOL",
    "CONV",
    "CONV",
    "AND",
    "DIVS",
    "MUX",
    "BCD",
];

/// The user function block programs may instantiate: inputs `IN0`, `IN1`, outputs
/// `OUT0`, `OUT1`, a local `L0`.
const USER_FB: &str = "UserFb";
const FB_INPUTS: &[&str] = &["IN0", "IN1"];
const FB_BITS: &[&str] = &["OUT0", "OUT1", "L0"];

struct Gen {
    rng: Rng,
    id: u64,
    body: String,
    instances: Vec<(String, &'static str)>,
    y: i64,
    /// The names the body reads as inputs, the bits it writes, a bit nothing writes.
    inputs: &'static [&'static str],
    bits: &'static [&'static str],
    ghost: &'static str,
    /// Whether blocks may be instances of the user function block.
    user_fb: bool,
    /// Every position 0,0 (the statements then run in document order).
    no_layout: bool,
    /// Whether the body may use the integer variables.
    ints: bool,
    /// The TIME variables timers may take as presets (the main program's).
    times: Option<time::Times>,
}

fn pins(rng: &mut Rng, ty: &str) -> Vec<&'static str> {
    match ty {
        "TON" | "TOF" | "TP" => vec!["IN", "PT"],
        "SR" => vec!["S1", "R"],
        "RS" => vec!["S", "R1"],
        "R_TRIG" | "F_TRIG" => vec!["CLK"],
        "CTU" => vec!["CU", "R", "PV"],
        "NOT" | "MOVE" => vec!["IN"],
        "SEL" => vec!["G", "IN0", "IN1"],
        "GT" => vec!["IN1", "IN2"],
        USER_FB => vec!["IN0", "IN1"],
        _ => {
            let n = 2 + rng.below(2) as usize;
            ["IN1", "IN2", "IN3"][..n].to_vec()
        }
    }
}

fn outputs(ty: &str) -> Vec<&'static str> {
    match ty {
        "TON" | "TOF" | "TP" => vec!["Q", "ET"],
        "SR" | "RS" => vec!["Q1"],
        "R_TRIG" | "F_TRIG" => vec!["Q"],
        "CTU" | "CTD" => vec!["Q", "CV"],
        "CTUD" => vec!["QU", "QD", "CV"],
        USER_FB => vec!["OUT0", "OUT1"],
        _ => vec!["OUT"],
    }
}

impl Gen {
    fn nid(&mut self) -> u64 {
        self.id += 1;
        self.id
    }

    fn pos(&mut self, x: i64) -> String {
        if self.no_layout {
            // CODESYS writes 0,0 everywhere: document order.
            return r#"<position x="0" y="0"/>"#.into();
        }
        let jitter = if self.rng.chance(20) { self.rng.below(12) as i64 } else { 0 };
        format!(r#"<position x="{x}" y="{}"/>"#, self.y + jitter)
    }

    fn order(&mut self, fbd: bool) -> String {
        if fbd && self.rng.chance(15) {
            format!(r#" executionOrderId="{}""#, self.rng.below(4))
        } else {
            String::new()
        }
    }

    fn conn(refs: &[(u64, Option<&str>)]) -> String {
        if refs.is_empty() {
            return "<connectionPointIn/>".into();
        }
        let mut s = String::from("<connectionPointIn>");
        for (r, f) in refs {
            match f {
                Some(f) => write!(s, r#"<connection refLocalId="{r}" formalParameter="{f}"/>"#),
                None => write!(s, r#"<connection refLocalId="{r}"/>"#),
            }
            .unwrap();
        }
        s.push_str("</connectionPointIn>");
        s
    }

    /// A Boolean operand: an input, a written bit, the ghost, a constant, or an FB member.
    fn operand(&mut self) -> String {
        match self.rng.below(10) {
            0..=3 => self.rng.pick(self.inputs).to_string(),
            4..=6 => self.rng.pick(self.bits).to_string(),
            7 => self.ghost.into(),
            8 if !self.instances.is_empty() => {
                let (inst, ty) = self.rng.pick(&self.instances).clone();
                format!("{inst}.{}", outputs(ty)[0])
            }
            _ if self.rng.chance(70) => self.rng.pick(self.inputs).to_string(),
            _ => if self.rng.chance(50) { "TRUE" } else { "FALSE" }.into(),
        }
    }

    fn modifiers(&mut self, edge_ok: bool) -> String {
        let mut s = String::new();
        if self.rng.chance(25) {
            s.push_str(r#" negated="true""#);
        }
        // Not both: a negated edge is refused (Beremiz drops the edge).
        if edge_ok && s.is_empty() && self.rng.chance(6) {
            s.push_str(if self.rng.chance(50) {
                r#" edge="rising""#
            } else {
                r#" edge="falling""#
            });
        }
        s
    }

    fn in_var(&mut self, expr: &str, fbd: bool) -> u64 {
        let id = self.nid();
        // No modifier: a variable object's modifier is refused (tools disagree on it).
        let (p, o) = (self.pos(20), self.order(fbd));
        writeln!(
            self.body,
            r#"<inVariable localId="{id}"{o}>{p}<connectionPointOut/><expression>{expr}</expression></inVariable>"#
        )
        .unwrap();
        id
    }

    /// A block fed from `sources`; returns its id and type.
    fn block(
        &mut self,
        sources: &mut Vec<(u64, Option<&'static str>)>,
        fbd: bool,
        en: bool,
    ) -> (u64, &'static str) {
        let fb = self.rng.chance(50);
        let ty = if fb && self.user_fb && self.rng.chance(30) {
            USER_FB
        } else if fb {
            *self.rng.pick(FBS)
        } else {
            *self.rng.pick(FUNCTIONS)
        };
        // Beremiz calls a function with EN/ENO formally, and `NOT(IN := …)` is not ST that
        // matiec parses (NOT is an operator there): such blocks stay out of the oracle's way.
        let en = en && ty != "NOT";
        let mut ins = String::new();
        if en && self.rng.chance(20) {
            let src = *self.rng.pick(sources);
            write!(ins, r#"<variable formalParameter="EN">{}</variable>"#, Gen::conn(&[src]))
                .unwrap();
        }
        let all = pins(&mut self.rng, ty);
        let last = all.len() - 1;
        for (j, pin) in all.into_iter().enumerate() {
            // An unconnected pin is left out of the call by Beremiz: only where that means
            // FALSE (an FB input, the last OR/XOR input), without modifiers.
            let may_be_open = fb || (j == last && j > 0 && matches!(ty, "OR" | "XOR"));
            let refs = match pin {
                "PT" => {
                    let preset = *self.rng.pick(PRESETS);
                    let preset = self.preset(preset);
                    vec![(self.in_var(preset, fbd), None)]
                }
                "PV" => vec![(self.in_var("3", fbd), None)],
                // A comparison of integers (its output is not modelled).
                _ if ty == "GT" => {
                    let n = *self.rng.pick(&["1", "2", "3"]);
                    vec![(self.in_var(n, fbd), None)]
                }
                _ if may_be_open && self.rng.chance(10) => Vec::new(),
                _ => vec![*self.rng.pick(sources)],
            };
            let m = if matches!(pin, "PT" | "PV") || refs.is_empty() || ty == "GT" {
                String::new()
            } else {
                self.modifiers(true)
            };
            write!(ins, r#"<variable formalParameter="{pin}"{m}>{}</variable>"#, Gen::conn(&refs))
                .unwrap();
        }
        let id = self.nid();
        let inst = if fb {
            let name = format!("{}{}", ty.replace('_', ""), id);
            self.instances.push((name.clone(), ty));
            format!(r#" instanceName="{name}""#)
        } else {
            String::new()
        };
        let mut outs = String::new();
        if en {
            outs.push_str(r#"<variable formalParameter="ENO"><connectionPointOut/></variable>"#);
        }
        for o in outputs(ty) {
            let neg = if self.rng.chance(10) { r#" negated="true""# } else { "" };
            write!(
                outs,
                r#"<variable formalParameter="{o}"{neg}><connectionPointOut/></variable>"#
            )
            .unwrap();
        }
        let (p, o) = (self.pos(200), self.order(fbd));
        writeln!(
            self.body,
            r#"<block localId="{id}" typeName="{ty}"{inst}{o}>{p}<inputVariables>{ins}</inputVariables><inOutVariables/><outputVariables>{outs}</outputVariables></block>"#
        )
        .unwrap();
        let out = outputs(ty)[0];
        sources.push((id, Some(out)));
        if en && self.rng.chance(30) {
            sources.push((id, Some("ENO")));
        }
        (id, ty)
    }

    /// The operands of a network: two or three drawn from `numbers`, one or two Boolean
    /// ones, as variable objects.
    #[allow(clippy::type_complexity)]
    fn network_operands(
        &mut self,
        numbers: &[&str],
    ) -> (Vec<(u64, Option<&'static str>)>, Vec<(u64, Option<&'static str>)>) {
        let mut nums = Vec::new();
        let mut bools = Vec::new();
        for _ in 0..2 + self.rng.below(2) {
            let v = *self.rng.pick(numbers);
            nums.push((self.in_var(v, true), None));
        }
        for _ in 0..1 + self.rng.below(2) {
            let v = self.operand();
            bools.push((self.in_var(&v, true), None));
        }
        (nums, bools)
    }

    /// An FBD network over integers: integer operands, arithmetic, comparisons and
    /// counters, integer and Boolean outputs.
    fn int_network(&mut self) {
        let (mut ints, mut bools) = self.network_operands(INT_OPERANDS);
        for _ in 0..1 + self.rng.below(4) {
            let ty = *self.rng.pick(INT_BLOCKS);
            if self.conversion(ty, &mut ints, &mut bools) {
                continue;
            }
            let counter = ty.starts_with("CT");
            let extensible = matches!(
                ty,
                "ADD" | "MUL" | "MIN" | "MAX" | "GT" | "GE" | "EQ" | "NE" | "LT" | "LE"
            );
            let pins: Vec<&str> = match ty {
                "CTU" => vec!["CU", "R", "PV"],
                "CTD" => vec!["CD", "LD", "PV"],
                "CTUD" => vec!["CU", "CD", "R", "LD", "PV"],
                "LIMIT" => vec!["MN", "IN", "MX"],
                "ABS" | "MOVE" | "SINT_TO_INT" => vec!["IN"],
                "SEL" => vec!["G", "IN0", "IN1"],
                // K from the network's integers: an input's small values, negative ones
                // and ones past the inputs among them.
                "MUX" if self.rng.chance(40) => vec!["K", "IN0", "IN1", "IN2"],
                "MUX" => vec!["K", "IN0", "IN1"],
                _ if extensible && self.rng.chance(25) => vec!["IN1", "IN2", "IN3"],
                _ => vec!["IN1", "IN2"],
            };
            let mut ins = String::new();
            // A MUX of BOOL inputs (K an integer), drawn without EN/ENO.
            let bool_mux = ty == "MUX" && self.rng.chance(30);
            // EN wired to a random Boolean (Beremiz draws EN first, ENO first).
            let en = !bool_mux && self.rng.chance(30);
            if en {
                let src = *self.rng.pick(&bools);
                write!(ins, r#"<variable formalParameter="EN">{}</variable>"#, Gen::conn(&[src]))
                    .unwrap();
            }
            for pin in pins {
                let refs = match pin {
                    "CU" | "CD" | "R" | "LD" | "G" => {
                        if counter && pin != "CU" && pin != "CD" && self.rng.chance(30) {
                            Vec::new()
                        } else {
                            vec![*self.rng.pick(&bools)]
                        }
                    }
                    // A literal divisor, or any integer of the network (0 included:
                    // an input's small values, a BOOL_TO_INT's 0).
                    "IN2" if matches!(ty, "DIV" | "MOD") && self.rng.chance(50) => {
                        let d = *self.rng.pick(&["0", "1", "2", "3", "-2", "7", "-1"]);
                        vec![(self.in_var(d, true), None)]
                    }
                    "IN" if ty == "SINT_TO_INT" => vec![(self.in_var(SINT_VAR, true), None)],
                    "IN0" | "IN1" | "IN2" if bool_mux => vec![*self.rng.pick(&bools)],
                    _ => vec![*self.rng.pick(&ints)],
                };
                let m = if matches!(pin, "CU" | "CD") && self.rng.chance(15) {
                    r#" negated="true""#
                } else {
                    ""
                };
                write!(
                    ins,
                    r#"<variable formalParameter="{pin}"{m}>{}</variable>"#,
                    Gen::conn(&refs)
                )
                .unwrap();
            }
            let id = self.nid();
            let inst = if counter {
                let name = format!("{ty}{id}");
                self.instances.push((name.clone(), ty));
                format!(r#" instanceName="{name}""#)
            } else {
                String::new()
            };
            let outs: Vec<&str> = match ty {
                "CTU" | "CTD" => vec!["Q", "CV"],
                "CTUD" => vec!["QU", "QD", "CV"],
                _ => vec!["OUT"],
            };
            let mut o = String::new();
            if en {
                o.push_str(r#"<variable formalParameter="ENO"><connectionPointOut/></variable>"#);
            }
            for out in &outs {
                write!(o, r#"<variable formalParameter="{out}"><connectionPointOut/></variable>"#)
                    .unwrap();
            }
            let (p, ord) = (self.pos(200), self.order(true));
            writeln!(
                self.body,
                r#"<block localId="{id}" typeName="{ty}"{inst}{ord}>{p}<inputVariables>{ins}</inputVariables><inOutVariables/><outputVariables>{o}</outputVariables></block>"#
            )
            .unwrap();
            match ty {
                _ if bool_mux => bools.push((id, Some("OUT"))),
                "GT" | "GE" | "EQ" | "NE" | "LT" | "LE" => bools.push((id, Some("OUT"))),
                "CTUD" => {
                    bools.push((id, Some(if self.rng.chance(50) { "QU" } else { "QD" })));
                    ints.push((id, Some("CV")));
                }
                _ if counter => {
                    bools.push((id, Some("Q")));
                    ints.push((id, Some("CV")));
                }
                _ => ints.push((id, Some("OUT"))),
            }
            if en && self.rng.chance(40) {
                bools.push((id, Some("ENO")));
            }
        }
        // Integer results into integer variables (one through INT_TO_SINT), a Boolean one
        // into a bit.
        for _ in 0..1 + self.rng.below(2) {
            let mut src = *self.rng.pick(&ints);
            let target = if self.rng.chance(20) {
                src = (self.unary("INT_TO_SINT", src, ""), Some("OUT"));
                SINT_VAR
            } else {
                *self.rng.pick(INT_VARS)
            };
            self.out_var(src, target);
        }
        let src = *self.rng.pick(&bools);
        let v = *self.rng.pick(self.bits);
        self.out_var(src, v);
        self.y += 100;
    }

    /// An output variable `target` fed from `src`.
    fn out_var(&mut self, src: (u64, Option<&'static str>), target: &str) {
        let id = self.nid();
        let (p, o) = (self.pos(500), self.order(true));
        writeln!(
            self.body,
            r#"<outVariable localId="{id}"{o}>{p}{}<expression>{target}</expression></outVariable>"#,
            Gen::conn(&[src])
        )
        .unwrap();
    }

    fn ld_rung(&mut self) {
        let rail = self.nid();
        let p = self.pos(0);
        writeln!(self.body, r#"<leftPowerRail localId="{rail}">{p}<connectionPointOut formalParameter=""/></leftPowerRail>"#).unwrap();
        let mut nodes: Vec<(u64, Option<&'static str>)> = vec![(rail, None)];
        for _ in 0..1 + self.rng.below(5) {
            if self.rng.chance(20) {
                self.block(&mut nodes, false, true);
                continue;
            }
            let k = 1 + usize::from(self.rng.chance(25)) + usize::from(self.rng.chance(10));
            let refs: Vec<_> = (0..k).map(|_| *self.rng.pick(&nodes)).collect();
            let id = self.nid();
            let (m, v) = (self.modifiers(true), self.operand());
            let p = self.pos(100);
            writeln!(
                self.body,
                r#"<contact localId="{id}"{m}>{p}{}<connectionPointOut/><variable>{v}</variable></contact>"#,
                Gen::conn(&refs)
            )
            .unwrap();
            nodes.push((id, None));
        }
        for _ in 0..1 + self.rng.below(2) {
            let k = 1 + usize::from(self.rng.chance(20));
            let refs: Vec<_> = (0..k).map(|_| *self.rng.pick(&nodes)).collect();
            let id = self.nid();
            let m = match self.rng.below(8) {
                0 => r#" negated="true""#,
                1 => r#" storage="set""#,
                2 => r#" storage="reset""#,
                3 => r#" edge="rising""#,
                4 => r#" edge="falling""#,
                _ => "",
            };
            let v = *self.rng.pick(self.bits);
            let p = self.pos(500);
            writeln!(
                self.body,
                r#"<coil localId="{id}"{m}>{p}{}<connectionPointOut/><variable>{v}</variable></coil>"#,
                Gen::conn(&refs)
            )
            .unwrap();
            // Coil chains: a later coil may be fed by this one (if it has one wire: a
            // chained coil's wires are read as a series by Beremiz, and refused).
            if k == 1 {
                nodes.push((id, None));
            }
        }
        self.y += 100;
    }

    fn fbd_network(&mut self) {
        let mut sources: Vec<(u64, Option<&'static str>)> = Vec::new();
        for _ in 0..2 + self.rng.below(3) {
            // Now and then an integer literal matiec types as BOOL (0 or 1).
            let v = if self.rng.chance(8) {
                self.rng.pick(&["0", "1", "2#1", "BOOL#0"]).to_string()
            } else {
                self.operand()
            };
            let id = self.in_var(&v, true);
            sources.push((id, None));
        }
        // Feedback: an input may be fed by a block drawn later (resolved at the end).
        let feedback = self.rng.chance(15);
        let mut later = Vec::new();
        for _ in 0..1 + self.rng.below(4) {
            let (id, ty) = self.block(&mut sources, true, false);
            later.push((id, outputs(ty)[0]));
        }
        if self.rng.chance(20) {
            let name = format!("link{}", self.id);
            let src = *self.rng.pick(&sources);
            let (c, k) = (self.nid(), self.nid());
            let p = self.pos(300);
            writeln!(
                self.body,
                r#"<connector localId="{c}" name="{name}">{p}{}</connector>"#,
                Gen::conn(&[src])
            )
            .unwrap();
            writeln!(self.body, r#"<continuation localId="{k}" name="{name}">{p}<connectionPointOut/></continuation>"#).unwrap();
            sources.push((k, None));
        }
        if feedback {
            let (id, out) = *self.rng.pick(&later);
            let pin = self.rng.pick(&["IN1", "IN2"]).to_string();
            let and = self.nid();
            let p = self.pos(250);
            let src = *self.rng.pick(&sources);
            writeln!(
                self.body,
                r#"<block localId="{and}" typeName="OR">{p}<inputVariables><variable formalParameter="{pin}">{}</variable><variable formalParameter="IN9">{}</variable></inputVariables><inOutVariables/><outputVariables><variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables></block>"#,
                Gen::conn(&[(id, Some(out))]),
                Gen::conn(&[src])
            )
            .unwrap();
            sources.push((and, Some("OUT")));
        }
        for _ in 0..1 + self.rng.below(3) {
            let src = *self.rng.pick(&sources);
            let id = self.nid();
            let v = *self.rng.pick(self.bits);
            let (p, o) = (self.pos(500), self.order(true));
            let tag = if self.rng.chance(15) { "inOutVariable" } else { "outVariable" };
            let out = if tag == "inOutVariable" { "<connectionPointOut/>" } else { "" };
            writeln!(
                self.body,
                r#"<{tag} localId="{id}"{o}>{p}{}{out}<expression>{v}</expression></{tag}>"#,
                Gen::conn(&[src])
            )
            .unwrap();
            if tag == "inOutVariable" {
                sources.push((id, None));
            }
        }
        self.y += 100;
    }
}

/// A random body (LD or FBD) over `inputs` and `bits`: the body text, its language and
/// the declarations of its FB instances.
fn random_body(
    rng: Rng,
    inputs: &'static [&'static str],
    bits: &'static [&'static str],
    ghost: &'static str,
    user_fb: bool,
    reals: Option<Rng>,
    times: Option<time::Times>,
) -> (String, &'static str, String, Rng) {
    let mut g = Gen {
        rng,
        id: 0,
        body: String::new(),
        instances: Vec::new(),
        y: 0,
        inputs,
        bits,
        ghost,
        user_fb,
        no_layout: false,
        ints: inputs == INPUTS,
        times,
    };
    g.no_layout = g.rng.chance(15);
    let fbd = g.rng.chance(45);
    for _ in 0..1 + g.rng.below(5) {
        if fbd && g.ints && g.rng.chance(40) {
            g.int_network()
        } else if fbd {
            g.fbd_network()
        } else {
            g.ld_rung()
        }
    }
    // REAL networks, drawn apart so that the other draws stay as they were.
    if let Some(mut r) = reals.filter(|_| fbd && g.ints) {
        std::mem::swap(&mut g.rng, &mut r);
        for _ in 0..g.rng.below(3) {
            g.real_network();
        }
        std::mem::swap(&mut g.rng, &mut r);
    }
    if fbd {
        g.time_writes();
    }
    let mut decls = String::new();
    for (inst, ty) in &g.instances {
        writeln!(
            decls,
            r#"<variable name="{inst}"><type><derived name="{ty}"/></type></variable>"#
        )
        .unwrap();
    }
    (g.body, if fbd { "FBD" } else { "LD" }, decls, g.rng)
}

/// A variable of an elementary type (`INT`) or a derived one (`HMI_INT`).
fn typed(name: &str, ty: &str) -> String {
    let t = if ty.starts_with("HMI_") {
        format!(r#"<derived name="{ty}"/>"#)
    } else {
        format!("<{ty}/>")
    };
    format!(r#"<variable name="{name}"><type>{t}</type></variable>"#)
}

fn bools(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!(r#"<variable name="{n}"><type><BOOL/></type></variable>"#))
        .collect::<Vec<_>>()
        .join("\n")
}

/// A random PLCopen program: LD or FBD, with its declarations and a task, and sometimes
/// a user function block (itself LD or FBD) it instantiates.
pub fn random_program(seed: u64) -> String {
    let mut rng = Rng::new(seed);
    let user_fb = rng.chance(30);
    let mut fb_pou = String::new();
    if user_fb {
        let (body, lang, decls, r) = random_body(rng, FB_INPUTS, FB_BITS, "G1", false, None, None);
        rng = r;
        fb_pou = format!(
            r#"<pou name="{USER_FB}" pouType="functionBlock"><interface><inputVars>{}</inputVars><outputVars>{}</outputVars><localVars>{}
{decls}</localVars></interface>
<body><{lang}>
{body}</{lang}></body></pou>"#,
            bools(FB_INPUTS),
            bools(&FB_BITS[..2]),
            bools(&["L0", "G1"])
        );
    }
    let reals = Some(Rng::new(seed ^ 0x5EA1));
    let times = time::Times::new(seed);
    let time_decls = times.decls();
    let (body, lang, decls, mut rng) =
        random_body(rng, INPUTS, BITS, GHOST, user_fb, reals, Some(times));
    // Beremiz SVGHMI variables (the HMI writes them before any scan): the first bit an
    // HMI_BOOL, the first integer an HMI_INT (both written by the program too, so latched),
    // the integer input an HMI_INT; drawn apart so that the other draws stay as they were.
    let hmi = Rng::new(seed ^ 0x4D11).chance(30);
    let mut vars = String::new();
    let located = rng.chance(50);
    let mut inputs = String::new();
    for (k, n) in INPUTS.iter().enumerate() {
        if located {
            writeln!(
                vars,
                r#"<variable name="{n}" address="%IX0.{k}"><type><BOOL/></type></variable>"#
            )
            .unwrap();
        } else {
            writeln!(inputs, r#"<variable name="{n}"><type><BOOL/></type></variable>"#).unwrap();
        }
    }
    // Start-up state: some bits declared TRUE, some retained (any start value).
    let mut retained = String::new();
    for n in BITS {
        match rng.below(8) {
            _ if hmi && *n == BITS[0] => writeln!(vars, "{}", typed(n, "HMI_BOOL")).unwrap(),
            0 => writeln!(
                vars,
                r#"<variable name="{n}"><type><BOOL/></type><initialValue><simpleValue value="TRUE"/></initialValue></variable>"#
            )
            .unwrap(),
            1 => writeln!(retained, "{}", bools(&[n])).unwrap(),
            _ => writeln!(vars, "{}", bools(&[n])).unwrap(),
        }
    }
    writeln!(vars, "{}", bools(&[GHOST])).unwrap();
    for n in INT_VARS {
        let ty = if hmi && *n == INT_VARS[0] { "HMI_INT" } else { "INT" };
        writeln!(vars, "{}", typed(n, ty)).unwrap();
    }
    writeln!(vars, r#"<variable name="{SINT_VAR}"><type><SINT/></type><initialValue><simpleValue value="-3"/></initialValue></variable>"#).unwrap();
    if located {
        writeln!(
            vars,
            r#"<variable name="{INT_INPUT}" address="%IW0"><type><INT/></type></variable>"#
        )
        .unwrap();
    } else if hmi {
        writeln!(vars, "{}", typed(INT_INPUT, "HMI_INT")).unwrap();
    } else {
        writeln!(inputs, r#"<variable name="{INT_INPUT}"><type><INT/></type></variable>"#).unwrap();
    }
    let [r0, r1] = real::REAL_VARS;
    writeln!(vars, r#"<variable name="{r1}"><type><REAL/></type><initialValue><simpleValue value="1.5"/></initialValue></variable>"#).unwrap();
    if located {
        writeln!(vars, r#"<variable name="{r0}" address="%ID1"><type><REAL/></type></variable>"#)
            .unwrap();
    } else {
        writeln!(inputs, r#"<variable name="{r0}"><type><REAL/></type></variable>"#).unwrap();
    }
    vars.push_str(&decls);
    writeln!(vars, "{time_decls}").unwrap();
    let retained = if retained.is_empty() {
        String::new()
    } else {
        format!("<localVars retain=\"true\">\n{retained}</localVars>")
    };
    let cycle = rng.pick(&["T#10ms", "T#7ms", "T#20ms"]).to_string();
    let input_list = if inputs.is_empty() {
        String::new()
    } else {
        format!("<inputVars>\n{inputs}</inputVars>")
    };
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201">
<fileHeader companyName="test" productName="test" productVersion="1" creationDateTime="2026-01-01T00:00:00"/>
<contentHeader name="random"><coordinateInfo><fbd><scaling x="1" y="1"/></fbd><ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc></coordinateInfo></contentHeader>
<types><dataTypes/><pous>
<pou name="main" pouType="program"><interface>{input_list}<localVars>
{vars}</localVars>{retained}</interface>
<body><{lang}>
{body}</{lang}></body></pou>
{fb_pou}
</pous></types>
<instances><configurations><configuration name="C"><resource name="R"><task name="t" priority="0" interval="{cycle}"><pouInstance name="i" typeName="main"/></task></resource></configuration></configurations></instances>
</project>
"#
    )
}

// ---------------------------------------------------------------- the check

#[derive(Default, Debug)]
pub struct Figures {
    pub programs: u64,
    pub refused: u64,
    pub scans: u64,
    pub checked: u64,
    pub skipped: u64,
    /// Programs not compared: their text blocks have one-shots.
    pub text_edges: u64,
    pub timer_fired: u64,
    /// Equations of integer bits checked (each over every scan of its run).
    pub int_checked: u64,
    pub failures: Vec<String>,
}

impl Figures {
    /// Adds another run's figures (and failures) to these.
    pub fn add(&mut self, other: Figures) {
        self.programs += other.programs;
        self.refused += other.refused;
        self.scans += other.scans;
        self.checked += other.checked;
        self.skipped += other.skipped;
        self.text_edges += other.text_edges;
        self.timer_fired += other.timer_fired;
        self.int_checked += other.int_checked;
        self.failures.extend(other.failures);
    }
}

/// A program loaded, lowered and compiled, its hypotheses ready to evaluate.
pub struct Prepared {
    pub plc: PlcProgram,
    pub lowered: Lowered,
    pub compiled: CompiledProgram,
    /// The values the hypotheses read, in the order `Hyp::scan` expects them.
    pub known: Known,
    pub hyps: Vec<Hyp>,
    /// A one-shot's memory index in the lowered program → its edge detector (an index
    /// into `lowered.edges`).
    pub edge_of: BTreeMap<usize, usize>,
}

/// Loads `xml`, lowers and compiles it, and checks that every name a hypothesis
/// reads is a signal (`known_to` says whether the reference knows a bit). `None` when
/// it is refused (counted, and a failure when `must_load`) or malformed (a failure).
pub fn prepare(
    xml: &str,
    seed: u64,
    fig: &mut Figures,
    must_load: bool,
    sel: &Selection,
) -> Option<Prepared> {
    let mut sources = Sources::new();
    let file = sources.add("random.xml", xml);
    let loaded = read_plcopen(&sources, file)
        .map(|mut p| {
            prepare_text_blocks(&mut sources, &mut p, sel);
            p
        })
        .and_then(|p| select(&p, sel))
        .and_then(|p| lower(&p).map(|l| (p, l)));
    let (plc, lowered) = match loaded {
        Ok(x) => x,
        Err(e) => {
            fig.refused += 1;
            // An edge contact read on several paths is refused (Beremiz makes one edge
            // detector per path); the generator wires contacts to several readers.
            let per_path = |x: &PlcError| matches!(x, PlcError::Unsupported { what, .. } if what == "an edge contact on more than one path");
            if must_load && !e.iter().all(per_path) {
                fig.failures.push(format!("seed {seed}: refused: {e:?}\n{xml}"));
            }
            return None;
        }
    };
    let compiled = match compile(&lowered.program, &Default::default()) {
        Ok(c) => c,
        Err(e) => {
            fig.failures
                .push(format!("seed {seed}: the compiler refused the lowering: {e:?}\n{xml}"));
            return None;
        }
    };
    if std::env::var_os("II_PLC_DIFF_SEED").is_some() {
        eprintln!(
            "{xml}\n{}",
            ii_prove::ladder::program_to_ii(&compiled, ii_prove::syntax::Notation::Paper)
        );
    }
    let cycle = plc.cycle_us;
    let mut known = Known::default();
    let loose = super::scan_eval::loose_names(&compiled);
    let hyps: Vec<Hyp> = compiled
        .hypotheses
        .iter()
        .map(|h| Hyp::new(h, &compiled, cycle, &mut known, &loose))
        .collect();
    // The one-shots, and those outside any `IF` (a function block's under a wired EN
    // are inside one).
    let (mut one_shots, mut outside) = (0, 0);
    for s in lowered.program.blocks.iter().flat_map(|b| &b.stmts) {
        s.visit(&mut |_| {}, &mut |x| one_shots += usize::from(matches!(x, BoolExpr::Edge { .. })));
        if let Some(e) = s.expr() {
            walk(e, &mut |x| outside += usize::from(matches!(x, BoolExpr::Edge { .. })));
        }
    }
    // The one-shots of text blocks (an `R_TRIG` in an ST body or a chart, under the
    // chart's or the body's conditions) are their own simulator's, not edge detectors
    // of the graphical body: such a program is not compared here (the IEC text front
    // end's tests and the matiec oracle check them).
    if outside != lowered.edges.len() && has_text_calls(&plc) {
        fig.text_edges += 1;
        return None;
    }
    if one_shots != lowered.edges.len() {
        fig.failures
            .push(format!("seed {seed}: the one-shots and their edge detectors differ\n{xml}"));
        return None;
    }
    // The compiler's edge memories are the one-shots' hidden bits: the memory with
    // index j is the j-th edge detector.
    let edge_of: BTreeMap<usize, usize> = (0..lowered.edges.len()).map(|j| (j, j)).collect();
    if known.iter().any(|src| matches!(src, Src::Edge(k) if !edge_of.contains_key(k))) {
        fig.failures.push(format!("seed {seed}: an edge memory names no one-shot\n{xml}"));
        return None;
    }
    for h in &compiled.hypotheses {
        for side in [&h.lhs, &h.rhs] {
            for node in side.as_ref() {
                if let Term::Name(n) = node
                    && !compiled.signals.contains_key(n.as_str())
                {
                    fig.failures
                        .push(format!("seed {seed}: {}: {n} is not a signal\n{xml}", h.name));
                    return None;
                }
            }
        }
    }
    // Inputs are what the program declares; everything the compiler calls an input must be one.
    for (n, k) in &compiled.signals {
        if *k == SignalKind::Input && !plc.is_input(n) {
            fig.failures
                .push(format!("seed {seed}: {n} is compiled as an input but is not one\n{xml}"));
            return None;
        }
    }
    fig.programs += 1;
    let hyps = super::scan_eval::in_order(hyps, &known);
    Some(Prepared { plc, lowered, compiled, known, hyps, edge_of })
}

/// Whether `plc` (or a block it inlines) calls a text block.
fn has_text_calls(plc: &PlcProgram) -> bool {
    !plc.text_calls.is_empty() || plc.subs.values().any(has_text_calls)
}

/// Random values of the declared inputs for `scans` scans, each held for a random
/// number of scans.
pub fn input_schedule(plc: &PlcProgram, seed: u64, scans: usize) -> Vec<BTreeMap<String, bool>> {
    let mut driven: Vec<String> = Vec::new();
    let mut words: Vec<(String, u32)> = Vec::new();
    let mut reals: Vec<String> = Vec::new();
    for n in &plc.inputs {
        match plc.input_int_type(n).and_then(|t| ii_prove::program::library::number_type(&t)) {
            Some(t) if t.real => reals.push(n.clone()),
            Some(t) => words.push((n.clone(), t.bits)),
            None => driven.push(n.clone()),
        }
    }
    // The free inputs of `REAL_TO_*` blocks: C's undefined results, any value.
    let mut free = plc.undefined_inputs();
    free.extend(plc.subs.values().flat_map(|s| s.undefined_inputs()));
    for (n, t) in free {
        words.extend(ii_prove::program::library::int_type(&t).map(|t| (n, t.bits)));
    }
    let mut rng = Rng::new(seed ^ 0x51A7);
    let mut current: BTreeMap<String, bool> = driven.iter().map(|n| (n.clone(), false)).collect();
    let mut hold: BTreeMap<String, u64> = driven.iter().map(|n| (n.clone(), 0)).collect();
    let mut out = Vec::with_capacity(scans);
    for _ in 0..scans {
        for n in &driven {
            let h = hold.get_mut(n).expect("driven");
            if *h == 0 {
                current.insert(n.clone(), rng.chance(50));
                let long = if rng.chance(40) { 2 } else { 12 };
                *h = 1 + rng.below(long);
            }
            *h -= 1;
        }
        for (n, bits) in &words {
            // Small values mostly (near presets and limits), sometimes any.
            if rng.chance(30) {
                let v: i64 = match rng.below(4) {
                    0 => rng.below(1 << bits) as i64,
                    _ => rng.below(12) as i64 - 3,
                };
                for k in 0..*bits {
                    current.insert(format!("{n}_b{k}"), v >> k & 1 == 1);
                }
            }
        }
        for n in &reals {
            real::drive(&mut rng, n, &mut current);
        }
        out.push(current.clone());
    }
    out
}

/// Checks every hypothesis of `p` at every scan of a run: `values(scan)` gives the
/// reference's value of each of `p.known` at the end of that scan (or why it cannot).
pub fn check_run(
    p: &mut Prepared,
    seed: u64,
    xml: &str,
    scans: usize,
    fig: &mut Figures,
    mut values: impl FnMut(usize) -> Result<(Vec<bool>, String), String>,
) {
    let mut vals = Vec::new();
    let mut stats = TimerStats::default();
    let mut previous = String::new();
    let mut carry = super::scan_eval::Carry::new(&p.known);
    for scan in 0..scans {
        let (mut known, shown) = match values(scan) {
            Ok(v) => v,
            Err(e) => {
                fig.failures.push(format!("seed {seed}: {e}\n{xml}"));
                return;
            }
        };
        carry.fill(&mut known);
        fig.scans += 1;
        for h in p.hyps.iter_mut() {
            if !h.run(&mut known, &mut vals, &mut stats) {
                fig.failures.push(format!(
                    "seed {seed}: {}: {} fails at scan {scan}; bits: {shown}; previous: {previous}\n{}\n{xml}",
                    h.name,
                    h.text,
                    ii_prove::ladder::program_to_ii(&p.compiled, ii_prove::syntax::Notation::Paper)
                ));
                return;
            }
        }
        carry.keep(&known);
        previous = shown;
    }
    for h in &p.hyps {
        if h.skip.is_some() {
            fig.skipped += 1;
        } else {
            fig.checked += 1;
            let c = p.compiled.hypotheses.iter().find(|c| c.name == h.name);
            let lhs = c.map(|c| &c.lhs[ii_prove::term::root(&c.lhs)]);
            fig.int_checked += u64::from(matches!(lhs, Some(Term::Name(n))
                if matches!(p.compiled.signals.get(n.as_str()), Some(SignalKind::IntBit { .. }))));
            fig.timer_fired += u64::from(h.has_timer && h.timer_fired);
        }
    }
}

/// Loads `xml`, compiles it, runs it on the simulator with random inputs and checks
/// every hypothesis at every scan.
pub fn check(xml: &str, seed: u64, fig: &mut Figures, must_load: bool) {
    let Some(mut p) = prepare(xml, seed, fig, must_load, &Selection::default()) else { return };
    let mut sim = PlcSimulator::new(&p.plc);
    if p.lowered.edges.iter().any(|(path, k, pin)| sim.edge_memory_of(path, *k, pin).is_none()) {
        fig.failures.push(format!("seed {seed}: a one-shot names no edge detector\n{xml}"));
        return;
    }
    for src in &p.known {
        if let Src::Bit(n) = src
            && !sim.bits().contains_key(n)
            && !matches!(p.compiled.signals.get(n), Some(SignalKind::Input))
        {
            fig.failures.push(format!("seed {seed}: {src:?} is not known to the simulator\n{xml}"));
            return;
        }
    }
    const SCANS: usize = 160;
    let schedule = input_schedule(&p.plc, seed, SCANS);
    let (known, lowered, edge_of) = (p.known.clone(), p.lowered.edges.clone(), p.edge_of.clone());
    check_run(&mut p, seed, xml, SCANS, fig, |scan| {
        let current = &schedule[scan];
        sim.step(current);
        let values = known
            .iter()
            .map(|src| match src {
                Src::Bit(n) => sim
                    .bits()
                    .get(n)
                    .copied()
                    .unwrap_or_else(|| current.get(n).copied().unwrap_or(false)),
                Src::Edge(k) => {
                    let (path, owner, pin) = &lowered[edge_of[k]];
                    sim.edge_memory_of(path, *owner, pin).unwrap_or(false)
                }
                Src::IntBit { .. } | Src::Defined(_) | Src::PreDefined(_) => {
                    src.read(&|_| false, &|_| None, &|x| sim.int(x))
                }
            })
            .collect();
        let shown: Vec<String> =
            sim.bits().iter().map(|(n, v)| format!("{n}={}", u8::from(*v))).collect();
        Ok((values, shown.join(" ")))
    });
}
