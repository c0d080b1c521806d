//! FE decks (bumpsim-export), the calls `bumpsim export lsdyna|calculix`
//! make: the layout and options from the arguments, the deck as text (the
//! caller writes it where it wants; `bumpsim_io::output::write_file` is the
//! CLI's part).

use crate::arrays::vector;
use crate::convert::{count, ids, whole};
use crate::errors::{input, invalid, message};
use crate::model::car_of;
use bumpsim_core::series::UniformSeries;
use bumpsim_export::calculix::{Analysis, CalculixOptions, DEFAULT_PREFIX, calculix_deck};
use bumpsim_export::layout::{Axis, Layout, UnitSystem};
use bumpsim_export::lsdyna::{LsDynaOptions, lsdyna_include};
use bumpsim_io::car::Car;
use pyo3::prelude::*;

/// Registers the functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(lsdyna_deck, m)?)?;
    m.add_function(wrap_pyfunction!(calculix, m)?)?;
    m.add_function(wrap_pyfunction!(critical_time_step, m)?)?;
    Ok(())
}

fn layout(units: &str, axis: &str, origin: [f64; 3], spacing: f64) -> PyResult<Layout> {
    let units: UnitSystem = units
        .parse()
        .map_err(|e| invalid(format!("units: {}", message(&e))))?;
    let axis: Axis = axis
        .parse()
        .map_err(|e| invalid(format!("axis: {}", message(&e))))?;
    if spacing <= 0.0 {
        return Err(invalid(format!(
            "spacing {spacing} m: the distance between mass nodes must be positive"
        )));
    }
    Ok(Layout {
        units,
        axis,
        origin,
        spacing,
    })
}

/// The critical explicit time step of the car alone, s (what limits an
/// LS-DYNA run's step; `bumpsim export lsdyna` prints it).
#[pyfunction]
fn critical_time_step(py: Python<'_>, car: &Bound<'_, PyAny>) -> PyResult<f64> {
    let car = car_of(py, car)?;
    Ok(bumpsim_export::timestep::critical_time_step(&car.model))
}

fn title(car: &Car, title: Option<String>) -> String {
    title.unwrap_or_else(|| car.name.clone().unwrap_or_else(|| "MSD car model".into()))
}

/// The id offset (default 0) and attached nodes (default none): whole numbers.
fn numbering(
    id_offset: Option<&Bound<'_, PyAny>>,
    attach: Option<&Bound<'_, PyAny>>,
) -> PyResult<(u64, Vec<u64>)> {
    let offset = id_offset.map_or(Ok(0), |n| whole(n, "id_offset", 0, u64::MAX))?;
    let attach = attach.map_or(Ok(Vec::new()), |a| ids(a, "attach"))?;
    Ok((offset, attach))
}

/// A force history from optional times and values: both or neither.
fn force_history(
    time: Option<&Bound<'_, PyAny>>,
    force: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<UniformSeries>> {
    match (time, force) {
        (Some(time), Some(force)) => {
            UniformSeries::from_times(&vector(time, "time")?, vector(force, "force")?)
                .map(Some)
                .map_err(input)
        }
        (None, None) => Ok(None),
        _ => Err(invalid(
            "time and force go together: give both for a force history, or neither",
        )),
    }
}

/// The LS-DYNA keyword include of `car` (as `bumpsim export lsdyna`):
/// masses, discrete springs and dampers, rigid coupling to `attach` nodes;
/// with `time` (s, uniform) and `force` (N on m1) a load curve, with
/// `output_interval` (s) history outputs, `standalone` a complete run.
#[pyfunction]
#[pyo3(signature = (car, units = "si", axis = "+x", origin = [0.0, 0.0, 0.0], spacing = 0.1, id_offset = None, attach = None, initial_velocity = None, title = None, time = None, force = None, output_interval = None, standalone = false))]
// one Rust argument per Python keyword argument
#[allow(clippy::too_many_arguments)]
fn lsdyna_deck(
    py: Python<'_>,
    car: &Bound<'_, PyAny>,
    units: &str,
    axis: &str,
    origin: [f64; 3],
    spacing: f64,
    id_offset: Option<&Bound<'_, PyAny>>,
    attach: Option<&Bound<'_, PyAny>>,
    initial_velocity: Option<f64>,
    title: Option<String>,
    time: Option<&Bound<'_, PyAny>>,
    force: Option<&Bound<'_, PyAny>>,
    output_interval: Option<f64>,
    standalone: bool,
) -> PyResult<String> {
    let car = &car_of(py, car)?;
    let (id_offset, attach) = numbering(id_offset, attach)?;
    let options = LsDynaOptions {
        layout: layout(units, axis, origin, spacing)?,
        id_offset,
        attach,
        initial_velocity,
        title: self::title(car, title),
        force: force_history(time, force)?,
        output_interval,
        standalone,
    };
    lsdyna_include(&car.model, &options).map_err(input)
}

/// The CalculiX/Abaqus deck of `car` (as `bumpsim export calculix`); with
/// `time` (s, uniform) and `force` (N on m1), a complete transient analysis.
#[pyfunction]
#[pyo3(signature = (car, time = None, force = None, units = "si", axis = "+x", origin = [0.0, 0.0, 0.0], spacing = 0.1, increment = None, output_every = None, initial_velocity = None, title = None, id_offset = None, prefix = DEFAULT_PREFIX.to_string(), attach = None))]
// one Rust argument per Python keyword argument
#[allow(clippy::too_many_arguments)]
fn calculix(
    py: Python<'_>,
    car: &Bound<'_, PyAny>,
    time: Option<&Bound<'_, PyAny>>,
    force: Option<&Bound<'_, PyAny>>,
    units: &str,
    axis: &str,
    origin: [f64; 3],
    spacing: f64,
    increment: Option<f64>,
    output_every: Option<&Bound<'_, PyAny>>,
    initial_velocity: Option<f64>,
    title: Option<String>,
    id_offset: Option<&Bound<'_, PyAny>>,
    prefix: String,
    attach: Option<&Bound<'_, PyAny>>,
) -> PyResult<String> {
    let car = &car_of(py, car)?;
    let (id_offset, attach) = numbering(id_offset, attach)?;
    let output_every = output_every.map_or(Ok(1), |n| count(n, "output_every", 1, usize::MAX))?;
    let analysis = force_history(time, force)?.map(|force| Analysis {
        force,
        increment,
        output_every,
    });
    let options = CalculixOptions {
        layout: layout(units, axis, origin, spacing)?,
        initial_velocity,
        analysis,
        title: self::title(car, title),
        id_offset,
        prefix,
        attach,
    };
    calculix_deck(&car.model, &options).map_err(input)
}
