//! Human-readable and CSV text of impact results (terminal and reports
//! share it): the summary with units, the time histories, sweep grids.

use crate::impact::ImpactResult;
use crate::reduction::Grid;
use bumpsim_core::units::{Dimension, format_quantity};

/// The summary: peak force, compressions, contact time, energies.
pub fn summary(r: &ImpactResult) -> String {
    format!(
        "  peak force {}\n  maximum compression {}, remaining {}\n  contact time {}\n  absorbed by the bumper {}; energy balance error {:.2e}\n",
        format_quantity(r.peak_force, Dimension::Force),
        format_quantity(r.max_compression, Dimension::Length),
        format_quantity(r.remaining_compression, Dimension::Length),
        format_quantity(r.contact_time, Dimension::Time),
        format_quantity(r.absorbed_energy, Dimension::Energy),
        r.energy.relative_error
    )
}

/// The time histories as CSV (SI).
pub fn histories(r: &ImpactResult) -> String {
    let mut csv = String::from("time [s],force [N],compression [m]");
    for b in &r.bodies {
        csv += &format!(",x {b} [m],v {b} [m/s]");
    }
    csv.push('\n');
    for k in 0..r.time.len() {
        csv += &format!("{},{},{}", r.time[k], r.force[k], r.compression[k]);
        for (x, v) in r.displacements.iter().zip(&r.velocities) {
            csv += &format!(",{},{}", x[k], v[k]);
        }
        csv.push('\n');
    }
    csv
}

/// A sweep grid as CSV: x, y, scale factor (empty without an answer).
pub fn grid_csv(grid: &Grid) -> String {
    let mut csv = format!("{},{},scale factor [-]\n", grid.x_label, grid.y_label);
    for (i, x) in grid.x.iter().enumerate() {
        for (j, y) in grid.y.iter().enumerate() {
            let value = grid.values[i][j].map_or(String::new(), |v| v.to_string());
            csv += &format!("{x},{y},{value}\n");
        }
    }
    csv
}
