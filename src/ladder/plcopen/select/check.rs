//! The check of one POU's body: names (POU variables over globals, SVGHMI types), the
//! outside world's inputs and latches, every wire, block type and operand, hidden
//! variables of blocks and edges, start values, user function blocks inlined per instance.

use std::collections::{BTreeMap, BTreeSet};

use super::super::*;
use super::operand::{is_member, not_bool};
use super::refusals::{fbd_only, negated_edge, unconnected_pins, variable_modifier};
use super::{Operand, PlcProgram, Std, is_known_library_block, is_true, unconnected};
use crate::diag::Span;
use crate::program::library;

/// How deep user function blocks are inlined into each other.
const MAX_INLINE_DEPTH: usize = 8;

/// Checks one POU's body: names, wires, blocks (inlining user function blocks), order.
/// `depth` > 0 for the body of an inlined function block, whose interface variables
/// are then written by the caller, not by the outside world.
pub(super) fn check_pou(
    project: &Project,
    pou: &Pou,
    cycle_us: u64,
    depth: usize,
) -> Result<PlcProgram, Vec<PlcError>> {
    let mut warnings = Vec::new();
    let mut errors = Vec::new();
    if !pou.errors.is_empty() {
        return Err(pou.errors.clone());
    }
    let Some(body) = &pou.body else {
        return Err(vec![PlcError::Unsupported {
            span: pou.span,
            what: format!("POU `{}` without a body", pou.name),
            reason: "there is nothing to scan".into(),
        }]);
    };
    if !matches!(body.lang, Lang::Ld | Lang::Fbd) {
        return Err(vec![PlcError::Unsupported {
            span: body.span,
            what: format!("the {} body of `{}`", body.lang.as_str(), pou.name),
            reason: "only LD and FBD bodies are read".into(),
        }]);
    }
    // matiec sets an LD/FBD body's `tempVars` to their initial values at the start of
    // every call (or scan): the graphical bodies keep them like `localVars`, so a body
    // reading one before writing it would be read wrongly.
    if let Some(v) = pou.vars.iter().find(|v| v.class == VarClass::Temp) {
        return Err(vec![PlcError::Unsupported {
            span: v.span,
            what: format!("the temporary variable `{}` of `{}`", v.name, pou.name),
            reason: "matiec starts it from its initial value at every call or scan, which \
                     ii-prove does not follow in LD and FBD bodies yet (their Structured Text \
                     and IL bodies do)"
                .into(),
        }]);
    }
    // Names: POU variables shadow globals; case-insensitive; two spellings of one name are ambiguous.
    let mut vars: BTreeMap<String, Var> = BTreeMap::new();
    let mut spellings: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for v in &pou.vars {
        let key = v.name.to_ascii_uppercase();
        spellings.entry(key.clone()).or_default().insert(v.name.clone());
        vars.insert(key, v.clone());
    }
    for v in &project.globals {
        vars.entry(v.name.to_ascii_uppercase()).or_insert_with(|| v.clone());
    }
    let mut hmi = BTreeMap::new();
    for v in vars.values_mut() {
        if let Ty::Derived(t) = &v.ty
            && let Some(base) = hmi_base(t)
        {
            hmi.insert(v.name.clone(), t.to_ascii_uppercase());
            v.ty = base;
        }
    }
    let mut inputs = BTreeSet::new();
    for v in vars.values() {
        let addr = v.address.as_deref().unwrap_or("").to_ascii_uppercase();
        let interface = matches!(v.class, VarClass::Input | VarClass::InOut) && depth == 0;
        let external = interface
            || matches!(v.class, VarClass::External | VarClass::Global | VarClass::Access)
            || addr.starts_with("%I")
            || addr.starts_with("%M")
            || hmi.contains_key(&v.name);
        if external {
            inputs.insert(v.name.clone());
        }
    }
    let objects = &body.objects;
    let mut index = BTreeMap::new();
    for (k, o) in objects.iter().enumerate() {
        if matches!(o.kind, ObjKind::Ignored) {
            continue;
        }
        if let Some(first) = index.insert(o.id, k) {
            errors.push(PlcError::Malformed {
                span: o.span,
                what: format!(
                    "two objects with `localId=\"{}\"` (the first at object {})",
                    o.id,
                    first + 1
                ),
                expected: "unique ids".into(),
            });
        }
        if let ObjKind::ControlFlow { tag } = &o.kind {
            errors.push(PlcError::Unsupported {
                span: o.span,
                what: format!("`{tag}`"),
                reason: "control flow inside a body skips statements; ii-prove models a plain scan"
                    .into(),
            });
        }
    }
    let user_pous: BTreeSet<String> =
        project.pous.iter().map(|p| p.name.to_ascii_uppercase()).collect();
    let mut program = PlcProgram {
        file: project.file,
        pou: pou.clone(),
        cycle_us,
        vars,
        index,
        order: Vec::new(),
        rule: OrderRule::Document,
        document_order: Vec::new(),
        hidden: BTreeMap::new(),
        operands: BTreeMap::new(),
        inputs,
        latches: BTreeMap::new(),
        hmi,
        starts: BTreeMap::new(),
        started: None,
        subs: BTreeMap::new(),
        text_calls: BTreeMap::new(),
        warnings: Vec::new(),
        peripherals: BTreeSet::new(),
    };
    // Check every wire, block type and operand.
    let mut taken: BTreeSet<String> = program.vars.keys().cloned().collect();
    let hide = |taken: &mut BTreeSet<String>, base: String| -> String {
        let mut name = base.clone();
        let mut k = 2;
        while taken.contains(&name.to_ascii_uppercase()) {
            name = format!("{base}_{k}");
            k += 1;
        }
        taken.insert(name.to_ascii_uppercase());
        name
    };
    // One block per function block instance: a second call of the same instance would
    // share its state in ways the rung model does not follow.
    let mut called: BTreeMap<String, Span> = BTreeMap::new();
    for o in objects {
        if let ObjKind::Block { instance: Some(inst), .. } = &o.kind
            && called.insert(inst.to_ascii_uppercase(), o.span).is_some()
        {
            errors.push(PlcError::Unsupported {
                span: o.span,
                what: format!("a second call of the instance `{inst}`"),
                reason: "another block already calls it; give each block its own instance".into(),
            });
        }
    }
    for (k, o) in objects.iter().enumerate() {
        // Why a user block with a text body is kept opaque.
        let mut opaque_why: Option<String> = None;
        let mut pins: Vec<&PinIn> = Vec::new();
        match &o.kind {
            ObjKind::Contact { var, edge, input, negated } => {
                pins.push(input);
                if *negated && *edge != Edge::None {
                    errors.push(negated_edge(o.span, "contact"));
                }
                if body.lang == Lang::Fbd {
                    errors.push(fbd_only(o));
                }
                match program.operand(&var.0, var.1, &spellings) {
                    Ok(op @ (Operand::Bool(_) | Operand::Member(..) | Operand::Const(_))) => {
                        program.operands.insert(k, op);
                    }
                    Ok(Operand::Other(n)) if is_member(&n) => {
                        program.operands.insert(k, Operand::Other(n));
                    }
                    Ok(_) => errors.push(not_bool(var)),
                    Err(e) => errors.push(e),
                }
                if *edge != Edge::None {
                    let n = hide(&mut taken, format!("_TRIG{}", o.id));
                    program.hidden.insert((k, String::new()), n);
                }
            }
            ObjKind::Coil { var, negated, storage, edge, input } => {
                pins.push(input);
                if body.lang == Lang::Fbd {
                    errors.push(fbd_only(o));
                }
                if *negated && (*storage != Storage::None || *edge != Edge::None) {
                    errors.push(PlcError::Unsupported {
                        span: o.span,
                        what: "a negated coil with a storage or edge modifier".into(),
                        reason:
                            "the combination has no agreed meaning (Beremiz lets `negated` win)"
                                .into(),
                    });
                }
                match program.operand(&var.0, var.1, &spellings) {
                    Ok(op @ Operand::Bool(_)) => {
                        program.operands.insert(k, op);
                    }
                    Ok(_) => errors.push(PlcError::Unsupported {
                        span: var.1,
                        what: format!("a coil on `{}`", var.0),
                        reason: "a coil must write a declared BOOL variable of the POU".into(),
                    }),
                    Err(e) => errors.push(e),
                }
            }
            ObjKind::InVar { expr, edge, negated } => {
                if *negated || *edge != Edge::None {
                    errors.push(variable_modifier(o, if *negated { "negated" } else { "edge" }));
                }
                match program.operand(&expr.0, expr.1, &spellings) {
                    Ok(op) => {
                        program.operands.insert(k, op);
                    }
                    Err(e) => errors.push(e),
                }
                if *edge != Edge::None {
                    let n = hide(&mut taken, format!("_TRIG{}", o.id));
                    program.hidden.insert((k, String::new()), n);
                }
            }
            ObjKind::OutVar { expr, input, negated, storage, edge } => {
                pins.push(input);
                if *negated || *storage != Storage::None || *edge != Edge::None {
                    let what = match (negated, storage) {
                        (true, _) => "negated",
                        (_, Storage::None) => "edge",
                        _ => "storage",
                    };
                    errors.push(variable_modifier(o, what));
                }
                match program.operand(&expr.0, expr.1, &spellings) {
                    Ok(Operand::Const(_) | Operand::Duration(_) | Operand::Member(..)) => errors
                        .push(PlcError::Unsupported {
                            span: expr.1,
                            what: format!("an assignment to `{}`", expr.0),
                            reason: "an output variable must name a declared variable".into(),
                        }),
                    Ok(op) => {
                        program.operands.insert(k, op);
                    }
                    Err(e) => errors.push(e),
                }
            }
            ObjKind::InOutVar { expr, input } => {
                pins.push(input);
                match program.operand(&expr.0, expr.1, &spellings) {
                    Ok(op @ (Operand::Bool(_) | Operand::Other(_))) => {
                        program.operands.insert(k, op);
                    }
                    Ok(_) => errors.push(not_bool(expr)),
                    Err(e) => errors.push(e),
                }
            }
            ObjKind::Connector { input, .. } => pins.push(input),
            ObjKind::Block { type_name, instance, inputs, outputs } => {
                pins.extend(inputs);
                errors.extend(unconnected_pins(o, type_name, inputs));
                if let Some(p) = outputs.iter().find(|p| p.expr.is_some()) {
                    errors.push(PlcError::Unsupported {
                        span: p.span,
                        what: "an expression on a block's output pin".into(),
                        reason: "wire the output to an `outVariable` instead".into(),
                    });
                }
                match Std::of(type_name) {
                    Some(s) if s.is_fb() => {
                        let Some(inst) = instance else {
                            errors.push(PlcError::Malformed {
                                span: o.span,
                                what: format!("a `{type_name}` block without `instanceName`"),
                                expected: "the name of its instance variable".into(),
                            });
                            continue;
                        };
                        let declared = program.vars.get(&inst.to_ascii_uppercase());
                        let inst_name = declared.map_or(inst.clone(), |v| v.name.clone());
                        match declared.map(|v| &v.ty) {
                            Some(Ty::Derived(t)) if t.eq_ignore_ascii_case(type_name) => {}
                            _ => {
                                errors.push(PlcError::Unknown {
                                    span: o.span,
                                    kind: format!("{type_name} instance"),
                                    name: inst.clone(),
                                    candidates: program
                                        .vars
                                        .values()
                                        .filter(|v| matches!(&v.ty, Ty::Derived(t) if t.eq_ignore_ascii_case(type_name)))
                                        .map(|v| v.name.clone())
                                        .collect(),
                                    ambiguous: false,
                                });
                                continue;
                            }
                        }
                        let mut pins_of = vec![s.output().to_string()];
                        if let Some((set, reset)) = s.set_reset() {
                            pins_of.extend([set.into(), reset.into()]);
                        }
                        if matches!(s, Std::Tp) {
                            pins_of.push("DONE".into());
                        }
                        // The instance's ENO, written by each call (its EN).
                        if en_drawn(inputs, outputs) {
                            pins_of.push("ENO".into());
                        }
                        for pin in pins_of {
                            if program
                                .hidden
                                .values()
                                .any(|h| h.eq_ignore_ascii_case(&format!("{inst_name}_{pin}")))
                            {
                                // A second block on the same instance shares its hidden variables.
                                let existing = program
                                    .hidden
                                    .iter()
                                    .find(|(_, h)| {
                                        h.eq_ignore_ascii_case(&format!("{inst_name}_{pin}"))
                                    })
                                    .map(|(_, h)| h.clone())
                                    .unwrap_or_default();
                                program.hidden.insert((k, pin), existing);
                                continue;
                            }
                            let n = hide(&mut taken, format!("{inst_name}_{pin}"));
                            program.hidden.insert((k, pin), n);
                        }
                    }
                    Some(s) => {
                        let n = hide(
                            &mut taken,
                            format!(
                                "_TMP_{}{}_{}",
                                type_name.to_ascii_uppercase(),
                                o.id,
                                s.output()
                            ),
                        );
                        program.hidden.insert((k, s.output().to_string()), n);
                    }
                    None if let Some(b) = IntBlock::of(type_name) => {
                        let inst = instance.as_deref().and_then(|i| {
                            let v = program.vars.get(&i.to_ascii_uppercase())?;
                            matches!(&v.ty, Ty::Derived(t) if t.eq_ignore_ascii_case(type_name))
                                .then(|| v.name.clone())
                        });
                        match (&b, inst) {
                            (IntBlock::Counter(ty), Some(inst)) => {
                                let kind = library::Counter::of(ty);
                                let outs = kind.map_or(&[][..], library::Counter::outputs);
                                let eno = en_drawn(inputs, outputs).then_some("ENO");
                                for pin in outs.iter().chain(&["CV"]).chain(&eno) {
                                    let n = hide(&mut taken, format!("{inst}_{pin}"));
                                    program.hidden.insert((k, pin.to_string()), n);
                                }
                            }
                            (IntBlock::Counter(_), None) => {}
                            _ => {
                                let upper = type_name.to_ascii_uppercase();
                                let n = hide(&mut taken, format!("_TMP_{upper}{}_OUT", o.id));
                                program.hidden.insert((k, "OUT".into()), n);
                            }
                        }
                    }
                    None if is_known_library_block(type_name) => {}
                    None if let Some(child) = inline(
                        project,
                        type_name,
                        instance.as_deref(),
                        &program,
                        cycle_us,
                        depth,
                        &mut warnings,
                        o.span,
                    )
                    .transpose()
                    .unwrap_or_else(|mut e| {
                        errors.append(&mut e);
                        None
                    }) =>
                    {
                        for n in child.names() {
                            if !taken.insert(n.to_ascii_uppercase()) {
                                errors.push(clash(o.span, type_name, instance.as_deref(), &n));
                            }
                        }
                        program.inputs.extend(child.inputs.iter().cloned());
                        program.latches.extend(child.latches.clone());
                        // Its ENO.
                        if let Some(inst) = instance.as_ref().filter(|_| en_drawn(inputs, outputs))
                        {
                            let name = program
                                .vars
                                .get(&inst.to_ascii_uppercase())
                                .map_or(inst, |v| &v.name);
                            let n = hide(&mut taken, format!("{name}_ENO"));
                            program.hidden.insert((k, "ENO".into()), n);
                        }
                        program.subs.insert(k, child);
                    }
                    None if let Some(call) = super::super::text::call(
                        project,
                        type_name,
                        (
                            instance
                                .as_deref()
                                .and_then(|i| program.vars.get(&i.to_ascii_uppercase())),
                            // A function's call: its variables named after the block.
                            &call_name(&taken, type_name, o.id),
                        ),
                        inputs,
                        cycle_us,
                        &|pin| wired_duration(&program, pin),
                    )
                    .and_then(|c| c.map_err(|why| opaque_why = Some(why)).ok()) =>
                    {
                        let own: BTreeMap<String, &String> = call
                            .program
                            .names
                            .iter()
                            .chain(call.program.integers.keys())
                            .map(|n| (n.to_ascii_uppercase(), n))
                            .collect();
                        for (upper, n) in own {
                            if !taken.insert(upper) {
                                errors.push(clash(o.span, type_name, instance.as_deref(), n));
                                break;
                            }
                        }
                        if let Some(Ok(b)) =
                            project.text_blocks.get(&type_name.to_ascii_uppercase())
                        {
                            for w in &b.warnings {
                                if !warnings.contains(w) {
                                    warnings.push(w.clone());
                                }
                            }
                        }
                        program.text_calls.insert(k, call);
                    }
                    None => {
                        // An opaque block (a user POU, a vendor library block): it can
                        // change the program's variables only through in-out pins (the
                        // globals it might write are inputs already).
                        let user = user_pous.contains(&type_name.to_ascii_uppercase());
                        let what = if user { "user block" } else { "library block" };
                        let wired =
                            |p: &&PinIn| p.in_out && (!p.conns.is_empty() || p.expr.is_some());
                        match inputs.iter().find(wired) {
                            Some(p) => errors.push(PlcError::Unsupported {
                                span: p.span,
                                what: format!(
                                    "the in-out pin `{}` of the {what} `{type_name}`",
                                    p.name
                                ),
                                reason: "the block may write what is wired to it, and its body is \
                                         not modelled"
                                    .into(),
                            }),
                            None => warnings.push(PlcError::Note {
                                span: o.span,
                                message: match super::super::peripherals::peripheral(type_name) {
                                    Some(why) if !user => {
                                        program.peripherals.insert(k);
                                        format!(
                                            "the library block `{type_name}` is a peripheral \
                                         ({why}): its Boolean outputs, and the integers \
                                         and strings read from it, are free inputs"
                                        )
                                    }
                                    _ => format!(
                                        "the {what} `{type_name}` is not modelled{}: its Boolean \
                                         outputs are unconstrained signals",
                                        opaque_why
                                            .take()
                                            .or_else(|| own_en_eno(project, type_name))
                                            .map_or(String::new(), |w| format!(" ({w})"))
                                    ),
                                },
                            }),
                        }
                    }
                }
                // A function drawn with EN/ENO: Beremiz's `_TMP_…_ENO` variable, which the
                // call writes (`ENO => _TMP_ADD7_ENO`, `PLCGenerator.py` `GenerateBlock`).
                let function = Std::of(type_name).map(|s| !s.is_fb()).unwrap_or_else(|| {
                    IntBlock::of(type_name).is_some_and(|b| !matches!(b, IntBlock::Counter(_)))
                });
                if function
                    && (inputs.iter().any(|p| p.name.eq_ignore_ascii_case("EN"))
                        || outputs.iter().any(|p| p.name.eq_ignore_ascii_case("ENO")))
                {
                    let upper = type_name.to_ascii_uppercase();
                    let n = hide(&mut taken, format!("_TMP_{upper}{}_ENO", o.id));
                    program.hidden.insert((k, "ENO".into()), n);
                }
                for p in inputs.iter().filter(|p| p.edge != Edge::None) {
                    let n = hide(&mut taken, format!("_TRIG{}_{}", o.id, p.name));
                    program.hidden.insert((k, p.name.to_ascii_uppercase()), n);
                }
            }
            _ => {}
        }
        for p in pins {
            if body.lang == Lang::Fbd && p.conns.len() > 1 {
                errors.push(PlcError::Unsupported {
                    span: p.span,
                    what: "several wires into one FBD input".into(),
                    reason: "a wired OR exists only in LD; use an OR block".into(),
                });
            }
            for c in &p.conns {
                if program.source(c).is_none() {
                    let what = match program.index.get(&c.from).and_then(|j| program.obj(*j)) {
                        Some(o) => format!(
                            "a wire from `{}` {} (pin `{}`)",
                            o.tag(),
                            c.from,
                            c.formal.as_deref().unwrap_or("")
                        ),
                        None => format!("a wire from `refLocalId=\"{}\"`", c.from),
                    };
                    errors.push(PlcError::Malformed {
                        span: c.span,
                        what,
                        expected: "the localId of an object with an output (and, for a block, one of its output pins)".into(),
                    });
                }
            }
            if let Some((text, span)) = &p.expr
                && let Err(e) = program.operand(text, *span, &spellings)
            {
                errors.push(e);
            }
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let written: BTreeSet<String> = program
        .operands
        .iter()
        .filter(|(k, _)| {
            matches!(
                program.obj(**k).map(|o| &o.kind),
                Some(ObjKind::Coil { .. } | ObjKind::OutVar { .. } | ObjKind::InOutVar { .. })
            )
        })
        .filter_map(|(_, op)| match op {
            Operand::Bool(n) => Some(n.clone()),
            _ => None,
        })
        .collect();
    // A BOOL declared TRUE, or retained (any value after a warm restart): unwritten,
    // it is a free input (sound); written, it starts with that value before the first
    // scan (`starts`, which the lowering sets on the first scan).
    let vars: Vec<Var> = program.vars.values().cloned().collect();
    for v in vars {
        let starts_true = v.init.as_deref().is_some_and(is_true);
        if v.ty != Ty::Bool || !(starts_true || v.retain) || program.inputs.contains(&v.name) {
            continue;
        }
        if !written.contains(&v.name) {
            program.inputs.insert(v.name.clone());
        } else if v.retain {
            let start = hide(&mut taken, format!("{}_START", v.name));
            program.inputs.insert(start.clone());
            program.starts.insert(v.name.clone(), Some(start));
        } else {
            program.starts.insert(v.name.clone(), None);
        }
        if program.started.is_none() {
            program.started = Some(hide(&mut taken, "STARTED".into()));
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    // Inputs the program also writes (BOOLs by coils and output variables, integers by
    // output variables) are latched from outside at the start of every scan.
    let written_ints = program.operands.iter().filter_map(|(k, op)| match (program.obj(*k), op) {
        (Some(o), Operand::Other(n))
            if matches!(o.kind, ObjKind::OutVar { .. } | ObjKind::InOutVar { .. })
                && !unconnected(&o.kind)
                && program.int_var_type(n).is_some() =>
        {
            program.vars.get(&n.to_ascii_uppercase()).map(|v| v.name.clone())
        }
        _ => None,
    });
    // An HMI input of an inlined block is written by its caller when the pin is wired.
    let passed = program.hmi.keys().filter(|x| {
        depth > 0
            && program.vars.get(&x.to_ascii_uppercase()).is_some_and(|v| v.class == VarClass::Input)
    });
    let written: BTreeSet<String> = written
        .into_iter()
        .chain(written_ints.collect::<Vec<_>>())
        .chain(passed.cloned())
        .collect();
    let written: Vec<String> = written.into_iter().filter(|n| program.inputs.contains(n)).collect();
    for x in written {
        let latch = hide(&mut taken, format!("{x}_IN"));
        program.inputs.remove(&x);
        program.inputs.insert(latch.clone());
        program.latches.insert(x, latch);
    }
    warnings.extend(program.hmi_notes(depth));
    program.order_statements(&mut warnings)?;
    program.warnings = warnings;
    Ok(program)
}

/// The base type of one of Beremiz's SVGHMI types (`svghmi/pous.xml`: `HMI_INT` is a
/// derived type of `INT`, `HMI_BOOL` and `HMI_NODE` of `BOOL`, …), which the project
/// file names without declaring (`HMI_REAL` of `REAL`). `HMI_STRING` stays opaque, as
/// `STRING` variables are.
pub fn hmi_base(type_name: &str) -> Option<Ty> {
    let upper = type_name.to_ascii_uppercase();
    let base = upper.strip_prefix("HMI_")?;
    Some(match base {
        "BOOL" | "NODE" => Ty::Bool,
        "SINT" | "INT" | "DINT" | "LINT" | "USINT" | "UINT" | "UDINT" | "ULINT" | "REAL" => {
            Ty::Other(base.to_string())
        }
        _ => return None,
    })
}

/// The body of a user function block instance, checked and with its names prefixed,
/// when it can be inlined: an LD/FBD function block without in-out variables, whose
/// body writes no input (a global), instantiated by a declared instance of its type.
#[allow(clippy::too_many_arguments)]
fn inline(
    project: &Project,
    type_name: &str,
    instance: Option<&str>,
    program: &PlcProgram,
    cycle_us: u64,
    depth: usize,
    warnings: &mut Vec<PlcError>,
    span: Span,
) -> Option<Result<PlcProgram, Vec<PlcError>>> {
    let fb = project
        .pous
        .iter()
        .find(|p| p.name.eq_ignore_ascii_case(type_name) && p.kind == PouKind::FunctionBlock)?;
    let graphical = fb.body.as_ref().is_some_and(|b| matches!(b.lang, Lang::Ld | Lang::Fbd));
    let inst = program.vars.get(&instance?.to_ascii_uppercase())?;
    let typed = matches!(&inst.ty, Ty::Derived(t) if t.eq_ignore_ascii_case(type_name));
    if !graphical || !typed || fb.vars.iter().any(|v| v.class == VarClass::InOut) {
        return None;
    }
    if declares_en_eno(fb) {
        return None;
    }
    if depth + 1 > MAX_INLINE_DEPTH {
        return Some(Err(vec![PlcError::Unsupported {
            span,
            what: format!("the user block `{type_name}`"),
            reason: format!(
                "function blocks nest more than {MAX_INLINE_DEPTH} deep (a recursive type?)"
            ),
        }]));
    }
    let mut child = match check_pou(project, fb, cycle_us, depth + 1) {
        Ok(c) => c,
        Err(e) => return Some(Err(e)),
    };
    // Latches of the outside world's writes run at the start of the scan, before the
    // caller: only those of variables the body owns (not globals) are hoisted to it.
    let owned = |x: &String| {
        child.vars.get(&x.to_ascii_uppercase()).is_some_and(|v| {
            !matches!(v.class, VarClass::External | VarClass::Global | VarClass::Access)
        })
    };
    if !child.latches.keys().all(owned) || !child.starts.is_empty() {
        return None;
    }
    // The same note at the same place, once for all instances.
    for w in std::mem::take(&mut child.warnings) {
        if !warnings.contains(&w) {
            warnings.push(w);
        }
    }
    child.prefix_names(&format!("{}_", inst.name));
    Some(Ok(child))
}

/// The name of a call of the user function `type_name` by the block `id`
/// (`_TMP_F12`, Beremiz's name for its result without `_OUT`), unique among `taken`:
/// the call's variables are named after it.
fn call_name(taken: &BTreeSet<String>, type_name: &str, id: u64) -> String {
    let base = format!("_TMP_{}{id}", type_name.to_ascii_uppercase());
    let mut name = base.clone();
    let mut k = 2;
    while taken.iter().any(|t| t.starts_with(&format!("{}_", name.to_ascii_uppercase()))) {
        name = format!("{base}_{k}");
        k += 1;
    }
    name
}

/// A variable of an instance whose name is already one of the program's (an instance
/// called twice, or a name the prefix makes again).
fn clash(span: Span, type_name: &str, instance: Option<&str>, name: &str) -> PlcError {
    PlcError::Unsupported {
        span,
        what: format!("the instance `{}` of `{type_name}`", instance.unwrap_or("")),
        reason: format!("its variable `{name}` clashes with a name of the program"),
    }
}

impl PlcProgram {
    /// Prefixes every name this body owns (not the globals it refers to), recursively.
    fn prefix_names(&mut self, prefix: &str) {
        let mut map: BTreeMap<String, String> = BTreeMap::new();
        for v in self.vars.values_mut() {
            if !matches!(v.class, VarClass::External | VarClass::Global | VarClass::Access) {
                let new = format!("{prefix}{}", v.name);
                map.insert(v.name.clone(), new.clone());
                v.name = new;
            }
        }
        // A latch is of a variable this body or an inlined one owns (see `inline`).
        for (x, l) in &self.latches {
            map.insert(x.clone(), format!("{prefix}{x}"));
            map.insert(l.clone(), format!("{prefix}{l}"));
        }
        let rename = |n: &String| map.get(n).cloned().unwrap_or_else(|| n.clone());
        self.latches = self.latches.iter().map(|(x, l)| (rename(x), rename(l))).collect();
        self.hmi = self.hmi.iter().map(|(x, t)| (rename(x), t.clone())).collect();
        for op in self.operands.values_mut() {
            match op {
                Operand::Bool(n) => *n = rename(n),
                Operand::Member(i, _) => *i = rename(i),
                _ => {}
            }
        }
        for h in self.hidden.values_mut() {
            *h = format!("{prefix}{h}");
        }
        self.inputs = self.inputs.iter().map(rename).collect();
        for sub in self.subs.values_mut() {
            sub.prefix_names(prefix);
        }
        for call in self.text_calls.values_mut() {
            call.prefix(prefix);
        }
    }

    /// What the program's HMI variables are (those it owns, and at `depth` 0 the
    /// globals): a note at each declaration.
    fn hmi_notes(&self, depth: usize) -> Vec<PlcError> {
        let mut notes = Vec::new();
        for (x, ty) in &self.hmi {
            let Some(v) = self.vars.get(&x.to_ascii_uppercase()) else { continue };
            let global = matches!(v.class, VarClass::Global | VarClass::Access);
            if v.class == VarClass::External || (global && depth > 0) {
                continue;
            }
            let base = match &v.ty {
                Ty::Bool => "BOOL".to_string(),
                Ty::Derived(t) | Ty::Other(t) => t.to_ascii_uppercase(),
            };
            let mut message = format!(
                "`{x}` is an {ty}: Beremiz's SVGHMI server may write it before any scan, so \
                 the outside world writes it: a free {base} input"
            );
            if let Some(latch) = self.latches.get(x) {
                message.push_str(&format!(
                    "; the program writes it too, so each scan starts with the value from \
                     outside (`{latch}`) and then sees the program's writes"
                ));
            }
            notes.push(PlcError::Note { span: v.span, message });
        }
        notes
    }
}

/// The duration a literal wired to `pin` gives (its own text, or a variable object's).
fn wired_duration(program: &PlcProgram, pin: &PinIn) -> Option<u64> {
    if let Some((text, _)) = &pin.expr {
        return parse_duration(text);
    }
    let [c] = pin.conns.as_slice() else { return None };
    let Some(Source::Object(j)) = program.source(c) else { return None };
    match &program.obj(j)?.kind {
        ObjKind::InVar { expr, .. } => parse_duration(&expr.0),
        _ => None,
    }
}

/// Whether the user block `fb` declares `EN` or `ENO` itself: matiec's call then skips
/// its body while that `EN` is FALSE (also where none is wired and it is declared
/// `:= FALSE`), and the body may clear `ENO`, which the inlined body does not follow.
fn declares_en_eno(fb: &Pou) -> bool {
    fb.vars.iter().any(|v| v.name.eq_ignore_ascii_case("EN") || v.name.eq_ignore_ascii_case("ENO"))
}

/// Why the graphical user block `type_name` is not inlined, where it declares `EN` or
/// `ENO` ([`declares_en_eno`]).
fn own_en_eno(project: &Project, type_name: &str) -> Option<String> {
    let fb = project.pous.iter().find(|p| p.name.eq_ignore_ascii_case(type_name))?;
    let graphical = fb.body.as_ref().is_some_and(|b| matches!(b.lang, Lang::Ld | Lang::Fbd));
    (graphical && declares_en_eno(fb)).then(|| {
        "it declares EN or ENO, whose run ii-prove does not follow in a graphical body yet".into()
    })
}

/// Whether a block is drawn with its `EN` wired (or given) or its `ENO`: a function
/// block's call then writes the instance's ENO.
fn en_drawn(inputs: &[PinIn], outputs: &[PinOut]) -> bool {
    inputs
        .iter()
        .any(|p| p.name.eq_ignore_ascii_case("EN") && (!p.conns.is_empty() || p.expr.is_some()))
        || outputs.iter().any(|p| p.name.eq_ignore_ascii_case("ENO"))
}
