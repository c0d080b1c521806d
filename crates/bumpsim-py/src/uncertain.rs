//! The car's uncertainty carried through `impact` and `planar_impact`
//! (issue 39, item 4), the call `bumpsim impact|planar --uncertainty`
//! makes: `bumpsim_impact::propagation::Propagation` checks the keyword
//! arguments before anything runs, then predicts (each scalar output's
//! median and interval, each history's pointwise band over seeded draws of
//! the car) and, with `sobol=True`, gives Saltelli's first-order and total
//! Sobol' indices, with the GIL released. The results are the JSON objects
//! `--json` writes under `prediction` and `sensitivity`.

use crate::arrays::array1;
use crate::convert::{count_or, from_json, seed};
use crate::errors::{input, invalid, message};
use crate::frames;
use bumpsim_engine::EngineError;
use bumpsim_impact::prediction::{self, Outputs, Sampling};
use bumpsim_impact::propagation::{
    DEFAULT_SAMPLES, DEFAULT_SEED, DEFAULT_SOBOL_BASE, Propagation, PropagationError,
};
use bumpsim_impact::uncertainty::{Model, UncertaintyError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::path::PathBuf;

/// The uncertainty keyword arguments of `impact` and `planar_impact`, as
/// Python gave them.
pub struct Arguments<'a, 'py> {
    /// `uncertainty`: the file, or None.
    pub path: Option<PathBuf>,
    /// `samples`: draws (None: `DEFAULT_SAMPLES`).
    pub samples: Option<&'a Bound<'py, PyAny>>,
    /// `seed` (None: `DEFAULT_SEED`).
    pub seed: Option<&'a Bound<'py, PyAny>>,
    /// `level` of the intervals and bands.
    pub level: f64,
    /// `sobol`: also the indices.
    pub sobol: bool,
    /// `sobol_base`: base samples N (None: `DEFAULT_SOBOL_BASE`).
    pub sobol_base: Option<&'a Bound<'py, PyAny>>,
}

/// The checked arguments and the uncertainty they read.
pub struct Uncertain<M: Model> {
    propagation: Propagation<M>,
}

/// What a prediction gave: the JSON objects of `--json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Predicted {
    /// The `prediction` object.
    pub prediction: Value,
    /// The `sensitivity` object (with `sobol=True`).
    pub sensitivity: Option<Value>,
}

/// A refusal of the propagation as an `InputError` naming the keyword
/// argument (`samples`, `level`, `sobol_base` or `uncertainty`).
fn named(error: &PropagationError) -> PyErr {
    let text = message(error);
    match error {
        PropagationError::Sampling(UncertaintyError::Value { .. }) => invalid(text),
        PropagationError::Sampling(_) => invalid(format!("samples: {text}")),
        PropagationError::Sobol(_) => invalid(format!("sobol_base: {text}")),
        _ => invalid(format!("uncertainty: {text}")),
    }
}

/// The uncertainty keyword arguments checked, for a request the engine
/// runs (it reads the file against the car).
pub struct Checked {
    /// The file.
    pub path: PathBuf,
    /// Draws.
    pub samples: usize,
    /// Seed of the draws.
    pub seed: u64,
    /// Base samples of the Sobol indices, when asked.
    pub sobol_base: Option<usize>,
}

impl Arguments<'_, '_> {
    /// The arguments checked (`None`: no `uncertainty`): a value given
    /// without a file, or `sobol_base` without `sobol`, is refused, as the
    /// CLI's `requires`.
    pub fn options(&self) -> PyResult<Option<Checked>> {
        let given = [
            ("samples", self.samples.is_some()),
            ("seed", self.seed.is_some()),
            ("sobol", self.sobol),
            ("sobol_base", self.sobol_base.is_some()),
        ];
        let Some(path) = &self.path else {
            return match given.iter().find(|(_, set)| *set) {
                Some((name, _)) => Err(invalid(format!("{name}: needs uncertainty (a file)"))),
                None => Ok(None),
            };
        };
        if self.sobol_base.is_some() && !self.sobol {
            return Err(invalid("sobol_base: needs sobol=True"));
        }
        let limits = prediction::SAMPLES;
        let samples =
            count_or(self.samples, "samples", limits[0], limits[1])?.unwrap_or(DEFAULT_SAMPLES);
        let seed = seed(self.seed)?.unwrap_or(DEFAULT_SEED);
        let [low, high] = prediction::SOBOL_BASE;
        let base = count_or(self.sobol_base, "sobol_base", low, high)?;
        Ok(Some(Checked {
            path: path.clone(),
            samples,
            seed,
            sobol_base: self.sobol.then(|| base.unwrap_or(DEFAULT_SOBOL_BASE)),
        }))
    }
}

/// A refusal of an engine request as the exception it is: the car's
/// uncertainty named by the keyword argument, the rest with the library's
/// message.
pub fn engine(error: EngineError) -> PyErr {
    match &error {
        EngineError::Uncertainty { source, .. } => named(source),
        EngineError::Propagation(e) => invalid(format!("uncertainty: {}", message(e))),
        _ => input(error),
    }
}

impl<M: Model> Uncertain<M> {
    /// The arguments checked against `car` (`None`: no `uncertainty`).
    pub fn read(arguments: &Arguments, car: &M::Car) -> PyResult<Option<Self>> {
        let Some(checked) = arguments.options()? else {
            return Ok(None);
        };
        let sampling = Sampling {
            samples: checked.samples,
            seed: checked.seed,
            level: arguments.level,
        };
        let (path, base) = (&checked.path, checked.sobol_base);
        let propagation = Propagation::read(path, sampling, base, car).map_err(|e| named(&e))?;
        Ok(Some(Uncertain { propagation }))
    }

    /// The prediction of `run` over the uncertainty (and the Sobol indices
    /// when asked), the GIL released; `nominal` is `run`'s result for `car`.
    pub fn run<R: Outputs + Sync>(
        &self,
        py: Python<'_>,
        car: &M::Car,
        nominal: &R,
        run: &(dyn Fn(&M::Car) -> Option<R> + Sync),
    ) -> PyResult<Predicted> {
        let out = py
            .detach(|| self.propagation.run(car, nominal, run))
            .map_err(|e| invalid(format!("uncertainty: {}", message(&e))))?;
        let json = |e: serde_json::Error| invalid(e.to_string());
        let sensitivity = out.sensitivity.as_ref().map(serde_json::to_value);
        Ok(Predicted {
            prediction: serde_json::to_value(&out.prediction).map_err(json)?,
            sensitivity: sensitivity.transpose().map_err(json)?,
        })
    }
}

impl Predicted {
    /// `document` (a result's JSON) with the prediction and the indices
    /// beside its results, as `--json` writes it.
    pub fn with(predicted: &Option<Predicted>, document: impl Serialize) -> PyResult<String> {
        let mut document = serde_json::to_value(document).map_err(crate::errors::input)?;
        if let (Some(p), Some(fields)) = (predicted, document.as_object_mut()) {
            fields.insert("prediction".into(), p.prediction.clone());
            if let Some(s) = &p.sensitivity {
                fields.insert("sensitivity".into(), s.clone());
            }
        }
        serde_json::to_string_pretty(&document).map_err(crate::errors::input)
    }

    /// The pickled form: the JSON text (None without a prediction).
    pub fn state(predicted: &Option<Predicted>) -> PyResult<Option<String>> {
        predicted
            .as_ref()
            .map(|p| serde_json::to_string(p).map_err(crate::errors::input))
            .transpose()
    }

    /// The prediction of a pickled form.
    pub fn of_state(state: Option<&str>) -> PyResult<Option<Predicted>> {
        state
            .map(|s| serde_json::from_str(s).map_err(crate::errors::input))
            .transpose()
    }

    /// The `prediction` object as a dict (None without one).
    pub fn prediction<'py>(
        py: Python<'py>,
        predicted: &Option<Predicted>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        predicted
            .as_ref()
            .map(|p| from_json(py, &p.prediction))
            .transpose()
    }

    /// The `sensitivity` object as a dict (None without one).
    pub fn sensitivity<'py>(
        py: Python<'py>,
        predicted: &Option<Predicted>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let value = predicted.as_ref().and_then(|p| p.sensitivity.as_ref());
        value.map(|s| from_json(py, s)).transpose()
    }

    /// The bands of the histories: name → dict of numpy arrays `time`,
    /// `nominal`, `low`, `median`, `high` (the prediction's `bands`).
    pub fn bands<'py>(
        py: Python<'py>,
        predicted: &Option<Predicted>,
    ) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(p) = predicted else {
            return Ok(None);
        };
        let bands = PyDict::new(py);
        let empty = Vec::new();
        let list = p.prediction["bands"].as_array().unwrap_or(&empty);
        for b in list {
            let arrays = PyDict::new(py);
            let numbers = |v: &Value| -> Vec<f64> {
                let values = v.as_array().map_or(&[][..], Vec::as_slice);
                values
                    .iter()
                    .map(|x| x.as_f64().unwrap_or(f64::NAN))
                    .collect()
            };
            arrays.set_item("time", array1(py, numbers(&b["time"])))?;
            arrays.set_item("nominal", array1(py, numbers(&b["nominal"])))?;
            for end in ["low", "median", "high"] {
                arrays.set_item(end, array1(py, numbers(&b["band"][end])))?;
            }
            bands.set_item(b["name"].as_str().unwrap_or("?"), arrays)?;
        }
        Ok(Some(bands))
    }

    /// The spreads as a table: index `output`, columns `unit`, `nominal`,
    /// `median`, `low`, `high`, `mean`, `sd` (SI, in `unit`); attrs: the
    /// sampling (samples, seed, level) and the failed draws.
    pub fn frame<'py>(
        py: Python<'py>,
        predicted: &Option<Predicted>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let Some(p) = predicted else {
            return Ok(None);
        };
        let rows = PyList::empty(py);
        let empty = Vec::new();
        for o in p.prediction["outputs"].as_array().unwrap_or(&empty) {
            let row = PyDict::new(py);
            row.set_item("output", from_json(py, &o["name"])?)?;
            row.set_item("unit", from_json(py, &o["unit"])?)?;
            row.set_item("nominal", from_json(py, &o["nominal"])?)?;
            for key in ["median", "low", "high", "mean", "sd"] {
                row.set_item(key, from_json(py, &o["spread"][key])?)?;
            }
            rows.append(row)?;
        }
        let attrs = PyDict::new(py);
        attrs.set_item("sampling", from_json(py, &p.prediction["sampling"])?)?;
        attrs.set_item("failed", from_json(py, &p.prediction["failed"])?)?;
        frames::records(py, rows, &["output"], &attrs).map(Some)
    }
}
