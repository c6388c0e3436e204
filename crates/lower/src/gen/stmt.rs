//! Statements and the POU entry (prologue re-initialising temporaries and
//! function locals from the POU's template, body, epilogue).

use super::{Gen, LoopCx, Res, V};
use crate::cx::Cx;
use crate::layout::Slot;
use automat_ir::code::{Addr, Cmp, Func, Inst, IntOp, RegClass};
use automat_sema::model::Section;
use automat_sema::value::Value;
use automat_sema::PouId;
use automat_syntax::ast::{Body, CaseLabel, Expr, PouKind, Stmt, StmtKind};

/// The code of one POU (an empty function for one without a body).
pub fn pou(cx: &mut Cx, id: PouId) -> Func {
    let model = cx.model;
    let Some(p) = model.pou(id) else {
        return crate::empty_func("?");
    };
    let name = cx.interner.name(p.name).to_string();
    let Some(ast) = model.pou_ast(cx.units, id) else {
        return crate::empty_func(&name);
    };
    let frame = cx.frames.get(id.0 as usize).copied().flatten();
    let mut g = Gen::new(cx, id, &name, frame);
    g.prologue(p.kind == PouKind::Function);
    let Body::St(stmts) = &ast.body;
    g.block(stmts);
    let _ = g.unresolved_gotos();
    let end = g.here();
    for j in std::mem::take(&mut g.returns) {
        g.patch(j, end);
    }
    g.emit(Inst::Ret);
    super::peep::tidy(&mut g.f);
    g.f
}

impl Gen<'_, '_> {
    /// Re-initialises VAR_TEMP (and, in a function, the return value,
    /// outputs and locals) from the template copy of the frame.
    fn prologue(&mut self, function: bool) {
        let model = self.cx.model;
        let Some(p) = model.pou(self.pou) else { return };
        let Some(tpl) = self
            .cx
            .templates
            .get(self.pou.0 as usize)
            .copied()
            .flatten()
        else {
            return;
        };
        let l = self.cx.layout.pou(self.pou);
        self.edges(&l.edges);
        for (v, slot) in p.vars.vars.iter().zip(l.slots.iter()) {
            let reinit = match v.section {
                Section::Temp => true,
                Section::Return | Section::Output | Section::Local => function,
                _ => false,
            };
            if let (true, Slot::Rel(off)) = (reinit, *slot) {
                let (len, _) = self.cx.layout.size(v.ty);
                let dst = match self.frame {
                    Some(f) => Addr::abs(f + off),
                    None => Addr::this(off),
                };
                self.emit(Inst::Copy {
                    dst,
                    src: Addr::abs(tpl + off),
                    len,
                });
            }
        }
    }

    /// `R_EDGE` / `F_EDGE` inputs: the body sees the edge, the hidden byte
    /// keeps the raw value for the next call.
    fn edges(&mut self, edges: &[(u32, u32)]) {
        let model = self.cx.model;
        let Some(p) = model.pou(self.pou) else { return };
        for &(idx, mem) in edges {
            let Some(var) = p.vars.vars.get(idx as usize) else {
                continue;
            };
            let Ok(lv) = self.raw_var_lv(idx, var.span) else {
                continue;
            };
            let V::I(raw) = self.load(lv).v else { continue };
            let m_at = match self.frame {
                Some(f) => Addr::abs(f + mem),
                None => Addr::this(mem),
            };
            let m = self.reg(RegClass::I64);
            self.emit(Inst::Load {
                dst: m,
                ty: automat_ir::code::MemTy::U8,
                addr: m_at,
            });
            let one = self.iconst(1);
            let (a, b) = if var.edge == Some(automat_syntax::ast::Edge::Rising) {
                (raw, m)
            } else {
                (m, raw)
            };
            // a AND NOT b
            let nb = self.reg(RegClass::I64);
            self.emit(Inst::Int {
                op: IntOp::Xor,
                dst: nb,
                a: b,
                b: one,
            });
            let e = self.reg(RegClass::I64);
            self.emit(Inst::Int {
                op: IntOp::And,
                dst: e,
                a,
                b: nb,
            });
            self.emit(Inst::Store {
                src: raw,
                ty: automat_ir::code::MemTy::U8,
                addr: m_at,
            });
            let edge_at = match self.frame {
                Some(f) => Addr::abs(f + mem + 1),
                None => Addr::this(mem + 1),
            };
            self.emit(Inst::Store {
                src: e,
                ty: automat_ir::code::MemTy::U8,
                addr: edge_at,
            });
        }
    }

    pub fn block(&mut self, stmts: &[Stmt]) {
        for s in stmts {
            // A failed statement was reported; keep going to report others.
            // A failure nobody reported must still stop the build: running
            // a program with a statement silently left out is the one
            // thing lowering may never do.
            let before = self.cx.diags.len();
            if self.stmt(s).is_err() && self.cx.diags.len() == before {
                self.error(
                    s.span,
                    "internal error: this statement could not be compiled".into(),
                );
            }
        }
    }

    fn stmt(&mut self, s: &Stmt) -> Res<()> {
        // No value of an earlier statement is still needed.
        self.free_temps();
        // Not `here()`: a statement start is no jump target by itself.
        let at = self.f.code.len() as u32;
        let site = self.site(s.span);
        self.f.stmt_sites.push((at, site));
        match &s.kind {
            StmtKind::Assign { target, value } => {
                let lv = self.place(target)?;
                let v = self.expr(value, Some(lv.ty))?;
                self.store(lv, v, s.span)
            }
            StmtKind::Expr(e) => self.expr(e, None).map(|_| ()),
            StmtKind::Return => {
                let j = self.jump_fwd();
                self.returns.push(j);
                Ok(())
            }
            StmtKind::Empty => Ok(()),
            StmtKind::Label(l) => {
                self.place_label(*l);
                Ok(())
            }
            StmtKind::Goto(l) => {
                self.goto(*l);
                Ok(())
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                let mut ends = Vec::new();
                for b in branches {
                    let c = self.cond(&b.cond)?;
                    let br = self.emit(Inst::Branch {
                        cond: c,
                        then: u32::MAX,
                        els: u32::MAX,
                    });
                    let t = self.here();
                    self.set_then(br, t);
                    self.block(&b.body);
                    ends.push(self.jump_fwd());
                    let next = self.here();
                    self.patch(br, next);
                }
                if let Some(b) = else_body {
                    self.block(b);
                }
                let end = self.here();
                for j in ends {
                    self.patch(j, end);
                }
                Ok(())
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => self.case(selector, arms, else_body.as_deref()),
            StmtKind::While { cond, body } => {
                let top = self.here();
                let c = self.cond(cond)?;
                let br = self.emit(Inst::Branch {
                    cond: c,
                    then: u32::MAX,
                    els: u32::MAX,
                });
                let t = self.here();
                self.set_then(br, t);
                self.loop_body(body, top, br)
            }
            StmtKind::Repeat { body, until } => {
                let top = self.here();
                self.loops.push(LoopCx {
                    continues: Vec::new(),
                    exits: Vec::new(),
                });
                self.block(body);
                let test = self.here();
                let c = self.cond(until)?;
                let br = self.emit(Inst::Branch {
                    cond: c,
                    then: u32::MAX,
                    els: top,
                });
                let end = self.here();
                self.patch(br, end);
                self.close_loop(test, end);
                Ok(())
            }
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => self.for_loop(var, from, to, by.as_deref(), body, s),
            StmtKind::Exit => {
                let j = self.jump_fwd();
                match self.loops.last_mut() {
                    Some(l) => l.exits.push(j),
                    None => return Err(self.error(s.span, "EXIT outside a loop".into())),
                }
                Ok(())
            }
            StmtKind::Continue => {
                let j = self.jump_fwd();
                match self.loops.last_mut() {
                    Some(l) => l.continues.push(j),
                    None => return Err(self.error(s.span, "CONTINUE outside a loop".into())),
                }
                Ok(())
            }
        }
    }

    pub(super) fn set_then(&mut self, br: u32, t: u32) {
        if let Some(Inst::Branch { then, .. }) = self.f.code.get_mut(br as usize) {
            *then = t;
        }
    }

    /// A BOOL condition in a register.
    fn cond(&mut self, e: &Expr) -> Res<u32> {
        match self.expr(e, Some(automat_sema::types::TypeId::BOOL))?.v {
            V::I(r) => Ok(r),
            _ => Err(self.error(e.span, "a BOOL condition is needed".into())),
        }
    }

    /// Body of a test-at-top loop: `br` exits when false, the end jumps to `top`.
    fn loop_body(&mut self, body: &[Stmt], top: u32, br: u32) -> Res<()> {
        self.loops.push(LoopCx {
            continues: Vec::new(),
            exits: Vec::new(),
        });
        self.block(body);
        self.emit(Inst::Jump { target: top });
        let end = self.here();
        self.patch(br, end);
        self.close_loop(top, end);
        Ok(())
    }

    pub(super) fn close_loop(&mut self, cont: u32, end: u32) {
        if let Some(l) = self.loops.pop() {
            for j in l.continues {
                self.patch(j, cont);
            }
            for j in l.exits {
                self.patch(j, end);
            }
        }
    }

    fn case(
        &mut self,
        selector: &Expr,
        arms: &[automat_syntax::ast::CaseArm],
        else_body: Option<&[Stmt]>,
    ) -> Res<()> {
        let sel = self.expr(selector, None)?;
        let V::I(r) = sel.v else {
            return Err(self.error(
                selector.span,
                "CASE needs an integer or enumeration selector".into(),
            ));
        };
        let mut ends = Vec::new();
        for arm in arms {
            // Any label matching jumps to the body.
            let mut to_body = Vec::new();
            for l in &arm.labels {
                let c = match l {
                    CaseLabel::Value(e) => {
                        let k = self.label(e)?;
                        let kr = self.iconst(k);
                        let c = self.reg(RegClass::I64);
                        self.emit(Inst::ICmp {
                            cmp: Cmp::Eq,
                            signed: true,
                            dst: c,
                            a: r,
                            b: kr,
                        });
                        c
                    }
                    CaseLabel::Range(a, b) => {
                        let (ka, kb) = (self.label(a)?, self.label(b)?);
                        let (ra, rb) = (self.iconst(ka), self.iconst(kb));
                        let (c1, c2, c) = (
                            self.reg(RegClass::I64),
                            self.reg(RegClass::I64),
                            self.reg(RegClass::I64),
                        );
                        self.emit(Inst::ICmp {
                            cmp: Cmp::Ge,
                            signed: true,
                            dst: c1,
                            a: r,
                            b: ra,
                        });
                        self.emit(Inst::ICmp {
                            cmp: Cmp::Le,
                            signed: true,
                            dst: c2,
                            a: r,
                            b: rb,
                        });
                        self.emit(Inst::Int {
                            op: IntOp::And,
                            dst: c,
                            a: c1,
                            b: c2,
                        });
                        c
                    }
                };
                let br = self.emit(Inst::Branch {
                    cond: c,
                    then: u32::MAX,
                    els: u32::MAX,
                });
                let next = self.here();
                // The else side continues with the next label.
                if let Some(Inst::Branch { els, .. }) = self.f.code.get_mut(br as usize) {
                    *els = next;
                }
                to_body.push(br);
            }
            let skip = self.jump_fwd();
            let body = self.here();
            for b in to_body {
                self.set_then(b, body);
            }
            self.block(&arm.body);
            ends.push(self.jump_fwd());
            let next = self.here();
            self.patch(skip, next);
        }
        if let Some(b) = else_body {
            self.block(b);
        }
        let end = self.here();
        for j in ends {
            self.patch(j, end);
        }
        Ok(())
    }

    /// The value of a CASE label (a constant).
    fn label(&mut self, e: &Expr) -> Res<i64> {
        match self.typed(e).value.as_ref().and_then(Value::as_int) {
            Some(v) => Ok(v as i64),
            None => Err(self.error(e.span, "CASE label is not a constant integer".into())),
        }
    }
}
