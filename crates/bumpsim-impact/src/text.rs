//! Human-readable and CSV text of impact results (terminal and reports
//! share it): the summary with units, the time histories, sweep grids.

use crate::impact::ImpactResult;
use crate::reduction::Grid;
use bumpsim_core::units::{Dimension, format_quantity};

/// The summary: peak force, compressions, contact time, energies.
pub fn summary(r: &ImpactResult) -> String {
    format!(
        "  peak force {}\n  maximum compression {}, remaining {}\n  contact time {}\n  absorbed by the bumper {}; relative energy balance error {:.2e} of the initial energy\n",
        format_quantity(r.peak_force, Dimension::Force),
        format_quantity(r.max_compression, Dimension::Length),
        remaining(r.remaining_compression),
        format_quantity(r.contact_time, Dimension::Time),
        format_quantity(r.absorbed_energy, Dimension::Energy),
        r.energy.relative_error
    )
}

/// The remaining compression in words: a negative one is no permanent
/// crush but the bumper's front springing past its unloaded position (an
/// FE mesh still vibrating at the end), said so instead of "-0.07 mm".
fn remaining(compression: f64) -> String {
    if compression < 0.0 {
        format!(
            "0 mm (the bumper springs back fully; at the end its front is {} beyond its unloaded position)",
            format_quantity(-compression, Dimension::Length)
        )
    } else {
        format_quantity(compression, Dimension::Length)
    }
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

#[cfg(test)]
mod tests {
    use super::remaining;

    #[test]
    fn a_negative_remaining_compression_is_a_spring_back_not_a_crush() {
        assert_eq!(remaining(2.5e-3), "2.500 mm");
        let text = remaining(-7.127e-5);
        assert!(
            text.starts_with("0 mm (the bumper springs back fully")
                && text.contains("0.07127 mm beyond"),
            "{text}"
        );
    }
}
