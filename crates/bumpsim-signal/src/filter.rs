//! Low-pass filters: SAE J211-1 / ISO 6487 channel frequency classes (CFC),
//! Butterworth of any order, and the N-point moving average.
//!
//! **CFC** (SAE J211-1 appendix C, ISO 6487 annex A): a 2-pole Butterworth
//! run forward and backward (zero phase). With `T` the sample interval,
//! `wd = 2 pi CFC k` (`k` = 2.0775 in SAE J211-1, 1.25·5/3 in ISO 6487),
//! `wa = tan(wd T / 2)`, `a0 = wa² / (1 + √2 wa + wa²)`, `a1 = 2 a0`, `a2 = a0`,
//! `b1 = −2 (wa² − 1) / (1 + √2 wa + wa²)`, `b2 = (−1 + √2 wa − wa²) / (1 + √2 wa + wa²)`,
//! `y[k] = a0 x[k] + a1 x[k−1] + a2 x[k−2] + b1 y[k−1] + b2 y[k−2]`.
//! These are the coefficients of scipy's `butter(2, k·CFC, fs = 1/T)`.
//!
//! **Butterworth** of order n: analog poles on the circle of the prewarped
//! cut-off `wa = 2 fs tan(pi fc / fs)`, mapped by the bilinear transform into
//! second-order sections (one first-order section for odd n), each with unit
//! gain at DC.
//!
//! **Start-up** (zero-phase runs): the signal is extended at both ends by
//! `padding` samples mirrored through the end value (`2 x0 − x[i]`, ISO 6487
//! practice, scipy's `padtype="odd"`), and each pass starts from the steady
//! state of its first input sample. The result equals
//! `scipy.signal.sosfiltfilt(sos, x, padtype="odd", padlen=padding)` to
//! rounding. The default padding is three periods of the cut-off frequency,
//! `ceil(3 fs / fc)`, clipped to `n − 1`.
//!
//! Written by hand: the one Rust DSP crate with Butterworth design (sci-rs)
//! pins an older nalgebra, and a biquad cascade is a few lines.
//!
//! ```
//! use bumpsim_signal::filter::{Cfc, CfcStandard};
//! let cfc = Cfc::new(60.0, CfcStandard::SaeJ211).unwrap();
//! let x = vec![1.0; 200];
//! let y = cfc.filter(&x, 1e-4).unwrap();
//! assert!((y[100] - 1.0).abs() < 1e-12); // unit gain at DC
//! ```

use serde::Deserialize;
use std::f64::consts::{PI, SQRT_2};

/// Why a filter cannot be built or run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FilterError {
    /// A filter parameter is out of range.
    #[error("filter parameter {name} = {value:?}: expected {expected}")]
    Parameter {
        /// Parameter name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What is allowed.
        expected: String,
    },
    /// The signal is too short to filter.
    #[error("the signal has {samples} samples; the filter needs at least {needed}")]
    TooShort {
        /// Samples given.
        samples: usize,
        /// Samples needed.
        needed: usize,
    },
}

/// Which standard's constant relates the CFC number to the design frequency.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CfcStandard {
    /// SAE J211-1: `k` = 2.0775.
    #[default]
    SaeJ211,
    /// ISO 6487: `k` = 1.25 · 5/3.
    Iso6487,
}

impl CfcStandard {
    /// The design-frequency factor `k` (design frequency = k · CFC).
    pub fn factor(self) -> f64 {
        match self {
            CfcStandard::SaeJ211 => 2.0775,
            CfcStandard::Iso6487 => 1.25 * 5.0 / 3.0,
        }
    }
}

/// The lowest design frequency of a CFC filter relative to the sample rate:
/// below it the section's squared prewarped frequency (about 1e-11) nears
/// the rounding of its unit gain and the filter no longer filters (a class
/// of 1e-300 returned the first sample for every sample).
pub const MIN_RELATIVE_CUTOFF: f64 = 1e-6;

impl CfcStandard {
    /// The classes a CFC filter of this standard may have at sample
    /// interval `step` s: from `MIN_RELATIVE_CUTOFF / (k step)` up to
    /// (excluding) the class whose design frequency is the Nyquist
    /// frequency, `1 / (2 k step)`.
    pub fn classes(self, step: f64) -> (f64, f64) {
        let rate = 1.0 / step;
        (
            MIN_RELATIVE_CUTOFF * rate / self.factor(),
            0.5 * rate / self.factor(),
        )
    }
}

/// `x` with 5 significant digits at most, no trailing zeros (for messages).
fn short(x: f64) -> String {
    let text = format!("{x:.4e}");
    match text.parse::<f64>() {
        Ok(v) if (1e-3..1e7).contains(&v.abs()) => format!("{v}"),
        Ok(v) => format!("{v:e}"),
        Err(_) => text,
    }
}

/// A CFC standard's name that names none.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown CFC standard '{text}': expected sae-j211 or iso-6487")]
pub struct CfcStandardError {
    /// The name as given.
    pub text: String,
}

impl std::str::FromStr for CfcStandard {
    type Err = CfcStandardError;
    fn from_str(text: &str) -> Result<Self, CfcStandardError> {
        match text.to_ascii_lowercase().replace([' ', '_'], "-").as_str() {
            "sae-j211" | "j211" | "sae" => Ok(CfcStandard::SaeJ211),
            "iso-6487" | "iso6487" | "iso" => Ok(CfcStandard::Iso6487),
            _ => Err(CfcStandardError {
                text: text.to_string(),
            }),
        }
    }
}

/// One second-order section `b0 + b1 z⁻¹ + b2 z⁻²` over `1 + a1 z⁻¹ + a2 z⁻²`
/// (scipy's sign convention for `a`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Numerator coefficients.
    pub b: [f64; 3],
    /// Denominator coefficients `a1`, `a2` (`a0` = 1).
    pub a: [f64; 2],
}

impl Section {
    /// Runs the section over `values` in place (direct form I), starting from
    /// the steady state of a constant input `initial` (unit DC gain).
    fn run(&self, values: &mut [f64], initial: f64) {
        let (mut x1, mut x2, mut y1, mut y2) = (initial, initial, initial, initial);
        for v in values.iter_mut() {
            let x0 = *v;
            let y0 =
                self.b[0] * x0 + self.b[1] * x1 + self.b[2] * x2 - self.a[0] * y1 - self.a[1] * y2;
            (x2, x1, y2, y1) = (x1, x0, y1, y0);
            *v = y0;
        }
    }
}

/// A Butterworth low-pass as a cascade of second-order sections.
#[derive(Debug, Clone, PartialEq)]
pub struct Butterworth {
    /// Cut-off frequency (−3 dB of one pass), Hz.
    pub cutoff: f64,
    /// Sample interval, s.
    pub step: f64,
    /// The sections, in order.
    pub sections: Vec<Section>,
}

fn check_positive(name: &'static str, value: f64) -> Result<(), FilterError> {
    if value.is_finite() && value > 0.0 {
        return Ok(());
    }
    Err(FilterError::Parameter {
        name,
        value,
        expected: "a positive finite number".into(),
    })
}

impl Butterworth {
    /// Designs an order-`order` low-pass with cut-off `cutoff` Hz for sample
    /// interval `step` s. The cut-off must lie from [`MIN_RELATIVE_CUTOFF`]
    /// of the sample rate (as a CFC class's design frequency: 1e-300 Hz no
    /// longer filtered) to below the Nyquist frequency.
    pub fn new(order: usize, cutoff: f64, step: f64) -> Result<Butterworth, FilterError> {
        check_positive("cutoff (Hz)", cutoff)?;
        check_positive("sample interval (s)", step)?;
        let nyquist = 0.5 / step;
        let lowest = MIN_RELATIVE_CUTOFF / step;
        let usable = (lowest..nyquist).contains(&cutoff);
        if !(1..=16).contains(&order) || !usable {
            let (name, value, expected) = if !usable {
                (
                    "cutoff (Hz)",
                    cutoff,
                    format!(
                        "from {} Hz to below the Nyquist frequency {} Hz",
                        short(lowest),
                        short(nyquist)
                    ),
                )
            } else {
                ("order", order as f64, "an integer from 1 to 16".to_string())
            };
            return Err(FilterError::Parameter {
                name,
                value,
                expected,
            });
        }
        let fs2 = 2.0 / step;
        let warped = fs2 * (PI * cutoff * step).tan();
        let sections = (0..order / 2)
            .map(|k| pair_section(order, k, warped, fs2))
            .chain((order % 2 == 1).then(|| real_section(warped, fs2)))
            .collect();
        Ok(Butterworth {
            cutoff,
            step,
            sections,
        })
    }

    /// Runs the filter forward once (causal, with phase lag).
    pub fn causal(&self, values: &[f64]) -> Vec<f64> {
        let mut out = values.to_vec();
        let initial = values.first().copied().unwrap_or(0.0);
        for section in &self.sections {
            section.run(&mut out, initial);
        }
        out
    }

    /// Runs the filter forward and backward (zero phase, squared magnitude)
    /// with odd mirrored padding of `padding` samples (clipped to `n − 1`).
    pub fn zero_phase(&self, values: &[f64], padding: usize) -> Result<Vec<f64>, FilterError> {
        let n = values.len();
        if n < 2 {
            return Err(FilterError::TooShort {
                samples: n,
                needed: 2,
            });
        }
        let pad = padding.min(n - 1);
        let mut ext = mirrored(values, pad);
        self.pass(&mut ext);
        ext.reverse();
        self.pass(&mut ext);
        ext.reverse();
        Ok(ext[pad..pad + n].to_vec())
    }

    /// The default padding: three periods of the cut-off, in samples.
    pub fn default_padding(&self) -> usize {
        (3.0 / (self.cutoff * self.step)).ceil() as usize
    }

    fn pass(&self, values: &mut [f64]) {
        let initial = values[0];
        for section in &self.sections {
            section.run(values, initial);
        }
    }
}

/// The section of the `k`-th conjugate pole pair of an order-`order` design.
fn pair_section(order: usize, k: usize, warped: f64, fs2: f64) -> Section {
    let angle = PI * (2 * k + order + 1) as f64 / (2 * order) as f64;
    let (re, im) = (warped * angle.cos(), warped * angle.sin());
    // z = (fs2 + p) / (fs2 - p) for p = re + i im.
    let den = (fs2 - re).powi(2) + im * im;
    let zr = ((fs2 + re) * (fs2 - re) - im * im) / den;
    let zi = 2.0 * fs2 * im / den;
    let a = [-2.0 * zr, zr * zr + zi * zi];
    let gain = (1.0 + a[0] + a[1]) / 4.0;
    Section {
        b: [gain, 2.0 * gain, gain],
        a,
    }
}

/// The first-order section of the real pole of an odd-order design.
fn real_section(warped: f64, fs2: f64) -> Section {
    let z = (fs2 - warped) / (fs2 + warped);
    let gain = (1.0 - z) / 2.0;
    Section {
        b: [gain, gain, 0.0],
        a: [-z, 0.0],
    }
}

/// Extends `values` by `pad` samples at each end, mirrored through the end values.
fn mirrored(values: &[f64], pad: usize) -> Vec<f64> {
    let n = values.len();
    let (first, last) = (values[0], values[n - 1]);
    let head = (1..=pad).rev().map(|i| 2.0 * first - values[i]);
    let tail = (1..=pad).map(|i| 2.0 * last - values[n - 1 - i]);
    head.chain(values.iter().copied()).chain(tail).collect()
}

/// A channel frequency class filter (SAE J211-1 / ISO 6487).
#[derive(Debug, Clone, PartialEq)]
pub struct Cfc {
    /// The class number (60, 180, 600, 1000 or any positive number).
    pub class: f64,
    /// The standard whose constant is used.
    pub standard: CfcStandard,
}

impl Cfc {
    /// A CFC filter of any positive class.
    pub fn new(class: f64, standard: CfcStandard) -> Result<Cfc, FilterError> {
        check_positive("CFC class", class)?;
        Ok(Cfc { class, standard })
    }

    /// The 2-pole Butterworth that one pass of the CFC filter uses; the
    /// class must lie in [`CfcStandard::classes`] for the sample interval `step` s.
    pub fn design(&self, step: f64) -> Result<Butterworth, FilterError> {
        check_positive("sample interval (s)", step)?;
        let (low, high) = self.standard.classes(step);
        if !(self.class >= low && self.class < high) {
            return Err(FilterError::Parameter {
                name: "CFC class",
                value: self.class,
                expected: format!(
                    "a class from {} to below {} for a channel sampled at {} Hz (the design \
                     frequency {} × CFC must lie from {MIN_RELATIVE_CUTOFF:e} × the sample \
                     rate to below the Nyquist frequency {} Hz)",
                    short(low),
                    short(high),
                    short(1.0 / step),
                    self.standard.factor(),
                    short(0.5 / step)
                ),
            });
        }
        Butterworth::new(2, self.standard.factor() * self.class, step)
    }

    /// Filters a signal sampled every `step` s, zero phase, default padding.
    pub fn filter(&self, values: &[f64], step: f64) -> Result<Vec<f64>, FilterError> {
        let design = self.design(step)?;
        design.zero_phase(values, design.default_padding())
    }
}

/// The J211 coefficients `[a0, a1, a2, b1, b2]` of one pass, as the standard writes them.
pub fn j211_coefficients(class: f64, standard: CfcStandard, step: f64) -> [f64; 5] {
    let wd = 2.0 * PI * class * standard.factor();
    let wa = (wd * step / 2.0).tan();
    let d = 1.0 + SQRT_2 * wa + wa * wa;
    let a0 = wa * wa / d;
    [
        a0,
        2.0 * a0,
        a0,
        -2.0 * (wa * wa - 1.0) / d,
        (-1.0 + SQRT_2 * wa - wa * wa) / d,
    ]
}

/// Centred N-point moving average; near the ends the window shrinks to the
/// samples available. For even `points` the window reaches one sample further
/// ahead than back (`[k − (N−1)/2, k + N/2]`).
pub fn moving_average(values: &[f64], points: usize) -> Result<Vec<f64>, FilterError> {
    if points == 0 {
        return Err(FilterError::Parameter {
            name: "moving-average points",
            value: 0.0,
            expected: "at least 1".into(),
        });
    }
    let mut prefix = Vec::with_capacity(values.len() + 1);
    prefix.push(0.0);
    for v in values {
        prefix.push(prefix[prefix.len() - 1] + v);
    }
    let (back, ahead) = ((points - 1) / 2, points / 2);
    let n = values.len();
    Ok((0..n)
        .map(|k| {
            let (lo, hi) = (k.saturating_sub(back), (k + ahead + 1).min(n));
            (prefix[hi] - prefix[lo]) / (hi - lo) as f64
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn second_order_design_equals_the_j211_coefficients() {
        for class in [60.0, 180.0, 600.0, 1000.0] {
            for standard in [CfcStandard::SaeJ211, CfcStandard::Iso6487] {
                let s = Cfc::new(class, standard)
                    .unwrap()
                    .design(1e-4)
                    .unwrap()
                    .sections[0];
                let [a0, a1, a2, b1, b2] = j211_coefficients(class, standard, 1e-4);
                for (x, y) in [
                    (s.b[0], a0),
                    (s.b[1], a1),
                    (s.b[2], a2),
                    (-s.a[0], b1),
                    (-s.a[1], b2),
                ] {
                    assert_relative_eq!(x, y, max_relative = 1e-12);
                }
            }
        }
    }

    #[test]
    fn odd_orders_have_unit_dc_gain_and_reject_bad_parameters() {
        let f = Butterworth::new(5, 200.0, 1e-4).unwrap();
        assert_eq!(f.sections.len(), 3);
        let y = f.causal(&[2.5; 50]);
        assert_relative_eq!(y[49], 2.5, max_relative = 1e-12);
        assert!(Butterworth::new(2, 6000.0, 1e-4).is_err());
        assert!(Butterworth::new(0, 60.0, 1e-4).is_err());
        // 1e-300 Hz no longer filtered (hostile pass of issue 34)
        let low = Butterworth::new(4, 1e-300, 1e-4).unwrap_err().to_string();
        assert!(low.contains("from 0.01 Hz to below the Nyquist"), "{low}");
        assert!(Cfc::new(-60.0, CfcStandard::SaeJ211).is_err());
        assert!(f.zero_phase(&[1.0], 3).is_err());
    }

    #[test]
    fn moving_average_is_centred_and_shrinks_at_the_ends() {
        let y = moving_average(&[0.0, 3.0, 6.0, 9.0], 3).unwrap();
        assert_eq!(y.len(), 4);
        assert_relative_eq!(y[0], 1.5);
        assert_relative_eq!(y[1], 3.0);
        assert_relative_eq!(y[3], 7.5);
        assert!(moving_average(&[1.0], 0).is_err());
        assert_eq!("iso".parse::<CfcStandard>(), Ok(CfcStandard::Iso6487));
    }
}
