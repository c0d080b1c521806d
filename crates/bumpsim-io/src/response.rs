//! Writing a simulation response as CSV (docs/formats.md).
//!
//! Columns, all SI with `name [unit]` headers: `time [s]`, `force [N]`, then
//! per mass i `x{i} [m]`, `v{i} [m/s]`, `a{i} [m/s^2]`, per link j
//! `spring{j} [N]` and `damper{j} [N]` (positive in compression), and the
//! energies `kinetic_energy`, `spring_energy`, `dissipated_energy`, `work`
//! (J; the last two summed from the first sample). The file reads back with
//! [`crate::table::Table`].

use crate::table::{OutputColumn, TableError, write_table};
use bumpsim_core::simulate::Response;
use bumpsim_core::units::{Dimension, Unit};
use std::path::Path;

/// Column names and values of a response, in file order (time excluded).
pub fn response_columns(response: &Response) -> Vec<(String, Dimension, &[f64])> {
    let mut columns: Vec<(String, Dimension, &[f64])> =
        vec![("force".into(), Dimension::Force, &response.force)];
    let per_mass = [
        ("x", Dimension::Length, &response.displacement),
        ("v", Dimension::Velocity, &response.velocity),
        ("a", Dimension::Acceleration, &response.acceleration),
        ("spring", Dimension::Force, &response.spring_force),
        ("damper", Dimension::Force, &response.damper_force),
    ];
    for (prefix, dimension, series) in per_mass {
        for (i, values) in series.iter().enumerate() {
            columns.push((format!("{prefix}{}", i + 1), dimension, values));
        }
    }
    let e = &response.energy;
    for (name, values) in [
        ("kinetic_energy", &e.kinetic),
        ("spring_energy", &e.spring),
        ("dissipated_energy", &e.dissipated),
        ("work", &e.work),
    ] {
        columns.push((name.into(), Dimension::Energy, values));
    }
    columns
}

/// Writes a response as CSV.
pub fn write_response(path: &Path, response: &Response) -> Result<usize, TableError> {
    let columns = response_columns(response);
    let output: Vec<OutputColumn<'_>> = columns
        .iter()
        .map(|(name, dimension, values)| OutputColumn {
            name,
            unit: Unit::si(*dimension),
            values,
        })
        .collect();
    write_table(path, &response.time, &output)?;
    Ok(output.len() + 1)
}
