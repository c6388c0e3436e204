//! `GET /api/v1/charts`: the SFC charts of the project as the compiler
//! reads them (`automat_project::charts`), each with the paths of the
//! instances that run it, so a client reads a step's activity and time as
//! `INSTANCE.STEP.X` and `INSTANCE.STEP.T`.

use crate::api::{authorize, error};
use crate::auth::Role;
use crate::App;
use automat_ir::Program;
use automat_project::charts::PouChart;
use automat_session::Node;
use axum::extract::{RawQuery, State as Ax};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use serde_json::{json, Value};

/// The paths of the FB instances of type `pou` in the tree.
fn fb_instances(nodes: &[Node], pou: &str, out: &mut Vec<String>) {
    for n in nodes {
        if n.ty.eq_ignore_ascii_case(pou) {
            out.push(n.path.clone());
        } else {
            fb_instances(&n.children, pou, out);
        }
    }
}

/// The paths of the program instances of `pou`, as the configuration's
/// tasks run them (`PROGRAM Ctrl WITH MainTask : Crane` gives `Ctrl`), in
/// task order, each once.
fn program_instances(program: &Program, pou: &str, out: &mut Vec<String>) {
    for inst in program.tasks.iter().flat_map(|t| &t.programs) {
        let runs_pou = usize::try_from(inst.func)
            .ok()
            .and_then(|f| program.funcs.get(f))
            .is_some_and(|f| f.name.eq_ignore_ascii_case(pou));
        if runs_pou && !out.iter().any(|p| p.eq_ignore_ascii_case(&inst.name)) {
            out.push(inst.name.clone());
        }
    }
}

/// The paths of the instances that run POU `pou`: program instances in
/// task order, then function block instances in the tree.
pub fn instances_of(pou: &str, program: &Program, tree: &[Node]) -> Vec<String> {
    let mut at = Vec::new();
    program_instances(program, pou, &mut at);
    fb_instances(tree, pou, &mut at);
    at
}

/// The answer: every chart with its instances (computed once per server).
pub fn answer(charts: &[PouChart], program: &Program, tree: &[Node]) -> Value {
    let list: Vec<Value> = charts
        .iter()
        .map(|c| {
            let at = instances_of(&c.pou, program, tree);
            let mut v = serde_json::to_value(c).unwrap_or(Value::Null);
            v["instances"] = json!(at);
            v
        })
        .collect();
    json!({ "charts": list })
}

pub async fn charts(Ax(app): Ax<App>, headers: HeaderMap, RawQuery(q): RawQuery) -> Response {
    if let Err(r) = authorize(
        &app,
        &headers,
        q.as_deref(),
        Role::Viewer,
        "read the charts",
    ) {
        return r.into_response();
    }
    match app.charts.as_ref() {
        Some(v) => axum::Json(v.clone()).into_response(),
        None => error(StatusCode::SERVICE_UNAVAILABLE, "the charts are not known"),
    }
}
