//! Impacts and mass reduction (bumpsim-impact), the calls `bumpsim impact`
//! and `bumpsim mass-reduction` make: a preset or a pendulum or barrier
//! scenario, the library's impact simulation, results with the JSON's fields.
//! A function that takes a bumper takes a `Bumper` or the path of its file.

use crate::arrays::{cached1, cached2};
use crate::convert::from_json;
use crate::errors::{input, invalid, message, reading};
use crate::frames;
use crate::model::car_of;
use crate::state::impact::{BumperState, ImpactState};
use crate::state::{decode, encode, reduce};
use crate::uncertain::{Arguments, Predicted, Uncertain};
use bumpsim_impact::bumper::{Bumper as CoreBumper, Loading};
use bumpsim_impact::impact::{ImpactResult, Options, simulate};
use bumpsim_impact::presets::{PRESETS, ScenarioSpec};
use bumpsim_impact::reduction::{Criterion, TwoDof, equivalent_mass};
use bumpsim_impact::uncertainty::{Chain, ChainCar};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBytes, PyDict, PyType};
use std::path::PathBuf;

/// What `__reduce__` returns.
type Reduced<'py> = (Bound<'py, PyAny>, (Bound<'py, PyBytes>,));

/// What `__reduce__` of a result with a prediction returns: the state and
/// the prediction's JSON.
pub(crate) type Predictable<'py> = (Bound<'py, PyAny>, (Bound<'py, PyBytes>, Option<String>));

/// Registers the classes and functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Bumper>()?;
    m.add_class::<Impact>()?;
    m.add_function(wrap_pyfunction!(impact, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(mass_reduction, m)?)?;
    Ok(())
}

/// A bumper characteristic (three-part or tabulated, with elastic unloading).
#[pyclass(frozen, module = "bumpsim")]
pub struct Bumper {
    inner: CoreBumper,
}

/// The bumper of an argument: a `Bumper`, or the path of a bumper file.
pub(crate) fn bumper_of(value: &Bound<'_, PyAny>) -> PyResult<CoreBumper> {
    if let Ok(bumper) = value.cast::<Bumper>() {
        return Ok(bumper.get().inner.clone());
    }
    let path = crate::convert::path(value, "bumper", "a bumpsim.Bumper")?;
    CoreBumper::read(&path).map_err(|e| reading(&path, e))
}

#[pymethods]
impl Bumper {
    /// Reads a bumper file (TOML: ramp, plateau, unloading; or curve, unloading).
    #[staticmethod]
    fn from_file(path: &Bound<'_, PyAny>) -> PyResult<Self> {
        Ok(Bumper {
            inner: bumper_of(path)?,
        })
    }
    /// The unloading slope, N/m.
    #[getter]
    fn unloading(&self) -> f64 {
        self.inner.unloading_slope()
    }
    /// The loading curve: index `compression [m]`, column `force [N]` (a
    /// three-part curve as its knee and a plateau point, as the FE decks
    /// write it); attrs: unloading [N/m].
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (d, f): (Vec<f64>, Vec<f64>) = self.inner.loading_points().into_iter().unzip();
        let columns = vec![("force [N]".into(), f.into_pyobject(py)?.into_any())];
        let attrs = PyDict::new(py);
        attrs.set_item("unloading [N/m]", self.inner.unloading_slope())?;
        let index = ("compression [m]".into(), d.into_pyobject(py)?.into_any());
        frames::frame(py, columns, Some(index), &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        let b = &slf.get().inner;
        let state = BumperState {
            loading: b.loading().clone(),
            unloading: b.unloading_slope(),
        };
        reduce(slf.as_any(), &encode(&state)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        let BumperState { loading, unloading } = decode(state, "Bumper")?;
        let inner = match loading {
            Loading::ThreePart { ramp, plateau } => {
                CoreBumper::three_part(ramp, plateau, unloading)
            }
            Loading::Table { compression, force } => {
                CoreBumper::table(compression, force, unloading)
            }
        };
        Ok(Bumper {
            inner: inner.map_err(input)?,
        })
    }
    fn __repr__(&self) -> String {
        let unloading = self.inner.unloading_slope();
        match self.inner.loading() {
            Loading::ThreePart { ramp, plateau } => {
                format!("Bumper(ramp={ramp} N/m, plateau={plateau} N, unloading={unloading} N/m)")
            }
            Loading::Table { compression, .. } => format!(
                "Bumper(curve of {} points to {} m, unloading={unloading} N/m)",
                compression.len(),
                compression.last().copied().unwrap_or(0.0)
            ),
        }
    }
}

/// The load-case presets, the one table of tests (as `bumpsim impact --case
/// list`): dicts with name, protocol, speed_kmh, description, source,
/// uncertain and what a 1-D impact drops of it (`dropped_in_1d`, or None).
#[pyfunction]
fn presets(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyAny>>> {
    PRESETS
        .iter()
        .map(|p| {
            let d = pyo3::types::PyDict::new(py);
            d.set_item("name", p.name)?;
            d.set_item("protocol", p.protocol)?;
            d.set_item("speed_kmh", p.speed_kmh())?;
            d.set_item("description", p.description)?;
            d.set_item("source", p.source)?;
            d.set_item("uncertain", p.uncertain)?;
            d.set_item("dropped_in_1d", p.dropped_in_1d())?;
            Ok(d.into_any())
        })
        .collect()
}

/// Simulates an impact on `car` through `bumper`, as `bumpsim impact`:
/// a preset `case`, or a `pendulum` of that mass (kg) or a rigid `barrier`,
/// at `speed` (m/s; default the preset's). With `uncertainty` (a file), also
/// the prediction over `samples` draws of the car (`seed`, `level`) and,
/// with `sobol`, the Sobol indices (`sobol_base` base samples), as
/// `--uncertainty`.
#[pyfunction]
#[pyo3(signature = (car, bumper, case = None, pendulum = None, barrier = false, speed = None, *, uncertainty = None, samples = None, seed = None, level = 0.9, sobol = false, sobol_base = None))]
// one Rust argument per Python keyword argument
#[allow(clippy::too_many_arguments)]
fn impact(
    py: Python<'_>,
    car: &Bound<'_, PyAny>,
    bumper: &Bound<'_, PyAny>,
    case: Option<&str>,
    pendulum: Option<f64>,
    barrier: bool,
    speed: Option<f64>,
    uncertainty: Option<PathBuf>,
    samples: Option<&Bound<'_, PyAny>>,
    seed: Option<&Bound<'_, PyAny>>,
    level: f64,
    sobol: bool,
    sobol_base: Option<&Bound<'_, PyAny>>,
) -> PyResult<Impact> {
    let (car, bumper) = (car_of(py, car)?, bumper_of(bumper)?);
    let model = &car.model;
    let spec = ScenarioSpec {
        case: case.map(str::to_string),
        pendulum,
        barrier,
        speed,
    };
    let (scenario, _) = spec.scenario(model.total_mass()).map_err(input)?;
    let chain = ChainCar {
        model: model.clone(),
        bumper: bumper.clone(),
    };
    let arguments = Arguments {
        path: uncertainty,
        samples,
        seed,
        level,
        sobol,
        sobol_base,
    };
    let uncertain = Uncertain::<Chain>::read(&arguments, &chain)?;
    let result = py
        .detach(|| simulate(model, &bumper, scenario, &Options::default()))
        .map_err(input)?;
    let run = |c: &ChainCar| simulate(&c.model, &c.bumper, scenario, &Options::default()).ok();
    let predicted = uncertain
        .map(|u| u.run(py, &chain, &result, &run))
        .transpose()?;
    Ok(Impact::of(ImpactState { scenario, result }, predicted))
}

/// The result of an impact: peak force, compressions, contact time,
/// absorbed energy, energy balance and the time histories, SI.
#[pyclass(frozen, module = "bumpsim")]
pub struct Impact {
    data: ImpactState,
    predicted: Option<Predicted>,
    time: PyOnceLock<Py<PyArray1<f64>>>,
    force: PyOnceLock<Py<PyArray1<f64>>>,
    compression: PyOnceLock<Py<PyArray1<f64>>>,
    displacements: PyOnceLock<Py<PyArray2<f64>>>,
    velocities: PyOnceLock<Py<PyArray2<f64>>>,
}

impl Impact {
    fn of(data: ImpactState, predicted: Option<Predicted>) -> Impact {
        Impact {
            data,
            predicted,
            time: PyOnceLock::new(),
            force: PyOnceLock::new(),
            compression: PyOnceLock::new(),
            displacements: PyOnceLock::new(),
            velocities: PyOnceLock::new(),
        }
    }

    fn result(&self) -> &ImpactResult {
        &self.data.result
    }
}

#[pymethods]
impl Impact {
    /// What hit what at which speed (the JSON's `scenario`).
    #[getter]
    fn scenario<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.data.scenario)
    }
    /// Peak contact force, N.
    #[getter]
    fn peak_force(&self) -> f64 {
        self.result().peak_force
    }
    /// Maximum bumper compression, m.
    #[getter]
    fn max_compression(&self) -> f64 {
        self.result().max_compression
    }
    /// Remaining (permanent) compression, m.
    #[getter]
    fn remaining_compression(&self) -> f64 {
        self.result().remaining_compression
    }
    /// Contact time, s.
    #[getter]
    fn contact_time(&self) -> f64 {
        self.result().contact_time
    }
    /// Energy absorbed by the bumper, J.
    #[getter]
    fn absorbed_energy(&self) -> f64 {
        self.result().absorbed_energy
    }
    /// Energy balance terms, J, and its relative error.
    #[getter]
    fn energy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result().energy)
    }
    /// Integration step, s.
    #[getter]
    fn step(&self) -> f64 {
        self.result().step
    }
    /// Names of the bodies (rows of displacements and velocities).
    #[getter]
    fn bodies(&self) -> Vec<String> {
        self.result().bodies.clone()
    }
    /// Output times, s.
    #[getter]
    fn time(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.time, || self.result().time.clone())
    }
    /// Contact force, N.
    #[getter]
    fn force(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.force, || self.result().force.clone())
    }
    /// Bumper compression, m.
    #[getter]
    fn compression(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.compression, || self.result().compression.clone())
    }
    /// Displacements, m, one row per body.
    #[getter]
    fn displacements(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        let r = self.result();
        cached2(py, &self.displacements, &r.displacements, r.time.len())
    }
    /// Velocities, m/s, one row per body.
    #[getter]
    fn velocities(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        let r = self.result();
        cached2(py, &self.velocities, &r.velocities, r.time.len())
    }
    /// Warnings about the result (energy balance, ...).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.result().warnings()
    }
    /// The summary `bumpsim impact` prints.
    fn summary(&self) -> String {
        bumpsim_impact::text::summary(self.result())
    }
    /// The result as `bumpsim impact --json` writes it (with `prediction`
    /// and `sensitivity` when asked).
    fn to_json(&self) -> PyResult<String> {
        let json = bumpsim_impact::document::ImpactSummary::of(self.data.scenario, self.result());
        Predicted::with(&self.predicted, json)
    }
    /// The prediction over the car's uncertainty, the JSON's `prediction`
    /// (None without `uncertainty`).
    #[getter]
    fn prediction<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        Predicted::prediction(py, &self.predicted)
    }
    /// The Sobol indices, the JSON's `sensitivity` (None without `sobol`).
    #[getter]
    fn sensitivity<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        Predicted::sensitivity(py, &self.predicted)
    }
    /// The histories' bands over the draws: name → dict of arrays `time`
    /// [s], `nominal`, `low`, `median`, `high` (None without `uncertainty`).
    #[getter]
    fn bands<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        Predicted::bands(py, &self.predicted)
    }
    /// The prediction's spreads as a table: index `output`; columns `unit`,
    /// `nominal`, `median`, `low`, `high`, `mean`, `sd`; attrs: sampling,
    /// failed draws (None without `uncertainty`).
    fn prediction_to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        Predicted::frame(py, &self.predicted)
    }
    /// The histories as `bumpsim impact --csv` writes them: index `time
    /// [s]`, columns `force [N]`, `compression [m]`, `x BODY [m]`, `v BODY
    /// [m/s]`; attrs: the scenario and the peaks.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let r = self.result();
        let attrs = PyDict::new(py);
        attrs.set_item("scenario", self.scenario(py)?)?;
        attrs.set_item("peak_force [N]", r.peak_force)?;
        attrs.set_item("max_compression [m]", r.max_compression)?;
        attrs.set_item("contact_time [s]", r.contact_time)?;
        attrs.set_item("warnings", r.warnings())?;
        frames::csv(py, &bumpsim_impact::text::histories(r), &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.data.scenario == other.data.scenario
            && self.data.result == other.data.result
            && self.predicted == other.predicted
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Predictable<'py>> {
        let (restore, (state,)) = reduce(slf.as_any(), &encode(&slf.get().data)?)?;
        Ok((restore, (state, Predicted::state(&slf.get().predicted)?)))
    }
    #[classmethod]
    #[pyo3(signature = (state, predicted = None))]
    fn _from_state(
        _cls: &Bound<'_, PyType>,
        state: &[u8],
        predicted: Option<&str>,
    ) -> PyResult<Self> {
        let predicted = Predicted::of_state(predicted)?;
        Ok(Impact::of(decode(state, "Impact")?, predicted))
    }
    fn __repr__(&self) -> String {
        let r = self.result();
        format!(
            "Impact(peak_force={} N, max_compression={} m, contact_time={} s)",
            r.peak_force, r.max_compression, r.contact_time
        )
    }
}

/// Paper A's reduced point mass of a 2-DOF car (m1, m2 in kg, k in N/m)
/// hitting a rigid barrier at `speed` m/s through `bumper`, as
/// `bumpsim mass-reduction --json`: a dict with the equivalent mass and
/// scale factor.
#[pyfunction]
#[pyo3(signature = (m1, m2, k, bumper, speed, criterion = "remaining"))]
fn mass_reduction<'py>(
    py: Python<'py>,
    m1: f64,
    m2: f64,
    k: f64,
    bumper: &Bound<'py, PyAny>,
    speed: f64,
    criterion: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let criterion: Criterion = criterion
        .parse()
        .map_err(|e| invalid(format!("criterion: {}", message(&e))))?;
    let car = TwoDof { m1, m2, k };
    let bumper = bumper_of(bumper)?;
    let r = py
        .detach(|| equivalent_mass(&car, &bumper, speed, criterion))
        .map_err(input)?;
    from_json(py, &r)
}
