//! Stated priors: what an engineer knows of a parameter before the test
//! (the test sheet's mass, a yaw inertia from the car's geometry, a tyre's
//! grip), as Gaussian priors on `ln θ` added to any least-squares problem
//! (issue 44, item 3).
//!
//! A prior on `v(p) = ln Σ_{i∈S} e^{p_i}` (one parameter, or the sum of
//! several: a total mass) with centre `c` and spread `s` (the standard
//! deviation of `ln θ`, ≈ a relative spread: 0.02 is ±2 %) adds the
//! residual `r = σ (v(p) − ln c)/s` to the problem's, where σ is the noise
//! of one of the problem's residuals ([`noise`]). Minimising
//! `F + σ² Σ z²` with `z = (v − ln c)/s` is then maximising the posterior
//! `−F/(2σ²) − Σ z²/2` (Gaussian errors, log-normal priors; Tarantola 2005,
//! ch. 3), and the problem's uncertainty ([`crate::uncertainty`]) taken over
//! the extended residuals is the Laplace approximation of that posterior:
//! `Cov(ln θ) = σ² (JᵀJ + σ² Σ g gᵀ / s²)⁻¹`, `g = ∇v`.
//!
//! A ratio prior ([`Prior::ratio`]) is the same on `v(p) = p_i − p_j`,
//! `ln(θ_i/θ_j)`: what an engineer knows of two parameters' ratio and not
//! of their level (a car's left and right crash boxes are mirror images of
//! one part: their stiffnesses' ratio is near 1, whatever the stiffness);
//! its gradient is `+1` on `i`, `−1` on `j`. In general `v` is
//! `ln Σ_{i∈S} e^{p_i} − ln Σ_{j∈L} e^{p_j}` ([`Prior::less`]).
//!
//! The problem's own objective is untouched: [`Priored`] wraps it. Each
//! prior is reported with how far the data moved the parameter from it,
//! `z` in prior standard deviations ([`Moved`]): |z| above
//! [`MOVED_FAR`] says the data and the prior disagree.
//!
//! ```
//! use bumpsim_estimate::lm::{LeastSquares, minimise, Settings};
//! use bumpsim_estimate::prior::{Prior, Priored, moved};
//! use nalgebra::DMatrix;
//! /// r = (p0 + p1 − 1): only the sum is determined
//! struct Sum;
//! impl LeastSquares for Sum {
//!     fn residual_count(&self) -> usize { 1 }
//!     fn parameter_count(&self) -> usize { 2 }
//!     fn evaluate(&self, p: &[f64], r: &mut [f64], j: Option<&mut DMatrix<f64>>) -> bool {
//!         r[0] = p[0] + p[1] - 1.0;
//!         if let Some(j) = j { j[(0, 0)] = 1.0; j[(0, 1)] = 1.0; }
//!         true
//!     }
//! }
//! // a prior θ0 = e^0.2 ± 1 % separates them
//! let prior = Prior::single("a", 0, 0.2f64.exp(), 0.01).unwrap();
//! let problem = Priored::new(Sum, vec![prior.clone()], 0.1).unwrap();
//! let out = minimise(&problem, &[0.0, 0.0], &[-5.0; 2], &[5.0; 2], &Settings::default());
//! assert!((out.parameters[0] - 0.2).abs() < 1e-3 && (out.parameters[1] - 0.8).abs() < 1e-3);
//! assert!(moved(&[prior], &out.parameters)[0].z.abs() < 0.1);
//! ```

use crate::lm::LeastSquares;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// A prior's |z| above this: the data moved the parameter far from it
/// (a 95 % two-sided disagreement).
pub const MOVED_FAR: f64 = 2.0;

/// A parameter whose posterior standard deviation of ln θ exceeds this
/// fraction of its prior's spread is informed by its prior alone: the data
/// carry less than half of its information (`1/s_post² < 2/s²`).
pub const PRIOR_ONLY: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// A prior that cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PriorError {
    /// Its centre is outside [`CENTRE_RANGE`].
    #[error("prior '{name}': centre {value:?} must be from 1e-12 to 1e15 (SI, the search's range)")]
    Centre {
        /// The prior's name.
        name: String,
        /// The value given.
        value: f64,
    },
    /// Its spread is outside [`SPREAD_RANGE`].
    #[error(
        "prior '{name}': spread {value:?} must be from 1e-6 to 100 (the standard deviation of ln θ, e.g. 0.1 for ±10 %)"
    )]
    Spread {
        /// The prior's name.
        name: String,
        /// The value given.
        value: f64,
    },
    /// It names no parameter, or one the problem does not have.
    #[error("prior '{name}': parameter index {index} outside the problem's {count} parameters")]
    Index {
        /// The prior's name.
        name: String,
        /// The index given.
        index: usize,
        /// The problem's parameter count.
        count: usize,
    },
    /// The noise scale is not finite and positive.
    #[error("the priors' noise scale {value:?} must be finite and positive")]
    Noise {
        /// The value given.
        value: f64,
    },
}

/// The centres a prior may have, SI: the range the searches work in
/// (issue 44's hostile pass: a centre of 1e300 kg·m² ran to exit 0 with the
/// car at its bounds).
pub const CENTRE_RANGE: std::ops::RangeInclusive<f64> = 1e-12..=1e15;

/// The spreads (sd of ln θ) a prior may have: below 1e-6 (a parameter
/// known to a millionth: fix it instead) its weight overflowed the
/// residuals (1e-300 failed every start, "check the forces"); above 100
/// (a factor e^100 either way) it says nothing (write "none").
pub const SPREAD_RANGE: std::ops::RangeInclusive<f64> = 1e-6..=100.0;

/// A Gaussian prior on `ln Σ_{i∈terms} θ_i` (see the module).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Prior {
    /// Its name (`total_mass`, `body.yaw_inertia`).
    pub name: String,
    /// The log parameters whose values are summed (one: a prior on it).
    pub terms: Vec<usize>,
    /// The log parameters whose values' sum divides the terms' (empty
    /// but for a ratio prior, [`Prior::ratio`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub less: Vec<usize>,
    /// The centre, SI (> 0; a ratio's is dimensionless).
    pub centre: f64,
    /// The standard deviation of the log, ≈ relative (> 0).
    pub spread: f64,
    /// Where it comes from, for the report (`the test sheet`).
    pub source: String,
}

impl Prior {
    /// A prior on the sum of the parameters `terms`, checked.
    pub fn sum(
        name: impl Into<String>,
        terms: Vec<usize>,
        centre: f64,
        spread: f64,
    ) -> Result<Prior, PriorError> {
        let name = name.into();
        if !CENTRE_RANGE.contains(&centre) {
            return Err(PriorError::Centre {
                name,
                value: centre,
            });
        }
        if !SPREAD_RANGE.contains(&spread) {
            return Err(PriorError::Spread {
                name,
                value: spread,
            });
        }
        if terms.is_empty() {
            return Err(PriorError::Index {
                name,
                index: 0,
                count: 0,
            });
        }
        Ok(Prior {
            name,
            terms,
            less: Vec::new(),
            centre,
            spread,
            source: String::new(),
        })
    }

    /// A prior on parameter `index` alone.
    pub fn single(
        name: impl Into<String>,
        index: usize,
        centre: f64,
        spread: f64,
    ) -> Result<Prior, PriorError> {
        Prior::sum(name, vec![index], centre, spread)
    }

    /// A prior on the ratio `θ_numerator/θ_denominator` (a difference of
    /// their logs; see the module), checked: the two must differ.
    pub fn ratio(
        name: impl Into<String>,
        numerator: usize,
        denominator: usize,
        centre: f64,
        spread: f64,
    ) -> Result<Prior, PriorError> {
        let prior = Prior::single(name, numerator, centre, spread)?;
        if numerator == denominator {
            return Err(PriorError::Index {
                name: prior.name,
                index: denominator,
                count: 0,
            });
        }
        Ok(Prior {
            less: vec![denominator],
            ..prior
        })
    }

    /// Whether it is a prior on a ratio (its centre dimensionless).
    pub fn is_ratio(&self) -> bool {
        !self.less.is_empty()
    }

    /// The same prior, its source named.
    pub fn from_source(self, source: impl Into<String>) -> Prior {
        Prior {
            source: source.into(),
            ..self
        }
    }

    /// `v(p) = ln Σ e^{p_i}` over the terms less the same over
    /// [`Prior::less`], and its gradient (index, entry): the shares
    /// `e^{p_i}/Σ`, negative for `less`), stably.
    fn value(&self, p: &[f64]) -> (f64, Vec<(usize, f64)>) {
        let (v, mut gradient) = log_sum(&self.terms, p);
        if self.less.is_empty() {
            return (v, gradient);
        }
        let (w, less) = log_sum(&self.less, p);
        gradient.extend(less.into_iter().map(|(i, s)| (i, -s)));
        (v - w, gradient)
    }

    /// How many prior standard deviations `p` lies from the centre.
    pub fn z(&self, p: &[f64]) -> f64 {
        (self.value(p).0 - self.centre.ln()) / self.spread
    }
}

/// `ln Σ e^{p_i}` over `terms` and its shares `e^{p_i}/Σ`, stably.
fn log_sum(terms: &[usize], p: &[f64]) -> (f64, Vec<(usize, f64)>) {
    let top = terms
        .iter()
        .map(|&i| p[i])
        .fold(f64::NEG_INFINITY, f64::max);
    let weights: Vec<f64> = terms.iter().map(|&i| (p[i] - top).exp()).collect();
    let total: f64 = weights.iter().sum();
    (
        top + total.ln(),
        terms
            .iter()
            .zip(&weights)
            .map(|(&i, w)| (i, w / total))
            .collect(),
    )
}

/// A problem with priors: its residuals followed by one per prior.
#[derive(Debug, Clone)]
pub struct Priored<P> {
    problem: P,
    priors: Vec<Prior>,
    noise: f64,
}

impl<P: LeastSquares> Priored<P> {
    /// `problem` with `priors`, each residual `noise · z` (`noise`: the
    /// standard deviation of one of the problem's residuals, [`noise`]).
    pub fn new(problem: P, priors: Vec<Prior>, noise: f64) -> Result<Priored<P>, PriorError> {
        let count = problem.parameter_count();
        if !(noise.is_finite() && noise > 0.0) {
            return Err(PriorError::Noise { value: noise });
        }
        for prior in &priors {
            if let Some(&index) = prior.terms.iter().chain(&prior.less).find(|&&i| i >= count) {
                return Err(PriorError::Index {
                    name: prior.name.clone(),
                    index,
                    count,
                });
            }
        }
        Ok(Priored {
            problem,
            priors,
            noise,
        })
    }

    /// `problem` without priors (its own residuals only).
    pub fn none(problem: P) -> Priored<P> {
        Priored {
            problem,
            priors: Vec::new(),
            noise: 1.0,
        }
    }

    /// The wrapped problem.
    pub fn problem(&self) -> &P {
        &self.problem
    }

    /// The priors.
    pub fn priors(&self) -> &[Prior] {
        &self.priors
    }

    /// The noise scale of the priors' residuals.
    pub fn noise(&self) -> f64 {
        self.noise
    }

    /// Writes the priors' residuals after the problem's `m` and, when
    /// asked, their Jacobian rows; returns the rows' gradients.
    fn rows(&self, p: &[f64], residuals: &mut [f64]) -> Vec<(f64, Vec<(usize, f64)>)> {
        let m = self.problem.residual_count();
        self.priors
            .iter()
            .enumerate()
            .map(|(k, prior)| {
                let (v, gradient) = prior.value(p);
                let factor = self.noise / prior.spread;
                residuals[m + k] = factor * (v - prior.centre.ln());
                let row = gradient.into_iter().map(|(i, s)| (i, factor * s)).collect();
                (residuals[m + k], row)
            })
            .collect()
    }
}

impl<P: LeastSquares> LeastSquares for Priored<P> {
    fn residual_count(&self) -> usize {
        self.problem.residual_count() + self.priors.len()
    }

    fn parameter_count(&self) -> usize {
        self.problem.parameter_count()
    }

    fn evaluate(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        jacobian: Option<&mut DMatrix<f64>>,
    ) -> bool {
        let (m, n) = (self.problem.residual_count(), self.parameter_count());
        let ok = match jacobian {
            None => self.problem.evaluate(p, &mut residuals[..m], None),
            Some(jac) => {
                let mut inner = DMatrix::zeros(m, n);
                let ok = self
                    .problem
                    .evaluate(p, &mut residuals[..m], Some(&mut inner));
                jac.fill(0.0);
                jac.rows_mut(0, m).copy_from(&inner);
                let rows = self.rows(p, residuals);
                for (k, (_, row)) in rows.into_iter().enumerate() {
                    for (i, d) in row {
                        jac[(m + k, i)] += d;
                    }
                }
                return ok;
            }
        };
        self.rows(p, residuals);
        ok
    }

    fn normal(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        jtj: &mut DMatrix<f64>,
        gradient: &mut DVector<f64>,
    ) -> bool {
        let m = self.problem.residual_count();
        let ok = self.problem.normal(p, &mut residuals[..m], jtj, gradient);
        for (r, row) in self.rows(p, residuals) {
            for &(i, a) in &row {
                gradient[i] += r * a;
                for &(j, b) in &row {
                    jtj[(i, j)] += a * b;
                }
            }
        }
        ok
    }

    /// The problem's `Jᵀv` on its residuals plus the priors' rows'.
    fn transposed(&self, p: &[f64], v: &[f64], product: &mut DVector<f64>) -> bool {
        let m = self.problem.residual_count();
        if v.len() != self.residual_count() || !self.problem.transposed(p, &v[..m], product) {
            return false;
        }
        let mut scratch = vec![0.0; self.residual_count()];
        for (k, (_, row)) in self.rows(p, &mut scratch).into_iter().enumerate() {
            for (i, a) in row {
                product[i] += a * v[m + k];
            }
        }
        true
    }
}

/// The noise of one residual the priors weigh against: `√(κ F/(n − q))`
/// with F the problem's own objective, n its residuals, q its parameters
/// and κ the variance inflation of its correlated residuals
/// ([`crate::uncertainty::Uncertainty::inflation`]): the σ of the
/// problem's uncertainty, so that the covariance of the priored problem is
/// the posterior's. A floor keeps it positive on an exact fit.
pub fn noise(objective: f64, residuals: usize, parameters: usize, inflation: f64) -> f64 {
    let dof = residuals.saturating_sub(parameters).max(1) as f64;
    let variance = inflation.max(1.0) * objective / dof;
    match variance.is_finite() && variance > 0.0 {
        true => variance.sqrt(),
        false => f64::MIN_POSITIVE.sqrt(),
    }
}

/// A prior and where the data left its parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Moved {
    /// The prior's name.
    pub name: String,
    /// Its centre, SI.
    pub centre: f64,
    /// Its spread (standard deviation of the log).
    pub spread: f64,
    /// Where it comes from.
    pub source: String,
    /// Whether it is a prior on a ratio ([`Prior::ratio`]).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub ratio: bool,
    /// The estimate (of the sum, for a prior on several parameters), SI.
    pub estimate: f64,
    /// How far the data moved it, in prior standard deviations,
    /// `(ln θ̂ − ln c)/s`.
    pub z: f64,
}

/// Each prior with the estimate at `p` and how far the data moved it.
pub fn moved(priors: &[Prior], p: &[f64]) -> Vec<Moved> {
    priors
        .iter()
        .map(|prior| Moved {
            name: prior.name.clone(),
            centre: prior.centre,
            spread: prior.spread,
            source: prior.source.clone(),
            ratio: prior.is_ratio(),
            estimate: prior.value(p).0.exp(),
            z: prior.z(p),
        })
        .collect()
}

/// A spread (sd of ln θ) as the prior lines print it: three decimals from
/// 0.01 on (`0.010`, `1.151`), three significant digits below, so that a
/// tight prior reads `1.00e-6` rather than `0.000`.
pub fn spread_text(spread: f64) -> String {
    match spread >= 0.01 {
        true => format!("{spread:.3}"),
        false => bumpsim_core::units::format_number(spread, 3),
    }
}

/// One line per prior: `prior body.yaw_inertia: 2137 ± 20 % (the car's
/// geometry) -> 2290 (moved +0.36 sd)`, a warning where |z| > [`MOVED_FAR`];
/// values printed by `format` (the model's units).
pub fn text(moved: &[Moved], format: &dyn Fn(&str, f64) -> String) -> String {
    moved
        .iter()
        .map(|m| {
            let source = match m.source.is_empty() {
                true => String::new(),
                false => format!(" ({})", m.source),
            };
            let far = match m.z.abs() > MOVED_FAR {
                true => ": the data disagree with the prior",
                false => "",
            };
            let (kind, value): (&str, &dyn Fn(f64) -> String) = match m.ratio {
                true => ("left/right ratio ", &|v| format!("{v:.3}")),
                false => ("", &|v| format(&m.name, v)),
            };
            format!(
                "prior {}: {kind}{} ± {} (ln){source} -> {} (moved {:+.2} sd){far}\n",
                m.name,
                value(m.centre),
                spread_text(m.spread),
                value(m.estimate),
                m.z
            )
        })
        .collect()
}

/// [`text`] indented by two spaces, each value printed in its parameter's
/// unit (a sum's prior, named by no parameter, as a mass): the lines both
/// cars' summaries print; empty without any prior.
pub fn indented_text(moved: &[Moved], parameters: &[crate::uncertainty::Parameter]) -> String {
    use bumpsim_core::units::{Dimension, format_quantity};
    let format = |name: &str, value: f64| match parameters.iter().find(|p| p.name == name) {
        Some(p) => p.format(value),
        None => format_quantity(value, Dimension::Mass),
    };
    text(moved, &format)
        .lines()
        .map(|l| format!("  {l}\n"))
        .collect()
}

/// The priors on one parameter each whose parameter the data hardly
/// inform: its posterior standard deviation of ln θ (`log_sd`, by
/// parameter; `None`: none) above [`PRIOR_ONLY`] of the prior's spread.
/// Returns the parameter's index and the prior.
pub fn prior_only<'a>(priors: &'a [Prior], log_sd: &[Option<f64>]) -> Vec<(usize, &'a Prior)> {
    priors
        .iter()
        .filter(|prior| !prior.is_ratio())
        .filter_map(|prior| match prior.terms.as_slice() {
            [i] => log_sd
                .get(*i)
                .copied()
                .flatten()
                .filter(|sd| *sd > PRIOR_ONLY * prior.spread)
                .map(|_| (*i, prior)),
            _ => None,
        })
        .collect()
}

/// The warnings of priors the data moved by more than [`MOVED_FAR`].
pub fn warnings(moved: &[Moved]) -> Vec<String> {
    moved
        .iter()
        .filter(|m| m.z.abs() > MOVED_FAR)
        .map(|m| {
            format!(
                "prior {}: the data moved it {:+.1} prior standard deviations (centre {:.4e}, estimate {:.4e}): the data and the prior disagree",
                m.name, m.z, m.centre, m.estimate
            )
        })
        .collect()
}

/// The priors' information on the free log parameters `p` (q of them):
/// `Σ g gᵀ / s²`, `g = ∇v` (see the module).
pub fn information(priors: &[Prior], p: &[f64]) -> DMatrix<f64> {
    let mut out = DMatrix::zeros(p.len(), p.len());
    for prior in priors {
        let (_, gradient) = prior.value(p);
        let weight = prior.spread.powi(-2);
        for &(i, a) in &gradient {
            for &(j, b) in &gradient {
                out[(i, j)] += weight * a * b;
            }
        }
    }
    out
}

/// `u`, the data's uncertainty of the estimate `theta` (free log
/// parameters `p`, the model's parameters `free`), with the priors'
/// information added: `Cov = (C⁻¹ + Σ g gᵀ/s²)⁻¹` over the parameters that
/// have a standard error (C their data covariance, from the standard
/// errors and correlations; the Laplace approximation of the posterior
/// when the data's covariance is not `σ² (JᵀJ)⁻¹`, e.g. a random walk's
/// sandwich). Standard errors, 95 % intervals (the same quantile) and
/// correlations follow; `u` is returned as is when C cannot be inverted.
pub fn with_priors(
    mut u: crate::uncertainty::Uncertainty,
    priors: &[Prior],
    theta: &[f64],
    free: &[usize],
    p: &[f64],
) -> crate::uncertainty::Uncertainty {
    let known: Vec<(usize, usize, f64)> = free
        .iter()
        .enumerate()
        .filter_map(|(j, &i)| u.standard_errors[i].map(|se| (j, i, se / theta[i])))
        .collect();
    let k = known.len();
    let data = DMatrix::from_fn(k, k, |a, b| {
        let (ia, ib) = (known[a].1, known[b].1);
        let rho = if a == b {
            Some(1.0)
        } else {
            u.correlation[ia][ib]
        };
        rho.unwrap_or(0.0) * known[a].2 * known[b].2
    });
    let prior = information(priors, p);
    let precision = match data.try_inverse() {
        Some(inverse) => inverse + DMatrix::from_fn(k, k, |a, b| prior[(known[a].0, known[b].0)]),
        None => return u,
    };
    let Some(cov) = precision.try_inverse() else {
        return u;
    };
    for (a, &(_, i, log_se)) in known.iter().enumerate() {
        let sd = cov[(a, a)].sqrt();
        let quantile = u.ci95[i].map_or(1.96, |[_, high]| (high / theta[i]).ln() / log_se);
        u.standard_errors[i] = Some(theta[i] * sd);
        u.ci95[i] = Some([
            theta[i] * (-quantile * sd).exp(),
            theta[i] * (quantile * sd).exp(),
        ]);
        for (b, &(_, ib, _)) in known.iter().enumerate() {
            u.correlation[i][ib] = Some(cov[(a, b)] / (sd * cov[(b, b)].sqrt()));
        }
    }
    u.determined = (0..u.names.len())
        .map(|i| crate::uncertainty::is_determined(&u, i))
        .collect();
    u
}

#[cfg(test)]
mod tests;
