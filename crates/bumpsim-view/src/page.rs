//! The page: one HTML file, its script and style, and uPlot (MIT, Leon
//! Sorokin; `assets/uPlot.LICENSE`), all compiled into the binary so the
//! page works offline. Served, the assets come as separate files under the
//! token; standalone (`--html`), they are inlined with the data: every
//! present channel's raw samples in its display unit (g, kN, mm), so the
//! file opens from disk and draws the same plots without a server.

use crate::api;
use crate::error::ViewError;
use crate::session::Session;
use serde_json::{Value, json};

const INDEX: &str = include_str!("../assets/index.html");
const APP_JS: &str = include_str!("../assets/app.js");
const APP_CSS: &str = include_str!("../assets/app.css");
const UPLOT_JS: &str = include_str!("../assets/uPlot.iife.min.js");
const UPLOT_CSS: &str = include_str!("../assets/uPlot.min.css");
const UPLOT_LICENSE: &str = include_str!("../assets/uPlot.LICENSE");

/// A fixed file the server serves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Asset {
    /// The page.
    Index,
    /// The page's script.
    AppJs,
    /// The page's style.
    AppCss,
    /// uPlot's script.
    UplotJs,
    /// uPlot's style.
    UplotCss,
    /// uPlot's licence.
    UplotLicense,
}

impl Asset {
    /// The asset a route names, if any.
    pub fn named(route: &str) -> Option<Asset> {
        Some(match route {
            "" | "index.html" => Asset::Index,
            "app.js" => Asset::AppJs,
            "app.css" => Asset::AppCss,
            "uPlot.js" => Asset::UplotJs,
            "uPlot.css" => Asset::UplotCss,
            "uPlot.LICENSE" => Asset::UplotLicense,
            _ => return None,
        })
    }

    /// Its content type.
    pub fn content_type(self) -> &'static str {
        match self {
            Asset::Index => "text/html; charset=utf-8",
            Asset::AppJs | Asset::UplotJs => "text/javascript; charset=utf-8",
            Asset::AppCss | Asset::UplotCss => "text/css; charset=utf-8",
            Asset::UplotLicense => "text/plain; charset=utf-8",
        }
    }

    /// Its text.
    pub fn bytes(self, _session: &Session) -> String {
        match self {
            Asset::Index => served_index(),
            Asset::AppJs => APP_JS.into(),
            Asset::AppCss => APP_CSS.into(),
            Asset::UplotJs => UPLOT_JS.into(),
            Asset::UplotCss => UPLOT_CSS.into(),
            Asset::UplotLicense => UPLOT_LICENSE.into(),
        }
    }
}

fn served_index() -> String {
    INDEX
        .replace(
            "{{HEAD}}",
            "<link rel=\"stylesheet\" href=\"uPlot.css\"><link rel=\"stylesheet\" href=\"app.css\">",
        )
        .replace(
            "{{SCRIPTS}}",
            "<script src=\"uPlot.js\"></script><script src=\"app.js\"></script>",
        )
}

/// JSON safe inside `<script>`: no `</` and no `<!--`.
fn script_json(value: &Value) -> String {
    value
        .to_string()
        .replace("</", "<\\/")
        .replace("<!--", "<\\!--")
}

/// Every present channel's raw samples, in its display unit.
fn embedded(session: &Session) -> Value {
    let mut raw = serde_json::Map::new();
    for (t, test) in session.tests.iter().enumerate() {
        for (i, entry) in test.data.entries.iter().enumerate() {
            if !entry.present {
                continue;
            }
            let Ok(c) = test.data.load(i) else { continue };
            let unit = c.dimension.display_unit();
            let values: Vec<f64> = c.series.values().iter().map(|&v| unit.from_si(v)).collect();
            raw.insert(
                format!("{t}:{i}"),
                json!({
                    "label": format!("T{}: {} {}", t + 1, c.code, c.name),
                    "test": t, "code": c.code, "name": c.name,
                    "dimension": c.dimension.name(), "unit": unit.symbol,
                    "start": c.series.start(), "step": c.series.step(), "value": values,
                }),
            );
        }
    }
    json!({ "inputs": api::inputs(session), "raw": raw })
}

/// The standalone page (`--html`).
pub fn standalone(session: &Session) -> Result<String, ViewError> {
    let data = script_json(&embedded(session));
    let style = format!("<style>{UPLOT_CSS}\n{APP_CSS}</style>");
    let scripts = format!(
        "<script id=\"bumpsim-data\" type=\"application/json\">{data}</script>\n<script>{}</script>\n<script>{}</script>",
        UPLOT_JS.replace("</script", "<\\/script"),
        APP_JS.replace("</script", "<\\/script")
    );
    Ok(INDEX
        .replace("{{HEAD}}", &style)
        .replace("{{SCRIPTS}}", &scripts))
}
