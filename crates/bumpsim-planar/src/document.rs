//! The documents of the planar car that every front end writes (`bumpsim
//! planar --json`, `bumpsim identify --json` on a planar study, `bumpsim
//! predict --json` with a planar car; Python's `to_json`): serialisable
//! types, so each JSON is assembled once, here.

use crate::car::Body;
use crate::forward::Forward;
use crate::identify::{CaseFit, PlanarIdentification};
use crate::result::PlanarResult;
use crate::striker::Striker;
use bumpsim_estimate::document::Predictions;
use serde::Serialize;

/// `bumpsim planar --json`: the car's name, the striker, the result and
/// the car's body (mass, yaw inertia, CG behind the bumper, wheelbase, CG
/// behind the front axle, track: what places the body's outline, e.g. in
/// `bumpsim view`'s top view).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ImpactDocument<'a> {
    /// The car's name (or its file).
    pub car: &'a str,
    /// What hit the car.
    pub striker: &'a Striker,
    /// Histories, peaks and balances.
    pub result: &'a PlanarResult,
    /// The car's body (left out when None).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body: Option<&'a Body>,
}

/// `bumpsim identify --json` on a planar study: the identification, the
/// fits of the validation cases, the forward predictions of the tests with
/// a striker and the notes on the channels.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct IdentificationDocument<'a> {
    /// The identification.
    pub result: &'a PlanarIdentification,
    /// Fits of the cases predicted, not fitted.
    pub validation: &'a [CaseFit],
    /// Forward predictions (car, bumper and striker; no measured force).
    pub forward: &'a [Forward],
    /// Notes on the channels' time base.
    pub notes: &'a [String],
    /// The predictive bands of the held-out replays and forward
    /// predictions, judged ([`crate::bands`]; left out when None).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bands: Option<&'a crate::bands::Bands>,
}

/// `bumpsim predict --json` with a planar car: the layer's document of each
/// case's fit of x and yaw, the warnings of negative fits, and the notes;
/// with the forward predictions of the cases that give their striker.
#[derive(Debug, Clone, Serialize)]
pub struct PredictionDocument<'a> {
    /// The replays' fits.
    #[serde(flatten)]
    pub predictions: Predictions<'a, CaseFit>,
    /// Forward predictions (car, bumper and striker; no measured force).
    pub forward: &'a [Forward],
}

/// The prediction document of `fits` and `forward` of the car `car`.
pub fn predictions<'a>(
    car: &'a str,
    fits: &'a [CaseFit],
    forward: &'a [Forward],
    notes: &'a [String],
) -> PredictionDocument<'a> {
    let mut warnings: Vec<String> = fits.iter().flat_map(CaseFit::warnings).collect();
    warnings.extend(forward.iter().flat_map(forward_warnings));
    PredictionDocument {
        predictions: Predictions::new(car, fits, warnings, notes),
        forward,
    }
}

/// The warnings of a forward prediction: negative fits and the simulation's own.
pub fn forward_warnings(f: &Forward) -> Vec<String> {
    let mut out: Vec<String> = f
        .channels
        .iter()
        .filter_map(|c| {
            bumpsim_estimate::fit::negative_fit(
                &f.case,
                &format!("forward {}", c.name),
                c.fit_percent,
            )
        })
        .collect();
    out.extend(
        f.warnings
            .iter()
            .map(|w| format!("case '{}': forward prediction: {w}", f.case)),
    );
    out
}
