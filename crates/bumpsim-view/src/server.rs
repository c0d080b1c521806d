//! The local server: bound to 127.0.0.1 on a port the system picks, every
//! path under a random 128-bit token (`http://127.0.0.1:PORT/TOKEN/`).
//!
//! A request without the token, with another `Host` than the server's own
//! address (a page elsewhere reaching it by DNS rebinding), or with a
//! method other than GET (POST for the one export that writes) is answered
//! 404 with an empty body. Behind the token it serves the page and its
//! fixed assets (uPlot, the page's script and style) from the binary, and
//! the JSON answers of [`crate::api`], which name tests and channels by
//! index: no request can name a path, so nothing but the given files is
//! ever read.

use crate::api;
use crate::error::ViewError;
use crate::page::{self, Asset};
use crate::query::Query;
use crate::session::Session;
use std::path::PathBuf;
use tiny_http::{Header, Method, Request, Response, Server};

/// A running viewer server.
pub struct Viewer {
    server: Server,
    token: String,
    port: u16,
    session: Session,
    export_folder: PathBuf,
}

/// 128 random bits as 32 hex digits.
fn token() -> Result<String, ViewError> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes).map_err(|e| ViewError::Server {
        reason: format!("no random token: {e}"),
    })?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// Equal strings, compared in a time that does not depend on where they differ.
fn same(a: &str, b: &str) -> bool {
    a.len() == b.len() && a.bytes().zip(b.bytes()).fold(0u8, |d, (x, y)| d | (x ^ y)) == 0
}

fn header(name: &str, value: &str) -> Header {
    // both are ASCII constants or the content type of a fixed asset
    Header::from_bytes(name.as_bytes(), value.as_bytes())
        .unwrap_or_else(|_| Header::from_bytes(&b"X-Bumpsim"[..], &b"1"[..]).expect("ASCII header"))
}

type Answer = Response<std::io::Cursor<Vec<u8>>>;

fn answer(status: u16, content_type: &str, body: Vec<u8>) -> Answer {
    Response::from_data(body)
        .with_status_code(status)
        .with_header(header("Content-Type", content_type))
        .with_header(header("Cache-Control", "no-store"))
        .with_header(header("X-Content-Type-Options", "nosniff"))
        .with_header(header("Referrer-Policy", "no-referrer"))
        .with_header(header(
            "Content-Security-Policy",
            "default-src 'self'; img-src 'self' data: blob:; style-src 'self' 'unsafe-inline'; connect-src 'self'",
        ))
}

fn nothing() -> Answer {
    answer(404, "text/plain", Vec::new())
}

fn json(value: &serde_json::Value) -> Answer {
    answer(200, "application/json", value.to_string().into_bytes())
}

impl Viewer {
    /// Opens the inputs and binds the server (not yet serving).
    pub fn bind(session: Session, export_folder: PathBuf) -> Result<Viewer, ViewError> {
        let server = Server::http("127.0.0.1:0").map_err(|e| ViewError::Server {
            reason: format!("cannot listen on 127.0.0.1: {e}"),
        })?;
        let port = server
            .server_addr()
            .to_ip()
            .map(|a| a.port())
            .ok_or_else(|| ViewError::Server {
                reason: "no port".into(),
            })?;
        Ok(Viewer {
            server,
            token: token()?,
            port,
            session,
            export_folder,
        })
    }

    /// The page's address, token included.
    pub fn url(&self) -> String {
        format!("http://127.0.0.1:{}/{}/", self.port, self.token)
    }

    /// Serves requests until the process ends.
    pub fn serve(mut self) -> Result<(), ViewError> {
        loop {
            let request = self.server.recv().map_err(|e| ViewError::Server {
                reason: e.to_string(),
            })?;
            let response = self.respond(&request);
            // a browser that closed the connection is no error of the viewer
            let _ = request.respond(response);
        }
    }

    fn host_ok(&self, request: &Request) -> bool {
        let host = request
            .headers()
            .iter()
            .find(|h| h.field.equiv("Host"))
            .map(|h| h.value.as_str().to_string());
        let ours = [
            format!("127.0.0.1:{}", self.port),
            format!("localhost:{}", self.port),
        ];
        host.is_some_and(|h| ours.contains(&h))
    }

    fn respond(&mut self, request: &Request) -> Answer {
        let url = request.url().to_string();
        let (path, query) = url.split_once('?').unwrap_or((&url, ""));
        let Some(rest) = path.strip_prefix('/').and_then(|p| p.split_once('/')) else {
            return nothing();
        };
        let (token, route) = rest;
        let method = request.method().clone();
        let allowed =
            method == Method::Get || (method == Method::Post && route == "api/export-iso");
        if !same(token, &self.token) || !self.host_ok(request) || !allowed {
            return nothing();
        }
        if let Some(asset) = Asset::named(route) {
            return answer(
                200,
                asset.content_type(),
                asset.bytes(&self.session).into_bytes(),
            );
        }
        let Some(api_name) = route.strip_prefix("api/") else {
            return nothing();
        };
        match self.api(api_name, query) {
            Ok(Some(r)) => r,
            Ok(None) => nothing(),
            Err(e) => answer(
                400,
                "application/json",
                serde_json::json!({"error": e.to_string()})
                    .to_string()
                    .into_bytes(),
            ),
        }
    }

    fn api(&mut self, name: &str, query: &str) -> Result<Option<Answer>, ViewError> {
        const NAMES: [&str; 6] = [
            "series",
            "cursor",
            "metrics",
            "command",
            "export.csv",
            "export-iso",
        ];
        if name == "inputs" {
            return Ok(Some(json(&api::inputs(&self.session))));
        }
        if !NAMES.contains(&name) {
            return Ok(None);
        }
        let q = Query::parse(query)?;
        let s = &mut self.session;
        Ok(Some(match name {
            "series" => json(&api::series(s, &q)?),
            "cursor" => json(&api::cursor(s, &q)?),
            "metrics" => json(&api::pulse(s, &q)?),
            "command" => json(&api::command(s, &q)?),
            "export.csv" => answer(200, "text/csv", api::csv(s, &q)?.into_bytes()).with_header(
                header("Content-Disposition", "attachment; filename=\"view.csv\""),
            ),
            "export-iso" => json(&api::iso_mme(s, &q, &self.export_folder)?),
            _ => return Ok(None),
        }))
    }
}

/// The page as one self-contained file: assets inline, every present
/// channel's raw samples embedded (no server, no network).
pub fn standalone(session: &Session) -> Result<String, ViewError> {
    page::standalone(session)
}
