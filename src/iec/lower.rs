//! Lowering of a Structured Text program into the scan model: declarations to bits and integers, function-block instances and initial values; statements to blocks (one per top-level statement, named after its line); `//#ASSERT` comments to properties checked where they are written.
//!
//! A BOOL variable is a bit; `VAR_INPUT` variables and those located at `%I` are the
//! inputs. An initial value `TRUE` is set on the first scan, before any statement reads
//! it (a hidden `_STARTED` bit, as for PLCopen). Integers (`ints`) are integers of the
//! scan model computed as matiec's C computes them; one that cannot be computed exactly
//! is opaque, and the program is lowered again without it. Function-block instances
//! write hidden bits `T1_Q`, `R1_Q`, `SR1_Q1` and counts `C1_CV` (`calls`): TON/TOF/TP
//! as timers counted as matiec counts them ([`Preset::iec`]), R_TRIG/F_TRIG as one-shots
//! (`Q := CLK ∧ ¬M; M := CLK`), SR/RS as set and reset in the order their definitions
//! give, CTU/CTD/CTUD as matiec's library counts. Loops are unrolled where their counts
//! are known before the scan (`flow`, `known`), and `EXIT`, `CONTINUE` and `RETURN` guard
//! what follows them with hidden bits; a loop whose count is not known then, and an FB
//! input assigned outside its call, are refused with a located error.

mod calls;
mod durations;
mod effects;
mod elapsed;
mod enable;
mod expr;
mod flow;
mod il;
mod int_functions;
mod ints;
mod known;
mod reals;
mod runs;
mod user;

use calls::Fb;
use runs::pick;

use std::collections::{BTreeMap, BTreeSet};

use super::StError;
use super::ast::{self, ExprKind, Ident, PouKind, StmtKind, VarClass};
use crate::diag::{Sources, Span};
use crate::program::{Block, BoolExpr, Inputs, IntVar, Program, Stmt, WriteKind};

/// The cycle used when neither the task nor the command line gives one.
pub const DEFAULT_CYCLE_US: u64 = 20_000;

/// A lowered program: the scan model, its properties and the notes of lowering.
pub struct Lowered {
    /// The program.
    pub program: Program,
    /// The `//#ASSERT` comments, in scan order.
    pub asserts: Vec<Assertion>,
    /// Warnings (cycle taken by default, elements not modelled exactly), located.
    pub warnings: Vec<StError>,
    /// The program's TIME inputs no statement writes (a timer whose `PT` is one is
    /// unconstrained here, [`Preset::Variable`](crate::program::Preset) named after it).
    pub time_inputs: BTreeSet<String>,
    /// The input bit the body runs under ([`lower_under_en`]).
    pub enable: Option<String>,
}

/// A property written in the program: the bit that holds its truth at that point of the
/// scan.
#[derive(Clone, Debug)]
pub struct Assertion {
    /// Its name (`: name` in the comment, else `ASSERT_L12`, line 12).
    pub name: String,
    /// The hidden bit written where the comment is (`assert_NAME`).
    pub signal: String,
    /// The asserted expression.
    pub span: Span,
}

#[derive(Clone, Debug)]
enum Ty {
    Bool,
    Fb(Fb, String),
    /// An integer of a type the scan model computes.
    Int(crate::program::IntType),
    /// An instance of a function block the file declares (its type, upper-case).
    User(String),
    Other(String),
}

impl Ty {
    /// The type's name, for a variable holding a value that is not a BOOL.
    fn value_type(&self) -> Option<String> {
        match self {
            Ty::Other(t) => Some(t.clone()),
            Ty::Int(t) => Some(ints::type_name(*t).to_string()),
            _ => None,
        }
    }
}

#[derive(Clone, Debug)]
struct Sym {
    name: String,
    ty: Ty,
    span: Span,
}

/// Lowers the program `pou` (else the configuration's one program instance, else the file's
/// one `PROGRAM`) of `unit`, scanned every `cycle_us` (else its task's interval).
pub fn lower(
    sources: &Sources,
    unit: &ast::Unit,
    pou: Option<&str>,
    cycle_us: Option<u64>,
) -> Result<Lowered, Vec<StError>> {
    lower_wanting(sources, unit, pou, cycle_us, &BTreeSet::new())
}

/// [`lower`], computing also the elapsed time `ET` of the timer instances `wanted`
/// names (lowered names, upper case) as if a statement read it: a property may name it
/// (`[T1.ET < T#2s]`) though the program does not. A name that is no timer instance
/// changes nothing.
pub fn lower_wanting(
    sources: &Sources,
    unit: &ast::Unit,
    pou: Option<&str>,
    cycle_us: Option<u64>,
    wanted: &BTreeSet<String>,
) -> Result<Lowered, Vec<StError>> {
    lower_inner(sources, unit, pou, cycle_us, wanted, false)
}

/// [`lower`] for a function block's body called under a wired `EN`: every block of the
/// body runs only while the input bit [`Lowered::enable`] is TRUE (matiec's `if (!EN)
/// return;`), as statements under a condition (timers followed call by call).
pub fn lower_under_en(
    sources: &Sources,
    unit: &ast::Unit,
    pou: Option<&str>,
    cycle_us: Option<u64>,
) -> Result<Lowered, Vec<StError>> {
    lower_inner(sources, unit, pou, cycle_us, &BTreeSet::new(), true)
}

fn lower_inner(
    sources: &Sources,
    unit: &ast::Unit,
    pou: Option<&str>,
    cycle_us: Option<u64>,
    wanted: &BTreeSet<String>,
    under_en: bool,
) -> Result<Lowered, Vec<StError>> {
    let runs = pick(unit, pou)?;
    let first = &runs[0];
    let mut warnings = Vec::new();
    // One cycle for all: several tasks must share their interval.
    let intervals: BTreeSet<u64> =
        runs.iter().filter_map(|r| r.task.and_then(|t| t.interval)).collect();
    if intervals.len() > 1 {
        let t = runs
            .iter()
            .filter_map(|r| r.task)
            .find(|t| t.interval != first.task.and_then(|f| f.interval))
            .unwrap_or_else(|| runs.iter().find_map(|r| r.task).expect("a task"));
        let shown: Vec<String> =
            intervals.iter().map(|us| format!("{} ms", *us as f64 / 1000.0)).collect();
        return Err(vec![StError::new(
            t.name.span,
            format!(
                "the configuration's tasks run at different intervals ({}): running each at its own rate is not modelled yet; choose one program with --pou",
                shown.join(", ")
            ),
            "a task with another interval",
        )]);
    }
    let cycle_us = match (cycle_us, intervals.first()) {
        (Some(c), _) | (None, Some(&c)) => c,
        (None, None) => {
            warnings.push(StError::warning(
                first.pou.name.span,
                format!(
                    "no task with an interval runs `{}`: the scan cycle is taken to be {} ms (give --cycle to choose it)",
                    first.pou.name.name,
                    DEFAULT_CYCLE_US / 1000
                ),
            ));
            DEFAULT_CYCLE_US
        }
    };
    if cycle_us == 0 {
        let span = first.task.map_or(first.pou.name.span, |t| t.name.span);
        return Err(vec![StError::new(
            span,
            "a scan cycle of 0",
            "expected a positive interval (or give --cycle)",
        )]);
    }
    // A chart is lowered as the Structured Text matiec runs for it.
    if let Some(charts) = super::sfc::desugar(unit, cycle_us)? {
        let mut lowered = lower_inner(sources, &charts, pou, Some(cycle_us), wanted, under_en)?;
        lowered.warnings.splice(0..0, warnings);
        return Ok(lowered);
    }
    let globals: Vec<&ast::VarDecl> = unit.configs.iter().flat_map(|c| &c.globals).collect();
    // A local name declared by more than one program instance is prefixed with the
    // instance's name (`Main_Pump`); every other name is used as declared.
    let mut count: BTreeMap<String, usize> = BTreeMap::new();
    for r in &runs {
        for v in r.pou.vars.iter().filter(|v| v.class != VarClass::External) {
            *count.entry(v.name.key()).or_default() += 1;
        }
    }
    // An integer found opaque while lowering changes what reads it: lowered again
    // until no new one appears (each round adds one at least).
    let (mut opaque, mut omitted, mut multi) = (BTreeMap::new(), BTreeSet::new(), BTreeSet::new());
    let mut enabled = BTreeSet::new();
    let mut elapsed: BTreeMap<String, elapsed::Wanted> =
        wanted.iter().map(|w| (w.to_ascii_uppercase(), elapsed::Wanted::default())).collect();
    let time_facts = durations::time_facts(sources, unit);
    loop {
        let mut l = Lowering::new(sources, cycle_us, warnings.clone());
        l.time_facts = time_facts.clone();
        l.opaque = opaque.clone();
        l.omitted = omitted.clone();
        l.multi = multi.clone();
        l.enabled = enabled.clone();
        l.elapsed = elapsed.clone();
        l.user = unit
            .pous
            .iter()
            .filter(|p| p.kind != PouKind::Program)
            .map(|p| (p.name.key(), p.clone()))
            .collect();
        let mut tables = Vec::new();
        for r in &runs {
            l.syms = BTreeMap::new();
            let prefix = r.instance.map(|i| i.name.name.clone());
            let rename = |name: &str| match &prefix {
                Some(p) if count.get(&name.to_ascii_uppercase()).is_some_and(|n| *n > 1) => {
                    format!("{p}_{name}")
                }
                _ => name.to_string(),
            };
            l.declare(r.pou, &globals, &rename);
            tables.push(std::mem::take(&mut l.syms));
        }
        if under_en {
            let en = l.unique("EN");
            l.inputs.insert(en.clone());
            l.enable = Some(en);
        }
        for (r, table) in runs.iter().zip(tables) {
            l.syms = table;
            l.program_run(r.pou);
        }
        if !l.errors.is_empty() {
            return Err(l.errors);
        }
        l.elapsed_after_lowering();
        let called: BTreeSet<String> = l
            .called
            .iter()
            .filter(|(_, n)| **n > 1)
            .map(|(inst, _)| inst.to_ascii_uppercase())
            .collect();
        if l.opaque.len() > opaque.len()
            || l.omitted.len() > omitted.len()
            || called.len() > multi.len()
            || l.elapsed != elapsed
            || l.enabled.len() > enabled.len()
        {
            (opaque, omitted, multi, elapsed) = (l.opaque, l.omitted, called, l.elapsed);
            enabled = l.enabled;
            continue;
        }
        l.warn_opaque();
        return Ok(l.finish());
    }
}

struct Lowering<'s> {
    sources: &'s Sources,
    cycle_us: u64,
    syms: BTreeMap<String, Sym>,
    inputs: BTreeSet<String>,
    /// BOOL globals (not located at `%Q`): inputs unless a statement writes them.
    globals: BTreeSet<String>,
    /// BOOL variables with the initial value TRUE.
    starts: Vec<String>,
    /// The bit the start-up block keys on (1 from the first scan on).
    started: Option<String>,
    /// Hidden bits of FB instances: (instance key, pin) → name.
    hidden: BTreeMap<(String, String), String>,
    taken: BTreeSet<String>,
    /// The suffix [`Lowering::unique`] tries next, per base name.
    suffixes: crate::program::unique::Suffixes,
    blocks: Vec<Block>,
    labels: BTreeSet<String>,
    next_temp: usize,
    edges: usize,
    asserts: Vec<Assertion>,
    warnings: Vec<StError>,
    errors: Vec<StError>,
    /// The current block's line.
    line: usize,
    /// Whether a body is Instruction List.
    il: bool,
    /// `CONSTANT` TIME variables with a literal initial value and TIME variables
    /// constant in fact (by their names in the scan model): their µs.
    durations: BTreeMap<String, u64>,
    /// Every TIME variable of the file: its one value, or why it may change (given).
    time_facts: durations::TimeFacts,
    /// TIME variables that may change (by their names in the scan model): why.
    time_why: BTreeMap<String, String>,
    /// The programs' TIME inputs no statement writes (by their names in the scan model).
    time_inputs: BTreeSet<String>,
    /// The function blocks and functions the file declares, by upper-case name.
    user: BTreeMap<String, ast::Pou>,
    /// Each user FB instance's variables (by the instance's name in the scan model).
    instances: BTreeMap<String, BTreeMap<String, Sym>>,
    /// The user FBs and functions being inlined (a recursion is refused).
    inlining: Vec<String>,
    /// Statements the user functions of the expression being lowered run before it.
    prelude: Vec<Stmt>,
    /// Calls of user functions so far (each call's variables are its own).
    calls: usize,
    /// The integers: (name in the scan model) → type, start value, whether an input.
    ints: BTreeMap<String, IntVar>,
    /// The free integers standing for what C leaves undefined ([`Program::undefined`]).
    undefined: BTreeSet<String>,
    /// `CONSTANT` integers with their values.
    constants: BTreeMap<String, i64>,
    /// The limits of the integers of a subrange type.
    ranges: BTreeMap<String, (i64, i64)>,
    /// Integers whose value is not computed, with the reason and where it was found
    /// (given; grows while lowering, which then runs again).
    opaque: BTreeMap<String, (ints::Opaque, Span)>,
    /// Integer globals (not located at `%Q`): inputs unless a statement writes them.
    int_globals: BTreeSet<String>,
    /// Standard function blocks' inputs some call leaves out (instance key, pin): every
    /// call that gives them keeps them in a hidden bit or integer (given; grows while
    /// lowering, like `opaque`).
    omitted: BTreeSet<(String, String)>,
    /// Calls of each standard function-block instance (by its name in the scan model).
    called: BTreeMap<String, usize>,
    /// The standard function-block instances called more than once in a scan (instance
    /// key; given, grows while lowering, like `opaque`).
    multi: BTreeSet<String>,
    /// The FB instances some call gives `EN` (key; grows like `opaque`): every call of
    /// them runs its body under the instance's EN bit ([`enable`]).
    enabled: BTreeSet<String>,
    /// The user FB instances whose type declares `EN : BOOL := FALSE` (key).
    en_off: BTreeSet<String>,
    /// While a call under its EN is lowered: the writes of the inputs it keeps, which
    /// run whatever its EN.
    kept_writes: Option<Vec<Stmt>>,
    /// The input bit every block of the body runs under ([`lower_under_en`]).
    enable: Option<String>,
    /// The timer instances whose `ET` a statement reads (key), with what the calls told
    /// of it (grows like `opaque`).
    elapsed: BTreeMap<String, elapsed::Wanted>,
    /// The values known at this point of the scan (to count `WHILE`/`REPEAT` loops).
    known: known::Known,
    /// The bodies being lowered, with their `RETURN` and loop bits, innermost last.
    frames: Vec<flow::Frame>,
    /// The hidden bits of `EXIT`, `CONTINUE` and `RETURN`, by statement.
    flow_bits: BTreeMap<(Span, &'static str), String>,
    /// Where a top-level `#ASSERT` stands after a `RETURN`: when it is reached.
    reached: Option<BoolExpr>,
    /// The variables a chart's translation declared (by their names in the scan model):
    /// hidden, as the front end's own.
    made: BTreeSet<String>,
}

impl<'s> Lowering<'s> {
    fn new(sources: &'s Sources, cycle_us: u64, warnings: Vec<StError>) -> Lowering<'s> {
        Lowering {
            sources,
            cycle_us,
            syms: BTreeMap::new(),
            inputs: BTreeSet::new(),
            globals: BTreeSet::new(),
            starts: Vec::new(),
            started: None,
            hidden: BTreeMap::new(),
            taken: BTreeSet::new(),
            suffixes: Default::default(),
            blocks: Vec::new(),
            labels: BTreeSet::new(),
            next_temp: 0,
            edges: 0,
            asserts: Vec::new(),
            warnings,
            errors: Vec::new(),
            line: 0,
            il: false,
            durations: BTreeMap::new(),
            time_facts: durations::TimeFacts::default(),
            time_why: BTreeMap::new(),
            time_inputs: BTreeSet::new(),
            user: BTreeMap::new(),
            instances: BTreeMap::new(),
            inlining: Vec::new(),
            prelude: Vec::new(),
            calls: 0,
            ints: BTreeMap::new(),
            undefined: BTreeSet::new(),
            constants: BTreeMap::new(),
            ranges: BTreeMap::new(),
            opaque: BTreeMap::new(),
            int_globals: BTreeSet::new(),
            omitted: BTreeSet::new(),
            called: BTreeMap::new(),
            multi: BTreeSet::new(),
            enabled: BTreeSet::new(),
            en_off: BTreeSet::new(),
            kept_writes: None,
            enable: None,
            elapsed: BTreeMap::new(),
            known: known::Known::default(),
            frames: Vec::new(),
            flow_bits: BTreeMap::new(),
            reached: None,
            made: BTreeSet::new(),
        }
    }

    /// Declares the globals and `pou`'s variables, its locals named by `rename`.
    fn declare(
        &mut self,
        pou: &ast::Pou,
        globals: &[&ast::VarDecl],
        rename: &dyn Fn(&str) -> String,
    ) {
        let n_globals = globals.len();
        for (k, v) in globals.iter().copied().chain(&pou.vars).enumerate() {
            let key = v.name.key();
            let name = if k < n_globals || v.class == VarClass::External {
                v.name.name.clone()
            } else {
                rename(&v.name.name)
            };
            if v.class == VarClass::External {
                if !self.syms.contains_key(&key) {
                    self.errors.push(StError::new(
                        v.name.span,
                        format!(
                            "`{}` is declared VAR_EXTERNAL but no VAR_GLOBAL declares it",
                            v.name.name
                        ),
                        "no such global",
                    ));
                }
                continue;
            }
            if let Some(prev) = self.syms.get(&key) {
                let prev = prev.span;
                self.twice(v, prev);
                continue;
            }
            let ty = self.type_of(&v.ty);
            if matches!(ty, Ty::Bool) {
                if k < n_globals
                    && !v
                        .location
                        .as_deref()
                        .is_some_and(|l| l.to_ascii_uppercase().starts_with("%Q"))
                {
                    self.globals.insert(name.clone());
                }
                let input = v.class == VarClass::Input
                    || v.location
                        .as_deref()
                        .is_some_and(|l| l.to_ascii_uppercase().starts_with("%I"));
                if input {
                    self.inputs.insert(name.clone());
                }
                // matiec reads an integer literal 0 or 1 as a BOOL here too.
                match v.init.as_ref().map(|e| &e.kind) {
                    _ if user::starts_true(v) => {
                        if !input && !self.starts.contains(&name) {
                            self.starts.push(name.clone())
                        }
                    }
                    Some(ExprKind::Bool(_) | ExprKind::Int(0)) | None => {}
                    Some(_) if input => {}
                    Some(_) => self.bad_bool_init(v),
                }
            }
            if let Ty::Int(t) = ty {
                let global = k < n_globals
                    && !v
                        .location
                        .as_deref()
                        .is_some_and(|l| l.to_ascii_uppercase().starts_with("%Q"));
                if global {
                    self.int_globals.insert(name.clone());
                }
                self.declare_int(v, &name, t, v.class == VarClass::Input);
            }
            let owner = if k < n_globals { String::new() } else { pou.name.key() };
            self.constant_duration(v, &name, &owner);
            if let Ty::Fb(
                Fb::Ton | Fb::Tof | Fb::Tp | Fb::RTrig | Fb::FTrig | Fb::Sr | Fb::Rs | Fb::Counter,
                _,
            ) = ty
                && v.init.is_some()
            {
                self.errors.push(StError::new(
                    v.ty.span,
                    "an initialised function-block instance is not modelled yet",
                    "give its inputs in its call",
                ));
            }
            self.taken.insert(name.clone());
            if v.made {
                self.made.insert(name.clone());
            }
            if let Ty::User(fb) = &ty {
                self.instantiate(&name, fb, &format!("{owner}.{key}"), v.name.span);
            }
            if let Ty::Fb(Fb::Ton | Fb::Tof | Fb::Tp, _) = ty {
                self.declare_timer(&name, &format!("{owner}.{key}"));
            }
            self.syms.insert(key, Sym { name, ty, span: v.name.span });
        }
    }

    /// `v`, a BOOL, has an initial value that is not `TRUE` or `FALSE`.
    fn bad_bool_init(&mut self, v: &ast::VarDecl) {
        self.errors.push(StError::new(
            v.init.as_ref().map_or(v.name.span, |e| e.span),
            "a BOOL's initial value must be TRUE, FALSE, 0 or 1",
            "expected `TRUE` or `FALSE`",
        ));
    }

    /// A `CONSTANT` TIME `v` with a literal value, or a TIME variable of the POU `owner`
    /// (`""`: a global) constant in fact: a preset timers may take (as `name`); else why
    /// its value may change.
    fn constant_duration(&mut self, v: &ast::VarDecl, name: &str, owner: &str) {
        if v.constant
            && let Some(ExprKind::Time(us)) = v.init.as_ref().map(|e| &e.kind)
        {
            self.durations.insert(name.to_string(), *us);
            return;
        }
        let key = (owner.to_string(), v.name.key());
        if self.time_facts.unwritten_inputs.contains(&key) {
            self.time_inputs.insert(name.to_string());
        }
        match self.time_facts.values.get(&key) {
            Some(Ok(us)) => {
                self.durations.insert(name.to_string(), *us);
            }
            Some(Err(why)) => {
                self.time_why.insert(name.to_string(), why.clone());
            }
            None => {}
        }
    }

    /// `v` is declared a second time (first at `prev`).
    fn twice(&mut self, v: &ast::VarDecl, prev: Span) {
        let mut e = StError::new(
            v.name.span,
            format!("`{}` is declared twice", v.name.name),
            "declared again here",
        );
        e.related = Some(Box::new((prev, "first declared here".into())));
        self.errors.push(e);
    }

    fn unique(&mut self, base: &str) -> String {
        let (taken, syms) = (&self.taken, &self.syms);
        let name = self
            .suffixes
            .unique(base, |n| taken.contains(n) || syms.contains_key(&n.to_ascii_uppercase()));
        self.taken.insert(name.clone());
        name
    }

    fn line_of(&self, span: Span) -> usize {
        self.sources.line_col(span.file, span.start).0
    }

    /// A block of the current line's statements (none: no block).
    fn push_block(&mut self, span: Span, mut stmts: Vec<Stmt>) {
        if stmts.is_empty() {
            return;
        }
        if let Some(en) = &self.enable {
            stmts = Stmt::guarded(&BoolExpr::var(en), stmts, span);
        }
        let mut label = format!("L{:02}", self.line);
        let mut k = 2;
        while !self.labels.insert(label.clone()) {
            label = format!("L{:02}_{k}", self.line);
            k += 1;
        }
        self.blocks.push(Block { number: self.line, label: Some(label), span, stmts });
    }

    /// The span of the first word of `span` (a statement's keyword).
    fn keyword(&self, span: Span) -> Span {
        let text = self.sources.text(span.file).get(span.range()).unwrap_or("");
        let n = text.find(|c: char| !c.is_ascii_alphanumeric() && c != '_').unwrap_or(text.len());
        Span::new(span.file, span.start..span.start + n.max(1))
    }

    fn refuse(&mut self, span: Span, what: &str, why: &str) {
        self.errors.push(StError::new(
            span,
            format!("{what} is not modelled yet"),
            why.to_string(),
        ));
    }

    /// The statements of `s`, after those the user functions it calls run.
    fn stmt(&mut self, s: &ast::Stmt, depth: usize) -> Vec<Stmt> {
        self.check_effects(s);
        let outer = std::mem::take(&mut self.prelude);
        let out = self.stmt_alone(s, depth);
        let mut all = std::mem::replace(&mut self.prelude, outer);
        all.extend(out);
        all
    }

    fn stmt_alone(&mut self, s: &ast::Stmt, depth: usize) -> Vec<Stmt> {
        match &s.kind {
            StmtKind::Assign(target, value) => self.assign(target, value, s.span),
            StmtKind::Call(callee, args) => self.call(callee, args, s.span),
            StmtKind::If(branches, otherwise) => {
                // The conditions first: the functions they call run before the `IF`.
                let conditions: Vec<BoolExpr> =
                    branches.iter().map(|(c, _)| self.bool_expr(c)).collect();
                let branches = conditions
                    .into_iter()
                    .zip(branches)
                    .map(|(c, (_, body))| (c, self.branch(body, depth + 1)))
                    .collect();
                let otherwise = self.branch(otherwise, depth + 1);
                vec![Stmt::If { branches, otherwise, span: s.span }]
            }
            StmtKind::Case(selector, arms, otherwise) => {
                // An `IF` chain on `selector = label` (a label that is not computed is
                // unconstrained, so any arm may be taken: sound, as the real selector
                // makes exactly one of them true).
                let mut branches = Vec::new();
                for (labels, body) in arms {
                    let terms: Vec<BoolExpr> =
                        labels.iter().map(|l| self.case_label(selector, l)).collect();
                    let condition = BoolExpr::Or(terms);
                    let body = self.branch(body, depth + 1);
                    branches.push((condition, body));
                }
                let otherwise = self.branch(otherwise, depth + 1);
                if branches.is_empty() {
                    return otherwise;
                }
                vec![Stmt::If { branches, otherwise, span: s.span }]
            }
            StmtKind::For(var, from, to, by, body) => {
                self.for_loop(s, var, (from, to, by.as_ref()), body, depth)
            }
            StmtKind::While(cond, body) => self.while_loop(s, cond, body, depth, false),
            StmtKind::Repeat(body, cond) => self.while_loop(s, cond, body, depth, true),
            StmtKind::Exit | StmtKind::Continue | StmtKind::Return => self.jump(s),
            StmtKind::Empty => Vec::new(),
            StmtKind::Assert(e, name) => {
                if depth > 0 {
                    self.refuse(
                        s.span,
                        "an #ASSERT inside IF",
                        "write it between top-level statements",
                    );
                    return Vec::new();
                }
                let reached = self.reached.clone();
                self.assertion(e, name.as_ref(), reached)
            }
        }
    }

    fn assign(&mut self, target: &ast::Expr, value: &ast::Expr, span: Span) -> Vec<Stmt> {
        let ExprKind::Var(id) = &target.kind else {
            self.refuse(
                target.span,
                "assigning to a member or an array element",
                "pass a function block's inputs in its call",
            );
            return Vec::new();
        };
        let Some(sym) = self.lookup(id) else { return Vec::new() };
        match sym.ty {
            Ty::Bool if self.inputs.contains(&sym.name) => {
                self.errors.push(StError::new(id.span, format!("`{}` is an input, written from outside the program", sym.name), "what a statement reads would depend on when that write comes; assign a local or output variable instead"));
                Vec::new()
            }
            Ty::Bool => {
                let v = self.bool_expr(value);
                vec![Stmt::Write { target: sym.name, kind: WriteKind::Assign, value: v, span }]
            }
            Ty::Int(_) if self.ints.get(&sym.name).is_some_and(|v| v.input) => {
                self.errors.push(StError::new(id.span, format!("`{}` is an input, written from outside the program", sym.name), "what a statement reads would depend on when that write comes; assign a local or output variable instead"));
                Vec::new()
            }
            Ty::Int(_) if self.constants.contains_key(&sym.name) => {
                self.errors.push(StError::new(
                    id.span,
                    format!("`{}` is a CONSTANT", sym.name),
                    "a constant is not assigned",
                ));
                Vec::new()
            }
            Ty::Int(t) => self.int_assign(&sym.name, t, value, span),
            // A TIME variable constant in fact written with its one value: no change.
            Ty::Other(_)
                if matches!(value.kind, ExprKind::Time(us)
                    if self.durations.get(&sym.name) == Some(&us)) =>
            {
                Vec::new()
            }
            Ty::Other(t) => vec![ints::integer_write(span, ":=", &t, &sym.name)],
            Ty::Fb(..) | Ty::User(_) => {
                self.refuse(id.span, "assigning a function-block instance", "call it instead");
                Vec::new()
            }
        }
    }

    fn lookup(&mut self, id: &Ident) -> Option<Sym> {
        if let Some(s) = self.syms.get(&id.key()) {
            return Some(s.clone());
        }
        let mut e =
            StError::new(id.span, format!("unknown variable `{}`", id.name), "not declared");
        if let Some(m) =
            crate::diag::did_you_mean(&id.name, self.syms.values().map(|s| s.name.as_str()))
        {
            e.notes.push(format!("did you mean `{m}`?"));
        }
        self.errors.push(e);
        None
    }

    fn finish(mut self) -> Lowered {
        // A global no statement writes is written from outside (an HMI, another
        // resource): an input, never a constant.
        let mut written = BTreeSet::new();
        for s in self.blocks.iter().flat_map(|b| &b.stmts) {
            s.visit(
                &mut |s| match s {
                    Stmt::Write { target, .. } | Stmt::SetInt { target, .. } => {
                        written.insert(target.clone());
                    }
                    _ => {}
                },
                &mut |_| {},
            );
        }
        let outside: Vec<String> = self.globals.difference(&written).cloned().collect();
        self.inputs.extend(outside);
        for x in self.int_globals.difference(&written) {
            if let Some(v) = self.ints.get_mut(x) {
                *v = IntVar { input: true, init: 0, ..*v };
            }
        }
        // The integers computed exactly; an input's bits are inputs.
        let opaque = &self.opaque;
        self.ints.retain(|x, _| !opaque.contains_key(x));
        for (x, v) in self.ints.iter().filter(|(_, v)| v.input) {
            self.inputs.extend((0..v.ty.bits).map(|k| Program::int_bit(x, k)));
        }
        self.starts();
        let mut signals = crate::program::bits(&self.blocks);
        let mut names = self.taken.clone();
        for s in self.syms.values() {
            names.insert(s.name.clone());
            if matches!(s.ty, Ty::Bool) {
                signals.insert(s.name.clone());
            }
        }
        let declared: BTreeSet<&String> =
            self.syms.values().map(|s| &s.name).filter(|n| !self.made.contains(*n)).collect();
        let hidden = signals
            .iter()
            .chain(self.ints.keys())
            .filter(|n| !declared.contains(n))
            .cloned()
            .collect();
        let program = Program {
            cycle_us: self.cycle_us,
            blocks: self.blocks,
            inputs: Inputs::Declared(self.inputs),
            signals,
            names,
            skipped: Vec::new(),
            integer_writers: BTreeMap::new(),
            integers: self.ints,
            exact_names: true,
            block_noun: "line",
            language: if self.il { "an Instruction List" } else { "a Structured Text" },
            started: self.started,
            hidden,
            undefined: self.undefined,
        };
        Lowered {
            program,
            asserts: self.asserts,
            warnings: self.warnings,
            time_inputs: self.time_inputs,
            enable: self.enable,
        }
    }
}
