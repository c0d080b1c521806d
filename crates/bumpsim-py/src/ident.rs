//! Identification of MSD models: a study identified as `bumpsim identify`
//! identifies it, by the same engine request
//! (`bumpsim_engine::identify`: for a chain study one order, or the DOF
//! table over several, each continued from the last; a study of another
//! model, its kind declared, through the engine's registry,
//! [`crate::identified`]); and load cases built from numpy arrays
//! identified with the library's defaults. The chain's results are in
//! [`crate::identification`].

use crate::arrays::{cached1, vector};
use crate::convert::{count_or, dofs, path, seed};
use crate::errors::{input, invalid, message, reading};
use crate::frames;
use crate::identification::{DofTable, Identification};
use crate::state::ident::LoadCaseState;
use bumpsim_core::series::UniformSeries;
use bumpsim_engine::sizes::{Identified, Size};
use bumpsim_engine::{IdentifyRequest, Progress};
use bumpsim_ident::case::{LoadCase, fit_window};
use bumpsim_ident::estimate::{Settings, identify as core_identify};
use bumpsim_io::kind::{ModelKind, Role};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBytes, PyDict, PyType};
use std::path::Path;

/// Starts at most, as the CLI's `--starts`.
const MAX_STARTS: usize = 100_000;

/// Registers the classes and functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(identify, m)?)?;
    m.add_function(wrap_pyfunction!(dof_table, m)?)?;
    m.add_class::<Case>()?;
    m.add_function(wrap_pyfunction!(identify_cases, m)?)?;
    crate::identification::register(m)
}

/// A load case from numpy arrays: force on m1 (N) and the measured
/// displacement (m) of mass `output_dof` (1 = m1) at uniform `time` (s);
/// `window` (t0, t1) in s is the fit window (default: every sample).
#[pyclass(frozen, module = "bumpsim", name = "LoadCase")]
pub struct Case {
    inner: LoadCase,
    time: PyOnceLock<Py<PyArray1<f64>>>,
    force: PyOnceLock<Py<PyArray1<f64>>>,
    displacement: PyOnceLock<Py<PyArray1<f64>>>,
}

impl Case {
    fn of(inner: LoadCase) -> Case {
        Case {
            inner,
            time: PyOnceLock::new(),
            force: PyOnceLock::new(),
            displacement: PyOnceLock::new(),
        }
    }

    fn series(&self) -> Option<UniformSeries> {
        UniformSeries::new(self.inner.start, self.inner.step, self.inner.force.clone()).ok()
    }
}

#[pymethods]
impl Case {
    #[new]
    #[pyo3(signature = (name, time, force, displacement, output_dof = None, initial_velocity = 0.0, window = None))]
    fn new(
        name: String,
        time: &Bound<'_, PyAny>,
        force: &Bound<'_, PyAny>,
        displacement: &Bound<'_, PyAny>,
        output_dof: Option<&Bound<'_, PyAny>>,
        initial_velocity: f64,
        window: Option<(f64, f64)>,
    ) -> PyResult<Self> {
        let output_dof = count_or(output_dof, "output_dof", 1, usize::MAX)?.unwrap_or(1);
        let force = UniformSeries::from_times(&vector(time, "time")?, vector(force, "force")?)
            .map_err(input)?;
        let last = force.len() - 1;
        let window = match window {
            None => (0, last),
            Some((t0, t1)) => fit_window(&name, &force, [t0, t1]).map_err(input)?,
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
            compare: Default::default(),
        };
        case.validate().map_err(input)?;
        Ok(Case::of(case))
    }

    /// Case name.
    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }
    /// The mass whose displacement is measured (1 = m1).
    #[getter]
    fn output_dof(&self) -> usize {
        self.inner.output_dof
    }
    /// Initial velocity of every mass, m/s.
    #[getter]
    fn initial_velocity(&self) -> f64 {
        self.inner.initial_velocity
    }
    /// Sample times, s.
    #[getter]
    fn time(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.time, || {
            self.series().map(|s| s.times()).unwrap_or_default()
        })
    }
    /// Force on m1, N.
    #[getter]
    fn force(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.force, || self.inner.force.clone())
    }
    /// Measured displacement, m.
    #[getter]
    fn displacement(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.displacement, || self.inner.measured.clone())
    }
    /// The fit window's first and last sample time, s.
    #[getter]
    fn window(&self) -> (f64, f64) {
        let (a, b) = self.inner.window;
        self.series()
            .map_or((f64::NAN, f64::NAN), |s| (s.time(a), s.time(b)))
    }
    /// The case as a DataFrame: index `time [s]`, columns `force [N]` and
    /// `displacement [m]`; attrs: name, output_dof, initial_velocity, window.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let columns = vec![
            ("force [N]".into(), self.force(py).into_bound(py).into_any()),
            (
                "displacement [m]".into(),
                self.displacement(py).into_bound(py).into_any(),
            ),
        ];
        let attrs = PyDict::new(py);
        attrs.set_item("name", &self.inner.name)?;
        attrs.set_item("output_dof", self.inner.output_dof)?;
        attrs.set_item("initial_velocity", self.inner.initial_velocity)?;
        attrs.set_item("window", self.window())?;
        let index = ("time [s]".into(), self.time(py).into_bound(py).into_any());
        frames::frame(py, columns, Some(index), &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        let state = crate::state::encode(&LoadCaseState(slf.get().inner.clone()))?;
        crate::state::reduce(slf.as_any(), &state)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        let LoadCaseState(case) = crate::state::decode(state, "LoadCase")?;
        Ok(Case::of(case))
    }
    fn __repr__(&self) -> String {
        let (t0, t1) = self.window();
        format!(
            "LoadCase({:?}, {} samples at {} s, output_dof={}, window=({t0}, {t1}) s)",
            self.inner.name,
            self.inner.force.len(),
            self.inner.step,
            self.inner.output_dof
        )
    }
}

/// Identifies one `dof`-mass model from load cases built in Python, with
/// the library's default settings (every parameter ≥ 1 in SI) and `starts`
/// seeded starts.
#[pyfunction]
#[pyo3(signature = (cases, dof, starts = None, seed = None, progress = None))]
fn identify_cases(
    py: Python<'_>,
    cases: Vec<PyRef<'_, Case>>,
    dof: &Bound<'_, PyAny>,
    starts: Option<&Bound<'_, PyAny>>,
    seed: Option<&Bound<'_, PyAny>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Identification> {
    let dof = one_dof(dof)?;
    let starts = count_or(starts, "starts", 1, MAX_STARTS)?.unwrap_or(32);
    let cases: Vec<LoadCase> = cases.iter().map(|c| c.inner.clone()).collect();
    let mut settings = Settings::new(dof, starts);
    settings.seed = self::seed(seed)?.unwrap_or(1);
    let tick = progress_callback(&progress);
    let result = py
        .detach(|| core_identify(&cases, &settings, &tick))
        .map_err(|e| failed(dof, &e))?;
    Ok(Identification::new(
        result,
        cases,
        Vec::new(),
        None,
        &settings,
    ))
}

/// `dof` as one number of masses (`3` or `"3"`), as the CLI's `--dof`.
fn one_dof(value: &Bound<'_, PyAny>) -> PyResult<usize> {
    match dofs(value)?[..] {
        [dof] => Ok(dof),
        _ => Err(invalid(format!(
            "dof {}: one number of masses here; bumpsim.dof_table identifies several",
            value.repr().map_or_else(|_| "?".into(), |r| r.to_string())
        ))),
    }
}

fn failed(dof: usize, error: &dyn std::error::Error) -> PyErr {
    invalid(format!("{dof}-DOF identification: {}", message(error)))
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

/// The identify request on the study file at `path` (the model sizes
/// `sizes` over the study's), as `bumpsim identify` makes it.
fn request<'a>(
    path: &'a Path,
    sizes: Option<&'a [usize]>,
    starts: Option<&Bound<'_, PyAny>>,
    seed: Option<&Bound<'_, PyAny>>,
    progress: &'a Ticks,
) -> PyResult<IdentifyRequest<'a>> {
    Ok(IdentifyRequest {
        study: path,
        starts: count_or(starts, "starts", 1, MAX_STARTS)?,
        seed: self::seed(seed)?,
        report: false,
        posterior: None,
        sizes,
        sensitivity: false,
        car: false,
        progress,
    })
}

/// The model sizes the request asks, the study read (a study that cannot
/// be read raises as its file).
fn sizes(py: Python<'_>, request: &IdentifyRequest<'_>) -> PyResult<Vec<usize>> {
    py.detach(|| bumpsim_engine::identify::sizes(request))
        .map_err(|e| reading(request.study, e))
}

/// The study's identification over the sizes the request asks: the
/// engine's one loop, as `bumpsim identify` runs it.
fn identified(py: Python<'_>, request: &IdentifyRequest<'_>) -> PyResult<Identified> {
    py.detach(|| bumpsim_engine::identify::identified(request))
        .map_err(input)
}

/// Identifies the study file at `study` as `bumpsim identify STUDY --dof N
/// --starts S --seed X` does, by the model its declared kind names: a
/// chain study's one MSD model from all its load cases (an
/// [`Identification`]), a study of another model (links, planar) as the
/// engine's identify request on it (a
/// [`crate::identified::StudyIdentification`]); `progress` (optional) is
/// called once per finished start.
#[pyfunction]
#[pyo3(signature = (study, dof = None, starts = None, seed = None, progress = None))]
fn identify<'py>(
    py: Python<'py>,
    study: &Bound<'py, PyAny>,
    dof: Option<&Bound<'py, PyAny>>,
    starts: Option<&Bound<'py, PyAny>>,
    seed: Option<&Bound<'py, PyAny>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let dof = dof.map(one_dof).transpose()?.map(|d| [d]);
    let path = path(study, "study", "a study")?;
    let ticks = Ticks(progress);
    let request = request(&path, dof.as_ref().map(|d| &d[..]), starts, seed, &ticks)?;
    let kind = ModelKind::of_path(&path, Role::Study).map_err(|e| reading(&path, e))?;
    if kind != ModelKind::Chain {
        let identified = crate::identified::identify(py, kind, &request)?;
        return Ok(Bound::new(py, identified)?.into_any());
    }
    Ok(Bound::new(py, chain(py, &path, &request)?)?.into_any())
}

/// A chain study's one model size identified.
fn chain(py: Python<'_>, path: &Path, request: &IdentifyRequest<'_>) -> PyResult<Identification> {
    let sizes = self::sizes(py, request)?;
    if sizes.len() != 1 {
        return Err(invalid(format!(
            "{}: the study asks for the DOF sweep {sizes:?}; pass dof= for one model, or call bumpsim.dof_table",
            path.display(),
        )));
    }
    let identified = self::identified(py, request)?;
    match identified.sizes.into_iter().next() {
        Some(Size::Done(done)) => Ok(Identification::new(
            done.result,
            done.cases,
            identified.notes,
            Some(path.to_path_buf()),
            &done.settings,
        )),
        Some(Size::Failed { dof, error }) => Err(failed(dof, &error)),
        None => Err(invalid(format!("{}: no model size", path.display()))),
    }
}

/// The DOF table (the thesis's table 1) of the study file at `study` over
/// `dofs` (a number, a range `"1..5"` or a list; default the study's), each
/// model continued from the last one identified, as `bumpsim identify
/// STUDY --dof 1..5`; an order that fails is listed with its reason and the
/// others go on.
#[pyfunction]
#[pyo3(signature = (study, dofs = None, starts = None, seed = None, progress = None))]
fn dof_table(
    py: Python<'_>,
    study: &Bound<'_, PyAny>,
    dofs: Option<&Bound<'_, PyAny>>,
    starts: Option<&Bound<'_, PyAny>>,
    seed: Option<&Bound<'_, PyAny>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<DofTable> {
    let sizes = dofs.map(self::dofs).transpose()?;
    let path = path(study, "study", "a study")?;
    let ticks = Ticks(progress);
    let request = request(&path, sizes.as_deref(), starts, seed, &ticks)?;
    self::sizes(py, &request)?;
    let identified = self::identified(py, &request)?;
    let results = identified
        .done()
        .into_iter()
        .map(|d| {
            Identification::new(
                d.result.clone(),
                d.cases.clone(),
                identified.notes.clone(),
                Some(path.clone()),
                &d.settings,
            )
        })
        .collect();
    let failed = identified.failed();
    Ok(DofTable::new(results, failed, identified.notes))
}

/// The progress callback (if any) as the engine's progress: called once
/// per finished start, with the GIL; an exception in it is printed, not
/// raised.
struct Ticks(Option<Py<PyAny>>);

impl Progress for Ticks {
    fn start_finished(&self) {
        progress_callback(&self.0)();
    }
}
