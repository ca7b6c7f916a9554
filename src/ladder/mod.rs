//! Ladder front ends: LDmicro `.ld` files read into an AST ([`ldmicro`]), lowered into the scan model ([`lower`]) and run by a reference scan-cycle simulator ([`simulate`]); PLCopen XML read, checked and lowered into the scan model ([`plcopen`]). [`compile()`] lowers and compiles an LDmicro program.
//!
//! The reader never panics; every problem it finds is a [`LadderError`] with a
//! [`Span`] into the source text, rendered by [`crate::diag::render`].

pub mod ldmicro;
pub mod lower;
pub mod plcopen;
pub mod simulate;
mod slice;

pub use crate::program::simulate::{Reference, ScanSimulator};
pub use crate::program::{
    CompileOptions, CompileWarning, CompiledProgram, Hypothesis, HypothesisKind, SignalKind,
    TimerInfo, TimerModel, program_to_ii, short_name,
};
pub use ldmicro::{
    Circuit, CoilKind, CompareOp, CounterEdge, CounterKind, EdgeKind, Element, ElementKind,
    HeaderVersion, IoEntry, LdProgram, MathOp, Operand, Rung, TimerDelay, TimerKind, decode_latin1,
    read_ldmicro,
};
pub use simulate::{Simulator, run};
pub use slice::SliceIndex;

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

use crate::program::simulate::Recording;

use crate::diag::{Report, Severity, Span};
use crate::program::IntType;

/// Lowers and compiles an LDmicro program with the default options (PLC timer counts).
pub fn compile(program: &LdProgram) -> Result<CompiledProgram, Vec<LadderError>> {
    compile_with(program, &CompileOptions::default())
}

/// Lowers an LDmicro program into the scan model and compiles it. Never panics. An
/// element whose effect the equations cannot describe soundly (control flow) refuses
/// the program with a located error; everything else not expressed exactly is a sound
/// over-approximation and a warning.
pub fn compile_with(
    program: &LdProgram,
    options: &CompileOptions,
) -> Result<CompiledProgram, Vec<LadderError>> {
    let lowered = lower::lower(program)?;
    crate::program::compile(&lowered, options)
        .map_err(|errors| errors.into_iter().map(LadderError::from).collect())
}

/// A peripheral read of an LDmicro program (`READ_ADC var`, `UART_RECV var`, the
/// UART's status contacts `UART_RECV_AVAIL`, `UART_SEND_READY`, `I2C_RD`'s byte and
/// `PERSIST var`'s load from EEPROM): the free integer inputs the outside world gives it
/// at each scan
/// (ldmicro.md §4, "peripheral reads").
/// Both the lowering and the simulator take their values from these names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Reading {
    /// The variable the element writes; none for a status contact.
    pub var: Option<String>,
    /// The value read: the ADC's reading, the received byte(s), or the status flag.
    pub value: String,
    /// The values the hardware gives: the ADC's resolution (unsigned), one byte
    /// (unsigned), the variable's 16 bits for a read of several bytes, or one bit.
    pub ty: IntType,
    /// The 1-bit unsigned input that lets the write happen: for `UART_RECV` and
    /// `I2C_RD` (no target, or an ARM one), 1 when a byte arrived; for `PERSIST`, 1 when
    /// the EEPROM is ready.
    pub arrived: Option<String>,
    /// Whether the element's output is its input and-ed with `arrived` (`UART_RECV`);
    /// else it passes its input.
    pub gated: bool,
    /// What is written when `arrived` is 0 (an ARM target's `I2C_RD`: -1, no data);
    /// None: nothing is written then.
    pub fallback: Option<i64>,
    /// For `PERSIST`, the hidden 1-bit integer that becomes 1 once the variable is loaded
    /// from EEPROM (its one-shot `isInit`, 0 at power-up).
    pub once: Option<String>,
}

impl Reading {
    /// The names the read adds to the program: its value, its arrival or ready flag,
    /// and `PERSIST`'s hidden one-shot.
    pub fn names(&self) -> impl Iterator<Item = &String> {
        std::iter::once(&self.value).chain(&self.arrived).chain(&self.once)
    }

    /// The 1-bit input the element's output is its input and-ed with: the arrival of
    /// `UART_RECV`, a status contact's flag; none for `READ_ADC`, `I2C_RD` and
    /// `PERSIST`, which pass their input.
    pub fn gate(&self) -> Option<&str> {
        match &self.var {
            None => Some(&self.value),
            Some(_) if self.gated => self.arrived.as_deref(),
            Some(_) => None,
        }
    }

    /// The 1-bit input that, with the element's input, makes the write happen (the
    /// arrival of `UART_RECV` and of a byte of `I2C_RD` with no target; `PERSIST`'s
    /// ready flag, whose one-shot also takes part); none when the input alone does.
    pub fn write_gate(&self) -> Option<&str> {
        if self.fallback.is_some() { None } else { self.arrived.as_deref() }
    }
}

/// Every name of `program`: its bits and the names its elements read and write.
fn program_names(program: &LdProgram) -> BTreeSet<String> {
    let mut taken: BTreeSet<String> = program.signals().into_iter().collect();
    for e in program.elements() {
        taken.extend(e.names_read().into_iter().map(str::to_string));
        taken.extend(e.names_written());
    }
    taken
}

/// The state bits of THI, TLO and TCY (`intcode.cpp`'s `$once_…` bits), by element
/// index (`program.elements()` order) and bit — 0: THI's and TLO's pulse bit, TCY's
/// phase; 1: TLO's "has been high" — hidden 1-bit integers, 0 at power-up, named
/// `THI_name_rN_on`, `TLO_name_rN_on`, `TLO_name_rN_high`, `TCY_name_rN_phase`; a
/// suffix `_2`, … keeps them apart from the program's names and the reads' ones.
pub fn timer_bits(program: &LdProgram) -> std::collections::BTreeMap<(usize, u8), String> {
    // The names taken, gathered at the first timer that needs a bit (most programs have none).
    let mut taken = None;
    let mut out = std::collections::BTreeMap::new();
    let mut index = 0;
    for rung in &program.rungs {
        for e in rung.elements() {
            if let ElementKind::Timer { kind, name, .. } = &e.kind {
                let bits: &[&str] = match kind {
                    TimerKind::Thi => &["on"],
                    TimerKind::Tlo => &["on", "high"],
                    TimerKind::Tcy => &["phase"],
                    _ => &[],
                };
                for (k, what) in bits.iter().enumerate() {
                    let taken = taken.get_or_insert_with(|| {
                        let mut taken = program_names(program);
                        taken.extend(readings(program).values().flat_map(|r| r.names().cloned()));
                        taken
                    });
                    let base = format!("{}_{name}_r{}_{what}", e.kind.keyword(), rung.number);
                    let mut bit = base.clone();
                    let mut n = 1;
                    while taken.contains(&bit) {
                        n += 1;
                        bit = format!("{base}_{n}");
                    }
                    taken.insert(bit.clone());
                    out.insert((index, k as u8), bit);
                }
            }
            index += 1;
        }
    }
    out
}

/// The UART's status contacts and their aliases (`loadsave.cpp`): `o = i · flag`, the
/// flag read from the hardware (`intcode.cpp`, `ELEM_UART_RECV_AVAIL`,
/// `ELEM_UART_SEND_READY`).
pub const STATUS_CONTACTS: &[&str] =
    &["UART_RECV_AVAIL", "UART_SEND_READY", "UART_SEND_BUSY", "UART_UDRE"];

/// The resolution in bits of the ADC of LDmicro's target `micro` (`MICRO=`), from
/// `adcMax` in LDmicro's `mcutable.h`: 8 bits (ATtiny10, PIC16F72), 12 bits (the STM32
/// targets), 10 bits for every other target with an ADC, and for a file with no target,
/// as LDmicro's simulator reads it (`maxVal = 1023` in `iolist.cpp`). Err: why the
/// readings of that target are not known (no ADC, or a target ii-prove does not know).
pub fn adc_bits(micro: Option<&str>) -> Result<u32, String> {
    let Some(micro) = micro.map(str::trim) else { return Ok(10) };
    let known = |names: &[&str]| names.iter().any(|n| micro.starts_with(n));
    if known(&["Atmel AVR ATtiny10", "Microchip PIC16F72 "]) {
        Ok(8)
    } else if known(&["St ARM STM32"]) {
        Ok(12)
    } else if known(&["Atmel AVR ATmega162", "Microchip PIC16F628", "Microchip PIC10F", "PC LPT"]) {
        Err(format!("the target {micro} has no ADC"))
    } else if known(&["Atmel AVR ", "Microchip PIC", "ESP8266", "Controllino"]) {
        Ok(10)
    } else {
        Err(format!("the ADC range of the target {micro} is not known"))
    }
}

/// What `I2C_RD` writes on LDmicro's target `micro`: the type of the byte read, whether
/// a free 1-bit input tells that it arrived, and what is written when it did not. The C
/// code `ansic.cpp` generates (`INT_I2C_READ`; `avr.cpp` and `pic16.cpp` have no I2C)
/// writes `recv = I2C_Recv(addr, reg)` on AVR, PIC and ARM targets, and
/// `recv = I2C_RECV(name, addr, reg)`, a function the user supplies, on the others:
///
/// * AVR (avr-gcc): `I2C_MasterGetReg` of `LIBRARIES_FOR/Avr/I2CLib.c` returns a
///   `char`, signed in avr-gcc: -128 to 127;
/// * PIC16/PIC18 (HI-TECH C): the same function of `LIBRARIES_FOR/Pic16`, `PIC18`
///   returns a `char`, unsigned in HI-TECH C: 0 to 255;
/// * ARM: `LibI2C_GetReg` of `LIBRARIES_FOR/Arm/*/Lib_i2c.c` returns the `uint8_t` read,
///   or -1 when no byte came (`LibI2C_ReadLast`): a byte and an arrival flag, -1 without;
/// * ESP8266, Controllino, PC: any value the destination can receive (32 bits, cut to it);
/// * no target: LDmicro's simulator (`simulate.cpp`, `INT_I2C_READ`) writes a typed
///   byte, 0 to 255, only when one is queued: a byte and an arrival flag.
pub fn i2c_read(micro: Option<&str>) -> (IntType, bool, Option<i64>) {
    let byte = IntType::int(8, false);
    match micro.map(str::trim) {
        None => (byte, true, None),
        Some(m) if m.starts_with("Atmel AVR") => (IntType::int(8, true), false, None),
        Some(m) if m.starts_with("Microchip PIC") => (byte, false, None),
        Some(m) if m.starts_with("St ARM") => (byte, true, Some(-1)),
        Some(_) => (IntType::int(32, true), false, None),
    }
}

/// The peripheral reads of `program` whose values are known, by element index
/// (`program.elements()` order). The value of the read in rung `n` of `KEYWORD var` is
/// named `KEYWORD_var_rn`, and its arrival flag `KEYWORD_var_rn_got`; a suffix `_2`,
/// `_3`, … keeps them apart from each other and from the program's names. A `READ_ADC`
/// of a target whose ADC range is not known ([`adc_bits`]) is not among them.
pub fn readings(program: &LdProgram) -> std::collections::BTreeMap<usize, Reading> {
    // The names taken, gathered at the first read (most programs have none).
    let mut taken = None;
    let mut fresh = |base: String| {
        let taken = taken.get_or_insert_with(|| program_names(program));
        let mut name = base.clone();
        let mut k = 1;
        while ["", "_got", "_ready", "_loaded"]
            .iter()
            .any(|suffix| taken.contains(&format!("{name}{suffix}")))
        {
            k += 1;
            name = format!("{base}_{k}");
        }
        taken.insert(name.clone());
        name
    };
    let adc = adc_bits(program.micro.as_deref());
    let i2c = i2c_read(program.micro.as_deref());
    let mut out = std::collections::BTreeMap::new();
    let mut index = 0;
    for rung in &program.rungs {
        for e in rung.elements() {
            if let ElementKind::Other { keyword, .. } = &e.kind
                && STATUS_CONTACTS.contains(&keyword.as_str())
            {
                let value = fresh(format!("{keyword}_r{}", rung.number));
                let ty = IntType::BIT;
                let (arrived, once, fallback) = (None, None, None);
                let r = Reading { var: None, value, ty, arrived, gated: true, fallback, once };
                out.insert(index, r);
            } else if let ElementKind::Other { keyword, args } = &e.kind
                && let [var] = e.names_written().as_slice()
            {
                let ty = match keyword.as_str() {
                    "READ_ADC" => adc.as_ref().ok().map(|&bits| IntType::int(bits, false)),
                    // `UART_RECV var [bytes wait]`: one byte unless more are asked for.
                    "UART_RECV" => Some(match args.get(1).and_then(|b| b.parse::<u32>().ok()) {
                        Some(n) if n > 1 => IntType::I16,
                        _ => IntType::int(8, false),
                    }),
                    // What EEPROM holds: any 16-bit value.
                    "PERSIST" => Some(IntType::I16),
                    "I2C_RD" => Some(i2c.0),
                    _ => None,
                };
                if let Some(ty) = ty {
                    let value = fresh(format!("{keyword}_{var}_r{}", rung.number));
                    let arrived = match keyword.as_str() {
                        "UART_RECV" => Some(format!("{value}_got")),
                        "PERSIST" => Some(format!("{value}_ready")),
                        "I2C_RD" if i2c.1 => Some(format!("{value}_got")),
                        _ => None,
                    };
                    let once = (keyword == "PERSIST").then(|| format!("{value}_loaded"));
                    let var = Some(var.clone());
                    let gated = keyword == "UART_RECV";
                    let fallback = i2c.2.filter(|_| keyword == "I2C_RD");
                    out.insert(index, Reading { var, value, ty, arrived, gated, fallback, once });
                }
            }
            index += 1;
        }
    }
    out
}

impl From<crate::program::CompileError> for LadderError {
    fn from(e: crate::program::CompileError) -> LadderError {
        LadderError::Unsupported { span: e.span, keyword: e.keyword, reason: e.reason }
    }
}

impl crate::program::simulate::Reference for LdProgram {
    fn simulator(&self) -> Box<dyn ScanSimulator> {
        Box::new(Simulator::new(self))
    }

    fn simulator_for(&self, names: &BTreeSet<String>) -> Box<dyn ScanSimulator> {
        match self.slice(names) {
            Some(part) => Box::new(Simulator::new(&part)),
            None => Box::new(Simulator::new(self)),
        }
    }

    fn record(
        &self,
        names: &BTreeSet<String>,
        inputs: &[BTreeMap<String, bool>],
    ) -> Option<Recording> {
        Some(Arc::new(LdProgram::record(self, names, inputs)?))
    }

    fn simulator_near(
        &self,
        names: &BTreeSet<String>,
        base: &Recording,
        changed: &BTreeSet<String>,
        scans: usize,
    ) -> Option<Box<dyn ScanSimulator>> {
        let record = base.clone().downcast::<simulate::RunRecord>().ok()?;
        Some(Box::new(self.slice_near(names, &record, changed, scans)?))
    }
}

impl crate::program::simulate::Reference for plcopen::PlcReference {
    fn simulator(&self) -> Box<dyn ScanSimulator> {
        Box::new(plcopen::PlcSimulator::new(&self.program).showing(self.edges.clone()))
    }
}

impl ScanSimulator for Simulator {
    fn step(&mut self, inputs: &std::collections::BTreeMap<String, bool>) {
        Simulator::step(self, inputs)
    }
    fn bit(&self, name: &str) -> bool {
        Simulator::bit(self, name)
    }
    fn is_known(&self, name: &str) -> bool {
        Simulator::is_known(self, name)
    }
    fn reads(&self, input: &str) -> bool {
        Simulator::reads(self, input)
    }
    fn read_names(&self) -> Option<Vec<&str>> {
        Some(Simulator::read_names(self))
    }
    fn edge_memory(&self, index: usize) -> Option<bool> {
        Simulator::edge_memory(self, index)
    }
    fn int(&self, name: &str) -> Option<i64> {
        Some(Simulator::int(self, name))
    }
    fn start_from(&mut self, state: &crate::program::any_state::StartState) -> bool {
        Simulator::start_from(self, state)
    }
}

impl ScanSimulator for plcopen::PlcSimulator {
    fn step(&mut self, inputs: &std::collections::BTreeMap<String, bool>) {
        plcopen::PlcSimulator::step(self, inputs)
    }
    fn bit(&self, name: &str) -> bool {
        plcopen::PlcSimulator::bit(self, name)
    }
    fn is_known(&self, name: &str) -> bool {
        plcopen::PlcSimulator::is_known(self, name)
    }
    fn int(&self, name: &str) -> Option<i64> {
        plcopen::PlcSimulator::int(self, name)
    }
    fn edge_memory(&self, index: usize) -> Option<bool> {
        plcopen::PlcSimulator::edge_memory(self, index)
    }
}

/// A malformed ladder file, or something the reader or compiler reports about it.
///
/// Variants with [`Severity::Warning`] (see [`Report::severity`]) do not stop
/// loading; they are collected in [`LdProgram::warnings`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LadderError {
    /// An element keyword the reader does not know.
    UnknownKeyword {
        /// The keyword token.
        span: Span,
        /// The keyword as written.
        keyword: String,
        /// The nearest known keyword, if one is close.
        suggestion: Option<String>,
    },
    /// An element line with too few arguments.
    Arity {
        /// The whole line.
        span: Span,
        /// The element keyword.
        keyword: String,
        /// The minimum number of arguments.
        min: usize,
        /// How many were given.
        found: usize,
        /// The expected shape, e.g. `CONTACTS name neg [set1]`.
        usage: String,
    },
    /// An argument that does not have the expected form (e.g. a delay that is not an integer).
    BadArgument {
        /// The argument token.
        span: Span,
        /// The element keyword.
        keyword: String,
        /// The argument as written.
        found: String,
        /// What was expected there.
        expected: String,
    },
    /// A line that is not allowed where it stands (PARALLEL directly in PARALLEL,
    /// a stray `END`, a non-`RUNG` line between rungs, …).
    Unexpected {
        /// The offending line or token.
        span: Span,
        /// What was found.
        found: String,
        /// What was expected there.
        expected: String,
    },
    /// The file ends inside a block.
    Truncated {
        /// The end of the file.
        span: Span,
        /// The block that is still open (`RUNG`, `PARALLEL`, `IO LIST`, …).
        open: String,
        /// Where that block was opened.
        opened_at: Span,
    },
    /// No `PROGRAM` line: not an LDmicro program.
    MissingProgram {
        /// The end of the file.
        span: Span,
        /// Whether an `LDmicro…` header line was seen.
        saw_header: bool,
    },
    /// `SERIES`/`PARALLEL` nested deeper than the reader allows.
    TooDeep {
        /// The line that opens one level too many.
        span: Span,
        /// The limit.
        limit: usize,
    },
    /// Warning: a line before `PROGRAM` that the reader does not understand and skips.
    IgnoredLine {
        /// The line.
        span: Span,
        /// Why it is ignored.
        reason: String,
    },
    /// Warning: a `PLACEHOLDER` (an empty editor slot; LDmicro refuses to compile it).
    Placeholder {
        /// The element line.
        span: Span,
    },
    /// An element the compiler cannot model soundly yet: the program is refused.
    Unsupported {
        /// The element line.
        span: Span,
        /// The element keyword.
        keyword: String,
        /// What the element does that the model cannot express.
        reason: String,
    },
}

impl Report for LadderError {
    fn span(&self) -> Option<Span> {
        Some(match self {
            LadderError::UnknownKeyword { span, .. }
            | LadderError::Arity { span, .. }
            | LadderError::BadArgument { span, .. }
            | LadderError::Unexpected { span, .. }
            | LadderError::Truncated { span, .. }
            | LadderError::MissingProgram { span, .. }
            | LadderError::TooDeep { span, .. }
            | LadderError::IgnoredLine { span, .. }
            | LadderError::Placeholder { span }
            | LadderError::Unsupported { span, .. } => *span,
        })
    }

    fn message(&self) -> String {
        match self {
            LadderError::UnknownKeyword { keyword, .. } => {
                format!("unknown LDmicro element `{keyword}`")
            }
            LadderError::Arity { keyword, min, found, .. } => format!(
                "`{keyword}` needs at least {min} argument{}, found {found}",
                if *min == 1 { "" } else { "s" }
            ),
            LadderError::BadArgument { keyword, found, expected, .. } => {
                format!("bad argument `{found}` to `{keyword}`: expected {expected}")
            }
            LadderError::Unexpected { found, expected, .. } => {
                format!("unexpected `{found}`: expected {expected}")
            }
            LadderError::Truncated { open, .. } => {
                format!("file ends inside `{open}`: expected `END`")
            }
            LadderError::MissingProgram { saw_header, .. } => {
                if *saw_header {
                    "no `PROGRAM` line: expected `PROGRAM` followed by rungs".into()
                } else {
                    "not an LDmicro file: no `LDmicro` header and no `PROGRAM` line".into()
                }
            }
            LadderError::TooDeep { limit, .. } => {
                format!("SERIES/PARALLEL nested more than {limit} levels deep")
            }
            LadderError::IgnoredLine { reason, .. } => format!("line ignored: {reason}"),
            LadderError::Placeholder { .. } => {
                "PLACEHOLDER: an empty editor slot; LDmicro refuses to compile it (treated as OPEN)"
                    .into()
            }
            LadderError::Unsupported { keyword, reason, .. } => {
                format!("`{keyword}` is not supported: {reason}")
            }
        }
    }

    fn label(&self) -> String {
        match self {
            LadderError::UnknownKeyword { .. } => "expected an element keyword".into(),
            LadderError::Arity { usage, .. } => format!("expected `{usage}`"),
            LadderError::BadArgument { expected, .. } => format!("expected {expected}"),
            LadderError::Unexpected { expected, .. } => format!("expected {expected}"),
            LadderError::Truncated { .. } => "expected `END` before the end of the file".into(),
            LadderError::MissingProgram { .. } => "expected `PROGRAM`".into(),
            LadderError::TooDeep { .. } => "too deep".into(),
            LadderError::IgnoredLine { .. } => "ignored".into(),
            LadderError::Placeholder { .. } => "empty slot".into(),
            LadderError::Unsupported { .. } => "the program is refused here".into(),
        }
    }

    fn related(&self) -> Vec<(Span, String)> {
        match self {
            LadderError::Truncated { open, opened_at, .. } => {
                vec![(*opened_at, format!("`{open}` opened here"))]
            }
            _ => Vec::new(),
        }
    }

    fn notes(&self) -> Vec<String> {
        match self {
            LadderError::UnknownKeyword { suggestion: Some(s), .. } => {
                vec![format!("did you mean `{s}`?")]
            }
            _ => Vec::new(),
        }
    }

    fn severity(&self) -> Severity {
        match self {
            LadderError::IgnoredLine { .. } | LadderError::Placeholder { .. } => Severity::Warning,
            _ => Severity::Error,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::adc_bits;

    #[test]
    fn the_adc_range_follows_ldmicros_table_of_targets() {
        assert_eq!(adc_bits(None), Ok(10));
        assert_eq!(adc_bits(Some("Atmel AVR ATmega328 28-PDIP")), Ok(10));
        assert_eq!(adc_bits(Some("Microchip PIC16F877 40-PDIP")), Ok(10));
        assert_eq!(adc_bits(Some("Microchip PIC12F675 8-pin packages")), Ok(10));
        assert_eq!(adc_bits(Some("Atmel AVR ATtiny10 6-Pin packages")), Ok(8));
        assert_eq!(adc_bits(Some("Microchip PIC16F72 28-Pin PDIP, SOIC, SSOP")), Ok(8));
        assert_eq!(adc_bits(Some("St ARM STM32F40X 144-LQFP")), Ok(12));
        let none = adc_bits(Some("Atmel AVR ATmega162 40-PDIP")).unwrap_err();
        assert!(none.contains("has no ADC"), "{none}");
        let unknown = adc_bits(Some("ANSI C Code")).unwrap_err();
        assert!(unknown.contains("not known"), "{unknown}");
    }
}
