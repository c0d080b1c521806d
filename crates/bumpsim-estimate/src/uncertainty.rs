//! Uncertainty of an estimate from the Jacobian at the optimum, for any
//! model (its residuals and Jacobian in log parameters).
//!
//! With the Jacobian `J` of the residuals with respect to the log
//! parameters that are neither fixed nor at a bound (q of them), n
//! residuals and `F = Σ r²`: `σ² = κ F / (n − q)`, `Cov(ln θ) = σ² (JᵀJ)⁻¹`
//! (through the SVD `J = U S Vᵀ`: `(JᵀJ)⁻¹ = V S⁻² Vᵀ`). Standard errors of
//! θ follow by the delta method, `SE(θ) = θ SE(ln θ)`; the 95 % intervals
//! are `θ exp(± t₀.₉₇₅,ₙ₋q SE(ln θ))` (Student t; positive, as θ must be).
//!
//! **Correlated residuals.** κ is the variance inflation of the model's
//! [`Correlation`]: 1 for independent errors, `(1 + ρ)/(1 − ρ)` for AR(1)
//! errors with ρ the pooled lag-1 autocorrelation of the residual series
//! ([`Series`]): n samples of an AR(1) series carry only `n (1 − ρ)/(1 + ρ)`
//! independent observations (Bayley & Hammersley 1946). Displacements
//! integrated from accelerations have strongly correlated errors; ρ is
//! reported whatever the model's choice.
//!
//! **Random-walk errors** ([`Correlation::RandomWalk`], issue 44): when
//! each series' error is integrated noise, one factor for every direction
//! is wrong (the fit absorbs the walk's low frequencies along some
//! directions more than others). The covariance is then the sandwich of
//! [`crate::walk`] (`P Jᵀ Σ_walk J P`, `P = (JᵀJ)⁻¹`, the walk's start and
//! bias window given by [`with_walks`]) plus the spectral covariance of
//! what the fit leaves, `τ σ² P`; [`Uncertainty::inflation`] is the
//! largest widening of a variance against independent errors.
//!
//! **Rank.** Directions whose singular value is below [`RANK_TOLERANCE`] of
//! the largest carry no information at all (the Jacobian is numerically rank
//! deficient): the covariance is the truncated pseudo-inverse over the
//! others, and a parameter with a share of more than [`NULL_SHARE`] in a
//! dropped direction gets no interval, while the parameters outside it keep
//! theirs. A small ratio of the smallest to the largest singular value marks
//! a poorly identifiable direction; its largest components are named.
//!
//! **Determination.** [`determination`] sorts the parameters into those the
//! data determine (a 95 % interval within a factor [`SPREAD`]) and those they
//! do not (issue 19), naming the combination they leave freest (the largest
//! shares of the weakest direction); [`Uncertainty::determined`] and
//! [`Uncertainty::weakest_direction`] carry the same as data.

use bumpsim_core::units::{Dimension, format_number, format_quantity};
use nalgebra::DMatrix;
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// A parameter whose 95 % interval spans more than this factor is not
/// determined by the data.
pub const SPREAD: f64 = 1e3;

/// Singular values below this fraction of the largest are dropped from the
/// covariance (a direction the data do not inform, ≈ 1e6 × the rounding of
/// the Jacobian's columns).
pub const RANK_TOLERANCE: f64 = 1e-10;

/// A parameter whose squared component in a dropped direction exceeds this
/// has no interval (it moves along the direction the data leave free).
pub const NULL_SHARE: f64 = 1e-6;

/// A parameter within this distance (log) of a bound is at it.
pub const BOUND_TOLERANCE: f64 = 1e-6;

/// A parameter of a model: its name and how its values print.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// The name (`k1`, `body.yaw_inertia`).
    pub name: String,
    /// Its unit.
    pub unit: ParameterUnit,
    /// How it is searched: in `ln θ` (positive quantities) or as is.
    pub scale: Scale,
}

/// How a parameter is searched and judged.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Scale {
    /// `p = ln θ` (masses, springs, dampers: positive, spanning decades);
    /// determined when its 95 % interval lies within a factor [`SPREAD`].
    Log,
    /// `p = θ` (a position, which may be negative); determined when its 95 %
    /// interval is at most this wide (in θ's unit).
    Linear(f64),
}

/// How a parameter's value prints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParameterUnit {
    /// A physical dimension, printed in its display unit (kg, N/mm, ...).
    Dimension(Dimension),
    /// An SI unit symbol printed as is (`kg·m²`, `-`).
    Symbol(&'static str),
}

impl Parameter {
    /// A parameter of a dimension, searched in `ln θ`.
    pub fn new(name: impl Into<String>, dimension: Dimension) -> Parameter {
        Parameter {
            name: name.into(),
            unit: ParameterUnit::Dimension(dimension),
            scale: Scale::Log,
        }
    }

    /// A parameter printed with an SI symbol, searched in `ln θ`.
    pub fn with_symbol(name: impl Into<String>, symbol: &'static str) -> Parameter {
        Parameter {
            name: name.into(),
            unit: ParameterUnit::Symbol(symbol),
            scale: Scale::Log,
        }
    }

    /// The same parameter searched as is (`p = θ`), determined when its
    /// 95 % interval is at most `width` wide.
    pub fn linear(self, width: f64) -> Parameter {
        Parameter {
            scale: Scale::Linear(width),
            ..self
        }
    }

    /// θ of the search variable `p`.
    pub fn theta(&self, p: f64) -> f64 {
        match self.scale {
            Scale::Log => p.exp(),
            Scale::Linear(_) => p,
        }
    }

    /// The search variable `p` of θ.
    pub fn search(&self, theta: f64) -> f64 {
        match self.scale {
            Scale::Log => theta.ln(),
            Scale::Linear(_) => theta,
        }
    }

    /// `value` (SI) with its unit, four significant digits.
    pub fn format(&self, value: f64) -> String {
        match self.unit {
            ParameterUnit::Dimension(d) => format_quantity(value, d),
            ParameterUnit::Symbol(s) => format!("{} {s}", format_number(value, 4)),
        }
    }
}

/// How the residual errors are modelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Correlation {
    /// Independent errors: σ² = F/(n − q).
    Independent,
    /// First-order autoregressive errors in each residual series: σ²
    /// inflated by `(1 + ρ)/(1 − ρ)`.
    Ar1,
    /// Stationary errors of any correlation: σ² inflated by the integrated
    /// autocorrelation time τ = n / n_eff of the residual series
    /// ([`crate::effective`], Sokal's window; issue 44).
    Spectral,
    /// Each residual series a random walk (integrated stationary noise,
    /// less its mean over a bias window): the sandwich covariance of
    /// [`crate::walk`], weighing each direction by how the walk reaches it
    /// (issue 44).
    RandomWalk,
}

pub use crate::effective::Series;

/// Standard errors, intervals and correlations of the estimate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Uncertainty {
    /// Parameter names, in the model's order.
    pub names: Vec<String>,
    /// Standard errors, SI; `None` for fixed parameters, parameters at a
    /// bound, and when the Jacobian is rank deficient.
    pub standard_errors: Vec<Option<f64>>,
    /// 95 % intervals, SI.
    pub ci95: Vec<Option<[f64; 2]>>,
    /// Parameters at a bound.
    pub at_bound: Vec<bool>,
    /// Parameters held fixed.
    pub fixed: Vec<bool>,
    /// Correlation matrix of the estimated log parameters (p × p; `None`
    /// where a parameter is not estimated).
    pub correlation: Vec<Vec<Option<f64>>>,
    /// Residual standard deviation σ (with the inflation), residual unit.
    pub residual_std: f64,
    /// Degrees of freedom n − q.
    pub degrees_of_freedom: usize,
    /// Singular values of the log-parameter Jacobian, largest first.
    pub singular_values: Vec<f64>,
    /// Largest over smallest singular value.
    pub condition: f64,
    /// How each parameter was searched and is judged.
    pub scales: Vec<Scale>,
    /// Whether the data determine each parameter: `Some(true)` when its 95 %
    /// interval lies within a factor [`SPREAD`], `Some(false)` when it is at
    /// a bound, has no interval or a wider one, `None` when it is fixed
    /// ([`is_determined`]).
    pub determined: Vec<Option<bool>>,
    /// The combination of parameters the data inform least: the right
    /// singular vector of the smallest singular value of the Jacobian in
    /// the estimated log parameters (neither fixed nor at a bound), one
    /// entry per parameter, largest share first. Empty when no parameter
    /// is estimated, no degrees of freedom remain, or the Jacobian is zero
    /// or not finite.
    pub weakest_direction: Vec<Share>,
    /// The error model of the intervals.
    pub error_model: Correlation,
    /// Pooled lag-1 autocorrelation ρ of the residual series, in [0, 1).
    pub residual_correlation: f64,
    /// The variance inflation κ applied: 1, `(1 + ρ)/(1 − ρ)` under AR(1),
    /// τ (spectral), or the largest of any parameter (random walk).
    pub inflation: f64,
    /// Warnings (parameters at bounds, poorly identifiable directions).
    pub warnings: Vec<String>,
}

/// A parameter's share of a direction in log-parameter space.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Share {
    /// The parameter (`k1`).
    pub parameter: String,
    /// Its squared component, 0..1 (the shares of a direction sum to 1).
    pub share: f64,
    /// Its component, −1..1, signed so that the largest is positive:
    /// moving along the direction raises the parameters with a positive
    /// component and lowers those with a negative one in proportion (in
    /// log parameters), e.g. m2 +0.77, m3 −0.64: their ratio.
    pub component: f64,
}

/// An estimate to assess: the model's parameters and where the search
/// ended, with the residuals and their Jacobian there.
#[derive(Debug, Clone, Copy)]
pub struct Estimated<'a> {
    /// Every parameter of the model (fixed ones too), in its order.
    pub parameters: &'a [Parameter],
    /// Their SI values.
    pub theta: &'a [f64],
    /// Indices of the free parameters.
    pub free: &'a [usize],
    /// The free log parameters.
    pub p: &'a [f64],
    /// Their bounds (log).
    pub bounds: (&'a [f64], &'a [f64]),
    /// The residuals at `p`.
    pub residuals: &'a [f64],
    /// Their Jacobian (n × free) at `p`.
    pub jacobian: &'a DMatrix<f64>,
    /// The residual series (for ρ).
    pub series: &'a [Series],
    /// The error model.
    pub correlation: Correlation,
}

/// Whether the data determine parameter `i` of `u`: its 95 % interval
/// within a factor [`SPREAD`] (`Some(true)`), or not: at its bound, without
/// an interval or with a wider one (`Some(false)`); `None` when it is fixed.
pub fn is_determined(u: &Uncertainty, i: usize) -> Option<bool> {
    let scale = u.scales.get(i).copied().unwrap_or(Scale::Log);
    (!u.fixed[i]).then(|| match (u.at_bound[i], u.ci95[i], scale) {
        (false, Some([a, b]), Scale::Log) => b / a <= SPREAD,
        (false, Some([a, b]), Scale::Linear(width)) => b - a <= width,
        _ => false,
    })
}

/// The uncertainty of an estimate (see the module).
///
/// ```
/// use bumpsim_estimate::uncertainty::{Correlation, Estimated, Parameter, Series, uncertainty};
/// use nalgebra::DMatrix;
/// // y = a t fitted at a = 2 on t = 0.1 .. 1: residuals ±0.01, J = ∂r/∂ln a = a t
/// let t: Vec<f64> = (1..=10).map(|k| 0.1 * k as f64).collect();
/// let r: Vec<f64> = (0..10).map(|k| if k % 2 == 0 { 0.01 } else { -0.01 }).collect();
/// let jacobian = DMatrix::from_fn(10, 1, |i, _| 2.0 * t[i]);
/// let u = uncertainty(&Estimated {
///     parameters: &[Parameter::with_symbol("a", "-")],
///     theta: &[2.0],
///     free: &[0],
///     p: &[2f64.ln()],
///     bounds: (&[-10.0], &[10.0]),
///     residuals: &r,
///     jacobian: &jacobian,
///     series: &Series::contiguous([10].into_iter()),
///     correlation: Correlation::Independent,
/// });
/// // SE(a) = σ / √Σt², σ² = Σr²/(n − 1)
/// let sigma = (10.0 * 1e-4 / 9.0f64).sqrt();
/// let se = sigma / t.iter().map(|t| t * t).sum::<f64>().sqrt();
/// assert!((u.standard_errors[0].unwrap() - se).abs() < 1e-12);
/// assert_eq!(u.determined, vec![Some(true)]);
/// ```
pub fn uncertainty(e: &Estimated) -> Uncertainty {
    with_walks(e, &[])
}

/// [`uncertainty`] with the random walks of the series (used by
/// [`Correlation::RandomWalk`]: where each walk starts and where its bias
/// was removed; a series without one walks from its first residual).
pub fn with_walks(e: &Estimated, walks: &[crate::walk::Walk]) -> Uncertainty {
    let mut u = intervals(e, walks);
    u.determined = (0..u.names.len()).map(|i| is_determined(&u, i)).collect();
    u
}

/// The pooled lag-1 autocorrelation of the residual series, clamped to
/// [0, 0.999999] (0 without power).
///
/// ```
/// use bumpsim_estimate::uncertainty::{Series, lag_one};
/// let alternating = [1.0, -1.0, 1.0, -1.0];
/// let one = [Series { start: 0, len: 4, stride: 1 }];
/// assert_eq!(lag_one(&alternating, &one), 0.0);               // negative: clamped
/// let smooth = [1.0, 1.0, 1.0, 1.0];
/// assert!((lag_one(&smooth, &one) - 0.75).abs() < 1e-12);
/// ```
pub fn lag_one(residuals: &[f64], series: &[Series]) -> f64 {
    let (mut lag, mut power) = (0.0, 0.0);
    for s in series {
        let at = |k: usize| residuals[s.start + s.stride * k];
        for k in 0..s.len {
            power += at(k) * at(k);
            if k + 1 < s.len {
                lag += at(k) * at(k + 1);
            }
        }
    }
    match power > 0.0 {
        true => (lag / power).clamp(0.0, 0.999_999),
        false => 0.0,
    }
}

/// [`uncertainty`] without the determination.
fn intervals(e: &Estimated, walks: &[crate::walk::Walk]) -> Uncertainty {
    let total = e.parameters.len();
    let (lower, upper) = e.bounds;
    let (p, free, theta) = (e.p, e.free, e.theta);
    let (m, q_free) = (e.residuals.len(), free.len());
    let sse: f64 = e.residuals.iter().map(|v| v * v).sum();
    let rho = lag_one(e.residuals, e.series);
    let inflation = match e.correlation {
        Correlation::Independent | Correlation::RandomWalk => 1.0,
        Correlation::Ar1 => (1.0 + rho) / (1.0 - rho),
        Correlation::Spectral => {
            crate::effective::of_residuals(
                e.residuals,
                e.series,
                crate::effective::Method::Spectral,
            )
            .time
        }
    };
    let names: Vec<String> = e.parameters.iter().map(|p| p.name.clone()).collect();
    let at_bound_free: Vec<bool> = (0..q_free)
        .map(|j| p[j] - lower[j] < BOUND_TOLERANCE || upper[j] - p[j] < BOUND_TOLERANCE)
        .collect();
    let estimated: Vec<usize> = (0..q_free).filter(|&j| !at_bound_free[j]).collect();
    let mut result = Uncertainty {
        standard_errors: vec![None; total],
        ci95: vec![None; total],
        at_bound: vec![false; total],
        fixed: (0..total).map(|i| !free.contains(&i)).collect(),
        correlation: vec![vec![None; total]; total],
        residual_std: 0.0,
        degrees_of_freedom: m.saturating_sub(estimated.len()),
        singular_values: Vec::new(),
        condition: f64::INFINITY,
        determined: Vec::new(),
        weakest_direction: Vec::new(),
        scales: e.parameters.iter().map(|p| p.scale).collect(),
        error_model: e.correlation,
        residual_correlation: rho,
        inflation,
        warnings: Vec::new(),
        names,
    };
    for (j, &i) in free.iter().enumerate().filter(|(j, _)| at_bound_free[*j]) {
        result.at_bound[i] = true;
        let side = if p[j] - lower[j] < BOUND_TOLERANCE {
            "lower"
        } else {
            "upper"
        };
        result.warnings.push(format!(
            "{} is at its {side} bound ({}): not identifiable from these data within the bounds",
            result.names[i],
            e.parameters[i].format(theta[i])
        ));
    }
    if estimated.is_empty() || result.degrees_of_freedom == 0 {
        return result;
    }
    let je = DMatrix::from_fn(m, estimated.len(), |r, c| e.jacobian[(r, estimated[c])]);
    let svd = je.clone().svd(false, true);
    let Some(v_t) = svd.v_t.as_ref() else {
        return result;
    };
    let mut order: Vec<usize> = (0..estimated.len()).collect();
    order.sort_by(|&a, &b| svd.singular_values[b].total_cmp(&svd.singular_values[a]));
    result.singular_values = order.iter().map(|&k| svd.singular_values[k]).collect();
    let (largest, smallest) = (
        result.singular_values[0],
        *result.singular_values.last().unwrap_or(&0.0),
    );
    result.condition = largest / smallest;
    let variance = sse / result.degrees_of_freedom as f64 * inflation;
    result.residual_std = variance.sqrt();
    let k = estimated.len();
    let kept = |s: usize| svd.singular_values[s] > RANK_TOLERANCE * largest;
    if !(largest > 0.0 && largest.is_finite()) {
        result
            .warnings
            .push("the Jacobian is rank deficient: no standard errors".into());
        return result;
    }
    let pseudo_inverse = DMatrix::from_fn(k, k, |a, b| {
        (0..k)
            .filter(|&s| kept(s))
            .map(|s| v_t[(s, a)] * v_t[(s, b)] / svd.singular_values[s].powi(2))
            .sum::<f64>()
    });
    let cov = match e.correlation {
        Correlation::RandomWalk => {
            let omega2 = crate::walk::increment_variance(e.residuals, e.series);
            let meat = crate::walk::meat(&je, e.series, walks, omega2);
            // the walk's sandwich (what the fit absorbs along the
            // Jacobian) plus the spectral covariance of what it leaves
            let spectral = crate::effective::of_residuals(
                e.residuals,
                e.series,
                crate::effective::Method::Spectral,
            )
            .time;
            let cov =
                &pseudo_inverse * meat * &pseudo_inverse + &pseudo_inverse * (variance * spectral);
            // the largest widening of a standard error's square against
            // independent errors, as the text reports it
            result.inflation = (0..k)
                .filter(|&a| pseudo_inverse[(a, a)] > 0.0)
                .map(|a| cov[(a, a)] / (variance * pseudo_inverse[(a, a)]))
                .fold(1.0, f64::max);
            cov
        }
        _ => pseudo_inverse * variance,
    };
    // a parameter with a share in a dropped direction is not determined
    let determined: Vec<bool> = (0..k)
        .map(|a| {
            let share: f64 = (0..k)
                .filter(|&s| !kept(s))
                .map(|s| v_t[(s, a)].powi(2))
                .sum();
            share <= NULL_SHARE
        })
        .collect();
    let dropped = (0..k).filter(|&s| !kept(s)).count();
    if dropped > 0 {
        result.warnings.push(format!(
            "the Jacobian is rank deficient: {dropped} direction(s) below {RANK_TOLERANCE:.0e} of the largest singular value carry no information; the parameters in them have no interval"
        ));
    }
    let t = StudentsT::new(0.0, 1.0, result.degrees_of_freedom as f64)
        .map_or(1.96, |d| d.inverse_cdf(0.975));
    for (a, &ja) in estimated.iter().enumerate() {
        let i = free[ja];
        let se_log = if determined[a] {
            cov[(a, a)].sqrt()
        } else {
            f64::INFINITY
        };
        let (interval, se) = match e.parameters[i].scale {
            Scale::Log => (
                [
                    theta[i] * (-t * se_log).exp(),
                    theta[i] * (t * se_log).exp(),
                ],
                theta[i] * se_log,
            ),
            Scale::Linear(_) => ([theta[i] - t * se_log, theta[i] + t * se_log], se_log),
        };
        let positive = matches!(e.parameters[i].scale, Scale::Linear(_)) || interval[0] > 0.0;
        let usable = se_log.is_finite() && positive && interval.iter().all(|v| v.is_finite());
        result.standard_errors[i] = usable.then_some(se);
        result.ci95[i] = usable.then_some(interval);
        for (b, &jb) in estimated.iter().enumerate() {
            let both = usable && determined[b];
            result.correlation[i][free[jb]] =
                both.then(|| cov[(a, b)] / (se_log * cov[(b, b)].sqrt()));
        }
    }
    let weakest = order[k - 1];
    let largest_component = (0..k)
        .map(|c| v_t[(weakest, c)])
        .fold(0.0, |a: f64, b| if b.abs() > a.abs() { b } else { a });
    let sign = if largest_component < 0.0 { -1.0 } else { 1.0 };
    let mut shares: Vec<Share> = (0..k)
        .map(|c| Share {
            parameter: result.names[free[estimated[c]]].clone(),
            share: v_t[(weakest, c)].powi(2),
            component: sign * v_t[(weakest, c)],
        })
        .collect();
    shares.sort_by(|a, b| b.share.total_cmp(&a.share));
    result.weakest_direction = shares;
    if result.condition > 1e6 {
        result.warnings.push(format!(
            "poorly identifiable direction (condition number {:.2e}): it {}",
            result.condition,
            combination(&result.weakest_direction).unwrap_or_default()
        ));
    }
    result
}

/// Which estimated parameters the data determine — a 95 % interval within
/// a factor [`SPREAD`] — and which they do not (at a bound, no interval, or
/// a wider interval), as one statement with the reason for each; `None`
/// when all are determined.
///
/// ```
/// use bumpsim_estimate::uncertainty::{Correlation, Uncertainty, determination};
/// let u = Uncertainty {
///     names: vec!["m1".into(), "m2".into(), "k1".into()],
///     standard_errors: vec![None; 3],
///     ci95: vec![Some([9.0, 11.0]), Some([1e-3, 1e6]), None],
///     at_bound: vec![false, false, true],
///     fixed: vec![false; 3],
///     correlation: vec![vec![None; 3]; 3],
///     residual_std: 1e-5,
///     degrees_of_freedom: 100,
///     singular_values: vec![],
///     condition: f64::INFINITY,
///     scales: vec![],
///     determined: vec![Some(true), Some(false), Some(false)],
///     weakest_direction: vec![],
///     error_model: Correlation::Independent,
///     residual_correlation: 0.0,
///     inflation: 1.0,
///     warnings: vec![],
/// };
/// let text = determination(&u).unwrap();
/// assert!(text.starts_with("the data determine m1 "), "{text}");
/// assert!(text.contains("m2 (95 % interval spans a factor 1.000e9)"), "{text}");
/// assert!(text.contains("k1 (at its bound)"), "{text}");
/// ```
pub fn determination(u: &Uncertainty) -> Option<String> {
    let (mut determined, mut free) = (Vec::new(), Vec::new());
    for (i, name) in u.names.iter().enumerate() {
        match (is_determined(u, i), u.at_bound[i], u.ci95[i]) {
            (None, _, _) => {}
            (Some(true), _, _) => determined.push(name.clone()),
            (Some(false), true, _) => free.push(format!("{name} (at its bound)")),
            (Some(false), false, Some([a, b])) => free.push(match u.scales.get(i) {
                Some(Scale::Linear(_)) => {
                    format!("{name} (95 % interval {} wide)", format_number(b - a, 4))
                }
                _ => format!(
                    "{name} (95 % interval spans a factor {})",
                    format_number(b / a, 4)
                ),
            }),
            (Some(false), false, None) => free.push(format!("{name} (no interval)")),
        }
    }
    if free.is_empty() {
        return None;
    }
    let determined = match determined.is_empty() {
        true => "none of the parameters".to_string(),
        false => determined.join(", "),
    };
    let mut text = format!(
        "the data determine {determined} (95 % intervals within a factor {}); they do not determine {}",
        format_number(SPREAD, 4),
        free.join(", ")
    );
    // the direction is of the estimated parameters, and above condition
    // 1e6 the uncertainty's own warning names it already
    let unresolved =
        (0..u.names.len()).any(|i| is_determined(u, i) == Some(false) && !u.at_bound[i]);
    if unresolved
        && u.condition <= 1e6
        && let Some(combination) = combination(&u.weakest_direction)
    {
        text += &format!("; the direction they leave freest {combination}");
    }
    Some(text)
}

/// The largest shares of a direction (at most three, each at least 1 %),
/// with the way each moves: `raises m2 (59 %) and lowers m3 (41 %)`, or
/// `is m5 alone (100 %)`; None when it is empty.
fn combination(direction: &[Share]) -> Option<String> {
    let named: Vec<&Share> = direction
        .iter()
        .take(3)
        .filter(|s| s.share >= 0.01)
        .collect();
    let part = |s: &Share| {
        let way = if s.component >= 0.0 {
            "raises"
        } else {
            "lowers"
        };
        format!("{way} {} ({:.0} %)", s.parameter, 100.0 * s.share)
    };
    match named.as_slice() {
        [] => None,
        [one] => Some(format!(
            "is {} alone ({:.0} %)",
            one.parameter,
            100.0 * one.share
        )),
        [first @ .., last] => Some(format!(
            "{} and {}",
            first.iter().map(|s| part(s)).collect::<Vec<_>>().join(", "),
            part(last)
        )),
    }
}

/// The warnings of an uncertainty: its own (bounds, rank, poorly
/// identifiable directions), then the determination statement.
pub fn warnings(u: &Uncertainty) -> Vec<String> {
    let mut out = u.warnings.clone();
    out.extend(determination(u));
    out
}

/// `u` when the Jacobian could not be evaluated at the optimum: no
/// interval, standard error or correlation, every estimated parameter not
/// determined, and a warning that says why.
pub fn unassessed(u: Uncertainty) -> Uncertainty {
    let n = u.names.len();
    Uncertainty {
        standard_errors: vec![None; n],
        ci95: vec![None; n],
        correlation: vec![vec![None; n]; n],
        determined: u.fixed.iter().map(|f| (!f).then_some(false)).collect(),
        weakest_direction: Vec::new(),
        warnings: vec!["the Jacobian could not be evaluated at the optimum: no intervals".into()],
        ..u
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// m1 determined, m2 with a wide interval, k1 at its bound; the weakest
    /// direction trades m2 against m1.
    fn uncertainty(wide: bool, condition: f64) -> Uncertainty {
        let share = |parameter: &str, component: f64| Share {
            parameter: parameter.into(),
            share: component * component,
            component,
        };
        Uncertainty {
            names: vec!["m1".into(), "m2".into(), "k1".into()],
            standard_errors: vec![None; 3],
            ci95: vec![
                Some([9.0, 11.0]),
                Some([1.0, if wide { 1e6 } else { 2.0 }]),
                None,
            ],
            at_bound: vec![false, false, true],
            fixed: vec![false; 3],
            correlation: vec![vec![None; 3]; 3],
            residual_std: 1e-5,
            degrees_of_freedom: 100,
            singular_values: vec![],
            condition,
            scales: vec![],
            determined: vec![],
            weakest_direction: vec![share("m2", 0.8), share("m1", -0.6)],
            error_model: Correlation::Independent,
            residual_correlation: 0.0,
            inflation: 1.0,
            warnings: vec![],
        }
    }

    #[test]
    fn the_freest_direction_is_named_only_for_an_estimated_undetermined_parameter() {
        let text = determination(&uncertainty(true, 1e4)).unwrap();
        assert!(
            text.ends_with(
                "; the direction they leave freest raises m2 (64 %) and lowers m1 (36 %)"
            ),
            "{text}"
        );
        // only the bound parameter undetermined: the direction (of m1, m2)
        // is not what is free
        let text = determination(&uncertainty(false, 1e4)).unwrap();
        assert!(
            text.ends_with("they do not determine k1 (at its bound)"),
            "{text}"
        );
        // above condition 1e6 the uncertainty's warning names it instead
        let text = determination(&uncertainty(true, 1e7)).unwrap();
        assert!(!text.contains("freest"), "{text}");
        let u = uncertainty(true, 1e4);
        let flags: Vec<_> = (0..3).map(|i| is_determined(&u, i)).collect();
        assert_eq!(flags, vec![Some(true), Some(false), Some(false)]);
    }

    /// y = θ0 x + θ1 on a line: the intervals of a linear model in log
    /// parameters against the textbook covariance σ² (XᵀX)⁻¹ (delta method
    /// at θ: SE(ln θ) = SE(θ)/θ), and AR(1) inflation from ρ.
    #[test]
    fn intervals_match_the_linear_least_squares_covariance() {
        let (a, b) = (2.0f64, 3.0f64);
        let x: Vec<f64> = (0..20).map(|k| k as f64 * 0.1).collect();
        let noise: Vec<f64> = (0..20)
            .map(|k| if k % 2 == 0 { 0.01 } else { -0.013 })
            .collect();
        let residuals = noise.clone();
        // J in ln θ: ∂r/∂ln a = a x, ∂r/∂ln b = b
        let jac = DMatrix::from_fn(20, 2, |r, c| if c == 0 { a * x[r] } else { b });
        let params = [
            Parameter::with_symbol("a", "-"),
            Parameter::with_symbol("b", "-"),
        ];
        let series = [Series {
            start: 0,
            len: 20,
            stride: 1,
        }];
        let e = Estimated {
            parameters: &params,
            theta: &[a, b],
            free: &[0, 1],
            p: &[a.ln(), b.ln()],
            bounds: (&[-50.0, -50.0], &[50.0, 50.0]),
            residuals: &residuals,
            jacobian: &jac,
            series: &series,
            correlation: Correlation::Independent,
        };
        let u = super::uncertainty(&e);
        let design = DMatrix::from_fn(20, 2, |r, c| if c == 0 { x[r] } else { 1.0 });
        let sigma2 = noise.iter().map(|v| v * v).sum::<f64>() / 18.0;
        let cov = (design.transpose() * &design).try_inverse().unwrap() * sigma2;
        assert!((u.standard_errors[0].unwrap() - cov[(0, 0)].sqrt()).abs() < 1e-12);
        assert!((u.standard_errors[1].unwrap() - cov[(1, 1)].sqrt()).abs() < 1e-12);
        assert_eq!(u.determined, vec![Some(true), Some(true)]);
        assert_eq!(u.inflation, 1.0);
        // alternating residuals: no positive correlation, no inflation
        let ar1 = super::uncertainty(&Estimated {
            correlation: Correlation::Ar1,
            ..e
        });
        assert_eq!(ar1.inflation, 1.0);
        assert_eq!(ar1.residual_correlation, 0.0);
    }
}
