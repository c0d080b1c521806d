//! ISO/TS 18571:2014 objective rating of how well a signal (a model's, the
//! candidate) follows a reference signal (a test's): the corridor, phase,
//! magnitude and slope ratings and their weighted sum, the overall rating,
//! each between 0 (no likeness) and 1 (identical).
//!
//! Both signals are taken at 10 kHz, as the standard requires: signals of
//! another step `T` are first interpolated linearly at `t_k = k·10⁻⁴ s`,
//! `0 ≤ t_k < (N−1)·T` (pyisomme's rule: a step within 10⁻⁵ s of 10⁻⁴ s is
//! taken as it is). With `r` the reference, `c` the candidate and `N`
//! samples:
//!
//! - **corridor** `Z = (1/N) Σ C_i`, with `δ_i = |c_i − r_i|`, the inner and
//!   outer half widths `a = 0.05·max|r|`, `b = 0.5·max|r|`, `C_i = 1` for
//!   `δ_i < a`, `0` for `δ_i > b`, else `((b − δ_i)/(b − a))^2`;
//! - **phase** `E_P`: the candidate is shifted left (first) and right by
//!   `m = 1 … ⌊0.2 N⌋` samples against the reference, keeping the shift of
//!   the largest Pearson correlation `ρ` (the smallest shift when two are
//!   equal); `E_P = 1` for no shift, `0` for `m ≥ 0.2 N`, else
//!   `(0.2 N − m)/(0.2 N)`;
//! - **magnitude** `E_M`: the two shifted signals are aligned by dynamic
//!   time warping (squared differences, steps (−1,0), (0,−1), (−1,−1) of
//!   weight 1, Sakoe–Chiba band `|i − j| ≤ ⌈0.1 N'⌉ − 1`); over the warped
//!   pairs `ε = Σ|c_w − r_w| / Σ|r_w|`, `E_M = 1` for `ε = 0`, `0` for
//!   `ε > 0.5`, else `(0.5 − ε)/0.5`;
//! - **slope** `E_S`: the shifted signals' central-difference derivatives,
//!   smoothed by a 9-point moving average (1, 3, 5, 7 points at the ends);
//!   `ε = Σ|c' − r'| / Σ|r'|`, `E_S = 1` for `ε ≤ 0`, `0` for `ε ≥ 2`, else
//!   `(2 − ε)/2`;
//! - **overall** `R = 0.4 Z + 0.2 E_P + 0.2 E_M + 0.2 E_S`, graded
//!   excellent above 0.94, good above 0.8, fair above 0.58, else poor.
//!
//! Source: ISO/TS 18571:2014 *Road vehicles — Objective rating metric for
//! non-ambiguous signals*, with the parameters of its table 1 (`a0` 0.05,
//! `b0` 0.5, `k_Z` 2, `ε_P` 0.2, `k_P` 1, `ε_M` 0.5, `k_M` 1, `ε_S` 2,
//! weights 0.4/0.2/0.2/0.2). The reference implementation matched to 1e-6
//! (`tests/peers/iso18571_rating.py`) is `objective_rating_metrics` 1.3, the
//! one pyisomme's `Correlation_ISO18571` calls, whose warping path and tie
//! rules this module follows. Where that implementation divides zero by zero
//! (a shifted reference of no magnitude or no slope) this one rates 1 for
//! identical signals and 0 otherwise, never NaN.
//!
//! ```
//! use bumpsim_signal::rating::rate;
//! let t: Vec<f64> = (0..1000).map(|k| k as f64 * 1e-4).collect();
//! let test: Vec<f64> = t.iter().map(|t| (40.0 * t).sin()).collect();
//! let model: Vec<f64> = t.iter().map(|t| 1.1 * (40.0 * (t - 0.002)).sin()).collect();
//! let rating = rate(&test, &model, 1e-4).unwrap();
//! assert!((rating.phase - 0.9).abs() < 1e-12); // 20 samples of 200 allowed
//! assert!(rating.overall > 0.8 && rating.overall < 0.94);
//! ```

use serde::Serialize;
use std::fmt;

/// The sample step the standard rates at, s (10 kHz).
pub const ISO_STEP: f64 = 1e-4;
/// A step closer than this to [`ISO_STEP`] is taken as 10 kHz, s (pyisomme's rule).
const STEP_TOLERANCE: f64 = 1e-5;
/// The fewest samples at 10 kHz a rating needs (the slope's 9-point average).
pub const MIN_SAMPLES: usize = 10;
/// The most samples at 10 kHz a rating takes (2 s; the warping band grows as N²).
pub const MAX_SAMPLES: usize = 20_000;

/// The ISO/TS 18571 ratings of a candidate signal against a reference, each in [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Rating {
    /// The overall rating `0.4 Z + 0.2 E_P + 0.2 E_M + 0.2 E_S`.
    pub overall: f64,
    /// The corridor rating `Z`.
    pub corridor: f64,
    /// The phase rating `E_P`.
    pub phase: f64,
    /// The magnitude rating `E_M`.
    pub magnitude: f64,
    /// The slope rating `E_S`.
    pub slope: f64,
}

/// The grade ISO/TS 18571 gives an overall rating.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Grade {
    /// Overall rating above 0.94.
    Excellent,
    /// Above 0.8, up to 0.94.
    Good,
    /// Above 0.58, up to 0.8.
    Fair,
    /// Up to 0.58.
    Poor,
}

/// Why two signals cannot be rated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RatingError {
    /// The two signals differ in length.
    #[error(
        "the reference has {reference} samples and the candidate {candidate}; a rating compares samples at the same instants"
    )]
    Lengths {
        /// Samples of the reference.
        reference: usize,
        /// Samples of the candidate.
        candidate: usize,
    },
    /// The sample step is not a positive number.
    #[error("sample step {step} s: expected a positive number of seconds")]
    Step {
        /// The step given, s.
        step: f64,
    },
    /// A sample is NaN or infinite.
    #[error("{signal} sample {index} is {value}: a rating needs finite samples")]
    NotFinite {
        /// "reference" or "candidate".
        signal: &'static str,
        /// Index of the sample (0-based).
        index: usize,
        /// The value.
        value: f64,
    },
    /// Too few or too many samples at 10 kHz.
    #[error(
        "the signals span {samples} samples at 10 kHz; a rating takes {MIN_SAMPLES} to {MAX_SAMPLES} (1 ms to 2 s)"
    )]
    Span {
        /// Samples at 10 kHz.
        samples: usize,
    },
    /// A history's times are not increasing, or not one per value.
    #[error("a history's times are not finite and increasing, one per value")]
    Times,
    /// The reference is zero throughout, so its corridors have no width.
    #[error("the reference is zero throughout: its corridors have no width")]
    FlatReference,
}

impl Rating {
    /// The grade of the overall rating.
    pub fn grade(&self) -> Grade {
        match self.overall {
            r if r > 0.94 => Grade::Excellent,
            r if r > 0.8 => Grade::Good,
            r if r > 0.58 => Grade::Fair,
            _ => Grade::Poor,
        }
    }
}

impl fmt::Display for Grade {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let word = match self {
            Grade::Excellent => "excellent",
            Grade::Good => "good",
            Grade::Fair => "fair",
            Grade::Poor => "poor",
        };
        f.write_str(word)
    }
}

impl fmt::Display for Rating {
    /// `0.908 (good; corridor 0.865, phase 0.900, magnitude 0.959, slope 0.950)`
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:.3} ({}; corridor {:.3}, phase {:.3}, magnitude {:.3}, slope {:.3})",
            self.overall,
            self.grade(),
            self.corridor,
            self.phase,
            self.magnitude,
            self.slope
        )
    }
}

/// Rates `candidate` against `reference`, both sampled every `step` s at
/// the same instants (see the module's equations).
pub fn rate(reference: &[f64], candidate: &[f64], step: f64) -> Result<Rating, RatingError> {
    check(reference, candidate, step)?;
    let (reference, candidate) = at_iso_step(reference, candidate, step)?;
    Ok(rate_at_iso_step(&reference, &candidate))
}

/// Rates a candidate history against a reference history sampled at other
/// instants (an FE run's increments against a 1-D model's steps): both are
/// interpolated linearly at 10 kHz over the span they share, `t_k = t_0 +
/// k·10⁻⁴ s ≤ min(end)`, `t_0 = max(start)`; each history is `(times, s,
/// increasing; values)`.
pub fn rate_histories(
    reference: (&[f64], &[f64]),
    candidate: (&[f64], &[f64]),
) -> Result<Rating, RatingError> {
    let span = |(t, v): (&[f64], &[f64])| -> Result<(f64, f64), RatingError> {
        let increasing = t.windows(2).all(|w| w[1] > w[0]) && t.len() == v.len();
        match (t.first(), t.last()) {
            (Some(&a), Some(&b)) if increasing && a.is_finite() && b.is_finite() => Ok((a, b)),
            _ => Err(RatingError::Times),
        }
    };
    let (a, b) = (span(reference)?, span(candidate)?);
    let (start, end) = (a.0.max(b.0), a.1.min(b.1));
    let count = ((end - start) / ISO_STEP + 1e-9).floor() + 1.0;
    if !(count >= MIN_SAMPLES as f64 && count <= MAX_SAMPLES as f64) {
        return Err(RatingError::Span {
            samples: count.max(0.0) as usize,
        });
    }
    let at = |(t, v): (&[f64], &[f64])| -> Vec<f64> {
        (0..count as usize)
            .map(|k| at_time(t, v, start + k as f64 * ISO_STEP))
            .collect()
    };
    rate(&at(reference), &at(candidate), ISO_STEP)
}

/// The value of a history at `t` (within its times), linearly interpolated.
fn at_time(times: &[f64], values: &[f64], t: f64) -> f64 {
    let upper = times.partition_point(|&x| x < t).clamp(1, times.len() - 1);
    let (t0, t1) = (times[upper - 1], times[upper]);
    let fraction = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
    values[upper - 1] + fraction * (values[upper] - values[upper - 1])
}

fn check(reference: &[f64], candidate: &[f64], step: f64) -> Result<(), RatingError> {
    if reference.len() != candidate.len() {
        return Err(RatingError::Lengths {
            reference: reference.len(),
            candidate: candidate.len(),
        });
    }
    if !(step.is_finite() && step > 0.0) {
        return Err(RatingError::Step { step });
    }
    finite("reference", reference)?;
    finite("candidate", candidate)?;
    if reference.iter().all(|&r| r == 0.0) {
        return Err(RatingError::FlatReference);
    }
    Ok(())
}

fn finite(signal: &'static str, values: &[f64]) -> Result<(), RatingError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(RatingError::NotFinite {
            signal,
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

/// Both signals at 10 kHz: as given when the step is 10⁻⁴ s, else linearly
/// interpolated at `k·10⁻⁴ s < (N−1)·T`.
fn at_iso_step(
    reference: &[f64],
    candidate: &[f64],
    step: f64,
) -> Result<(Vec<f64>, Vec<f64>), RatingError> {
    let end = reference.len().saturating_sub(1) as f64 * step;
    let iso = (step - ISO_STEP).abs() < STEP_TOLERANCE;
    let samples = if iso {
        reference.len() as f64
    } else {
        (end / ISO_STEP).ceil()
    };
    if !(MIN_SAMPLES as f64..=MAX_SAMPLES as f64).contains(&samples) {
        return Err(RatingError::Span {
            samples: samples as usize,
        });
    }
    if iso {
        return Ok((reference.to_vec(), candidate.to_vec()));
    }
    let at = |values: &[f64]| -> Vec<f64> {
        (0..samples as usize)
            .map(|k| interpolate(values, k as f64 * ISO_STEP / step))
            .collect()
    };
    Ok((at(reference), at(candidate)))
}

/// The value at fractional index `position` (within the samples).
fn interpolate(values: &[f64], position: f64) -> f64 {
    let low = (position.floor() as usize).min(values.len().saturating_sub(2));
    let fraction = position - low as f64;
    values[low] + fraction * (values[low + 1] - values[low])
}

fn rate_at_iso_step(reference: &[f64], candidate: &[f64]) -> Rating {
    let corridor = corridor(reference, candidate);
    let shift = best_shift(reference, candidate);
    let (shifted_reference, shifted_candidate) = shift.apply(reference, candidate);
    let phase = phase(shift.samples, reference.len());
    let magnitude = magnitude(shifted_reference, shifted_candidate);
    let slope = slope(shifted_reference, shifted_candidate);
    Rating {
        overall: 0.4 * corridor + 0.2 * phase + 0.2 * magnitude + 0.2 * slope,
        corridor,
        phase,
        magnitude,
        slope,
    }
}

/// `Z = (1/N) Σ C_i` with the inner and outer corridors of 5 % and 50 % of `max|r|`.
fn corridor(reference: &[f64], candidate: &[f64]) -> f64 {
    let norm = reference.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
    let (inner, outer) = (0.05 * norm, 0.5 * norm);
    let score = |(r, c): (&f64, &f64)| {
        let deviation = (c - r).abs();
        match deviation {
            d if d < inner => 1.0,
            d if d > outer => 0.0,
            d => ((outer - d) / (outer - inner)).powi(2),
        }
    };
    let sum: f64 = reference.iter().zip(candidate).map(score).sum();
    sum / reference.len() as f64
}

/// Which way the candidate is moved against the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Side {
    /// The candidate lags: compare `r[..N−m]` with `c[m..]`.
    Left,
    /// The candidate leads: compare `r[m..]` with `c[..N−m]`.
    Right,
}

/// The shift of the largest correlation.
#[derive(Debug, Clone, Copy)]
struct Shift {
    samples: usize,
    side: Side,
}

impl Shift {
    /// The overlapping parts of the two signals under this shift.
    fn apply<'a>(&self, reference: &'a [f64], candidate: &'a [f64]) -> (&'a [f64], &'a [f64]) {
        let (n, m) = (reference.len(), self.samples);
        match self.side {
            Side::Left => (&reference[..n - m], &candidate[m..]),
            Side::Right => (&reference[m..], &candidate[..n - m]),
        }
    }
}

/// Shifts of 1 … ⌊0.2 N⌋ samples, left before right, kept only when the
/// correlation is strictly larger (so the smallest shift wins a tie).
fn best_shift(reference: &[f64], candidate: &[f64]) -> Shift {
    let window = (reference.len() as f64 * 0.2).floor() as usize + 1;
    let mut best = Shift {
        samples: 0,
        side: Side::Left,
    };
    let mut best_rho = pearson(reference, candidate);
    for samples in 1..window {
        for side in [Side::Left, Side::Right] {
            let shift = Shift { samples, side };
            let (r, c) = shift.apply(reference, candidate);
            let rho = pearson(r, c);
            if rho > best_rho {
                (best, best_rho) = (shift, rho);
            }
        }
    }
    best
}

/// Pearson's correlation, clipped to [−1, 1]; NaN for a constant signal
/// (as numpy's `corrcoef`, so a constant signal is never shifted).
fn pearson(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        let (dx, dy) = (a - mx, b - my);
        sxy += dx * dy;
        sxx += dx * dx;
        syy += dy * dy;
    }
    (sxy / sxx.sqrt() / syy.sqrt()).clamp(-1.0, 1.0)
}

/// `E_P = (0.2 N − m)/(0.2 N)`, 1 for no shift.
fn phase(shift: usize, samples: usize) -> f64 {
    let limit = samples as f64 * 0.2;
    match shift as f64 {
        0.0 => 1.0,
        m if m >= limit => 0.0,
        m => (limit - m) / limit,
    }
}

/// `E_M` from the relative L1 error over the warped pairs.
fn magnitude(reference: &[f64], candidate: &[f64]) -> f64 {
    let (error, size) = warped_error(candidate, reference);
    let epsilon = relative(error, size);
    match epsilon {
        0.0 => 1.0,
        e if e > 0.5 => 0.0,
        e => (0.5 - e) / 0.5,
    }
}

/// `error / size`, with 0/0 as 0 (identical) and x/0 as infinity.
fn relative(error: f64, size: f64) -> f64 {
    match (error, size) {
        (0.0, _) => 0.0,
        (_, 0.0) => f64::INFINITY,
        (e, s) => e / s,
    }
}

/// The warping step taken into a cell.
const FROM_ROW: u8 = 0;
const FROM_COLUMN: u8 = 1;
const FROM_DIAGONAL: u8 = 2;

/// Dynamic time warping of candidate rows `i` against reference columns
/// `j` (cost `(c_i − r_j)²`, band `|i − j| ≤ ⌈0.1 N⌉ − 1`); returns
/// `Σ|c_i − r_j|` and `Σ|r_j|` over the warping path.
fn warped_error(candidate: &[f64], reference: &[f64]) -> (f64, f64) {
    let n = candidate.len();
    let half = ((0.1 * n as f64).ceil() as usize).saturating_sub(1);
    let width = 2 * half + 1;
    let steps = warp_steps(candidate, reference, half);
    let (mut i, mut j) = (n - 1, n - 1);
    let (mut error, mut size) = (0.0, 0.0);
    loop {
        error += (candidate[i] - reference[j]).abs();
        size += reference[j].abs();
        if i == 0 && j == 0 {
            return (error, size);
        }
        match steps[i * width + j + half - i] {
            FROM_ROW => i -= 1,
            FROM_COLUMN => j -= 1,
            _ => (i, j) = (i - 1, j - 1),
        }
    }
}

/// The step into each band cell of the cheapest warping (ties: row, then
/// column, then diagonal, as dtwalign's `argmin`), row by row.
fn warp_steps(candidate: &[f64], reference: &[f64], half: usize) -> Vec<u8> {
    let width = 2 * half + 1;
    let mut steps = vec![FROM_DIAGONAL; candidate.len() * width];
    let mut previous = vec![f64::INFINITY; width];
    let mut current = vec![f64::INFINITY; width];
    for (i, row) in steps.chunks_exact_mut(width).enumerate() {
        current.fill(f64::INFINITY);
        let band = Band { i, half };
        band.fill(candidate[i], reference, &previous, &mut current, row);
        std::mem::swap(&mut previous, &mut current);
    }
    steps
}

/// Row `i` of the warping band: columns `j = i − half … i + half`, stored at `j + half − i`.
struct Band {
    i: usize,
    half: usize,
}

impl Band {
    /// The accumulated costs and steps of this row from the previous row's costs.
    fn fill(
        &self,
        c: f64,
        reference: &[f64],
        previous: &[f64],
        current: &mut [f64],
        row: &mut [u8],
    ) {
        let (i, half, width) = (self.i, self.half, 2 * self.half + 1);
        let first = i.saturating_sub(half);
        let last = (i + half).min(reference.len() - 1);
        for (j, r) in reference.iter().enumerate().take(last + 1).skip(first) {
            let k = j + half - i;
            let d = c - r;
            let from = [
                if i > 0 && k + 1 < width {
                    previous[k + 1]
                } else {
                    f64::INFINITY
                },
                if j > 0 && k > 0 {
                    current[k - 1]
                } else {
                    f64::INFINITY
                },
                if i > 0 && j > 0 {
                    previous[k]
                } else {
                    f64::INFINITY
                },
            ];
            let (step, cost) = cheapest(&from);
            current[k] = if i == 0 && j == 0 {
                d * d
            } else {
                cost + d * d
            };
            row[k] = step;
        }
    }
}

/// The first of the smallest costs and its step.
fn cheapest(from: &[f64; 3]) -> (u8, f64) {
    let mut best = (FROM_ROW, from[0]);
    for (step, &cost) in [FROM_COLUMN, FROM_DIAGONAL].into_iter().zip(&from[1..]) {
        if cost < best.1 {
            best = (step, cost);
        }
    }
    best
}

/// `E_S` from the relative L1 error of the smoothed derivatives.
fn slope(reference: &[f64], candidate: &[f64]) -> f64 {
    let (r, c) = (smoothed_slope(reference), smoothed_slope(candidate));
    let error: f64 = r.iter().zip(&c).map(|(r, c)| (c - r).abs()).sum();
    let size: f64 = r.iter().map(|r| r.abs()).sum();
    match relative(error, size) {
        e if e <= 0.0 => 1.0,
        e if e >= 2.0 => 0.0,
        e => (2.0 - e) / 2.0,
    }
}

/// Central differences (one-sided at the ends) at 10 kHz, then the 9-point
/// moving average; the first and last four samples average the 1, 3, 5, 7
/// samples at their end.
fn smoothed_slope(values: &[f64]) -> Vec<f64> {
    let derivative = crate::integrate::derivative(values, ISO_STEP);
    let n = derivative.len();
    let mut smoothed = vec![0.0; n];
    for (index, count) in [(0, 1), (1, 3), (2, 5), (3, 7)] {
        smoothed[index] = mean(&derivative[..count]);
        smoothed[n - 1 - index] = mean(&derivative[n - count..]);
    }
    for (index, window) in derivative.windows(9).enumerate() {
        smoothed[index + 4] = window.iter().map(|d| d / 9.0).sum();
    }
    smoothed
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pulse(n: usize, delay: f64, scale: f64) -> Vec<f64> {
        (0..n)
            .map(|k| {
                let t = k as f64 * 1e-4 - delay;
                scale * (std::f64::consts::PI * t / 0.06).sin().max(0.0) * f64::from(t < 0.06)
            })
            .collect()
    }

    #[test]
    fn identical_signals_rate_one() {
        let r = pulse(800, 0.005, 1.0);
        let rating = rate(&r, &r, 1e-4).unwrap();
        assert_eq!(rating.overall, 1.0);
        assert_eq!(rating.grade(), Grade::Excellent);
    }

    #[test]
    fn a_lag_is_found_and_costs_phase() {
        let (r, c) = (pulse(800, 0.005, 1.0), pulse(800, 0.008, 1.0));
        let shift = best_shift(&r, &c);
        assert_eq!((shift.samples, shift.side), (30, Side::Left));
        let rating = rate(&r, &c, 1e-4).unwrap();
        assert!((rating.phase - (160.0 - 30.0) / 160.0).abs() < 1e-12);
        assert!((rating.magnitude - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_scaled_copy_loses_magnitude_and_slope_in_proportion() {
        let (r, c) = (pulse(800, 0.005, 1.0), pulse(800, 0.005, 1.2));
        let rating = rate(&r, &c, 1e-4).unwrap();
        // warping pairs peaks with flanks, so the magnitude error is below 20 %
        assert!(rating.magnitude > 0.6 && rating.magnitude < 1.0);
        assert!((rating.slope - (2.0 - 0.2) / 2.0).abs() < 1e-9);
    }

    #[test]
    fn a_constant_offset_is_a_magnitude_error_of_its_size() {
        let rating = rate(&[1.0; 100], &[1.2; 100], 1e-4).unwrap();
        assert!((rating.magnitude - (0.5 - 0.2) / 0.5).abs() < 1e-12);
        assert_eq!((rating.phase, rating.slope), (1.0, 1.0));
    }

    #[test]
    fn coarse_steps_are_interpolated_to_ten_kilohertz() {
        let r: Vec<f64> = (0..101).map(|k| f64::from(k) * 1e-3).collect();
        let (iso, _) = at_iso_step(&r, &r, 1e-3).unwrap();
        assert_eq!(iso.len(), 1000);
        assert!((iso[505] - 0.0505).abs() < 1e-15);
    }

    #[test]
    fn histories_on_other_instants_are_rated_on_their_common_span() {
        let fine: Vec<f64> = (0..=1000).map(|k| k as f64 * 1e-4).collect();
        let coarse: Vec<f64> = (0..=40).map(|k| 0.002 + k as f64 * 2.5e-3).collect();
        let f = |t: &f64| (t * 30.0).sin();
        let (a, b): (Vec<f64>, Vec<f64>) =
            (fine.iter().map(f).collect(), coarse.iter().map(f).collect());
        let rating = rate_histories((&fine, &a), (&coarse, &b)).unwrap();
        assert!(rating.overall > 0.99, "{rating}");
        assert_eq!(
            rate_histories((&fine, &a), (&[0.5, 0.2], &[1.0, 2.0])),
            Err(RatingError::Times)
        );
    }

    #[test]
    fn bad_input_is_named() {
        let r = pulse(100, 0.0, 1.0);
        assert_eq!(
            rate(&r, &r[..50], 1e-4),
            Err(RatingError::Lengths {
                reference: 100,
                candidate: 50
            })
        );
        let mut c = r.clone();
        c[7] = f64::NAN;
        assert!(matches!(
            rate(&r, &c, 1e-4),
            Err(RatingError::NotFinite {
                signal: "candidate",
                index: 7,
                ..
            })
        ));
        assert_eq!(
            rate(&[0.0; 20], &r[..20], 1e-4),
            Err(RatingError::FlatReference)
        );
        assert_eq!(
            rate(&r[..5], &r[..5], 1e-4),
            Err(RatingError::Span { samples: 5 })
        );
        assert!(matches!(rate(&r, &r, 0.0), Err(RatingError::Step { .. })));
    }
}
