//! PLCopen POUs whose body is text: the POU's declarations from the XML and its `<ST>` or `<IL>` body, lowered by the IEC text front end into the scan model — the chosen program, and the user function blocks a graphical body calls.

use std::collections::{BTreeMap, BTreeSet};

use super::{
    Lang, PlcError, Pou, PouKind, Project, Selection, StatementOrder, Ty, VarClass, parse_duration,
};
use crate::diag::{Diagnostic, Report, Sources};
use crate::iec::StError;
use crate::iec::ast::{self, Expr, ExprKind, Ident};
use crate::program::{BoolExpr, Preset, Program};

/// A user function block or function whose body is Structured Text or Instruction
/// List, lowered by the IEC text front end as a standalone program: its input variables
/// are the program's inputs, its outputs and locals (and a function's return variable)
/// its variables. A graphical body's call of an instance runs it with every name
/// prefixed by the instance's, a function's call with names of that call alone
/// (`select`, `lower`).
#[derive(Clone, Debug)]
pub struct TextBlock {
    /// The body as a program of its own.
    pub program: Program,
    /// Whether it is a function: it keeps nothing between calls, each call runs the
    /// program from power-up (every variable at its initial value).
    pub function: bool,
    /// What the IEC front end said of it (elements not modelled exactly), as notes.
    pub warnings: Vec<PlcError>,
    /// Its TIME inputs the body never writes: a call that wires a literal to one gives
    /// the timers reading it that preset.
    pub time_inputs: BTreeSet<String>,
    /// A function block's program lowered to run under its input bit `EN` (the second
    /// of the pair), for the calls that wire `EN`; `None` where no call does, or where
    /// the body cannot run so (a call under a wired EN then is not run).
    pub enabled: Option<(Program, String)>,
}

/// The chosen program, when its body is Structured Text or Instruction List: lowered by
/// the IEC text front end (`None` for an LD or FBD body, which the graphical path reads).
pub fn st_program(
    sources: &mut Sources,
    project: &Project,
    sel: &Selection,
) -> Option<Result<crate::iec::Lowered, Vec<Diagnostic>>> {
    let (pou, task) = super::select::pick(project, sel).ok()?;
    pou.body.as_ref().filter(|b| matches!(b.lang, Lang::St | Lang::Il | Lang::Sfc))?;
    if let Err(e) = super::select::event_task(pou, task) {
        return Some(Err(e.into_iter().map(Diagnostic::from).collect()));
    }
    let fail = |errors: Vec<StError>| errors.into_iter().map(Diagnostic::from).collect::<Vec<_>>();
    let unit = match unit_of(sources, project, pou, false, sel.order) {
        Ok(u) => u,
        Err(e) => return Some(Err(fail(vec![e]))),
    };
    let cycle = task_cycle(sel, task);
    Some(
        crate::iec::lower_wanting(sources, &unit, Some(&pou.name), cycle, &sel.elapsed)
            .map_err(fail),
    )
}

/// The cycle `--cycle` or the task's interval gives, if any.
fn task_cycle(sel: &Selection, task: Option<&super::Task>) -> Option<u64> {
    let interval = task.and_then(|t| t.interval.as_ref()).and_then(|(text, _)| {
        parse_duration(text).or_else(|| parse_duration(&format!("T#{}", text.trim())))
    });
    sel.cycle_us.or(interval)
}

/// The parsed body of `pou` (`None` when it has no ST, IL or SFC body).
fn parse_body(
    sources: &mut Sources,
    project: &Project,
    pou: &Pou,
    order: Option<StatementOrder>,
) -> Option<Result<ast::Body, StError>> {
    let body = pou.body.as_ref().filter(|b| matches!(b.lang, Lang::St | Lang::Il | Lang::Sfc))?;
    if body.lang == Lang::Sfc {
        return Some(super::sfc::read(sources, project, pou, order));
    }
    let il = body.lang == Lang::Il;
    let what = format!("{} body of {}", body.lang.as_str(), pou.name);
    let text = body.text.clone().unwrap_or((None, String::new()));
    Some(if il {
        parse_text(sources, project, text, &what, crate::iec::parser::parse_il_body)
            .map(ast::Body::Il)
    } else {
        parse_text(sources, project, text, &what, crate::iec::parser::parse_body).map(ast::Body::St)
    })
}

/// Parses a text of the project (a body, an action, a condition) where it stands in the
/// file, or, when entities were decoded, as a source of its own named after `what`.
pub(super) fn parse_text<T>(
    sources: &mut Sources,
    project: &Project,
    (raw, decoded): (Option<std::ops::Range<usize>>, String),
    what: &str,
    parse: impl Fn(usize, &str, std::ops::Range<usize>) -> Result<T, StError>,
) -> Result<T, StError> {
    match raw {
        Some(range) => parse(project.file, sources.text(project.file), range),
        None => {
            let name = format!("{} ({what})", sources.name(project.file));
            let file = sources.add(name, decoded.clone());
            parse(file, &decoded, 0..decoded.len())
        }
    }
}

/// The IEC unit of `pou` as a PROGRAM (its declarations from the XML, its parsed body)
/// with the project's globals, and with `callees` the project's other function blocks
/// with a text body that parses, for its calls.
fn unit_of(
    sources: &mut Sources,
    project: &Project,
    pou: &Pou,
    callees: bool,
    order: Option<StatementOrder>,
) -> Result<ast::Unit, StError> {
    let body = parse_body(sources, project, pou, order).unwrap_or(Ok(ast::Body::St(Vec::new())))?;
    let as_pou = |p: &Pou, kind: ast::PouKind, body: ast::Body| ast::Pou {
        kind,
        name: Ident { name: p.name.clone(), span: p.span },
        vars: {
            let mut vars: Vec<ast::VarDecl> =
                p.vars.iter().map(|v| decl(v, class(v.class))).collect();
            if let ast::Body::Sfc(chart) = &body {
                vars.extend(chart.temps.iter().cloned());
            }
            vars
        },
        result: None,
        body,
        span: p.span,
    };
    let mut main = as_pou(pou, ast::PouKind::Program, body);
    // A function's return variable is an output of the standalone program.
    main.vars.extend(pou.result.iter().map(|v| decl(v, ast::VarClass::Output)));
    let mut pous = vec![main];
    if callees {
        for p in project.pous.iter().filter(|p| p.kind == PouKind::FunctionBlock) {
            // A callee with a pragma is left out: its calls are then not read.
            if p.name.eq_ignore_ascii_case(&pou.name) || has_pragma(p) {
                continue;
            }
            if let Some(Ok(b)) = parse_body(sources, project, p, order) {
                pous.push(as_pou(p, ast::PouKind::FunctionBlock, b));
            }
        }
    }
    let globals = project.globals.iter().map(|v| decl(v, ast::VarClass::Global)).collect();
    let name = Ident { name: pou.name.clone(), span: pou.span };
    Ok(ast::Unit {
        pous,
        configs: vec![ast::Config { name, tasks: Vec::new(), instances: Vec::new(), globals }],
    })
}

/// A variable of the XML as the IEC front end's declaration.
fn decl(v: &super::Var, class: ast::VarClass) -> ast::VarDecl {
    ast::VarDecl {
        name: Ident { name: v.name.clone(), span: v.span },
        class,
        ty: Ident { name: v.ty.iec_name(), span: v.span },
        init: v.init.as_ref().map(|text| Expr {
            kind: match super::select::bool_literal(text) {
                Some(b) => ExprKind::Bool(b),
                None => ExprKind::Literal(text.clone()),
            },
            span: v.span,
        }),
        retain: v.retain,
        constant: false,
        made: false,
        location: v.address.clone(),
        range: v.range,
    }
}

fn class(c: VarClass) -> ast::VarClass {
    match c {
        VarClass::Input => ast::VarClass::Input,
        VarClass::Output => ast::VarClass::Output,
        VarClass::InOut => ast::VarClass::InOut,
        VarClass::Temp => ast::VarClass::Temp,
        VarClass::External => ast::VarClass::External,
        VarClass::Global => ast::VarClass::Global,
        VarClass::Local | VarClass::Access => ast::VarClass::Local,
    }
}

/// Lowers every user function block and function of the project whose body is text into
/// [`Project::text_blocks`] at the cycle the selection gives, for the graphical body
/// that calls them; a block that cannot be run exactly is kept with the reason, and its
/// instances stay opaque.
pub fn prepare_text_blocks(sources: &mut Sources, project: &mut Project, sel: &Selection) {
    let task = super::select::pick(project, sel).ok().and_then(|(_, t)| t);
    let cycle = task_cycle(sel, task).unwrap_or(super::DEFAULT_CYCLE_US);
    let mut blocks = BTreeMap::new();
    let user = |p: &&Pou| matches!(p.kind, PouKind::FunctionBlock | PouKind::Function);
    for fb in project.pous.iter().filter(user) {
        if !fb.body.as_ref().is_some_and(|b| matches!(b.lang, Lang::St | Lang::Il | Lang::Sfc)) {
            continue;
        }
        let under_en = wires_en(project, &fb.name);
        let lowered = text_block(sources, project, fb, cycle, sel.order, under_en);
        blocks.insert(fb.name.to_ascii_uppercase(), lowered);
    }
    project.text_blocks = blocks;
}

/// Whether some block of the project calling `name` wires its `EN`.
fn wires_en(project: &Project, name: &str) -> bool {
    let objects = project.pous.iter().filter_map(|p| p.body.as_ref()).flat_map(|b| &b.objects);
    objects.into_iter().any(|o| match &o.kind {
        super::ObjKind::Block { type_name, inputs, .. } => {
            type_name.eq_ignore_ascii_case(name)
                && inputs.iter().any(|p| {
                    p.name.eq_ignore_ascii_case("EN") && (!p.conns.is_empty() || p.expr.is_some())
                })
        }
        _ => false,
    })
}

/// Whether the POU's text body has a pragma `{…}` (or a `{` in a comment or string):
/// matiec copies a pragma's text into the C it generates, code ii-prove cannot see.
fn has_pragma(pou: &Pou) -> bool {
    pou.body.as_ref().and_then(|b| b.text.as_ref()).is_some_and(|(_, text)| text.contains('{'))
}

/// `fb`, whose body is text, as a [`TextBlock`], or why it stays opaque.
fn text_block(
    sources: &mut Sources,
    project: &Project,
    fb: &Pou,
    cycle: u64,
    order: Option<StatementOrder>,
    under_en: bool,
) -> Result<TextBlock, String> {
    if !fb.errors.is_empty() {
        return Err("its declarations are malformed".into());
    }
    if fb.vars.iter().any(|v| v.class == VarClass::InOut) {
        return Err("it has in-out variables, which its body may write through".into());
    }
    if fb.vars.iter().any(|v| matches!(v.class, VarClass::External | VarClass::Global)) {
        return Err("it reads or writes global variables, which ii-prove does not share \
                    with the caller's yet"
            .into());
    }
    if has_pragma(fb) {
        return Err("its body has a pragma `{…}`, C code that ii-prove cannot see".into());
    }
    // Lowered as a program, a declared `EN` would be an input like the others and `ENO`
    // a variable no call sets: matiec's call skips the body while `EN` is FALSE and sets
    // `ENO` from it before the body.
    if let Some(v) =
        fb.vars.iter().find(|v| matches!(v.name.to_ascii_uppercase().as_str(), "EN" | "ENO"))
    {
        return Err(format!(
            "it declares `{}`, which ii-prove does not follow in a block drawn in a graphical body yet",
            v.name
        ));
    }
    let function = fb.kind == PouKind::Function;
    if function {
        function_check(project, fb)?;
    }
    let first =
        |e: Vec<StError>| e.first().map_or_else(|| "its body is not read".into(), |e| e.message());
    let mut unit = unit_of(sources, project, fb, true, order).map_err(|e| first(vec![e]))?;
    // Its body sees no global variable (it declares none external): the project's
    // globals would only be inputs of the standalone program that nothing reads.
    for config in &mut unit.configs {
        config.globals.clear();
    }
    let lowered = crate::iec::lower(sources, &unit, Some(&fb.name), Some(cycle)).map_err(first)?;
    // Only its input variables are the standalone program's inputs: the call writes
    // them; anything else the outside world wrote would read 0 inlined.
    let program = &lowered.program;
    let input_var = |x: &str| {
        fb.vars.iter().any(|v| v.class == VarClass::Input && v.name.eq_ignore_ascii_case(x))
    };
    let int_inputs = program.integers.iter().filter(|(_, v)| v.input);
    let bits: Vec<String> =
        int_inputs.flat_map(|(x, v)| (0..v.ty.bits).map(|k| Program::int_bit(x, k))).collect();
    let outside = match &program.inputs {
        crate::program::Inputs::Declared(set) => {
            set.iter().find(|n| !input_var(n) && !bits.contains(n)).cloned()
        }
        crate::program::Inputs::ByPrefix => Some("its inputs".into()),
    };
    let int_outside = program
        .integers
        .iter()
        .find(|(x, v)| v.input && !input_var(x) && !program.undefined.contains(*x));
    if let Some(x) = outside.or(int_outside.map(|(x, _)| x.clone())) {
        return Err(format!("`{x}` is written by the outside world, not by the call"));
    }
    // What the compiler refuses in the body (a timer under an `IF`) keeps the block
    // opaque rather than refusing the caller.
    if let Err(e) = crate::program::compile::accepts(program, &Default::default()) {
        let why = e.first().map_or_else(String::new, |e| format!(": {}", e.reason));
        return Err(format!("its body is refused by the compiler{why}"));
    }
    // Run from power-up at each call, a function's program must keep nothing but its
    // variables: no timer, edge memory or clock.
    if function {
        let mut timed = program.blocks.iter().any(|b| b.is_clock()) || program.edges_used() > 0;
        for (_, st) in program.stmts() {
            st.visit(&mut |_| {}, &mut |e| timed |= matches!(e, BoolExpr::Timer(_)));
        }
        if timed {
            return Err("its body keeps timers or edge memories, which a function cannot".into());
        }
    }
    let warnings = lowered
        .warnings
        .iter()
        .filter_map(|w| Some(PlcError::Note { span: w.span()?, message: w.message() }))
        .collect();
    // The same body, each of its blocks under EN: what else it reads is as above.
    let enabled = (under_en && !function)
        .then(|| crate::iec::lower_under_en(sources, &unit, Some(&fb.name), Some(cycle)).ok())
        .flatten()
        .filter(|l| crate::program::compile::accepts(&l.program, &Default::default()).is_ok())
        .and_then(|l| Some((l.program, l.enable?)));
    let time_inputs = lowered.time_inputs;
    Ok(TextBlock { program: lowered.program, function, warnings, time_inputs, enabled })
}

/// Why the function `f` cannot run as a program started afresh at each call: no return
/// type, an SFC body, or a function block instance among its variables (matiec refuses
/// both in a function: a function keeps no state).
fn function_check(project: &Project, f: &Pou) -> Result<(), String> {
    if f.result.is_none() {
        return Err("it has no return type".into());
    }
    if f.body.as_ref().is_some_and(|b| b.lang == Lang::Sfc) {
        return Err("its body is a chart, which matiec refuses in a function".into());
    }
    let fb_type = |t: &str| {
        project
            .pous
            .iter()
            .any(|p| p.kind == PouKind::FunctionBlock && p.name.eq_ignore_ascii_case(t))
            || super::Std::of(t).is_some_and(super::Std::is_fb)
            || super::IntBlock::of(t).is_some_and(|b| b.is_fb())
            || super::peripherals::peripheral(t).is_some()
    };
    match f.vars.iter().find(|v| matches!(&v.ty, Ty::Derived(t) if fb_type(t))) {
        Some(v) => Err(format!(
            "it declares the function block instance `{}`: matiec refuses one in a function, \
             which keeps no state between calls",
            v.name
        )),
        None => Ok(()),
    }
}

/// One instance of a [`TextBlock`] called from a graphical body: its program with every
/// name prefixed by the instance's (`Inst_`), and which of its variables each pin is.
#[derive(Clone, Debug)]
pub struct TextCall {
    /// The block's program for this instance (or this call of a function).
    pub program: Program,
    /// Whether it is a function's: each call runs it from power-up.
    pub function: bool,
    /// Per input pin wired on the call (upper case): the instance's variable and whether
    /// it is an integer (else a BOOL).
    pub inputs: BTreeMap<String, (String, bool)>,
    /// Per BOOL output pin (upper case): the instance's variable.
    pub outputs: BTreeMap<String, String>,
    /// Per integer output pin (upper case): the instance's variable.
    pub int_outputs: BTreeMap<String, String>,
    /// The instance's `EN` bit, when the call wires `EN`: `program` then runs its body
    /// only while it is TRUE ([`TextBlock::enabled`]), and `ENO` is it.
    pub enable: Option<String>,
}

/// The call of the user function block or function `type_name` with a text body by the
/// block `inputs` of `instance` (a declared instance of that type, `inst`; for a
/// function, `call_name` names this call's variables instead): `None` for a type
/// without a text body, the reason when it is kept opaque. `literal` is the duration
/// wired to a pin, when a literal is.
pub fn call(
    project: &Project,
    type_name: &str,
    (inst, call_name): (Option<&super::Var>, &str),
    inputs: &[super::PinIn],
    cycle_us: u64,
    literal: &dyn Fn(&super::PinIn) -> Option<u64>,
) -> Option<Result<TextCall, String>> {
    let block = project.text_blocks.get(&type_name.to_ascii_uppercase())?;
    let fb = project.pous.iter().find(|p| p.name.eq_ignore_ascii_case(type_name))?;
    Some(block.clone().and_then(|b| {
        let inst =
            inst.filter(|v| matches!(&v.ty, Ty::Derived(t) if t.eq_ignore_ascii_case(type_name)));
        let prefix = match inst {
            _ if b.function => format!("{call_name}_"),
            Some(inst) => format!("{}_", inst.name),
            None => return Err("it is not called through a declared instance of its type".into()),
        };
        if b.program.cycle_us != cycle_us {
            return Err("it was lowered at another scan cycle".into());
        }
        let wired = |name: &str| {
            inputs.iter().any(|p| {
                p.name.eq_ignore_ascii_case(name) && (!p.conns.is_empty() || p.expr.is_some())
            })
        };
        // The program's spelling of a declared variable.
        let spelled = |name: &str| {
            let all = b.program.names.iter().chain(b.program.integers.keys());
            all.into_iter().find(|n| n.eq_ignore_ascii_case(name)).cloned()
        };
        let (program, enable) = match &b.enabled {
            Some((program, en)) if wired("EN") => (program, Some(format!("{prefix}{en}"))),
            _ => (&b.program, None),
        };
        let mut call = TextCall {
            program: program.prefixed(&prefix),
            function: b.function,
            inputs: BTreeMap::new(),
            outputs: BTreeMap::new(),
            int_outputs: BTreeMap::new(),
            enable,
        };
        let mut presets = BTreeMap::new();
        for v in fb.vars.iter().chain(&fb.result) {
            // A function's return value is the block's `OUT` pin.
            let result = fb.result.as_ref().is_some_and(|r| std::ptr::eq(r, v));
            let upper = if result { "OUT".into() } else { v.name.to_ascii_uppercase() };
            let name = spelled(&v.name).unwrap_or_else(|| v.name.clone());
            let int = b.program.integers.contains_key(&name);
            let named = format!("{prefix}{name}");
            let time = matches!(&v.ty, Ty::Other(t) if t.eq_ignore_ascii_case("TIME"));
            if v.class == VarClass::Input && time {
                let preset = time_preset(&b, (&v.name, &named), inputs, literal, cycle_us);
                presets.insert(named.clone(), preset);
            }
            match v.class {
                // An input a call does not pass keeps its initial value, which the
                // standalone program (whose inputs are free) does not have.
                VarClass::Input if !wired(&v.name) && v.init.is_some() => {
                    return Err(format!(
                        "its input `{}` has an initial value and no wire on this call",
                        v.name
                    ));
                }
                // matiec holds what the call passes within the limits (`__CHECK_…`),
                // which the standalone program's free input does not.
                VarClass::Input if wired(&v.name) && v.range.is_some() => {
                    return Err(format!(
                        "its input `{}` is of a subrange type, which text blocks do not model yet",
                        v.name
                    ));
                }
                VarClass::Input if wired(&v.name) && (int || v.ty == Ty::Bool) => {
                    call.inputs.insert(upper, (named, int));
                }
                VarClass::Output if v.ty == Ty::Bool => {
                    call.outputs.insert(upper, named);
                }
                VarClass::Output if int => {
                    call.int_outputs.insert(upper, named);
                }
                _ => {}
            }
        }
        call.program = call.program.with_presets(&presets);
        Ok(call)
    }))
}

/// The preset of the timers of a text block whose `PT` is its TIME input `var` (`named`
/// in this instance) on a call with `inputs`: the literal wired to it when the body never
/// writes it, else unconstrained with the reason.
fn time_preset(
    b: &TextBlock,
    (var, named): (&str, &str),
    inputs: &[super::PinIn],
    literal: &dyn Fn(&super::PinIn) -> Option<u64>,
    cycle_us: u64,
) -> Preset {
    let pin = inputs.iter().find(|p| p.name.eq_ignore_ascii_case(var));
    let why = match pin.map(literal) {
        _ if !b.time_inputs.iter().any(|n| n.eq_ignore_ascii_case(var)) => {
            "the block's body writes it too"
        }
        Some(Some(us)) => return Preset::iec(us, cycle_us),
        Some(None) => "this call wires it to a value that is not a literal duration",
        None => "this call does not wire it",
    };
    Preset::Variable { name: named.to_string(), why: Some(why.into()) }
}

impl TextCall {
    /// Every name prefixed by `prefix` (the instance sits in an inlined body).
    pub fn prefix(&mut self, prefix: &str) {
        self.program = self.program.prefixed(prefix);
        for (var, _) in self.inputs.values_mut() {
            *var = format!("{prefix}{var}");
        }
        for var in self.outputs.values_mut().chain(self.int_outputs.values_mut()) {
            *var = format!("{prefix}{var}");
        }
        if let Some(en) = &mut self.enable {
            *en = format!("{prefix}{en}");
        }
    }
}
