//! The domain in which a measured series and its model are compared
//! (issue 44): displacement as the thesis does, or its first or second
//! backward difference, velocity or acceleration.
//!
//! With a displacement series `y[k]` on step `h`, the compared value at
//! sample k is
//!
//! - displacement: `y[k]` (m);
//! - velocity: `(y[k] − y[k−1]) / h` (m/s);
//! - acceleration: `(y[k] − 2 y[k−1] + y[k−2]) / h²` (m/s²).
//!
//! Applied alike to the model's displacement and to the measured one
//! (integrated twice from an acceleration by the trapezoidal rule), the
//! difference undoes the integration: the measured velocity value is the
//! mean of two trapezoidal velocities, the acceleration value
//! `(a[k] + 2 a[k−1] + a[k−2]) / 4`, a smoothing of the measured
//! acceleration by three samples. Noise that the double integration made
//! a random walk (lag-1 correlation near 1) is, in the acceleration
//! domain, as white as the sensor's (or as coloured as its filter). The
//! difference is linear, so its Jacobian is the same difference of the
//! exact displacement sensitivities (no finite difference in the
//! parameters). A constant displacement offset drops out of velocity, and
//! an error of the initial velocity (a rigid motion `v₀ t`) out of
//! acceleration.
//!
//! ```
//! use bumpsim_estimate::domain::Domain;
//! let y = [0.0, 1.0, 4.0, 9.0]; // t², h = 1
//! assert_eq!(Domain::Velocity.at(&y, 3, 1.0), 5.0);
//! assert_eq!(Domain::Acceleration.at(&y, 3, 1.0), 2.0);
//! assert_eq!(Domain::Displacement.at(&y, 3, 1.0), 9.0);
//! ```

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Where a displacement series is compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Domain {
    /// The displacement itself (the thesis's objective, m²).
    #[default]
    Displacement,
    /// Its first backward difference over the step, m/s.
    Velocity,
    /// Its second backward difference over the step squared, m/s².
    Acceleration,
}

/// The range of a measurement noise a study gives (its standard deviation,
/// SI: m, m/s, m/s² or rad/s): a residual divided by it, squared and summed
/// over any record, stays finite (a noise of 1e-300 m/s made every start
/// fail "to be simulated"; a hostile pass, issue 44).
pub const NOISE_RANGE: std::ops::RangeInclusive<f64> = 1e-12..=1e15;

/// A domain name that is none of the three, written exactly (`"Velocity"`
/// and `"velocity "` were taken for `"velocity"`, while every other name of
/// a study is exact; a hostile pass, issue 44). The message names the key,
/// the value as given and the accepted names.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "objective {0:?}: expected \"displacement\", \"velocity\" or \"acceleration\", written exactly (lower case, no spaces)"
)]
pub struct UnknownDomain(pub String);

impl FromStr for Domain {
    type Err = UnknownDomain;

    fn from_str(s: &str) -> Result<Domain, UnknownDomain> {
        match s {
            "displacement" => Ok(Domain::Displacement),
            "velocity" => Ok(Domain::Velocity),
            "acceleration" => Ok(Domain::Acceleration),
            _ => Err(UnknownDomain(s.to_string())),
        }
    }
}

impl fmt::Display for Domain {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Domain {
    /// Its name as the study writes it.
    pub fn name(self) -> &'static str {
        match self {
            Domain::Displacement => "displacement",
            Domain::Velocity => "velocity",
            Domain::Acceleration => "acceleration",
        }
    }

    /// The order of the difference: 0, 1 or 2 (the first sample that has
    /// a value).
    pub fn order(self) -> usize {
        match self {
            Domain::Displacement => 0,
            Domain::Velocity => 1,
            Domain::Acceleration => 2,
        }
    }

    /// The SI unit of its values.
    pub fn unit(self) -> &'static str {
        match self {
            Domain::Displacement => "m",
            Domain::Velocity => "m/s",
            Domain::Acceleration => "m/s²",
        }
    }

    /// The unit of a sum of its values squared (an objective compared in
    /// it): m², (m/s)², (m/s²)².
    pub fn squared_unit(self) -> &'static str {
        match self {
            Domain::Displacement => "m²",
            Domain::Velocity => "(m/s)²",
            Domain::Acceleration => "(m/s²)²",
        }
    }

    /// Its value at sample `k ≥ order` of the displacement series `y` on
    /// step `h`.
    pub fn at(self, y: &[f64], k: usize, h: f64) -> f64 {
        self.strided(|i| y[i], k, h)
    }

    /// Its value at sample k of a series read through `y(i)` (a column of
    /// a row-major Jacobian, say).
    #[inline]
    pub fn strided(self, y: impl Fn(usize) -> f64, k: usize, h: f64) -> f64 {
        match self {
            Domain::Displacement => y(k),
            Domain::Velocity => (y(k) - y(k - 1)) / h,
            Domain::Acceleration => (y(k) - 2.0 * y(k - 1) + y(k - 2)) / (h * h),
        }
    }

    /// The noise of a displacement series `y` on step `h` in this domain:
    /// the standard deviation of its values about their mean over samples
    /// `order..y.len()` (a pre-trigger, say); None with fewer than 3.
    pub fn noise(self, y: &[f64], h: f64) -> Option<f64> {
        let values: Vec<f64> = (self.order()..y.len()).map(|k| self.at(y, k, h)).collect();
        if values.len() < 3 {
            return None;
        }
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let variance =
            values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (values.len() - 1) as f64;
        Some(variance.sqrt()).filter(|s| s.is_finite() && *s > 0.0)
    }
}

/// White noise of level `sigma` (an accelerometer's, m/s²) sampled every
/// `step` (s), integrated `integrations` times: its rms over `duration` (s).
/// Once, a random walk: `σ √(h T / 2)`; twice, `σ √h T^{3/2} / √12`
/// (the rms over the window of the integrated walk).
///
/// ```
/// use bumpsim_estimate::domain::integrated_noise;
/// assert_eq!(integrated_noise(0.5, 1e-4, 0.1, 0), 0.5);
/// let twice = integrated_noise(1.0, 1e-4, 0.1, 2);
/// assert!((twice - 1e-2 * 0.1f64.powf(1.5) / 12f64.sqrt()).abs() < 1e-15);
/// ```
pub fn integrated_noise(sigma: f64, step: f64, duration: f64, integrations: usize) -> f64 {
    match integrations {
        0 => sigma,
        1 => sigma * (0.5 * step * duration).sqrt(),
        _ => sigma * step.sqrt() * duration.powf(1.5) / 12f64.sqrt(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_back_and_others_are_refused() {
        for d in [Domain::Displacement, Domain::Velocity, Domain::Acceleration] {
            assert_eq!(d.name().parse::<Domain>(), Ok(d));
        }
        let err = "speed".parse::<Domain>().unwrap_err().to_string();
        assert!(
            err.contains("objective \"speed\"") && err.contains("velocity"),
            "{err}"
        );
        // the names are exact: another case or a space is refused, named
        for near in ["Displacement", "displacement ", " velocity", "ACCELERATION"] {
            let err = near.parse::<Domain>().unwrap_err().to_string();
            assert!(
                err.starts_with(&format!("objective {near:?}: expected \"displacement\""))
                    && err.ends_with("written exactly (lower case, no spaces)"),
                "{err}"
            );
        }
    }

    #[test]
    fn differences_of_a_parabola_are_its_derivatives() {
        // y = 3 t², h = 0.01: velocity 6 t − 3 h at the backward midpoint, acceleration 6
        let h = 0.01;
        let y: Vec<f64> = (0..10).map(|k| 3.0 * (k as f64 * h).powi(2)).collect();
        let t = 5.0 * h;
        approx::assert_relative_eq!(
            Domain::Velocity.at(&y, 5, h),
            6.0 * t - 3.0 * h,
            epsilon = 1e-9
        );
        approx::assert_relative_eq!(Domain::Acceleration.at(&y, 5, h), 6.0, epsilon = 1e-9);
    }

    #[test]
    fn noise_of_white_acceleration_is_its_spread() {
        // a displacement whose second differences alternate ±1: spread 1
        let mut y = vec![0.0, 0.0];
        for k in 2..2002 {
            let a = if k % 2 == 0 { 1.0 } else { -1.0 };
            let next = a + 2.0 * y[k - 1] - y[k - 2];
            y.push(next);
        }
        let s = Domain::Acceleration.noise(&y, 1.0).unwrap();
        approx::assert_relative_eq!(s, 1.0, epsilon = 1e-3);
        assert_eq!(Domain::Velocity.noise(&[0.0, 1.0], 1.0), None);
    }
}
