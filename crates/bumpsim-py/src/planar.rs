//! The planar car (bumpsim-planar), the calls `bumpsim planar` makes:
//! a preset or an angled/offset barrier, pendulum or pole striker, the
//! library's simulation, the result with the JSON's fields.

use crate::errors::{InputError, file_or_input, input};
use crate::ident::from_json;
use bumpsim_planar::presets::StrikerSpec;
use bumpsim_planar::{PlanarCar as CorePlanarCar, PlanarResult, Settings, Side, Striker, simulate};
use pyo3::prelude::*;
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

#[pymethods]
impl PlanarCar {
    /// Reads a planar car file (TOML, docs/planar.md).
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let inner = CorePlanarCar::read(&path).map_err(file_or_input)?;
        Ok(PlanarCar { inner, path })
    }
    /// The name from the file, or None.
    #[getter]
    fn name(&self) -> Option<String> {
        self.inner.name().map(str::to_string)
    }
}

/// An angled, offset, corner or pole impact of the planar car, as
/// `bumpsim planar`: a preset `case`, or a barrier (or a `pendulum` of that
/// mass, kg) at `angle` degrees with `overlap` % from `side`, or a pole of
/// diameter `pole` m at `pole_offset` m; `speed` m/s.
#[pyfunction]
#[pyo3(signature = (car, case = None, angle = None, overlap = None, side = "left", pole = None, pole_offset = 0.0, pendulum = None, speed = None))]
// one Rust argument per Python keyword argument
#[allow(clippy::too_many_arguments)]
fn planar_impact(
    py: Python<'_>,
    car: &PlanarCar,
    case: Option<&str>,
    angle: Option<f64>,
    overlap: Option<f64>,
    side: &str,
    pole: Option<f64>,
    pole_offset: f64,
    pendulum: Option<f64>,
    speed: Option<f64>,
) -> PyResult<PlanarImpact> {
    let side: Side = side
        .parse()
        .map_err(|e: bumpsim_planar::striker::SideError| {
            InputError::new_err(format!("side: {e}"))
        })?;
    let spec = StrikerSpec {
        case: case.map(str::to_string),
        angle,
        overlap,
        side: Some(side),
        pole,
        pole_offset: Some(pole_offset),
        pendulum,
        speed,
    };
    let (striker, _) = spec.striker().map_err(input)?;
    let result = py
        .detach(|| simulate(&car.inner, &striker, &Settings::default()))
        .map_err(input)?;
    let name = car
        .inner
        .name()
        .map_or_else(|| car.path.display().to_string(), str::to_string);
    Ok(PlanarImpact {
        name,
        striker,
        result,
    })
}

/// The result of a planar impact, with the fields of `bumpsim planar --json`.
#[pyclass(frozen, module = "bumpsim")]
pub struct PlanarImpact {
    name: String,
    striker: Striker,
    result: PlanarResult,
}

#[pymethods]
impl PlanarImpact {
    /// The result (peak and side-member forces, crush per segment, yaw,
    /// balances, histories) as the JSON's `result`.
    #[getter]
    fn result<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.result)
    }
    /// Warnings about the result.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.result.warnings.clone()
    }
    /// The summary `bumpsim planar` prints.
    fn summary(&self) -> String {
        bumpsim_planar::text::summary(&self.result)
    }
    /// The result as `bumpsim planar --json` writes it.
    fn to_json(&self) -> PyResult<String> {
        let document = bumpsim_planar::document::ImpactDocument {
            car: &self.name,
            striker: &self.striker,
            result: &self.result,
        };
        serde_json::to_string_pretty(&document).map_err(input)
    }
}
