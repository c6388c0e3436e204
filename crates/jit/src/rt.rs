//! What generated code sees at run time: the [`RunCtx`] it is passed, and
//! the `extern "C"` helpers it calls for everything that is not worth
//! inlining (faults, standard functions, block copies). The helpers build
//! faults and run builtins through `automat_engine::shared`, so messages and
//! semantics exist once, in the interpreter.

use automat_engine::shared::{builtin, check_range, fault, interrupted, run_str_in_place, Ctx};
use automat_ir::code::{Builtin, CheckKind, MemTy, Reg};
use automat_ir::interrupt::{POLL_COPY_BYTES, POLL_INSTRUCTIONS};
use automat_ir::{Fault, FaultKind, Interrupt, Program};

/// The state of one run. Generated code reads the first four fields at the
/// offsets below (`#[repr(C)]` fixes them); the rest is for the helpers.
#[repr(C)]
pub struct RunCtx {
    /// Start of the image (valid for `image_len` bytes during the run).
    pub image: *mut u8,
    pub image_len: u64,
    /// Watchdog budget left: instructions the run may still execute.
    pub left: i64,
    /// The scan time in ns (`Inst::Now`).
    pub now: i64,
    pub shared: *const Shared,
    /// Loop headers poll the interrupt flag ([`jit_poll`]) when `left`
    /// falls below this.
    pub mark: i64,
    /// The fault a helper recorded before generated code returned status 1.
    pub fault: Option<Fault>,
    /// What the last [`jit_poll`] returned, written by the poll trampoline
    /// (`compile.rs`), whose calling convention has no return value.
    pub polled: i32,
}

pub const OFF_IMAGE: i32 = std::mem::offset_of!(RunCtx, image) as i32;
pub const OFF_LEN: i32 = std::mem::offset_of!(RunCtx, image_len) as i32;
pub const OFF_LEFT: i32 = std::mem::offset_of!(RunCtx, left) as i32;
pub const OFF_NOW: i32 = std::mem::offset_of!(RunCtx, now) as i32;
pub const OFF_MARK: i32 = std::mem::offset_of!(RunCtx, mark) as i32;
pub const OFF_POLLED: i32 = std::mem::offset_of!(RunCtx, polled) as i32;

/// One `Inst::Builtin` of the program, numbered in compile order; generated
/// code passes the number and a slot array holding the argument registers
/// (`0..count`) and room for the result (slot `count`).
pub struct BuiltinCall {
    pub op: Builtin,
    pub func: u32,
    pub site: u32,
    pub has_dst: bool,
    /// `0..count`: the argument "registers" are the slots.
    pub args: Vec<Reg>,
}

/// Per-program data the helpers need; owned by the `Jit`, pointed to by
/// every `RunCtx` of a run.
pub struct Shared {
    pub program: *const Program,
    pub builtins: Vec<BuiltinCall>,
    pub budget: u64,
    /// Raised from outside to stop the run (polled by [`jit_poll`] and
    /// after long copies).
    pub interrupt: Interrupt,
}

// SAFETY: `program` points into the `Box<Program>` of the `Jit` that owns
// this `Shared` (also boxed); both move together to another thread and the
// program is only read. So a whole `Jit` can be handed to another thread
// between runs (`automat test` lends compiled programs to its workers); a
// run itself never crosses threads (`run_func` takes `&mut self`).
unsafe impl Send for Shared {}

/// The first poll mark of a run with `left` instructions of budget.
pub fn first_mark(left: i64) -> i64 {
    left.saturating_sub(POLL_INSTRUCTIONS as i64)
}

/// Called at a loop header when the budget `left` has fallen below
/// `RunCtx::mark`: returns 1 with the fault recorded when the interrupt
/// flag is raised (the site is the header's statement: `pc` of function
/// `func`), else sets the next mark and returns 0.
///
/// # Safety
/// `ctx` as for [`jit_fault`].
pub unsafe extern "C" fn jit_poll(ctx: *mut RunCtx, left: i64, func: i64, pc: i64) -> i32 {
    // SAFETY: see the function's contract.
    let ctx = unsafe { &mut *ctx };
    // SAFETY: `shared` and its program outlive the run (owned by the Jit).
    let shared = unsafe { &*ctx.shared };
    if shared.interrupt.is_raised() {
        let program = unsafe { &*shared.program };
        ctx.fault = Some(interrupt_fault(program, func, pc));
        return 1;
    }
    ctx.mark = first_mark(left);
    0
}

fn interrupt_fault(program: &Program, func: i64, pc: i64) -> Fault {
    let f = func as u32;
    let site = program
        .funcs
        .get(f as usize)
        .and_then(|x| x.stmt_site(pc as u32));
    interrupted(program, f, site)
}

/// Fault kinds passed to [`jit_fault`] (`kind` argument).
pub const F_WATCHDOG: i64 = 0;
pub const F_DIV: i64 = 1;
pub const F_INDEX: i64 = 2;
pub const F_SUBRANGE: i64 = 3;
pub const F_REF: i64 = 4;
/// An access outside the image; `site` says which (`M_*`).
pub const F_MEMORY: i64 = 5;

pub const M_LOAD: i64 = 0;
pub const M_STORE: i64 = 1;
pub const M_BIT_LOAD: i64 = 2;
pub const M_BIT_STORE: i64 = 3;

pub fn check_code(kind: CheckKind) -> i64 {
    match kind {
        CheckKind::Index => F_INDEX,
        CheckKind::Subrange => F_SUBRANGE,
        CheckKind::Ref => F_REF,
    }
}

const MEM_TYS: [MemTy; 9] = [
    MemTy::I8,
    MemTy::U8,
    MemTy::I16,
    MemTy::U16,
    MemTy::I32,
    MemTy::U32,
    MemTy::I64,
    MemTy::F32,
    MemTy::F64,
];

pub fn mem_ty_code(ty: MemTy) -> i64 {
    MEM_TYS.iter().position(|t| *t == ty).unwrap_or(0) as i64
}

/// Builds the fault generated code asks for; see the `F_*` kinds.
///
/// # Safety
/// `ctx` is the `RunCtx` of the current run (generated code only ever
/// passes the pointer it was called with), whose `shared.program` is alive.
pub unsafe extern "C" fn jit_fault(
    ctx: *mut RunCtx,
    kind: i64,
    func: i64,
    site: i64,
    a: i64,
    b: i64,
    c: i64,
) {
    // SAFETY: see the function's contract; nothing else borrows the context
    // while generated code is inside this call.
    let ctx = unsafe { &mut *ctx };
    // SAFETY: `shared` and its program outlive the run (owned by the Jit).
    let shared = unsafe { &*ctx.shared };
    let program = unsafe { &*shared.program };
    ctx.fault = Some(make_fault(
        program,
        shared.budget,
        kind,
        func,
        site,
        a,
        b,
        c,
    ));
}

#[allow(clippy::too_many_arguments)]
fn make_fault(
    program: &Program,
    budget: u64,
    kind: i64,
    func: i64,
    site: i64,
    a: i64,
    b: i64,
    c: i64,
) -> Fault {
    let f = func as u32;
    let bad = |message: String| fault(program, f, None, FaultKind::Function, message);
    match kind {
        F_WATCHDOG => {
            let site = program
                .funcs
                .get(f as usize)
                .and_then(|x| x.stmt_site(site as u32));
            fault(
                program,
                f,
                site,
                FaultKind::Watchdog,
                format!("watchdog: more than {budget} instructions in one run"),
            )
        }
        F_DIV => {
            let what = if b != 0 { "division" } else { "MOD" };
            fault(
                program,
                f,
                Some(site as u32),
                FaultKind::DivisionByZero,
                format!("{what} by zero ({a} / 0)"),
            )
        }
        F_INDEX | F_SUBRANGE | F_REF => {
            let k = match kind {
                F_INDEX => CheckKind::Index,
                F_SUBRANGE => CheckKind::Subrange,
                _ => CheckKind::Ref,
            };
            match check_range(program, f, k, a, b, c, site as u32) {
                Err(e) => e,
                // Generated code only calls this when the check failed.
                Ok(()) => bad(format!("range check of {a} in {b}..{c} passed")),
            }
        }
        F_MEMORY => {
            let ty = MEM_TYS.get(b as usize).copied().unwrap_or(MemTy::U8);
            let at = a as u32;
            bad(match site {
                M_LOAD => format!("load of {ty:?} at {at} outside the image"),
                M_STORE => format!("store of {ty:?} at {at} outside the image"),
                M_BIT_LOAD => format!("bit load at {at} outside the image"),
                _ => format!("bit store at {at} outside the image"),
            })
        }
        _ => bad(format!("unknown fault {kind}")),
    }
}

/// Runs builtin number `index` over `slots`; returns 0, or 1 with the fault
/// recorded in the context.
///
/// # Safety
/// `ctx` as for [`jit_fault`]; `slots` points to `count + 1` u64s in the
/// caller's frame, where `count` is the builtin's argument count.
pub unsafe extern "C" fn jit_builtin(ctx: *mut RunCtx, index: i64, slots: *mut u64) -> i32 {
    // SAFETY: see the function's contract.
    let ctx = unsafe { &mut *ctx };
    let shared = unsafe { &*ctx.shared };
    let program = unsafe { &*shared.program };
    let Some(call) = shared.builtins.get(index as usize) else {
        ctx.fault = Some(fault(
            program,
            0,
            None,
            FaultKind::Function,
            format!("unknown builtin call {index}"),
        ));
        return 1;
    };
    // SAFETY: generated code sized the slot array to the builtin's arguments
    // plus the result; the image pointer and length describe the Jit's image,
    // which nothing else accesses while the helper runs.
    let regs = unsafe { std::slice::from_raw_parts_mut(slots, call.args.len() + 1) };
    let image = unsafe { std::slice::from_raw_parts_mut(ctx.image, ctx.image_len as usize) };
    let mut c = Ctx {
        image,
        regs,
        base: 0,
    };
    let dst = call.has_dst.then_some(call.args.len() as Reg);
    match builtin(&mut c, call.op, dst, &call.args) {
        Ok(()) => 0,
        Err((kind, message)) => {
            ctx.fault = Some(fault(program, call.func, Some(call.site), kind, message));
            1
        }
    }
}

/// `Inst::Copy`: memmove of `len` bytes inside the image, or the
/// interpreter's fault when either range leaves it. Returns 0 or 1.
/// `func` holds the function index in its low 32 bits and the copy's pc
/// in the high ones: a long copy polls the interrupt flag when done, and
/// its fault names the copy's statement.
///
/// # Safety
/// `ctx` as for [`jit_fault`].
pub unsafe extern "C" fn jit_copy(
    ctx: *mut RunCtx,
    func: i64,
    dst: i64,
    src: i64,
    len: i64,
) -> i32 {
    // SAFETY: see the function's contract.
    let ctx = unsafe { &mut *ctx };
    // SAFETY: the image pointer and length describe the Jit's image.
    let image = unsafe { std::slice::from_raw_parts_mut(ctx.image, ctx.image_len as usize) };
    let (d, s, n) = (dst as usize, src as usize, len as usize);
    if d + n > image.len() || s + n > image.len() {
        let shared = unsafe { &*ctx.shared };
        let program = unsafe { &*shared.program };
        ctx.fault = Some(fault(
            program,
            func as u32,
            None,
            FaultKind::Function,
            format!("copy of {n} bytes {s} -> {d} outside the image"),
        ));
        return 1;
    }
    image.copy_within(s..s + n, d);
    let shared = unsafe { &*ctx.shared };
    if len >= i64::from(POLL_COPY_BYTES) && shared.interrupt.is_raised() {
        let program = unsafe { &*shared.program };
        ctx.fault = Some(interrupt_fault(program, func & 0xFFFF_FFFF, func >> 32));
        return 1;
    }
    0
}

/// The string builtins worked in place (`automat_engine::shared::
/// run_str_in_place`: LEN, assignment, LEFT, CONCAT of two, integer to
/// STRING) with the operand bits passed in machine registers: the
/// program's builtin number `index` names the operation. Returns LEN's
/// length (else 0), or -1 when the call is not handled in place (nothing
/// was written): generated code then takes the general path
/// ([`jit_builtin`]), which also produces every fault. Why: through the
/// general entry a string loop spent more time storing slots and
/// dispatching than copying.
///
/// # Safety
/// `ctx` as for [`jit_fault`].
pub unsafe extern "C" fn jit_str(
    ctx: *mut RunCtx,
    index: i64,
    a: i64,
    b: i64,
    c: i64,
    d: i64,
) -> i64 {
    // SAFETY: see the function's contract.
    let ctx = unsafe { &mut *ctx };
    // SAFETY: `shared` outlives the run (owned by the Jit).
    let shared = unsafe { &*ctx.shared };
    let Some(call) = shared.builtins.get(index as usize) else {
        return -1;
    };
    // SAFETY: the image pointer and length describe the Jit's image, which
    // nothing else accesses while the helper runs.
    let image = unsafe { std::slice::from_raw_parts_mut(ctx.image, ctx.image_len as usize) };
    let args = [a as u64, b as u64, c as u64, d as u64];
    match run_str_in_place(image, call.op, args) {
        Some(r) => r.min(i64::MAX as u64) as i64,
        None => -1,
    }
}
