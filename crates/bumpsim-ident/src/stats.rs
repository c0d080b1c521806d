//! Uncertainty of the estimate from the Jacobian at the optimum.
//!
//! With the Jacobian `J` of the residuals with respect to the log
//! parameters that are neither fixed nor at a bound (q of them), n
//! residuals and `F = Σ r²`: `σ² = F / (n − q)`, `Cov(ln θ) = σ² (JᵀJ)⁻¹`
//! (through the SVD `J = U S Vᵀ`: `(JᵀJ)⁻¹ = V S⁻² Vᵀ`). Standard errors of
//! θ follow by the delta method, `SE(θ) = θ SE(ln θ)`; the 95 % intervals
//! are `θ exp(± t₀.₉₇₅,ₙ₋q SE(ln θ))` (Student t; positive, as θ must be).
//! A small ratio of the smallest to the largest singular value marks a
//! poorly identifiable direction; its largest components are named.
//! Directions whose singular value is below [`RANK_TOLERANCE`] of the
//! largest carry no information at all (the Jacobian is numerically rank
//! deficient): the covariance is the truncated pseudo-inverse over the
//! others, and a parameter with a share of more than [`NULL_SHARE`] in a
//! dropped direction gets no interval, while the parameters outside it keep
//! theirs (before, one free spring left every parameter without one).
//! [`determination`] sorts the parameters into those the data determine (a
//! 95 % interval within a factor [`crate::reduce::SPREAD`]) and those they
//! do not (issue 19), naming the combination they leave freest (the
//! largest shares of the weakest direction); [`Uncertainty::determined`] and
//! [`Uncertainty::weakest_direction`] carry the same for the JSON.

use crate::case::Objective;
use crate::lm::LeastSquares;
use crate::reduce::SPREAD;
use bumpsim_core::model::{parameter_count, parameter_name};
use bumpsim_core::units::format_number;
use nalgebra::DMatrix;
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Singular values below this fraction of the largest are dropped from the
/// covariance (a direction the data do not inform, ≈ 1e6 × the rounding of
/// the Jacobian's columns).
pub const RANK_TOLERANCE: f64 = 1e-10;

/// A parameter whose squared component in a dropped direction exceeds this
/// has no interval (it moves along the direction the data leave free).
pub const NULL_SHARE: f64 = 1e-6;

/// Standard errors, intervals and correlations of the estimate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Uncertainty {
    /// Parameter names, thesis order.
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
    /// Residual standard deviation σ, m.
    pub residual_std: f64,
    /// Degrees of freedom n − q.
    pub degrees_of_freedom: usize,
    /// Singular values of the log-parameter Jacobian, largest first.
    pub singular_values: Vec<f64>,
    /// Largest over smallest singular value.
    pub condition: f64,
    /// Whether the data determine each parameter (thesis order):
    /// `Some(true)` when its 95 % interval lies within a factor
    /// [`SPREAD`], `Some(false)` when it is at a bound, has no interval or
    /// a wider one, `None` when it is fixed ([`is_determined`]).
    pub determined: Vec<Option<bool>>,
    /// The combination of parameters the data inform least: the right
    /// singular vector of the smallest singular value of the Jacobian in
    /// the estimated log parameters (neither fixed nor at a bound), one
    /// entry per parameter, largest share first. Empty when no parameter
    /// is estimated, no degrees of freedom remain, or the Jacobian is zero
    /// or not finite.
    pub weakest_direction: Vec<Share>,
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

/// Whether the data determine parameter `i` of `u`: its 95 % interval
/// within a factor [`SPREAD`] (`Some(true)`), or not: at its bound, without
/// an interval or with a wider one (`Some(false)`); `None` when it is fixed.
pub fn is_determined(u: &Uncertainty, i: usize) -> Option<bool> {
    (!u.fixed[i]).then(|| match (u.at_bound[i], u.ci95[i]) {
        (false, Some([a, b])) => b / a <= SPREAD,
        _ => false,
    })
}

/// Which estimated parameters the data determine — a 95 % interval within
/// a factor [`SPREAD`] — and which they do not (at a bound, no interval, or
/// a wider interval), as one statement with the reason for each; `None`
/// when all are determined.
///
/// ```
/// use bumpsim_ident::stats::{Uncertainty, determination};
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
///     determined: vec![Some(true), Some(false), Some(false)],
///     weakest_direction: vec![],
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
            (Some(false), false, Some([a, b])) => free.push(format!(
                "{name} (95 % interval spans a factor {})",
                format_number(b / a, 4)
            )),
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
    if unresolved && u.condition <= 1e6 {
        if let Some(combination) = combination(&u.weakest_direction) {
            text += &format!("; the direction they leave freest {combination}");
        }
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

/// Uncertainty at free log parameters `p` of `objective`.
pub fn uncertainty(
    objective: &Objective,
    p: &[f64],
    lower: &[f64],
    upper: &[f64],
    dof: usize,
) -> Uncertainty {
    let mut u = intervals(objective, p, lower, upper, dof);
    u.determined = (0..u.names.len()).map(|i| is_determined(&u, i)).collect();
    u
}

/// [`uncertainty`] without the determination.
fn intervals(
    objective: &Objective,
    p: &[f64],
    lower: &[f64],
    upper: &[f64],
    dof: usize,
) -> Uncertainty {
    let total = parameter_count(dof);
    let free = objective.free();
    let (m, q_free) = (objective.residual_count(), free.len());
    let mut r = vec![0.0; m];
    let mut jac = DMatrix::zeros(m, q_free);
    objective.evaluate(p, &mut r, Some(&mut jac));
    let sse: f64 = r.iter().map(|v| v * v).sum();
    let theta = objective.theta(p);
    let names: Vec<String> = (0..total).map(|i| parameter_name(dof, i)).collect();
    let bound_tolerance = 1e-6;
    let at_bound_free: Vec<bool> = (0..q_free)
        .map(|j| p[j] - lower[j] < bound_tolerance || upper[j] - p[j] < bound_tolerance)
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
        warnings: Vec::new(),
        names,
    };
    for (j, &i) in free.iter().enumerate().filter(|(j, _)| at_bound_free[*j]) {
        result.at_bound[i] = true;
        let side = if p[j] - lower[j] < bound_tolerance {
            "lower"
        } else {
            "upper"
        };
        result.warnings.push(format!(
            "{} is at its {side} bound ({}): not identifiable from these data within the bounds",
            result.names[i],
            bumpsim_core::model::format_parameter(dof, i, theta[i])
        ));
    }
    if estimated.is_empty() || result.degrees_of_freedom == 0 {
        return result;
    }
    let je = DMatrix::from_fn(m, estimated.len(), |r, c| jac[(r, estimated[c])]);
    let svd = je.svd(false, true);
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
    let variance = sse / result.degrees_of_freedom as f64;
    result.residual_std = variance.sqrt();
    let k = estimated.len();
    let kept = |s: usize| svd.singular_values[s] > RANK_TOLERANCE * largest;
    if !(largest > 0.0 && largest.is_finite()) {
        result
            .warnings
            .push("the Jacobian is rank deficient: no standard errors".into());
        return result;
    }
    let cov = DMatrix::from_fn(k, k, |a, b| {
        (0..k)
            .filter(|&s| kept(s))
            .map(|s| v_t[(s, a)] * v_t[(s, b)] / svd.singular_values[s].powi(2))
            .sum::<f64>()
            * variance
    });
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
        let interval = [
            theta[i] * (-t * se_log).exp(),
            theta[i] * (t * se_log).exp(),
        ];
        let usable = se_log.is_finite() && interval.iter().all(|v| v.is_finite() && *v > 0.0);
        result.standard_errors[i] = usable.then_some(theta[i] * se_log);
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
            determined: vec![],
            weakest_direction: vec![share("m2", 0.8), share("m1", -0.6)],
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
}
