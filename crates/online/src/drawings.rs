//! `GET /api/v1/drawings`: the LD and FBD bodies of the program as drawn
//! (the drawing `automat draw` makes, as SVG, with the box of every element
//! and the point of every block pin), and per element the variables whose
//! values the HMI shows on it: a contact's or coil's power flow (the hidden
//! BOOL `__ld_n<localId>` the lowering keeps, read-only), a block
//! instance's pins (`T1.Q`), a variable element's variable.
//!
//! The front end (`automat run`, which knows the sources) makes the
//! [`Drawing`]s with paths relative to an instance of the POU; [`answer`]
//! resolves them against the running program: a path the POU's first
//! instance has becomes `.PATH` (the client prefixes the instance it shows),
//! a global one stays `PATH`, one the program does not have is dropped.

use crate::api::{authorize, error};
use crate::auth::Role;
use crate::charts::instances_of;
use crate::App;
use automat_session::{Node, Session};
use axum::extract::{RawQuery, State as Ax};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use serde_json::{json, Value};

/// One graphical POU as drawn.
#[derive(Clone, Debug, Serialize)]
pub struct Drawing {
    pub pou: String,
    /// The POU whose instances run this drawing, when it is not `pou`
    /// (an SLC program file `LAD 2` runs in the program `SLC`).
    #[serde(skip)]
    pub runs_in: Option<String>,
    /// `slc` for an SLC-500 program file: the HMI shows its bits as 1/0,
    /// as RSLogix does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dialect: Option<&'static str>,
    /// `LD` or `FBD`.
    pub lang: &'static str,
    pub file: String,
    /// The drawing (`automat draw`'s SVG).
    pub svg: String,
    pub width: f64,
    pub height: f64,
    pub elements: Vec<Element>,
}

/// One element: its box in the drawing and what to show on it.
#[derive(Clone, Debug, Serialize)]
pub struct Element {
    pub id: u32,
    /// `contact`, `coil`, `block`, `in-variable`, ...
    pub kind: &'static str,
    pub text: String,
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
    /// The BOOL power flow out of a contact or coil.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub power: Option<String>,
    /// The value a variable element reads or writes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value: Option<String>,
    pub pins: Vec<Pin>,
}

/// A block pin with a value to show beside it.
#[derive(Clone, Debug, Serialize)]
pub struct Pin {
    pub name: String,
    pub x: f64,
    pub y: f64,
    pub output: bool,
    pub path: String,
}

/// Where `rel` (relative to an instance of the POU) is in the program:
/// `.rel` when `inst.rel` reads, `rel` when it is a global, else `None`.
fn resolve(session: &Session, inst: Option<&str>, rel: &str) -> Option<String> {
    if let Some(i) = inst {
        if session.place(&format!("{i}.{rel}")).is_ok() {
            return Some(format!(".{rel}"));
        }
    }
    session.place(rel).is_ok().then(|| rel.to_string())
}

/// The answer: every drawing with its instances and resolved paths
/// (computed once per server).
pub fn answer(drawings: &[Drawing], session: &Session, tree: &[Node]) -> Value {
    let list: Vec<Value> = drawings
        .iter()
        .map(|d| {
            let pou = d.runs_in.as_deref().unwrap_or(&d.pou);
            let at = instances_of(pou, session.program(), tree);
            let first = at.first().map(String::as_str);
            let mut d = d.clone();
            for e in &mut d.elements {
                e.power = e.power.take().and_then(|p| resolve(session, first, &p));
                e.value = e.value.take().and_then(|p| resolve(session, first, &p));
                e.pins = std::mem::take(&mut e.pins)
                    .into_iter()
                    .filter_map(|mut p| {
                        p.path = resolve(session, first, &p.path)?;
                        Some(p)
                    })
                    .collect();
            }
            let mut v = serde_json::to_value(&d).unwrap_or(Value::Null);
            v["instances"] = json!(at);
            v
        })
        .collect();
    json!({ "drawings": list })
}

pub async fn drawings(Ax(app): Ax<App>, headers: HeaderMap, RawQuery(q): RawQuery) -> Response {
    if let Err(r) = authorize(
        &app,
        &headers,
        q.as_deref(),
        Role::Viewer,
        "read the drawings",
    ) {
        return r.into_response();
    }
    match app.drawings.as_ref() {
        Some(v) => axum::Json(v.clone()).into_response(),
        None => error(
            StatusCode::SERVICE_UNAVAILABLE,
            "the drawings are not known",
        ),
    }
}
