//! The bumper law fitted to the training tests' forward runs: its record
//! and the curve transforms ([`crate::bumper_fit`] fits it, see there for
//! the equations). Loading `F(d) = a F₀(d/λ)`, unloading slope `u` times
//! the new curve's steepest secant.

use crate::car::PlanarCar;
use bumpsim_impact::bumper::{Bumper, BumperError, Loading};
use serde::Serialize;

/// The fitted bumper law and what it changed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BumperFit {
    /// Force scale `a` of the loading curve (1: the start's).
    pub scale: f64,
    /// Compression stretch `λ` of the loading curve (1: the start's).
    pub stretch: f64,
    /// Unloading slope over the curve's steepest secant, `u` (≥ 1).
    pub unloading_ratio: f64,
    /// The contact's rate coefficient `c`, s/m (0 when not fitted).
    pub rate: f64,
    /// The tests run forward, by name, with their force fit % before and after.
    pub tests: Vec<(String, f64, f64)>,
    /// Σ r² at the start and at the end.
    pub objective: (f64, f64),
    /// LM iterations.
    pub iterations: usize,
    /// The car with the fitted segments.
    #[serde(skip)]
    pub car: PlanarCar,
}

/// `bumper` with its loading curve scaled by `scale` in force and `stretch`
/// in compression, unloading at `ratio` times the new curve's steepest
/// secant (see the module).
pub fn transformed(
    bumper: &Bumper,
    scale: f64,
    stretch: f64,
    ratio: f64,
) -> Result<Bumper, BumperError> {
    match bumper.loading() {
        Loading::ThreePart { ramp, plateau } => {
            let ramp = ramp * scale / stretch;
            Bumper::three_part(ramp, plateau * scale, ratio * ramp)
        }
        Loading::Table { compression, force } => {
            let d: Vec<f64> = compression.iter().map(|c| c * stretch).collect();
            let f: Vec<f64> = force.iter().map(|v| v * scale).collect();
            let secant = d
                .iter()
                .zip(&f)
                .skip(1)
                .map(|(d, f)| f / d)
                .fold(0.0, f64::max);
            Bumper::table(d, f, ratio * secant)
        }
    }
}

/// A bumper's unloading slope over its curve's steepest secant.
pub fn unloading_ratio(bumper: &Bumper) -> f64 {
    let secant = bumper
        .loading_points()
        .iter()
        .skip(1)
        .map(|(d, f)| f / d)
        .fold(0.0, f64::max);
    bumper.unloading_slope() / secant
}
