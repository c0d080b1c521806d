//! The planar car (bumpsim-planar), the calls `bumpsim planar` makes:
//! a preset or an angled/offset barrier, pendulum or pole striker, the
//! library's simulation, the result with the JSON's fields. A function that
//! takes a planar car takes a `PlanarCar` or the path of its file.

use crate::convert::from_json;
use crate::errors::{input, invalid, reading};
use crate::frames;
use crate::impact::Predictable;
use crate::state::planar::{PlanarImpactState, StrikerArgs};
use crate::state::{decode, encode, reduce};
use crate::uncertain::{Arguments, Predicted, Uncertain};
use bumpsim_planar::presets::{PlanarPreset, StrikerSpec, prepared};
use bumpsim_planar::uncertainty::Planar;
use bumpsim_planar::{PlanarCar as CorePlanarCar, Settings, Side, Striker, simulate};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple, PyType};
use std::path::PathBuf;

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
    inner: CorePlanarCar,
    path: PathBuf,
}

/// The planar car of an argument: a `PlanarCar`, or the path of its file.
pub(crate) fn planar_car_of(value: &Bound<'_, PyAny>) -> PyResult<(CorePlanarCar, PathBuf)> {
    if let Ok(car) = value.cast::<PlanarCar>() {
        let car = car.get();
        return Ok((car.inner.clone(), car.path.clone()));
    }
    let path = crate::convert::path(value, "car", "a bumpsim.PlanarCar")?;
    let car = CorePlanarCar::read(&path).map_err(|e| reading(&path, e))?;
    Ok((car, path))
}

#[pymethods]
impl PlanarCar {
    /// Reads a planar car file (TOML, docs/planar.md).
    #[staticmethod]
    fn from_file(path: &Bound<'_, PyAny>) -> PyResult<Self> {
        let (inner, path) = planar_car_of(path)?;
        Ok(PlanarCar { inner, path })
    }
    /// The name from the file, or None.
    #[getter]
    fn name(&self) -> Option<String> {
        self.inner.name().map(str::to_string)
    }
    /// The file it was read from.
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }
    /// The car as a planar car file (SI lengths), which reads back to the same car.
    fn to_toml(&self) -> String {
        self.inner.to_toml()
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner && self.path == other.path
    }
    /// Pickles as its file text and path.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let car = slf.get();
        let restore = slf.get_type().getattr("_from_toml")?;
        let args = (car.inner.to_toml(), car.path.clone()).into_pyobject(slf.py())?;
        Ok((restore, args))
    }
    /// The car from its file text (`to_toml`) and the path it names.
    #[classmethod]
    fn _from_toml(_cls: &Bound<'_, PyType>, text: &str, path: PathBuf) -> PyResult<Self> {
        let inner = CorePlanarCar::parse(text, &path).map_err(input)?;
        Ok(PlanarCar { inner, path })
    }
    fn __repr__(&self) -> String {
        format!(
            "PlanarCar({:?} from {:?})",
            self.inner.name().unwrap_or("unnamed"),
            self.path
        )
    }
}

impl StrikerArgs {
    /// The striker these arguments ask for and its preset (bumpsim-planar's presets).
    fn striker(&self) -> PyResult<(Striker, Option<&'static PlanarPreset>)> {
        let side: Side = self
            .side
            .parse()
            .map_err(|e: bumpsim_planar::striker::SideError| invalid(format!("side: {e}")))?;
        let spec = StrikerSpec {
            case: self.case.clone(),
            angle: self.angle,
            overlap: self.overlap,
            side: Some(side),
            pole: self.pole,
            pole_offset: Some(self.pole_offset),
            pendulum: self.pendulum,
            speed: self.speed,
            car_mass: self.car_mass,
        };
        spec.striker().map_err(input)
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
    let (car, path) = planar_car_of(car)?;
    let spec = StrikerArgs {
        case,
        angle,
        overlap,
        side: side.to_string(),
        pole,
        pole_offset,
        pendulum,
        speed,
        car_mass: Some(car.total_mass()),
    };
    let (striker, preset) = spec.striker()?;
    // a preset runs with the tyres its protocol prescribes, as in the CLI
    let car = prepared(&car, preset);
    let arguments = Arguments {
        path: uncertainty,
        samples,
        seed,
        level,
        sobol,
        sobol_base,
    };
    let uncertain = Uncertain::<Planar>::read(&arguments, &car)?;
    let settings = Settings::default();
    let result = py
        .detach(|| simulate(&car, &striker, &settings))
        .map_err(input)?;
    let run = |c: &CorePlanarCar| simulate(c, &striker, &settings).ok();
    let predicted = uncertain
        .map(|u| u.run(py, &car, &result, &run))
        .transpose()?;
    let name = car
        .name()
        .map_or_else(|| path.display().to_string(), str::to_string);
    Ok(PlanarImpact {
        striker,
        data: PlanarImpactState {
            name,
            spec,
            result,
            body: Some(*car.body()),
        },
        predicted,
    })
}

/// The result of a planar impact, with the fields of `bumpsim planar --json`.
#[pyclass(frozen, module = "bumpsim")]
pub struct PlanarImpact {
    data: PlanarImpactState,
    striker: Striker,
    predicted: Option<Predicted>,
}

#[pymethods]
impl PlanarImpact {
    /// The result (peak and side-member forces, crush per segment, yaw,
    /// balances, histories) as the JSON's `result`.
    #[getter]
    fn result<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.data.result)
    }
    /// Warnings about the result.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.data.result.warnings.clone()
    }
    /// The summary `bumpsim planar` prints.
    fn summary(&self) -> String {
        bumpsim_planar::text::summary(&self.data.result)
    }
    /// The result as `bumpsim planar --json` writes it (with `prediction`
    /// and `sensitivity` when asked).
    fn to_json(&self) -> PyResult<String> {
        let document = bumpsim_planar::document::ImpactDocument {
            car: &self.data.name,
            striker: &self.striker,
            result: &self.data.result,
            body: self.data.body.as_ref(),
        };
        Predicted::with(&self.predicted, document)
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
    /// The histories as `bumpsim planar --csv` writes them: index `time
    /// [s]`, columns `force x [N]`, ..., `crush segment N [m]`; attrs: car,
    /// peak force, warnings.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let r = &self.data.result;
        let attrs = PyDict::new(py);
        attrs.set_item("car", &self.data.name)?;
        attrs.set_item("peak_force [N]", r.peak_force)?;
        attrs.set_item("max_compression [m]", r.max_compression)?;
        attrs.set_item("warnings", &r.warnings)?;
        frames::csv(py, &bumpsim_planar::text::histories(r), &attrs)
    }
    fn __eq__(&self, other: &Self) -> bool {
        self.data == other.data && self.predicted == other.predicted
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
        let data: PlanarImpactState = decode(state, "PlanarImpact")?;
        Ok(PlanarImpact {
            striker: data.spec.striker()?.0,
            data,
            predicted: Predicted::of_state(predicted)?,
        })
    }
    fn __repr__(&self) -> String {
        let r = &self.data.result;
        format!(
            "PlanarImpact({:?}, peak_force={} N, max_compression={} m, peak_yaw_rate={} rad/s)",
            self.data.name, r.peak_force, r.max_compression, r.peak_yaw_rate
        )
    }
}
