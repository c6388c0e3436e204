//! `GET /api/v1/watch`: a WebSocket whose client sends
//! `{"subscribe": [paths], "period_ms": n}` (again to change it) and gets
//! `{"plc_time_ns", "scans", "seq", "values": {...}}` (and `"forced": [paths]`
//! when some watched paths are forced) after every scan
//! (`period_ms` 0 or absent) or at most once per period of PLC time, and
//! once at once with the current values.
//!
//! The scan thread only hands each due snapshot to a bounded channel
//! (`try_send`): a slow client misses updates, the scan never waits. The
//! values are formatted here, on the server's threads.

use crate::api::{authorize, error};
use crate::auth::Role;
use crate::App;
use automat_runtime::Locator;
use automat_session::Snapshot;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{RawQuery, State as Ax};
use axum::http::{HeaderMap, StatusCode};
use axum::response::Response;
use serde::Deserialize;
use serde_json::{json, Map, Value};
use std::sync::Arc;
use tokio::sync::mpsc;
use tokio::sync::mpsc::error::TrySendError;

/// Largest message a client may send.
pub const MAX_MESSAGE: usize = 64 * 1024;
/// Paths one subscription may name.
pub const MAX_WATCHED: usize = 1000;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Subscribe {
    subscribe: Vec<String>,
    #[serde(default)]
    period_ms: u64,
}

pub async fn watch(
    ws: WebSocketUpgrade,
    Ax(app): Ax<App>,
    headers: HeaderMap,
    RawQuery(q): RawQuery,
) -> Response {
    if let Err(r) = authorize(&app, &headers, q.as_deref(), Role::Viewer, "watch") {
        return axum::response::IntoResponse::into_response(r);
    }
    let Ok(slot) = Arc::clone(&app.watchers).try_acquire_owned() else {
        return error(
            StatusCode::SERVICE_UNAVAILABLE,
            "too many WebSocket clients; retry later",
        );
    };
    ws.max_message_size(MAX_MESSAGE)
        .max_frame_size(MAX_MESSAGE)
        .on_upgrade(move |socket| async move {
            serve(socket, app).await;
            drop(slot);
        })
}

/// One update; `forced` lists the watched paths that are forced (only
/// when some are).
fn values(app: &App, places: &[(String, Locator)], snap: &Snapshot) -> String {
    let map: Map<String, Value> = places
        .iter()
        .map(|(n, l)| (n.clone(), json!(l.format(&snap.image))))
        .collect();
    let mut msg = json!({
        "plc_time_ns": snap.plc_time_ns,
        "scans": snap.scans,
        "seq": snap.seq,
        "values": map,
    });
    if !snap.forces.is_empty() {
        let forced: Vec<&str> = places
            .iter()
            .filter(|(_, l)| {
                l.place(&snap.image)
                    .is_ok_and(|p| app.session.is_forced_in(snap, &p))
            })
            .map(|(n, _)| n.as_str())
            .collect();
        if !forced.is_empty() {
            msg["forced"] = json!(forced);
        }
    }
    msg.to_string()
}

async fn next(rx: &mut Option<mpsc::Receiver<Arc<Snapshot>>>) -> Option<Arc<Snapshot>> {
    match rx {
        Some(r) => r.recv().await,
        None => std::future::pending().await,
    }
}

async fn serve(mut socket: WebSocket, app: App) {
    let mut rx: Option<mpsc::Receiver<Arc<Snapshot>>> = None;
    let mut places: Vec<(String, Locator)> = Vec::new();
    loop {
        tokio::select! {
            msg = socket.recv() => {
                let text = match msg {
                    Some(Ok(Message::Text(t))) => t.to_string(),
                    Some(Ok(Message::Binary(_))) => {
                        let e = json!({"error": "send the subscription as a text message"});
                        if socket.send(Message::Text(e.to_string().into())).await.is_err() {
                            return;
                        }
                        continue;
                    }
                    Some(Ok(Message::Close(_))) | None | Some(Err(_)) => return,
                    Some(Ok(_)) => continue,
                };
                match subscribe(&app, &text).await {
                    Ok((p, r)) => {
                        places = p;
                        rx = Some(r);
                        let now = values(&app, &places, &app.session.snapshot());
                        if socket.send(Message::Text(now.into())).await.is_err() {
                            return;
                        }
                    }
                    Err(e) => {
                        let e = json!({"error": e}).to_string();
                        if socket.send(Message::Text(e.into())).await.is_err() {
                            return;
                        }
                    }
                }
            }
            snap = next(&mut rx) => {
                let Some(snap) = snap else {
                    // The session ended.
                    let _ = socket.send(Message::Close(None)).await;
                    return;
                };
                if socket.send(Message::Text(values(&app, &places, &snap).into())).await.is_err() {
                    return;
                }
            }
        }
    }
}

type Subscribed = (Vec<(String, Locator)>, mpsc::Receiver<Arc<Snapshot>>);

async fn subscribe(app: &App, text: &str) -> Result<Subscribed, String> {
    let req: Subscribe =
        serde_json::from_str(text).map_err(|e| format!("malformed subscription: {e}"))?;
    if req.subscribe.len() > MAX_WATCHED {
        return Err(format!("at most {MAX_WATCHED} paths per subscription"));
    }
    let places = req
        .subscribe
        .iter()
        .map(|p| app.session.locate(p).map(|l| (p.clone(), l)))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.message().to_string())?;
    let (tx, rx) = mpsc::channel::<Arc<Snapshot>>(4);
    let period_ns = i64::try_from(req.period_ms.saturating_mul(1_000_000)).unwrap_or(i64::MAX);
    let session = Arc::clone(&app.session);
    let sink = Box::new(move |s: &Arc<Snapshot>| match tx.try_send(Arc::clone(s)) {
        Ok(()) | Err(TrySendError::Full(_)) => true,
        Err(TrySendError::Closed(_)) => false,
    });
    tokio::task::spawn_blocking(move || session.subscribe_raw(period_ns, sink))
        .await
        .map_err(|_| "the subscription failed".to_string())?
        .map_err(|e| e.message().to_string())?;
    Ok((places, rx))
}
