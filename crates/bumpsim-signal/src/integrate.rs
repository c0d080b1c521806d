//! Trapezoidal integration and numerical differentiation (thesis ch. 3.1).
//!
//! `y[0] = y0`, `y[k] = y[k−1] + T (x[k−1] + x[k]) / 2`: acceleration to
//! velocity with the initial velocity (0 for a car at rest, the speed-trap
//! speed for a moving vehicle), velocity to displacement with 0. The
//! global error of the trapezoidal rule over a duration `D` is at most
//! `D T² max|x''| / 12`.
//!
//! The derivative uses central differences inside and one-sided differences
//! at the two ends.
//!
//! ```
//! use bumpsim_signal::integrate::cumulative_trapezoid;
//! let v = cumulative_trapezoid(&[-9.81; 11], 0.01, 2.0);
//! assert!((v[10] - (2.0 - 0.981)).abs() < 1e-12);
//! ```

/// The running trapezoidal integral (kept in core beside the integral
/// between times, so the workspace has one trapezoid rule).
pub use bumpsim_core::series::cumulative_trapezoid;

/// The time derivative of samples spaced `step` s (same length; a single
/// sample has derivative 0).
pub fn derivative(values: &[f64], step: f64) -> Vec<f64> {
    let n = values.len();
    if n < 2 {
        return vec![0.0; n];
    }
    (0..n)
        .map(|k| {
            let (lo, hi) = (k.saturating_sub(1), (k + 1).min(n - 1));
            (values[hi] - values[lo]) / ((hi - lo) as f64 * step)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn trapezoid_is_exact_for_linear_signals() {
        let x: Vec<f64> = (0..101).map(|k| 3.0 * k as f64 * 0.01).collect();
        let y = cumulative_trapezoid(&x, 0.01, 1.0);
        assert_relative_eq!(y[100], 1.0 + 1.5, max_relative = 1e-12);
        assert!(cumulative_trapezoid(&[], 0.1, 0.0).is_empty());
    }

    #[test]
    fn derivative_of_a_parabola_is_exact_inside() {
        let x: Vec<f64> = (0..11).map(|k| (k as f64 * 0.1).powi(2)).collect();
        let d = derivative(&x, 0.1);
        assert_relative_eq!(d[5], 1.0, max_relative = 1e-12);
        assert_eq!(derivative(&[1.0], 0.1), vec![0.0]);
    }
}
