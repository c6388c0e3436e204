//! The HTTP/JSON endpoints of `docs/online-api.md` over the session.
//!
//! Every endpoint but `login` needs a bearer token; bodies are parsed
//! here (not by an extractor) so a malformed one gets `400 {"error"}`
//! like every other refusal. Calls that wait for the scan thread's answer
//! run on the blocking pool, never on the async threads.

use crate::auth::{LoginError, Role};
use crate::listen::Peer;
use crate::App;
use automat_session::{Control, Error, Node, Session, State};
use axum::body::Bytes;
use axum::extract::{ConnectInfo, RawQuery, State as Ax};
use axum::http::{header, HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use serde::Deserialize;
use serde_json::{json, Map, Value};
use std::sync::Arc;

/// Paths one `read` may name.
pub const MAX_PATHS: usize = 1000;

pub fn error(status: StatusCode, message: impl Into<String>) -> Response {
    (status, axum::Json(json!({ "error": message.into() }))).into_response()
}

/// A refused request: its status and message (`{"error": message}`).
pub struct Refusal {
    pub status: StatusCode,
    pub message: String,
}

impl IntoResponse for Refusal {
    fn into_response(self) -> Response {
        let unauthorized = self.status == StatusCode::UNAUTHORIZED;
        let mut r = error(self.status, self.message);
        if unauthorized {
            r.headers_mut().insert(
                header::WWW_AUTHENTICATE,
                header::HeaderValue::from_static("Bearer"),
            );
        }
        r
    }
}

fn refuse(status: StatusCode, message: impl Into<String>) -> Refusal {
    Refusal {
        status,
        message: message.into(),
    }
}

pub fn session_error(e: &Error) -> Response {
    let status = match e {
        Error::Path(_) | Error::Value(_) => StatusCode::BAD_REQUEST,
        Error::ReadOnly(_) | Error::Refused(_) => StatusCode::CONFLICT,
        Error::Gone(_) => StatusCode::SERVICE_UNAVAILABLE,
    };
    error(status, e.message())
}

fn ok() -> Response {
    axum::Json(json!({ "ok": true })).into_response()
}

/// The bearer token of a request: the `Authorization` header, or a
/// `token` query parameter (browsers cannot set headers on a WebSocket).
fn bearer<'a>(headers: &'a HeaderMap, query: Option<&'a str>) -> Option<String> {
    if let Some(v) = headers
        .get(header::AUTHORIZATION)
        .and_then(|v| v.to_str().ok())
    {
        return v.strip_prefix("Bearer ").map(|t| t.trim().to_string());
    }
    query_values(query.unwrap_or(""), "token")
        .into_iter()
        .next()
}

/// The caller's role, refused with 401 or 403 below `need`.
pub fn authorize(
    app: &App,
    headers: &HeaderMap,
    query: Option<&str>,
    need: Role,
    what: &str,
) -> Result<Role, Refusal> {
    let role = bearer(headers, query)
        .and_then(|t| app.auth.role_of(&t))
        .ok_or_else(|| refuse(StatusCode::UNAUTHORIZED, "missing or invalid credentials"))?;
    if role < need {
        return Err(refuse(
            StatusCode::FORBIDDEN,
            format!(
                "the role {} may not {what}; it needs {}",
                role.name(),
                need.name()
            ),
        ));
    }
    Ok(role)
}

/// Decodes `%XX` and `+` of a query component.
fn decode(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while let Some(&c) = b.get(i) {
        match c {
            b'+' => out.push(b' '),
            b'%' => {
                let hex = b
                    .get(i + 1..i + 3)
                    .and_then(|h| std::str::from_utf8(h).ok())
                    .and_then(|h| u8::from_str_radix(h, 16).ok());
                match hex {
                    Some(v) => {
                        out.push(v);
                        i += 2;
                    }
                    None => out.push(b'%'),
                }
            }
            _ => out.push(c),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Every value of `key` in a query string, in order.
pub fn query_values(query: &str, key: &str) -> Vec<String> {
    query
        .split('&')
        .filter_map(|kv| {
            let (k, v) = kv.split_once('=').unwrap_or((kv, ""));
            (decode(k) == key).then(|| decode(v))
        })
        .collect()
}

fn parse<T: for<'de> Deserialize<'de>>(body: &Bytes) -> Result<T, Refusal> {
    serde_json::from_slice(body)
        .map_err(|e| refuse(StatusCode::BAD_REQUEST, format!("malformed request: {e}")))
}

async fn blocking<F>(app: &App, f: F) -> Response
where
    F: FnOnce(&Session) -> Result<(), Error> + Send + 'static,
{
    let session = Arc::clone(&app.session);
    match tokio::task::spawn_blocking(move || f(&session)).await {
        Ok(Ok(())) => ok(),
        Ok(Err(e)) => session_error(&e),
        Err(_) => error(StatusCode::INTERNAL_SERVER_ERROR, "the request failed"),
    }
}

fn us(ns: Option<i64>) -> Value {
    ns.map_or(Value::Null, |n| json!(n as f64 / 1000.0))
}

pub async fn status(Ax(app): Ax<App>, headers: HeaderMap, RawQuery(q): RawQuery) -> Response {
    if let Err(r) = authorize(
        &app,
        &headers,
        q.as_deref(),
        Role::Viewer,
        "read the status",
    ) {
        return r.into_response();
    }
    let s = app.session.snapshot();
    let fault = match &s.state {
        State::Fault { message, site } => json!({ "message": message, "site": site }),
        _ => Value::Null,
    };
    axum::Json(json!({
        "project": app.about["project"],
        "cycle_time_ns": app.about["cycle_time_ns"],
        "tasks": app.about["tasks"],
        "state": s.state.name(),
        "plc_time_ns": s.plc_time_ns,
        "scans": s.scans,
        "scan_time_us": { "min": us(s.stats.min_ns), "avg": us(s.stats.avg_ns), "max": us(s.stats.max_ns) },
        "overruns": s.stats.overruns,
        "fault": fault,
    }))
    .into_response()
}

pub async fn read(Ax(app): Ax<App>, headers: HeaderMap, RawQuery(q): RawQuery) -> Response {
    if let Err(r) = authorize(&app, &headers, q.as_deref(), Role::Viewer, "read") {
        return r.into_response();
    }
    let paths = query_values(q.as_deref().unwrap_or(""), "path");
    if paths.is_empty() {
        return error(
            StatusCode::BAD_REQUEST,
            "name at least one path: ?path=A&path=B",
        );
    }
    if paths.len() > MAX_PATHS {
        return error(
            StatusCode::BAD_REQUEST,
            format!("at most {MAX_PATHS} paths per read"),
        );
    }
    match app.session.read_seq(&paths) {
        Ok((seq, values)) => {
            let map: Map<String, Value> = values.into_iter().map(|(k, v)| (k, json!(v))).collect();
            axum::Json(json!({ "seq": seq, "values": map })).into_response()
        }
        Err(e) => session_error(&e),
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PathValue {
    path: String,
    value: Value,
}

/// A value given as a JSON string, number or boolean, as its literal text.
fn literal(v: &Value) -> Result<String, Refusal> {
    match v {
        Value::String(s) => Ok(s.clone()),
        Value::Bool(b) => Ok(if *b { "TRUE" } else { "FALSE" }.to_string()),
        Value::Number(n) => Ok(n.to_string()),
        _ => Err(refuse(
            StatusCode::BAD_REQUEST,
            "`value` must be a string (an IEC literal such as \"TRUE\" or \"T#3s\"), a number or a boolean",
        )),
    }
}

/// The authorized `{"path", "value"}` body of `write` and `force`: the
/// path and the value as IEC literal text, or the refusal.
fn path_value(
    app: &App,
    headers: &HeaderMap,
    body: &Bytes,
    what: &str,
) -> Result<(String, String), Refusal> {
    authorize(app, headers, None, Role::Operator, what)?;
    let req: PathValue = parse(body)?;
    let value = literal(&req.value)?;
    Ok((req.path, value))
}

pub async fn write(Ax(app): Ax<App>, headers: HeaderMap, body: Bytes) -> Response {
    match path_value(&app, &headers, &body, "write") {
        Ok((path, value)) => blocking(&app, move |s| s.write(&path, &value)).await,
        Err(r) => r.into_response(),
    }
}

pub async fn force(Ax(app): Ax<App>, headers: HeaderMap, body: Bytes) -> Response {
    match path_value(&app, &headers, &body, "force") {
        Ok((path, value)) => blocking(&app, move |s| s.force(&path, &value)).await,
        Err(r) => r.into_response(),
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Unforce {
    path: Option<String>,
    #[serde(default)]
    all: bool,
}

pub async fn unforce(Ax(app): Ax<App>, headers: HeaderMap, body: Bytes) -> Response {
    if let Err(r) = authorize(&app, &headers, None, Role::Operator, "release forces") {
        return r.into_response();
    }
    let req: Unforce = match parse(&body) {
        Ok(r) => r,
        Err(r) => return r.into_response(),
    };
    match (req.path, req.all) {
        (None, true) => blocking(&app, |s| s.unforce_all()).await,
        (Some(p), false) => blocking(&app, move |s| s.unforce(&p)).await,
        _ => error(
            StatusCode::BAD_REQUEST,
            "give either {\"path\": PATH} or {\"all\": true}",
        ),
    }
}

pub async fn forces(Ax(app): Ax<App>, headers: HeaderMap, RawQuery(q): RawQuery) -> Response {
    if let Err(r) = authorize(&app, &headers, q.as_deref(), Role::Viewer, "list forces") {
        return r.into_response();
    }
    let snap = app.session.snapshot();
    let map: Map<String, Value> = snap
        .forces
        .iter()
        .map(|(k, v)| (k.clone(), json!(v)))
        .collect();
    axum::Json(json!({ "seq": snap.seq, "forces": map })).into_response()
}

fn node_json(n: &Node, session: &Session) -> Value {
    let mut v = json!({
        "name": n.name,
        "path": n.path,
        "type": n.ty,
        "writable": n.writable,
    });
    if !n.children.is_empty() {
        v["children"] = Value::Array(n.children.iter().map(|c| node_json(c, session)).collect());
    } else if n.writable && !session.forces().is_empty() {
        if let Ok(place) = session.place(&n.path) {
            if session.is_forced(&place) {
                v["forced"] = json!(true);
            }
        }
    }
    if n.more > 0 {
        v["more"] = json!(n.more);
    }
    v
}

pub async fn symbols(Ax(app): Ax<App>, headers: HeaderMap, RawQuery(q): RawQuery) -> Response {
    if let Err(r) = authorize(&app, &headers, q.as_deref(), Role::Viewer, "browse symbols") {
        return r.into_response();
    }
    let prefix = query_values(q.as_deref().unwrap_or(""), "prefix")
        .into_iter()
        .next()
        .unwrap_or_default();
    match app.session.symbols(&prefix) {
        Ok(nodes) => axum::Json(json!({
            "symbols": nodes.iter().map(|n| node_json(n, &app.session)).collect::<Vec<Value>>()
        }))
        .into_response(),
        Err(e) => session_error(&e),
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ControlReq {
    command: String,
    scans: Option<u64>,
}

pub async fn control(Ax(app): Ax<App>, headers: HeaderMap, body: Bytes) -> Response {
    if let Err(r) = authorize(&app, &headers, None, Role::Engineer, "control the run") {
        return r.into_response();
    }
    let req: ControlReq = match parse(&body) {
        Ok(r) => r,
        Err(r) => return r.into_response(),
    };
    let c = match req.command.as_str() {
        "start" => Control::Start,
        "stop" => Control::Stop,
        "step" => Control::Step(req.scans.unwrap_or(1)),
        "cold_restart" => Control::ColdRestart,
        "warm_restart" => Control::WarmRestart,
        other => {
            return error(
                StatusCode::BAD_REQUEST,
                format!(
                    "unknown command `{other}`: start, stop, step, cold_restart or warm_restart"
                ),
            )
        }
    };
    blocking(&app, move |s| s.control(c)).await
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LoginReq {
    user: String,
    password: String,
}

pub async fn login(
    Ax(app): Ax<App>,
    ConnectInfo(Peer(peer)): ConnectInfo<Peer>,
    body: Bytes,
) -> Response {
    let req: LoginReq = match parse(&body) {
        Ok(r) => r,
        Err(r) => return r.into_response(),
    };
    let auth = Arc::clone(&app.auth);
    let ip = peer.ip();
    let result =
        tokio::task::spawn_blocking(move || auth.login(ip, &req.user, &req.password)).await;
    match result {
        Ok(Ok((token, role))) => {
            axum::Json(json!({ "token": token, "role": role.name() })).into_response()
        }
        Ok(Err(LoginError::Denied)) => error(StatusCode::UNAUTHORIZED, "wrong user or password"),
        Ok(Err(LoginError::Limited(secs))) => {
            let mut r = error(
                StatusCode::TOO_MANY_REQUESTS,
                format!("too many failed logins; retry in {secs} s"),
            );
            if let Ok(v) = header::HeaderValue::from_str(&secs.to_string()) {
                r.headers_mut().insert(header::RETRY_AFTER, v);
            }
            r
        }
        Err(_) => error(StatusCode::INTERNAL_SERVER_ERROR, "the request failed"),
    }
}

#[cfg(test)]
mod tests {
    use super::query_values;

    #[test]
    fn queries_decode_repeated_keys() {
        assert_eq!(
            query_values("path=Ctrl.M1S&path=arr%5B1%2C%202%5D&x=1", "path"),
            ["Ctrl.M1S", "arr[1, 2]"]
        );
        assert_eq!(query_values("prefix=a+b", "prefix"), ["a b"]);
        assert!(query_values("", "path").is_empty());
    }
}
