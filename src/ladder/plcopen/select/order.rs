//! Evaluation order: the statements of a body ordered as Beremiz's
//! `PLCGenerator.ComputeProgram` orders them (execution order ids, else by position as
//! its `SortInstances` sorts, else document order), the document order Beremiz has used
//! since 2022 beside it, and the choice between the two (`--order`).

use std::collections::BTreeSet;

use super::super::*;
use super::{OrderRule, PlcProgram, StatementOrder};

/// What to do about a statement order that depends on the editor.
pub const ORDER_CHOICE: &str = "Beremiz before 2022 and the OpenPLC editor run statements by \
    position, Beremiz since 2022 in document order; choose with `--order layout` or `--order \
    document` (`ii-prove equiv FILE FILE --order layout --order-b document` compares the two)";

impl PlcProgram {
    /// This program with the statements of every body in the order `choice` gives.
    pub fn with_order(&self, choice: StatementOrder) -> PlcProgram {
        let mut p = self.clone();
        p.choose_order(choice);
        p
    }

    pub(super) fn choose_order(&mut self, choice: StatementOrder) {
        if choice == StatementOrder::Document && self.order != self.document_order {
            self.order = self.document_order.clone();
            self.rule = OrderRule::Document;
        }
        for child in self.subs.values_mut() {
            child.choose_order(choice);
        }
    }

    /// Where the two editors' statement orders first differ, in this body or an inlined
    /// one: the error to report if the difference changes what the program does.
    pub fn order_dispute(&self) -> Option<PlcError> {
        let first = self.order.iter().zip(&self.document_order).find(|(a, b)| a != b);
        if let Some((a, b)) = first {
            let (oa, ob) = (&self.objects()[*a], &self.objects()[*b]);
            return Some(PlcError::Unsupported {
                span: oa.span,
                what: format!(
                    "a statement order that depends on the editor (this `{}` runs before the \
                     `{}` {} by position, after it in document order, and the program computes \
                     differently)",
                    oa.tag(),
                    ob.tag(),
                    ob.id
                ),
                reason: ORDER_CHOICE.into(),
            });
        }
        self.subs.values().find_map(PlcProgram::order_dispute)
    }

    /// Orders the statements as Beremiz's `PLCGenerator.ComputeProgram` does (§8).
    pub(super) fn order_statements(
        &mut self,
        warnings: &mut Vec<PlcError>,
    ) -> Result<(), Vec<PlcError>> {
        let mut errors = Vec::new();
        let objects = self.objects();
        let mut ordered: Vec<(u64, usize)> = Vec::new();
        let mut outputs: Vec<usize> = Vec::new();
        let mut blocks: Vec<usize> = Vec::new();
        let mut connectors: Vec<usize> = Vec::new();
        for (k, o) in objects.iter().enumerate() {
            match &o.kind {
                ObjKind::OutVar { .. } | ObjKind::InOutVar { .. } | ObjKind::Block { .. }
                    if o.order > 0 =>
                {
                    ordered.push((o.order, k))
                }
                ObjKind::OutVar { .. } | ObjKind::InOutVar { .. } | ObjKind::Coil { .. } => {
                    outputs.push(k)
                }
                ObjKind::Block { .. } => blocks.push(k),
                ObjKind::Connector { .. } => connectors.push(k),
                _ => {}
            }
        }
        ordered.sort();
        let positioned = outputs.iter().chain(&blocks).all(|k| objects[*k].pos.is_some());
        let distinct: BTreeSet<(i64, i64)> =
            outputs.iter().chain(&blocks).filter_map(|k| objects[*k].pos).collect();
        let layout = positioned && distinct.len() > 1;
        let rule = if !ordered.is_empty() && outputs.is_empty() && blocks.is_empty() {
            OrderRule::ExecutionOrder
        } else if layout {
            OrderRule::Layout
        } else {
            OrderRule::Document
        };
        if layout {
            let mut rows_of = |list: &mut Vec<usize>| {
                let amb = match geometric(list, &|k| objects[k].pos.unwrap_or((0, 0))) {
                    Ok(amb) => amb,
                    Err((a, b)) => {
                        errors.push(PlcError::Unsupported {
                            span: objects[b].span,
                            what: format!(
                                "a statement order by position among 64 or more objects where this `{}` and the `{}` {} lie less than 10 units apart in height",
                                objects[b].tag(),
                                objects[a].tag(),
                                objects[a].id
                            ),
                            reason: "Beremiz's position comparison is no order there, and what its sort makes of it is not reproduced for so many objects; align the two or move them 10 units apart".into(),
                        });
                        None
                    }
                };
                if let Some((a, b)) = amb {
                    warnings.push(PlcError::Note {
                        span: objects[b].span,
                        message: format!(
                            "evaluation order: this `{}` and the `{}` at line-of-sight (object {}) lie \
                             within 10 units of height of each other, so they count as one row and are \
                             ordered left to right (Beremiz's rule); move one to make the order explicit",
                            objects[b].tag(),
                            objects[a].tag(),
                            objects[a].id
                        ),
                    });
                }
            };
            rows_of(&mut outputs);
            rows_of(&mut blocks);
        } else if outputs.len() + blocks.len() > 1 {
            let span = self.pou.body.as_ref().map_or(self.pou.span, |b| b.span);
            warnings.push(PlcError::Note {
                span,
                message: "evaluation order: the objects have no distinct positions, so the \
                          statements run in document order"
                    .into(),
            });
        }
        let mut order: Vec<usize> = ordered.into_iter().map(|(_, k)| k).collect();
        let mut document = order.clone();
        document.extend(outputs.iter().copied().collect::<BTreeSet<usize>>());
        document.extend(blocks.iter().copied().collect::<BTreeSet<usize>>());
        document.extend(&connectors);
        self.document_order = document;
        order.extend(outputs);
        order.extend(blocks);
        order.extend(connectors);
        self.order = order;
        self.rule = rule;
        if errors.is_empty() { Ok(()) } else { Err(errors) }
    }
}

/// Sorts `list` as Beremiz's `SortInstances` does: two objects less than 10 units apart
/// in height by `x`, others by `y`. That comparison is no order (a ~ b and b ~ c by the
/// 10-unit rule while a < c by height), so the result is the sorting algorithm's:
/// CPython's `list.sort`, which for fewer than 64 items takes the first run (reversed if
/// strictly descending) and inserts the rest by binary search. Returns a pair whose order
/// depended on the 10-unit rule (different heights, one row), if any; `Err` with such a
/// pair for a longer list, where the merges of the algorithm are not reproduced here.
/// `pos` gives the position `(x, y)` of each item of `list`.
pub(in crate::ladder::plcopen) fn geometric(
    list: &mut Vec<usize>,
    pos: &dyn Fn(usize) -> (i64, i64),
) -> Result<Option<(usize, usize)>, (usize, usize)> {
    let lt = |a: usize, b: usize| {
        let ((ax, ay), (bx, by)) = (pos(a), pos(b));
        if (ay - by).abs() < 10 { ax < bx } else { ay < by }
    };
    let mut ambiguous = None;
    for (i, &a) in list.iter().enumerate() {
        for &b in &list[i + 1..] {
            let dy = (pos(a).1 - pos(b).1).abs();
            if dy > 0 && dy < 10 && ambiguous.is_none() {
                ambiguous = Some((a, b));
            }
        }
    }
    if list.len() >= 64 {
        return match ambiguous {
            Some(pair) => Err(pair),
            // Without such a pair the comparison is (y, x), an order: any sort agrees.
            None => {
                list.sort_by_key(|k| (pos(*k).1, pos(*k).0));
                Ok(None)
            }
        };
    }
    let n = list.len();
    if n < 2 {
        return Ok(None);
    }
    let mut run = 2;
    if lt(list[1], list[0]) {
        while run < n && lt(list[run], list[run - 1]) {
            run += 1;
        }
        list[..run].reverse();
    } else {
        while run < n && !lt(list[run], list[run - 1]) {
            run += 1;
        }
    }
    for start in run..n {
        let pivot = list[start];
        let (mut l, mut r) = (0, start);
        while l < r {
            let p = l + (r - l) / 2;
            if lt(pivot, list[p]) {
                r = p;
            } else {
                l = p + 1;
            }
        }
        list.remove(start);
        list.insert(l, pivot);
    }
    Ok(ambiguous)
}
