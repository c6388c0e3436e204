//! `[opcua]` of `automat.toml` (E346), read from the project file's text
//! so spans point at the key:
//!
//! ```toml
//! [opcua]
//! listen = "127.0.0.1:4840"     # [ADDR:]PORT; a port alone binds 127.0.0.1
//! pki_dir = "pki"               # the server's certificate and key, client certificates
//!                               # (relative to the project; default .automat/opcua-pki)
//! trust_client_certs = false    # true: any client certificate (the login still decides)
//! ```

use automat_base::{Code, Diagnostic, FileId, Span};
use serde::Deserialize;
use std::net::SocketAddr;
use std::path::PathBuf;
use toml::Spanned;

#[derive(Deserialize)]
struct RawRoot {
    opcua: Option<RawOpcua>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOpcua {
    listen: Spanned<String>,
    pki_dir: Option<String>,
    #[serde(default)]
    trust_client_certs: bool,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Config {
    pub addr: SocketAddr,
    /// As written (relative to the project folder when not absolute).
    pub pki_dir: Option<PathBuf>,
    pub trust_client_certs: bool,
}

/// `[ADDR:]PORT`: a port alone binds 127.0.0.1.
pub fn parse_addr(s: &str) -> Result<SocketAddr, String> {
    let s = s.trim();
    if let Ok(port) = s.parse::<u16>() {
        return Ok(SocketAddr::from(([127, 0, 0, 1], port)));
    }
    s.parse::<SocketAddr>().map_err(|_| {
        format!("`{s}` is not PORT or ADDR:PORT (e.g. 4840, 127.0.0.1:4840, [::1]:4840)")
    })
}

/// `[opcua]` of the project file `text` (`file` in the caller's source
/// map); `None` when there is none.
pub fn load(text: &str, file: FileId) -> Result<Option<Config>, Vec<Diagnostic>> {
    let c = |x: usize| u32::try_from(x).unwrap_or(u32::MAX);
    let err = |r: std::ops::Range<usize>, msg: String| {
        vec![Diagnostic::error(
            Code::E346,
            Span::new(file, c(r.start), c(r.end)),
            msg,
        )]
    };
    let raw: RawRoot = toml::from_str(text).map_err(|e| {
        err(
            e.span().unwrap_or(0..0),
            format!("invalid [opcua] table: {}", e.message().trim_end()),
        )
    })?;
    let Some(raw) = raw.opcua else {
        return Ok(None);
    };
    let addr = parse_addr(raw.listen.get_ref())
        .map_err(|e| err(raw.listen.span(), format!("listen: {e}")))?;
    Ok(Some(Config {
        addr,
        pki_dir: raw.pki_dir.map(PathBuf::from),
        trust_client_certs: raw.trust_client_certs,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_read_and_its_errors_point_at_the_key() {
        let f = FileId(0);
        assert_eq!(load("[project]\nname = \"x\"\n", f), Ok(None));
        assert_eq!(
            load("[opcua]\nlisten = \"4841\"\n", f),
            Ok(Some(Config {
                addr: SocketAddr::from(([127, 0, 0, 1], 4841)),
                pki_dir: None,
                trust_client_certs: false
            }))
        );
        let text = "[opcua]\nlisten = \"nowhere\"\n";
        let e = load(text, f).expect_err("bad listen");
        assert_eq!(e[0].code, Code::E346);
        assert_eq!(
            e[0].message,
            "listen: `nowhere` is not PORT or ADDR:PORT (e.g. 4840, 127.0.0.1:4840, [::1]:4840)"
        );
        assert_eq!(
            &text[e[0].span.start as usize..e[0].span.end as usize],
            "\"nowhere\""
        );
        let e = load("[opcua]\nlisten = \"4840\"\nport = 1\n", f).expect_err("unknown key");
        assert!(
            e[0].message
                .starts_with("invalid [opcua] table: unknown field `port`"),
            "{}",
            e[0].message
        );
    }
}
