//! Impacts and mass reduction (bumpsim-impact), the calls `bumpsim impact`
//! and `bumpsim mass-reduction` make: a preset or a pendulum or barrier
//! scenario, the library's impact simulation, results with the JSON's fields.

use crate::arrays::{array1, array2};
use crate::errors::{InputError, file_or_input, input, message};
use crate::ident::from_json;
use crate::model::Car;
use bumpsim_impact::bumper::Bumper as CoreBumper;
use bumpsim_impact::impact::{ImpactResult, Options, Scenario, simulate};
use bumpsim_impact::presets::{PRESETS, ScenarioSpec};
use bumpsim_impact::reduction::{Criterion, TwoDof, equivalent_mass};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use std::path::PathBuf;

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

#[pymethods]
impl Bumper {
    /// Reads a bumper file (TOML: ramp, plateau, unloading; or curve, unloading).
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let inner = CoreBumper::read(&path).map_err(file_or_input)?;
        Ok(Bumper { inner })
    }
}

/// The load-case presets: dicts with name, speed_kmh, description and source.
#[pyfunction]
fn presets(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyAny>>> {
    PRESETS
        .iter()
        .map(|p| {
            let d = pyo3::types::PyDict::new(py);
            d.set_item("name", p.name)?;
            d.set_item("speed_kmh", p.speed_kmh)?;
            d.set_item("description", p.description)?;
            d.set_item("source", p.source)?;
            Ok(d.into_any())
        })
        .collect()
}

/// Simulates an impact on `car` through `bumper`, as `bumpsim impact`:
/// a preset `case`, or a `pendulum` of that mass (kg) or a rigid `barrier`,
/// at `speed` (m/s; default the preset's).
#[pyfunction]
#[pyo3(signature = (car, bumper, case = None, pendulum = None, barrier = false, speed = None))]
fn impact(
    py: Python<'_>,
    car: &Car,
    bumper: &Bumper,
    case: Option<&str>,
    pendulum: Option<f64>,
    barrier: bool,
    speed: Option<f64>,
) -> PyResult<Impact> {
    let model = &car.inner.model;
    let spec = ScenarioSpec {
        case: case.map(str::to_string),
        pendulum,
        barrier,
        speed,
    };
    let (scenario, _) = spec.scenario(model.total_mass()).map_err(input)?;
    let result = py
        .detach(|| simulate(model, &bumper.inner, scenario, &Options::default()))
        .map_err(input)?;
    Ok(Impact { scenario, result })
}

/// The result of an impact: peak force, compressions, contact time,
/// absorbed energy, energy balance and the time histories, SI.
#[pyclass(frozen, module = "bumpsim")]
pub struct Impact {
    scenario: Scenario,
    result: ImpactResult,
}

#[pymethods]
impl Impact {
    /// What hit what at which speed (the JSON's `scenario`).
    #[getter]
    fn scenario<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.scenario)
    }
    /// Peak contact force, N.
    #[getter]
    fn peak_force(&self) -> f64 {
        self.result.peak_force
    }
    /// Maximum bumper compression, m.
    #[getter]
    fn max_compression(&self) -> f64 {
        self.result.max_compression
    }
    /// Remaining (permanent) compression, m.
    #[getter]
    fn remaining_compression(&self) -> f64 {
        self.result.remaining_compression
    }
    /// Contact time, s.
    #[getter]
    fn contact_time(&self) -> f64 {
        self.result.contact_time
    }
    /// Energy absorbed by the bumper, J.
    #[getter]
    fn absorbed_energy(&self) -> f64 {
        self.result.absorbed_energy
    }
    /// Energy balance terms, J, and its relative error.
    #[getter]
    fn energy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result.energy)
    }
    /// Integration step, s.
    #[getter]
    fn step(&self) -> f64 {
        self.result.step
    }
    /// Names of the bodies (rows of displacements and velocities).
    #[getter]
    fn bodies(&self) -> Vec<String> {
        self.result.bodies.clone()
    }
    /// Output times, s.
    #[getter]
    fn time(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.result.time.clone())
    }
    /// Contact force, N.
    #[getter]
    fn force(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.result.force.clone())
    }
    /// Bumper compression, m.
    #[getter]
    fn compression(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.result.compression.clone())
    }
    /// Displacements, m, one row per body.
    #[getter]
    fn displacements(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        array2(py, &self.result.displacements, self.result.time.len())
    }
    /// Velocities, m/s, one row per body.
    #[getter]
    fn velocities(&self, py: Python<'_>) -> Py<PyArray2<f64>> {
        array2(py, &self.result.velocities, self.result.time.len())
    }
    /// Warnings about the result (energy balance, ...).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.result.warnings()
    }
    /// The summary `bumpsim impact` prints.
    fn summary(&self) -> String {
        bumpsim_impact::text::summary(&self.result)
    }
    /// The result as `bumpsim impact --json` writes it.
    fn to_json(&self) -> PyResult<String> {
        let json = bumpsim_impact::document::ImpactSummary::of(self.scenario, &self.result);
        serde_json::to_string_pretty(&json).map_err(input)
    }
    fn __repr__(&self) -> String {
        format!(
            "Impact(peak_force={} N, max_compression={} m, contact_time={} s)",
            self.result.peak_force, self.result.max_compression, self.result.contact_time
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
    bumper: &Bumper,
    speed: f64,
    criterion: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let criterion: Criterion = criterion
        .parse()
        .map_err(|e| InputError::new_err(format!("criterion: {}", message(&e))))?;
    let car = TwoDof { m1, m2, k };
    let r = py
        .detach(|| equivalent_mass(&car, &bumper.inner, speed, criterion))
        .map_err(input)?;
    from_json(py, &r)
}
