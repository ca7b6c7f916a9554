//! Random sequential function charts for the differential tests, as text or as a PLCopen `<SFC>` body (the same chart; steps entered through jumps, a selection divergence where a step has several transitions, simultaneous divergences and convergences for transitions to or from two steps): steps (one or two initial), transitions with priorities and conditions over inputs and steps' `X` (inline, or a named transition in the XML), every untimed qualifier on BOOL variables and on actions whose bodies assign outputs, count and call a timer, and `D`/`L` with short times on the steps that are not initial; in the XML, some conditions drawn as networks (contacts in series and parallel, negated, from a left rail or a timer's `Q`, or an FBD variable; in the chart's body or as a named transition's LD body) and some named actions as LD or FBD bodies (coils plain, negated, set and reset, output variables, a `TON` call, functions `NOT`/`AND`/`OR`/`XOR` read once or twice and an `XOR` wired to its own output, rows drawn top to bottom or bottom to top).
#![allow(dead_code)]

use super::rng::Rng;

/// A random chart and what to compare (its integers: none given).
pub use super::st_gen::Generated;

/// A step: name, initial, associations (action, qualifier, duration in ms).
type StepDesc = (String, bool, Vec<(String, String, Option<u64>)>);

/// A transition: from, to, priority, condition.
type TransitionDesc = (Vec<String>, Vec<String>, Option<u64>, String);

struct Chart {
    steps: Vec<StepDesc>,
    transitions: Vec<TransitionDesc>,
    /// Actions with a body: name and Structured Text.
    actions: Vec<(String, String)>,
    cycle_us: u64,
}

const QUALIFIERS: [&str; 7] = ["N", "S", "R", "P", "P1", "P0", ""];
const INPUTS: [&str; 3] = ["In0", "In1", "In2"];
const OUTPUTS: [&str; 4] = ["Out0", "Out1", "Out2", "Out3"];

/// The chart of `seed`; `early` steps only (the initial `S0`) in `S.X` reads: matiec
/// knows a step's name only after its declaration, and the generator of a PLCopen chart
/// writes the steps in its own order.
fn chart(seed: u64, early: bool) -> Chart {
    let mut r = Rng::new(seed ^ 0x5FC0);
    let n_steps = 3 + r.below(4) as usize;
    let steps: Vec<String> = (0..n_steps).map(|k| format!("S{k}")).collect();
    let n_actions = 1 + r.below(3) as usize;
    let actions: Vec<String> = (0..n_actions).map(|k| format!("A{k}")).collect();
    // Durations in whole milliseconds: matiec reads no `us`.
    let cycle_us = *r.pick(&[10_000u64, 20_000, 100_000]);
    let second_initial = r.chance(15);
    let literal = |r: &mut Rng| -> String {
        let x = if r.chance(25) {
            format!("{}.X", if early { &steps[0] } else { r.pick(&steps) })
        } else {
            r.pick(&INPUTS).to_string()
        };
        if r.chance(30) { format!("NOT {x}") } else { x }
    };
    let condition = |r: &mut Rng| -> String {
        match r.below(4) {
            0 => literal(r),
            1 => format!("{} AND {}", literal(r), literal(r)),
            2 => format!("{} OR {}", literal(r), literal(r)),
            _ => "TRUE".to_string(),
        }
    };
    let mut step_descs = Vec::new();
    for (k, s) in steps.iter().enumerate() {
        let initial = k == 0 || (k == 1 && second_initial);
        let mut assoc = Vec::new();
        for _ in 0..r.below(3) {
            let target =
                if r.chance(50) { r.pick(&OUTPUTS).to_string() } else { r.pick(&actions).clone() };
            if !initial && r.chance(15) {
                let q = r.pick(&["D", "L"]).to_string();
                let ms = ((1 + r.below(4)) * cycle_us
                    - if r.chance(50) { cycle_us / 2 } else { 0 })
                    / 1000;
                assoc.push((target, q, Some(ms)));
            } else {
                assoc.push((target, r.pick(&QUALIFIERS).to_string(), None));
            }
        }
        step_descs.push((s.clone(), initial, assoc));
    }
    let mut transitions = Vec::new();
    for k in 0..n_steps + r.below(3) as usize {
        // Every step is left by some transition: the k-th from step k, then random ones.
        let first = if k < n_steps { steps[k].clone() } else { r.pick(&steps).clone() };
        let mut from = vec![first.clone()];
        if r.chance(10) {
            let other = r.pick(&steps).clone();
            if other != first {
                from.push(other);
            }
        }
        // The k-th goes on to step k + 1: every step is reached.
        let to_first =
            if k < n_steps { steps[(k + 1) % n_steps].clone() } else { r.pick(&steps).clone() };
        let mut to = vec![to_first.clone()];
        if r.chance(10) {
            let other = r.pick(&steps).clone();
            if other != to_first {
                to.push(other);
            }
        }
        let priority = if r.chance(20) { Some(r.below(3)) } else { None };
        transitions.push((from, to, priority, condition(&mut r)));
    }
    let mut action_descs = Vec::new();
    for a in &actions {
        let mut body = String::new();
        for _ in 0..1 + r.below(2) {
            body += &match r.below(4) {
                0 => "Cnt := Cnt + 1;\n".to_string(),
                1 => format!("Tm(IN := {}, PT := T#{}ms);\n", literal(&mut r), 2 * cycle_us / 1000),
                2 => format!("{} := Tm.Q OR {};\n", r.pick(&OUTPUTS), literal(&mut r)),
                _ => format!("{} := {};\n", r.pick(&OUTPUTS), condition(&mut r)),
            };
        }
        action_descs.push((a.clone(), body));
    }
    Chart { steps: step_descs, transitions, actions: action_descs, cycle_us }
}

fn generated(text: String, cycle_us: u64) -> Generated {
    Generated {
        text,
        pou: "Chart".into(),
        inputs: INPUTS.iter().map(|s| s.to_string()).collect(),
        bits: OUTPUTS.iter().map(|s| s.to_string()).collect(),
        cycle_us,
        ints: Vec::new(),
        int_inputs: Vec::new(),
    }
}

/// The random chart of `seed`, as a Structured Text file.
pub fn program(seed: u64) -> Generated {
    let c = chart(seed, false);
    let mut text = String::from("PROGRAM Chart\nVAR_INPUT\n");
    for i in INPUTS {
        text += &format!("  {i} : BOOL;\n");
    }
    text += "END_VAR\nVAR\n";
    for o in OUTPUTS {
        text += &format!("  {o} : BOOL;\n");
    }
    text += "  Cnt : INT;\n  Tm : TON;\nEND_VAR\n";
    for (s, initial, assoc) in &c.steps {
        text += &format!("{} {s}:\n", if *initial { "INITIAL_STEP" } else { "STEP" });
        for (target, q, ms) in assoc {
            match ms {
                Some(ms) => text += &format!("  {target}({q}, T#{ms}ms);\n"),
                None => text += &format!("  {target}({q});\n"),
            }
        }
        text += "END_STEP\n";
    }
    let list = |xs: &[String]| {
        if xs.len() == 1 { xs[0].clone() } else { format!("({})", xs.join(", ")) }
    };
    for (from, to, priority, cond) in &c.transitions {
        let p = priority.map_or(String::new(), |p| format!(" (PRIORITY := {p})"));
        text += &format!(
            "TRANSITION{p} FROM {} TO {}\n  := {cond};\nEND_TRANSITION\n",
            list(from),
            list(to)
        );
    }
    for (a, body) in &c.actions {
        text += &format!("ACTION {a}:\n{body}END_ACTION\n");
    }
    text += "END_PROGRAM\n";
    text += &format!(
        "CONFIGURATION Config\n  RESOURCE Res ON PLC\n    TASK Main(INTERVAL := T#{}ms, PRIORITY := 0);\n    PROGRAM Inst WITH Main : Chart;\n  END_RESOURCE\nEND_CONFIGURATION\n",
        c.cycle_us / 1000
    );
    generated(text, c.cycle_us)
}

fn cdata(text: &str) -> String {
    format!("<xhtml:p><![CDATA[{text}]]></xhtml:p>")
}

fn connect(to: u64) -> String {
    format!("<connectionPointIn><connection refLocalId=\"{to}\"/></connectionPointIn>")
}

/// The random chart of `seed`, as a PLCopen project whose program's body is the chart:
/// every step entered through jumps; some conditions named transitions of the POU, some
/// actions inline.
pub fn project(seed: u64) -> Generated {
    let c = chart(seed, true);
    let mut r = Rng::new(seed ^ 0xC0DE);
    let mut next = 0u64;
    let mut id = || {
        next += 1;
        next
    };
    let mut body = String::new();
    let step_id: Vec<u64> = c.steps.iter().map(|_| id()).collect();
    for ((name, initial, _), sid) in c.steps.iter().zip(&step_id) {
        body += &format!(
            "<step localId=\"{sid}\" name=\"{name}\" initialStep=\"{initial}\"><position x=\"0\" y=\"0\"/><connectionPointOut formalParameter=\"\"/></step>\n"
        );
    }
    let index = |name: &str| c.steps.iter().position(|s| s.0 == name).unwrap_or(0);
    // A step with several transitions from it alone is left through a selection divergence.
    let mut source: Vec<u64> = step_id.clone();
    for (k, sid) in step_id.iter().enumerate() {
        let alone = c.transitions.iter().filter(|t| t.0.len() == 1 && index(&t.0[0]) == k);
        if alone.count() > 1 {
            let d = id();
            body += &format!(
                "<selectionDivergence localId=\"{d}\"><position x=\"0\" y=\"0\"/>{}</selectionDivergence>\n",
                connect(*sid)
            );
            source[k] = d;
        }
    }
    let mut named = String::new();
    for (k, (from, to, priority, cond)) in c.transitions.iter().enumerate() {
        let input = if from.len() == 1 {
            source[index(&from[0])]
        } else {
            let v = id();
            let ins: String = from.iter().map(|s| connect(step_id[index(s)])).collect();
            body += &format!(
                "<simultaneousConvergence localId=\"{v}\"><position x=\"0\" y=\"0\"/>{ins}</simultaneousConvergence>\n"
            );
            v
        };
        let t = id();
        let p = priority.map_or(String::new(), |p| format!(" priority=\"{p}\""));
        let drawn = r.below(100);
        let condition = if drawn < 20 {
            // Drawn in the chart's body.
            let ends = drawn_condition(&mut r, &mut id, &mut body, c.cycle_us);
            connections(&ends)
        } else if drawn < 30 {
            // A named transition drawn in LD: a coil named after it.
            let n = format!("TR{k}");
            let mut ld = String::new();
            let mut lid = 0u64;
            let mut lid = || {
                lid += 1;
                lid
            };
            let ends = drawn_condition(&mut r, &mut lid, &mut ld, c.cycle_us);
            let c = lid();
            named += &format!(
                "<transition name=\"{n}\"><body><LD>\n{ld}<coil localId=\"{c}\" height=\"15\" width=\"21\"><position x=\"300\" y=\"0\"/>{}<connectionPointOut/><variable>{n}</variable></coil>\n</LD></body></transition>\n",
                connections(&ends)
            );
            format!("<reference name=\"{n}\"/>")
        } else if r.chance(33) {
            let n = format!("TR{k}");
            named += &format!(
                "<transition name=\"{n}\"><body><ST>{}</ST></body></transition>\n",
                cdata(&format!(":= {cond};"))
            );
            format!("<reference name=\"{n}\"/>")
        } else {
            format!("<inline name=\"\"><ST>{}</ST></inline>", cdata(cond))
        };
        body += &format!(
            "<transition localId=\"{t}\"{p}><position x=\"0\" y=\"0\"/>{}<connectionPointOut/><condition>{condition}</condition></transition>\n",
            connect(input)
        );
        let out = if to.len() == 1 {
            t
        } else {
            let d = id();
            body += &format!(
                "<simultaneousDivergence localId=\"{d}\"><position x=\"0\" y=\"0\"/>{}</simultaneousDivergence>\n",
                connect(t)
            );
            d
        };
        for s in to {
            let j = id();
            body += &format!(
                "<jumpStep localId=\"{j}\" targetName=\"{s}\"><position x=\"0\" y=\"0\"/>{}</jumpStep>\n",
                connect(out)
            );
        }
    }
    for ((_, _, assoc), sid) in c.steps.iter().zip(&step_id) {
        if assoc.is_empty() {
            continue;
        }
        let b = id();
        let mut acts = String::new();
        for (target, q, ms) in assoc {
            let q = if q.is_empty() { "N" } else { q };
            let d = ms.map_or(String::new(), |ms| format!(" duration=\"T#{ms}ms\""));
            let body = c.actions.iter().find(|a| &a.0 == target).map(|a| &a.1);
            let content = match body {
                // Some actions written inline in the block, each its own action.
                Some(text) if r.chance(30) => {
                    format!("<inline><ST>{}</ST></inline>", cdata(text))
                }
                _ => format!("<reference name=\"{target}\"/>"),
            };
            acts += &format!("<action localId=\"0\" qualifier=\"{q}\"{d}>{content}</action>");
        }
        body += &format!(
            "<actionBlock localId=\"{b}\"><position x=\"0\" y=\"0\"/>{}{acts}</actionBlock>\n",
            connect(*sid)
        );
    }
    let actions: String = c
        .actions
        .iter()
        .map(|(a, text)| {
            let body = if r.chance(40) {
                network_action(&mut r, c.cycle_us)
            } else {
                format!("<ST>{}</ST>", cdata(text))
            };
            format!("<action name=\"{a}\"><body>{body}</body></action>\n")
        })
        .collect();
    let inputs: String = INPUTS
        .iter()
        .map(|i| format!("<variable name=\"{i}\"><type><BOOL/></type></variable>\n"))
        .collect();
    let outputs: String = OUTPUTS
        .iter()
        .map(|o| format!("<variable name=\"{o}\"><type><BOOL/></type></variable>\n"))
        .collect();
    let actions =
        if actions.is_empty() { actions } else { format!("<actions>\n{actions}</actions>\n") };
    let named =
        if named.is_empty() { named } else { format!("<transitions>\n{named}</transitions>\n") };
    let cycle = format!("T#{}ms", c.cycle_us / 1000);
    let text = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201" xmlns:xhtml="http://www.w3.org/1999/xhtml">
<fileHeader companyName="test" productName="test" productVersion="1" creationDateTime="2026-01-01T00:00:00"/>
<contentHeader name="chart"><coordinateInfo><fbd><scaling x="1" y="1"/></fbd><ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc></coordinateInfo></contentHeader>
<types><dataTypes/><pous>
<pou name="Chart" pouType="program"><interface><inputVars>
{inputs}</inputVars><localVars>
{outputs}<variable name="Cnt"><type><INT/></type></variable>
<variable name="Tm"><type><derived name="TON"/></type></variable>
<variable name="Tc"><type><derived name="TON"/></type></variable>
</localVars></interface>
{actions}{named}<body><SFC>
{body}</SFC></body></pou>
</pous></types>
<instances><configurations><configuration name="Config"><resource name="Res"><task name="Main" priority="0" interval="{cycle}"><pouInstance name="Inst" typeName="Chart"/></task></resource></configuration></configurations></instances>
</project>
"#
    );
    generated(text, c.cycle_us)
}

/// A random series-parallel network of contacts over the inputs and `S0.X`.
enum Net {
    Contact(String, bool),
    Series(Box<Net>, Box<Net>),
    Parallel(Box<Net>, Box<Net>),
}

fn net(r: &mut Rng, depth: u32) -> Net {
    if depth == 0 || r.chance(40) {
        let x = if r.chance(20) { "S0.X".to_string() } else { r.pick(&INPUTS).to_string() };
        return Net::Contact(x, r.chance(30));
    }
    let (a, b) = (Box::new(net(r, depth - 1)), Box::new(net(r, depth - 1)));
    if r.chance(50) { Net::Series(a, b) } else { Net::Parallel(a, b) }
}

fn connections(from: &[(u64, Option<&str>)]) -> String {
    let conns: String = from
        .iter()
        .map(|(id, pin)| match pin {
            Some(p) => format!("<connection refLocalId=\"{id}\" formalParameter=\"{p}\"/>"),
            None => format!("<connection refLocalId=\"{id}\"/>"),
        })
        .collect();
    format!("<connectionPointIn>{conns}</connectionPointIn>")
}

/// Writes `n`'s contacts, powered by `from`, into `out`; the objects whose outputs carry
/// its power.
fn draw<'p>(
    n: &Net,
    from: &[(u64, Option<&'p str>)],
    id: &mut dyn FnMut() -> u64,
    out: &mut String,
) -> Vec<(u64, Option<&'p str>)> {
    match n {
        Net::Contact(x, negated) => {
            let c = id();
            *out += &format!(
                "<contact localId=\"{c}\" height=\"15\" width=\"21\" negated=\"{negated}\"><position x=\"0\" y=\"0\"/>{}<connectionPointOut/><variable>{x}</variable></contact>\n",
                connections(from)
            );
            vec![(c, None)]
        }
        Net::Series(a, b) => {
            let mid = draw(a, from, id, out);
            draw(b, &mid, id, out)
        }
        Net::Parallel(a, b) => {
            let mut outs = draw(a, from, id, out);
            outs.extend(draw(b, from, id, out));
            outs
        }
    }
}

fn rail(id: &mut dyn FnMut() -> u64, out: &mut String) -> u64 {
    let k = id();
    *out += &format!(
        "<leftPowerRail localId=\"{k}\" height=\"40\" width=\"3\"><position x=\"0\" y=\"0\"/><connectionPointOut formalParameter=\"\"/></leftPowerRail>\n"
    );
    k
}

/// What a condition drawn as a network is wired to: a network of contacts from a left rail,
/// or (FBD) a variable holding a literal.
fn drawn_condition(
    r: &mut Rng,
    id: &mut dyn FnMut() -> u64,
    out: &mut String,
    cycle_us: u64,
) -> Vec<(u64, Option<&'static str>)> {
    if r.chance(25) {
        let v = id();
        let x = r.pick(&INPUTS);
        let x = if r.chance(40) { format!("NOT {x}") } else { x.to_string() };
        *out += &format!(
            "<inVariable localId=\"{v}\" height=\"30\" width=\"60\"><position x=\"0\" y=\"0\"/><connectionPointOut/><expression>{x}</expression></inVariable>\n"
        );
        return vec![(v, None)];
    }
    if r.chance(15) {
        return vec![(function(r, id, out, 0), Some("OUT"))];
    }
    // Some networks read a timer `Tc` (its call then runs in the generator's
    // `COMPUTE_FUNCTION_BLOCKS` action).
    let from = if r.chance(20) {
        (fbd_timer(r, id, out, cycle_us, "Tc"), Some("Q"))
    } else {
        (rail(id, out), None)
    };
    let n = net(r, 2);
    draw(&n, &[from], id, out).into_iter().map(|(k, _)| (k, None)).collect()
}

/// A random LD or FBD body for an action: rungs of contacts to coils (plain, negated,
/// set, reset) on the outputs, a call of the timer `Tm` and coils or variables reading
/// its `Q`, functions (`function`), one statement per row (a quarter of the bodies drawn
/// bottom to top, so that by position they run in the reverse of document order).
fn network_action(r: &mut Rng, cycle_us: u64) -> String {
    let mut next = 0u64;
    let mut id = || {
        next += 1;
        next
    };
    let mut out = String::new();
    let fbd = r.chance(30);
    let mut timer: Option<u64> = None;
    let mut last_function: Option<u64> = None;
    let statements = 1 + r.below(3);
    // Some bodies drawn bottom to top: by position, their statements run in the reverse
    // of document order.
    let upwards = r.chance(25);
    for k in 0..statements {
        let row = 100 * if upwards { statements - k } else { k + 1 };
        let target = r.pick(&OUTPUTS);
        if fbd {
            // A variable (a literal), the timer's output or a function's to an output
            // variable.
            let from = if r.chance(40) {
                let t =
                    *timer.get_or_insert_with(|| fbd_timer(r, &mut id, &mut out, cycle_us, "Tm"));
                vec![(t, Some("Q"))]
            } else if r.chance(40) {
                let f = match last_function {
                    Some(f) if r.chance(30) => f,
                    _ => function(r, &mut id, &mut out, row),
                };
                last_function = Some(f);
                vec![(f, Some("OUT"))]
            } else {
                let v = id();
                let x = r.pick(&INPUTS);
                let x = if r.chance(30) { format!("NOT {x}") } else { x.to_string() };
                out += &format!(
                    "<inVariable localId=\"{v}\" height=\"30\" width=\"60\"><position x=\"0\" y=\"{row}\"/><connectionPointOut/><expression>{x}</expression></inVariable>\n"
                );
                vec![(v, None)]
            };
            let o = id();
            out += &format!(
                "<outVariable localId=\"{o}\" height=\"30\" width=\"60\"><position x=\"300\" y=\"{row}\"/>{}<expression>{target}</expression></outVariable>\n",
                connections(&from)
            );
            continue;
        }
        let rl = rail(&mut id, &mut out);
        let mut from = vec![(rl, None)];
        if r.chance(30) {
            let t = *timer.get_or_insert_with(|| fbd_timer(r, &mut id, &mut out, cycle_us, "Tm"));
            from = vec![(t, Some("Q"))];
        }
        let n = net(r, 2);
        let ends = draw(&n, &from, &mut id, &mut out);
        let (negated, storage) = match r.below(5) {
            0 => ("true", "none"),
            1 => ("false", "set"),
            2 => ("false", "reset"),
            _ => ("false", "none"),
        };
        let c = id();
        out += &format!(
            "<coil localId=\"{c}\" height=\"15\" width=\"21\" negated=\"{negated}\" storage=\"{storage}\"><position x=\"300\" y=\"{row}\"/>{}<connectionPointOut/><variable>{target}</variable></coil>\n",
            connections(&ends)
        );
    }
    let lang = if fbd { "FBD" } else { "LD" };
    format!("<{lang}>\n{out}</{lang}>")
}

/// A function of the inputs at height `row`, as Beremiz's editor draws it: `NOT`, a
/// two-input `AND`, `OR` or `XOR`, or an `XOR` of an input and its own output (a toggle:
/// the generator reads the output of its last call there).
fn function(r: &mut Rng, id: &mut dyn FnMut() -> u64, out: &mut String, row: u64) -> u64 {
    let f = id();
    let mut variable = |r: &mut Rng, out: &mut String| {
        let v = id();
        let x = r.pick(&INPUTS);
        let x = if r.chance(30) { format!("NOT {x}") } else { x.to_string() };
        *out += &format!(
            "<inVariable localId=\"{v}\" height=\"30\" width=\"60\"><position x=\"0\" y=\"{row}\"/><connectionPointOut/><expression>{x}</expression></inVariable>\n"
        );
        v
    };
    let (ty, inputs) = match r.below(5) {
        0 => ("NOT", vec![("IN", (variable(r, out), None))]),
        1 => ("XOR", vec![("IN1", (variable(r, out), None)), ("IN2", (f, Some("OUT")))]),
        k => {
            let ty = ["AND", "OR", "XOR"][k as usize - 2];
            let (a, b) = (variable(r, out), variable(r, out));
            (ty, vec![("IN1", (a, None)), ("IN2", (b, None))])
        }
    };
    let pins: String = inputs
        .iter()
        .map(|(pin, from)| {
            format!("<variable formalParameter=\"{pin}\">{}</variable>", connections(&[*from]))
        })
        .collect();
    *out += &format!(
        "<block localId=\"{f}\" height=\"60\" width=\"60\" typeName=\"{ty}\"><position x=\"150\" y=\"{row}\"/><inputVariables>{pins}</inputVariables><inOutVariables/><outputVariables><variable formalParameter=\"OUT\"><connectionPointOut/></variable></outputVariables></block>\n"
    );
    f
}

/// A call of the timer `name` (its `IN` a literal, its `PT` twice the cycle) placed below
/// the rungs.
fn fbd_timer(
    r: &mut Rng,
    id: &mut dyn FnMut() -> u64,
    out: &mut String,
    cycle_us: u64,
    name: &str,
) -> u64 {
    let (b, v, p) = (id(), id(), id());
    let x = r.pick(&INPUTS);
    let x = if r.chance(30) { format!("NOT {x}") } else { x.to_string() };
    *out += &format!(
        "<inVariable localId=\"{v}\" height=\"30\" width=\"60\"><position x=\"0\" y=\"1000\"/><connectionPointOut/><expression>{x}</expression></inVariable>\n\
         <inVariable localId=\"{p}\" height=\"30\" width=\"60\"><position x=\"0\" y=\"1040\"/><connectionPointOut/><expression>T#{}ms</expression></inVariable>\n\
         <block localId=\"{b}\" height=\"60\" width=\"60\" typeName=\"TON\" instanceName=\"{name}\"><position x=\"100\" y=\"1000\"/><inputVariables><variable formalParameter=\"IN\">{}</variable><variable formalParameter=\"PT\">{}</variable></inputVariables><inOutVariables/><outputVariables><variable formalParameter=\"Q\"><connectionPointOut/></variable><variable formalParameter=\"ET\"><connectionPointOut/></variable></outputVariables></block>\n",
        2 * cycle_us / 1000,
        connections(&[(v, None)]),
        connections(&[(p, None)]),
    );
    b
}
