//! How well a model follows a measurement: the fit percentage of the
//! thesis (paper B), `100 (1 − ‖y − ŷ‖ / ‖y − ȳ‖)` %, 100 for a perfect
//! fit, 0 for a model no better than the measurement's mean, negative for
//! a worse one; and the warning a negative fit gets.
//!
//! ```
//! use bumpsim_estimate::fit::{percent, negative_fit};
//! let measured = [0.0, 1.0, 2.0, 3.0];
//! assert_eq!(percent(&measured, &measured), 100.0);
//! assert_eq!(percent(&[1.5; 4], &measured), 0.0);           // the mean
//! assert!(percent(&[3.0, 2.0, 1.0, 0.0], &measured) < 0.0);
//! assert!(negative_fit("flat", "displacement", -5.0).is_some());
//! assert!(negative_fit("flat", "displacement", 5.0).is_none());
//! ```

use bumpsim_core::units::format_number;

/// `Σ (y − ŷ)²` of `model` against `measured`.
pub fn sse(model: &[f64], measured: &[f64]) -> f64 {
    model
        .iter()
        .zip(measured)
        .map(|(s, y)| (y - s).powi(2))
        .sum()
}

/// `Σ (y − ȳ)²` of `measured` about its mean.
pub fn spread(measured: &[f64]) -> f64 {
    let mean = measured.iter().sum::<f64>() / measured.len() as f64;
    measured.iter().map(|y| (y - mean).powi(2)).sum()
}

/// The fit % of a sum of squared errors `sse` against the spread `sst` of
/// the measurement about its mean; 0 when the measurement does not vary.
pub fn from_sums(sse: f64, sst: f64) -> f64 {
    match sst > 0.0 {
        true => 100.0 * (1.0 - (sse / sst).sqrt()),
        false => 0.0,
    }
}

/// The fit % of `model` against `measured` (same length).
pub fn percent(model: &[f64], measured: &[f64]) -> f64 {
    from_sums(sse(model, measured), spread(measured))
}

/// The warning for case `case` whose `signal` fits `fit` %, when negative:
/// the model follows it worse than its mean does.
pub fn negative_fit(case: &str, signal: &str, fit: f64) -> Option<String> {
    (fit < 0.0).then(|| {
        format!(
            "case '{case}': fit {} %: the model follows the {signal} worse than its mean does; check its channels, their window and any note on their time base",
            format_number(fit, 4)
        )
    })
}
