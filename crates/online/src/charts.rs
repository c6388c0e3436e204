//! `GET /api/v1/charts`: the SFC charts of the project as the compiler
//! reads them (`automat_project::charts`), each with the paths of the
//! instances that run it, so a client reads a step's activity and time as
//! `INSTANCE.STEP.X` and `INSTANCE.STEP.T`.

use crate::api::{authorize, error};
use crate::auth::Role;
use crate::App;
use automat_project::charts::PouChart;
use automat_session::Node;
use axum::extract::{RawQuery, State as Ax};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use serde_json::{json, Value};

/// The paths of the instances of `pou`: FB instances of that type, and
/// program instances (typed `PROGRAM` in the tree) holding every step of
/// the chart as a `STEP` member.
fn instances(nodes: &[Node], pou: &str, steps: &[&str], out: &mut Vec<String>) {
    for n in nodes {
        let holds_steps = !steps.is_empty()
            && steps.iter().all(|s| {
                n.children
                    .iter()
                    .any(|c| c.ty == "STEP" && c.name.eq_ignore_ascii_case(s))
            });
        if n.ty.eq_ignore_ascii_case(pou) || (n.ty == "PROGRAM" && holds_steps) {
            out.push(n.path.clone());
        } else {
            instances(&n.children, pou, steps, out);
        }
    }
}

/// The answer: every chart with its instances (computed once per server).
pub fn answer(charts: &[PouChart], tree: &[Node]) -> Value {
    let list: Vec<Value> = charts
        .iter()
        .map(|c| {
            let mut at = Vec::new();
            let steps: Vec<&str> = c.chart.steps.iter().map(|s| s.name.as_str()).collect();
            instances(tree, &c.pou, &steps, &mut at);
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
