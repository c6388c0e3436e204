//! `[tasks.NAME]` of `automat.toml`: per-task settings applied to the
//! lowered program's tasks (today the watchdog: `watchdog = "100ms"` or
//! `"off"`, `sensitivity = n` consecutive overruns).
//!
//! NAME is a TASK of the program's CONFIGURATION, or the implicit task of a
//! program without one, which is named as the PROGRAM it runs (`DEFAULT`
//! when a configuration leaves some program without a task). Names compare
//! case-insensitively, as IEC names do.

use automat_base::{Code, Diagnostic, Span};
use automat_ir::{Program, TaskWatchdog};

/// One `[tasks.NAME]` table.
#[derive(Clone, Debug, PartialEq)]
pub struct TaskSpec {
    pub name: String,
    pub name_span: Span,
    /// `Default` when the table has no `watchdog`.
    pub watchdog: TaskWatchdog,
}

/// Sets the settings of every `[tasks.NAME]` on the task of that name; a
/// name that is no task of `program` is an E300 naming the tasks it has.
pub fn apply(specs: &[TaskSpec], program: &mut Program) -> Result<(), Vec<Diagnostic>> {
    let mut errors = Vec::new();
    for spec in specs {
        match program
            .tasks
            .iter_mut()
            .find(|t| t.name.eq_ignore_ascii_case(&spec.name))
        {
            Some(t) => t.watchdog = spec.watchdog,
            None => {
                let names: Vec<&str> = program.tasks.iter().map(|t| t.name.as_str()).collect();
                errors.push(
                    Diagnostic::error(
                        Code::E300,
                        spec.name_span,
                        format!(
                            "[tasks.{}]: the program has no task `{}`",
                            spec.name, spec.name
                        ),
                    )
                    .with_note(format!("its tasks: {}", names.join(", "))),
                );
            }
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}
