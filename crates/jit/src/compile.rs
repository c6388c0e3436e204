//! Compiles every function of a [`Program`] into one Cranelift JIT module:
//! the host ISA, one declaration per POU (direct calls between them), the
//! Rust helpers imported by name, then [`crate::translate`] per function.

use crate::instances;
use crate::rt::{self, BuiltinCall};
use crate::translate::{self, Helpers};
use crate::JitError;
use automat_ir::code::Inst;
use automat_ir::Program;
use cranelift_codegen::control::ControlPlane;
use cranelift_codegen::ir::{types, AbiParam, InstBuilder, Signature, UserFuncName};
use cranelift_codegen::isa::{CallConv, TargetIsa};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_codegen::Context;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, FuncId, Linkage, Module, ModuleReloc};

/// The signature of a compiled POU: `(ctx: *mut RunCtx, this: u64) -> status`
/// (0 ok, 1 fault recorded in the context).
pub type EntryFn = unsafe extern "C" fn(*mut rt::RunCtx, u64) -> i32;

pub struct Compiled {
    pub module: JITModule,
    /// `None`: not reachable from any task, not compiled.
    pub entries: Vec<Option<EntryFn>>,
    pub builtins: Vec<BuiltinCall>,
    /// `Some(bound)`: the function was compiled without an entry check,
    /// for instances `this` with `this + bound <= image size` only
    /// (`instances.rs`).
    pub bounds: Vec<Option<u64>>,
}

fn err(what: impl std::fmt::Display) -> JitError {
    JitError::Backend(what.to_string())
}

/// Functions longer than this many IR instructions are compiled with
/// Cranelift's `opt_level = "none"`. Why: the egraph pass looks up a
/// block's depth in its scope stack linearly, so a body whose dominator
/// tree is deep (a CASE or an ELSIF chain of thousands of arms) compiles
/// in time quadratic in its length; 20,000 ELSIF arms took 1.02 s with it
/// and 0.77 s without, and 20,000 CASE arms 1.47 s and 0.89 s
/// (`benches/compile_size.rs`). A body that long is straight-line control
/// code, where the egraph's rewrites gain little. The compute kernels are
/// hundreds of instructions long and keep `speed`.
pub const QUICK_CODE: usize = crate::promote::MAX_CODE;

fn isa(opt_level: &str) -> Result<std::sync::Arc<dyn TargetIsa>, JitError> {
    let mut flags = settings::builder();
    for (k, v) in [
        ("opt_level", opt_level),
        ("use_colocated_libcalls", "false"),
        ("is_pic", "false"),
        (
            "enable_verifier",
            if cfg!(debug_assertions) {
                "true"
            } else {
                "false"
            },
        ),
    ] {
        flags.set(k, v).map_err(err)?;
    }
    cranelift_native::builder()
        .map_err(err)?
        .finish(settings::Flags::new(flags))
        .map_err(err)
}

fn module() -> Result<JITModule, JitError> {
    let mut b = JITBuilder::with_isa(isa("speed")?, default_libcall_names());
    b.symbol("automat_jit_fault", rt::jit_fault as *const u8);
    b.symbol("automat_jit_builtin", rt::jit_builtin as *const u8);
    b.symbol("automat_jit_copy", rt::jit_copy as *const u8);
    b.symbol("automat_jit_poll", rt::jit_poll as *const u8);
    Ok(JITModule::new(b))
}

fn sig(m: &JITModule, params: &[types::Type], ret: bool) -> Signature {
    let mut s = m.make_signature();
    s.params.extend(params.iter().map(|t| AbiParam::new(*t)));
    if ret {
        s.returns.push(AbiParam::new(types::I32));
    }
    s
}

/// Compiles all functions; `Err` if the backend refuses something.
/// `counted`: with the instruction budget's bookkeeping (see
/// `translate.rs`); `flag`: the address of the interrupt flag the code
/// polls, alive as long as the code.
pub fn compile(program: &Program, counted: bool, flag: i64) -> Result<Compiled, JitError> {
    let mut m = module()?;
    let ptr = m.target_config().pointer_type();
    let i64t = types::I64;
    let pou_sig = sig(&m, &[ptr, i64t], true);
    let mut ids: Vec<FuncId> = Vec::with_capacity(program.funcs.len());
    // The variant with every `This` access checked, for functions that have
    // such accesses (see `Helpers::checked`).
    let mut checked_ids: Vec<Option<(FuncId, u64)>> = Vec::with_capacity(program.funcs.len());
    let bounds = instances::static_bounds(program);
    for (i, f) in program.funcs.iter().enumerate() {
        ids.push(
            m.declare_function(&format!("pou{i}"), Linkage::Local, &pou_sig)
                .map_err(err)?,
        );
        let extent = translate::this_extent(f);
        let is_static = bounds.get(i).copied().flatten().is_some();
        checked_ids.push(if extent > 0 && !is_static {
            let id = m
                .declare_function(&format!("pou{i}_checked"), Linkage::Local, &pou_sig)
                .map_err(err)?;
            Some((id, extent))
        } else {
            None
        });
    }
    let fault = m
        .declare_function(
            "automat_jit_fault",
            Linkage::Import,
            &sig(&m, &[ptr, i64t, i64t, i64t, i64t, i64t, i64t], false),
        )
        .map_err(err)?;
    let builtin = m
        .declare_function(
            "automat_jit_builtin",
            Linkage::Import,
            &sig(&m, &[ptr, i64t, ptr], true),
        )
        .map_err(err)?;
    let copy = m
        .declare_function(
            "automat_jit_copy",
            Linkage::Import,
            &sig(&m, &[ptr, i64t, i64t, i64t, i64t], true),
        )
        .map_err(err)?;

    let poll_rt = m
        .declare_function(
            "automat_jit_poll",
            Linkage::Import,
            &sig(&m, &[ptr, i64t, i64t, i64t], true),
        )
        .map_err(err)?;
    let poll = poll_trampoline(&mut m, poll_rt, &[ptr, i64t, i64t, i64t])?;

    let mut builtins = Vec::new();
    let mut ctx = m.make_context();
    let mut fctx = FunctionBuilderContext::new();
    let wanted = reachable(program);
    // `AUTOMAT_JIT_DUMP=1`: print every function's Cranelift IR and
    // machine code to stderr (for profiling generated code).
    let dump = std::env::var_os("AUTOMAT_JIT_DUMP").is_some();
    // The ISA for functions longer than `QUICK_CODE`, made when one is met.
    let mut quick: Option<std::sync::Arc<dyn TargetIsa>> = None;
    for (i, f) in program.funcs.iter().enumerate() {
        if !wanted.get(i).copied().unwrap_or(false) {
            continue;
        }
        let twin = checked_ids.get(i).copied().flatten();
        // The checked variant first (when there is one), then the entry.
        let variants = twin
            .map(|(id, _)| (id, false))
            .into_iter()
            .chain([(*ids.get(i).ok_or_else(|| err("function ids"))?, true)]);
        for (id, entry) in variants {
            ctx.func.signature = pou_sig.clone();
            ctx.func.name = UserFuncName::user(u32::from(!entry), i as u32);
            let mut refs = Vec::new();
            for inst in &f.code {
                if let Inst::Call { func: c, .. } = inst {
                    let cid = *ids
                        .get(*c as usize)
                        .ok_or_else(|| err(format!("no function {c}")))?;
                    refs.push((*c, m.declare_func_in_func(cid, &mut ctx.func)));
                }
            }
            let checked = match (entry, twin) {
                (true, Some((cid, extent))) => {
                    Some((m.declare_func_in_func(cid, &mut ctx.func), extent))
                }
                _ => None,
            };
            let helpers = Helpers {
                fault: m.declare_func_in_func(fault, &mut ctx.func),
                builtin: m.declare_func_in_func(builtin, &mut ctx.func),
                copy: m.declare_func_in_func(copy, &mut ctx.func),
                poll: m.declare_func_in_func(poll, &mut ctx.func),
                counted,
                flag,
                callees: refs,
                checked,
                static_this: bounds.get(i).copied().flatten().is_some(),
                ptr,
                target: m.target_config(),
            };
            translate::function(
                &mut ctx.func,
                &mut fctx,
                f,
                i as u32,
                &helpers,
                &mut builtins,
                &program.funcs,
            )?;
            if dump {
                ctx.set_disasm(true);
            }
            if f.code.len() > QUICK_CODE {
                let isa = match &quick {
                    Some(isa) => isa.clone(),
                    None => quick.insert(isa("none")?).clone(),
                };
                define_quick(&mut m, &*isa, id, &mut ctx)
                    .map_err(|e| err(format!("{}: {e}", f.name)))?;
            } else {
                m.define_function(id, &mut ctx)
                    .map_err(|e| err(format!("{}: {e:?}", f.name)))?;
            }
            if dump {
                eprintln!("=== {} entry={entry}\n{}", f.name, ctx.func.display());
                if let Some(c) = ctx.compiled_code() {
                    eprintln!("{}", c.vcode.as_deref().unwrap_or(""));
                }
            }
            m.clear_context(&mut ctx);
        }
    }
    m.finalize_definitions().map_err(err)?;
    let entries = ids
        .iter()
        .zip(&wanted)
        .map(|(id, &w)| {
            if !w {
                return None;
            }
            let p = m.get_finalized_function(*id);
            // SAFETY: `p` is the entry of a function compiled above with
            // `pou_sig`, i.e. the platform C convention with a pointer and a
            // u64 argument and an i32 result, exactly `EntryFn`; the module
            // that owns the code lives as long as these pointers (both are
            // fields of the `Jit`, and the module is freed only in its Drop).
            Some(unsafe { std::mem::transmute::<*const u8, EntryFn>(p) })
        })
        .collect();
    Ok(Compiled {
        module: m,
        entries,
        builtins,
        bounds,
    })
}

/// Compiles `ctx`'s function with `isa` (not the module's own) and
/// defines it in `m` as that code and its relocations, as
/// `Module::define_function` does with the module's ISA.
fn define_quick(
    m: &mut JITModule,
    isa: &dyn TargetIsa,
    id: FuncId,
    ctx: &mut Context,
) -> Result<(), String> {
    let (align, bytes, relocs) = {
        let code = ctx
            .compile(isa, &mut ControlPlane::default())
            .map_err(|e| format!("{:?}", e.inner))?;
        (
            code.buffer.alignment as u64,
            code.code_buffer().to_vec(),
            code.buffer.relocs().to_vec(),
        )
    };
    let relocs: Vec<ModuleReloc> = relocs
        .iter()
        .map(|r| ModuleReloc::from_mach_reloc(r, &ctx.func, id))
        .collect();
    m.define_function_bytes(id, align, &bytes, &relocs)
        .map_err(|e| format!("{e:?}"))
}

/// A function with the `preserve_all` convention (it saves every register
/// it or its callee touches) that calls `rt::jit_poll` and leaves the
/// status in `RunCtx::polled`. Why: a loop header's poll is a call on a
/// cold path, but a call with the ordinary convention clobbers the
/// caller-saved registers, so the register allocator kept loop variables
/// live across it on the stack (the sieve's `j` went through memory on
/// every iteration). Through this trampoline the call clobbers nothing.
fn poll_trampoline(
    m: &mut JITModule,
    poll_rt: FuncId,
    params: &[types::Type],
) -> Result<FuncId, JitError> {
    let mut s = sig(m, params, false);
    s.call_conv = CallConv::PreserveAll;
    let id = m
        .declare_function("automat_poll_trampoline", Linkage::Local, &s)
        .map_err(err)?;
    let mut ctx = m.make_context();
    ctx.func.signature = s;
    ctx.func.name = UserFuncName::user(2, 0);
    let target = m.declare_func_in_func(poll_rt, &mut ctx.func);
    let mut fctx = FunctionBuilderContext::new();
    let mut b = FunctionBuilder::new(&mut ctx.func, &mut fctx);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    let args = b.block_params(entry).to_vec();
    let call = b.ins().call(target, &args);
    let status = b
        .inst_results(call)
        .first()
        .copied()
        .ok_or_else(|| err("poll result"))?;
    let ctx_ptr = args.first().copied().ok_or_else(|| err("poll context"))?;
    b.ins()
        .store(translate::mem(), status, ctx_ptr, rt::OFF_POLLED);
    b.ins().return_(&[]);
    b.seal_all_blocks();
    b.finalize(m.target_config());
    m.define_function(id, &mut ctx)
        .map_err(|e| err(format!("poll trampoline: {e:?}")))?;
    m.clear_context(&mut ctx);
    Ok(id)
}

/// The functions the tasks can run (all of them when there are no tasks,
/// as in tests that run functions directly): compiling only these keeps
/// the load time of a program proportional to what it uses, not to the
/// whole standard library.
fn reachable(program: &Program) -> Vec<bool> {
    let n = program.funcs.len();
    let roots: Vec<usize> = program
        .tasks
        .iter()
        .flat_map(|t| t.programs.iter().map(|p| p.func as usize))
        .collect();
    if roots.is_empty() {
        return vec![true; n];
    }
    let mut seen = vec![false; n];
    let mut todo = roots;
    while let Some(f) = todo.pop() {
        match seen.get_mut(f) {
            Some(s) if !*s => *s = true,
            _ => continue,
        }
        if let Some(func) = program.funcs.get(f) {
            for inst in &func.code {
                if let Inst::Call { func, .. } = inst {
                    todo.push(*func as usize);
                }
            }
        }
    }
    seen
}
