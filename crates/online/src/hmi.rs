//! The web HMI: a single-page application (plain HTML, CSS and JS, no
//! build step) embedded in the binary and served at `/` and `/hmi/…`.
//!
//! The files need no authentication: they hold no data, everything they
//! show comes through the authenticated API (`docs/hmi.md`). Every answer
//! carries a Content-Security-Policy that allows only this origin (no
//! inline scripts, nothing from elsewhere), and no referrer, since a
//! `/?token=` address holds a secret.

use axum::http::{header, HeaderName, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};

const INDEX: &str = include_str!("../hmi/index.html");
const APP_JS: &str = include_str!("../hmi/app.js");
const CHARTS_JS: &str = include_str!("../hmi/charts.js");
const DRAWINGS_JS: &str = include_str!("../hmi/drawings.js");
const MIMIC_JS: &str = include_str!("../hmi/mimic.js");
const APP_CSS: &str = include_str!("../hmi/app.css");

/// `connect-src 'self'` covers the WebSocket of the same host and port.
const CSP: &str = "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data:; \
connect-src 'self'; form-action 'self'; base-uri 'none'; frame-ancestors 'none'";

fn asset(content_type: &'static str, body: &'static str) -> Response {
    let headers: [(HeaderName, HeaderValue); 5] = [
        (header::CONTENT_TYPE, HeaderValue::from_static(content_type)),
        (
            header::CONTENT_SECURITY_POLICY,
            HeaderValue::from_static(CSP),
        ),
        (
            header::REFERRER_POLICY,
            HeaderValue::from_static("no-referrer"),
        ),
        (
            header::X_CONTENT_TYPE_OPTIONS,
            HeaderValue::from_static("nosniff"),
        ),
        // The files change only with the binary; a new build must be seen.
        (header::CACHE_CONTROL, HeaderValue::from_static("no-cache")),
    ];
    (StatusCode::OK, headers, body).into_response()
}

pub async fn index() -> Response {
    asset("text/html; charset=utf-8", INDEX)
}

pub async fn app_js() -> Response {
    asset("text/javascript; charset=utf-8", APP_JS)
}

pub async fn charts_js() -> Response {
    asset("text/javascript; charset=utf-8", CHARTS_JS)
}

pub async fn drawings_js() -> Response {
    asset("text/javascript; charset=utf-8", DRAWINGS_JS)
}

pub async fn mimic_js() -> Response {
    asset("text/javascript; charset=utf-8", MIMIC_JS)
}

pub async fn app_css() -> Response {
    asset("text/css; charset=utf-8", APP_CSS)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every file the page loads is one the server embeds and routes, and
    /// the page loads nothing from elsewhere (the CSP would block it).
    #[test]
    fn the_page_loads_only_its_own_files() {
        for file in [
            "/hmi/app.js",
            "/hmi/charts.js",
            "/hmi/drawings.js",
            "/hmi/mimic.js",
            "/hmi/app.css",
        ] {
            assert!(INDEX.contains(&format!("\"{file}\"")), "{file}");
        }
        for text in [INDEX, APP_JS, CHARTS_JS, DRAWINGS_JS, MIMIC_JS, APP_CSS] {
            assert!(!text.contains("http://") || text.contains("http://www.w3.org/2000/svg"));
            assert!(!text.contains("https://"));
        }
        // No inline script or style attribute the policy would refuse.
        assert!(!INDEX.contains("<script>") && !INDEX.contains(" style="));
        assert!(!INDEX.contains(" onclick="));
    }
}
