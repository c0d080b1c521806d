//! `Car`, `simulate` and `Response`: bumpsim-core's MSD model and
//! simulation, car files through bumpsim-io (as `bumpsim simulate` does).
//! A function that takes a car takes a `Car` or the path of a car file.

use crate::arrays::{array1, array2, cached1, rows, values, vector};
use crate::errors::{input, invalid, message};
use crate::frames;
use bumpsim_core::discrete::{Method, Substeps};
use bumpsim_core::model::{MsdModel, parameter_kind, parameter_name};
use bumpsim_core::series::UniformSeries;
use bumpsim_core::simulate::{InitialState, Response as CoreResponse, Simulator};
use bumpsim_core::units::Unit;
use bumpsim_io::car::Car as IoCar;
use bumpsim_io::response::response_columns;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyTuple};
use serde::{Deserialize, Serialize};

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
pub struct Car {
    /// The validated car.
    pub inner: IoCar,
    masses: PyOnceLock<Py<PyArray1<f64>>>,
    dampers: PyOnceLock<Py<PyArray1<f64>>>,
    springs: PyOnceLock<Py<PyArray1<f64>>>,
}

impl Car {
    /// The Python object of a library car.
    pub fn of(inner: IoCar) -> Car {
        Car {
            inner,
            masses: PyOnceLock::new(),
            dampers: PyOnceLock::new(),
            springs: PyOnceLock::new(),
        }
    }
}

/// The car of an argument: a `Car`, or the path of a car file (TOML, or an
/// identification result JSON) read as `Car.from_file` does.
pub fn car_of(py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<IoCar> {
    if let Ok(car) = value.cast::<Car>() {
        return Ok(car.get().inner.clone());
    }
    let path = crate::convert::path(value, "car", "a bumpsim.Car")?;
    py.detach(|| IoCar::read_model_file(&path))
        .map_err(|e| crate::errors::reading(&path, e))
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
        Ok(Car::of(IoCar { name, model }))
    }

    /// Reads a car file (TOML) or an identification result (JSON).
    #[staticmethod]
    fn from_file(py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<Self> {
        car_of(py, path).map(Car::of)
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
        cached1(py, &self.masses, || self.inner.model.masses().to_vec())
    }

    /// Dampers c1..c(n-1), N·s/m.
    #[getter]
    fn dampers(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.dampers, || self.inner.model.dampers().to_vec())
    }

    /// Springs k1..k(n-1), N/m.
    #[getter]
    fn springs(&self, py: Python<'_>) -> Py<PyArray1<f64>> {
        cached1(py, &self.springs, || self.inner.model.springs().to_vec())
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

    /// The parameters as a DataFrame: index `parameter` (m1.., c1.., k1..),
    /// columns `value` (SI) and `unit`.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let model = &self.inner.model;
        let dof = model.dof();
        let parameters = model.parameters();
        let names: Vec<String> = (0..parameters.len())
            .map(|i| parameter_name(dof, i))
            .collect();
        let units: Vec<&str> = (0..parameters.len())
            .map(|i| parameter_kind(dof, i).0.unit())
            .collect();
        let columns = vec![
            (
                "value".to_string(),
                array1(py, parameters.to_vec()).into_bound(py).into_any(),
            ),
            ("unit".to_string(), units.into_pyobject(py)?.into_any()),
        ];
        let attrs = PyDict::new(py);
        attrs.set_item("name", &self.inner.name)?;
        let index = ("parameter".to_string(), names.into_pyobject(py)?.into_any());
        frames::frame(py, columns, Some(index), &attrs)
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }

    /// Pickles as its constructor's arguments.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let car = &slf.get().inner;
        let m = &car.model;
        let args = (
            m.masses().to_vec(),
            m.dampers().to_vec(),
            m.springs().to_vec(),
            car.name.clone(),
        );
        Ok((slf.get_type().into_any(), args.into_pyobject(py)?))
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
    /// The CLI's CSV headers after `time [s]` (`force [N]`, `x1 [m]`, ...).
    columns: Vec<String>,
}

/// A response's values (pickling and equality).
#[derive(Serialize, Deserialize, PartialEq)]
struct ResponseState {
    method: String,
    columns: Vec<String>,
    /// time, force, kinetic, spring and dissipated energy, work, impulse, momentum
    series: [Vec<f64>; 8],
    /// displacement, velocity, acceleration, spring and damper force (rows)
    rows: [Vec<Vec<f64>>; 5],
    energy_error: f64,
    momentum_error: f64,
    warnings: Vec<String>,
}

#[pymethods]
impl Response {
    /// The response as `bumpsim simulate -o` writes it: index `time [s]`,
    /// columns `force [N]`, `x1 [m]`, ..., `work [J]`; attrs: method,
    /// energy_error, momentum_error, warnings.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let mut arrays: Vec<Bound<'py, PyAny>> = vec![self.force.bind(py).clone().into_any()];
        for rows in [
            &self.displacement,
            &self.velocity,
            &self.acceleration,
            &self.spring_force,
            &self.damper_force,
        ] {
            for row in rows.bind(py).try_iter()? {
                arrays.push(row?);
            }
        }
        for energy in [
            &self.kinetic_energy,
            &self.spring_energy,
            &self.dissipated_energy,
            &self.work,
        ] {
            arrays.push(energy.bind(py).clone().into_any());
        }
        let columns = self.columns.iter().cloned().zip(arrays).collect();
        let attrs = PyDict::new(py);
        attrs.set_item("method", &self.method)?;
        attrs.set_item("energy_error", self.energy_error)?;
        attrs.set_item("momentum_error", self.momentum_error)?;
        attrs.set_item("warnings", &self.warnings)?;
        let index = (
            "time [s]".to_string(),
            self.time.bind(py).clone().into_any(),
        );
        frames::frame(py, columns, Some(index), &attrs)
    }
    fn __eq__(&self, py: Python<'_>, other: &Self) -> bool {
        self.state(py) == other.state(py)
    }
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, pyo3::types::PyBytes>,))> {
        let state = crate::state::encode(&slf.get().state(slf.py()))?;
        crate::state::reduce(slf.as_any(), &state)
    }
    #[classmethod]
    fn _from_state(
        _cls: &Bound<'_, pyo3::types::PyType>,
        py: Python<'_>,
        state: &[u8],
    ) -> PyResult<Self> {
        let s: ResponseState = crate::state::decode(state, "Response")?;
        let [
            time,
            force,
            kinetic,
            spring,
            dissipated,
            work,
            impulse,
            momentum,
        ] = s.series;
        let [x, v, a, spring_force, damper_force] = s.rows;
        let n = time.len();
        Ok(Response {
            method: s.method,
            columns: s.columns,
            displacement: array2(py, &x, n),
            velocity: array2(py, &v, n),
            acceleration: array2(py, &a, n),
            spring_force: array2(py, &spring_force, n),
            damper_force: array2(py, &damper_force, n),
            time: array1(py, time),
            force: array1(py, force),
            kinetic_energy: array1(py, kinetic),
            spring_energy: array1(py, spring),
            dissipated_energy: array1(py, dissipated),
            work: array1(py, work),
            impulse: array1(py, impulse),
            momentum: array1(py, momentum),
            energy_error: s.energy_error,
            momentum_error: s.momentum_error,
            warnings: s.warnings,
        })
    }
    fn __repr__(&self, py: Python<'_>) -> String {
        let shape = self.displacement.bind(py).shape().to_vec();
        format!(
            "Response(method={:?}, dof={}, samples={}, energy_error={:e})",
            self.method, shape[0], shape[1], self.energy_error
        )
    }
}

use numpy::PyUntypedArrayMethods;

impl Response {
    fn state(&self, py: Python<'_>) -> ResponseState {
        let one = |a: &Py<PyArray1<f64>>| values(py, a);
        let two = |a: &Py<PyArray2<f64>>| rows(py, a);
        ResponseState {
            method: self.method.clone(),
            columns: self.columns.clone(),
            series: [
                one(&self.time),
                one(&self.force),
                one(&self.kinetic_energy),
                one(&self.spring_energy),
                one(&self.dissipated_energy),
                one(&self.work),
                one(&self.impulse),
                one(&self.momentum),
            ],
            rows: [
                two(&self.displacement),
                two(&self.velocity),
                two(&self.acceleration),
                two(&self.spring_force),
                two(&self.damper_force),
            ],
            energy_error: self.energy_error,
            momentum_error: self.momentum_error,
            warnings: self.warnings.clone(),
        }
    }

    fn from_core(py: Python<'_>, r: CoreResponse) -> Response {
        let n = r.time.len();
        let (energy_error, momentum_error, warnings) =
            (r.energy.relative_error(), r.momentum_error(), r.warnings());
        let columns = response_columns(&r)
            .into_iter()
            .map(|(name, dimension, _)| format!("{name} [{}]", Unit::si(dimension).symbol))
            .collect();
        Response {
            method: r.method.name().to_string(),
            columns,
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
        _ => Err(invalid(format!(
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
    car: &Bound<'_, PyAny>,
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
    let car = car_of(py, car)?;
    let model = &car.model;
    let response = py.detach(|| {
        let force = UniformSeries::from_times(&time, force).map_err(input)?;
        let simulator = Simulator::with_substeps(model, method, force.step(), substeps).map_err(|e| {
            invalid(format!(
                "cannot simulate the car with {method}: {}",
                message(&e)
            ))
        })?;
        let initial = InitialState::UniformVelocity(initial_velocity);
        let response = simulator.run(&force, &initial).map_err(input)?;
        if !response.is_finite() {
            return Err(invalid(format!(
                "the simulation produced non-finite values (inf or NaN): the model, force or initial velocity is beyond what the {method} discretisation can represent"
            )));
        }
        Ok(response)
    })?;
    Ok(Response::from_core(py, response))
}
