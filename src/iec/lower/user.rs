//! User function blocks and functions, inlined: an instance's variables are bits of its own (`Inst_Var`), a call writes its inputs, runs the body with the instance's names and reads its outputs; a function call runs its body on variables of that call alone, before the statement that uses its result.

use std::collections::BTreeMap;

use super::calls::Fb;
use super::{Lowering, Sym, Ty};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::{self, Arg, ExprKind, Ident, PouKind, VarClass};
use crate::program::{BoolExpr, IntExpr, Stmt, WriteKind};

/// How deep user POUs may nest.
const MAX_DEPTH: usize = 16;

impl Lowering<'_> {
    /// The type a declaration names.
    pub(super) fn type_of(&self, ty: &Ident) -> Ty {
        match ty.name.as_str() {
            "BOOL" => Ty::Bool,
            t if crate::program::library::number_type(t).is_some() => Ty::Int(
                crate::program::library::number_type(t).unwrap_or(crate::program::IntType::I16),
            ),
            t => match Fb::of(t) {
                Some(fb) => Ty::Fb(fb, t.to_string()),
                None if self
                    .user
                    .get(&ty.key())
                    .is_some_and(|p| p.kind == PouKind::FunctionBlock) =>
                {
                    Ty::User(ty.key())
                }
                None => Ty::Other(t.to_string()),
            },
        }
    }

    /// Whether `pou` is being inlined already (or nesting is too deep): refused at `span`.
    fn recursive(&mut self, pou: &str, span: Span) -> bool {
        let again = self.inlining.iter().any(|p| p == pou) || self.inlining.len() >= MAX_DEPTH;
        if again {
            let name = self.user.get(pou).map_or(pou.to_string(), |p| p.name.name.clone());
            self.refuse(
                span,
                &format!("`{name}` used within itself"),
                "a recursive function block or function has no finite scan",
            );
        }
        again
    }

    /// The variables of the user FB instance `inst` (its name in the scan model) of type
    /// `fb`: bits named `inst_Var`, nested instances, globals through `VAR_EXTERNAL`.
    /// `decl`: the instance's declaration, `POU.INSTANCE` (upper case, `.INSTANCE` for
    /// a global), which the facts of its TIME inputs name.
    pub(super) fn instantiate(&mut self, inst: &str, fb: &str, decl: &str, span: Span) {
        if self.recursive(fb, span) {
            return;
        }
        let Some(pou) = self.user.get(fb).cloned() else { return };
        self.inlining.push(fb.to_string());
        let mut table = self.variables(&pou, inst, Some(decl));
        self.inlining.pop();
        // An `ENO` the body uses without declaring it: matiec declares it, TRUE at first.
        if !table.contains_key("ENO") && self.mentions_eno(&pou) {
            let name = self.hidden(inst, "ENO");
            self.starts.push(name.clone());
            table.insert("ENO".into(), Sym { name, ty: Ty::Bool, span: pou.name.span });
        }
        self.instances.insert(inst.to_string(), table);
    }

    /// Whether the body of `pou` names `ENO` (matiec's implicit `ENO` is then a variable
    /// of it; a word `ENO` in a comment or in a nested call's `ENO =>` counts too, which
    /// only adds a bit that nothing else writes).
    fn mentions_eno(&self, pou: &ast::Pou) -> bool {
        let text = self.text(pou.span).to_ascii_uppercase();
        let word = |c: char| c.is_ascii_alphanumeric() || c == '_';
        text.match_indices("ENO")
            .any(|(k, _)| !text[..k].ends_with(word) && !text[k + 3..].starts_with(word))
    }

    /// Whether the declaration `v` of `pou` is an `EN` or `ENO` matiec accepts: `EN` a
    /// `VAR_INPUT` `BOOL` with its initial value, `ENO` a `VAR_OUTPUT` `BOOL` without
    /// one (`EN : BOOL := TRUE;`, `ENO : BOOL;`); a located error otherwise.
    fn en_eno_declaration(&mut self, pou: &ast::Pou, v: &ast::VarDecl) -> bool {
        let (class, init) = match v.name.key().as_str() {
            "EN" => (VarClass::Input, true),
            "ENO" => (VarClass::Output, false),
            _ => return true,
        };
        let fits = pou.kind != PouKind::Program
            && v.class == class
            && v.ty.key() == "BOOL"
            && v.init.is_some() == init
            && v.location.is_none();
        if !fits {
            let shape = if init {
                "VAR_INPUT EN : BOOL := TRUE; END_VAR"
            } else {
                "VAR_OUTPUT ENO : BOOL; END_VAR"
            };
            self.errors.push(StError::new(
                v.name.span,
                format!(
                    "matiec accepts `{}` of a function block or function only as `{shape}`",
                    v.name.name
                ),
                "declare it so, or use another name",
            ));
        }
        fits
    }

    /// The variables of `pou` named `prefix_Var`: an instance's (`instance`, its
    /// declaration `POU.INSTANCE`), from the first scan on, else a function call's,
    /// which start from their initial values at each call.
    fn variables(
        &mut self,
        pou: &ast::Pou,
        prefix: &str,
        instance: Option<&str>,
    ) -> BTreeMap<String, Sym> {
        let fresh = instance.is_none();
        let mut table: BTreeMap<String, Sym> = BTreeMap::new();
        for v in &pou.vars {
            let key = v.name.key();
            if v.class == VarClass::External {
                match self.syms.get(&key) {
                    Some(g) if !fresh => {
                        table.insert(key, g.clone());
                    }
                    _ => self.errors.push(StError::new(
                        v.name.span,
                        format!("`{}` is declared VAR_EXTERNAL but no VAR_GLOBAL of the program's configuration declares it", v.name.name),
                        "no such global",
                    )),
                }
                continue;
            }
            if v.class == VarClass::InOut {
                self.refuse(
                    v.name.span,
                    &format!("the VAR_IN_OUT `{}` of `{}`", v.name.name, pou.name.name),
                    "a variable passed by reference is not modelled yet",
                );
                continue;
            }
            if let Some(prev) = table.get(&key) {
                let prev = prev.span;
                self.twice(v, prev);
                continue;
            }
            if !self.en_eno_declaration(pou, v) {
                continue;
            }
            // An instance's `EN` is the bit its calls' `EN := …` write
            // ([`Lowering::enable`]), its `ENO` the bit each call sets from it.
            let name = match (key.as_str(), fresh) {
                ("EN" | "ENO", false) => self.hidden(prefix, &key),
                _ => self.unique(&format!("{prefix}_{}", v.name.name)),
            };
            match (key.as_str(), fresh) {
                ("EN", false) if !starts_true(v) => {
                    self.en_off.insert(prefix.to_ascii_uppercase());
                }
                ("ENO", false) => self.starts.push(name.clone()),
                _ => {}
            }
            let ty = self.type_of(&v.ty);
            match (&ty, v.init.as_ref().map(|e| &e.kind)) {
                (Ty::Bool, Some(ExprKind::Bool(true))) if !fresh => self.starts.push(name.clone()),
                (Ty::Bool, Some(ExprKind::Bool(_)) | None) => {}
                (Ty::Bool, Some(_)) => self.bad_bool_init(v),
                (Ty::Fb(..) | Ty::User(_), _) if fresh => self.refuse(
                    v.ty.span,
                    "a function-block instance in a function",
                    "a function keeps no state between calls; declare it in a function block",
                ),
                (Ty::Fb(..) | Ty::User(_), Some(_)) => self.refuse(
                    v.ty.span,
                    "an initialised function-block instance",
                    "give its inputs in its call",
                ),
                _ => {}
            }
            if let Ty::Int(t) = ty {
                if fresh {
                    let why = format!(
                        "it is a variable of the function `{}`, whose integers ii-prove does not compute yet",
                        pou.name.name
                    );
                    self.make_opaque(&name, why, v.name.span);
                } else {
                    self.declare_int(v, &name, t, false);
                }
            }
            let owner = match (v.class, instance) {
                (VarClass::Input, Some(decl)) => decl.to_string(),
                _ => pou.name.key(),
            };
            self.constant_duration(v, &name, &owner);
            let decl = format!("{}.{key}", pou.name.key());
            if let Ty::User(fb) = &ty {
                let fb = fb.clone();
                self.instantiate(&name, &fb, &decl, v.name.span);
            }
            if let (Ty::Fb(Fb::Ton | Fb::Tof | Fb::Tp, _), false) = (&ty, fresh) {
                self.declare_timer(&name, &decl);
            }
            table.insert(key, Sym { name, ty, span: v.name.span });
        }
        table
    }

    /// The statements of a user POU's body, with its names.
    fn body(&mut self, pou: &ast::Pou, names: BTreeMap<String, Sym>) -> Vec<Stmt> {
        let caller = std::mem::replace(&mut self.syms, names);
        let line = self.line;
        self.inlining.push(pou.name.key());
        let stmts = match &pou.body {
            ast::Body::St(body) => {
                let mut out = body.first().map_or(Vec::new(), |s| self.enter_body(body, s.span));
                self.run_known(&out);
                out.extend(self.seq(body, 1, true));
                if !body.is_empty() {
                    self.leave_body();
                }
                out
            }
            ast::Body::Il(lines) => self.il_run(lines).into_iter().flat_map(|r| r.2).collect(),
            // Charts are Structured Text by the time a body is lowered (`sfc::desugar`).
            ast::Body::Sfc(_) => Vec::new(),
        };
        self.inlining.pop();
        self.line = line;
        self.syms = caller;
        stmts
    }

    /// The inputs of a call: `(variable, value)` for each BOOL input given (a positional
    /// argument takes the next `VAR_INPUT`), evaluated in the caller's scope.
    /// A declared `EN` is an input like the others (given by position too, as matiec
    /// gives it) for a function; a function block's is read by the call
    /// ([`Lowering::enable`]).
    fn inputs_of(
        &mut self,
        pou: &ast::Pou,
        names: &BTreeMap<String, Sym>,
        first: Option<BoolExpr>,
        args: &[Arg],
        out: &mut Vec<Stmt>,
    ) -> Vec<(String, BoolExpr)> {
        let order: Vec<&ast::VarDecl> =
            pou.vars.iter().filter(|v| v.class == VarClass::Input).collect();
        let en_input = pou.kind == PouKind::Function && names.contains_key("EN");
        let mut given = Vec::new();
        let mut next = 0;
        if let Some(v) = first {
            if let Some(d) = order.first() {
                given.push((d.name.key(), v, d.name.span));
            }
            next = 1;
        }
        for a in args {
            let (key, e, span) = match a {
                Arg::Input(n, e) if en_input && n.key() == "EN" => (n.key(), e, n.span),
                _ if super::enable::is_en_eno(a) => continue,
                Arg::Input(n, e) => (n.key(), e, n.span),
                Arg::Positional(e)
                    if !en_input && order.get(next).is_some_and(|d| d.name.key() == "EN") =>
                {
                    self.refuse(
                        e.span,
                        &format!("`{}`'s declared EN given by position", pou.name.name),
                        "give it as `EN := …`",
                    );
                    next += 1;
                    continue;
                }
                Arg::Positional(e) => {
                    let Some(d) = order.get(next) else {
                        self.errors.push(StError::new(
                            e.span,
                            format!(
                                "`{}` has {} inputs; this is one more",
                                pou.name.name,
                                order.len()
                            ),
                            "no input left for it",
                        ));
                        continue;
                    };
                    next += 1;
                    (d.name.key(), e, e.span)
                }
                Arg::Output(..) => continue,
            };
            let is_input = order.iter().any(|d| d.name.key() == key);
            match names.get(&key) {
                Some(Sym { ty: Ty::Bool, .. }) if is_input => {
                    let v = self.bool_expr(e);
                    given.push((key, v, span));
                }
                Some(Sym { ty: Ty::Int(t), name, .. }) if is_input => {
                    let (t, name) = (*t, name.clone());
                    if !self.opaque.contains_key(&name) {
                        match self.int_input(e, t) {
                            Ok(value) => {
                                out.push(Stmt::SetInt { target: name.clone(), value, span });
                                out.extend(self.subrange_check(&name, t, span));
                            }
                            Err(why) => self.make_opaque(&name, why, e.span),
                        }
                    }
                }
                Some(_) if is_input => {}
                _ => self.errors.push(StError::new(
                    span,
                    format!("`{}` has no input `{key}`", pou.name.name),
                    format!(
                        "its inputs are {}",
                        order.iter().map(|d| d.name.name.as_str()).collect::<Vec<_>>().join(", ")
                    ),
                )),
            }
        }
        // Every value is read before any input is written.
        given
            .into_iter()
            .map(|(key, v, _)| {
                let v = self.temp(out, v);
                (names[&key].name.clone(), v)
            })
            .collect()
    }

    /// A call of the user FB instance `inst` (its name in the scan model) of type `fb`.
    pub(super) fn user_call(
        &mut self,
        inst: &str,
        fb: &str,
        args: &[Arg],
        span: Span,
    ) -> Vec<Stmt> {
        if self.recursive(fb, span) {
            return Vec::new();
        }
        let Some(pou) = self.user.get(fb).cloned() else { return Vec::new() };
        let names = self.instances.get(inst).cloned().unwrap_or_default();
        let mut en = self.enable(inst, args);
        en.eno_bit = names.get("ENO").map(|s| s.name.clone());
        let mut before = Vec::new();
        let writes = self.inputs_of(&pou, &names, None, args, &mut before);
        for (target, value) in writes {
            before.push(Stmt::Write { target, kind: WriteKind::Assign, value, span });
        }
        // matiec's body of a function block starts by setting its VAR_TEMP variables
        // to their initial values, at every call its EN lets run.
        let mut body = self.temp_resets(&pou, &names);
        // The body is lowered knowing what the call wrote before it.
        self.run_known(&before);
        self.run_known(&body);
        body.extend(self.body(&pou, names.clone()));
        let out = self.output_copies(&pou, &names, args, span, true);
        // A declared `ENO` is copied among the outputs, in its place.
        if pou.vars.iter().any(|v| v.class == VarClass::Output && v.name.key() == "ENO") {
            en.eno_among_outputs();
        }
        self.enabled_call(en, [before, body, out], span)
    }

    /// The copies of a call's `=>` outputs from the variables `names` gives the
    /// VAR_OUTPUTs of `pou`, after its body, in the order matiec copies them: the
    /// outputs' declaration order (whatever the call's). `ENO` is the caller's business
    /// ([`Lowering::enabled_call`], [`Lowering::eno_copies`]), but a function block's
    /// declared `ENO` (`with_eno`), copied in its place.
    fn output_copies(
        &mut self,
        pou: &ast::Pou,
        names: &BTreeMap<String, Sym>,
        args: &[Arg],
        span: Span,
        with_eno: bool,
    ) -> Vec<Stmt> {
        let outputs: Vec<String> =
            pou.vars.iter().filter(|v| v.class == VarClass::Output).map(|v| v.name.key()).collect();
        let mut given: Vec<(Option<usize>, &Ident, bool, &ast::Expr)> = Vec::new();
        for a in args {
            let Arg::Output(pin, negated, target) = a else { continue };
            let rank = outputs.iter().position(|o| *o == pin.key());
            if super::enable::is_en_eno(a) && !(with_eno && rank.is_some()) {
                continue;
            }
            given.push((rank, pin, *negated, target));
        }
        // Stable: two copies of one output stay in the call's order.
        given.sort_by_key(|g| g.0.unwrap_or(usize::MAX));
        let mut out = Vec::new();
        for (rank, pin, negated, target) in given {
            let declared = rank.is_some();
            match names.get(&pin.key()) {
                Some(Sym { ty: Ty::Bool, name, .. }) if declared => {
                    let q = BoolExpr::var(name);
                    let value = if negated { BoolExpr::negate(q) } else { q };
                    out.extend(self.assign_value(target, value, span));
                }
                Some(Sym { ty: Ty::Int(t), name, .. }) if declared && !negated => {
                    let (t, source) = (*t, name.clone());
                    out.extend(self.int_copy(target, &source, t, span));
                }
                _ => self.refuse(
                    pin.span,
                    &format!("the output {} of {}", pin.name, pou.name.name),
                    "only its BOOL outputs are modelled",
                ),
            }
        }
        out
    }

    /// The BOOL variable `field` of the user FB instance `inst`, if it is one.
    pub(super) fn member(&self, inst: &str, field: &Ident) -> Option<String> {
        match self.instances.get(inst)?.get(&field.key())? {
            Sym { ty: Ty::Bool, name, .. } => Some(name.clone()),
            _ => None,
        }
    }

    /// Whether `f` is a user function with a BOOL result.
    pub(super) fn bool_function(&self, f: &Ident) -> bool {
        self.user.get(&f.key()).is_some_and(|p| {
            p.kind == PouKind::Function && p.result.as_ref().is_some_and(|r| r.key() == "BOOL")
        })
    }

    /// A call of the user function `f` (`first`: the value of its first input, given by
    /// an IL current result): its body runs, on variables of this call alone, before the
    /// statement being lowered; its BOOL result (`None` for another type).
    pub(super) fn user_function(
        &mut self,
        f: &Ident,
        first: Option<BoolExpr>,
        args: &[Arg],
    ) -> Option<BoolExpr> {
        if self.recursive(&f.key(), f.span) {
            return None;
        }
        let pou = self.user.get(&f.key()).cloned()?;
        self.calls += 1;
        let prefix = format!("{}_{}", pou.name.name, self.calls);
        let mut names = self.variables(&pou, &prefix, None);
        // Its `ENO`, declared or used undeclared: TRUE at each call, as matiec starts it.
        if !names.contains_key("ENO") && self.mentions_eno(&pou) {
            let name = self.unique(&format!("{prefix}_ENO"));
            names.insert("ENO".into(), Sym { name, ty: Ty::Bool, span: pou.name.span });
        }
        let eno = names.get("ENO").map(|s| s.name.clone());
        let result_ty = pou.result.as_ref().map_or(Ty::Other("?".into()), |r| self.type_of(r));
        let result = self.unique(&prefix);
        names.insert(
            pou.name.key(),
            Sym { name: result.clone(), ty: result_ty.clone(), span: pou.name.span },
        );
        let mut out = Vec::new();
        let writes = self.inputs_of(&pou, &names, first, args, &mut out);
        // The `EN` of a call of a function that does not declare it.
        let en_given = match args.iter().find(|a| matches!(a, Arg::Input(n, _) if n.key() == "EN"))
        {
            Some(Arg::Input(_, e)) if !names.contains_key("EN") => {
                let v = self.bool_expr(e);
                Some(self.temp(&mut out, v))
            }
            _ => None,
        };
        // Each call starts from the initial values.
        out.extend(self.initial_writes(pou.vars.iter(), &names));
        if let Some(n) = &eno {
            let (target, value) = (n.clone(), BoolExpr::Const(true));
            out.push(Stmt::Write { target, kind: WriteKind::Assign, value, span: f.span });
        }
        if matches!(result_ty, Ty::Bool) {
            out.push(Stmt::Write {
                target: result.clone(),
                kind: WriteKind::Assign,
                value: BoolExpr::Const(false),
                span: pou.name.span,
            });
        }
        for (target, value) in writes {
            out.push(Stmt::Write { target, kind: WriteKind::Assign, value, span: f.span });
        }
        // matiec's C: `if (!EN) { *__ENO = FALSE; return <result's initial value>; }`,
        // its outputs then left as they were; else the body, then its outputs and ENO.
        let guard = match names.get("EN") {
            Some(s) => Some(BoolExpr::var(&s.name)),
            None => en_given,
        };
        let mut body = self.body(&pou, names.clone());
        body.extend(self.output_copies(&pou, &names, args, f.span, false));
        match &guard {
            Some(g) => out.extend(Stmt::guarded(g, body, f.span)),
            None => out.extend(body),
        }
        let eno = match (eno, guard) {
            (Some(n), Some(g)) => BoolExpr::and(g, BoolExpr::var(&n)),
            (Some(n), None) => BoolExpr::var(&n),
            (None, g) => g.unwrap_or(BoolExpr::Const(true)),
        };
        out.extend(self.eno_copies(args, &eno, f.span));
        self.prelude.extend(out);
        matches!(result_ty, Ty::Bool).then(|| BoolExpr::var(&result))
    }
}

impl Lowering<'_> {
    /// Writes that give `vars` (named in `names`) their initial values, the type's
    /// default where none is declared: a BOOL its value, an integer or `REAL` computed
    /// exactly its start value (one not computed is unconstrained anyway).
    fn initial_writes<'v>(
        &self,
        vars: impl Iterator<Item = &'v ast::VarDecl>,
        names: &BTreeMap<String, Sym>,
    ) -> Vec<Stmt> {
        let mut out = Vec::new();
        for v in vars {
            let span = v.name.span;
            match names.get(&v.name.key()) {
                Some(Sym { ty: Ty::Bool, name, .. }) => {
                    let value = BoolExpr::Const(starts_true(v));
                    out.push(Stmt::Write {
                        target: name.clone(),
                        kind: WriteKind::Assign,
                        value,
                        span,
                    });
                }
                Some(Sym { ty: Ty::Int(_), name, .. }) if !self.opaque.contains_key(name) => {
                    if let Some(x) = self.ints.get(name) {
                        let value = IntExpr::Const(x.init);
                        out.push(Stmt::SetInt { target: name.clone(), value, span });
                    }
                }
                _ => {}
            }
        }
        out
    }

    /// The start of each run of `pou`'s body (a program's at every scan, a function
    /// block's at every call), as matiec's C begins it: every `VAR_TEMP` variable set
    /// to its initial value, the type's default where none is declared. A function-block
    /// instance declared there is refused, as matiec refuses it.
    pub(super) fn temp_resets(
        &mut self,
        pou: &ast::Pou,
        names: &BTreeMap<String, Sym>,
    ) -> Vec<Stmt> {
        let temps: Vec<&ast::VarDecl> =
            pou.vars.iter().filter(|v| v.class == VarClass::Temp).collect();
        for v in &temps {
            let instance =
                matches!(names.get(&v.name.key()), Some(Sym { ty: Ty::Fb(..) | Ty::User(_), .. }));
            if instance && !self.errors.iter().any(|e| e.span == v.ty.span) {
                self.refuse(
                    v.ty.span,
                    "a function-block instance in VAR_TEMP",
                    "declare it in VAR (matiec accepts no instance in VAR_TEMP)",
                );
            }
        }
        self.initial_writes(temps.into_iter(), names)
    }
}

/// Whether a BOOL's declared initial value is TRUE (matiec reads an integer literal 1 as
/// a BOOL there too).
pub(super) fn starts_true(v: &ast::VarDecl) -> bool {
    matches!(v.init.as_ref().map(|e| &e.kind), Some(ExprKind::Bool(true) | ExprKind::Int(1)))
}
