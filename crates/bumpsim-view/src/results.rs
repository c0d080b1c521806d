//! bumpsim result JSONs in the viewer: an identification or prediction
//! (`identify --json`, `predict --json`) shows its model and each case's
//! fit and ISO/TS 18571 rating in the words `identify` prints them
//! (`fit 99.69 %`, `ISO/TS 18571 rating 0.998 (excellent; corridor …)`,
//! through [`Rating`]'s own text); a verdict (`verdict --json`) its
//! criteria per test (value, limit, margin, outcome); any other result its
//! top-level numbers and texts as a table. A prediction's JSON holds no
//! curves; given with its study, the model file it names (`model`, the
//! path `predict` was given) is simulated on the study's cases.

use crate::error::ViewError;
use bumpsim_core::units::format_number;
use bumpsim_signal::rating::Rating;
use serde::Serialize;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The largest result JSON read, bytes.
pub const MAX_RESULT_BYTES: u64 = 256 << 20;

/// One case of an identification or prediction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseLine {
    /// Case name.
    pub name: String,
    /// `fit 99.69 %`.
    pub fit: String,
    /// `ISO/TS 18571 rating 0.998 (excellent; …)`.
    pub rating: String,
}

/// A result file as the page shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResultFile {
    /// The path as given.
    pub path: PathBuf,
    /// `identification`, `prediction` or `result`.
    pub kind: &'static str,
    /// Model lines (masses, dampers, springs) when it has a model.
    pub model: Vec<String>,
    /// Per-case fit and rating.
    pub cases: Vec<CaseLine>,
    /// Top-level scalars (key, value as text).
    pub fields: Vec<(String, String)>,
    /// A verdict's criteria: one row per test and criterion (test, name,
    /// value, limit, margin, outcome), numbers as the JSON holds them (SI).
    pub criteria: Vec<[String; 6]>,
    /// Measured against model per case, when the study was given too.
    pub curves: Vec<crate::curves::CaseCurves>,
    /// A planar result's top view over time.
    pub planar: Option<crate::planar_view::PlanarView>,
    /// A verdict's tests with histories (`verdict --json`'s `history`):
    /// each test's top view and curves, linked from its criteria.
    pub tests: Vec<TestView>,
    /// What the page says about the curves (a prediction's: where they
    /// come from, or why there are none).
    pub note: Option<String>,
    /// The model file a prediction names (its `model`), when it is one.
    #[serde(skip)]
    pub model_file: Option<PathBuf>,
}

/// A prediction JSON holds each case's fit, not its curves.
pub const PREDICTION_NOTE: &str = "the prediction JSON holds each case's fit and rating, not its curves: give its study too (bumpsim view STUDY.toml PREDICTION.json) and the model file it names is simulated on the study's cases";

fn text_of(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        Value::Null => String::new(),
        other => other.to_string(),
    }
}

/// One test of a verdict, drawn from the histories its JSON holds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TestView {
    /// The test's name (the criteria table's first column).
    pub name: String,
    /// Its top view, force and yaw over time.
    pub planar: crate::planar_view::PlanarView,
}

fn test_name(test: &Value) -> &str {
    test["test"]["name"]
        .as_str()
        .or(test["test"].as_str())
        .unwrap_or("test")
}

/// A verdict's tests that carry their histories.
fn test_views(value: &Value) -> Vec<TestView> {
    let verdict = value.get("verdict").unwrap_or(value);
    let tests = verdict["tests"].as_array().into_iter().flatten();
    tests
        .filter_map(|test| {
            let impact = serde_json::json!({ "result": test["history"], "body": test["body"] });
            Some(TestView {
                name: test_name(test).to_string(),
                planar: crate::planar_view::planar_view(&impact)?,
            })
        })
        .collect()
}

/// A verdict's rows: each test's criteria.
fn criteria_rows(value: &Value) -> Vec<[String; 6]> {
    // `verdict --json` nests the verdict beside the bumper target
    let verdict = value.get("verdict").unwrap_or(value);
    let Some(tests) = verdict["tests"].as_array() else {
        return Vec::new();
    };
    let mut rows = Vec::new();
    for test in tests {
        let name = test_name(test);
        for c in test["criteria"].as_array().into_iter().flatten() {
            rows.push([
                name.to_string(),
                text_of(&c["name"]),
                text_of(&c["value"]),
                text_of(&c["limit"]),
                text_of(&c["margin"]),
                text_of(&c["outcome"]),
            ]);
        }
    }
    rows
}

fn numbers(value: &Value, key: &str) -> Vec<f64> {
    value[key]
        .as_array()
        .map(|a| a.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default()
}

fn rating(value: &Value) -> Option<Rating> {
    let r = &value["rating"];
    Some(Rating {
        overall: r["overall"].as_f64()?,
        corridor: r["corridor"].as_f64()?,
        phase: r["phase"].as_f64()?,
        magnitude: r["magnitude"].as_f64()?,
        slope: r["slope"].as_f64()?,
    })
}

fn case_line(case: &Value) -> Option<CaseLine> {
    let fit = case["fit_percent"].as_f64()?;
    Some(CaseLine {
        name: case["name"].as_str().unwrap_or("case").to_string(),
        fit: format!("fit {} %", format_number(fit, 4)),
        rating: match rating(case) {
            Some(r) => format!("ISO/TS 18571 rating {r}"),
            None => "ISO/TS 18571 rating: none".into(),
        },
    })
}

fn model_lines(value: &Value) -> Vec<String> {
    let list = |key: &str, unit: &str, factor: f64| -> Option<String> {
        let v = numbers(value, key);
        (!v.is_empty()).then(|| {
            let parts: Vec<String> = v
                .iter()
                .map(|x| format!("{} {unit}", format_number(x * factor, 4)))
                .collect();
            format!("{key}: {}", parts.join(", "))
        })
    };
    [
        list("masses", "kg", 1.0),
        list("dampers", "Ns/mm", 1e-3),
        list("springs", "N/mm", 1e-3),
    ]
    .into_iter()
    .flatten()
    .collect()
}

impl ResultFile {
    /// Reads a result JSON.
    pub fn read(path: &Path) -> Result<ResultFile, ViewError> {
        let input = |reason: String| ViewError::Input {
            path: path.to_path_buf(),
            reason,
        };
        let size = std::fs::metadata(path)
            .map_err(|e| input(e.to_string()))?
            .len();
        if size > MAX_RESULT_BYTES {
            return Err(input(format!(
                "{size} bytes: larger than a bumpsim result ({MAX_RESULT_BYTES} bytes at most)"
            )));
        }
        // regular files only: a pipe would block the viewer, not end
        if let Some(what) =
            bumpsim_core::files::not_a_file(path).map_err(|e| input(e.to_string()))?
        {
            return Err(input(format!("{what}, not a result file")));
        }
        let text = std::fs::read_to_string(path).map_err(|e| input(e.to_string()))?;
        let value: Value =
            serde_json::from_str(&text).map_err(|e| input(format!("not a JSON result: {e}")))?;
        if !value.is_object() {
            return Err(input("not a bumpsim result: expected a JSON object".into()));
        }
        let cases: Vec<CaseLine> = value["cases"]
            .as_array()
            .map(|a| a.iter().filter_map(case_line).collect())
            .unwrap_or_default();
        let criteria = criteria_rows(&value);
        let planar = crate::planar_view::planar_view(&value);
        let kind = match (value.get("objective"), cases.is_empty()) {
            (Some(_), false) => "identification",
            (None, false) => "prediction",
            _ if !criteria.is_empty() => "verdict",
            _ if planar.is_some() => "planar impact",
            _ => "result",
        };
        let fields = value
            .as_object()
            .map(|o| {
                o.iter()
                    .filter_map(|(k, v)| match v {
                        Value::Number(n) => Some((k.clone(), n.to_string())),
                        Value::String(s) => Some((k.clone(), s.clone())),
                        Value::Bool(b) => Some((k.clone(), b.to_string())),
                        _ => None,
                    })
                    .collect()
            })
            .unwrap_or_default();
        Ok(ResultFile {
            path: path.to_path_buf(),
            kind,
            model: model_lines(&value),
            cases,
            fields,
            criteria,
            curves: Vec::new(),
            planar,
            tests: test_views(&value),
            note: (kind == "prediction").then(|| PREDICTION_NOTE.to_string()),
            model_file: value["model"]
                .as_str()
                .map(PathBuf::from)
                .filter(|p| kind == "prediction" && p.is_file()),
        })
    }
}
