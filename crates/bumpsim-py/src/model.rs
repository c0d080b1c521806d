//! `Car`, `simulate` and `Response`: bumpsim-core's MSD model and
//! simulation, car files through bumpsim-io (as `bumpsim simulate` does).

use crate::arrays::{array1, array2, vector};
use crate::errors::{InputError, file_or_input, input};
use bumpsim_core::discrete::{Method, Substeps};
use bumpsim_core::model::MsdModel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::simulate::{InitialState, Response as CoreResponse, Simulator};
use bumpsim_io::car::Car as IoCar;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use std::path::PathBuf;

/// Registers the classes and functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Car>()?;
    m.add_class::<Response>()?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    Ok(())
}

/// An n-DOF chain MSD car model: masses (kg), dampers (N·s/m) and springs
/// (N/m), validated by the core at construction.
#[pyclass(frozen, module = "bumpsim")]
#[derive(Clone)]
pub struct Car {
    /// The validated car.
    pub inner: IoCar,
}

#[pymethods]
impl Car {
    #[new]
    #[pyo3(signature = (masses, dampers, springs, name = None))]
    fn new(
        masses: &Bound<'_, PyAny>,
        dampers: &Bound<'_, PyAny>,
        springs: &Bound<'_, PyAny>,
        name: Option<String>,
    ) -> PyResult<Self> {
        let model = MsdModel::new(
            vector(masses, "masses")?,
            vector(dampers, "dampers")?,
            vector(springs, "springs")?,
        )
        .map_err(input)?;
        Ok(Car {
            inner: IoCar { name, model },
        })
    }

    /// Reads a car file (TOML) or an identification result (JSON).
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let car = py
            .detach(|| IoCar::read_model_file(&path))
            .map_err(file_or_input)?;
        Ok(Car { inner: car })
    }

    /// The name from the file or the constructor, or None.
    #[getter]
    fn name(&self) -> Option<String> {
        self.inner.name.clone()
    }

    /// Number of masses.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.model.dof()
    }

    /// Masses, kg (m1 carries the bumper).
    #[getter]
    fn masses(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.inner.model.masses().to_vec())
    }

    /// Dampers c1..c(n-1), N·s/m.
    #[getter]
    fn dampers(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.inner.model.dampers().to_vec())
    }

    /// Springs k1..k(n-1), N/m.
    #[getter]
    fn springs(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        array1(py, self.inner.model.springs().to_vec())
    }

    /// Total mass, kg.
    #[getter]
    fn total_mass(&self) -> f64 {
        self.inner.model.total_mass()
    }

    /// The car file text (TOML).
    fn to_toml(&self) -> String {
        self.inner.to_toml()
    }

    fn __repr__(&self) -> String {
        let m = &self.inner.model;
        let name = match &self.inner.name {
            Some(name) => format!(", name={name:?}"),
            None => String::new(),
        };
        format!(
            "Car(masses={:?}, dampers={:?}, springs={:?}{name})",
            m.masses(),
            m.dampers(),
            m.springs()
        )
    }
}

/// The response of a simulation, SI, one row per mass (displacement,
/// velocity, acceleration) or link (spring and damper forces, positive in
/// compression), one column per sample.
#[pyclass(frozen, module = "bumpsim")]
pub struct Response {
    #[pyo3(get)]
    method: String,
    #[pyo3(get)]
    time: Py<PyArray1<f64>>,
    #[pyo3(get)]
    force: Py<PyArray1<f64>>,
    #[pyo3(get)]
    displacement: Py<PyArray2<f64>>,
    #[pyo3(get)]
    velocity: Py<PyArray2<f64>>,
    #[pyo3(get)]
    acceleration: Py<PyArray2<f64>>,
    #[pyo3(get)]
    spring_force: Py<PyArray2<f64>>,
    #[pyo3(get)]
    damper_force: Py<PyArray2<f64>>,
    #[pyo3(get)]
    kinetic_energy: Py<PyArray1<f64>>,
    #[pyo3(get)]
    spring_energy: Py<PyArray1<f64>>,
    #[pyo3(get)]
    dissipated_energy: Py<PyArray1<f64>>,
    #[pyo3(get)]
    work: Py<PyArray1<f64>>,
    #[pyo3(get)]
    impulse: Py<PyArray1<f64>>,
    #[pyo3(get)]
    momentum: Py<PyArray1<f64>>,
    #[pyo3(get)]
    energy_error: f64,
    #[pyo3(get)]
    momentum_error: f64,
    #[pyo3(get)]
    warnings: Vec<String>,
}

#[pymethods]
impl Response {
    fn __repr__(&self, py: Python<'_>) -> String {
        let shape = self.displacement.bind(py).shape().to_vec();
        format!(
            "Response(method={:?}, dof={}, samples={})",
            self.method, shape[0], shape[1]
        )
    }
}

use numpy::PyUntypedArrayMethods;

impl Response {
    fn from_core(py: Python<'_>, r: CoreResponse) -> Response {
        let n = r.time.len();
        let (energy_error, momentum_error, warnings) =
            (r.energy.relative_error(), r.momentum_error(), r.warnings());
        Response {
            method: r.method.name().to_string(),
            displacement: array2(py, &r.displacement, n),
            velocity: array2(py, &r.velocity, n),
            acceleration: array2(py, &r.acceleration, n),
            spring_force: array2(py, &r.spring_force, n),
            damper_force: array2(py, &r.damper_force, n),
            time: array1(py, r.time),
            force: array1(py, r.force),
            kinetic_energy: array1(py, r.energy.kinetic),
            spring_energy: array1(py, r.energy.spring),
            dissipated_energy: array1(py, r.energy.dissipated),
            work: array1(py, r.energy.work),
            impulse: array1(py, r.impulse),
            momentum: array1(py, r.momentum),
            energy_error,
            momentum_error,
            warnings,
        }
    }
}

/// taylor1's sub-steps per sample: a whole number ≥ 1 or "auto" (as `--substeps`).
fn substeps(given: Option<&Bound<'_, PyAny>>) -> PyResult<Substeps> {
    let Some(given) = given else {
        return Ok(Substeps::default());
    };
    if given.extract::<String>().is_ok_and(|s| s == "auto") {
        return Ok(Substeps::Auto);
    }
    match given.extract::<u32>() {
        Ok(n) if n > 0 => Ok(Substeps::Count(n)),
        _ => Err(InputError::new_err(format!(
            "substeps {given}: expected a whole number of at least 1, or 'auto'"
        ))),
    }
}

/// Simulates `car` under `force` (N, on m1) sampled at `time` (s, uniform),
/// every mass starting at `initial_velocity` (m/s), as `bumpsim simulate`.
#[pyfunction]
#[pyo3(signature = (car, time, force, method = "zoh", initial_velocity = 0.0, substeps = None))]
fn simulate(
    py: Python<'_>,
    car: &Car,
    time: &Bound<'_, PyAny>,
    force: &Bound<'_, PyAny>,
    method: &str,
    initial_velocity: f64,
    substeps: Option<&Bound<'_, PyAny>>,
) -> PyResult<Response> {
    let method: Method = method.parse().map_err(input)?;
    let substeps = self::substeps(substeps)?;
    let time = vector(time, "time")?;
    let force = vector(force, "force")?;
    let model = &car.inner.model;
    let response = py.detach(|| {
        let force = UniformSeries::from_times(&time, force).map_err(input)?;
        let simulator = Simulator::with_substeps(model, method, force.step(), substeps).map_err(|e| {
            InputError::new_err(format!(
                "cannot simulate the car with {method}: {}",
                crate::errors::message(&e)
            ))
        })?;
        let initial = InitialState::UniformVelocity(initial_velocity);
        let response = simulator.run(&force, &initial).map_err(input)?;
        if !response.is_finite() {
            return Err(InputError::new_err(format!(
                "the simulation produced non-finite values (inf or NaN): the model, force or initial velocity is beyond what the {method} discretisation can represent"
            )));
        }
        Ok(response)
    })?;
    Ok(Response::from_core(py, response))
}
