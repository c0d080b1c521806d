//! Stiffness of a quasi-static force–displacement curve (paper C, spec §7):
//! the slope of the least-squares line through the points of the fit range.
//! Default range: the points whose force lies between 10 % and 90 % of the
//! largest force (leaving out the settling start and any yield at the top).

use crate::data::Data;
use bumpsim_core::units::{Dimension, Unit, UnitError};
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
    /// R² of the line; `None` when the force does not vary over the fit
    /// range (R² = 1 − SS_res/SS_tot is 0/0: undefined, not a perfect fit).
    pub r2: Option<f64>,
}

/// Why no stiffness can be given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("stiffness: {0}")]
pub struct StiffnessError(pub String);

/// Why a table is not a force–displacement curve.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CurveError {
    /// Fewer than two columns.
    #[error("expected a displacement and a force column")]
    Columns,
    /// A column without a `[unit]`.
    #[error("column '{column}' needs a unit, e.g. '{column} [mm]'")]
    NoUnit {
        /// Column name.
        column: String,
    },
    /// A unit that does not parse.
    #[error("column '{column}'")]
    Unit {
        /// Column name.
        column: String,
        /// The reason.
        source: UnitError,
    },
    /// A unit of the wrong dimension.
    #[error("column '{column}' is in {unit}, expected a {expected}")]
    Dimension {
        /// Column name.
        column: String,
        /// The unit as written.
        unit: String,
        /// The dimension needed.
        expected: &'static str,
    },
}

/// A force–displacement curve in SI, with the displacement unit of its file.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Displacements, m.
    pub displacement: Vec<f64>,
    /// Forces, N.
    pub force: Vec<f64>,
    /// The unit the file gave displacements in.
    pub displacement_unit: Unit,
}

impl Curve {
    /// The curve from a table's first two columns: displacement (a length
    /// unit) and force (a force unit), converted to SI.
    pub fn from_table(data: &Data) -> Result<Curve, CurveError> {
        if data.names.len() < 2 {
            return Err(CurveError::Columns);
        }
        let unit_of = |i: usize, dimension: Dimension| -> Result<Unit, CurveError> {
            let column = data.names[i].clone();
            let Some(text) = data.units[i].clone() else {
                return Err(CurveError::NoUnit { column });
            };
            let unit = Unit::parse(&text).map_err(|source| CurveError::Unit {
                column: column.clone(),
                source,
            })?;
            if unit.dimension != dimension {
                let expected = dimension.name();
                return Err(CurveError::Dimension {
                    column,
                    unit: text,
                    expected,
                });
            }
            Ok(unit)
        };
        let (ud, uf) = (
            unit_of(0, Dimension::Length)?,
            unit_of(1, Dimension::Force)?,
        );
        Ok(Curve {
            displacement: data.rows.iter().map(|r| ud.to_si(r[0])).collect(),
            force: data.rows.iter().map(|r| uf.to_si(r[1])).collect(),
            displacement_unit: ud,
        })
    }

    /// The stiffness over `range` given in the file's displacement unit
    /// (default: 10–90 % of the peak force).
    /// A range that is not two finite numbers D0 < D1 is refused as such.
    pub fn stiffness(&self, range: Option<[f64; 2]>) -> Result<Stiffness, StiffnessError> {
        if let Some([d0, d1]) = range
            && !(d0.is_finite() && d1.is_finite() && d0 < d1)
        {
            return Err(StiffnessError(format!(
                "fit range {d0} to {d1} {}: expected finite D0 < D1",
                self.displacement_unit.symbol
            )));
        }
        let si = range.map(|r| r.map(|d| self.displacement_unit.to_si(d)));
        stiffness(&self.displacement, &self.force, si)
    }
}

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
    if let Some(v) = inside
        .iter()
        .flat_map(|&i| [displacement[i], force[i]])
        .find(|v| !v.is_finite())
    {
        return Err(StiffnessError(format!(
            "a value of {v} in the fit range: displacement and force must be finite"
        )));
    }
    let scale = inside
        .iter()
        .fold(0.0_f64, |m, &i| m.max(displacement[i].abs()));
    if sxx <= n * (1e-9 * scale).powi(2) {
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
        r2: r_squared(
            ss_res,
            ss_tot,
            &inside.iter().map(|&i| force[i]).collect::<Vec<_>>(),
        ),
    })
}

/// `1 − SS_res/SS_tot`, or `None` when the forces do not vary (SS_tot
/// within rounding of 0 relative to the largest force: the mean of equal
/// values need not be exact).
fn r_squared(ss_res: f64, ss_tot: f64, force: &[f64]) -> Option<f64> {
    let scale = force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    let rounding = force.len() as f64 * (1e-12 * scale).powi(2);
    (ss_tot > rounding).then(|| 1.0 - ss_res / ss_tot)
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_core::units::Unit;

    fn curve() -> Curve {
        let mm = Unit::parse("mm").unwrap();
        Curve {
            displacement: (0..20).map(|i| mm.to_si(i as f64)).collect(),
            force: (0..20).map(|i| 3e3 * i as f64).collect(),
            displacement_unit: mm,
        }
    }

    #[test]
    fn a_reversed_or_non_finite_range_is_refused_as_such() {
        for range in [[5.0, 1.0], [f64::NAN, 1.0], [1.0, 1.0]] {
            let err = curve().stiffness(Some(range)).unwrap_err();
            assert!(err.0.contains("expected finite D0 < D1"), "{err}");
        }
        let fit = curve().stiffness(Some([2.0, 10.0])).unwrap();
        assert!((fit.slope - 3e6).abs() < 1e-3, "{fit:?}");
    }

    /// Forces all 0 (or all 5 kN) printed "R² 1.0000": a line through
    /// data that do not vary explains nothing; R² is undefined.
    #[test]
    fn the_r2_of_a_force_that_does_not_vary_is_undefined() {
        let d: Vec<f64> = (0..20).map(|i| f64::from(i) * 1e-3).collect();
        for (level, range) in [
            (0.0, None),
            (5e3, Some([0.0, 1.0])),
            (0.1, Some([0.0, 1.0])),
        ] {
            let f = vec![level; d.len()];
            let s = stiffness(&d, &f, range).unwrap();
            assert!(s.r2.is_none() && s.slope.abs() < 1e-9, "{level}: {s:?}");
        }
        let f: Vec<f64> = d.iter().map(|x| 3e6 * x).collect();
        let r2 = stiffness(&d, &f, None).unwrap().r2.unwrap();
        assert!((r2 - 1.0).abs() < 1e-12, "{r2}");
    }
}
