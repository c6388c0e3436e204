//! Who may do what: a token file for local tools, users with roles and
//! argon2id password hashes (from `automat.toml`), session tokens from
//! `POST /api/v1/login`, and a limit on failed logins per client address.
//!
//! Roles are ordered: a viewer reads, browses and watches; an operator
//! also writes and forces; an engineer also controls the run. The token
//! of the token file has the engineer's rights. Secrets never reach a log:
//! nothing here prints, and errors name no token or password.

use argon2::password_hash::{PasswordHash, PasswordHasher, PasswordVerifier, SaltString};
use argon2::Argon2;
use std::collections::HashMap;
use std::net::IpAddr;
use std::path::Path;
use std::sync::Mutex;
use std::time::{Duration, Instant};

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Role {
    Viewer,
    Operator,
    Engineer,
}

impl Role {
    pub fn parse(text: &str) -> Option<Role> {
        match text {
            "viewer" => Some(Role::Viewer),
            "operator" => Some(Role::Operator),
            "engineer" => Some(Role::Engineer),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Role::Viewer => "viewer",
            Role::Operator => "operator",
            Role::Engineer => "engineer",
        }
    }
}

#[derive(Clone, Debug)]
pub struct User {
    pub name: String,
    pub role: Role,
    /// A PHC string `$argon2id$v=19$...` made by `automat passwd`.
    pub hash: String,
}

/// Failed logins allowed per client address within [`FAIL_WINDOW`].
pub const MAX_FAILURES: u32 = 5;
pub const FAIL_WINDOW: Duration = Duration::from_secs(60);
/// How long a login's session token is valid.
pub const SESSION_LIFETIME: Duration = Duration::from_secs(8 * 3600);
/// Session tokens kept at most (the oldest go first).
const MAX_SESSIONS: usize = 1024;

pub struct Auth {
    token: Option<String>,
    users: Vec<User>,
    sessions: Mutex<HashMap<String, (Role, Instant)>>,
    failures: Mutex<HashMap<IpAddr, (u32, Instant)>>,
}

/// Why a login failed.
#[derive(Debug, PartialEq, Eq)]
pub enum LoginError {
    /// Wrong user or password (which one is not said).
    Denied,
    /// Too many failures from this address; retry after the seconds given.
    Limited(u64),
}

/// Equal strings, in time that does not depend on where they differ.
fn same(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

/// A fresh random token: 32 bytes from the OS, hex.
pub fn random_token() -> Result<String, String> {
    let mut bytes = [0u8; 32];
    getrandom::fill(&mut bytes).map_err(|e| format!("no random numbers from the OS: {e}"))?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// The token in `path`, or a new random one written there (mode 0600)
/// when the file does not exist.
pub fn token_file(path: &Path) -> Result<String, String> {
    let shown = path.display();
    match std::fs::read_to_string(path) {
        Ok(text) => {
            let t = text.trim().to_string();
            if t.len() < 16 {
                return Err(format!(
                    "{shown}: the token must be at least 16 characters long"
                ));
            }
            Ok(t)
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            let token = random_token()?;
            let mut opts = std::fs::OpenOptions::new();
            opts.write(true).create_new(true);
            #[cfg(unix)]
            {
                use std::os::unix::fs::OpenOptionsExt;
                opts.mode(0o600);
            }
            let mut f = opts.open(path).map_err(|e| format!("{shown}: {e}"))?;
            std::io::Write::write_all(&mut f, format!("{token}\n").as_bytes())
                .map_err(|e| format!("{shown}: {e}"))?;
            Ok(token)
        }
        Err(e) => Err(format!("{shown}: {e}")),
    }
}

/// An argon2id hash of `password` with a random salt (`automat passwd`).
pub fn hash_password(password: &str) -> Result<String, String> {
    let mut salt = [0u8; 16];
    getrandom::fill(&mut salt).map_err(|e| format!("no random numbers from the OS: {e}"))?;
    let salt = SaltString::encode_b64(&salt).map_err(|e| e.to_string())?;
    Argon2::default()
        .hash_password(password.as_bytes(), &salt)
        .map(|h| h.to_string())
        .map_err(|e| e.to_string())
}

/// Whether `hash` is a PHC string argon2 can check.
pub fn valid_hash(hash: &str) -> bool {
    PasswordHash::new(hash).is_ok_and(|h| h.algorithm.as_str() == "argon2id")
}

/// The role of `user` when `password` is theirs (slow by design: argon2id;
/// call it off async threads). Also the OPC UA server's check.
pub fn verify(users: &[User], user: &str, password: &str) -> Option<Role> {
    users.iter().find(|u| u.name == user).and_then(|u| {
        let hash = PasswordHash::new(&u.hash).ok()?;
        Argon2::default()
            .verify_password(password.as_bytes(), &hash)
            .ok()
            .map(|()| u.role)
    })
}

impl Auth {
    pub fn new(token: Option<String>, users: Vec<User>) -> Auth {
        Auth {
            token,
            users,
            sessions: Mutex::new(HashMap::new()),
            failures: Mutex::new(HashMap::new()),
        }
    }

    /// The role a bearer token carries.
    pub fn role_of(&self, bearer: &str) -> Option<Role> {
        if let Some(t) = &self.token {
            if same(t, bearer) {
                return Some(Role::Engineer);
            }
        }
        let mut sessions = self.sessions.lock().unwrap_or_else(|p| p.into_inner());
        let now = Instant::now();
        sessions.retain(|_, (_, until)| *until > now);
        sessions
            .iter()
            .find(|(t, _)| same(t, bearer))
            .map(|(_, (role, _))| *role)
    }

    /// Checks a user's password (slow by design: call off the async
    /// threads) and returns a session token and the user's role.
    pub fn login(
        &self,
        from: IpAddr,
        user: &str,
        password: &str,
    ) -> Result<(String, Role), LoginError> {
        let now = Instant::now();
        {
            let mut f = self.failures.lock().unwrap_or_else(|p| p.into_inner());
            f.retain(|_, (_, since)| now.duration_since(*since) < FAIL_WINDOW);
            if let Some((n, since)) = f.get(&from) {
                if *n >= MAX_FAILURES {
                    let left = FAIL_WINDOW.saturating_sub(now.duration_since(*since));
                    return Err(LoginError::Limited(left.as_secs().max(1)));
                }
            }
        }
        let ok = verify(&self.users, user, password);
        match ok {
            Some(role) => {
                let token = random_token().map_err(|_| LoginError::Denied)?;
                let mut s = self.sessions.lock().unwrap_or_else(|p| p.into_inner());
                if s.len() >= MAX_SESSIONS {
                    if let Some(oldest) = s
                        .iter()
                        .min_by_key(|(_, (_, u))| *u)
                        .map(|(t, _)| t.clone())
                    {
                        s.remove(&oldest);
                    }
                }
                s.insert(token.clone(), (role, now + SESSION_LIFETIME));
                Ok((token, role))
            }
            None => {
                let mut f = self.failures.lock().unwrap_or_else(|p| p.into_inner());
                let e = f.entry(from).or_insert((0, now));
                e.0 += 1;
                Err(LoginError::Denied)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passwords_verify_and_failures_are_limited() {
        let hash = hash_password("s3cret").unwrap();
        assert!(hash.starts_with("$argon2id$"), "{hash}");
        assert!(valid_hash(&hash));
        assert!(!valid_hash("plain"));
        let auth = Auth::new(
            None,
            vec![User {
                name: "op".into(),
                role: Role::Operator,
                hash,
            }],
        );
        let ip: IpAddr = "127.0.0.1".parse().unwrap();
        let (token, role) = auth.login(ip, "op", "s3cret").unwrap();
        assert_eq!(role, Role::Operator);
        assert_eq!(auth.role_of(&token), Some(Role::Operator));
        assert_eq!(auth.role_of("nope"), None);
        for _ in 0..MAX_FAILURES {
            assert_eq!(auth.login(ip, "op", "wrong"), Err(LoginError::Denied));
        }
        // Limited now, even with the right password.
        assert!(matches!(
            auth.login(ip, "op", "s3cret"),
            Err(LoginError::Limited(_))
        ));
        let other: IpAddr = "127.0.0.2".parse().unwrap();
        assert!(auth.login(other, "op", "s3cret").is_ok());
    }

    #[test]
    fn the_token_file_is_created_private_and_read_back() {
        let dir = std::env::temp_dir().join(format!("automat-token-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("token");
        let _ = std::fs::remove_file(&path);
        let t = token_file(&path).unwrap();
        assert_eq!(t.len(), 64);
        assert_eq!(token_file(&path).unwrap(), t);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&path).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o600);
        }
        let auth = Auth::new(Some(t.clone()), Vec::new());
        assert_eq!(auth.role_of(&t), Some(Role::Engineer));
        std::fs::write(&path, "short").unwrap();
        assert!(token_file(&path).unwrap_err().contains("at least 16"));
    }
}
