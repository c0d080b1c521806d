//! Contact windows from a force signal (spec §3–4).
//!
//! Contact starts at the first sample where `|F|` rises to `rise · max|F|`
//! and ends at the last sample where `|F|` is still at or above
//! `fall · max|F|` (`fall ≤ rise`, the hysteresis), so short dips inside
//! the impact do not split it. Defaults: rise 5 %, fall 2 %.
//!
//! ```
//! use bumpsim_signal::window::ContactThreshold;
//! let f = [0.0, 0.0, 1.0, 10.0, 0.5, 3.0, 0.1, 0.0];
//! let w = ContactThreshold::default().detect(&f).unwrap();
//! assert_eq!((w.first, w.last), (2, 5));
//! ```

use serde::Deserialize;

/// Why no window was found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WindowError {
    /// The thresholds are not fractions with `fall ≤ rise`.
    #[error("contact thresholds rise = {rise}, fall = {fall}: expected 0 < fall <= rise < 1")]
    Thresholds {
        /// Rise fraction given.
        rise: f64,
        /// Fall fraction given.
        fall: f64,
    },
    /// The force is zero everywhere.
    #[error("the force is zero everywhere: no contact to detect")]
    NoForce,
}

/// Rise and fall thresholds as fractions of the peak magnitude.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactThreshold {
    /// Fraction of the peak at which contact starts.
    pub rise: f64,
    /// Fraction of the peak below which contact has ended.
    pub fall: f64,
}

impl Default for ContactThreshold {
    fn default() -> Self {
        ContactThreshold {
            rise: 0.05,
            fall: 0.02,
        }
    }
}

/// Sample indices of a contact, inclusive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ContactWindow {
    /// First sample in contact.
    pub first: usize,
    /// Last sample in contact.
    pub last: usize,
}

impl ContactThreshold {
    /// Finds the contact window of `force` (any sign).
    pub fn detect(&self, force: &[f64]) -> Result<ContactWindow, WindowError> {
        let ok = 0.0 < self.fall && self.fall <= self.rise && self.rise < 1.0;
        if !ok {
            return Err(WindowError::Thresholds {
                rise: self.rise,
                fall: self.fall,
            });
        }
        let peak = force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
        if peak <= 0.0 {
            return Err(WindowError::NoForce);
        }
        let first = force.iter().position(|f| f.abs() >= self.rise * peak);
        let last = force.iter().rposition(|f| f.abs() >= self.fall * peak);
        match (first, last) {
            (Some(first), Some(last)) => Ok(ContactWindow {
                first,
                last: last.max(first),
            }),
            _ => Err(WindowError::NoForce),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_forces_and_bad_thresholds() {
        let f = [0.0, -0.1, -4.0, -0.3, 0.0];
        let w = ContactThreshold::default().detect(&f).unwrap();
        assert_eq!((w.first, w.last), (2, 3));
        assert!(
            ContactThreshold {
                rise: 0.01,
                fall: 0.1
            }
            .detect(&f)
            .is_err()
        );
        assert_eq!(
            ContactThreshold::default().detect(&[0.0; 3]),
            Err(WindowError::NoForce)
        );
    }
}
