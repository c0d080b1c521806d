//! Design of Experiments (bumpsim-doe), the calls `bumpsim doe design`,
//! `fit` and `predict` make: designs as tables, regressions of data-file
//! responses on factors in coded units, model files and predictions.

use crate::arrays::{cached2, vector};
use crate::convert::from_json;
use crate::convert::{count, path, seed};
use crate::errors::{input, invalid, message, reading};
use crate::frames;
use crate::state::doe::{DesignState, DoeModelState};
use crate::state::{decode, encode, reduce};
use bumpsim_doe::data::Data;
use bumpsim_doe::design::{self, DesignKind, DesignOptions};
use bumpsim_doe::model::{Factor, ModelFile};
use bumpsim_doe::table_fit::{StandardErrors, TableFitError, TableFitSpec, fit_table_weighted};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBytes, PyDict, PyList, PyType};

/// What `__reduce__` returns.
type Reduced<'py> = (Bound<'py, PyAny>, (Bound<'py, PyBytes>,));

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
                .map_err(|e| invalid(format!("factors: {}", message(&e))))
        })
        .collect()
}

/// A design: factor names, runs in coded and physical units, run order.
#[pyclass(frozen, module = "bumpsim")]
pub struct Design {
    data: DesignState,
    coded: PyOnceLock<Py<PyArray2<f64>>>,
    physical: PyOnceLock<Py<PyArray2<f64>>>,
}

impl Design {
    fn of(data: DesignState) -> Design {
        Design {
            data,
            coded: PyOnceLock::new(),
            physical: PyOnceLock::new(),
        }
    }

    fn to_text(&self) -> String {
        self.data
            .design
            .to_csv(&self.data.factors, &self.data.order)
    }
}

#[pymethods]
impl Design {
    /// Factor names.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.data.design.factors.clone()
    }
    /// Run order: indices (0-based) into the standard order.
    #[getter]
    fn order(&self) -> Vec<usize> {
        self.data.order.clone()
    }
    /// Resolution of a fractional design, else None.
    #[getter]
    fn resolution(&self) -> Option<usize> {
        self.data.resolution
    }
    /// Coded levels, runs (in run order) × factors.
    #[getter]
    fn coded(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        let d = &self.data;
        let rows: Vec<Vec<f64>> = d.order.iter().map(|&i| d.design.runs[i].clone()).collect();
        cached2(py, &self.coded, &rows, d.design.factors.len())
    }
    /// Physical levels, runs (in run order) × factors.
    #[getter]
    fn physical(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        let d = &self.data;
        let physical = |i: usize| -> Vec<f64> {
            let run = d.design.runs[i].iter().zip(&d.factors);
            run.map(|(z, f)| f.physical(*z)).collect()
        };
        let rows: Vec<Vec<f64>> = d.order.iter().map(|&i| physical(i)).collect();
        cached2(py, &self.physical, &rows, d.design.factors.len())
    }
    /// The design table as `bumpsim doe design -o` writes it.
    fn to_csv(&self) -> String {
        self.to_text()
    }
    /// The design table as `bumpsim doe design -o` writes it: index `run`,
    /// columns `standard order`, the factors' physical levels and `NAME
    /// (coded)`; attrs: factors (name, low, high, unit), resolution.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let attrs = PyDict::new(py);
        attrs.set_item("factors", from_json(py, &self.data.factors)?)?;
        attrs.set_item("resolution", self.data.resolution)?;
        frames::csv(py, &self.to_text(), &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.data == other.data
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        reduce(slf.as_any(), &encode(&slf.get().data)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        Ok(Design::of(decode(state, "Design")?))
    }
    fn __repr__(&self) -> String {
        let d = &self.data;
        format!(
            "Design({} runs of {:?}, resolution={})",
            d.order.len(),
            d.design.factors,
            d.resolution
                .map_or_else(|| "None".to_string(), |r| r.to_string())
        )
    }
}

/// Makes a design (as `bumpsim doe design`): `kind` full, fractional, ccf,
/// ccc, lhs or uniform; `factors` as "NAME:LOW:HIGH" strings.
#[pyfunction]
#[pyo3(signature = (kind, factors, generators = Vec::new(), centre = None, runs = None, seed = None, randomise = false))]
fn doe_design(
    kind: &str,
    factors: Vec<String>,
    generators: Vec<String>,
    centre: Option<&Bound<'_, PyAny>>,
    runs: Option<&Bound<'_, PyAny>>,
    seed: Option<&Bound<'_, PyAny>>,
    randomise: bool,
) -> PyResult<Design> {
    // the CLI's limits: --runs 1 to 1 000 000
    let centre = centre
        .map(|c| count(c, "centre", 0, 1_000_000))
        .transpose()?
        .unwrap_or(0);
    let runs = runs
        .map(|r| count(r, "runs", 1, 1_000_000))
        .transpose()?
        .unwrap_or(20);
    let seed = self::seed(seed)?.unwrap_or(1);
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
    Ok(Design::of(DesignState {
        design,
        factors,
        order,
        resolution,
    }))
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
    fn from_file(path: &Bound<'_, PyAny>) -> PyResult<Self> {
        let path = self::path(path, "path", "a DOE model")?;
        let inner = ModelFile::read(&path).map_err(|e| reading(&path, e))?;
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
    /// The coefficients in coded units: index (`response`, `term`), columns
    /// `coefficient`, `std_error`, `ci95_low`, `ci95_high` (in the row's
    /// `unit`, the response's); attrs: factors, r2, r2_adjusted, q2 per response.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows = PyList::empty(py);
        let (r2, r2_adjusted, q2) = (PyDict::new(py), PyDict::new(py), PyDict::new(py));
        for r in &self.inner.responses {
            for (term, value) in &r.coefficients {
                let se = r
                    .std_errors
                    .as_ref()
                    .and_then(|s| s.get(term).copied().flatten());
                let ci = r.ci95.as_ref().and_then(|c| c.get(term).copied().flatten());
                let row = PyDict::new(py);
                row.set_item("response", &r.name)?;
                row.set_item("term", term)?;
                row.set_item("coefficient", value)?;
                row.set_item("std_error", se.unwrap_or(f64::NAN))?;
                row.set_item("ci95_low", ci.map_or(f64::NAN, |c| c[0]))?;
                row.set_item("ci95_high", ci.map_or(f64::NAN, |c| c[1]))?;
                row.set_item("unit", &r.unit)?;
                rows.append(row)?;
            }
            r2.set_item(&r.name, r.r2)?;
            r2_adjusted.set_item(&r.name, r.r2_adjusted)?;
            q2.set_item(&r.name, r.q2)?;
        }
        let attrs = PyDict::new(py);
        attrs.set_item("factors", from_json(py, &self.inner.factors)?)?;
        attrs.set_item("r2", r2)?;
        attrs.set_item("r2_adjusted", r2_adjusted)?;
        attrs.set_item("q2", q2)?;
        frames::records(py, rows, &["response", "term"], &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        reduce(
            slf.as_any(),
            &encode(&DoeModelState(slf.get().inner.clone()))?,
        )
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        let DoeModelState(inner) = decode(state, "DoeModel")?;
        Ok(DoeModel { inner })
    }
    fn __repr__(&self) -> String {
        let names: Vec<&str> = self.inner.factors.iter().map(|f| f.name.as_str()).collect();
        let responses: Vec<&str> = self
            .inner
            .responses
            .iter()
            .map(|r| r.name.as_str())
            .collect();
        format!("DoeModel(factors={names:?}, responses={responses:?})")
    }
}

/// Fits `responses` on `factors` (columns of the data CSV at `data`, `name
/// [unit]` headers) in coded units, as `bumpsim doe fit`; `low`/`high`
/// default to the data's extremes; `se` as `doe fit --se`: "RESPONSE=COLUMN"
/// or "RESPONSE" (the column RESPONSE.se), those responses fitted with their
/// identification's standard errors (REML, weighted least squares).
#[pyfunction]
// one Rust argument per Python keyword argument
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (data, factors, responses, low = Vec::new(), high = Vec::new(), interactions = false, squares = false, se = Vec::new()))]
fn doe_fit(
    py: Python<'_>,
    data: &Bound<'_, PyAny>,
    factors: Vec<String>,
    responses: Vec<String>,
    low: Vec<f64>,
    high: Vec<f64>,
    interactions: bool,
    squares: bool,
    se: Vec<String>,
) -> PyResult<DoeModel> {
    let path = &self::path(data, "data", "a data table")?;
    let data = Data::read(path).map_err(|e| reading(path, e))?;
    let in_file = |e: TableFitError| invalid(format!("{}: {}", path.display(), message(&e)));
    let se = (se.iter().map(|s| s.parse::<StandardErrors>()))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| invalid(format!("se: {}", message(&e))))?;
    let spec = TableFitSpec {
        factors,
        responses,
        low,
        high,
        interactions,
        squares,
    };
    let (inner, _) = py
        .detach(|| fit_table_weighted(&data, &spec, &se))
        .map_err(in_file)?;
    Ok(DoeModel { inner })
}
