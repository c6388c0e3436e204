//! `GET /api/v1/plant` (the plant model's signals and quantities as the
//! last scan left them, and the mimic it declares) and `POST
//! /api/v1/plant` (an operator presses, releases, sets or frees a
//! signal), both run on the scan thread between two scans by the
//! session, as `automat run --live`'s `press Pornire` is.

use crate::api::{authorize, error, session_error};
use crate::auth::Role;
use crate::App;
use automat_plant::Value as PV;
use automat_session::plant::Op;
use axum::body::Bytes;
use axum::extract::{RawQuery, State as Ax};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use serde::Deserialize;
use serde_json::{json, Value};
use std::sync::Arc;

fn value(v: PV) -> Value {
    match v {
        PV::Bool(b) => json!(b),
        PV::Int(i) => json!(i),
        PV::Real(r) => json!(r),
    }
}

pub async fn get(Ax(app): Ax<App>, headers: HeaderMap, RawQuery(q): RawQuery) -> Response {
    if let Err(r) = authorize(&app, &headers, q.as_deref(), Role::Viewer, "read the plant") {
        return r.into_response();
    }
    let session = Arc::clone(&app.session);
    let view = match tokio::task::spawn_blocking(move || session.plant()).await {
        Ok(Ok(Some(v))) => v,
        Ok(Ok(None)) => {
            return error(
                StatusCode::NOT_FOUND,
                "this run has no plant (run a project folder with a [plant])",
            )
        }
        Ok(Err(e)) => return session_error(&e),
        Err(_) => return error(StatusCode::INTERNAL_SERVER_ERROR, "the request failed"),
    };
    let signals: Vec<Value> = view
        .signals
        .iter()
        .map(|s| {
            json!({
                "name": s.name, "dir": s.dir, "kind": s.kind, "doc": s.doc,
                "value": value(s.value), "bound": s.bound, "stuck": s.stuck,
            })
        })
        .collect();
    let quantities: Vec<Value> = view
        .quantities
        .iter()
        .map(|q| json!({ "name": q.name, "unit": q.unit, "doc": q.doc, "value": q.value }))
        .collect();
    let commands: Vec<Value> = view
        .commands
        .iter()
        .map(|(n, d)| json!({ "name": n, "doc": d }))
        .collect();
    axum::Json(json!({
        "model": view.model,
        "mimic": view.mimic,
        "plc_time_ns": view.now_ns,
        "signals": signals,
        "quantities": quantities,
        "commands": commands,
    }))
    .into_response()
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OpReq {
    action: String,
    signal: String,
    value: Option<Value>,
    for_ms: Option<u64>,
}

/// The operation a body asks for, or why it is malformed.
fn op(req: OpReq) -> Result<Op, String> {
    let signal = req.signal;
    let no_value = |what: &str| match req.value {
        Some(_) => Err(format!("`{what}` takes no `value`")),
        None => Ok(()),
    };
    match req.action.as_str() {
        "press" => {
            no_value("press")?;
            let for_ns = match req.for_ms {
                Some(0) => return Err("`for_ms` must be more than 0".into()),
                Some(ms) => Some(i64::try_from(ms.saturating_mul(1_000_000)).unwrap_or(i64::MAX)),
                None => None,
            };
            Ok(Op::Press { signal, for_ns })
        }
        "release" | "unstick" if req.for_ms.is_some() => {
            Err(format!("`{}` takes no `for_ms`", req.action))
        }
        "release" => no_value("release").map(|()| Op::Release { signal }),
        "unstick" => no_value("unstick").map(|()| Op::Unstick { signal }),
        "set" => {
            if req.for_ms.is_some() {
                return Err("`set` takes no `for_ms`".into());
            }
            let value = match req.value {
                Some(Value::String(s)) => s,
                Some(Value::Bool(b)) => if b { "TRUE" } else { "FALSE" }.to_string(),
                Some(Value::Number(n)) => n.to_string(),
                _ => return Err("`set` needs a `value`: a boolean, a number or a string".into()),
            };
            Ok(Op::Set { signal, value })
        }
        other => Err(format!(
            "unknown action `{other}`: press, release, set or unstick"
        )),
    }
}

pub async fn post(Ax(app): Ax<App>, headers: HeaderMap, body: Bytes) -> Response {
    if let Err(r) = authorize(&app, &headers, None, Role::Operator, "operate the plant") {
        return r.into_response();
    }
    let req: OpReq = match serde_json::from_slice(&body) {
        Ok(r) => r,
        Err(e) => return error(StatusCode::BAD_REQUEST, format!("malformed request: {e}")),
    };
    let op = match op(req) {
        Ok(o) => o,
        Err(m) => return error(StatusCode::BAD_REQUEST, m),
    };
    let session = Arc::clone(&app.session);
    match tokio::task::spawn_blocking(move || session.plant_op(op)).await {
        Ok(Ok(())) => axum::Json(json!({ "ok": true })).into_response(),
        Ok(Err(e)) => session_error(&e),
        Err(_) => error(StatusCode::INTERNAL_SERVER_ERROR, "the request failed"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(text: &str) -> Result<Op, String> {
        op(serde_json::from_str(text).map_err(|e| e.to_string())?)
    }

    #[test]
    fn bodies_name_one_operation() {
        assert_eq!(
            req(r#"{"action": "press", "signal": "Pornire", "for_ms": 200}"#),
            Ok(Op::Press {
                signal: "Pornire".into(),
                for_ns: Some(200_000_000)
            })
        );
        assert_eq!(
            req(r#"{"action": "set", "signal": "Speed1", "value": 6000}"#),
            Ok(Op::Set {
                signal: "Speed1".into(),
                value: "6000".into()
            })
        );
        assert_eq!(
            req(r#"{"action": "set", "signal": "l1", "value": true}"#),
            Ok(Op::Set {
                signal: "l1".into(),
                value: "TRUE".into()
            })
        );
        assert_eq!(
            req(r#"{"action": "release", "signal": "Pornire", "value": 1}"#),
            Err("`release` takes no `value`".into())
        );
        assert_eq!(
            req(r#"{"action": "press", "signal": "Pornire", "for_ms": 0}"#),
            Err("`for_ms` must be more than 0".into())
        );
        assert_eq!(
            req(r#"{"action": "kick", "signal": "Pornire"}"#),
            Err("unknown action `kick`: press, release, set or unstick".into())
        );
    }
}
