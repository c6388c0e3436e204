//! automat's OPC UA server (`docs/opcua.md`), on `async-opcua`.
//!
//! - [`space`]: the symbol tree as the address space (`ns=1;s=<path>`).
//! - [`values`]: IEC types and values as OPC UA data types and variants.
//! - [`auth`]: users and roles of `[users]`; anonymous read-only on the
//!   None endpoint, offered only on loopback.
//! - [`config`]: `[opcua]` of `automat.toml` (E346).
//!
//! Invariants: nothing runs on the scan thread but handing the snapshot
//! to a watch channel (latest value only, never a queue); values are
//! sampled at the scan: after each scan the changed values are set in the
//! address space, which notifies the monitored items; a client's write
//! goes through `Session::write_stored` (the session's rules: forces
//! hold, CONSTANTs and chart state are not writable), one write request's
//! values between two scans.

pub mod auth;
pub mod config;
pub mod space;
pub mod values;

use automat_online::User;
use automat_session::Session;
use opcua::server::diagnostics::{DiagnosticsNodeManagerBuilder, NamespaceMetadata};
use opcua::server::node_manager::memory::{
    simple_node_manager, CoreNodeManagerBuilder, InMemoryNodeManagerBuilder, SimpleNodeManager,
};
use opcua::server::{
    ServerBuilder, ServerEndpoint, ServerHandle, ServerUserToken, ANONYMOUS_USER_TOKEN_ID,
};
use opcua::types::{DataValue, DateTime, NumericRange, StatusCode, Variant};
use space::{Source, Var};
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::thread::JoinHandle;

/// Sessions served at once.
pub const MAX_SESSIONS: usize = 32;

/// The namespace of the PLC's nodes (index 1).
pub const NAMESPACE: &str = "urn:automat:plc";

#[derive(Clone, Debug)]
pub struct Options {
    pub addr: SocketAddr,
    /// The server's certificate and key (made self-signed at the first
    /// start), trusted and rejected client certificates.
    pub pki_dir: PathBuf,
    pub users: Vec<User>,
    /// Accept any client certificate on the encrypted endpoints (the
    /// login still decides); otherwise a client's certificate must be put
    /// in `pki_dir/trusted/certs`.
    pub trust_client_certs: bool,
    /// How often values are sampled: the PLC's cycle time.
    pub sample_ns: i64,
}

/// A running server; dropping it stops it.
pub struct OpcuaServer {
    pub addr: SocketAddr,
    /// Variable nodes of the PLC.
    pub variables: usize,
    /// Whether the None endpoint (anonymous, read-only) is offered.
    pub anonymous: bool,
    handle: ServerHandle,
    thread: Option<JoinHandle<()>>,
}

impl Drop for OpcuaServer {
    fn drop(&mut self) {
        self.handle.cancel();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// What a write of `v` to `var` stores: one or, for an array, every
/// element (all or none).
fn stored(
    session: &Session,
    var: &Var,
    v: &Variant,
) -> Result<Vec<automat_session::value::Stored>, StatusCode> {
    let one = |path: &str, p: &automat_runtime::Place, v: &Variant| {
        let text = values::literal(v, &p.ty).ok_or(StatusCode::BadTypeMismatch)?;
        session.target(path, &text).map_err(|e| match e {
            automat_session::Error::ReadOnly(_) => StatusCode::BadNotWritable,
            _ => StatusCode::BadOutOfRange,
        })
    };
    match (&var.source, v) {
        (Source::One(p), v) => Ok(vec![one(&var.path, p, v)?]),
        (Source::Array(items, _), Variant::Array(a)) if a.values.len() == items.len() => items
            .iter()
            .zip(a.values.iter())
            .map(|((path, p), v)| one(path, p, v))
            .collect(),
        _ => Err(StatusCode::BadTypeMismatch),
    }
}

/// Starts the server for `session`.
// async-opcua marks the Basic256Sha256 constructors deprecated (the
// policy is being superseded by the Aes*/RsaPss ones); it is still the
// policy every client implements, and the one asked for here.
#[allow(deprecated)]
pub fn start(session: Arc<Session>, opts: Options) -> Result<OpcuaServer, String> {
    let listener = std::net::TcpListener::bind(opts.addr)
        .map_err(|e| format!("OPC UA: cannot listen on {}: {e}", opts.addr))?;
    let addr = listener
        .local_addr()
        .map_err(|e| format!("OPC UA: cannot listen on {}: {e}", opts.addr))?;
    listener
        .set_nonblocking(true)
        .map_err(|e| format!("OPC UA: {e}"))?;
    // Anonymous (and unencrypted) sessions only where no other host can
    // reach the server.
    let anonymous = addr.ip().is_loopback();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .thread_name("automat-opcua")
        .enable_all()
        .build()
        .map_err(|e| format!("OPC UA: cannot start its threads: {e}"))?;
    // The node managers start their tasks when built: inside the runtime.
    let guard = runtime.enter();
    let users = Arc::new(auth::Users::new(opts.users.clone(), anonymous));
    let placeholder = automat_online::auth::random_token()?;
    let mut builder = ServerBuilder::new()
        .without_node_managers()
        .with_node_manager(InMemoryNodeManagerBuilder::new(CoreNodeManagerBuilder))
        .with_node_manager(simple_node_manager(
            NamespaceMetadata {
                namespace_uri: NAMESPACE.to_string(),
                ..Default::default()
            },
            "automat",
        ))
        .with_node_manager(DiagnosticsNodeManagerBuilder)
        .application_name("automat")
        .application_uri("urn:automat:server")
        .product_uri("urn:automat")
        .pki_dir(&opts.pki_dir)
        .certificate_path("own/cert.der")
        .private_key_path("private/private.pem")
        .create_sample_keypair(true)
        .trust_client_certs(opts.trust_client_certs)
        .host(addr.ip().to_string())
        .port(addr.port())
        .discovery_urls(vec!["/".to_string()])
        // Sessions at once: an HMI or two and a few SCADA clients; more
        // are refused rather than piling up.
        .max_sessions(MAX_SESSIONS)
        .with_authenticator(users.clone())
        // The secure endpoints' user-name token: the authenticator checks
        // the users of `[users]`; this entry only names the token (its
        // password is random and never compared).
        .add_user_token(
            auth::USERS_TOKEN_ID,
            ServerUserToken::user_pass(auth::USERS_TOKEN_ID.to_string(), placeholder),
        )
        .add_endpoint(
            "basic256sha256_sign",
            ServerEndpoint::new_basic256sha256_sign("/", &[auth::USERS_TOKEN_ID.to_string()]),
        )
        .add_endpoint(
            "basic256sha256_sign_encrypt",
            ServerEndpoint::new_basic256sha256_sign_encrypt(
                "/",
                &[auth::USERS_TOKEN_ID.to_string()],
            ),
        );
    if anonymous {
        builder = builder.add_endpoint(
            "none",
            ServerEndpoint::new_none("/", &[ANONYMOUS_USER_TOKEN_ID.to_string()]),
        );
    }
    let (server, handle) = builder.build().map_err(|e| format!("OPC UA: {e}"))?;
    let nm = handle
        .node_managers()
        .get_of_type::<SimpleNodeManager>()
        .ok_or("OPC UA: no node manager for the PLC")?;
    let ns = handle
        .get_namespace_index(NAMESPACE)
        .ok_or("OPC UA: the PLC namespace is not registered")?;
    let roots = session
        .symbols("")
        .map_err(|e| format!("OPC UA: {}", e.message()))?;
    let snap = session.snapshot();
    let vars = {
        let mut space = nm.address_space().write();
        let mut b = space::Builder {
            ns,
            session: &session,
            space: &mut space,
            vars: Vec::new(),
            image: &snap.image,
        };
        b.roots(&roots);
        b.vars
    };
    for var in vars.iter().filter(|v| v.writable) {
        let (s, v2) = (Arc::clone(&session), var.clone());
        nm.inner().add_write_callback(
            var.id.clone(),
            move |dv: DataValue, range: &NumericRange| {
                if !matches!(range, NumericRange::None) {
                    return StatusCode::BadIndexRangeInvalid;
                }
                let Some(v) = dv.value else {
                    return StatusCode::BadNothingToDo;
                };
                match stored(&s, &v2, &v) {
                    Ok(st) => match s.write_stored(st) {
                        Ok(()) => StatusCode::Good,
                        Err(_) => StatusCode::BadNotWritable,
                    },
                    Err(code) => code,
                }
            },
        );
    }
    let variables = vars.len();
    // After each scan: the latest snapshot, never a queue.
    let (tx, mut rx) = tokio::sync::watch::channel(Arc::clone(&snap));
    let period = opts.sample_ns.max(1_000_000);
    session
        .subscribe_raw(
            period,
            Box::new(move |snap| tx.send(Arc::clone(snap)).is_ok()),
        )
        .map_err(|e| format!("OPC UA: {}", e.message()))?;
    let (subs, nm2) = (Arc::clone(handle.subscriptions()), Arc::clone(&nm));
    drop(guard);
    let thread = std::thread::Builder::new()
        .name("automat-opcua".into())
        .spawn(move || {
            runtime.block_on(async move {
                tokio::spawn(async move {
                    let mut last: Vec<Variant> = Vec::new();
                    while rx.changed().await.is_ok() {
                        let snap = Arc::clone(&rx.borrow_and_update());
                        let now = DateTime::now();
                        let fresh: Vec<Variant> =
                            vars.iter().map(|v| v.value(&snap.image)).collect();
                        let changed: Vec<(
                            &opcua::types::NodeId,
                            Option<&NumericRange>,
                            DataValue,
                        )> = vars
                            .iter()
                            .zip(&fresh)
                            .enumerate()
                            .filter(|(i, (_, f))| last.get(*i) != Some(f))
                            .map(|(_, (v, f))| (&v.id, None, DataValue::new_at(f.clone(), now)))
                            .collect();
                        if !changed.is_empty() {
                            let _ = nm2.set_values(&subs, changed.into_iter());
                        }
                        last = fresh;
                    }
                });
                let Ok(listener) = tokio::net::TcpListener::from_std(listener) else {
                    return;
                };
                let _ = server.run_with(listener).await;
            });
        })
        .map_err(|e| format!("OPC UA: cannot start its thread: {e}"))?;
    Ok(OpcuaServer {
        addr,
        variables,
        anonymous,
        handle,
        thread: Some(thread),
    })
}
