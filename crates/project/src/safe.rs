//! The safe state of a project run: the runtime's default (the %Q area and
//! every program VAR_OUTPUT to 0/FALSE), every variable a plant actuator is
//! bound to (so the plant sees its actuators in the safe state whatever
//! kind of variable drives them), then the `[safe_state]` values of
//! `automat.toml`.

use crate::bind::Binding;
use crate::file::Project;
use automat_base::{Code, Diagnostic};
use automat_ir::Program;
use automat_plant::{Dir, Plant};
use automat_runtime::{resolve, SafeState};

/// The safe state of `program` in `project`, with `plant` bound by
/// `bindings` (`None` without a plant). Errors point at the
/// `[safe_state]` keys.
pub fn build(
    project: &Project,
    program: &Program,
    plant: Option<(&dyn Plant, &[Binding])>,
) -> Result<SafeState, Vec<Diagnostic>> {
    let mut safe = SafeState::of_program(program);
    if let Some((plant, bindings)) = plant {
        for b in bindings {
            let actuator = plant
                .signals()
                .get(b.signal)
                .is_some_and(|s| s.dir == Dir::Actuator);
            if actuator {
                safe.add_zero(&b.path, &b.place);
            }
        }
    }
    let mut errors = Vec::new();
    for spec in &project.safe_state {
        let place = match resolve(program, &spec.target) {
            Ok(p) => p,
            Err(e) => {
                // An actuator signal's name stands for the place it drives.
                let signal = plant.and_then(|(plant, bindings)| {
                    let i = plant
                        .signals()
                        .iter()
                        .position(|s| s.name.eq_ignore_ascii_case(&spec.target))?;
                    bindings.iter().find(|b| b.signal == i)
                });
                match signal {
                    Some(b) => b.place.clone(),
                    None => {
                        errors.push(Diagnostic::error(
                            Code::E300,
                            spec.span,
                            format!("[safe_state] `{}`: {e}", spec.target),
                        ));
                        continue;
                    }
                }
            }
        };
        if let Err(e) = safe.set_literal(&spec.target, &place, &spec.value) {
            errors.push(Diagnostic::error(
                Code::E300,
                spec.span,
                format!("[safe_state] `{}`: {e}", spec.target),
            ));
        }
    }
    if errors.is_empty() {
        Ok(safe)
    } else {
        Err(errors)
    }
}
