//! PLCopen programs whose body is Structured Text: the POU's declarations from the XML and its `<ST>` body, lowered by the ST front end into the scan model.

use super::{Lang, Project, Selection, Ty, VarClass, parse_duration};
use crate::diag::{Diagnostic, Sources};
use crate::st::ast::{self, Expr, ExprKind, Ident};

/// The chosen program, when its body is Structured Text: lowered by the ST front end
/// (`None` for an LD or FBD body, which the graphical path reads).
pub fn st_program(
    sources: &mut Sources,
    project: &Project,
    sel: &Selection,
) -> Option<Result<crate::st::Lowered, Vec<Diagnostic>>> {
    let (pou, task) = super::select::pick(project, sel).ok()?;
    let body = pou.body.as_ref().filter(|b| b.lang == Lang::St)?;
    let fail = |errors: Vec<crate::st::StError>| {
        errors.into_iter().map(Diagnostic::from).collect::<Vec<_>>()
    };
    let (raw, decoded) = body.text.clone().unwrap_or((None, String::new()));
    let stmts = match raw {
        Some(range) => {
            crate::st::parser::parse_body(project.file, sources.text(project.file), range)
        }
        None => {
            // Entities in the text: the decoded body is read as a source of its own.
            let name = format!("{} (ST body of {})", sources.name(project.file), pou.name);
            let file = sources.add(name, decoded.clone());
            crate::st::parser::parse_body(file, &decoded, 0..decoded.len())
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
            kind: match text.trim().to_ascii_uppercase().as_str() {
                "TRUE" | "1" | "BOOL#TRUE" | "BOOL#1" => ExprKind::Bool(true),
                "FALSE" | "0" | "BOOL#FALSE" | "BOOL#0" => ExprKind::Bool(false),
                _ => ExprKind::Literal(text.clone()),
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
            body,
            span: pou.span,
        }],
        configs: vec![ast::Config { name, tasks: Vec::new(), instances: Vec::new(), globals }],
    };
    let interval = task.and_then(|t| t.interval.as_ref()).and_then(|(text, _)| {
        parse_duration(text).or_else(|| parse_duration(&format!("T#{}", text.trim())))
    });
    let cycle = sel.cycle_us.or(interval);
    Some(crate::st::lower(sources, &unit, Some(&pou.name), cycle).map_err(fail))
}
