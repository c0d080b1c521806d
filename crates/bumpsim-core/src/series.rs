//! Uniformly sampled signals.
//!
//! A crash-test channel is sampled at a constant interval `T` (10 kHz is
//! usual: `T` = 1e-4 s). Sample `i` sits at time `t_i = start + i T`. Values
//! are SI; this type only guarantees that the time base is valid and every
//! value is finite, so that no NaN can enter a simulation.
//!
//! ```
//! use bumpsim_core::series::UniformSeries;
//! let s = UniformSeries::new(0.0, 1e-4, vec![0.0, 1.0, 2.0]).unwrap();
//! assert!((s.time(2) - 2e-4).abs() < 1e-18);
//! assert!(UniformSeries::new(0.0, 1e-4, vec![0.0, f64::NAN]).is_err());
//! ```

/// A signal sampled at a constant interval, values in SI.
#[derive(Debug, Clone, PartialEq)]
pub struct UniformSeries {
    start: f64,
    step: f64,
    values: Vec<f64>,
}

/// Why a series cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SeriesError {
    /// No samples at all.
    #[error("the signal has no samples")]
    Empty,
    /// The sample interval is zero, negative or not finite.
    #[error("sample interval {step} s must be positive and finite")]
    Step {
        /// The interval given, s.
        step: f64,
    },
    /// The start time is not finite.
    #[error("start time {start} s must be finite")]
    Start {
        /// The start given, s.
        start: f64,
    },
    /// A value is NaN or infinite.
    #[error("sample {index} (t = {time} s) is {value}, expected a finite number")]
    NonFinite {
        /// Index of the sample.
        index: usize,
        /// Its time, s.
        time: f64,
        /// The offending value.
        value: f64,
    },
}

impl UniformSeries {
    /// Builds a series from its first sample time (s), interval (s) and values (SI).
    pub fn new(start: f64, step: f64, values: Vec<f64>) -> Result<Self, SeriesError> {
        if !(step.is_finite() && step > 0.0) {
            return Err(SeriesError::Step { step });
        }
        if !start.is_finite() {
            return Err(SeriesError::Start { start });
        }
        if values.is_empty() {
            return Err(SeriesError::Empty);
        }
        if let Some(index) = values.iter().position(|v| !v.is_finite()) {
            return Err(SeriesError::NonFinite {
                index,
                time: start + index as f64 * step,
                value: values[index],
            });
        }
        Ok(Self {
            start,
            step,
            values,
        })
    }

    /// Time of the first sample, s.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// Sample interval, s.
    pub fn step(&self) -> f64 {
        self.step
    }

    /// Time of the last sample, s.
    pub fn end(&self) -> f64 {
        self.time(self.values.len() - 1)
    }

    /// Number of samples (at least one).
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Always false: a series has at least one sample.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// The values, SI.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Time of sample `index`, s.
    pub fn time(&self, index: usize) -> f64 {
        self.start + index as f64 * self.step
    }

    /// All sample times, s.
    pub fn times(&self) -> Vec<f64> {
        (0..self.len()).map(|i| self.time(i)).collect()
    }

    /// Index and value of the largest absolute value.
    pub fn peak(&self) -> (usize, f64) {
        peak_of(&self.values)
    }

    /// Time integral by the trapezoidal rule (unit: value unit × s).
    pub fn integral_trapezoidal(&self) -> f64 {
        let inner: f64 = self.values.windows(2).map(|w| w[0] + w[1]).sum();
        0.5 * inner * self.step
    }
}

/// Index and value of the largest absolute value of a non-empty slice
/// (`(0, 0.0)` for an empty one).
pub fn peak_of(values: &[f64]) -> (usize, f64) {
    values
        .iter()
        .copied()
        .enumerate()
        .fold(
            (0, 0.0),
            |best, (i, v)| if v.abs() > best.1.abs() { (i, v) } else { best },
        )
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn rejects_bad_time_base() {
        assert_eq!(
            UniformSeries::new(0.0, 0.0, vec![1.0]),
            Err(SeriesError::Step { step: 0.0 })
        );
        assert!(UniformSeries::new(f64::NAN, 1.0, vec![1.0]).is_err());
        assert_eq!(
            UniformSeries::new(0.0, 1.0, vec![]),
            Err(SeriesError::Empty)
        );
    }

    #[test]
    fn names_the_first_non_finite_sample() {
        let err = UniformSeries::new(1.0, 0.5, vec![0.0, 1.0, f64::INFINITY]).unwrap_err();
        assert!(matches!(err, SeriesError::NonFinite { index: 2, .. }));
        assert!(err.to_string().contains("t = 2 s"), "{err}");
    }

    #[test]
    fn trapezoid_integrates_a_line_exactly() {
        let s = UniformSeries::new(0.0, 0.1, (0..11).map(|i| i as f64 * 0.1).collect()).unwrap();
        assert_relative_eq!(s.integral_trapezoidal(), 0.5, max_relative = 1e-12);
        assert_eq!(s.peak(), (10, 1.0));
        assert_relative_eq!(s.end(), 1.0, max_relative = 1e-12);
    }
}
