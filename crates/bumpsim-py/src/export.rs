//! FE decks (bumpsim-export), the calls `bumpsim export lsdyna|calculix`
//! make: the layout and options from the arguments, the deck as text (the
//! caller writes it where it wants; `bumpsim_io::output::write_file` is the
//! CLI's part).

use crate::arrays::vector;
use crate::errors::{InputError, input, message};
use crate::model::Car;
use bumpsim_core::series::UniformSeries;
use bumpsim_export::calculix::{Analysis, CalculixOptions, DEFAULT_PREFIX, calculix_deck};
use bumpsim_export::layout::{Axis, Layout, UnitSystem};
use bumpsim_export::lsdyna::{LsDynaOptions, lsdyna_include};
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
        .map_err(|e| InputError::new_err(format!("units: {}", message(&e))))?;
    let axis: Axis = axis
        .parse()
        .map_err(|e| InputError::new_err(format!("axis: {}", message(&e))))?;
    if spacing <= 0.0 {
        return Err(InputError::new_err(format!(
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
fn critical_time_step(car: &Car) -> f64 {
    bumpsim_export::timestep::critical_time_step(&car.inner.model)
}

fn title(car: &Car, title: Option<String>) -> String {
    title.unwrap_or_else(|| {
        car.inner
            .name
            .clone()
            .unwrap_or_else(|| "MSD car model".into())
    })
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
        _ => Err(InputError::new_err(
            "time and force go together: give both for a force history, or neither",
        )),
    }
}

/// The LS-DYNA keyword include of `car` (as `bumpsim export lsdyna`):
/// masses, discrete springs and dampers, rigid coupling to `attach` nodes;
/// with `time` (s, uniform) and `force` (N on m1) a load curve, with
/// `output_interval` (s) history outputs, `standalone` a complete run.
#[pyfunction]
#[pyo3(signature = (car, units = "si", axis = "+x", origin = [0.0, 0.0, 0.0], spacing = 0.1, id_offset = 0, attach = Vec::new(), initial_velocity = None, title = None, time = None, force = None, output_interval = None, standalone = false))]
// one Rust argument per Python keyword argument
#[allow(clippy::too_many_arguments)]
fn lsdyna_deck(
    car: &Car,
    units: &str,
    axis: &str,
    origin: [f64; 3],
    spacing: f64,
    id_offset: u64,
    attach: Vec<u64>,
    initial_velocity: Option<f64>,
    title: Option<String>,
    time: Option<&Bound<'_, PyAny>>,
    force: Option<&Bound<'_, PyAny>>,
    output_interval: Option<f64>,
    standalone: bool,
) -> PyResult<String> {
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
    lsdyna_include(&car.inner.model, &options).map_err(input)
}

/// The CalculiX/Abaqus deck of `car` (as `bumpsim export calculix`); with
/// `time` (s, uniform) and `force` (N on m1), a complete transient analysis.
#[pyfunction]
#[pyo3(signature = (car, time = None, force = None, units = "si", axis = "+x", origin = [0.0, 0.0, 0.0], spacing = 0.1, increment = None, output_every = 1, initial_velocity = None, title = None, id_offset = 0, prefix = DEFAULT_PREFIX.to_string(), attach = Vec::new()))]
// one Rust argument per Python keyword argument
#[allow(clippy::too_many_arguments)]
fn calculix(
    car: &Car,
    time: Option<&Bound<'_, PyAny>>,
    force: Option<&Bound<'_, PyAny>>,
    units: &str,
    axis: &str,
    origin: [f64; 3],
    spacing: f64,
    increment: Option<f64>,
    output_every: usize,
    initial_velocity: Option<f64>,
    title: Option<String>,
    id_offset: u64,
    prefix: String,
    attach: Vec<u64>,
) -> PyResult<String> {
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
    calculix_deck(&car.inner.model, &options).map_err(input)
}
