//! Global sensitivity (issue 39): Sobol' first-order and total indices of
//! any scalar output over independent inputs, with bootstrap intervals.
//!
//! - **Sampling** (Saltelli 2002; Saltelli et al. 2010): N points of a
//!   2d-dimensional Sobol' sequence ([`sequence`]; Joe & Kuo 2008 direction
//!   numbers, as scipy's `qmc.Sobol` without scrambling; its first point,
//!   the origin, skipped) give the matrices A (first d columns) and B (last
//!   d); `A_B^(i)` is A with column i from B. The output is evaluated at the
//!   `N (d + 2)` rows, in parallel (rayon).
//! - **Estimators** (as SALib's `sobol.analyze`): with `V` the variance of
//!   the outputs of A and B together,
//!   first order `S_i = mean(f(B) (f(A_B^(i)) − f(A))) / V` (outputs
//!   centred on their mean first, as SALib standardises; Saltelli et al.
//!   2010, table 2 (b)), total `S_Ti = mean((f(A) − f(A_B^(i)))²) / (2V)`
//!   (Jansen 1999).
//! - **Intervals**: the N rows resampled with replacement
//!   [`Settings::resamples`] times (seeded); the 95 % half-width is
//!   `1.96` times the resampled indices' standard deviation (SALib's
//!   `S1_conf`, `ST_conf`).
//! - **Inputs**: uniform over a range, normal (a log-normal parameter's
//!   logarithm; its quantile function from statrs), the logarithm of a
//!   factor uniform over a range (`ln(low + (high − low) u)`: a parameter
//!   uniform on its range, where the inputs are log factors), or
//!   distributed as given draws (a
//!   posterior's marginal: the quantile function of the draws, so the
//!   inputs stay independent and their correlation is not carried).
//!   [`Law::of_normal`] gives a law's value at a standard normal draw `z`
//!   (its quantile at `Φ(z)`), so Monte Carlo draws of the same inputs
//!   come from the same law.
//!
//! ```
//! use bumpsim_estimate::sobol::{Input, Settings, indices};
//! // f = x1 + 2 x2 on the unit square: S = (1/5, 4/5), no interaction
//! let inputs = [Input::uniform("x1", 0.0, 1.0), Input::uniform("x2", 0.0, 1.0)];
//! let s = indices(&inputs, &|x: &[f64]| x[0] + 2.0 * x[1], &Settings::new(4096, 1)).unwrap();
//! assert!((s.first[0] - 0.2).abs() < 0.01 && (s.total[1] - 0.8).abs() < 0.01);
//! ```

use crate::search::Draws;
use rayon::prelude::*;
use serde::Serialize;

/// Direction numbers of the first [`DIMENSIONS`] dimensions (Joe & Kuo
/// 2008, `new-joe-kuo-6.21201`): the primitive polynomial with its leading
/// and trailing ones, and the initial numbers `m_1..m_s`.
const DIRECTIONS: [(u32, &[u32]); 24] = [
    (1, &[]),
    (3, &[1]),
    (7, &[1, 3]),
    (11, &[1, 3, 1]),
    (13, &[1, 1, 1]),
    (19, &[1, 1, 3, 3]),
    (25, &[1, 3, 5, 13]),
    (37, &[1, 1, 5, 5, 17]),
    (41, &[1, 1, 5, 5, 5]),
    (47, &[1, 1, 7, 11, 19]),
    (55, &[1, 1, 5, 1, 1]),
    (59, &[1, 1, 1, 3, 11]),
    (61, &[1, 3, 5, 5, 31]),
    (67, &[1, 3, 3, 9, 7, 49]),
    (91, &[1, 1, 1, 15, 21, 21]),
    (97, &[1, 3, 1, 13, 27, 49]),
    (103, &[1, 1, 1, 15, 7, 5]),
    (109, &[1, 3, 1, 15, 13, 25]),
    (115, &[1, 1, 5, 5, 19, 61]),
    (131, &[1, 3, 7, 11, 23, 15, 103]),
    (137, &[1, 3, 7, 13, 13, 15, 69]),
    (143, &[1, 1, 3, 13, 7, 35, 63]),
    (145, &[1, 3, 5, 9, 1, 25, 53]),
    (157, &[1, 3, 1, 13, 9, 35, 107]),
];

/// The dimensions of the sequence: inputs up to half of it.
pub const DIMENSIONS: usize = DIRECTIONS.len();

/// Bits of each coordinate.
const BITS: usize = 32;

/// The 95 % normal quantile of the bootstrap half-widths.
pub const Z95: f64 = 1.959_963_984_540_054;

/// The direction numbers `v_1..v_32` of dimension `j` (`v_k / 2^32`).
fn directions(j: usize) -> [u32; BITS] {
    let mut v = [0u32; BITS];
    let (poly, m) = DIRECTIONS[j];
    if j == 0 {
        (0..BITS).for_each(|k| v[k] = 1 << (BITS - 1 - k));
        return v;
    }
    let s = m.len();
    for k in 0..BITS {
        v[k] = match k < s {
            true => m[k] << (BITS - 1 - k),
            false => {
                let mut x = v[k - s] ^ (v[k - s] >> s);
                for i in 1..s {
                    if (poly >> (s - i)) & 1 == 1 {
                        x ^= v[k - i];
                    }
                }
                x
            }
        };
    }
    v
}

/// The first `count` points of the unscrambled Sobol' sequence in
/// `dimension` dimensions (Gray-code order, from the origin, as scipy's
/// `qmc.Sobol(d, scramble=False)`); `None` beyond [`DIMENSIONS`].
pub fn sequence(dimension: usize, count: usize) -> Option<Vec<Vec<f64>>> {
    if dimension > DIMENSIONS {
        return None;
    }
    let v: Vec<[u32; BITS]> = (0..dimension).map(directions).collect();
    let mut x = vec![0u32; dimension];
    let scale = 1.0 / (1u64 << BITS) as f64;
    let mut points = Vec::with_capacity(count);
    for n in 0..count {
        points.push(x.iter().map(|&b| f64::from(b) * scale).collect());
        let c = (!n).trailing_zeros() as usize;
        for (xj, vj) in x.iter_mut().zip(&v) {
            *xj ^= vj[c.min(BITS - 1)];
        }
    }
    Some(points)
}

/// `None` when `base` is a power of two, else the powers of two either
/// side of it: the Sobol' sequence is balanced (each elementary interval
/// holds its share of points) only over `2^m` points, so a base sample count
/// between two powers weights part of the unit cube twice.
///
/// ```
/// use bumpsim_estimate::sobol::unbalanced;
/// assert_eq!(unbalanced(64), None);
/// assert_eq!(unbalanced(100), Some((64, 128)));
/// assert_eq!(unbalanced(17), Some((16, 32)));
/// ```
pub fn unbalanced(base: usize) -> Option<(usize, usize)> {
    if base == 0 || base.is_power_of_two() {
        return None;
    }
    let below = 1usize << (usize::BITS - 1 - base.leading_zeros());
    Some((below, below.saturating_mul(2)))
}

/// One input of the output.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Input {
    /// Its name.
    pub name: String,
    /// How it is distributed.
    pub law: Law,
}

/// How an input is distributed.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Law {
    /// Uniform on `[low, high]`.
    Uniform {
        /// Lower end.
        low: f64,
        /// Upper end.
        high: f64,
    },
    /// Normal (e.g. the logarithm of a log-normal parameter).
    Normal {
        /// Mean.
        mean: f64,
        /// Standard deviation.
        sd: f64,
    },
    /// As these draws (sorted), e.g. a posterior's marginal.
    Draws(Vec<f64>),
    /// `ln f` with the factor `f` uniform on `[low, high]`, `0 < low`
    /// (a parameter uniform on a range, where the inputs are log factors).
    LogOfUniform {
        /// Lower end of the factor.
        low: f64,
        /// Upper end of the factor.
        high: f64,
    },
}

impl Law {
    /// The value at probability `u` in [0, 1] (its quantile function).
    fn at(&self, u: f64) -> f64 {
        match self {
            Law::Uniform { low, high } => low + u * (high - low),
            Law::Normal { mean, sd } => {
                // the sequence's points reach 0: the quantile's ends are ±inf
                let u = u.clamp(f64::EPSILON, 1.0 - f64::EPSILON);
                let unit = statrs::distribution::Normal::standard();
                mean + sd * statrs::distribution::ContinuousCDF::inverse_cdf(&unit, u)
            }
            Law::Draws(sorted) => crate::posterior::quantile(sorted, u),
            Law::LogOfUniform { low, high } => (low + u * (high - low)).ln(),
        }
    }

    /// The value at a standard normal draw `z`: its quantile at `Φ(z)`
    /// (a normal's exactly `mean + sd z`), so a Monte Carlo draw of an
    /// input comes from its law.
    ///
    /// ```
    /// use bumpsim_estimate::sobol::Law;
    /// let factor = Law::LogOfUniform { low: 0.8, high: 1.2 };
    /// assert!((factor.of_normal(0.0).exp() - 1.0).abs() < 1e-12);
    /// assert_eq!(Law::Normal { mean: 0.0, sd: 0.1 }.of_normal(2.0), 0.2);
    /// ```
    pub fn of_normal(&self, z: f64) -> f64 {
        match self {
            Law::Normal { mean, sd } => mean + sd * z,
            _ => {
                let unit = statrs::distribution::Normal::standard();
                self.at(statrs::distribution::ContinuousCDF::cdf(&unit, z))
            }
        }
    }
}

impl Input {
    /// Uniform on `[low, high]`.
    pub fn uniform(name: impl Into<String>, low: f64, high: f64) -> Input {
        Input {
            name: name.into(),
            law: Law::Uniform { low, high },
        }
    }

    /// Normal with `mean` and standard deviation `sd`.
    pub fn normal(name: impl Into<String>, mean: f64, sd: f64) -> Input {
        Input {
            name: name.into(),
            law: Law::Normal { mean, sd },
        }
    }

    /// Distributed as `draws`.
    pub fn draws(name: impl Into<String>, mut draws: Vec<f64>) -> Input {
        draws.sort_by(f64::total_cmp);
        Input {
            name: name.into(),
            law: Law::Draws(draws),
        }
    }

    /// The logarithm of a factor uniform on `[low, high]`, `0 < low < high`.
    pub fn log_of_uniform(name: impl Into<String>, low: f64, high: f64) -> Input {
        Input {
            name: name.into(),
            law: Law::LogOfUniform { low, high },
        }
    }

    /// The value at probability `u` in [0, 1).
    fn at(&self, u: f64) -> f64 {
        self.law.at(u)
    }

    /// Whether its law is usable: a finite, non-empty range or finite draws.
    fn usable(&self) -> bool {
        match &self.law {
            Law::Uniform { low, high } => low.is_finite() && high.is_finite() && low < high,
            Law::Normal { mean, sd } => mean.is_finite() && sd.is_finite() && *sd >= 0.0,
            Law::Draws(d) => !d.is_empty() && d.iter().all(|v| v.is_finite()),
            Law::LogOfUniform { low, high } => {
                low.is_finite() && high.is_finite() && 0.0 < *low && low < high
            }
        }
    }
}

/// How many points, resamples and which seed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Settings {
    /// Base samples N (the output is evaluated `N (d + 2)` times).
    pub base: usize,
    /// Bootstrap resamples.
    pub resamples: usize,
    /// Seed of the resampling.
    pub seed: u64,
}

impl Settings {
    /// `base` samples, 200 resamples, `seed`.
    pub fn new(base: usize, seed: u64) -> Settings {
        Settings {
            base,
            resamples: 200,
            seed,
        }
    }
}

/// The indices of every input.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Indices {
    /// Input names.
    pub names: Vec<String>,
    /// First-order indices `S_i`.
    pub first: Vec<f64>,
    /// Their 95 % bootstrap half-widths.
    pub first_conf: Vec<f64>,
    /// Total indices `S_Ti`.
    pub total: Vec<f64>,
    /// Their 95 % bootstrap half-widths.
    pub total_conf: Vec<f64>,
    /// The output's mean and variance over A and B.
    pub mean: f64,
    /// See `mean`.
    pub variance: f64,
    /// Evaluations of the output, `N (d + 2)`.
    pub evaluations: usize,
}

/// An index as printed, a share of variance within [0, 1]: `0.885 ±
/// 0.365`. An estimate outside is the estimator's sampling error (a share
/// cannot exceed 1 nor fall below 0), so it is printed at the bound with
/// the estimate and its 95 % half-width beside it: `1.000 (est. 1.037 ±
/// 0.040)`; a rounded −0 prints as 0.
///
/// ```
/// use bumpsim_estimate::sobol::share;
/// assert_eq!(share(0.8849, 0.3651), "0.885 ± 0.365");
/// assert_eq!(share(1.037, 0.040), "1.000 (est. 1.037 ± 0.040)");
/// assert_eq!(share(-0.0001, 0.002), "0.000 ± 0.002");
/// ```
pub fn share(index: f64, half_width: f64) -> String {
    let shown = |v: f64| {
        let text = format!("{v:.3}");
        match text.as_str() {
            "-0.000" => "0.000".to_string(),
            _ => text,
        }
    };
    match outside(index) {
        true => format!(
            "{} (est. {} ± {half_width:.3})",
            shown(index.clamp(0.0, 1.0)),
            shown(index)
        ),
        false => format!("{} ± {half_width:.3}", shown(index)),
    }
}

/// Whether an index estimate prints outside [0, 1] (above 1.0005 or below
/// −0.0005): [`share`] clips it, and a table says so ([`CLIPPED`]).
pub fn outside(index: f64) -> bool {
    !(-0.0005..1.0005).contains(&index)
}

/// The note under a table with a clipped index ([`share`]).
pub const CLIPPED: &str = "an index estimated outside [0, 1] is shown at the bound with its estimate ± 95 % half-width (est.): a share of variance lies within [0, 1], the excess is the estimator's sampling error; more base samples narrow it";

/// Why indices cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SobolError {
    /// No input, or more than the sequence's dimensions allow.
    #[error("Sobol indices: {inputs} inputs; 1 to {} are possible", DIMENSIONS / 2)]
    Inputs {
        /// Inputs given.
        inputs: usize,
    },
    /// An input without a usable law.
    #[error(
        "Sobol indices: input '{name}' needs a finite range low < high (0 < low for a factor), a finite normal or finite draws"
    )]
    Law {
        /// The input.
        name: String,
    },
    /// Too few base samples.
    #[error("Sobol indices: {base} base samples; at least 2 are needed")]
    Base {
        /// Given.
        base: usize,
    },
    /// The output is not finite at a point.
    #[error("Sobol indices: the output is {value} at {point:?}")]
    Output {
        /// The point.
        point: Vec<f64>,
        /// The value.
        value: f64,
    },
    /// The output does not vary.
    #[error("Sobol indices: the output is the same ({value}) at every point")]
    Constant {
        /// Its value.
        value: f64,
    },
}

/// The Sobol' indices of `output` over `inputs` (see the module).
pub fn indices(
    inputs: &[Input],
    output: &(dyn Fn(&[f64]) -> f64 + Sync),
    settings: &Settings,
) -> Result<Indices, SobolError> {
    let d = inputs.len();
    if d == 0 || 2 * d > DIMENSIONS {
        return Err(SobolError::Inputs { inputs: d });
    }
    if let Some(bad) = inputs.iter().find(|i| !i.usable()) {
        return Err(SobolError::Law {
            name: bad.name.clone(),
        });
    }
    let n = settings.base;
    if n < 2 {
        return Err(SobolError::Base { base: n });
    }
    let rows = saltelli(inputs, n);
    let values: Vec<f64> = rows.par_iter().map(|x| output(x)).collect();
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        return Err(SobolError::Output {
            point: rows[k].clone(),
            value: values[k],
        });
    }
    summarise(inputs, &values, n, settings)
}

/// The `N (d + 2)` rows: A, B, then `A_B^(i)` for each i.
fn saltelli(inputs: &[Input], n: usize) -> Vec<Vec<f64>> {
    let d = inputs.len();
    let points = sequence(2 * d, n + 1).unwrap_or_default();
    let map = |u: &[f64]| -> Vec<f64> { inputs.iter().zip(u).map(|(x, &u)| x.at(u)).collect() };
    let a: Vec<Vec<f64>> = points[1..].iter().map(|p| map(&p[..d])).collect();
    let b: Vec<Vec<f64>> = points[1..].iter().map(|p| map(&p[d..])).collect();
    let mut rows = a.clone();
    rows.extend(b.iter().cloned());
    for i in 0..d {
        rows.extend(a.iter().zip(&b).map(|(ra, rb)| {
            let mut r = ra.clone();
            r[i] = rb[i];
            r
        }));
    }
    rows
}

/// The indices and their bootstrap half-widths from the outputs.
fn summarise(
    inputs: &[Input],
    values: &[f64],
    n: usize,
    settings: &Settings,
) -> Result<Indices, SobolError> {
    let d = inputs.len();
    // centred on the mean of A and B (as SALib standardises): the same
    // indices, with far less resampling noise on an output far from zero
    let centre = values[..2 * n].iter().sum::<f64>() / (2 * n) as f64;
    let values: Vec<f64> = values.iter().map(|v| v - centre).collect();
    let (fa, fb) = (&values[..n], &values[n..2 * n]);
    let fab = |i: usize| &values[(2 + i) * n..(3 + i) * n];
    let all: Vec<usize> = (0..n).collect();
    let (mean, variance) = moments(fa, fb, &all);
    if variance.is_nan() || variance <= 0.0 {
        return Err(SobolError::Constant {
            value: mean + centre,
        });
    }
    let estimate = |rows: &[usize]| -> Vec<[f64; 2]> {
        let v = moments(fa, fb, rows).1;
        (0..d).map(|i| pair(fa, fb, fab(i), rows, v)).collect()
    };
    let point = estimate(&all);
    let mut draws = Draws::new(settings.seed, 0x5_0B01);
    let resampled: Vec<Vec<usize>> = (0..settings.resamples)
        .map(|_| {
            (0..n)
                .map(|_| ((draws.unit() * n as f64) as usize).min(n - 1))
                .collect()
        })
        .collect();
    let boot: Vec<Vec<[f64; 2]>> = resampled.par_iter().map(|r| estimate(r)).collect();
    let conf = |i: usize, k: usize| Z95 * deviation(boot.iter().map(|b| b[i][k]));
    Ok(Indices {
        names: inputs.iter().map(|i| i.name.clone()).collect(),
        first: point.iter().map(|p| p[0]).collect(),
        first_conf: (0..d).map(|i| conf(i, 0)).collect(),
        total: point.iter().map(|p| p[1]).collect(),
        total_conf: (0..d).map(|i| conf(i, 1)).collect(),
        mean: mean + centre,
        variance,
        evaluations: values.len(),
    })
}

/// Mean and variance of the outputs of A and B at `rows`.
fn moments(fa: &[f64], fb: &[f64], rows: &[usize]) -> (f64, f64) {
    let count = 2.0 * rows.len() as f64;
    let mean = rows.iter().map(|&k| fa[k] + fb[k]).sum::<f64>() / count;
    let square = |v: f64| (v - mean) * (v - mean);
    let variance = rows
        .iter()
        .map(|&k| square(fa[k]) + square(fb[k]))
        .sum::<f64>()
        / count;
    (mean, variance)
}

/// `[S_i, S_Ti]` at `rows` with variance `v`.
fn pair(fa: &[f64], fb: &[f64], fab: &[f64], rows: &[usize], v: f64) -> [f64; 2] {
    let count = rows.len() as f64;
    let first = rows.iter().map(|&k| fb[k] * (fab[k] - fa[k])).sum::<f64>() / count;
    let total = rows.iter().map(|&k| (fa[k] - fab[k]).powi(2)).sum::<f64>() / (2.0 * count);
    [first / v, total / v]
}

/// The sample standard deviation (0 for fewer than two values).
fn deviation(values: impl Iterator<Item = f64>) -> f64 {
    let v: Vec<f64> = values.collect();
    if v.len() < 2 {
        return 0.0;
    }
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A normal input's quantile function: the mean at the median, one
    /// standard deviation at Φ(1), finite at the sequence's 0 and 1.
    #[test]
    fn a_normal_input_has_the_normal_quantiles() {
        let x = Input::normal("x", 2.0, 0.5);
        assert!((x.at(0.5) - 2.0).abs() < 1e-12);
        assert!((x.at(0.841_344_746_068_542_9) - 2.5).abs() < 1e-9);
        assert!(x.at(0.0).is_finite() && x.at(1.0).is_finite() && x.at(0.0) < 0.0);
        assert!(x.usable() && !Input::normal("y", 0.0, f64::NAN).usable());
    }

    /// The logarithm of a uniform factor: `f = e^x1 + 2 e^x2` with factors
    /// uniform on [1, 2] is `u1 + 2 u2` of uniform inputs, whose indices
    /// are (1/5, 4/5) with no interaction; a standard normal draw maps to
    /// the factor's quantile at Φ(z); a range reaching 0 is refused.
    #[test]
    fn the_log_of_a_uniform_factor_has_the_uniform_factor_indices() {
        let inputs = [
            Input::log_of_uniform("x1", 1.0, 2.0),
            Input::log_of_uniform("x2", 1.0, 2.0),
        ];
        let f = |x: &[f64]| x[0].exp() + 2.0 * x[1].exp();
        let s = indices(&inputs, &f, &Settings::new(4096, 1)).unwrap();
        for (got, want) in [
            (s.first[0], 0.2),
            (s.first[1], 0.8),
            (s.total[0], 0.2),
            (s.total[1], 0.8),
        ] {
            assert!((got - want).abs() < 0.01, "{s:?}");
        }
        let law = &inputs[0].law;
        assert!((law.of_normal(1.0).exp() - 1.841_344_746_068_542_9).abs() < 1e-9);
        assert!((law.of_normal(-40.0).exp() - 1.0).abs() < 1e-12);
        assert!(!Input::log_of_uniform("y", 0.0, 1.0).usable());
        assert!(!Input::log_of_uniform("y", 1.2, 0.8).usable());
    }
}
