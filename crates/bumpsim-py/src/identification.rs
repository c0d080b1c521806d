//! The results of an identification (bumpsim-ident): `Identification`
//! (the fields of `bumpsim identify --json`, its predictions and report),
//! `Prediction` (a case simulated next to its measurement) and `DofTable`
//! (the thesis's table 1 over several orders); each with pandas tables.

use crate::arrays::{array1, cached1, values};
use crate::convert::from_json;
use crate::errors::input;
use crate::frames;
use crate::model::Car;
use crate::posterior::{Posterior, Run, sample};
use crate::state::ident::{DofTableState, IdentificationState, PredictionState};
use crate::state::{decode, encode, reduce};
use bumpsim_core::model::{parameter_kind, parameter_name};
use bumpsim_ident::case::LoadCase;
use bumpsim_ident::document::{Failed, IdentifyDocument};
use bumpsim_ident::estimate::Identification as CoreIdentification;
use bumpsim_ident::explore::{predict, sensitivity};
use bumpsim_ident::settings::Settings;
use bumpsim_ident::text::{dof_table, recommended_dof};
use bumpsim_io::car::Car as IoCar;
use bumpsim_report::identification::{DofOutcome, report};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBytes, PyDict, PyType};
use std::path::PathBuf;

/// What `__reduce__` returns.
type Reduced<'py> = (Bound<'py, PyAny>, (Bound<'py, PyBytes>,));

/// The DataFrame key (column or attrs) of an identification's objective:
/// its unit ([`CoreIdentification::objective_unit`]) in ASCII, so
/// `objective [m^2]` for the thesis's displacement objective, `objective
/// [(m/s)^2]` compared in velocity, `objective [(m/s^2)^2]` in
/// acceleration, `objective [dimensionless]` weighted by the noise.
fn objective_key(r: &CoreIdentification) -> String {
    format!("objective [{}]", r.objective_unit().replace('²', "^2"))
}

/// Registers the classes of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Identification>()?;
    m.add_class::<Prediction>()?;
    m.add_class::<DofTable>()?;
    Ok(())
}

/// An identified model with everything the library says about it (the
/// fields of `bumpsim identify --json`).
#[pyclass(frozen, module = "bumpsim")]
pub struct Identification {
    data: IdentificationState,
    masses: PyOnceLock<Py<PyArray1<f64>>>,
    dampers: PyOnceLock<Py<PyArray1<f64>>>,
    springs: PyOnceLock<Py<PyArray1<f64>>>,
}

impl Identification {
    /// The Python object of a result, its cases, notes, study and the
    /// settings it was identified with (their seed and bounds are kept).
    pub fn new(
        result: CoreIdentification,
        cases: Vec<LoadCase>,
        notes: Vec<String>,
        study: Option<PathBuf>,
        settings: &Settings,
    ) -> Identification {
        Identification::of(IdentificationState {
            result,
            cases,
            notes,
            study,
            seed: settings.seed,
            bounds: settings.bounds.clone(),
        })
    }

    fn of(data: IdentificationState) -> Identification {
        Identification {
            data,
            masses: PyOnceLock::new(),
            dampers: PyOnceLock::new(),
            springs: PyOnceLock::new(),
        }
    }

    fn result(&self) -> &CoreIdentification {
        &self.data.result
    }
}

#[pymethods]
impl Identification {
    /// Number of masses.
    #[getter]
    fn dof(&self) -> usize {
        self.result().dof
    }
    /// The identified model as a Car.
    #[getter]
    fn car(&self) -> Car {
        Car::of(IoCar {
            name: None,
            model: self.result().model.clone(),
        })
    }
    /// Masses, kg.
    #[getter]
    fn masses(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.masses, || self.result().model.masses().to_vec())
    }
    /// Dampers, N·s/m.
    #[getter]
    fn dampers(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.dampers, || self.result().model.dampers().to_vec())
    }
    /// Springs, N/m.
    #[getter]
    fn springs(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.springs, || self.result().model.springs().to_vec())
    }
    /// Parameters in the thesis's order: dicts with name, value, unit,
    /// standard_error and ci95 (None when not estimated).
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        let (dof, u) = (self.result().dof, &self.result().uncertainty);
        self.result()
            .model
            .parameters()
            .iter()
            .enumerate()
            .map(|(i, value)| {
                let d = PyDict::new(py);
                d.set_item("name", parameter_name(dof, i))?;
                d.set_item("value", value)?;
                d.set_item("unit", parameter_kind(dof, i).0.unit())?;
                d.set_item(
                    "standard_error",
                    u.standard_errors.get(i).copied().flatten(),
                )?;
                d.set_item("ci95", u.ci95.get(i).copied().flatten())?;
                Ok(d.into_any())
            })
            .collect()
    }
    /// Standard errors, SI, thesis order (None when not estimated).
    #[getter]
    fn standard_errors(&self) -> Vec<Option<f64>> {
        self.result().uncertainty.standard_errors.clone()
    }
    /// Standard errors, intervals, correlations, singular values, which
    /// parameters the data determine and the weakest direction (the JSON's
    /// `uncertainty`).
    #[getter]
    fn uncertainty<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result().uncertainty)
    }
    /// The objective at the optimum, in `objective_unit`: Σ (x − x̂)² over
    /// all cases in m² for the thesis's displacement objective, the
    /// domain's unit squared or dimensionless for the study's other
    /// comparisons.
    #[getter]
    fn objective(&self) -> f64 {
        self.result().objective
    }
    /// The objective's unit as the CLI prints it after the objective: `m²`,
    /// `(m/s)²`, `(m/s²)²` (the compared domain's unit squared),
    /// `dimensionless` when every case is weighted by its noise,
    /// `dimensionless + (m/s)²` when some are.
    #[getter]
    fn objective_unit(&self) -> String {
        self.result().objective_unit()
    }
    /// Overall fit, %.
    #[getter]
    fn fit_percent(&self) -> f64 {
        self.result().fit_percent
    }
    /// Akaike information criterion.
    #[getter]
    fn aic(&self) -> f64 {
        self.result().aic
    }
    /// Bayesian information criterion.
    #[getter]
    fn bic(&self) -> f64 {
        self.result().bic
    }
    /// Per-case fit: dicts with name, sse (m²), fit_percent, samples, rating,
    /// window (first and last sample time, s).
    #[getter]
    fn cases<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result().cases)
    }
    /// Start statistics (total, converged, failed, reached_best_fit,
    /// reached_best_fit_alone, reached_correlated and explored_correlated
    /// with their inflation κ,
    /// reached_best, reached_best_alone,
    /// explored_best_fit, abandoned, merged, unpolished, refined, best).
    #[getter]
    fn starts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result().starts)
    }
    /// Where the best start began, SI, thesis order (the JSON's `start`).
    #[getter]
    fn start(&self) -> Vec<f64> {
        self.result().start.clone()
    }
    /// Warnings for the user.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.result().warnings.clone()
    }
    /// The simpler model that fits as well, when a spring is undetermined or
    /// a link is not needed by the F-test (the JSON's `reduction`), or None.
    #[getter]
    fn reduction<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result().reduction)
    }
    /// The effective sample size of the residuals at the optimum (as the JSON).
    #[getter]
    fn effective_samples<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result().effective_samples)
    }
    /// Leave-one-load-case-out cross-validation (error m², folds), when a
    /// DOF table ran it; None otherwise.
    #[getter]
    fn cross_validation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result().cross_validation)
    }
    /// How the cases were compared when not in displacement (the study's
    /// `objective`: domain, noises, residual correlation), as the CLI's JSON
    /// `compared`; None for the thesis's displacement objective.
    #[getter]
    fn compared<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::convert::from_json(py, &self.result().compared)
    }
    /// The stated priors, each with its centre, spread (sd of ln θ), source,
    /// the estimate and how far the data moved it in prior standard
    /// deviations (the JSON's `priors`); empty without priors.
    #[getter]
    fn priors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::convert::from_json(py, &self.result().priors)
    }
    /// The noise of one residual the priors weigh against (the JSON's
    /// `prior_noise`, in the objective's unit), or None without priors.
    #[getter]
    fn prior_noise(&self) -> Option<f64> {
        self.result().prior_noise
    }
    /// Number of residuals (samples in all windows).
    #[getter]
    fn residuals(&self) -> usize {
        self.result().residuals
    }
    /// Solver iterations of the best start.
    #[getter]
    fn iterations(&self) -> usize {
        self.result().iterations
    }
    /// Why the best start stopped (the JSON's `stop`).
    #[getter]
    fn stop<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result().stop)
    }
    /// Wall-clock time of the identification, s.
    #[getter]
    fn run_time(&self) -> f64 {
        self.result().run_time
    }
    /// What the channel selections left out or used despite a mark.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.data.notes.clone()
    }
    /// The result as `bumpsim identify --json` writes it.
    fn to_json(&self) -> PyResult<String> {
        let document = IdentifyDocument::One {
            result: self.result(),
            notes: &self.data.notes,
        };
        serde_json::to_string_pretty(&document).map_err(input)
    }
    /// The parameter table: index `parameter` (m1.., c1.., k1..), columns
    /// `value`, `standard_error`, `ci95_low`, `ci95_high` (SI, in the row's
    /// `unit`), `unit`, `determined`, `at_bound`, `fixed`.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (r, u) = (self.result(), &self.result().uncertainty);
        let n = r.model.parameters().len();
        let names: Vec<String> = (0..n).map(|i| parameter_name(r.dof, i)).collect();
        let units: Vec<&str> = (0..n).map(|i| parameter_kind(r.dof, i).0.unit()).collect();
        let bound = |k: usize| -> Vec<Option<f64>> {
            (0..n)
                .map(|i| u.ci95.get(i).copied().flatten().map(|c| c[k]))
                .collect()
        };
        let list = |v: Bound<'py, PyAny>| v;
        let columns = vec![
            (
                "value".into(),
                list(r.model.parameters().to_vec().into_pyobject(py)?.into_any()),
            ),
            (
                "standard_error".into(),
                u.standard_errors.clone().into_pyobject(py)?.into_any(),
            ),
            ("ci95_low".into(), bound(0).into_pyobject(py)?.into_any()),
            ("ci95_high".into(), bound(1).into_pyobject(py)?.into_any()),
            ("unit".into(), units.into_pyobject(py)?.into_any()),
            (
                "determined".into(),
                u.determined.clone().into_pyobject(py)?.into_any(),
            ),
            (
                "at_bound".into(),
                u.at_bound.clone().into_pyobject(py)?.into_any(),
            ),
            (
                "fixed".into(),
                u.fixed.clone().into_pyobject(py)?.into_any(),
            ),
        ];
        let attrs = PyDict::new(py);
        attrs.set_item("dof", r.dof)?;
        attrs.set_item(objective_key(r), r.objective)?;
        attrs.set_item("fit [%]", r.fit_percent)?;
        attrs.set_item("warnings", &r.warnings)?;
        let index = ("parameter".into(), names.into_pyobject(py)?.into_any());
        frames::frame(py, columns, Some(index), &attrs)
    }
    /// The per-case fits: index `case`, columns `sse [m^2]`, `fit [%]`,
    /// `samples` and the ISO/TS 18571 ratings `rating`, `corridor`,
    /// `phase`, `magnitude`, `slope` (NaN where the window cannot be rated).
    fn cases_to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows = pyo3::types::PyList::empty(py);
        for c in &self.result().cases {
            let row = PyDict::new(py);
            row.set_item("case", &c.name)?;
            row.set_item("sse [m^2]", c.sse)?;
            row.set_item("fit [%]", c.fit_percent)?;
            row.set_item("samples", c.samples)?;
            let r = c.rating.as_ref();
            row.set_item("rating", r.map_or(f64::NAN, |r| r.overall))?;
            row.set_item("corridor", r.map_or(f64::NAN, |r| r.corridor))?;
            row.set_item("phase", r.map_or(f64::NAN, |r| r.phase))?;
            row.set_item("magnitude", r.map_or(f64::NAN, |r| r.magnitude))?;
            row.set_item("slope", r.map_or(f64::NAN, |r| r.slope))?;
            rows.append(row)?;
        }
        frames::records(py, rows, &["case"], &PyDict::new(py))
    }
    /// Samples the posterior of the parameters (bumpsim-ident's ensemble
    /// sampler with this identification's noise model, log-uniform prior
    /// within its bounds), seeded (default: the identification's seed);
    /// `steps` (a quarter of them burnt) and `walkers` override the
    /// library's run (4000 steps, 32 walkers at least; 4000 draws kept), as
    /// `bumpsim identify --posterior --steps --walkers --seed`.
    #[pyo3(signature = (seed = None, steps = None, walkers = None))]
    fn posterior(
        &self,
        py: Python<'_>,
        seed: Option<&Bound<'_, PyAny>>,
        steps: Option<&Bound<'_, PyAny>>,
        walkers: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Posterior> {
        let run = Run {
            seed,
            steps,
            walkers,
        };
        sample(py, &self.data, run)
    }
    /// Simulates the study's load cases with the identified model.
    fn predict(&self, py: Python<'_>) -> PyResult<Vec<Prediction>> {
        let predictions = py
            .detach(|| predict(&self.data.cases, &self.result().model))
            .map_err(input)?;
        Ok(predictions
            .into_iter()
            .map(|p| {
                Prediction::of(
                    py,
                    PredictionState {
                        name: p.fit.name,
                        sse: p.fit.sse,
                        fit_percent: p.fit.fit_percent,
                        window: (p.window[0], p.window[1]),
                        time: p.time,
                        measured: p.measured,
                        simulated: p.simulated,
                        rating: p.fit.rating,
                    },
                )
            })
            .collect())
    }
    /// The HTML report `bumpsim identify --report` writes, as the page and
    /// its SVG figures (file name → SVG text), with the ±3 % sensitivity.
    fn report(
        &self,
        py: Python<'_>,
    ) -> PyResult<(String, std::collections::BTreeMap<String, String>)> {
        let (inputs, source) = match &self.data.study {
            Some(path) => (
                std::fs::read_to_string(path).unwrap_or_default(),
                format!("Study {}", path.display()),
            ),
            None => (String::new(), "Load cases from Python".to_string()),
        };
        let r = self.result();
        let settings = format!(
            "{source}; DOF {}; {} starts, seed {}; exact zoh discretisation.",
            r.dof, r.starts.total, self.data.seed
        );
        let (html, figures) = py.detach(|| {
            let predictions = predict(&self.data.cases, &r.model).map_err(input)?;
            let sweeps = sensitivity(&self.data.cases, &r.model, 0.03, 13).map_err(input)?;
            let outcomes = [DofOutcome::Done {
                result: Box::new(r.clone()),
                predictions,
            }];
            let title = "bumpsim identification";
            report(
                title,
                &inputs,
                &settings,
                &self.data.notes,
                &outcomes,
                Some(&sweeps),
            )
            .map_err(input)
        })?;
        Ok((html, figures.into_iter().collect()))
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.data == other.data
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        reduce(slf.as_any(), &encode(&slf.get().data)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        Ok(Identification::of(decode(state, "Identification")?))
    }
    fn __repr__(&self) -> String {
        let r = self.result();
        format!(
            "Identification(dof={}, objective={:e} {}, fit={:.2} %, {} cases)",
            r.dof,
            r.objective,
            r.objective_unit(),
            r.fit_percent,
            r.cases.len()
        )
    }
}

/// A load case simulated with an identified model next to its measurement.
#[pyclass(frozen, module = "bumpsim")]
pub struct Prediction {
    data: PredictionState,
    /// Sample times, s.
    #[pyo3(get)]
    time: Py<PyArray1<f64>>,
    /// Measured displacement, m.
    #[pyo3(get)]
    measured: Py<PyArray1<f64>>,
    /// Simulated displacement, m.
    #[pyo3(get)]
    simulated: Py<PyArray1<f64>>,
}

impl Prediction {
    fn of(py: Python<'_>, data: PredictionState) -> Prediction {
        Prediction {
            time: array1(py, data.time.clone()),
            measured: array1(py, data.measured.clone()),
            simulated: array1(py, data.simulated.clone()),
            data,
        }
    }
}

#[pymethods]
impl Prediction {
    /// Case name.
    #[getter]
    fn name(&self) -> String {
        self.data.name.clone()
    }
    /// Sum of squared errors in the window, m².
    #[getter]
    fn sse(&self) -> f64 {
        self.data.sse
    }
    /// Fit in the window, %.
    #[getter]
    fn fit_percent(&self) -> f64 {
        self.data.fit_percent
    }
    /// Window start and end, s.
    #[getter]
    fn window(&self) -> (f64, f64) {
        self.data.window
    }
    /// ISO/TS 18571 rating in the window (overall, corridor, phase,
    /// magnitude, slope), or None when the window cannot be rated.
    #[getter]
    fn rating<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.data.rating)
    }
    /// Measured and simulated displacement: index `time [s]`, columns
    /// `measured [m]`, `simulated [m]`; attrs: name, sse, fit_percent,
    /// window, rating.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let columns = vec![
            (
                "measured [m]".into(),
                self.measured.bind(py).clone().into_any(),
            ),
            (
                "simulated [m]".into(),
                self.simulated.bind(py).clone().into_any(),
            ),
        ];
        let attrs = PyDict::new(py);
        attrs.set_item("name", &self.data.name)?;
        attrs.set_item("sse [m^2]", self.data.sse)?;
        attrs.set_item("fit [%]", self.data.fit_percent)?;
        attrs.set_item("window [s]", self.data.window)?;
        attrs.set_item("rating", self.rating(py)?)?;
        let index = ("time [s]".into(), self.time.bind(py).clone().into_any());
        frames::frame(py, columns, Some(index), &attrs)
    }
    fn __eq__(&self, py: Python<'_>, other: &Self) -> bool {
        self.data == other.data && values(py, &self.time) == values(py, &other.time)
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        reduce(slf.as_any(), &encode(&slf.get().data)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, py: Python<'_>, state: &[u8]) -> PyResult<Self> {
        Ok(Prediction::of(py, decode(state, "Prediction")?))
    }
    fn __repr__(&self) -> String {
        format!(
            "Prediction({:?}, fit={:.2} %, sse={:e} m², {} samples)",
            self.data.name,
            self.data.fit_percent,
            self.data.sse,
            self.data.time.len()
        )
    }
}

/// The thesis's table 1: models of several orders identified from one
/// study, each continued from the last (`bumpsim identify --dof 1..5`).
#[pyclass(frozen, module = "bumpsim")]
pub struct DofTable {
    data: DofTableState,
}

impl DofTable {
    /// The table of `results`, the orders that `failed` and the notes.
    pub fn new(results: Vec<Identification>, failed: Vec<Failed>, notes: Vec<String>) -> DofTable {
        DofTable {
            data: DofTableState {
                results: results.into_iter().map(|r| r.data).collect(),
                failed: failed.into_iter().map(|f| (f.dof, f.reason)).collect(),
                notes,
            },
        }
    }

    fn results(&self) -> Vec<CoreIdentification> {
        self.data.results.iter().map(|r| r.result.clone()).collect()
    }
}

#[pymethods]
impl DofTable {
    /// The orders identified, lowest first.
    #[getter(results)]
    fn identifications(&self) -> Vec<Identification> {
        let copy = |r: &IdentificationState| {
            Identification::of(IdentificationState {
                result: r.result.clone(),
                cases: r.cases.clone(),
                notes: r.notes.clone(),
                study: r.study.clone(),
                seed: r.seed,
                bounds: r.bounds.clone(),
            })
        };
        self.data.results.iter().map(copy).collect()
    }
    /// The orders that failed: DOF → reason.
    #[getter]
    fn failed(&self) -> std::collections::BTreeMap<usize, String> {
        self.data.failed.iter().cloned().collect()
    }
    /// What the channel selections left out or used despite a mark.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.data.notes.clone()
    }
    /// The recommended order (the model choice of `bumpsim_ident::choice`,
    /// as the CLI's), or None.
    #[getter]
    fn recommended(&self) -> Option<usize> {
        recommended_dof(&self.results())
    }
    /// The table as `bumpsim identify --dof 1..5` prints it.
    fn to_text(&self) -> String {
        dof_table(&self.results())
    }
    /// The table as `bumpsim identify --dof 1..5 --json` writes it.
    fn to_json(&self) -> PyResult<String> {
        let results = self.results();
        let failed: Vec<Failed> = self
            .data
            .failed
            .iter()
            .map(|(dof, reason)| Failed {
                dof: *dof,
                reason: reason.clone(),
            })
            .collect();
        let document = IdentifyDocument::new(&results, &failed, &self.data.notes);
        serde_json::to_string_pretty(&document).map_err(input)
    }
    /// The table: index `dof`, columns `objective [UNIT]` (as
    /// `objective_key`), `fit [%]`,
    /// `aic [-]`, `bic [-]`, `parameters`, `run_time [s]`; attrs:
    /// recommended (as the CLI's), failed (DOF → reason).
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows = pyo3::types::PyList::empty(py);
        for r in self.results() {
            let row = PyDict::new(py);
            row.set_item("dof", r.dof)?;
            row.set_item(objective_key(&r), r.objective)?;
            row.set_item("fit [%]", r.fit_percent)?;
            row.set_item("aic [-]", r.aic)?;
            row.set_item("bic [-]", r.bic)?;
            row.set_item("parameters", r.model.parameters().len())?;
            row.set_item("run_time [s]", r.run_time)?;
            rows.append(row)?;
        }
        let attrs = PyDict::new(py);
        attrs.set_item("recommended", self.recommended())?;
        attrs.set_item("failed", self.failed())?;
        frames::records(py, rows, &["dof"], &attrs)
    }
    fn __len__(&self) -> usize {
        self.data.results.len()
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.data == other.data
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        reduce(slf.as_any(), &encode(&slf.get().data)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        Ok(DofTable {
            data: decode(state, "DofTable")?,
        })
    }
    fn __repr__(&self) -> String {
        let dofs: Vec<usize> = self.data.results.iter().map(|r| r.result.dof).collect();
        format!(
            "DofTable(dofs={dofs:?}, failed={:?}, recommended={})",
            self.data.failed.iter().map(|f| f.0).collect::<Vec<_>>(),
            self.recommended()
                .map_or_else(|| "None".to_string(), |d| d.to_string())
        )
    }
}
