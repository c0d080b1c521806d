//! The planar car, the calls `bumpsim planar` makes: a preset or an
//! angled/offset barrier, pendulum or pole striker, as the engine's impact
//! request ([`bumpsim_engine::impact`]) on the car the `PlanarCar` holds
//! ([`bumpsim_engine::HeldCar`]); the result is the request's outcome,
//! with the JSON's fields. A function that takes a planar car takes a
//! `PlanarCar` or the path of its file.

use crate::convert::from_json;
use crate::errors::{input, invalid, reading};
use crate::frames;
use crate::state::{decode, encode, reduce};
use crate::uncertain::{Arguments, Predicted, engine};
use bumpsim_engine::{Face, HeldCar, ImpactRequest, Outcome, Side, UncertaintyOptions};
use bumpsim_io::kind::ModelKind;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple, PyType};
use serde_json::Value;
use std::path::PathBuf;

/// The model a `PlanarCar` is read as.
const PLANAR: ModelKind = ModelKind::Planar;

/// Registers the classes and functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PlanarCar>()?;
    m.add_class::<PlanarImpact>()?;
    m.add_function(wrap_pyfunction!(planar_impact, m)?)?;
    Ok(())
}

/// A planar car (yaw, left/right chains, segmented bumper beam, tyres).
#[pyclass(frozen, module = "bumpsim")]
pub struct PlanarCar {
    inner: HeldCar,
}

/// The planar car of an argument: a `PlanarCar`, or the path of its file.
pub(crate) fn planar_car_of(value: &Bound<'_, PyAny>) -> PyResult<HeldCar> {
    if let Ok(car) = value.cast::<PlanarCar>() {
        return Ok(car.get().inner.clone());
    }
    let path = crate::convert::path(value, "car", "a bumpsim.PlanarCar")?;
    HeldCar::read(&path, PLANAR).map_err(|e| reading(&path, e))
}

#[pymethods]
impl PlanarCar {
    /// Reads a planar car file (TOML, docs/planar.md).
    #[staticmethod]
    fn from_file(path: &Bound<'_, PyAny>) -> PyResult<Self> {
        Ok(PlanarCar {
            inner: planar_car_of(path)?,
        })
    }
    /// The name from the file, or None.
    #[getter]
    fn name(&self) -> Option<String> {
        self.inner.name().map(str::to_string)
    }
    /// The file it was read from.
    #[getter]
    fn path(&self) -> PathBuf {
        self.inner.path().to_path_buf()
    }
    /// The car as a planar car file (SI lengths), which reads back to the same car.
    fn to_toml(&self) -> String {
        self.inner.to_toml().to_string()
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }
    /// Pickles as its file text and path.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let car = &slf.get().inner;
        let restore = slf.get_type().getattr("_from_toml")?;
        let args = (car.to_toml(), car.path().to_path_buf()).into_pyobject(slf.py())?;
        Ok((restore, args))
    }
    /// The car from its file text (`to_toml`) and the path it names.
    #[classmethod]
    fn _from_toml(_cls: &Bound<'_, PyType>, text: &str, path: PathBuf) -> PyResult<Self> {
        let inner = HeldCar::parse(text, &path, PLANAR).map_err(input)?;
        Ok(PlanarCar { inner })
    }
    fn __repr__(&self) -> String {
        format!(
            "PlanarCar({:?} from {:?})",
            self.inner.name().unwrap_or("unnamed"),
            self.inner.path()
        )
    }
}

/// An angled, offset, corner or pole impact of the planar car, as
/// `bumpsim planar`: a preset `case`, or a barrier (or a `pendulum` of that
/// mass, kg) at `angle` degrees with `overlap` % from `side`, or a pole of
/// diameter `pole` m at `pole_offset` m; `speed` m/s. With `uncertainty`
/// (a file), also the prediction over `samples` draws of the car (`seed`,
/// `level`) and, with `sobol`, the Sobol indices (`sobol_base` base
/// samples), as `--uncertainty`.
#[pyfunction]
#[pyo3(signature = (car, case = None, angle = None, overlap = None, side = "left", pole = None, pole_offset = 0.0, pendulum = None, speed = None, *, uncertainty = None, samples = None, seed = None, level = 0.9, sobol = false, sobol_base = None))]
// one Rust argument per Python keyword argument
#[allow(clippy::too_many_arguments)]
fn planar_impact(
    py: Python<'_>,
    car: &Bound<'_, PyAny>,
    case: Option<String>,
    angle: Option<f64>,
    overlap: Option<f64>,
    side: &str,
    pole: Option<f64>,
    pole_offset: f64,
    pendulum: Option<f64>,
    speed: Option<f64>,
    uncertainty: Option<PathBuf>,
    samples: Option<&Bound<'_, PyAny>>,
    seed: Option<&Bound<'_, PyAny>>,
    level: f64,
    sobol: bool,
    sobol_base: Option<&Bound<'_, PyAny>>,
) -> PyResult<PlanarImpact> {
    let car = planar_car_of(car)?;
    let side: Side = side.parse().map_err(|e| invalid(format!("side: {e}")))?;
    let arguments = Arguments {
        path: uncertainty,
        samples,
        seed,
        level,
        sobol,
        sobol_base,
    };
    let checked = arguments.options()?;
    // the numbers in SI, as the request reads an option's text
    let (speed, pole, pole_offset) = (
        speed.map(|v| v.to_string()),
        pole.map(|v| v.to_string()),
        pole_offset.to_string(),
    );
    let request = ImpactRequest {
        car: Some(car.path()),
        car_text: Some(car.text()),
        case: case.as_deref(),
        pendulum,
        speed: speed.as_deref(),
        face: Face {
            angle,
            overlap,
            side: Some(side),
            pole: pole.as_deref(),
            pole_offset: Some(&pole_offset),
        },
        uncertainty: checked.as_ref().map(|c| UncertaintyOptions {
            path: &c.path,
            samples: c.samples,
            seed: c.seed,
            level,
            sobol_base: c.sobol_base,
        }),
        ..ImpactRequest::default()
    };
    let outcome = py
        .detach(|| bumpsim_engine::impact(car.kind(), &request))
        .map_err(engine)?;
    PlanarImpact::of(outcome)
}

/// The result of a planar impact, with the fields of `bumpsim planar --json`:
/// the engine's outcome and its JSON document.
#[pyclass(frozen, module = "bumpsim")]
pub struct PlanarImpact {
    data: Outcome,
    document: Value,
}

impl PlanarImpact {
    fn of(data: Outcome) -> PyResult<Self> {
        let document = serde_json::from_str(&data.json).map_err(input)?;
        Ok(PlanarImpact { data, document })
    }

    /// The prediction and the Sobol indices of the document, when asked.
    fn predicted(&self) -> Option<Predicted> {
        let prediction = self.document.get("prediction")?.clone();
        let sensitivity = self.document.get("sensitivity").cloned();
        Some(Predicted {
            prediction,
            sensitivity,
        })
    }

    /// A number of the document's `result`.
    fn number(&self, name: &str) -> f64 {
        self.document["result"][name].as_f64().unwrap_or(f64::NAN)
    }
}

#[pymethods]
impl PlanarImpact {
    /// The result (peak and side-member forces, crush per segment, yaw,
    /// balances, histories) as the JSON's `result`.
    #[getter]
    fn result<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.document["result"])
    }
    /// Warnings about the result.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.data.warnings.clone()
    }
    /// The summary `bumpsim planar` prints.
    fn summary(&self) -> String {
        self.data.text.clone()
    }
    /// The result as `bumpsim planar --json` writes it (with `prediction`
    /// and `sensitivity` when asked).
    fn to_json(&self) -> String {
        self.data.json.clone()
    }
    /// The prediction over the car's uncertainty, the JSON's `prediction`
    /// (None without `uncertainty`).
    #[getter]
    fn prediction<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        Predicted::prediction(py, &self.predicted())
    }
    /// The Sobol indices, the JSON's `sensitivity` (None without `sobol`).
    #[getter]
    fn sensitivity<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        Predicted::sensitivity(py, &self.predicted())
    }
    /// The histories' bands over the draws: name → dict of arrays `time`
    /// [s], `nominal`, `low`, `median`, `high` (None without `uncertainty`).
    #[getter]
    fn bands<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        Predicted::bands(py, &self.predicted())
    }
    /// The prediction's spreads as a table: index `output`; columns `unit`,
    /// `nominal`, `median`, `low`, `high`, `mean`, `sd`; attrs: sampling,
    /// failed draws (None without `uncertainty`).
    fn prediction_to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        Predicted::frame(py, &self.predicted())
    }
    /// The histories as `bumpsim planar --csv` writes them: index `time
    /// [s]`, columns `force x [N]`, ..., `crush segment N [m]`; attrs: car,
    /// peak force, warnings.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let attrs = PyDict::new(py);
        attrs.set_item("car", from_json(py, &self.document["car"])?)?;
        attrs.set_item("peak_force [N]", self.number("peak_force"))?;
        attrs.set_item("max_compression [m]", self.number("max_compression"))?;
        attrs.set_item("warnings", &self.data.warnings)?;
        frames::csv(py, &self.data.csv, &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.data == other.data
    }
    /// Pickles as the request's outcome.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        reduce(slf.as_any(), &encode(&slf.get().data)?)
    }
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        PlanarImpact::of(decode(state, "PlanarImpact")?)
    }
    fn __repr__(&self) -> String {
        format!(
            "PlanarImpact({:?}, peak_force={} N, max_compression={} m, peak_yaw_rate={} rad/s)",
            self.document["car"].as_str().unwrap_or("?"),
            self.number("peak_force"),
            self.number("max_compression"),
            self.number("peak_yaw_rate")
        )
    }
}
