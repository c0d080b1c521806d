//! The identification of a study whose model is not the linear chain (a
//! links study, a planar study): the engine's identify request
//! (`bumpsim_engine::identify`, the model picked from the study's declared
//! kind), exactly as `bumpsim identify STUDY` makes it, and its outcome
//! held whole: the text, the warnings, the JSON document (`identify
//! --json`, its top-level fields as attributes) and the identified car file
//! (`identify --car`), written through the library's writer (temporary
//! file and rename, never onto the study or a file it names). No
//! equations here: every figure is the document's.

use crate::convert::from_json;
use crate::errors::{input, invalid, reading};
use crate::frames;
use crate::state::{decode, encode, reduce};
use bumpsim_engine::{IdentifyRequest, Outcome};
use bumpsim_io::kind::ModelKind;
use bumpsim_io::output::Outputs;
use pyo3::exceptions::PyAttributeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyType};
use serde_json::{Map, Value};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Registers the class of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<StudyIdentification>()
}

/// The engine's identify request on the study of `kind` (the front end
/// asked the study's kind), its car file asked for, as the identification
/// it returns.
pub fn identify(
    py: Python<'_>,
    kind: ModelKind,
    request: &IdentifyRequest<'_>,
) -> PyResult<StudyIdentification> {
    let request = IdentifyRequest {
        car: true,
        ..*request
    };
    let outcome = py
        .detach(|| bumpsim_engine::identify(kind, &request))
        .map_err(|e| reading(request.study, e))?;
    StudyIdentification::of(Held {
        kind: kind.name().to_string(),
        study: request.study.to_path_buf(),
        outcome,
    })
}

/// What a [`StudyIdentification`] holds and pickles.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
struct Held {
    /// The study's model kind (`links`, `planar`).
    kind: String,
    /// The study file.
    study: PathBuf,
    /// The engine's answer.
    outcome: Outcome,
}

/// A study identified by the engine (`bumpsim identify STUDY` of a links or
/// planar study): the fields of its `identify --json` as attributes.
#[pyclass(frozen, module = "bumpsim")]
pub struct StudyIdentification {
    held: Held,
    document: Value,
}

impl StudyIdentification {
    fn of(held: Held) -> PyResult<Self> {
        let document = serde_json::from_str(&held.outcome.json).map_err(input)?;
        Ok(StudyIdentification { held, document })
    }

    /// The document's top-level fields whose values are lists (the tables).
    fn tables(&self) -> Vec<&str> {
        self.document
            .as_object()
            .map(|o| {
                o.iter()
                    .filter(|(_, v)| v.is_array())
                    .map(|(k, _)| k.as_str())
                    .collect()
            })
            .unwrap_or_default()
    }
}

#[pymethods]
impl StudyIdentification {
    /// The study's model kind: `links` or `planar`.
    #[getter]
    fn kind(&self) -> String {
        self.held.kind.clone()
    }
    /// The study file.
    #[getter]
    fn study(&self) -> PathBuf {
        self.held.study.clone()
    }
    /// The whole `identify --json` document as a dict.
    #[getter]
    fn document<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.document)
    }
    /// Warnings about the result.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.held.outcome.warnings.clone()
    }
    /// The identified car as a car file (TOML), as `identify --car` writes it.
    #[getter]
    fn car_toml(&self) -> Option<String> {
        self.held.outcome.car.clone()
    }
    /// What `bumpsim identify` prints.
    fn summary(&self) -> String {
        self.held.outcome.text.clone()
    }
    /// The document as `bumpsim identify --json` writes it.
    fn to_json(&self) -> String {
        self.held.outcome.json.clone()
    }
    /// Writes the identified car file to `path` as `identify --car` does:
    /// whole (a temporary file renamed) and never onto the study or a file
    /// it names.
    fn write_car(&self, py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<()> {
        let path = crate::convert::path(path, "path", "a file")?;
        let Some(car) = &self.held.outcome.car else {
            return Err(invalid(format!(
                "{}: the identification gave no car file",
                self.held.study.display()
            )));
        };
        let mut outputs = Outputs::new();
        outputs.input_with_references(&self.held.study);
        py.detach(|| outputs.write_file(&path, car.as_bytes()))
            .map_err(crate::errors::file_or_input)
    }
    /// A table of the document (a top-level field whose value is a list:
    /// `parameters`, `plastic_sets`, `forward`, `fits`, ...) as a
    /// DataFrame: one row per entry, indexed by its `case` and `name` where
    /// every entry has them; an interval `[low, high]` becomes the columns
    /// `K_low` and `K_high` (as `Identification.to_pandas`); a `[name, value]` pair the row `name`, column
    /// the field. Units are the document's (SI; a `unit` column where the
    /// rows differ).
    fn to_pandas<'py>(&self, py: Python<'py>, table: &str) -> PyResult<Bound<'py, PyAny>> {
        let Some(Value::Array(entries)) = self.document.get(table) else {
            return Err(invalid(format!(
                "table {table:?}: not a list of the document (its lists: {})",
                self.tables().join(", ")
            )));
        };
        let intervals = intervals(entries);
        let rows: Vec<Value> = entries.iter().map(|e| row(table, e, &intervals)).collect();
        let index: Vec<&str> = ["case", "name"]
            .into_iter()
            .filter(|k| !rows.is_empty() && rows.iter().all(|r| r.get(*k).is_some()))
            .collect();
        let rows = from_json(py, &rows)?.cast_into::<PyList>()?;
        let attrs = PyDict::new(py);
        attrs.set_item("kind", &self.held.kind)?;
        attrs.set_item("table", table)?;
        frames::records(py, rows, &index, &attrs)
    }
    /// A field of the `identify --json` document (`parameters`, `fits`,
    /// `verdict`, `plastic_sets`, `forward`, ... for a links study).
    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.document.get(name) {
            Some(value) => from_json(py, value),
            None => Err(PyAttributeError::new_err(format!(
                "'StudyIdentification' object has no attribute {name:?} (not a field of this {} study's document)",
                self.held.kind
            ))),
        }
    }
    fn __dir__(slf: &Bound<'_, Self>) -> PyResult<Vec<String>> {
        let object = slf.py().import("builtins")?.getattr("object")?;
        let mut names: Vec<String> = object.call_method1("__dir__", (slf,))?.extract()?;
        if let Some(o) = slf.get().document.as_object() {
            names.extend(o.keys().cloned());
        }
        names.sort();
        names.dedup();
        Ok(names)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.held == other.held
    }
    /// Pickles as the request's outcome.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        reduce(slf.as_any(), &encode(&slf.get().held)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        StudyIdentification::of(decode(state, "StudyIdentification")?)
    }
    fn __repr__(&self) -> String {
        format!(
            "StudyIdentification({} study {:?}, car {:?})",
            self.held.kind,
            shown(&self.held.study),
            self.document["car"].as_str().unwrap_or("?")
        )
    }
}

fn shown(path: &Path) -> String {
    path.display().to_string()
}

/// The keys whose value is an interval `[low, high]` in some entry.
fn intervals(entries: &[Value]) -> BTreeSet<String> {
    entries
        .iter()
        .filter_map(Value::as_object)
        .flat_map(|o| o.iter())
        .filter(|(_, v)| interval(v).is_some())
        .map(|(k, _)| k.clone())
        .collect()
}

/// `[low, high]`, each a number or null (an end JSON cannot write).
fn interval(value: &Value) -> Option<[&Value; 2]> {
    let end = |v: &Value| v.is_number() || v.is_null();
    match value.as_array().map(Vec::as_slice) {
        Some([low, high]) if end(low) && end(high) => Some([low, high]),
        _ => None,
    }
}

/// One entry of a table as a row: an object with its `intervals` split
/// (none: both ends null), a `[name, value]` pair as `{name, <field>}`,
/// anything else as `{<field>}`.
fn row(field: &str, entry: &Value, intervals: &BTreeSet<String>) -> Value {
    let mut row = Map::new();
    match entry {
        Value::Object(o) => {
            for (key, value) in o {
                if !intervals.contains(key) {
                    row.insert(key.clone(), value.clone());
                    continue;
                }
                let [low, high] = interval(value).unwrap_or([&Value::Null, &Value::Null]);
                row.insert(format!("{key}_low"), low.clone());
                row.insert(format!("{key}_high"), high.clone());
            }
        }
        Value::Array(pair) if matches!(pair.as_slice(), [Value::String(_), _]) => {
            row.insert("name".into(), pair[0].clone());
            row.insert(field.into(), pair[1].clone());
        }
        other => {
            row.insert(field.into(), other.clone());
        }
    }
    Value::Object(row)
}
