//! Differential test of the rung compiler against the scan simulator: every compiled equation and recurrence must hold at every scan of random runs of random LDmicro programs (every element kind of `formats/ldmicro.md` §4) and of the examples, data cases and corpus.
//!
//! The reference is [`Simulator`] (written from the format note, §6). The
//! hypotheses are evaluated on its scans by an evaluator written here from
//! `shared/spec/semantics.md`, "Programs, scan by scan", and nothing else:
//!
//! * `·`, `+`, `¬` pointwise; `SR(s, r)_k = s_k ∨ (¬r_k ∧ SR_(k−1))`,
//!   `RS(s, r)_k = ¬r_k ∧ (s_k ∨ RS_(k−1))`, both 0 before the first scan;
//! * `d/f` is 1 at scan `k` iff `f` is 1 at every scan `k−n … k`, and `f/d` iff `f`
//!   is 1 at some scan `max(0, k−n) … k`, with `n = ceil(d / δ)` for the program's
//!   cycle `δ` (the program's timers are not consulted);
//! * a program bit is the simulator's value at the end of the scan; `pre_X` is the
//!   simulator's `X` at the end of the previous scan (0 at the first);
//! * fresh signals (outputs of elements the algebra cannot express) are
//!   existential: a hypothesis must hold for *some* run of them. The evaluator
//!   keeps the set of its own states (timer counts, memories) reachable by runs of
//!   the fresh signals under which the hypothesis held at every scan so far; the
//!   hypothesis fails when the set becomes empty. (Pointwise occurrences keep the
//!   set a singleton; a hypothesis whose set grows too large is skipped and
//!   counted.)
//!
//! Where the simulator does not model an element (THI, TLO, TCY, ODF, OSC,
//! peripherals, …) it takes a best guess for its output and marks what depends
//! on it inexact. The compiler gives every such element a fresh output, so the
//! guess is one of the runs the hypotheses claim to cover, and they are checked
//! on it too (the scans with inexact values are counted).
//!
//! The run drives only the bits the outside world writes (names starting with
//! `X`, `I` or `M`), with values held for random numbers of scans (long enough
//! for timers to fire, and one-scan pulses). Programs with control flow must be
//! refused by the compiler, and only they. Failures print the program text and
//! the seed; `II_DIFF_PROGRAMS=N` scales the random part (6,000 by default,
//! about 75 s in release; 20,000 or more outside CI), `II_DIFF_SEED=S` reruns one program.
#![warn(missing_docs)]

use crate::common;
use crate::common::rng;
use crate::common::scan_eval;
use rng::Rng;
use scan_eval::*;

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use ii_prove::diag::Sources;
use ii_prove::kernel::Rel;
use ii_prove::ladder::{
    CompiledProgram, ElementKind, LadderError, LdProgram, SignalKind, Simulator, decode_latin1,
    read_ldmicro,
};
use ii_prove::term::{Expr, Term};
use num_rational::BigRational;
use num_traits::ToPrimitive;

// ---------------------------------------------------------------- program generator

/// Bits read by contacts. `Rg`/`Yg` never get a coil (ghost bits); `Ia`/`Mb` are
/// Modbus inputs the outside world writes.
const READ_BITS: &[&str] = &[
    "Xa", "Xb", "Xc", "Xd", "Ia", "Mb", "Ra", "Rb", "Rc", "Ya", "Yb", "Rg", "Yg", "Ra", "Rb", "Ya",
    "pre_Ra", "OSR_r2",
];
/// Bits written by coils; `pre_Ra`, `OSR_r2` and `TOGGLE_r3` clash with the compiler's
/// own names for previous values and fresh outputs.
const COIL_BITS: &[&str] =
    &["Ra", "Rb", "Rc", "Ya", "Yb", "Yc", "Ra", "Rb", "Ya", "pre_Ra", "OSR_r2", "TOGGLE_r3"];
/// Timer accumulators; `Ra` and `Ya` are also bit names (separate name spaces).
/// `T1` is also a stage of `SHIFT_REGISTER T 2`, and `Ta` a `PERSIST`ed variable;
/// `Ta` is also an integer that `MOVE`, arithmetic and comparisons write and read.
const TIMERS: &[&str] = &["Ta", "Tb", "Tc", "Ra", "Ya", "T1", "T1"];
const COUNTERS: &[&str] = &["Ca", "Cb"];
/// `Aa` is what `READ_ADC Aa` reads, `vb` what `UART_RECV vb` and `I2C_RD` receive.
const INTS: &[&str] = &["va", "vb", "Ca", "Ta", "Aa"];
const CYCLES: &[u64] = &[10_000, 10_000, 1_000, 5_000, 20_000, 2_500, 100_000, 40_000, 3_333];

struct Gen {
    rng: Rng,
    cycle: u64,
    control_flow: bool,
    /// Keywords emitted (coverage).
    used: BTreeSet<String>,
}

impl Gen {
    fn operand(&mut self) -> String {
        if self.rng.chance(50) {
            self.rng.pick(INTS).to_string()
        } else if self.rng.chance(15) {
            // Literals at the edges of LDmicro's 1- to 3-byte integers.
            self.rng
                .pick(&["127", "-128", "200", "254", "300", "32767", "40000", "-70000"])
                .to_string()
        } else {
            (self.rng.below(7) as i64 - 2).to_string()
        }
    }

    fn timer(&mut self) -> String {
        let kw = *self
            .rng
            .pick(&["TON", "TON", "TON", "TOF", "TOF", "TOF", "RTO", "RTL", "THI", "TLO", "TCY"]);
        let name = self.rng.pick(TIMERS);
        let n = self.rng.below(8);
        let rem = if self.rng.chance(60) { 0 } else { self.rng.below(self.cycle) };
        let delay =
            if self.rng.chance(3) { "va".to_string() } else { (n * self.cycle + rem).to_string() };
        if self.rng.chance(5) {
            // A long delay brought back to a few scans by a large negative adjust
            // (`TON Tdly 1000000 -95` on a 10 ms cycle counts 5 scans).
            let adjust = -95 - self.rng.below(6) as i64;
            return format!("{kw} {name} {} {adjust}", 100 * self.cycle + rem);
        }
        let adjust = if self.rng.chance(55) {
            String::new()
        } else {
            let a = match self.rng.below(10) {
                0 => -95,
                1 => 50,
                2 => -(n as i64) - self.rng.below(3) as i64,
                3 => 5,
                _ => self.rng.below(5) as i64 - 2,
            };
            format!(" {a}")
        };
        self.used.insert(kw.to_string());
        format!("{kw} {name} {delay}{adjust}")
    }

    fn coil(&mut self) -> String {
        // Now and then a coil on a Modbus coil, which the compiler must refuse.
        let name = if self.rng.chance(1) { "Mq" } else { self.rng.pick(COIL_BITS) };
        let (neg, set, reset, toggle) = match self.rng.below(12) {
            0..=4 => (0, 0, 0, 0),
            5 | 6 => (1, 0, 0, 0),
            7 | 8 => (0, 1, 0, 0),
            9 | 10 => (0, 0, 1, 0),
            _ => (0, 0, 0, 1),
        };
        self.used.insert(
            ["COIL", "COIL neg", "COIL set", "COIL reset", "COIL toggle"][usize::from(neg == 1)
                + 2 * usize::from(set == 1)
                + 3 * usize::from(reset == 1)
                + 4 * usize::from(toggle == 1)]
            .to_string(),
        );
        if toggle == 0 && self.rng.chance(50) {
            format!("COIL {name} {neg} {set} {reset}")
        } else {
            format!("COIL {name} {neg} {set} {reset} {toggle}")
        }
    }

    /// An element that ends a rung (an output-type element).
    fn output(&mut self) -> String {
        let text = match self.rng.below(20) {
            0..=11 => return self.coil(),
            12 => format!("RES {}", self.rng.pick(&["Ta", "Tb", "Ca", "Cb", "Ra"])),
            13 => format!("MOVE {} {}", self.rng.pick(INTS), self.operand()),
            14 => {
                let op = self.rng.pick(&["ADD", "SUB", "MUL", "DIV"]);
                format!("{op} {} {} {}", self.rng.pick(INTS), self.operand(), self.operand())
            }
            15 => self
                .rng
                .pick(&[
                    "MOD va vb 3",
                    "SET_BIT va 1",
                    "SHIFT_REGISTER sr 3",
                    "SHIFT_REGISTER T 2",
                    "PERSIST Ta",
                    "PERSIST T1",
                    "PERSIST va",
                    "NEG vb va",
                ])
                .to_string(),
            // Bit operations: on every target, or on AVR only (SHR, SR0, ROL, ROR, BIN2BCD),
            // on ARM and AVR (BCD2BIN, OPPOSITE), on ARM (SWAP).
            19 if self.rng.chance(50) => {
                let op = self.rng.pick(&[
                    "AND", "OR", "XOR", "SHL", "SHR", "SR0", "ROL", "ROR", "MOD", "NOT", "BIN2BCD",
                    "BCD2BIN", "OPPOSITE", "SWAP",
                ]);
                let (dest, a) = (self.rng.pick(INTS), self.rng.pick(INTS));
                let b = match self.rng.below(3) {
                    0 => self.operand(),
                    _ => self.rng.below(10).to_string(),
                };
                if matches!(*op, "NOT" | "BIN2BCD" | "BCD2BIN" | "OPPOSITE" | "SWAP") {
                    format!("{op} {dest} {a}")
                } else {
                    format!("{op} {dest} {a} {b}")
                }
            }
            16 => self
                .rng
                .pick(&[
                    "READ_ADC Aa",
                    "SET_PWM 50 1000",
                    "UART_SEND va",
                    "UART_RECV vb",
                    "FORMATTED_STRING va 2 65 66",
                    "I2C_WR i2c va 0 0 0 0 0 0",
                    "I2C_RD i2c - vb Master 0x68 0 MSB 100000",
                    "SPI_WR spi va 0 0 0 0 0 0",
                    "BUS vb va 7 6 5 4 3 2 1 0",
                    "7SEGMENTS vb va C",
                ])
                .to_string(),
            17 => self.counter(),
            _ => {
                // A timer at the end of a rung drives a coil, so that its output is observed.
                let t = self.timer();
                let c = self.coil();
                return format!("{t}\n{c}");
            }
        };
        let kw = text.split_whitespace().next().unwrap_or("").to_string();
        self.used.insert(kw);
        text
    }

    fn counter(&mut self) -> String {
        let kw = self.rng.pick(&["CTU", "CTD", "CTC", "CTR"]);
        let name = self.rng.pick(COUNTERS);
        let max = if self.rng.chance(10) {
            126 + self.rng.below(3) as i64
        } else {
            self.rng.below(4) as i64 - 1
        };
        let tail = match self.rng.below(3) {
            0 => String::new(),
            1 => format!(" {}", self.rng.below(3)),
            _ => format!(" {} {}", self.rng.below(3), self.rng.pick(&["/", "\\", "-", "o"])),
        };
        self.used.insert(kw.to_string());
        format!("{kw} {name} {max}{tail}")
    }

    fn leaf(&mut self) -> String {
        let text = match self.rng.below(40) {
            0..=17 => {
                let name = self.rng.pick(READ_BITS);
                let neg = self.rng.below(2);
                self.used.insert(if neg == 1 { "CONTACTS neg" } else { "CONTACTS" }.into());
                return if self.rng.chance(20) {
                    format!(
                        "CONTACTS {name} {neg} {}",
                        u8::from(name.starts_with('X') && self.rng.chance(50))
                    )
                } else {
                    format!("CONTACTS {name} {neg}")
                };
            }
            18 | 19 => "SHORT".into(),
            20 | 21 => "OPEN".into(),
            22 | 23 => "MASTER_RELAY".into(),
            24..=26 => return self.timer(),
            27 | 28 => self.rng.pick(&["OSR", "OSF", "ODR", "ODF", "OSL", "OSC"]).to_string(),
            29 => return self.counter(),
            30 | 31 => {
                let op = self.rng.pick(&["EQU", "NEQ", "GRT", "GEQ", "LES", "LEQ"]);
                format!("{op} {} {}", self.operand(), self.operand())
            }
            32 => self
                .rng
                .pick(&[
                    "IF_BIT_SET va 0",
                    "IF_BIT_CLEAR vb 1",
                    "UART_RECV_AVAIL",
                    "UART_SEND_READY",
                    "UART_SEND_BUSY",
                    "UART_UDRE",
                    "CLRWDT",
                ])
                .to_string(),
            33 => "LABEL Lx".into(),
            34 => "PLACEHOLDER".into(),
            35 => "COMMENT inline note".into(),
            36 if self.control_flow => self
                .rng
                .pick(&[
                    "GOTO Lx",
                    "GOTO Ly",
                    "GOSUB Sx",
                    "SUBPROG Sx",
                    "ENDSUB Sx",
                    "RETURN",
                    "LOCK",
                    "SLEEP",
                    "LABEL Ly",
                ])
                .to_string(),
            _ => return self.coil(),
        };
        let kw = text.split_whitespace().next().unwrap_or("").to_string();
        self.used.insert(kw);
        text
    }

    fn series(&mut self, depth: u32, out: &mut String, indent: usize) {
        let n = 1 + self.rng.below(3);
        for _ in 0..n {
            if depth > 0 && self.rng.chance(25) {
                self.parallel(depth - 1, out, indent);
            } else if depth > 0 && self.rng.chance(4) {
                // SERIES directly inside a series (new only; the reader flattens it).
                line(out, indent, "SERIES");
                self.series(depth - 1, out, indent + 2);
                line(out, indent, "END");
            } else {
                let l = self.leaf();
                line(out, indent, &l);
            }
        }
    }

    fn parallel(&mut self, depth: u32, out: &mut String, indent: usize) {
        line(out, indent, "PARALLEL");
        let n = 2 + self.rng.below(2);
        for _ in 0..n {
            if self.rng.chance(50) {
                line(out, indent + 2, "SERIES");
                self.series(depth, out, indent + 4);
                line(out, indent + 2, "END");
            } else {
                let l = self.leaf();
                line(out, indent + 2, &l);
            }
        }
        line(out, indent, "END");
    }

    fn rung(&mut self, out: &mut String) {
        if self.rng.chance(6) {
            // A comment rung (orig skips a lone COMMENT; new any rung starting with one).
            line(out, 2, "COMMENT a comment rung");
            if self.rng.chance(50) {
                let o = self.output();
                line(out, 2, &o);
            }
            return;
        }
        if self.rng.chance(3) {
            return; // an empty rung
        }
        if self.rng.chance(40) {
            // A timer rung: contacts, one or two TON/TOF, a coil.
            for _ in 0..1 + self.rng.below(2) {
                let name = self.rng.pick(READ_BITS);
                line(out, 2, &format!("CONTACTS {name} {}", self.rng.below(2)));
            }
            for _ in 0..1 + self.rng.below(2) {
                let mut t = self.timer();
                while !t.starts_with("TO") {
                    t = self.timer();
                }
                line(out, 2, &t);
            }
            let c = self.coil();
            line(out, 2, &c);
            return;
        }
        self.series(2, out, 2);
        match self.rng.below(10) {
            0..=5 => {
                let o = self.output();
                line(out, 2, &o);
            }
            6 | 7 => {
                // A parallel group of outputs at the end of the rung.
                line(out, 2, "PARALLEL");
                for _ in 0..2 + self.rng.below(2) {
                    if self.rng.chance(70) {
                        let o = self.output();
                        line(out, 4, &o);
                    } else {
                        line(out, 4, "SERIES");
                        let l = self.leaf();
                        line(out, 6, &l);
                        let o = self.output();
                        line(out, 6, &o);
                        line(out, 4, "END");
                    }
                }
                line(out, 2, "END");
            }
            _ => {}
        }
    }
}

fn line(out: &mut String, indent: usize, text: &str) {
    let _ = writeln!(out, "{:indent$}{text}", "");
}

/// A random program text, and whether it was generated with control-flow elements enabled.
fn random_program(seed: u64) -> (String, BTreeSet<String>) {
    let mut rng = Rng::new(seed);
    let header =
        *rng.pick(&["LDmicro0.1", "LDmicro0.1", "LDmicro0.2", "LDmicro0.2", "LDmicro", ""]);
    let cycle = *rng.pick(CYCLES);
    let control_flow = rng.chance(8);
    let mut g = Gen { rng, cycle, control_flow, used: BTreeSet::new() };
    let mut text = String::new();
    if !header.is_empty() {
        text.push_str(header);
        text.push('\n');
    }
    if cycle != 10_000 || g.rng.chance(50) {
        if header == "LDmicro0.2" && g.rng.chance(50) {
            let _ = writeln!(
                text,
                "CYCLE={cycle} us at Timer1, YPlcCycleDuty:0, ConfigurationWord(s):0x0"
            );
        } else {
            let _ = writeln!(text, "CYCLE={cycle}");
        }
    }
    if header == "LDmicro0.2" && g.rng.chance(50) {
        // LDmicro ≥ 2016 sizes its integers: 1 to 4 bytes (3 computed on AVR only).
        // The targets whose code differs: AVR, ARM (C only), PIC, ESP8266.
        if g.rng.chance(60) {
            text.push_str("MICRO=Atmel AVR ATmega328 28-PDIP\n");
        } else if g.rng.chance(50) {
            let micro = g.rng.pick(&[
                "St ARM STM32F40X 144-LQFP",
                "St ARM STM32F40X 144-LQFP",
                "Microchip PIC16F877 40-PDIP",
                "ESP8266",
            ]);
            let _ = writeln!(text, "MICRO={micro}");
        }
        text.push_str("VAR LIST\n");
        for name in ["va", "vb", "Ca", "Cb", "Ta", "Tb", "Aa"] {
            if g.rng.chance(60) {
                let _ = writeln!(text, "    {} bytes {name}", g.rng.pick(&[1, 1, 1, 2, 3, 4]));
            }
        }
        text.push_str("END\n");
        g.used.insert("VAR LIST".into());
    }
    if header.is_empty() {
        g.used.insert("headerless".into());
    } else {
        g.used.insert(header.into());
    }
    text.push_str("PROGRAM\n");
    // Mostly small programs; now and then a large one (long inlined reads, many atoms).
    let rungs = if g.rng.chance(10) { 8 + g.rng.below(17) } else { 1 + g.rng.below(8) };
    for k in 0..rungs {
        if header == "LDmicro0.2" {
            let _ = writeln!(text, "RUNG {}", k + 1);
        } else {
            text.push_str("RUNG\n");
        }
        g.rung(&mut text);
        text.push_str("END\n");
    }
    (text, g.used)
}

// ---------------------------------------------------------------- one program

/// Figures of one or many programs.
#[derive(Default, Debug, Clone)]
struct Figures {
    programs: u64,
    /// Programs the compiler refused (all with control flow or a coil on an outside bit).
    refused: u64,
    scans: u64,
    /// Scans on which some simulator value was inexact (an unmodelled element's guess).
    inexact_scans: u64,
    /// Hypotheses checked at every scan.
    checked: u64,
    /// Of those, with fresh signals (existential), and with fresh signals under a timer or memory.
    existential: u64,
    temporal_existential: u64,
    /// Hypothesis × scan pairs checked.
    checked_scans: u64,
    skipped_fresh: u64,
    skipped_states: u64,
    skipped_delay: u64,
    timers: TimerStats,
    /// Compiled TON/TOF terms with a positive delay, and how many of them were seen on.
    timer_terms: u64,
    /// Checked hypotheses with a `d/f` or `f/d` (`n > 0`), and those of them whose timer was
    /// on (`d/f`) or holding after its input fell (`f/d`) at some scan.
    timer_hyps: u64,
    timer_hyps_fired: u64,
    /// Programs whose exact model (no fresh signal) was also replayed by the unroller.
    unrolled: u64,
    disagreements: u64,
    failures: Vec<String>,
    keywords: BTreeSet<String>,
}

impl Figures {
    fn skipped(&self) -> u64 {
        self.skipped_fresh + self.skipped_states + self.skipped_delay
    }
    fn add(&mut self, o: &Figures) {
        self.programs += o.programs;
        self.refused += o.refused;
        self.scans += o.scans;
        self.inexact_scans += o.inexact_scans;
        self.checked += o.checked;
        self.existential += o.existential;
        self.temporal_existential += o.temporal_existential;
        self.checked_scans += o.checked_scans;
        self.skipped_fresh += o.skipped_fresh;
        self.skipped_states += o.skipped_states;
        self.skipped_delay += o.skipped_delay;
        self.timers.ton_on += o.timers.ton_on;
        self.timers.tof_hold += o.timers.tof_hold;
        self.timer_terms += o.timer_terms;
        self.timer_hyps += o.timer_hyps;
        self.timer_hyps_fired += o.timer_hyps_fired;
        self.unrolled += o.unrolled;
        self.disagreements += o.disagreements;
        if self.failures.len() < 10 {
            self.failures.extend(o.failures.iter().take(10 - self.failures.len()).cloned());
        }
        self.keywords.extend(o.keywords.iter().cloned());
    }
    fn summary(&self) -> String {
        let total = self.checked + self.skipped();
        format!(
            "{} programs ({} refused, all with control flow or a coil on an outside bit), {} scans ({} with inexact simulator values); {} hypotheses checked at \
             every scan ({} hypothesis-scans; {} with fresh signals, {} of them under a timer or \
             memory), {} skipped ({:.3}%: {} too many fresh signals, {} too many states, {} delay); \
             timers: {} TON/TOF terms, {} hypotheses with a timer, on in {} of them, {} scans with a d/f on, {} scans with an f/d holding after \
             its input fell; {} programs also replayed by the counterexample unroller; {} \
             disagreements",
            self.programs,
            self.refused,
            self.scans,
            self.inexact_scans,
            self.checked,
            self.checked_scans,
            self.existential,
            self.temporal_existential,
            self.skipped(),
            100.0 * self.skipped() as f64 / total.max(1) as f64,
            self.skipped_fresh,
            self.skipped_states,
            self.skipped_delay,
            self.timer_terms,
            self.timer_hyps,
            self.timer_hyps_fired,
            self.timers.ton_on,
            self.timers.tof_hold,
            self.unrolled,
            self.disagreements
        )
    }
}

const CONTROL_FLOW: &[&str] = &["GOTO", "GOSUB", "SUBPROG", "ENDSUB", "RETURN", "LOCK", "SLEEP"];

fn has_control_flow(p: &LdProgram) -> bool {
    p.elements().any(|e| CONTROL_FLOW.contains(&e.kind.keyword()))
}

/// A coil on a bit the outside world writes (an input pin, a Modbus input or coil).
fn writes_an_outside_bit(p: &LdProgram) -> bool {
    p.elements().any(
        |e| matches!(&e.kind, ElementKind::Coil { name, .. } if name.starts_with(['X', 'I', 'M'])),
    )
}

/// What the compiler must refuse: control flow, and coils on bits written from outside.
fn must_refuse(p: &LdProgram) -> bool {
    has_control_flow(p) || writes_an_outside_bit(p)
}

fn parse(name: &str, text: &str) -> Result<LdProgram, Vec<LadderError>> {
    let mut s = Sources::new();
    let f = s.add(name, text.to_string());
    read_ldmicro(&s, f)
}

/// Longest timer of the program in scans (for the input holds and the run length only).
fn longest_timer(p: &LdProgram) -> u64 {
    p.elements()
        .filter_map(|e| match &e.kind {
            ElementKind::Timer { delay, adjust, .. } => p.timer_scans(delay, *adjust),
            _ => None,
        })
        .map(|s| s.clamp(0, 200) as u64)
        .max()
        .unwrap_or(0)
}

/// Compiles `program`, runs it on the simulator from power-up with random inputs, and
/// checks every hypothesis at every scan. Disagreements are recorded in the figures
/// (with `label`, the program text and the scan).
fn check_program(label: &str, text: &str, program: &LdProgram, seed: u64) -> Figures {
    let mut fig = Figures { programs: 1, ..Figures::default() };
    let fail = |fig: &mut Figures, what: String| {
        fig.disagreements += 1;
        if fig.failures.len() < 3 {
            fig.failures.push(format!("{label} (seed {seed}): {what}\n---- program\n{text}----"));
        }
    };
    let compiled = match ii_prove::ladder::compile(program) {
        Ok(c) => c,
        Err(errors) => {
            fig.refused = 1;
            if !must_refuse(program) {
                fail(
                    &mut fig,
                    format!("refused without control flow or an outside bit: {errors:?}"),
                );
            }
            return fig;
        }
    };
    if must_refuse(program) {
        fail(&mut fig, "a program with control flow or a coil on an outside bit compiled".into());
        return fig;
    }
    // The bits the outside world writes.
    let driven: Vec<String> =
        program.signals().into_iter().filter(|n| n.starts_with(['X', 'I', 'M'])).collect();
    // The bits of the peripheral reads' values and arrival flags (free integer inputs).
    let reads: Vec<(String, u32)> = ii_prove::ladder::readings(program)
        .into_values()
        .flat_map(|r| std::iter::once((r.value, r.ty.bits)).chain(r.arrived.map(|g| (g, 1))))
        .collect();
    for (name, kind) in &compiled.signals {
        if *kind == SignalKind::Input && !driven.contains(name) {
            fail(
                &mut fig,
                format!(
                    "{name} is classified as an input, but nothing outside the program writes it"
                ),
            );
        }
    }
    let mut known = Known::default();
    let cycle = program.cycle_us;
    let loose = scan_eval::loose_names(&compiled);
    let mut hyps: Vec<Hyp> = compiled
        .hypotheses
        .iter()
        .map(|h| Hyp::new(h, &compiled, cycle, &mut known, &loose))
        .collect();
    hyps = scan_eval::in_order(hyps, &known);
    let mut carry = scan_eval::Carry::new(&known);
    fig.timer_terms = compiled.timer_info.iter().filter(|t| t.effective.is_some()).count() as u64;
    let longest = longest_timer(program);
    let total = (6 * (longest + 2)).clamp(64, 3_000);
    let hold_max = (longest + longest / 2 + 3).max(4);
    let mut rng = Rng::new(seed ^ 0xD1FF);
    let mut current: BTreeMap<String, bool> = driven.iter().map(|n| (n.clone(), false)).collect();
    let mut hold: BTreeMap<String, u64> = driven.iter().map(|n| (n.clone(), 0)).collect();
    let mut sim = Simulator::new(program);
    // Every name of a hypothesis is a signal of the compiled program, and every bit it
    // reads is one the simulator has.
    for h in &compiled.hypotheses {
        for side in [&h.lhs, &h.rhs] {
            for node in side.as_ref() {
                if let Term::Name(n) = node
                    && !compiled.signals.contains_key(n.as_str())
                {
                    fail(&mut fig, format!("{}: {n} is not a signal of the program", h.name));
                }
            }
        }
    }
    for src in &known {
        match src {
            Src::Bit(n) if !sim.bits().contains_key(n) => {
                fail(&mut fig, format!("{n} is not a bit of the program"))
            }
            Src::Edge(k) if sim.edge_memory(*k).is_none() => {
                fail(&mut fig, format!("element {k} has no edge memory"))
            }
            _ => {}
        }
    }
    let mut prev: BTreeMap<String, bool> = BTreeMap::new();
    let mut values = vec![false; known.len()];
    let mut vals = Vec::new();
    // Stretches where every input is frozen, long enough for the longest timer to fire.
    let mut frozen = 0;
    // Without fresh signals the equations are a complete model: the counterexample
    // search's unroller must then reproduce every written bit of the simulator.
    let exact_model =
        cycle > 0 && !compiled.signals.values().any(|k| matches!(k, SignalKind::Fresh { .. }));
    let mut input_trace: Vec<BTreeMap<String, bool>> = Vec::new();
    let mut bit_trace: Vec<BTreeMap<String, bool>> = Vec::new();
    'scans: for scan in 0..total {
        if frozen == 0 && rng.below(3 * (longest + 2)) == 0 {
            frozen = longest + 2 + rng.below(longest + 2);
        }
        for n in &driven {
            if frozen > 0 {
                break;
            }
            let h = hold.get_mut(n).expect("driven input");
            if *h == 0 {
                current.insert(n.clone(), rng.chance(50));
                *h = 1 + if rng.chance(35) { rng.below(2) } else { rng.below(hold_max) };
            }
            *h -= 1;
        }
        frozen = frozen.saturating_sub(1);
        for (name, width) in &reads {
            // Mostly values near the literals the comparisons use, sometimes any.
            let v =
                if rng.chance(80) { rng.below(8) as i64 - 3 } else { rng.below(1 << 16) as i64 };
            for k in 0..*width {
                current.insert(format!("{name}_b{k}"), v >> k & 1 == 1);
            }
        }
        sim.step(&current);
        if exact_model {
            input_trace.push(current.clone());
            // The integers' compiled bits beside the program's bits.
            let mut bits = sim.bits().clone();
            for (name, kind) in &compiled.signals {
                if let SignalKind::IntBit { of, bit, start, .. } = kind {
                    bits.insert(name.clone(), (sim.int(of) >> bit & 1 == 1) != *start);
                }
            }
            bit_trace.push(bits);
        }
        for (v, src) in values.iter_mut().zip(&known) {
            *v = src.read(&|n| sim.bit(n), &|k| sim.edge_memory(k), &|n| Some(sim.int(n)));
        }
        carry.fill(&mut values);
        fig.scans += 1;
        fig.inexact_scans += u64::from(!sim.unknown().is_empty());
        for h in hyps.iter_mut() {
            if !h.run(&mut values, &mut vals, &mut fig.timers) {
                let bits: Vec<String> =
                    sim.bits().iter().map(|(n, v)| format!("{n}={}", u8::from(*v))).collect();
                let pre: Vec<String> =
                    prev.iter().map(|(n, v)| format!("{n}={}", u8::from(*v))).collect();
                fail(
                    &mut fig,
                    format!(
                        "{}: {} fails at scan {scan} (0-based); bits at the end of the scan: {}; \
                         at the end of the previous scan: {}",
                        h.name,
                        h.text,
                        bits.join(" "),
                        pre.join(" ")
                    ),
                );
                break 'scans;
            }
        }
        carry.keep(&values);
        prev = sim.bits().clone();
    }
    if exact_model && fig.disagreements == 0 {
        if let Err(what) = unroll_agrees(program, &compiled, cycle, &input_trace, &bit_trace) {
            fail(&mut fig, what);
        }
        fig.unrolled = 1;
    }
    for h in &hyps {
        match h.skip {
            Some(Skip::TooManyFresh) => fig.skipped_fresh += 1,
            Some(Skip::TooManyStates) => fig.skipped_states += 1,
            Some(Skip::Delay) => fig.skipped_delay += 1,
            None => {
                fig.checked += 1;
                fig.existential += u64::from(h.n_free > 0);
                fig.temporal_existential += u64::from(h.temporal_free);
                fig.checked_scans += h.checked_scans;
                fig.timer_hyps += u64::from(h.has_timer);
                fig.timer_hyps_fired += u64::from(h.has_timer && h.timer_fired);
            }
        }
    }
    fig
}

/// The compiled equations unrolled by the counterexample search (`counterexample::unroll`,
/// its delay-to-steps rule `floor(d / δ)`) over the run's inputs give every equation's
/// bit exactly as the simulator computed it, at every scan.
fn unroll_agrees(
    program: &LdProgram,
    compiled: &CompiledProgram,
    cycle_us: u64,
    inputs: &[BTreeMap<String, bool>],
    bits: &[BTreeMap<String, bool>],
) -> Result<(), String> {
    use ii_prove::counterexample::unroll::{Concrete, unroll};
    let heads: Vec<Expr> = compiled.hypotheses.iter().map(|h| h.lhs.clone()).collect();
    let refs: Vec<&Expr> = heads.iter().collect();
    let model = ii_prove::counterexample::Program {
        reference: program,
        compiled,
        assumptions: &[],
        shared: None,
    }
    .model(&refs);
    let cycle = BigRational::new(cycle_us.into(), 1_000_000u64.into());
    let steps_of =
        |d: &ii_prove::term::Delay| (d.seconds() / &cycle).floor().to_integer().to_usize();
    let mut missing = None;
    let mut free = |_: &mut Concrete, name: &str, k: usize| -> bool {
        match inputs[k].get(name) {
            Some(v) => *v,
            None => {
                missing.get_or_insert_with(|| name.to_string());
                false
            }
        }
    };
    let u = unroll(&mut Concrete, &model, &[], inputs.len(), &steps_of, &mut free)
        .map_err(|e| format!("the unroller refuses the model: {e}"))?;
    if let Some(name) = missing {
        return Err(format!("the unroller asks for {name}, which is not an input"));
    }
    for (name, _) in &model.defs {
        let Some(values) = u.signals.get(name) else { continue };
        // Edge memories and intermediate values are not bits of the program (their
        // equations are checked above).
        if matches!(
            compiled.signals.get(name),
            Some(SignalKind::EdgeMemory { .. } | SignalKind::Intermediate { .. })
        ) {
            continue;
        }
        for (k, v) in values.iter().enumerate() {
            let sim = bits[k].get(name).copied().unwrap_or(false);
            if *v != sim {
                return Err(format!(
                    "the unroller gives {name} = {} at scan {k} (0-based), the simulator {}",
                    u8::from(*v),
                    u8::from(sim)
                ));
            }
        }
    }
    Ok(())
}

// ---------------------------------------------------------------- tests

fn programs_to_run() -> u64 {
    std::env::var("II_DIFF_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(6_000)
}

fn base_seed() -> u64 {
    std::env::var("PROPTEST_RNG_SEED").ok().and_then(|v| v.parse().ok()).unwrap_or(0x11_D1FF)
}

/// One random program: generate, parse, check. A panic is a disagreement too.
fn random_case(seed: u64) -> Figures {
    let (text, used) = random_program(seed);
    let result = catch_unwind(AssertUnwindSafe(|| match parse("random.ld", &text) {
        Ok(p) => check_program("random.ld", &text, &p, seed),
        Err(e) => Figures {
            programs: 1,
            disagreements: 1,
            failures: vec![format!(
                "seed {seed}: the generated text does not parse: {e:?}\n{text}"
            )],
            ..Figures::default()
        },
    }));
    let mut fig = result.unwrap_or_else(|_| Figures {
        programs: 1,
        disagreements: 1,
        failures: vec![format!("seed {seed}: panic\n---- program\n{text}----")],
        ..Figures::default()
    });
    fig.keywords = used;
    fig
}

/// Every element kind of ldmicro.md §4 the generator must emit.
const COVERAGE: &[&str] = &[
    "CONTACTS",
    "CONTACTS neg",
    "COIL",
    "COIL neg",
    "COIL set",
    "COIL reset",
    "COIL toggle",
    "SHORT",
    "OPEN",
    "MASTER_RELAY",
    "TON",
    "TOF",
    "RTO",
    "RTL",
    "THI",
    "TLO",
    "TCY",
    "OSR",
    "OSF",
    "ODR",
    "ODF",
    "OSL",
    "OSC",
    "CTU",
    "CTD",
    "CTC",
    "CTR",
    "RES",
    "EQU",
    "NEQ",
    "GRT",
    "GEQ",
    "LES",
    "LEQ",
    "MOVE",
    "ADD",
    "SUB",
    "MUL",
    "DIV",
    "MOD",
    "AND",
    "OR",
    "XOR",
    "NOT",
    "SHL",
    "SHR",
    "SR0",
    "ROL",
    "ROR",
    "BIN2BCD",
    "BCD2BIN",
    "OPPOSITE",
    "SWAP",
    "SET_BIT",
    "IF_BIT_SET",
    "SHIFT_REGISTER",
    "READ_ADC",
    "UART_RECV",
    "SET_PWM",
    "UART_SEND",
    "UART_RECV_AVAIL",
    "UART_SEND_READY",
    "UART_SEND_BUSY",
    "UART_UDRE",
    "I2C_WR",
    "I2C_RD",
    "SPI_WR",
    "BUS",
    "7SEGMENTS",
    "PERSIST",
    "FORMATTED_STRING",
    "PLACEHOLDER",
    "COMMENT",
    "LABEL",
    "GOTO",
    "GOSUB",
    "SUBPROG",
    "ENDSUB",
    "RETURN",
    "LOCK",
    "SLEEP",
    "LDmicro0.1",
    "LDmicro0.2",
    "LDmicro",
    "headerless",
    "VAR LIST",
];

#[test]
fn random_programs_agree_with_the_simulator() {
    if let Some(seed) = std::env::var("II_DIFF_SEED").ok().and_then(|v| v.parse().ok()) {
        let (text, _) = random_program(seed);
        eprintln!("{text}");
        let fig = random_case(seed);
        eprintln!("{}", fig.summary());
        assert_eq!(fig.disagreements, 0, "{}", fig.failures.join("\n\n"));
        return;
    }
    let n = programs_to_run();
    let base = base_seed();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()).clamp(1, 8) as u64;
    let total = Mutex::new(Figures::default());
    std::thread::scope(|s| {
        for t in 0..threads {
            let total = &total;
            s.spawn(move || {
                let mut fig = Figures::default();
                let mut i = t;
                while i < n {
                    fig.add(&random_case(base.wrapping_add(i)));
                    i += threads;
                }
                total.lock().expect("figures").add(&fig);
            });
        }
    });
    let fig = total.into_inner().expect("figures");
    eprintln!("differential, random programs (base seed {base}): {}", fig.summary());
    assert_eq!(fig.disagreements, 0, "{}\n\n{}", fig.summary(), fig.failures.join("\n\n"));
    assert_eq!(fig.programs, n);
    if n < 1_000 {
        return; // too few programs for the figures below
    }
    // Not vacuous: most hypotheses checked, timers fire and hold, control flow refused.
    assert!(fig.checked > 3 * n, "{}", fig.summary());
    // Skipped: mostly the bits of counters whose input passes through an unconstrained
    // element (each intermediate value computed from it is as free as it is, and a bit's
    // equation reads more than the evaluator enumerates); at most 2%.
    assert!(
        fig.skipped() * 50 <= fig.checked + fig.skipped(),
        "more than 2% skipped: {}",
        fig.summary()
    );
    assert!(
        fig.timers.ton_on > n && fig.timers.tof_hold > n / 2,
        "timers rarely on: {}",
        fig.summary()
    );
    // A TON/TOF whose count another element reads or writes is an integer accumulator
    // (its bits checked at every scan above), not a timer of the algebra, and so is one
    // sharing its name with a THI, TLO or TCY: about 55% of the algebra's timer
    // hypotheses fire over the default 20,000 programs (8374 of 15350), where 58% did
    // before THI/TLO/TCY were counted (a smaller run may fall under the floor).
    assert!(
        fig.timer_hyps > n / 3 && fig.timer_hyps_fired * 2 >= fig.timer_hyps,
        "timers rarely on: {}",
        fig.summary()
    );
    assert!(fig.refused > 0 && fig.refused < n / 5, "{}", fig.summary());
    let missing: Vec<&&str> = COVERAGE.iter().filter(|k| !fig.keywords.contains(**k)).collect();
    assert!(missing.is_empty(), "never generated: {missing:?}");
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn load(path: &Path) -> Option<(String, LdProgram)> {
    let text = decode_latin1(&std::fs::read(path).ok()?);
    let p = parse(&path.display().to_string(), &text).ok()?;
    Some((text, p))
}

fn check_files(files: &[PathBuf], seeds: &[u64]) -> Figures {
    let mut fig = Figures::default();
    for path in files {
        let Some((text, program)) = load(path) else { continue };
        for &seed in seeds {
            fig.add(&check_program(&path.display().to_string(), &text, &program, seed));
        }
    }
    fig
}

#[test]
fn examples_agree_with_the_simulator() {
    let files = common::files_with(&root().join("examples"), "ld");
    assert!(files.len() >= 5);
    let mut fig = Figures::default();
    for path in &files {
        let f = check_files(std::slice::from_ref(path), &[1, 2, 3, 4, 5, 6, 7, 8]);
        assert!(
            f.timer_hyps == 0 || f.timer_hyps_fired > 0,
            "{}: no timer ever on: {}",
            path.display(),
            f.summary()
        );
        fig.add(&f);
    }
    eprintln!("differential, examples: {}", fig.summary());
    assert_eq!(fig.disagreements, 0, "{}", fig.failures.join("\n\n"));
    assert_eq!(fig.refused, 0);
    assert_eq!(fig.skipped(), 0, "{}", fig.summary());
    assert_eq!(fig.existential, 0, "the examples compile exactly: {}", fig.summary());
    assert!(fig.timers.ton_on > 0 && fig.timers.tof_hold > 0, "{}", fig.summary());
}

#[test]
fn data_cases_and_corpus_agree_with_the_simulator() {
    let mut files = common::files_with(&root().join("tests/data/compile"), "ld");
    files.extend(common::files_with(&root().join("tests/data/ldmicro/corpus"), "ld"));
    let fig = check_files(&files, &[11, 12]);
    eprintln!("differential, data cases and corpus: {}", fig.summary());
    assert_eq!(fig.disagreements, 0, "{}", fig.failures.join("\n\n"));
    // Hypotheses skipped for too many fresh signals: mostly the bits of counters whose
    // input passes through an unconstrained element (each intermediate value computed
    // from it is as free as it is); at most 5%.
    assert!(fig.checked > 20 * fig.skipped().max(1) || fig.skipped() == 0, "{}", fig.summary());
    assert!(fig.programs as usize == 2 * files.len() || fig.programs > 20);
}

/// The cases, as texts: each must be refused (control flow) or agree with the
/// simulator at every scan.
#[test]
fn known_soundness_cases_agree_or_are_refused() {
    let cases = [
        // Timer presets with adjust fields.
        "LDmicro0.2\nCYCLE=10000\nPROGRAM\nRUNG 1\nCONTACTS XA 0\nTON Tdly 1000000 -95\nCOIL YOut 0 0 0\nEND\n",
        "LDmicro0.2\nCYCLE=10000\nPROGRAM\nRUNG 1\nCONTACTS XA 0\nTON Tdly 100000 50\nCOIL YOut 0 0 0\nEND\n",
        "LDmicro0.1\nCYCLE=10000\nPROGRAM\nRUNG\nCONTACTS Xa 0\nTON T1 30000 5\nCOIL Yp 0 0 0\nEND\n",
        "LDmicro0.1\nCYCLE=10000\nPROGRAM\nRUNG\nCONTACTS Xa 0\nTON T1 30000\nTOF T2 20000\nCOIL Yp 0 0 0\nEND\n",
        // Control flow.
        "LDmicro0.2\nCYCLE=10000\nPROGRAM\nRUNG 1\nCONTACTS XSkip 0\nGOTO Lend\nEND\nRUNG 2\nCONTACTS XA 0\nCOIL YOut 0 0 0\nEND\nRUNG 3\nLABEL Lend\nEND\n",
        // A toggle coil read before and after it.
        "LDmicro0.2\nCYCLE=10000\nPROGRAM\nRUNG 1\nCONTACTS Rb 0\nCOIL Ya 0 0 0\nEND\nRUNG 2\nCONTACTS Xin 0\nCOIL Rb 0 0 0 1\nEND\nRUNG 3\nCONTACTS Rb 0\nCOIL Yc 0 0 0\nEND\n",
        // A bit and a timer of the same name.
        "LDmicro0.2\nCYCLE=10000\nPROGRAM\nRUNG 1\nCONTACTS Rb 0\nCOIL Ya 0 0 0\nEND\nRUNG 2\nCONTACTS Xin 0\nCOIL Rb 0 0 0\nEND\nRUNG 3\nCONTACTS Rb 0\nCOIL Yc 0 0 0\nEND\nRUNG 4\nCONTACTS Xin 0\nTON Rb 20000 0\nCOIL Yd 0 0 0\nEND\n",
        // A bit read and never written.
        "LDmicro0.2\nCYCLE=10000\nPROGRAM\nRUNG 1\nCONTACTS Yghost 0\nCOIL Yout 0 0 0\nEND\n",
    ];
    let mut fig = Figures::default();
    for (k, text) in cases.iter().enumerate() {
        let program = parse("case.ld", text).expect("parses");
        for seed in 0..20 {
            fig.add(&check_program(&format!("case {k}"), text, &program, seed));
        }
    }
    eprintln!("differential, known cases: {}", fig.summary());
    assert_eq!(fig.disagreements, 0, "{}", fig.failures.join("\n\n"));
    assert_eq!(fig.refused, 20, "the GOTO program is refused");
    assert!(fig.timers.ton_on > 0 && fig.timers.tof_hold > 0);
}

/// The evaluator itself, on hand-made runs: `d/f` from the (n+1)-th consecutive
/// true scan, `f/d` for n scans after the fall, SR/RS by their recurrences, fresh
/// signals existential through a memory.
#[test]
fn the_evaluator_follows_semantics_md() {
    // d = 25 ms on a 10 ms cycle: n = ceil(2.5) = 3.
    assert_eq!(
        ceil_scans(&ii_prove::term::Delay::from_micros(25_000).expect("d"), 10_000),
        Some(3)
    );
    assert_eq!(
        ceil_scans(&ii_prove::term::Delay::from_micros(30_000).expect("d"), 10_000),
        Some(3)
    );
    let run = |nodes: Vec<Node>, n_free: usize, inputs: &[bool]| -> Vec<Vec<bool>> {
        let n_state = nodes
            .iter()
            .filter(|n| matches!(n, Node::Sr(..) | Node::Rs(..) | Node::Ton(..) | Node::Tof(..)))
            .count();
        let h = Hyp {
            name: "t".into(),
            text: String::new(),
            rel: Rel::Eq,
            lhs: nodes.len() - 1,
            rhs: nodes.len() - 1,
            nodes,
            n_free,
            temporal_free: false,
            states: BTreeSet::new(),
            skip: None,
            checked_scans: 0,
            has_timer: false,
            timer_fired: false,
            defines: None,
        };
        let mut state = vec![0; n_state];
        let mut vals = Vec::new();
        let mut stats = TimerStats::default();
        inputs
            .iter()
            .map(|&x| {
                h.step(&mut state, &[x], 0, &mut vals, &mut stats);
                vals.clone()
            })
            .collect()
    };
    let xs = [true, true, true, true, false, true, false, false, false, false];
    // d/f with n = 3: on at the 4th consecutive true scan, off with the input.
    let out: Vec<bool> =
        run(vec![Node::Known(0), Node::Ton(0, 3, 0)], 0, &xs).iter().map(|v| v[1]).collect();
    assert_eq!(out, [false, false, false, true, false, false, false, false, false, false]);
    // f/d with n = 2: on while f, and for 2 scans after it falls; never before f.
    let ys = [false, true, false, false, false, true, false, false, false, false];
    let out: Vec<bool> =
        run(vec![Node::Known(0), Node::Tof(0, 2, 0)], 0, &ys).iter().map(|v| v[1]).collect();
    assert_eq!(out, [false, true, true, true, false, true, true, true, false, false]);
    // SR(x, ¬x)... SR(s, r) with s = x, r = 0*: stays on once set; RS(x, x) is 0.
    let out: Vec<bool> = run(vec![Node::Known(0), Node::Const(false), Node::Sr(0, 1, 0)], 0, &ys)
        .iter()
        .map(|v| v[2])
        .collect();
    assert_eq!(out, [false, true, true, true, true, true, true, true, true, true]);
    let out: Vec<bool> =
        run(vec![Node::Known(0), Node::Rs(0, 0, 0)], 0, &ys).iter().map(|v| v[1]).collect();
    assert!(out.iter().all(|v| !v));
    // Existential through a memory: Q = SR(F, 0*) with F fresh holds for Q = 0,0,1,1
    // (F = 0,0,1,·) but not for Q = 1,0 (a set memory cannot drop).
    let exists = |q: &[bool]| -> bool {
        let nodes = vec![Node::Known(0), Node::Free(0), Node::Const(false), Node::Sr(1, 2, 0)];
        let mut h = Hyp {
            name: "t".into(),
            text: String::new(),
            rel: Rel::Eq,
            lhs: 0,
            rhs: 3,
            nodes,
            n_free: 1,
            temporal_free: true,
            states: [vec![0]].into_iter().collect(),
            skip: None,
            checked_scans: 0,
            has_timer: false,
            timer_fired: false,
            defines: None,
        };
        let mut vals = Vec::new();
        let mut stats = TimerStats::default();
        q.iter().all(|&v| h.scan(&[v], &mut vals, &mut stats))
    };
    assert!(exists(&[false, false, true, true]));
    assert!(!exists(&[true, false]));
}

// ---------------------------------------------------------------- random properties

/// Every state the scan simulator reaches from power-up under every input sequence
/// (breadth first, at most `limit` states), with the bits at the end of each scan.
fn reachable_scans(
    program: &LdProgram,
    inputs: &[String],
    limit: usize,
) -> Option<Vec<BTreeMap<String, bool>>> {
    let n_elements = program.elements().count();
    let key = |sim: &Simulator| {
        let bits: Vec<(String, bool)> = sim.bits().iter().map(|(n, v)| (n.clone(), *v)).collect();
        let edges: Vec<Option<bool>> = (0..n_elements).map(|k| sim.edge_memory(k)).collect();
        format!("{bits:?}{edges:?}")
    };
    let start = Simulator::new(program);
    let mut seen = BTreeSet::from([key(&start)]);
    let mut queue = std::collections::VecDeque::from([start]);
    let mut ends = Vec::new();
    while let Some(sim) = queue.pop_front() {
        for v in 0..(1u32 << inputs.len()) {
            let values: BTreeMap<String, bool> =
                inputs.iter().enumerate().map(|(i, n)| (n.clone(), v >> i & 1 == 1)).collect();
            let mut next = sim.clone();
            next.step(&values);
            ends.push(next.bits().clone());
            if seen.insert(key(&next)) {
                if seen.len() > limit {
                    return None;
                }
                queue.push_back(next);
            }
        }
    }
    Some(ends)
}

/// Random programs of the generator without timers, counters or other fresh outputs
/// (their reachable scans are enumerable); random properties `a · b = 0*` and `a ⇒ b`
/// over literals of their bits, judged on every reachable scan. A property that fails
/// on one must never be proved; of those that hold, the share proved is reported (the
/// figure of a long run with `II_PROP_PROGRAMS=N` is in the README).
#[test]
fn random_properties_that_hold_are_proved_and_no_false_one_is() {
    use ii_prove::prover::{Budget, Context, Obligation, Outcome, prove};
    use ii_prove::term::{and, constant, name, not};
    let programs: u64 =
        std::env::var("II_PROP_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(30);
    let mut sources = Sources::new();
    let theory = ii_prove::theory::standard(&mut sources).expect("theory");
    let budget = Budget { time: std::time::Duration::from_secs(2), ..Budget::default() };
    let (mut programs_used, mut true_props, mut proved, mut false_props) = (0, 0, 0, 0);
    let mut with_pre = 0;
    let mut unproved: Vec<String> = Vec::new();
    let mut seed = base_seed() ^ 0x5eed;
    while programs_used < programs {
        seed += 1;
        let (text, _) = random_program(seed);
        let Ok(program) = parse("random.ld", &text) else { continue };
        let Ok(compiled) = ii_prove::ladder::compile(&program) else { continue };
        let exact = compiled.timer_info.is_empty()
            && !compiled.signals.values().any(|k| matches!(k, SignalKind::Fresh { .. }));
        let inputs: Vec<String> = compiled
            .signals
            .iter()
            .filter(|(_, k)| matches!(k, SignalKind::Input))
            .map(|(n, _)| n.clone())
            .collect();
        let bits: Vec<String> = compiled
            .signals
            .iter()
            .filter(|(_, k)| {
                matches!(k, SignalKind::Input | SignalKind::Output | SignalKind::Relay)
            })
            .map(|(n, _)| n.clone())
            .filter(|n| !n.contains('\''))
            .collect();
        if !exact || inputs.len() > 4 || bits.len() < 2 || must_refuse(&program) {
            continue;
        }
        let Some(scans) = reachable_scans(&program, &inputs, 2_000) else { continue };
        programs_used += 1;
        let reads_back = compiled.hypotheses.iter().any(|h| ii_prove::term::mentions_pre(&h.rhs));
        with_pre += usize::from(reads_back);
        let cycle = Some(compiled.scan_cycle());
        let ctx = Context::with_scans(theory.axioms(), compiled.axioms(), cycle).expect("context");
        let mut rng = Rng::new(seed);
        for _ in 0..4 {
            let lit = |rng: &mut Rng| (rng.pick(&bits).clone(), rng.chance(50));
            let ((a, pa), (b, pb)) = (lit(&mut rng), lit(&mut rng));
            let value = |s: &BTreeMap<String, bool>, n: &str, p: bool| {
                s.get(n).copied().unwrap_or(false) == p
            };
            let term = |n: &str, p: bool| if p { name(n) } else { not(&name(n)) };
            let exclusive = rng.chance(50);
            let holds = scans.iter().all(|s| {
                let (x, y) = (value(s, &a, pa), value(s, &b, pb));
                if exclusive { !(x && y) } else { !x || y }
            });
            let goal = if exclusive {
                Obligation {
                    lhs: and(&term(&a, pa), &term(&b, pb)),
                    rel: Rel::Eq,
                    rhs: constant(false),
                }
            } else {
                Obligation { lhs: term(&a, pa), rel: Rel::Implies, rhs: term(&b, pb) }
            };
            let outcome = prove(&ctx, &goal, budget);
            let is_proved = matches!(outcome, Outcome::Proved(_));
            if holds {
                true_props += 1;
                proved += usize::from(is_proved);
                if !is_proved && unproved.len() < 10 {
                    unproved.push(format!(
                        "seed {seed}: {} {:?} {}\n{text}",
                        goal.lhs, goal.rel, goal.rhs
                    ));
                }
            } else {
                false_props += 1;
                assert!(
                    !is_proved,
                    "seed {seed}: {} {:?} {} fails on a reachable scan but was proved\n{text}",
                    goal.lhs, goal.rel, goal.rhs
                );
            }
        }
    }
    let share = 100.0 * proved as f64 / true_props.max(1) as f64;
    println!(
        "random properties: {programs_used} programs ({with_pre} reading a previous scan or \
         an edge), {true_props} properties that hold on every reachable scan ({proved} proved, \
         {share:.1}%), {false_props} that do not (none proved)"
    );
    for u in &unproved {
        println!("not proved: {u}");
    }
}

/// The scan model's own simulator, run on the lowering of random programs, computes every
/// bit it knows as LDmicro's simulator (written from the format note) does, at every scan:
/// a check of the lowering, independent of the compiler.
#[test]
fn the_scan_model_runs_as_ldmicro_does() {
    let programs: u64 =
        std::env::var("II_SCAN_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(3_000);
    let (mut run, mut compared, mut unknown) = (0u64, 0u64, 0u64);
    let mut failures = Vec::new();
    for seed in base_seed()..base_seed() + programs {
        let (text, _) = random_program(seed);
        let Ok(program) = parse("random.ld", &text) else { continue };
        let Ok(lowered) = ii_prove::ladder::lower::lower(&program) else { continue };
        run += 1;
        let mut reference = Simulator::new(&program);
        let mut model = ii_prove::program::simulate::Simulator::new(
            &lowered,
            ii_prove::ladder::TimerModel::Plc,
        );
        let driven: Vec<String> =
            program.signals().into_iter().filter(|n| n.starts_with(['X', 'I', 'M'])).collect();
        let mut rng = Rng::new(seed ^ 0x5CA7);
        let scans = (4 * longest_timer(&program) + 40).min(2_000);
        'scans: for scan in 0..scans {
            let inputs: BTreeMap<String, bool> = driven
                .iter()
                .map(|n| (n.clone(), rng.chance(if scan % 7 < 4 { 80 } else { 20 })))
                .collect();
            reference.step(&inputs);
            model.step(&inputs);
            // The integers the scan model computes exactly, as LDmicro counts them.
            for n in lowered.integers.keys() {
                if !model.is_known(n) || !reference.is_known(n) {
                    unknown += 1;
                    continue;
                }
                compared += 1;
                if model.int(n) != Some(reference.int(n)) {
                    failures.push(format!(
                        "seed {seed}: the integer {n} is {:?} in the scan model and {} in LDmicro at scan {scan}\n{text}",
                        model.int(n),
                        reference.int(n)
                    ));
                    break 'scans;
                }
            }
            for (n, v) in &reference.bits() {
                if !model.is_known(n) || !reference.is_known(n) {
                    unknown += 1;
                    continue;
                }
                compared += 1;
                if model.bit(n) != *v {
                    failures.push(format!(
                        "seed {seed}: {n} is {} in the scan model and {} in LDmicro at scan {scan}\n{text}",
                        u8::from(model.bit(n)),
                        u8::from(*v)
                    ));
                    break 'scans;
                }
            }
        }
    }
    eprintln!(
        "scan model vs LDmicro: {run} programs, {compared} bit-scans compared, {unknown} unknown to the scan model; {} disagreements",
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{}",
        failures.iter().take(3).cloned().collect::<Vec<_>>().join("\n")
    );
}
