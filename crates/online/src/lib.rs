//! The network API of a running PLC: HTTP/JSON plus one WebSocket over an
//! [`automat_session::Session`] (the contract is `docs/online-api.md`).
//!
//! Security from the first line: the server binds 127.0.0.1 unless an
//! address is given; a non-loopback address needs TLS unless `insecure`
//! is said; every request but `login` carries a bearer token (the token
//! file's, or one `login` returned) whose role decides what it may do;
//! request bodies, WebSocket messages, open connections and WebSocket
//! clients are bounded; failed logins are rate-limited per address.
//! The server runs on its own tokio runtime (two worker threads); the
//! scan thread never waits for it.

pub mod api;
pub mod auth;
pub mod charts;
pub mod drawings;
pub mod hmi;
pub mod listen;
pub mod plant;
pub mod watch;

pub use auth::{hash_password, token_file, Role, User};

use automat_session::Session;
use axum::extract::DefaultBodyLimit;
use axum::routing::{get, post};
use axum::Router;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use tokio::sync::{oneshot, Semaphore};

/// Largest request body accepted.
pub const MAX_BODY: usize = 64 * 1024;

pub struct Options {
    pub addr: SocketAddr,
    /// Certificate and private key (PEM) for HTTPS/WSS.
    pub tls: Option<(PathBuf, PathBuf)>,
    /// Allow a non-loopback address without TLS.
    pub insecure: bool,
    /// The token of `--token-file` (engineer rights).
    pub token: Option<String>,
    pub users: Vec<User>,
    pub max_connections: usize,
    pub max_watchers: usize,
    /// The SFC charts of the program (`GET /api/v1/charts`).
    pub charts: Vec<automat_project::charts::PouChart>,
    /// The LD and FBD drawings of the program (`GET /api/v1/drawings`).
    pub drawings: Vec<drawings::Drawing>,
    /// The project's name (`[project] name`) for `status`; `None` for
    /// source files.
    pub project: Option<String>,
    /// The base period of cyclic tasks, for `status`.
    pub cycle_time_ns: i64,
}

impl Options {
    pub fn new(addr: SocketAddr) -> Options {
        Options {
            addr,
            tls: None,
            insecure: false,
            token: None,
            users: Vec::new(),
            max_connections: 128,
            max_watchers: 32,
            charts: Vec::new(),
            drawings: Vec::new(),
            project: None,
            cycle_time_ns: 10_000_000,
        }
    }
}

#[derive(Clone)]
pub struct App {
    pub session: Arc<Session>,
    pub auth: Arc<auth::Auth>,
    pub watchers: Arc<Semaphore>,
    /// The answer of `GET /api/v1/charts`.
    pub charts: Arc<Option<serde_json::Value>>,
    /// The answer of `GET /api/v1/drawings`.
    pub drawings: Arc<Option<serde_json::Value>>,
    /// What `status` says of the program: its project, cycle and tasks
    /// (fixed while it runs).
    pub about: Arc<serde_json::Value>,
}

/// A running server; dropping it stops it.
pub struct Server {
    pub addr: SocketAddr,
    /// `http` or `https`.
    pub scheme: &'static str,
    stop: Option<oneshot::Sender<()>>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Drop for Server {
    fn drop(&mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

pub fn router(app: App) -> Router {
    Router::new()
        .route("/", get(hmi::index))
        .route("/hmi/app.js", get(hmi::app_js))
        .route("/hmi/charts.js", get(hmi::charts_js))
        .route("/hmi/drawings.js", get(hmi::drawings_js))
        .route("/hmi/mimic.js", get(hmi::mimic_js))
        .route("/hmi/app.css", get(hmi::app_css))
        .route("/api/v1/status", get(api::status))
        .route("/api/v1/read", get(api::read))
        .route("/api/v1/write", post(api::write))
        .route("/api/v1/force", post(api::force))
        .route("/api/v1/unforce", post(api::unforce))
        .route("/api/v1/forces", get(api::forces))
        .route("/api/v1/symbols", get(api::symbols))
        .route("/api/v1/control", post(api::control))
        .route("/api/v1/login", post(api::login))
        .route("/api/v1/watch", get(watch::watch))
        .route("/api/v1/charts", get(charts::charts))
        .route("/api/v1/drawings", get(drawings::drawings))
        .route("/api/v1/plant", get(plant::get).post(plant::post))
        .layer(DefaultBodyLimit::max(MAX_BODY))
        .with_state(app)
}

/// Checks the options, binds and starts serving `session`.
pub fn start(session: Arc<Session>, opts: Options) -> Result<Server, String> {
    if !opts.addr.ip().is_loopback() && opts.tls.is_none() && !opts.insecure {
        return Err(format!(
            "--listen {}: a non-loopback address needs TLS (--tls-cert FILE --tls-key FILE), or --insecure to serve plain HTTP",
            opts.addr
        ));
    }
    if opts.token.is_none() && opts.users.is_empty() {
        return Err(
            "--listen needs credentials: --token-file FILE, or [users] in automat.toml".into(),
        );
    }
    for u in &opts.users {
        if !auth::valid_hash(&u.hash) {
            return Err(format!(
                "user `{}`: the password is not an argon2id hash (make one with `automat passwd`)",
                u.name
            ));
        }
    }
    let tls = match &opts.tls {
        Some((cert, key)) => Some(listen::tls_config(cert, key)?),
        None => None,
    };
    let scheme = if tls.is_some() { "https" } else { "http" };
    let tree = session.symbols("").unwrap_or_default();
    let charts = Arc::new(Some(charts::answer(&opts.charts, session.program(), &tree)));
    let drawings = Arc::new(Some(drawings::answer(&opts.drawings, &session, &tree)));
    let tasks: Vec<serde_json::Value> = session
        .program()
        .tasks
        .iter()
        .map(|t| {
            serde_json::json!({
                "name": t.name,
                "interval_ns": t.interval_ns,
                "priority": t.priority,
                "programs": t.programs.iter().map(|p| p.name.as_str()).collect::<Vec<_>>(),
            })
        })
        .collect();
    let about = Arc::new(serde_json::json!({
        "project": opts.project,
        "cycle_time_ns": opts.cycle_time_ns,
        "tasks": tasks,
    }));
    let app = App {
        about,
        charts,
        drawings,
        session,
        auth: Arc::new(auth::Auth::new(opts.token.clone(), opts.users.clone())),
        watchers: Arc::new(Semaphore::new(opts.max_watchers.max(1))),
    };
    let (ready_tx, ready_rx) = std::sync::mpsc::channel::<Result<SocketAddr, String>>();
    let (stop_tx, stop_rx) = oneshot::channel::<()>();
    let addr = opts.addr;
    let max_conns = opts.max_connections;
    let thread = std::thread::Builder::new()
        .name("automat-online".into())
        .spawn(move || {
            let rt = match tokio::runtime::Builder::new_multi_thread()
                .worker_threads(2)
                .thread_name("automat-online")
                .enable_all()
                .build()
            {
                Ok(rt) => rt,
                Err(e) => {
                    let _ = ready_tx.send(Err(format!("cannot start the server: {e}")));
                    return;
                }
            };
            rt.block_on(async move {
                let tcp = match tokio::net::TcpListener::bind(addr).await {
                    Ok(t) => t,
                    Err(e) => {
                        let _ = ready_tx.send(Err(format!("--listen {addr}: {e}")));
                        return;
                    }
                };
                let listener = match listen::Listener::start(tcp, tls, max_conns) {
                    Ok(l) => l,
                    Err(e) => {
                        let _ = ready_tx.send(Err(format!("--listen {addr}: {e}")));
                        return;
                    }
                };
                let local = axum::serve::Listener::local_addr(&listener).unwrap_or(addr);
                let _ = ready_tx.send(Ok(local));
                let service = router(app).into_make_service_with_connect_info::<listen::Peer>();
                let _ = axum::serve(listener, service)
                    .with_graceful_shutdown(async {
                        let _ = stop_rx.await;
                    })
                    .await;
            });
        })
        .map_err(|e| format!("cannot start the server: {e}"))?;
    match ready_rx.recv() {
        Ok(Ok(addr)) => Ok(Server {
            addr,
            scheme,
            stop: Some(stop_tx),
            thread: Some(thread),
        }),
        Ok(Err(e)) => {
            let _ = thread.join();
            Err(e)
        }
        Err(_) => Err("the server thread ended before listening".into()),
    }
}
