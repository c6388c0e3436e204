//! `--realtime` and `[runtime]`: which real-time mode a run asks for, and
//! entering it on the scan thread with the messages a user needs (what the
//! mode is, why the system refused it). See docs/realtime.md.

use crate::cmd_run::RunArgs;
use crate::Outcome;
use automat_runtime::realtime::{self, Realtime};

/// The real-time mode of this run, if any. `real_time`: the run is on the
/// real-time clock. `--realtime` on the virtual clock is refused; a
/// project's `realtime = true` applies to its real-time runs only (its
/// scenarios keep running on the virtual clock).
pub(crate) fn settings(
    args: &RunArgs,
    project: Option<&automat_project::Project>,
    real_time: bool,
) -> Result<Option<Realtime>, Outcome> {
    let from_project = project.is_some_and(|p| p.runtime.realtime);
    if !args.realtime && (args.rt_priority.is_some() || args.cpus.is_some()) {
        eprintln!("error: --rt-priority and --cpus apply with --realtime (or `[runtime] realtime = true`)");
        return Err(Outcome::BadInput);
    }
    if args.realtime && !real_time {
        eprintln!(
            "error: --realtime applies to real-time runs; this one is on the virtual clock (--cycles, --duration, --scenario or --virtual-clock)"
        );
        return Err(Outcome::BadInput);
    }
    if !(args.realtime || from_project && real_time) {
        return Ok(None);
    }
    let mut rt = project
        .map(|p| p.runtime.settings.clone())
        .unwrap_or_default();
    if let Some(p) = args.rt_priority {
        rt.priority = p;
    }
    if let Some(c) = &args.cpus {
        rt.cpus = realtime::parse_cpus(c).map_err(|e| {
            eprintln!("error: --cpus: {e}");
            Outcome::BadInput
        })?;
    }
    rt.validate().map_err(|e| {
        eprintln!("error: {e}");
        Outcome::BadInput
    })?;
    Ok(Some(rt))
}

/// The notes printed when the mode is entered.
pub(crate) fn announce(rt: &Realtime) {
    eprintln!("note: real-time mode: {}", rt.describe());
    if let Some(n) = realtime::kernel_note() {
        eprintln!("note: {n}");
    }
}

/// Enters the mode on this thread (the one that will run the scans).
pub(crate) fn enter_here(rt: &Realtime) -> Result<(), Outcome> {
    realtime::enter(rt).map_err(|e| {
        eprintln!("error: {e}");
        Outcome::BadInput
    })?;
    announce(rt);
    Ok(())
}
