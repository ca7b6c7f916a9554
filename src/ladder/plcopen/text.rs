//! PLCopen programs whose body is text: the POU's declarations from the XML and its `<ST>` or `<IL>` body, lowered by the IEC text front end into the scan model.

use super::{Lang, Project, Selection, Ty, VarClass, parse_duration};
use crate::diag::{Diagnostic, Sources};
use crate::iec::ast::{self, Expr, ExprKind, Ident};

/// The chosen program, when its body is Structured Text or Instruction List: lowered by
/// the IEC text front end (`None` for an LD or FBD body, which the graphical path reads).
pub fn st_program(
    sources: &mut Sources,
    project: &Project,
    sel: &Selection,
) -> Option<Result<crate::iec::Lowered, Vec<Diagnostic>>> {
    let (pou, task) = super::select::pick(project, sel).ok()?;
    let body = pou.body.as_ref().filter(|b| matches!(b.lang, Lang::St | Lang::Il))?;
    let il = body.lang == Lang::Il;
    if let Err(e) = super::select::event_task(pou, task) {
        return Some(Err(e.into_iter().map(Diagnostic::from).collect()));
    }
    let parse = |file: usize, text: &str, range: std::ops::Range<usize>| {
        if il {
            crate::iec::parser::parse_il_body(file, text, range).map(ast::Body::Il)
        } else {
            crate::iec::parser::parse_body(file, text, range).map(ast::Body::St)
        }
    };
    let fail = |errors: Vec<crate::iec::StError>| {
        errors.into_iter().map(Diagnostic::from).collect::<Vec<_>>()
    };
    let (raw, decoded) = body.text.clone().unwrap_or((None, String::new()));
    let stmts = match raw {
        Some(range) => parse(project.file, sources.text(project.file), range),
        None => {
            // Entities in the text: the decoded body is read as a source of its own.
            let lang = body.lang.as_str();
            let name = format!("{} ({lang} body of {})", sources.name(project.file), pou.name);
            let file = sources.add(name, decoded.clone());
            parse(file, &decoded, 0..decoded.len())
        }
    };
    let body = match stmts {
        Ok(b) => b,
        Err(e) => return Some(Err(fail(vec![e]))),
    };
    let decl = |v: &super::Var, class: ast::VarClass| ast::VarDecl {
        name: Ident { name: v.name.clone(), span: v.span },
        class,
        ty: Ident {
            name: match &v.ty {
                Ty::Bool => "BOOL".into(),
                Ty::Derived(n) | Ty::Other(n) => n.to_ascii_uppercase(),
            },
            span: v.span,
        },
        init: v.init.as_ref().map(|text| Expr {
            kind: match super::select::bool_literal(text) {
                Some(b) => ExprKind::Bool(b),
                None => ExprKind::Literal(text.clone()),
            },
            span: v.span,
        }),
        retain: v.retain,
        constant: false,
        location: v.address.clone(),
    };
    let class = |c: VarClass| match c {
        VarClass::Input => ast::VarClass::Input,
        VarClass::Output => ast::VarClass::Output,
        VarClass::InOut => ast::VarClass::InOut,
        VarClass::Temp => ast::VarClass::Temp,
        VarClass::External => ast::VarClass::External,
        VarClass::Global => ast::VarClass::Global,
        VarClass::Local | VarClass::Access => ast::VarClass::Local,
    };
    let vars = pou.vars.iter().map(|v| decl(v, class(v.class))).collect();
    let globals = project.globals.iter().map(|v| decl(v, ast::VarClass::Global)).collect();
    let name = Ident { name: pou.name.clone(), span: pou.span };
    let unit = ast::Unit {
        pous: vec![ast::Pou {
            kind: ast::PouKind::Program,
            name: name.clone(),
            vars,
            result: None,
            body,
            span: pou.span,
        }],
        configs: vec![ast::Config { name, tasks: Vec::new(), instances: Vec::new(), globals }],
    };
    let interval = task.and_then(|t| t.interval.as_ref()).and_then(|(text, _)| {
        parse_duration(text).or_else(|| parse_duration(&format!("T#{}", text.trim())))
    });
    let cycle = sel.cycle_us.or(interval);
    Some(crate::iec::lower(sources, &unit, Some(&pou.name), cycle).map_err(fail))
}
