//! Uniformly sampled signals.
//!
//! A crash-test channel is sampled at a constant interval `T` (10 kHz is
//! usual: `T` = 1e-4 s). Sample `i` sits at time `t_i = start + i T`. Values
//! are SI; this type only guarantees that the time base is valid and every
//! value is finite, so that no NaN can enter a simulation.
//!
//! Windows and integrals between times share one rule for "inside": sample
//! `i` lies in `[t0, t1]` when `t0 − ε T ≤ t_i ≤ t1 + ε T` with
//! ε = [`WINDOW_TOLERANCE`] (1e-9 of the interval), so a boundary given as a
//! sample time (`0.12` s, or `start + k T` computed with rounding) includes
//! that sample. The integral is the trapezoidal rule
//! `∫ x dt ≈ Σ T (x_k + x_{k+1}) / 2` over the samples inside, plus the
//! partial intervals from `t0` to the first and from the last to `t1`
//! (trapezoids with the linearly interpolated boundary value), so it is exact
//! for piecewise-linear signals whatever the window.
//!
//! ```
//! use bumpsim_core::series::UniformSeries;
//! let s = UniformSeries::new(0.0, 1e-4, vec![0.0, 1.0, 2.0]).unwrap();
//! assert!((s.time(2) - 2e-4).abs() < 1e-18);
//! assert!(UniformSeries::new(0.0, 1e-4, vec![0.0, f64::NAN]).is_err());
//! assert_eq!(s.window(1e-4, 1.0), Some(1..=2));
//! assert!((s.integral(0.5e-4, 2e-4) - 1.875e-4).abs() < 1e-18);
//! ```

use std::ops::RangeInclusive;

/// The tolerance of "inside a window", as a fraction of the sample
/// interval: a sample within `1e-9 T` outside a boundary counts as inside.
pub const WINDOW_TOLERANCE: f64 = 1e-9;

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
    #[error(
        "start time {start} s must be finite, and small enough that the sample interval is resolved next to it"
    )]
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
    /// Sample times and values of different lengths ([`UniformSeries::from_times`]).
    #[error("{times} sample times for {values} values: expected one time per value")]
    Lengths {
        /// Number of times.
        times: usize,
        /// Number of values.
        values: usize,
    },
    /// Fewer than two sample times: the interval is unknown.
    #[error("{times} sample time(s): at least two are needed to know the sample interval")]
    TooFewTimes {
        /// Number of times.
        times: usize,
    },
    /// A sample time off the uniform grid ([`UniformSeries::from_times`]).
    #[error(
        "time {index} is {time} s but the uniform grid of the mean interval {step} s puts it at {expected} s (more than {TIME_GRID_TOLERANCE:e} of the interval off): the times are not uniformly sampled"
    )]
    OffGrid {
        /// Index of the sample.
        index: usize,
        /// Its time, s.
        time: f64,
        /// Where the grid puts it, s.
        expected: f64,
        /// The mean interval, s.
        step: f64,
    },
}

/// How far (fraction of the interval) a sample time given to
/// [`UniformSeries::from_times`] may lie off the uniform grid: rounding of
/// computed times (`start + k T`, `numpy.arange`), not a dropped sample.
pub const TIME_GRID_TOLERANCE: f64 = 1e-6;

impl UniformSeries {
    /// Builds a series from its first sample time (s), interval (s) and values (SI).
    pub fn new(start: f64, step: f64, values: Vec<f64>) -> Result<Self, SeriesError> {
        if !(step.is_finite() && step > 0.0) {
            return Err(SeriesError::Step { step });
        }
        // beyond ~1e15 intervals from zero, start + k·step no longer
        // separates the samples (a 1e308 s start collapses every time)
        if !start.is_finite() || start.abs() * 1e-15 > step {
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

    /// Builds a series from sample times (s) and values (SI), as given by a
    /// script: the interval is the mean one, `(t_last − t_0)/(n − 1)`, and
    /// every time must lie within [`TIME_GRID_TOLERANCE`] of an interval of
    /// its place on that grid.
    ///
    /// ```
    /// use bumpsim_core::series::UniformSeries;
    /// let s = UniformSeries::from_times(&[0.0, 1e-4, 2e-4], vec![0.0, 1.0, 2.0]).unwrap();
    /// assert!((s.step() - 1e-4).abs() < 1e-18);
    /// assert!(UniformSeries::from_times(&[0.0, 1e-4, 3e-4], vec![0.0; 3]).is_err());
    /// ```
    pub fn from_times(times: &[f64], values: Vec<f64>) -> Result<Self, SeriesError> {
        if times.len() != values.len() {
            return Err(SeriesError::Lengths {
                times: times.len(),
                values: values.len(),
            });
        }
        let n = times.len();
        if n < 2 {
            return Err(SeriesError::TooFewTimes { times: n });
        }
        let step = (times[n - 1] - times[0]) / (n - 1) as f64;
        let series = Self::new(times[0], step, values)?;
        if let Some(index) = (0..n).find(|&k| {
            let off = (times[k] - series.time(k)).abs();
            off.is_nan() || off > TIME_GRID_TOLERANCE * step
        }) {
            return Err(SeriesError::OffGrid {
                index,
                time: times[index],
                expected: series.time(index),
                step,
            });
        }
        Ok(series)
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

    /// Time integral over the whole series by the trapezoidal rule (unit:
    /// value unit × s).
    pub fn integral_trapezoidal(&self) -> f64 {
        trapezoid(&self.values, self.step)
    }

    /// The samples inside `[t0, t1]` s (with [`WINDOW_TOLERANCE`]), as an
    /// index range; `None` when no sample is inside or a bound is NaN.
    pub fn window(&self, t0: f64, t1: f64) -> Option<RangeInclusive<usize>> {
        if t0.is_nan() || t1.is_nan() {
            return None;
        }
        let slack = WINDOW_TOLERANCE * self.step;
        let last_index = (self.len() - 1) as f64;
        let first = ((t0 - slack - self.start) / self.step).ceil().max(0.0);
        let last = ((t1 + slack - self.start) / self.step)
            .floor()
            .min(last_index);
        (first.is_finite() && last.is_finite() && first <= last)
            .then_some(first as usize..=last as usize)
    }

    /// Time integral between `t0` and `t1` s (`t0 ≤ t1`, clipped to the
    /// series' span) by the trapezoidal rule, including the partial
    /// intervals at both ends (unit: value unit × s). Zero when the window
    /// holds no part of the series or a bound is NaN.
    pub fn integral(&self, t0: f64, t1: f64) -> f64 {
        if t0.is_nan() || t1.is_nan() || t0 > t1 {
            return 0.0;
        }
        let (t0, t1) = (t0.max(self.start), t1.min(self.end()));
        let Some(inside) = self.window(t0, t1) else {
            return self.partial(t0, t1);
        };
        let (a, b) = (*inside.start(), *inside.end());
        self.partial(t0, self.time(a))
            + trapezoid(&self.values[a..=b], self.step)
            + self.partial(self.time(b), t1)
    }

    /// Trapezoid from `t0` to `t1` with interpolated end values (zero when
    /// the interval is within the window tolerance or reversed).
    fn partial(&self, t0: f64, t1: f64) -> f64 {
        if t1 - t0 <= WINDOW_TOLERANCE * self.step {
            return 0.0;
        }
        0.5 * (t1 - t0) * (self.at(t0) + self.at(t1))
    }

    /// Linear interpolation at `t` s (clamped to the ends).
    pub fn at(&self, t: f64) -> f64 {
        let v = &self.values;
        let x = ((t - self.start) / self.step).clamp(0.0, (v.len() - 1) as f64);
        let i = (x.floor() as usize).min(v.len().saturating_sub(2));
        match v.len() {
            1 => v[0],
            _ => v[i] + (x - i as f64) * (v[i + 1] - v[i]),
        }
    }
}

/// Trapezoidal integral `Σ T (x_k + x_{k+1}) / 2` of samples spaced `step`
/// s (zero for fewer than two samples; unit: value unit × s).
pub fn trapezoid(values: &[f64], step: f64) -> f64 {
    values.windows(2).map(|w| interval(step, w[0], w[1])).sum()
}

/// The running trapezoidal integral of samples spaced `step` s, starting
/// at `initial`: `y[0] = y0`, `y[k] = y[k−1] + T (x[k−1] + x[k]) / 2`.
pub fn cumulative_trapezoid(values: &[f64], step: f64, initial: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(values.len());
    let mut sum = initial;
    for (k, &v) in values.iter().enumerate() {
        if k > 0 {
            sum += interval(step, values[k - 1], v);
        }
        out.push(sum);
    }
    out
}

/// One trapezoid: `T (a + b) / 2`.
fn interval(step: f64, a: f64, b: f64) -> f64 {
    0.5 * step * (a + b)
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
    fn from_times_takes_the_mean_interval_and_refuses_gaps() {
        let times: Vec<f64> = (0..1001).map(|k| -0.01 + k as f64 * 1e-4).collect();
        let s = UniformSeries::from_times(&times, vec![0.0; 1001]).unwrap();
        assert_relative_eq!(s.step(), 1e-4, max_relative = 1e-12);
        assert_eq!(s.start(), -0.01);
        let mut gap = times.clone();
        gap[500] += 0.5e-4;
        assert!(matches!(
            UniformSeries::from_times(&gap, vec![0.0; 1001]),
            Err(SeriesError::OffGrid { index: 500, .. })
        ));
        assert_eq!(
            UniformSeries::from_times(&times[..3], vec![0.0; 2]),
            Err(SeriesError::Lengths {
                times: 3,
                values: 2
            })
        );
        assert_eq!(
            UniformSeries::from_times(&[0.0], vec![0.0]),
            Err(SeriesError::TooFewTimes { times: 1 })
        );
        let mut nan = times;
        nan[7] = f64::NAN;
        assert!(UniformSeries::from_times(&nan, vec![0.0; 1001]).is_err());
    }

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

    fn ramp() -> UniformSeries {
        UniformSeries::new(
            -0.05,
            1e-4,
            (0..2100).map(|i| 3.0 * i as f64 * 1e-4).collect(),
        )
        .unwrap()
    }

    #[test]
    fn a_window_given_by_sample_times_includes_both_samples() {
        let s = ramp();
        assert_eq!(s.window(s.time(500), s.time(1700)), Some(500..=1700));
        assert_eq!(s.window(0.0, 0.12), Some(500..=1700));
        assert_eq!(s.window(0.5e-13, 0.12 - 0.5e-13), Some(500..=1700));
        assert_eq!(s.window(2e-13, 0.12 - 2e-13), Some(501..=1699));
        assert_eq!(s.window(0.5e-4, 1.5e-4), Some(501..=501));
        assert_eq!(s.window(-1.0, 1.0), Some(0..=2099));
        assert_eq!(s.window(0.2, 0.3), None);
        assert_eq!(s.window(0.01e-4, 0.99e-4), None);
        assert_eq!(s.window(f64::NAN, 1.0), None);
        assert_eq!(s.window(0.1, 0.0), None);
    }

    #[test]
    fn integral_between_times_is_exact_for_a_line() {
        let s = ramp();
        // x(t) = 3 (t + 0.05): ∫ from a to b = 1.5 ((b + 0.05)² − (a + 0.05)²).
        let exact = |a: f64, b: f64| 1.5 * ((b + 0.05).powi(2) - (a + 0.05).powi(2));
        for (a, b) in [
            (0.0, 0.12),
            (0.00003, 0.11997),
            (-1.0, 0.0),
            (0.01234, 0.01236),
        ] {
            assert_relative_eq!(
                s.integral(a, b),
                exact(a.max(-0.05), b),
                max_relative = 1e-10
            );
        }
        assert_eq!(s.integral(0.3, 0.4), 0.0);
        assert_eq!(s.integral(0.1, 0.0), 0.0);
        assert_eq!(s.integral(f64::NAN, 0.0), 0.0);
    }

    #[test]
    fn on_sample_windows_sum_whole_trapezoids_only() {
        let s = ramp();
        let whole = trapezoid(&s.values()[500..=1700], s.step());
        assert_eq!(s.integral(s.time(500), s.time(1700)), whole);
        assert_eq!(trapezoid(&[1.0], 0.1), 0.0);
        let running = cumulative_trapezoid(&s.values()[500..=1700], s.step(), 0.0);
        assert_eq!(running.last().copied(), Some(whole));
        assert_relative_eq!(s.at(0.00005), 3.0 * 0.05005, max_relative = 1e-12);
        assert_eq!(s.at(-9.0), 0.0);
    }

    #[test]
    fn trapezoid_integrates_a_line_exactly() {
        let s = UniformSeries::new(0.0, 0.1, (0..11).map(|i| i as f64 * 0.1).collect()).unwrap();
        assert_relative_eq!(s.integral_trapezoidal(), 0.5, max_relative = 1e-12);
        assert_eq!(s.peak(), (10, 1.0));
        assert_relative_eq!(s.end(), 1.0, max_relative = 1e-12);
    }
}
