//! Design of Experiments (bumpsim-doe), the calls `bumpsim doe design`,
//! `fit` and `predict` make: designs as tables, regressions of data-file
//! responses on factors in coded units, model files and predictions.

use crate::arrays::{array2, vector};
use crate::errors::{InputError, file_or_input, input, message};
use crate::ident::from_json;
use bumpsim_doe::data::Data;
use bumpsim_doe::design::{self, DesignKind, DesignOptions};
use bumpsim_doe::model::{Factor, ModelFile, Response};
use bumpsim_doe::regression::{fit as core_fit, terms};
use numpy::PyArray2;
use pyo3::prelude::*;
use std::path::PathBuf;

/// Registers the classes and functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Design>()?;
    m.add_class::<DoeModel>()?;
    m.add_function(wrap_pyfunction!(doe_design, m)?)?;
    m.add_function(wrap_pyfunction!(doe_fit, m)?)?;
    m.add_function(wrap_pyfunction!(doe_stiffness, m)?)?;
    Ok(())
}

fn factors(specs: &[String]) -> PyResult<Vec<Factor>> {
    specs
        .iter()
        .map(|s| {
            s.parse::<Factor>()
                .map_err(|e| InputError::new_err(format!("factors: {}", message(&e))))
        })
        .collect()
}

/// A design: factor names, runs in coded and physical units, run order.
#[pyclass(frozen, module = "bumpsim")]
pub struct Design {
    design: design::Design,
    factors: Vec<Factor>,
    order: Vec<usize>,
    #[pyo3(get)]
    resolution: Option<usize>,
}

#[pymethods]
impl Design {
    /// Factor names.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.design.factors.clone()
    }
    /// Run order: indices (0-based) into the standard order.
    #[getter]
    fn order(&self) -> Vec<usize> {
        self.order.clone()
    }
    /// Coded levels, runs (in run order) × factors.
    #[getter]
    fn coded(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        let rows: Vec<Vec<f64>> = self
            .order
            .iter()
            .map(|&i| self.design.runs[i].clone())
            .collect();
        array2(py, &rows, self.design.factors.len())
    }
    /// Physical levels, runs (in run order) × factors.
    #[getter]
    fn physical(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        let rows: Vec<Vec<f64>> = self
            .order
            .iter()
            .map(|&i| {
                self.design.runs[i]
                    .iter()
                    .zip(&self.factors)
                    .map(|(z, f)| f.physical(*z))
                    .collect()
            })
            .collect();
        array2(py, &rows, self.design.factors.len())
    }
    /// The design table as `bumpsim doe design -o` writes it.
    fn to_csv(&self) -> String {
        self.design.to_csv(&self.factors, &self.order)
    }
}

/// Makes a design (as `bumpsim doe design`): `kind` full, fractional, ccf,
/// ccc, lhs or uniform; `factors` as "NAME:LOW:HIGH" strings.
#[pyfunction]
#[pyo3(signature = (kind, factors, generators = Vec::new(), centre = 0, runs = 20, seed = 1, randomise = false))]
fn doe_design(
    kind: &str,
    factors: Vec<String>,
    generators: Vec<String>,
    centre: usize,
    runs: usize,
    seed: u64,
    randomise: bool,
) -> PyResult<Design> {
    let factors = self::factors(&factors)?;
    let kind: DesignKind = kind.parse().map_err(input)?;
    let names: Vec<&str> = factors.iter().map(|f| f.name.as_str()).collect();
    let options = DesignOptions {
        generators,
        centre,
        runs,
        seed,
    };
    let (design, resolution) = design::make(kind, &names, &options).map_err(input)?;
    let order = design.order(randomise, seed);
    Ok(Design {
        design,
        factors,
        order,
        resolution,
    })
}

/// The stiffness of a force–displacement curve (displacement m, force N):
/// slope of the least-squares line over `range` (m; default the points
/// between 10 % and 90 % of the peak force), as `bumpsim doe stiffness`.
#[pyfunction]
#[pyo3(signature = (displacement, force, range = None))]
fn doe_stiffness<'py>(
    py: Python<'py>,
    displacement: &Bound<'py, PyAny>,
    force: &Bound<'py, PyAny>,
    range: Option<(f64, f64)>,
) -> PyResult<Bound<'py, PyAny>> {
    let (d, f) = (
        vector(displacement, "displacement")?,
        vector(force, "force")?,
    );
    let result =
        bumpsim_doe::stiffness::stiffness(&d, &f, range.map(|(a, b)| [a, b])).map_err(input)?;
    from_json(py, &result)
}

/// A DOE model file: factors and fitted responses.
#[pyclass(frozen, module = "bumpsim")]
pub struct DoeModel {
    inner: ModelFile,
}

#[pymethods]
impl DoeModel {
    /// Reads a model file (JSON from `doe fit`, or written by hand).
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let inner = ModelFile::read(&path).map_err(file_or_input)?;
        Ok(DoeModel { inner })
    }
    /// The model as `bumpsim doe fit --json` writes it.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.inner).map_err(input)
    }
    /// The factors and responses (the JSON's fields).
    fn as_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.inner)
    }
    /// Predicts every response at physical factor values `at` (name → value):
    /// values with 95 % confidence and prediction intervals, and warnings.
    fn predict<'py>(&self, py: Python<'py>, at: Vec<(String, f64)>) -> PyResult<Bound<'py, PyAny>> {
        let prediction = self.inner.predict(&at).map_err(input)?;
        from_json(py, &prediction)
    }
}

/// Fits `responses` on `factors` (columns of the data CSV at `data`, `name
/// [unit]` headers) in coded units, as `bumpsim doe fit`; `low`/`high`
/// default to the data's extremes.
#[pyfunction]
// one Rust argument per Python keyword argument
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (data, factors, responses, low = Vec::new(), high = Vec::new(), interactions = false, squares = false))]
fn doe_fit(
    py: Python<'_>,
    data: PathBuf,
    factors: Vec<String>,
    responses: Vec<String>,
    low: Vec<f64>,
    high: Vec<f64>,
    interactions: bool,
    squares: bool,
) -> PyResult<DoeModel> {
    let path = data.as_path();
    let data = Data::read(path).map_err(file_or_input)?;
    let in_file = |e: bumpsim_doe::data::ColumnError| {
        InputError::new_err(format!("{}: {}", path.display(), message(&e)))
    };
    let (factors, coded) = data.coded(&factors, &low, &high).map_err(in_file)?;
    let names: Vec<String> = factors.iter().map(|f| f.name.clone()).collect();
    let model_terms = terms(factors.len(), interactions, squares);
    let mut model = ModelFile {
        factors: factors.clone(),
        responses: Vec::new(),
    };
    for response in &responses {
        let y = data.values(response).map_err(in_file)?;
        let f = py
            .detach(|| core_fit(&coded, &y, &model_terms, &names))
            .map_err(|e| InputError::new_err(format!("response '{response}': {}", message(&e))))?;
        model
            .responses
            .push(Response::from_fit(response, data.unit(response), &f));
    }
    Ok(DoeModel { inner: model })
}
