//! Stiffness of a quasi-static force–displacement curve (paper C, spec §7):
//! the slope of the least-squares line through the points of the fit range.
//! Default range: the points whose force lies between 10 % and 90 % of the
//! largest force (leaving out the settling start and any yield at the top).

use serde::Serialize;

/// The linearised stiffness.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Stiffness {
    /// Slope, N/m.
    pub slope: f64,
    /// Force at zero displacement of the line, N.
    pub intercept: f64,
    /// Fit range in displacement, m.
    pub range: [f64; 2],
    /// Points used.
    pub points: usize,
    /// Root-mean-square residual of the line, N.
    pub residual_rms: f64,
    /// R² of the line.
    pub r2: f64,
}

/// Why no stiffness can be given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("stiffness: {0}")]
pub struct StiffnessError(pub String);

/// Fits the line over `range` (displacement, m) or the default force range.
pub fn stiffness(
    displacement: &[f64],
    force: &[f64],
    range: Option<[f64; 2]>,
) -> Result<Stiffness, StiffnessError> {
    let peak = force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    let inside: Vec<usize> = (0..displacement.len().min(force.len()))
        .filter(|&i| match range {
            Some([a, b]) => displacement[i] >= a && displacement[i] <= b,
            None => force[i].abs() >= 0.1 * peak && force[i].abs() <= 0.9 * peak,
        })
        .collect();
    if inside.len() < 3 {
        return Err(StiffnessError(format!(
            "{} points in the fit range; need at least 3",
            inside.len()
        )));
    }
    let n = inside.len() as f64;
    let (mx, my) = (
        inside.iter().map(|&i| displacement[i]).sum::<f64>() / n,
        inside.iter().map(|&i| force[i]).sum::<f64>() / n,
    );
    let sxx: f64 = inside.iter().map(|&i| (displacement[i] - mx).powi(2)).sum();
    let sxy: f64 = inside
        .iter()
        .map(|&i| (displacement[i] - mx) * (force[i] - my))
        .sum();
    if sxx <= 0.0 {
        return Err(StiffnessError(
            "the displacement does not vary in the fit range".into(),
        ));
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let ss_res: f64 = inside
        .iter()
        .map(|&i| (force[i] - intercept - slope * displacement[i]).powi(2))
        .sum();
    let ss_tot: f64 = inside.iter().map(|&i| (force[i] - my).powi(2)).sum();
    let lo = inside
        .iter()
        .map(|&i| displacement[i])
        .fold(f64::INFINITY, f64::min);
    let hi = inside
        .iter()
        .map(|&i| displacement[i])
        .fold(f64::NEG_INFINITY, f64::max);
    Ok(Stiffness {
        slope,
        intercept,
        range: [lo, hi],
        points: inside.len(),
        residual_rms: (ss_res / n).sqrt(),
        r2: 1.0 - ss_res / ss_tot,
    })
}
