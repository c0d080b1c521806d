//! Identification of one MSD model from the load cases of a study file
//! (bumpsim-ident), the calls `bumpsim identify` makes: read the study,
//! load its cases for the DOF, take its settings with the caller's starts
//! and seed, identify, and predict the cases with the result.

use crate::arrays::{array1, vector};
use crate::errors::InputError;
use crate::errors::{file_or_input, input};
use crate::model::Car;
use bumpsim_core::series::UniformSeries;
use bumpsim_ident::case::LoadCase;
use bumpsim_ident::estimate::Settings;
use bumpsim_ident::estimate::{Identification as CoreIdentification, identify as core_identify};
use bumpsim_ident::explore::{predict, sensitivity};
use bumpsim_ident::study::{DofSpec, Study};
use bumpsim_io::car::Car as IoCar;
use bumpsim_report::identification::{DofOutcome, report};
use numpy::PyArray1;
use pyo3::prelude::*;
use std::path::PathBuf;

/// Registers the classes and functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Identification>()?;
    m.add_class::<Prediction>()?;
    m.add_function(wrap_pyfunction!(identify, m)?)?;
    m.add_class::<Case>()?;
    m.add_function(wrap_pyfunction!(identify_cases, m)?)?;
    Ok(())
}

/// A load case from numpy arrays: force on m1 (N) and the measured
/// displacement (m) of mass `output_dof` (1 = m1) at uniform `time` (s);
/// `window` (t0, t1) in s is the fit window (default: every sample).
#[pyclass(frozen, module = "bumpsim", name = "LoadCase")]
pub struct Case {
    inner: LoadCase,
}

#[pymethods]
impl Case {
    #[new]
    #[pyo3(signature = (name, time, force, displacement, output_dof = 1, initial_velocity = 0.0, window = None))]
    fn new(
        name: String,
        time: &Bound<'_, PyAny>,
        force: &Bound<'_, PyAny>,
        displacement: &Bound<'_, PyAny>,
        output_dof: usize,
        initial_velocity: f64,
        window: Option<(f64, f64)>,
    ) -> PyResult<Self> {
        let force = UniformSeries::from_times(&vector(time, "time")?, vector(force, "force")?)
            .map_err(input)?;
        let last = force.len() - 1;
        let window = match window {
            None => (0, last),
            Some((t0, t1)) => force
                .window(t0, t1)
                .map(|w| (*w.start(), *w.end()))
                .ok_or_else(|| {
                    InputError::new_err(format!(
                        "case '{name}': no sample inside the window [{t0}, {t1}] s"
                    ))
                })?,
        };
        let case = LoadCase {
            start: force.start(),
            step: force.step(),
            measured: vector(displacement, "displacement")?,
            force: force.values().to_vec(),
            name,
            output_dof,
            initial_velocity,
            window,
        };
        case.validate().map_err(input)?;
        Ok(Case { inner: case })
    }

    /// Case name.
    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }
}

/// Identifies one `dof`-mass model from load cases built in Python, with
/// the library's default settings (every parameter ≥ 1 in SI) and `starts`
/// seeded starts.
#[pyfunction]
#[pyo3(signature = (cases, dof, starts = 32, seed = 1, progress = None))]
fn identify_cases(
    py: Python<'_>,
    cases: Vec<PyRef<'_, Case>>,
    dof: usize,
    starts: usize,
    seed: u64,
    progress: Option<Py<PyAny>>,
) -> PyResult<Identification> {
    let cases: Vec<LoadCase> = cases.iter().map(|c| c.inner.clone()).collect();
    let mut settings = Settings::new(dof, starts);
    settings.seed = seed;
    let tick = progress_callback(&progress);
    let result = py
        .detach(|| core_identify(&cases, &settings, &tick))
        .map_err(|e| {
            crate::errors::InputError::new_err(format!(
                "{dof}-DOF identification: {}",
                crate::errors::message(&e)
            ))
        })?;
    Ok(Identification {
        result,
        cases,
        notes: Vec::new(),
        study: None,
        seed,
    })
}

/// The library's per-start progress hook calling a Python callable (if any)
/// with the GIL; an exception in it is printed, not raised.
fn progress_callback(progress: &Option<Py<PyAny>>) -> impl Fn() + Sync + '_ {
    move || {
        if let Some(callback) = progress {
            Python::attach(|py| {
                if let Err(e) = callback.call0(py) {
                    e.print(py);
                }
            });
        }
    }
}

/// Parses JSON the library serialised into Python objects.
pub fn from_json<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(input)?;
    py.import("json")?.call_method1("loads", (text,))
}

/// Identifies one MSD model from all load cases of the study file at
/// `study`, as `bumpsim identify STUDY --dof N --starts S --seed X`;
/// `progress` (optional) is called once per finished start.
#[pyfunction]
#[pyo3(signature = (study, dof = None, starts = None, seed = None, progress = None))]
fn identify(
    py: Python<'_>,
    study: PathBuf,
    dof: Option<usize>,
    starts: Option<usize>,
    seed: Option<u64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Identification> {
    let mut file = py.detach(|| Study::read(&study)).map_err(file_or_input)?;
    if let Some(dof) = dof {
        file.model.dof = DofSpec::One(dof);
    }
    let dofs = file.dofs();
    let [dof] = dofs[..] else {
        return Err(crate::errors::InputError::new_err(format!(
            "{}: the study asks for the DOF sweep {dofs:?}; pass dof= for one model",
            study.display()
        )));
    };
    let tick = progress_callback(&progress);
    let (result, cases, notes, seed) = py.detach(|| {
        let loaded = file.load(dof).map_err(input)?;
        let mut settings = file.settings(dof).map_err(input)?;
        settings.starts = starts.unwrap_or(settings.starts);
        settings.seed = seed.unwrap_or(settings.seed);
        let cases = file.retarget(&loaded.cases, dof);
        let result = core_identify(&cases, &settings, &tick).map_err(|e| {
            crate::errors::InputError::new_err(format!(
                "{dof}-DOF identification: {}",
                crate::errors::message(&e)
            ))
        })?;
        let notes: Vec<String> = loaded.notes.iter().map(ToString::to_string).collect();
        Ok::<_, PyErr>((result, cases, notes, settings.seed))
    })?;
    Ok(Identification {
        result,
        cases,
        notes,
        study: Some(study),
        seed,
    })
}

/// An identified model with everything the library says about it (the
/// fields of `bumpsim identify --json`).
#[pyclass(frozen, module = "bumpsim")]
pub struct Identification {
    result: CoreIdentification,
    cases: Vec<LoadCase>,
    notes: Vec<String>,
    /// The study file, when identified from one.
    study: Option<PathBuf>,
    /// Seed of the starts.
    seed: u64,
}

#[pymethods]
impl Identification {
    /// Number of masses.
    #[getter]
    fn dof(&self) -> usize {
        self.result.dof
    }
    /// The identified model as a Car.
    #[getter]
    fn car(&self) -> Car {
        Car {
            inner: IoCar {
                name: None,
                model: self.result.model.clone(),
            },
        }
    }
    /// Masses, kg.
    #[getter]
    fn masses(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.result.model.masses().to_vec())
    }
    /// Dampers, N·s/m.
    #[getter]
    fn dampers(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.result.model.dampers().to_vec())
    }
    /// Springs, N/m.
    #[getter]
    fn springs(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.result.model.springs().to_vec())
    }
    /// Parameters in the thesis's order: dicts with name, value, unit,
    /// standard_error and ci95 (None when not estimated).
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        let dof = self.result.dof;
        let u = &self.result.uncertainty;
        self.result
            .model
            .parameters()
            .iter()
            .enumerate()
            .map(|(i, value)| {
                let (kind, _) = bumpsim_core::model::parameter_kind(dof, i);
                let d = pyo3::types::PyDict::new(py);
                d.set_item("name", bumpsim_core::model::parameter_name(dof, i))?;
                d.set_item("value", value)?;
                d.set_item("unit", kind.unit())?;
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
        self.result.uncertainty.standard_errors.clone()
    }
    /// Standard errors, intervals, correlations, singular values, which
    /// parameters the data determine and the weakest direction (the JSON's
    /// `uncertainty`).
    #[getter]
    fn uncertainty<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result.uncertainty)
    }
    /// Σ (x − x̂)² over all cases, m².
    #[getter]
    fn objective(&self) -> f64 {
        self.result.objective
    }
    /// Overall fit, %.
    #[getter]
    fn fit_percent(&self) -> f64 {
        self.result.fit_percent
    }
    /// Akaike information criterion.
    #[getter]
    fn aic(&self) -> f64 {
        self.result.aic
    }
    /// Bayesian information criterion.
    #[getter]
    fn bic(&self) -> f64 {
        self.result.bic
    }
    /// Per-case fit: dicts with name, sse (m²), fit_percent, samples.
    #[getter]
    fn cases<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result.cases)
    }
    /// Start statistics (total, converged, failed, reached_best_fit,
    /// reached_best_fit_alone, reached_best, reached_best_alone,
    /// explored_best_fit, abandoned, merged, unpolished, refined, best).
    #[getter]
    fn starts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result.starts)
    }
    /// Where the best start began, SI, thesis order (the JSON's `start`).
    #[getter]
    fn start(&self) -> Vec<f64> {
        self.result.start.clone()
    }
    /// Warnings for the user.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.result.warnings.clone()
    }
    /// The simpler model that fits as well, when a spring is undetermined or
    /// a link is not needed by the F-test (the JSON's `reduction`), or None.
    #[getter]
    fn reduction<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result.reduction)
    }
    /// Number of residuals (samples in all windows).
    #[getter]
    fn residuals(&self) -> usize {
        self.result.residuals
    }
    /// Solver iterations of the best start.
    #[getter]
    fn iterations(&self) -> usize {
        self.result.iterations
    }
    /// Why the best start stopped (the JSON's `stop`).
    #[getter]
    fn stop<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result.stop)
    }
    /// Wall-clock time of the identification, s.
    #[getter]
    fn run_time(&self) -> f64 {
        self.result.run_time
    }
    /// What the channel selections left out or used despite a mark.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }
    /// The result as `bumpsim identify --json` writes it.
    fn to_json(&self) -> PyResult<String> {
        let document = bumpsim_ident::document::IdentifyDocument::One {
            result: &self.result,
            notes: &self.notes,
        };
        serde_json::to_string_pretty(&document).map_err(input)
    }
    /// Simulates the study's load cases with the identified model.
    fn predict(&self, py: Python<'_>) -> PyResult<Vec<Prediction>> {
        let predictions = py
            .detach(|| predict(&self.cases, &self.result.model))
            .map_err(input)?;
        predictions
            .into_iter()
            .map(|p| {
                let rating = p.fit.rating.as_ref().map(|r| from_json(py, r));
                Ok(Prediction {
                    rating: rating.transpose()?.map(Bound::unbind),
                    name: p.fit.name,
                    sse: p.fit.sse,
                    fit_percent: p.fit.fit_percent,
                    window: (p.window[0], p.window[1]),
                    time: array1(py, p.time),
                    measured: array1(py, p.measured),
                    simulated: array1(py, p.simulated),
                })
            })
            .collect()
    }
    /// The HTML report `bumpsim identify --report` writes, as the page and
    /// its SVG figures (file name → SVG text), with the ±3 % sensitivity.
    fn report(
        &self,
        py: Python<'_>,
    ) -> PyResult<(String, std::collections::BTreeMap<String, String>)> {
        let (inputs, source) = match &self.study {
            Some(path) => (
                std::fs::read_to_string(path).unwrap_or_default(),
                format!("Study {}", path.display()),
            ),
            None => (String::new(), "Load cases from Python".to_string()),
        };
        let settings = format!(
            "{source}; DOF {}; {} starts, seed {}; exact zoh discretisation.",
            self.result.dof, self.result.starts.total, self.seed
        );
        let (html, figures) = py.detach(|| {
            let model = &self.result.model;
            let predictions = predict(&self.cases, model).map_err(input)?;
            let sweeps = sensitivity(&self.cases, model, 0.03, 13).map_err(input)?;
            let outcomes = [DofOutcome::Done {
                result: Box::new(self.result.clone()),
                predictions,
            }];
            report(
                "bumpsim identification",
                &inputs,
                &settings,
                &self.notes,
                &outcomes,
                Some(&sweeps),
            )
            .map_err(input)
        })?;
        Ok((html, figures.into_iter().collect()))
    }
    fn __repr__(&self) -> String {
        format!(
            "Identification(dof={}, objective={:e} m², fit={:.2} %)",
            self.result.dof, self.result.objective, self.result.fit_percent
        )
    }
}

/// A load case simulated with an identified model next to its measurement.
#[pyclass(frozen, module = "bumpsim")]
pub struct Prediction {
    /// Case name.
    #[pyo3(get)]
    name: String,
    /// Sum of squared errors in the window, m².
    #[pyo3(get)]
    sse: f64,
    /// Fit in the window, %.
    #[pyo3(get)]
    fit_percent: f64,
    /// Window start and end, s.
    #[pyo3(get)]
    window: (f64, f64),
    /// Sample times, s.
    #[pyo3(get)]
    time: Py<PyArray1<f64>>,
    /// Measured displacement, m.
    #[pyo3(get)]
    measured: Py<PyArray1<f64>>,
    /// Simulated displacement, m.
    #[pyo3(get)]
    simulated: Py<PyArray1<f64>>,
    /// ISO/TS 18571 rating in the window (overall, corridor, phase,
    /// magnitude, slope), or None when the window cannot be rated.
    #[pyo3(get)]
    rating: Option<Py<PyAny>>,
}
