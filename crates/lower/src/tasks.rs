//! Program instances and tasks: from the CONFIGURATION, or one implicit
//! cyclic task running the single PROGRAM (or the one `--program` names).

use crate::cx::Cx;
use crate::LowerOptions;
use automat_base::{Code, Diagnostic, Span};
use automat_ir::{ProgramInstance, TaskDef};
use automat_sema::PouId;
use automat_syntax::ast::{Arg, PouKind, Retain};

pub struct Inst {
    pub name: String,
    pub pou: PouId,
    /// (config, resource, task) indexes; `None`: the implicit task.
    pub task: Option<(usize, usize, u32)>,
    pub retain: Retain,
    /// The configuration's connections of its inputs and outputs.
    pub conns: Vec<Arg>,
    /// The function the task runs: the program's, or the code storing the
    /// connections around it (`gen::connect`).
    pub func: u32,
}

/// The program instances; `every_program`: without a CONFIGURATION, one of
/// each PROGRAM (see `crate::check`).
pub fn instances(
    cx: &mut Cx,
    opts: &LowerOptions,
    every_program: bool,
) -> Result<Vec<Inst>, Diagnostic> {
    let model = cx.model;
    let name = |s| cx.interner.name(s).to_string();
    if !model.configs.is_empty() {
        let mut out = Vec::new();
        for (ci, c) in model.configs.iter().enumerate() {
            for (ri, r) in c.resources.iter().enumerate() {
                for p in &r.programs {
                    out.push(Inst {
                        name: name(p.name),
                        pou: p.pou,
                        task: p.task.map(|t| (ci, ri, t)),
                        retain: p.retain,
                        conns: p.conns.clone(),
                        func: p.pou.0,
                    });
                }
            }
        }
        return Ok(out);
    }
    let programs: Vec<(usize, &automat_sema::model::Pou)> = model
        .pous
        .iter()
        .enumerate()
        .filter(|(_, p)| p.kind == PouKind::Program && !p.builtin)
        .collect();
    if every_program {
        return Ok(programs
            .iter()
            .map(|(i, p)| Inst {
                name: name(p.name),
                pou: PouId(*i as u32),
                task: None,
                retain: Retain::Unspecified,
                conns: Vec::new(),
                func: *i as u32,
            })
            .collect());
    }
    let chosen = match &opts.program {
        Some(want) => programs
            .iter()
            .find(|(_, p)| cx.interner.name(p.name).eq_ignore_ascii_case(want))
            .ok_or_else(|| {
                let names: Vec<String> = programs.iter().map(|(_, p)| name(p.name)).collect();
                Diagnostic::error(
                    Code::E090,
                    Span::default(),
                    format!(
                        "no PROGRAM named {want} (the project has: {})",
                        names.join(", ")
                    ),
                )
            })?,
        None => match programs.as_slice() {
            [one] => one,
            [] => {
                return Err(Diagnostic::error(
                    Code::E090,
                    Span::default(),
                    "the project has no PROGRAM and no CONFIGURATION: nothing to run",
                ))
            }
            [_, second, ..] => {
                let names: Vec<String> = programs.iter().map(|(_, p)| name(p.name)).collect();
                return Err(Diagnostic::error(
                    Code::E090,
                    second.1.span,
                    format!(
                        "several PROGRAMs ({}) and no CONFIGURATION: choose one with --program",
                        names.join(", ")
                    ),
                ));
            }
        },
    };
    Ok(vec![Inst {
        name: name(chosen.1.name),
        pou: PouId(chosen.0 as u32),
        task: None,
        retain: Retain::Unspecified,
        conns: Vec::new(),
        func: chosen.0 as u32,
    }])
}

pub fn task_defs(cx: &Cx, insts: &[Inst], offsets: &[u32]) -> Vec<TaskDef> {
    let pi = |i: &Inst, off: u32| ProgramInstance {
        name: i.name.clone(),
        func: i.func,
        instance_offset: off,
    };
    let mut tasks: Vec<TaskDef> = Vec::new();
    let mut keys: Vec<Option<(usize, usize, u32)>> = Vec::new();
    for (ci, c) in cx.model.configs.iter().enumerate() {
        for (ri, r) in c.resources.iter().enumerate() {
            for (ti, t) in r.tasks.iter().enumerate() {
                keys.push(Some((ci, ri, ti as u32)));
                tasks.push(TaskDef {
                    name: cx.interner.name(t.name).to_string(),
                    interval_ns: t.interval.and_then(|v| i64::try_from(v).ok()),
                    priority: t.priority.and_then(|v| u32::try_from(v).ok()).unwrap_or(0),
                    single: t
                        .single
                        .and_then(|s| cx.globals.get(&s))
                        .map(|g| (g.0, g.1)),
                    programs: Vec::new(),
                    watchdog: Default::default(),
                });
            }
        }
    }
    for (i, off) in insts.iter().zip(offsets) {
        match keys.iter().position(|k| *k == i.task) {
            Some(k) => {
                if let Some(t) = tasks.get_mut(k) {
                    t.programs.push(pi(i, *off));
                }
            }
            None => {
                // A program without a task (or no configuration): the implicit cyclic task.
                keys.push(None);
                tasks.push(TaskDef {
                    name: if cx.model.configs.is_empty() {
                        i.name.clone()
                    } else {
                        "DEFAULT".into()
                    },
                    interval_ns: None,
                    priority: 0,
                    single: None,
                    programs: vec![pi(i, *off)],
                    watchdog: Default::default(),
                });
            }
        }
    }
    tasks
}
