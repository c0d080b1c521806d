//! FE decks (bumpsim-export), the calls `bumpsim export lsdyna|calculix`
//! make: the layout and options from the arguments, the deck as text (the
//! caller writes it where it wants; `bumpsim_io::output::write_file` is the
//! CLI's part).

use crate::arrays::vector;
use crate::errors::{InputError, input, message};
use crate::model::Car;
use bumpsim_core::series::UniformSeries;
use bumpsim_export::calculix::{Analysis, CalculixOptions, calculix_deck};
use bumpsim_export::layout::{Axis, Layout, UnitSystem};
use bumpsim_export::lsdyna::{LsDynaOptions, lsdyna_include};
use pyo3::prelude::*;

/// Registers the functions of this module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(lsdyna_deck, m)?)?;
    m.add_function(wrap_pyfunction!(calculix, m)?)?;
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

fn title(car: &Car, title: Option<String>) -> String {
    title.unwrap_or_else(|| {
        car.inner
            .name
            .clone()
            .unwrap_or_else(|| "MSD car model".into())
    })
}

/// The LS-DYNA keyword include of `car` (as `bumpsim export lsdyna`):
/// masses, discrete springs and dampers, rigid coupling to `attach` nodes.
#[pyfunction]
#[pyo3(signature = (car, units = "si", axis = "+x", origin = [0.0, 0.0, 0.0], spacing = 0.1, id_offset = 0, attach = Vec::new(), initial_velocity = None, title = None))]
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
) -> PyResult<String> {
    let options = LsDynaOptions {
        layout: layout(units, axis, origin, spacing)?,
        id_offset,
        attach,
        initial_velocity,
        title: self::title(car, title),
    };
    lsdyna_include(&car.inner.model, &options).map_err(input)
}

/// The CalculiX/Abaqus deck of `car` (as `bumpsim export calculix`); with
/// `time` (s, uniform) and `force` (N on m1), a complete transient analysis.
#[pyfunction]
#[pyo3(signature = (car, time = None, force = None, units = "si", axis = "+x", origin = [0.0, 0.0, 0.0], spacing = 0.1, increment = None, output_every = 1, initial_velocity = None, title = None))]
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
) -> PyResult<String> {
    let analysis = match (time, force) {
        (Some(time), Some(force)) => Some(Analysis {
            force: UniformSeries::from_times(&vector(time, "time")?, vector(force, "force")?)
                .map_err(input)?,
            increment,
            output_every,
        }),
        (None, None) => None,
        _ => {
            return Err(InputError::new_err(
                "time and force go together: give both for an analysis, or neither",
            ));
        }
    };
    let options = CalculixOptions {
        layout: layout(units, axis, origin, spacing)?,
        initial_velocity,
        analysis,
        title: self::title(car, title),
    };
    calculix_deck(&car.inner.model, &options).map_err(input)
}
