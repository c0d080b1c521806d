//! The documents of the planar car that every front end writes (`bumpsim
//! planar --json`, `bumpsim identify --json` on a planar study, `bumpsim
//! predict --json` with a planar car; Python's `to_json`): serialisable
//! types, so each JSON is assembled once, here.

use crate::identify::{CaseFit, PlanarIdentification};
use crate::result::PlanarResult;
use crate::striker::Striker;
use bumpsim_estimate::document::Predictions;
use serde::Serialize;

/// `bumpsim planar --json`: the car's name, the striker and the result.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ImpactDocument<'a> {
    /// The car's name (or its file).
    pub car: &'a str,
    /// What hit the car.
    pub striker: &'a Striker,
    /// Histories, peaks and balances.
    pub result: &'a PlanarResult,
}

/// `bumpsim identify --json` on a planar study: the identification, the
/// fits of the validation cases and the notes on the channels.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct IdentificationDocument<'a> {
    /// The identification.
    pub result: &'a PlanarIdentification,
    /// Fits of the cases predicted, not fitted.
    pub validation: &'a [CaseFit],
    /// Notes on the channels' time base.
    pub notes: &'a [String],
}

/// `bumpsim predict --json` with a planar car: the layer's document of each
/// case's fit of x and yaw, the warnings of negative fits, and the notes.
pub type PredictionDocument<'a> = Predictions<'a, CaseFit>;

/// The prediction document of `fits` of the car `car`.
pub fn predictions<'a>(
    car: &'a str,
    fits: &'a [CaseFit],
    notes: &'a [String],
) -> PredictionDocument<'a> {
    let warnings = fits.iter().flat_map(CaseFit::warnings).collect();
    Predictions::new(car, fits, warnings, notes)
}
