//! Who may do what over OPC UA: the users of `automat.toml`'s `[users]`
//! (argon2id hashes, the online API's roles) log in with user name and
//! password on the Basic256Sha256 endpoints; anonymous sessions exist only
//! on the None endpoint, which is only offered on loopback, and read.
//! A viewer reads, browses and subscribes; an operator (or engineer) also
//! writes: the user access level of every node says so, and the server
//! checks it before a write reaches the session.

use async_trait::async_trait;
use automat_online::{Role, User};
use opcua::crypto::SecurityPolicy;
use opcua::nodes::AccessLevel;
use opcua::server::authenticator::{
    user_pass_security_policy_id, user_pass_security_policy_uri, AuthManager, Password, UserToken,
};
use opcua::server::{ServerEndpoint, ANONYMOUS_USER_TOKEN_ID};
use opcua::types::{Error, NodeId, StatusCode, UAString, UserTokenPolicy, UserTokenType};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The id of the user-name token on the secure endpoints.
pub const USERS_TOKEN_ID: &str = "automat-users";
const POLICY_ID_ANONYMOUS: &str = "anonymous";

pub struct Users {
    pub users: Arc<Vec<User>>,
    /// Whether the None endpoint (anonymous, read-only) is offered.
    pub anonymous: bool,
    /// Failed logins in the current minute: after
    /// [`automat_online::auth::MAX_FAILURES`] more wait (password guessing
    /// costs a minute per five tries).
    failures: AtomicU32,
    window: std::sync::Mutex<Instant>,
}

impl Users {
    pub fn new(users: Vec<User>, anonymous: bool) -> Users {
        Users {
            users: Arc::new(users),
            anonymous,
            failures: AtomicU32::new(0),
            window: std::sync::Mutex::new(Instant::now()),
        }
    }

    fn role(&self, token: &UserToken) -> Option<Role> {
        self.users
            .iter()
            .find(|u| u.name == token.0)
            .map(|u| u.role)
    }

    fn limited(&self) -> bool {
        let mut w = self.window.lock().unwrap_or_else(|p| p.into_inner());
        if w.elapsed() > Duration::from_secs(60) {
            *w = Instant::now();
            self.failures.store(0, Ordering::Relaxed);
        }
        self.failures.load(Ordering::Relaxed) >= automat_online::auth::MAX_FAILURES
    }
}

fn rejected(what: &str) -> Error {
    Error::new(StatusCode::BadIdentityTokenRejected, what.to_string())
}

#[async_trait]
impl AuthManager for Users {
    async fn authenticate_anonymous_token(&self, endpoint: &ServerEndpoint) -> Result<(), Error> {
        if self.anonymous && endpoint.user_token_ids.contains(ANONYMOUS_USER_TOKEN_ID) {
            Ok(())
        } else {
            Err(rejected("anonymous sessions are not offered here"))
        }
    }

    async fn authenticate_username_identity_token(
        &self,
        endpoint: &ServerEndpoint,
        username: &str,
        password: &Password,
    ) -> Result<UserToken, Error> {
        if !endpoint.user_token_ids.contains(USERS_TOKEN_ID) {
            return Err(rejected("log in on an encrypted endpoint"));
        }
        if self.limited() {
            return Err(rejected("too many failed logins; retry in a minute"));
        }
        let (users, name, pw) = (
            Arc::clone(&self.users),
            username.to_string(),
            password.get().to_string(),
        );
        // argon2id takes tens of milliseconds: off the async threads.
        let role =
            tokio::task::spawn_blocking(move || automat_online::auth::verify(&users, &name, &pw))
                .await
                .ok()
                .flatten();
        match role {
            Some(_) => Ok(UserToken(username.to_string())),
            None => {
                self.failures.fetch_add(1, Ordering::Relaxed);
                Err(rejected("wrong user name or password"))
            }
        }
    }

    fn effective_user_access_level(
        &self,
        token: &UserToken,
        user_access_level: AccessLevel,
        _node_id: &NodeId,
    ) -> AccessLevel {
        let writes = !token.is_anonymous() && self.role(token).is_some_and(|r| r >= Role::Operator);
        if writes {
            user_access_level
        } else {
            user_access_level - AccessLevel::CURRENT_WRITE
        }
    }

    fn user_token_policies(&self, endpoint: &ServerEndpoint) -> Vec<UserTokenPolicy> {
        let mut out = Vec::new();
        if self.anonymous && endpoint.user_token_ids.contains(ANONYMOUS_USER_TOKEN_ID) {
            out.push(UserTokenPolicy {
                policy_id: UAString::from(POLICY_ID_ANONYMOUS),
                token_type: UserTokenType::Anonymous,
                issued_token_type: UAString::null(),
                issuer_endpoint_url: UAString::null(),
                security_policy_uri: UAString::null(),
            });
        }
        if endpoint.user_token_ids.contains(USERS_TOKEN_ID)
            && endpoint.security_policy() != SecurityPolicy::None
        {
            out.push(UserTokenPolicy {
                policy_id: user_pass_security_policy_id(endpoint),
                token_type: UserTokenType::UserName,
                issued_token_type: UAString::null(),
                issuer_endpoint_url: UAString::null(),
                security_policy_uri: user_pass_security_policy_uri(endpoint),
            });
        }
        out
    }
}
