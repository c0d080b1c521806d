//! The mass-reduction study of paper A (spec §6).
//!
//! A 2-DOF car — M1 carrying the bumper, M2 (engine, occupants) joined to it
//! by a spring k — hits a rigid barrier at V0 through the bumper R:
//! `M1 u1'' + k (u1 − u2) = −R(u1)`, `M2 u2'' + k (u2 − u1) = 0`. Which single
//! rigid mass M* gives the same **remaining** (permanent) deformation, or the
//! same **maximum** deformation? The scale factor is `M* / (M1 + M2)`.
//!
//! For a single mass the answer is closed-form: at the largest compression
//! `d` all kinetic energy is in the bumper, `½ M V0² = A(d)` (the area under
//! the loading curve), so `M* = 2 A(d) / V0²`. For the maximum criterion `d`
//! is the 2-DOF car's largest compression; for the remaining criterion `d`
//! solves `d − R(d)/s_u = r` (the unloading line ends at the 2-DOF car's
//! remaining deformation r), found by bisection on a bracket (the left side
//! grows with d because `s_u` is at least every loading slope). An elastic
//! impact (r = 0) has no remaining-deformation answer and says so.
//!
//! Sweeps over two parameters run in parallel (rayon).
//!
//! ```
//! use bumpsim_impact::bumper::Bumper;
//! use bumpsim_impact::reduction::{Criterion, TwoDof, equivalent_mass};
//! let bumper = Bumper::three_part(2e6, 60e3, 8e6).unwrap();
//! let car = TwoDof { m1: 650.0, m2: 400.0, k: 4e6 };
//! let r = equivalent_mass(&car, &bumper, 8.0 / 3.6, Criterion::Remaining).unwrap();
//! assert!(r.scale_factor > 650.0 / 1050.0 && r.scale_factor < 1.0);
//! ```

use crate::bumper::Bumper;
use crate::impact::{ImpactError, Options, Scenario, simulate};
use bumpsim_core::model::MsdModel;
use rayon::prelude::*;
use serde::Serialize;

/// Which deformation the single mass must reproduce.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Criterion {
    /// The remaining (permanent) deformation (paper A figs 5–6).
    Remaining,
    /// The maximum deformation (paper A fig. 7).
    Maximum,
}

/// A criterion name that is not `remaining` or `maximum`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("criterion '{0}': expected remaining or maximum")]
pub struct UnknownCriterion(pub String);

impl std::str::FromStr for Criterion {
    type Err = UnknownCriterion;
    fn from_str(text: &str) -> Result<Self, UnknownCriterion> {
        match text {
            "remaining" => Ok(Criterion::Remaining),
            "maximum" => Ok(Criterion::Maximum),
            _ => Err(UnknownCriterion(text.into())),
        }
    }
}

/// Why the study cannot answer.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ReductionError {
    /// The car is not valid.
    #[error("2-DOF car: {0}")]
    Car(#[source] bumpsim_core::model::ModelError),
    /// The impact failed.
    #[error(transparent)]
    Impact(#[from] ImpactError),
    /// A mass of the 2-DOF car outside [`MASS_RANGE`](crate::impact::MASS_RANGE),
    /// the impactor masses' range (0.1 g masses ran while `impact` refuses
    /// an impactor below 1 g).
    #[error(
        "{key} = {} kg: the 2-DOF car's masses must be from 0.001 to 1e7 kg (limit MASS_RANGE: 1 g to 10 000 t, as an impactor's)",
        bumpsim_core::units::short(*value)
    )]
    Mass {
        /// `m1` or `m2`.
        key: &'static str,
        /// The mass given, kg.
        value: f64,
    },
    /// The bumper stays elastic: no remaining deformation to match.
    #[error(
        "the bumper stays elastic (no remaining deformation): the remaining criterion has no answer; use the maximum criterion or a stronger impact"
    )]
    Elastic,
}

/// Paper A's 2-DOF car: M1 (kg) with the bumper, M2 (kg), spring k (N/m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TwoDof {
    /// Mass carrying the bumper, kg.
    pub m1: f64,
    /// The other mass, kg.
    pub m2: f64,
    /// The spring between them, N/m.
    pub k: f64,
}

impl TwoDof {
    fn model(&self) -> Result<MsdModel, ReductionError> {
        for (key, value) in [("m1", self.m1), ("m2", self.m2)] {
            if !crate::impact::MASS_RANGE.contains(&value) {
                return Err(ReductionError::Mass { key, value });
            }
        }
        MsdModel::new(vec![self.m1, self.m2], vec![0.0], vec![self.k]).map_err(ReductionError::Car)
    }
}

/// The answer for one car.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Reduction {
    /// The criterion used.
    pub criterion: Criterion,
    /// M*, kg.
    pub equivalent_mass: f64,
    /// M* / (M1 + M2).
    pub scale_factor: f64,
    /// The 2-DOF car's maximum compression, m.
    pub max_compression: f64,
    /// The 2-DOF car's remaining compression, m.
    pub remaining_compression: f64,
    /// The single mass's largest compression, m.
    pub equivalent_max_compression: f64,
}

/// M* and the scale factor of a 2-DOF car hitting a rigid barrier at `speed` m/s.
pub fn equivalent_mass(
    car: &TwoDof,
    bumper: &Bumper,
    speed: f64,
    criterion: Criterion,
) -> Result<Reduction, ReductionError> {
    let impact = simulate(
        &car.model()?,
        bumper,
        Scenario::Barrier { speed },
        &Options::default(),
    )?;
    let d = match criterion {
        Criterion::Maximum => impact.max_compression,
        Criterion::Remaining => compression_leaving(bumper, impact.remaining_compression)?,
    };
    let equivalent_mass = 2.0 * bumper.loading_energy(d) / (speed * speed);
    Ok(Reduction {
        criterion,
        equivalent_mass,
        scale_factor: equivalent_mass / (car.m1 + car.m2),
        max_compression: impact.max_compression,
        remaining_compression: impact.remaining_compression,
        equivalent_max_compression: d,
    })
}

/// The largest compression whose unloading line ends at `remaining`.
fn compression_leaving(bumper: &Bumper, remaining: f64) -> Result<f64, ReductionError> {
    if remaining <= 1e-12 {
        return Err(ReductionError::Elastic);
    }
    let left = |d: f64| d - bumper.loading_force(d) / bumper.unloading_slope() - remaining;
    let (mut lo, mut hi) = (remaining, 2.0 * remaining);
    while left(hi) < 0.0 {
        (lo, hi) = (hi, 2.0 * hi);
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if left(mid) < 0.0 {
            lo = mid
        } else {
            hi = mid
        }
        if hi - lo <= 1e-15 * hi {
            break;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// Values of a function on a grid: `values[i][j]` at `(x[i], y[j])`;
/// `None` where it has no answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Grid {
    /// Name and unit of x.
    pub x_label: String,
    /// x values.
    pub x: Vec<f64>,
    /// Name and unit of y.
    pub y_label: String,
    /// y values.
    pub y: Vec<f64>,
    /// The values.
    pub values: Vec<Vec<Option<f64>>>,
}

/// `count` evenly spaced values from `a` to `b`.
pub fn linspace(a: f64, b: f64, count: usize) -> Vec<f64> {
    match count {
        0 => vec![],
        1 => vec![a],
        n => (0..n)
            .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
            .collect(),
    }
}

/// Evaluates `f` on the grid in parallel; `progress` is called per row.
pub fn sweep(
    (x_label, x): (&str, Vec<f64>),
    (y_label, y): (&str, Vec<f64>),
    f: impl Fn(f64, f64) -> Option<f64> + Sync,
    progress: &(dyn Fn() + Sync),
) -> Grid {
    let values = x
        .par_iter()
        .map(|&xi| {
            let row = y.iter().map(|&yj| f(xi, yj)).collect();
            progress();
            row
        })
        .collect();
    Grid {
        x_label: x_label.into(),
        x,
        y_label: y_label.into(),
        y,
        values,
    }
}

/// Paper A figs 5–6: the scale factor over the spring k (N/m) and the mass
/// ratio M1/(M1+M2) at a fixed total mass.
pub fn sweep_car(
    total: f64,
    k: Vec<f64>,
    ratio: Vec<f64>,
    bumper: &Bumper,
    speed: f64,
    criterion: Criterion,
    progress: &(dyn Fn() + Sync),
) -> Grid {
    let f = |k: f64, r: f64| {
        let car = TwoDof {
            m1: r * total,
            m2: (1.0 - r) * total,
            k,
        };
        equivalent_mass(&car, bumper, speed, criterion)
            .ok()
            .map(|x| x.scale_factor)
    };
    sweep(
        ("spring k [N/m]", k),
        ("mass ratio M1/(M1+M2) [-]", ratio),
        f,
        progress,
    )
}

/// Paper A fig. 7: the scale factor over the ramp slope (N/m) and the
/// plateau F_max (N) of a three-part bumper with unloading slope `unloading`
/// (at least the ramp slope).
pub fn sweep_bumper(
    car: &TwoDof,
    ramp: Vec<f64>,
    plateau: Vec<f64>,
    unloading: f64,
    speed: f64,
    criterion: Criterion,
    progress: &(dyn Fn() + Sync),
) -> Grid {
    let f = |s: f64, fmax: f64| {
        let bumper = Bumper::three_part(s, fmax, unloading.max(s)).ok()?;
        equivalent_mass(car, &bumper, speed, criterion)
            .ok()
            .map(|x| x.scale_factor)
    };
    sweep(
        ("ramp slope s [N/m]", ramp),
        ("plateau F_max [N]", plateau),
        f,
        progress,
    )
}

/// The two sweeps of paper A's figures, over its parameter ranges.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PaperSweep {
    /// The car: spring k from 1e5 to 1e7 N/m and mass ratio M1/(M1+M2)
    /// from 0.52 to 0.95, at the car's total mass.
    Car,
    /// The bumper: ramp slope s from 1e6 to 8e6 N/m and plateau F_max from
    /// 40 to 200 kN, unloading slope as the bumper's.
    Bumper,
}

/// A sweep's name that names neither of paper A's sweeps.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("'{text}': expected car or bumper")]
pub struct PaperSweepError {
    /// The name as given.
    pub text: String,
}

impl std::str::FromStr for PaperSweep {
    type Err = PaperSweepError;

    fn from_str(text: &str) -> Result<PaperSweep, PaperSweepError> {
        match text {
            "car" => Ok(PaperSweep::Car),
            "bumper" => Ok(PaperSweep::Bumper),
            other => Err(PaperSweepError { text: other.into() }),
        }
    }
}

impl PaperSweep {
    /// Runs the sweep with `points` values per axis around `car` and
    /// `bumper` at `speed` (m/s); `progress` is called per row.
    pub fn run(
        self,
        points: usize,
        (car, bumper): (&TwoDof, &Bumper),
        speed: f64,
        criterion: Criterion,
        progress: &(dyn Fn() + Sync),
    ) -> Grid {
        let n = points;
        match self {
            PaperSweep::Car => sweep_car(
                car.m1 + car.m2,
                linspace(1e5, 1e7, n),
                linspace(0.52, 0.95, n),
                bumper,
                speed,
                criterion,
                progress,
            ),
            PaperSweep::Bumper => sweep_bumper(
                car,
                linspace(1e6, 8e6, n),
                linspace(40e3, 200e3, n),
                bumper.unloading_slope(),
                speed,
                criterion,
                progress,
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 0.1 g masses ran while `impact` refuses an impactor below 1 g: one
    /// range (`MASS_RANGE`) for both, named with the mass and its value.
    #[test]
    fn masses_outside_the_impactor_range_are_refused() {
        let bumper = Bumper::three_part(1e6, 1e9, 1e6).unwrap();
        let car = |m1, m2| TwoDof { m1, m2, k: 4e6 };
        for (m1, m2, head) in [
            (1e-4, 400.0, "m1 = 0.0001 kg"),
            (650.0, 1e-4, "m2 = 0.0001 kg"),
            (650.0, 1e308, "m2 = 1e308 kg"),
        ] {
            let e = equivalent_mass(&car(m1, m2), &bumper, 2.0, Criterion::Maximum).unwrap_err();
            let e = e.to_string();
            assert!(e.starts_with(head) && e.contains("MASS_RANGE"), "{e}");
        }
        assert!(equivalent_mass(&car(1e-3, 1e-3), &bumper, 2.0, Criterion::Maximum).is_ok());
    }
}
