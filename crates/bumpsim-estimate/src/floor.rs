//! A channel's error scale with a model-error floor (issue 46's links fit,
//! issue 44's planar objective): on a crash test the residual is model
//! error, not sensor noise, so each channel's residuals are divided by
//!
//! `s = √(σ² + (φ S)²)`
//!
//! with σ the channel's measurement noise in the compared domain, S the
//! measured channel's standard deviation over the compared samples
//! ([`spread`]) and φ ∈ [0, 1] the stated floor: the fraction of S a lumped
//! model is expected to leave. Its misfit then counts in units of the error
//! stated acceptable for it (a fit % of `100 (1 − ‖r‖/(√n S))` against
//! `100 (1 − φ)`), so channels of different units and sizes weigh alike
//! where the model follows each as well as stated. With φ = 0 the scale is
//! the noise alone (weighted least squares).
//!
//! ```
//! use bumpsim_estimate::floor::{scale, spread};
//! assert_eq!(spread(&[1.0, 3.0, 1.0, 3.0]), 1.0);
//! assert!((scale(0.03, 0.04, 1.0) - 0.05).abs() < 1e-15);
//! ```

/// The error scale `√(σ² + (φ S)²)` of a channel of noise `noise` (σ),
/// stated floor `floor` (φ) and spread `spread` (S), in the channel's unit.
pub fn scale(noise: f64, floor: f64, spread: f64) -> f64 {
    noise.hypot(floor * spread)
}

/// The standard deviation of `values` about their mean (population: n in
/// the denominator), 0 for an empty slice.
pub fn spread(values: &[f64]) -> f64 {
    let n = values.len().max(1) as f64;
    let mean = values.iter().sum::<f64>() / n;
    (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The floor's fraction of the spread and the noise add in quadrature;
    /// a zero floor leaves the noise, a zero noise the floor's part.
    #[test]
    fn noise_and_floor_add_in_quadrature() {
        assert_eq!(scale(0.3, 0.0, 10.0), 0.3);
        assert!((scale(0.0, 0.1, 10.0) - 1.0).abs() < 1e-15);
        assert!((scale(3.0, 0.4, 10.0) - 5.0).abs() < 1e-12);
        assert_eq!(spread(&[]), 0.0);
        assert_eq!(spread(&[2.0; 5]), 0.0);
        // 1..=4: mean 2.5, population variance 1.25
        assert!((spread(&[1.0, 2.0, 3.0, 4.0]) - 1.25f64.sqrt()).abs() < 1e-15);
    }
}
