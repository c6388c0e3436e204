//! The RETAIN file of `automat run`: where it is and how often it is saved
//! (command line, else `[retain]` of `automat.toml`), the start-up check
//! and warm start, and the messages of the saves. The logic is
//! `automat_runtime::retain`'s; this is the command's wording and exit codes.

use crate::cmd_run::RunArgs;
use crate::Outcome;
use automat_ir::Program;
use automat_runtime::retain::{self, Loaded};
use automat_runtime::Executor;
use std::path::PathBuf;

/// How often the RETAIN variables are saved while running when neither
/// `--retain-every` nor `save_every` says: a power cut loses at most 10 s.
pub(crate) const DEFAULT_EVERY_NS: i64 = 10_000_000_000;

/// The RETAIN settings of one run.
pub(crate) struct RetainCfg {
    pub path: PathBuf,
    /// Period of saves while running, in PLC time.
    pub every_ns: Option<i64>,
    /// A failed start-up check is a warning, not exit 2.
    pub optional: bool,
}

impl RetainCfg {
    /// From the command line, with the project's `[retain]` as defaults;
    /// `None` when no RETAIN file is named.
    pub fn of(args: &RunArgs, project: Option<&automat_project::RetainSpec>) -> Option<RetainCfg> {
        let path = args
            .retain
            .clone()
            .or_else(|| project.and_then(|p| p.file.clone()))?;
        let every = args
            .retain_every
            .or_else(|| project.and_then(|p| p.save_every_ns))
            .unwrap_or(DEFAULT_EVERY_NS);
        Some(RetainCfg {
            path,
            // 0: only when the run stops.
            every_ns: (every > 0).then_some(every),
            optional: args.retain_optional || project.is_some_and(|p| p.optional),
        })
    }
}

impl RetainCfg {
    /// The file as the session keeps it.
    pub(crate) fn file(&self) -> automat_session::RetainFile {
        automat_session::RetainFile {
            path: self.path.clone(),
            every_ns: self.every_ns,
        }
    }
}

/// Before the first scan: the path is checked (an error, exit 2, unless
/// optional), then the file loaded into the image unless `--cold`.
pub(crate) fn start<E: Executor>(
    engine: &mut E,
    cfg: Option<&RetainCfg>,
    cold: bool,
) -> Result<(), Outcome> {
    check(engine.program(), cfg)?;
    warm(engine, cfg, cold);
    Ok(())
}

/// The start-up check of the RETAIN path: an error (exit 2) unless
/// optional. Done before anything starts (a session, the live view).
pub(crate) fn check(program: &Program, cfg: Option<&RetainCfg>) -> Result<(), Outcome> {
    let Some(cfg) = cfg else {
        return Ok(());
    };
    if let Err(e) = retain::check_path(program, &cfg.path) {
        if !cfg.optional {
            eprintln!("error: RETAIN file {e}");
            eprintln!(
                "note: the PLC did not start; --retain-optional runs it anyway, without keeping RETAIN variables"
            );
            return Err(Outcome::BadInput);
        }
        eprintln!("warning: RETAIN file {e}; running anyway (--retain-optional)");
    }
    Ok(())
}

/// The warm start: the file loaded into the image unless `cold` (a file
/// that does not fit is a warning and a cold start).
pub(crate) fn warm<E: Executor>(engine: &mut E, cfg: Option<&RetainCfg>, cold: bool) {
    let Some(cfg) = cfg else {
        return;
    };
    if cold {
        return;
    }
    let program = engine.program().clone();
    match retain::load(&program, &cfg.path, engine.image_mut()) {
        Loaded::Warm | Loaded::NoFile => {}
        Loaded::Cold(why) => eprintln!("warning: {}: {why}; cold start", cfg.path.display()),
    }
}

/// The messages of the saves of a run: `last` the final save, `failures`
/// periodic saves that failed (`last_error` the last one's message).
pub(crate) fn report(
    last: Result<(), String>,
    failures: u64,
    last_error: Option<&str>,
    cfg: Option<&RetainCfg>,
) -> bool {
    if let Some(e) = last_error {
        eprintln!("warning: {failures} periodic RETAIN save(s) failed; the last: {e}");
    }
    match last {
        Ok(()) => true,
        Err(e) if cfg.is_some_and(|c| c.optional) => {
            eprintln!("warning: {e} (--retain-optional)");
            true
        }
        Err(e) => {
            eprintln!("error: {e}");
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        run: RunArgs,
    }

    fn cfg(args: &[&str], project: Option<&automat_project::RetainSpec>) -> Option<RetainCfg> {
        let cli = Cli::try_parse_from(std::iter::once("run").chain(args.iter().copied()))
            .unwrap_or_else(|e| panic!("{e}"));
        RetainCfg::of(&cli.run, project)
    }

    #[test]
    fn the_command_line_wins_over_the_project_and_10s_is_the_default() {
        assert!(cfg(&["x.st"], None).is_none());
        let c = cfg(&["x.st", "--retain", "a.retain"], None).unwrap();
        assert_eq!(
            (c.path, c.every_ns, c.optional),
            ("a.retain".into(), Some(10_000_000_000), false)
        );
        let c = cfg(
            &["x.st", "--retain", "a.retain", "--retain-every", "0s"],
            None,
        )
        .unwrap();
        assert_eq!(c.every_ns, None);
        let spec = automat_project::RetainSpec {
            file: Some("p/plc.retain".into()),
            save_every_ns: Some(2_000_000_000),
            optional: true,
        };
        let c = cfg(&["p"], Some(&spec)).unwrap();
        assert_eq!(
            (c.path, c.every_ns, c.optional),
            ("p/plc.retain".into(), Some(2_000_000_000), true)
        );
        let c = cfg(
            &["p", "--retain", "b.retain", "--retain-every", "500ms"],
            Some(&spec),
        )
        .unwrap();
        assert_eq!((c.path, c.every_ns), ("b.retain".into(), Some(500_000_000)));
    }
}
