//! The identification of [`super::barrier`]: a chain with yielding links
//! behind a tabulated front crush zone, from each barrier case's wall
//! force and output motion together, with the test sheet's mass as a
//! stated prior. The search is the linear chain's (the staged multi-start
//! bounded Levenberg–Marquardt of [`bumpsim_estimate::multistart`] on
//! `p = ln θ`) with each channel scaled by its residual at the first
//! start; then, [`POLISHING`] times, the knots move to the reached crush
//! and a polishing run follows with the channels weighted as
//! [`super::weighting`] says (by default a stated model-error floor held
//! fixed; with [`super::weighting::Weighting::Likelihood`] each channel's
//! residual at the optimum; [`super::barrier`] says why). The uncertainty is
//! the shared engine's on the extended residuals; each plastic set's 95 %
//! interval is `±1.96 √(gᵀ Σ g)`, Σ the engine's covariance of the free
//! log parameters (its standard errors and correlations), g exact by dual
//! numbers through the run ([`super::objective::jacobian::tangents`]).

use super::barrier::{
    BarrierLayout, BarrierObjective, BarrierSettings, front_start, motion, plastic_sets, run,
};
use super::objective::frame;
use super::objective::jacobian::{Tangent, tangents};
use super::{LinkIdentError, LinkIdentification, PlasticSet, start_points};
use crate::case::LoadCase;
use bumpsim_core::chain::Frame;
use bumpsim_estimate::lm::{self, LeastSquares};
use bumpsim_estimate::multistart::{self, AllFailed, Search};
use bumpsim_estimate::observer::Observer;
use bumpsim_estimate::prior::{Prior, Priored, moved};
use bumpsim_estimate::uncertainty::{Correlation, Estimated, Uncertainty, uncertainty};
use nalgebra::DMatrix;

/// Re-knotting, re-scaling and polishing rounds after the search.
pub const POLISHING: usize = 3;

/// Identifies the car of [`super::barrier`] from the barrier cases `cases`.
pub fn identify(
    cases: &[LoadCase],
    settings: &BarrierSettings,
    observer: &dyn Observer,
) -> Result<LinkIdentification, LinkIdentError> {
    let links = &settings.links;
    let chain = links.check()?;
    for case in cases {
        case.validate()?;
        if frame(case) != Frame::Forward {
            return Err(LinkIdentError::Settings(format!(
                "load case '{}': the barrier identification needs a car moving into the barrier (force on m1 mostly negative)",
                case.name
            )));
        }
    }
    let Some(first) = cases.first() else {
        return Err(LinkIdentError::Settings("no load case".into()));
    };
    let dof = chain.dof;
    let mass = settings
        .sheet_mass
        .map_or_else(|| links.start[..dof].iter().sum(), |m| m.0);
    let (knots, mut front) = match table_start(&settings.front_start, "front")? {
        Some(given) => given,
        None => front_start(first, mass, settings.knots)?,
    };
    let (path_knots, path) = match (
        settings.path_knots,
        table_start(&settings.path_start, "second path")?,
    ) {
        (0, _) => (vec![], vec![]),
        (_, Some(given)) => given,
        (j, None) => {
            // the two paths share the rigid car's force at the start
            let (at, mut values) = front_start(first, mass, j)?;
            for v in values.iter_mut().chain(front.iter_mut()) {
                *v *= 0.5;
            }
            (at, values)
        }
    };
    let rebound = match (settings.rebound, settings.rebound_start) {
        (Some(mass), _) if mass >= dof => {
            return Err(LinkIdentError::Settings(format!(
                "a rebound link on mass {} of a chain of {dof}",
                mass + 1
            )));
        }
        (Some(_), Some(given)) => given.to_vec(),
        (Some(_), None) => rebound_start(first, mass)?,
        (None, _) => vec![],
    };
    if let ([plateau, slope, gap], None) = (&rebound[..], settings.rebound_start) {
        // the front gives up what the rebound link carries while loading,
        // so the car's loading force starts where it was
        for (value, d) in front.iter_mut().zip(&knots) {
            *value = (*value - plateau.min(slope * (d - gap).max(0.0))).max(0.2 * *value);
        }
    }
    let front = [front, path, rebound].concat();
    let layout = BarrierLayout {
        chain,
        knots,
        path_knots,
        rebound: settings.rebound,
    };
    let (lower_si, upper_si) = {
        let (lo, hi) = layout.bounds();
        let c = chain.count();
        (
            [&links.lower[..], &lo[c..]].concat(),
            [&links.upper[..], &hi[c..]].concat(),
        )
    };
    let start_si = [&links.start[..], &front].concat();
    let fixed = [&links.fixed[..], &vec![None; front.len()]].concat();
    let unit = vec![[1.0, 1.0]; cases.len()];
    let objective = BarrierObjective::new(cases, layout.clone(), &fixed, unit);
    let free = objective.free().to_vec();
    let log = |v: &[f64]| free.iter().map(|&i| v[i].ln()).collect::<Vec<f64>>();
    let (lower, upper) = (log(&lower_si), log(&upper_si));
    let points = start_points(&log(&start_si), (&lower, &upper), links.starts, links.seed);
    let first_p = points[0].clone();
    let failed = || {
        LinkIdentError::from(AllFailed {
            starts: links.starts,
        })
    };
    // the search runs under the scales of the first start's residuals
    // whatever the weighting (a path: searched under fixed floors, a
    // 16-knot NHTSA car stopped at 96.45 % crossmember, 76.37 % force;
    // so, 99.74 % and 91.62 %); the polishing runs under the weighting's
    let given = settings.weighting.fixed(cases)?;
    let scales = objective.channel_scales(&first_p).ok_or_else(failed)?;
    let priors = match settings.sheet_mass {
        Some((centre, spread)) => {
            let terms: Vec<usize> = (0..free.len()).filter(|&j| free[j] < dof).collect();
            match terms.is_empty() {
                true => vec![],
                false => vec![
                    Prior::sum("total mass", terms, centre, spread)
                        .map_err(|e| LinkIdentError::Settings(e.to_string()))?
                        .from_source("the test sheet"),
                ],
            }
        }
        None => vec![],
    };
    let priored = |scales: Vec<[f64; 2]>, layout: &BarrierLayout| {
        let objective = BarrierObjective::new(cases, layout.clone(), &fixed, scales);
        Priored::new(objective, priors.clone(), 1.0)
            .map_err(|e| LinkIdentError::Settings(e.to_string()))
    };
    let problem = priored(scales, &layout)?;
    let search = Search {
        starts: links.starts,
        seed: links.seed,
        solver: links.solver,
        lower: &lower,
        upper: &upper,
        range: (&lower, &upper),
    };
    let found = multistart::search(&|| problem.clone(), points, &search, observer)?;
    // the knots moved to the crush the front reached, the channels' scales
    // at the optimum, and a polishing run with them, [`POLISHING`] times
    let (mut layout, mut p, mut scales) = (layout, found.best().parameters.clone(), vec![]);
    let mut objective_value = found.best().objective;
    for _ in 0..POLISHING {
        let theta = problem.problem().theta(&p);
        (layout, p) = reknotted(&layout, cases, &theta, &free, &lower, &upper)?;
        let objective = BarrierObjective::new(
            cases,
            layout.clone(),
            &fixed,
            scales_or_unit(&scales, cases.len()),
        );
        scales = match &given {
            Some(fixed) => fixed.clone(),
            None => objective.channel_scales(&p).ok_or_else(failed)?,
        };
        let problem = priored(scales.clone(), &layout)?;
        let polished = lm::minimise(&problem, &p, &lower, &upper, &links.solver);
        (p, objective_value) = (polished.parameters, polished.objective);
    }
    let problem = priored(scales.clone(), &layout)?;
    let theta = problem.problem().theta(&p);
    let car = layout.car(&theta)?;
    let mut r = vec![0.0; problem.residual_count()];
    let mut jacobian = DMatrix::zeros(r.len(), free.len());
    if !problem.evaluate(&p, &mut r, Some(&mut jacobian)) {
        return Err(failed());
    }
    let parameters = layout.parameters();
    let series = problem.problem().series();
    let u = uncertainty(&Estimated {
        parameters: &parameters,
        theta: &theta,
        free: &free,
        p: &p,
        bounds: (&lower, &upper),
        residuals: &r,
        jacobian: &jacobian,
        series: &series,
        correlation: Correlation::Spectral,
    });
    let (mut fits, mut force_fits) = (vec![], vec![]);
    for case in cases {
        let response = run(case, &car)?;
        let (a, b) = case.window;
        let y = &response.displacement[case.output_dof - 1];
        fits.push((case.name.clone(), case.fit(y).1));
        let force = bumpsim_estimate::fit::percent(&response.force[a..=b], &case.force[a..=b]);
        force_fits.push((case.name.clone(), force));
    }
    // per case: the front zone (0), the links (1..n−1), the second path
    // (n), the rebound link (after them), on dual numbers
    let per_case = dof + usize::from(car.path().is_some()) + usize::from(car.rebound().is_some());
    let sets = |theta: &[Tangent]| {
        let values = layout.values(&car, theta);
        let mut out = Vec::with_capacity(per_case * cases.len());
        for case in cases {
            let motion = motion(case, &car, &values).ok()?;
            out.extend(plastic_sets(&car, &values, &motion));
        }
        Some(out)
    };
    let (values, gradients) = tangents(&theta, &free, &sets).ok_or_else(failed)?;
    let plastic_sets = intervals(&values, &gradients, &u, &theta, &free)
        .into_iter()
        .enumerate()
        .map(|(at, (value, ci95))| {
            PlasticSet::new(
                cases[at / per_case].name.clone(),
                at % per_case,
                value,
                ci95,
            )
        })
        .collect();
    let c = chain.count();
    let front_link = car.front().cloned();
    let path = car.path().cloned();
    let rebound = car.rebound().cloned();
    Ok(LinkIdentification {
        layout: chain,
        parameters,
        chain: chain.chain(&theta[..c])?,
        theta,
        fits,
        force_fits,
        scales,
        moved: moved(problem.priors(), &p),
        objective: objective_value,
        uncertainty: u,
        plastic_sets,
        front: front_link,
        path,
        rebound,
        starts: found.starts,
    })
}

/// A tabulated link's start: its knots (m) and values `[F1..FK N, k_u
/// N/m]`.
type TableStart = (Vec<f64>, Vec<f64>);

/// A table's start as given, checked; None when not given.
fn table_start(
    given: &Option<TableStart>,
    what: &str,
) -> Result<Option<TableStart>, LinkIdentError> {
    match given {
        Some((knots, values)) if values.len() == knots.len() + 1 && knots.len() >= 2 => {
            Ok(Some((knots.clone(), values.clone())))
        }
        Some((knots, values)) => Err(LinkIdentError::Settings(format!(
            "a {what} start needs 2 knots or more and one force per knot and the unloading slope: {} knots, {} values",
            knots.len(),
            values.len()
        ))),
        None => Ok(None),
    }
}

/// The settings of a second stage: `settings` with a rebound link on
/// mass `mass` (0-based), started from the identification `found`
/// without one (its chain, its front table and unloading slope; a
/// second path and the rebound link start afresh).
pub fn with_rebound(
    found: &LinkIdentification,
    settings: &BarrierSettings,
    mass: usize,
) -> BarrierSettings {
    let mut out = started_at(found, settings);
    out.path_start = None;
    out.rebound = Some(mass);
    out.rebound_start = None;
    out
}

/// `settings` started at the identification `found` (its optimum: the
/// chain, the front table, the second path's and the rebound link's when
/// `settings` has them too), each table read off `found`'s curve at as
/// many knots as `settings` asks over the same reach: with one start, a
/// polishing of `found` under `settings`' objective (does a search miss
/// an optimum it would keep?).
pub fn started_at(found: &LinkIdentification, settings: &BarrierSettings) -> BarrierSettings {
    let mut out = settings.clone();
    let c = found.layout.count();
    out.links.start = found.theta[..c].to_vec();
    out.front_start = found
        .front
        .as_ref()
        .and_then(|front| table_of(front, settings.knots));
    out.path_start = found
        .path
        .as_ref()
        .filter(|_| settings.path_knots > 0)
        .and_then(|path| table_of(&path.link, settings.path_knots));
    out.rebound_start = found
        .rebound
        .as_ref()
        .filter(|_| settings.rebound.is_some())
        .map(|rebound| {
            let law = rebound.link.parameters();
            [law[1], law[0], rebound.gap]
        });
    out
}

/// A tabulated link's start at `count` knots over its reach (its own
/// knots when it has as many), the forces read off its curve, and its
/// unloading slope; None for another kind of link.
fn table_of(link: &bumpsim_core::link::Link, count: usize) -> Option<TableStart> {
    let (bumpsim_core::link::Curve::Table { points }, bumpsim_core::link::Unloading::Slope(slope)) =
        (link.curve(), link.unloading())
    else {
        return None;
    };
    let reach = points.last()?[0];
    let knots: Vec<f64> = match points.len() - 1 == count {
        true => points[1..].iter().map(|p| p[0]).collect(),
        false => (1..=count)
            .map(|i| reach * i as f64 / count as f64)
            .collect(),
    };
    let mut values: Vec<f64> = knots.iter().map(|d| link.curve().force(*d)).collect();
    values.push(slope);
    Some((knots, values))
}

/// A start for a rebound link `[Ft N, kt N/m, gt m]`: a plateau of 0.15
/// times the case's largest force given back over a tenth of the rigid
/// car's largest crush (its mass `mass`), after a gap of a quarter of it.
fn rebound_start(case: &LoadCase, mass: f64) -> Result<Vec<f64>, LinkIdentError> {
    let crush = super::barrier::rigid_crush(case, mass);
    let (a, b) = case.window;
    let reach = crush[a..=b].iter().fold(0.0_f64, |m, x| m.max(*x));
    let peak = case.force[a..=b]
        .iter()
        .fold(0.0_f64, |m, f| m.max(f.abs()));
    if !(reach > 0.0 && peak > 0.0) {
        return Err(LinkIdentError::Settings(format!(
            "load case '{}': a rebound link needs a car that crushes against a force (crush {reach} m, force {peak} N)",
            case.name
        )));
    }
    let plateau = 0.15 * peak;
    Ok(vec![plateau, plateau / (0.1 * reach), 0.25 * reach])
}

/// A value and its 95 % interval, when the covariance gives one.
pub(crate) type WithInterval = (f64, Option<[f64; 2]>);

/// The quantities `values` with their 95 % intervals by the delta method
/// on the covariance of the free log parameters that `u` gives, row i of
/// `gradients` the exact gradient of value i in them
/// ([`super::objective::jacobian::tangents`]). A free
/// parameter the data leave undetermined (no standard error) leaves a
/// value without an interval unless the value does not depend on it at
/// all (its gradient below [`INDIFFERENT`]: a link that never yields
/// leaves its yield force and hardening undetermined and its set at
/// zero whatever they are); its variance then does not enter `gᵀ Σ g`.
pub(crate) fn intervals(
    values: &[f64],
    gradients: &DMatrix<f64>,
    u: &Uncertainty,
    theta: &[f64],
    free: &[usize],
) -> Vec<WithInterval> {
    let (covariance, undetermined) = log_covariance(u, theta, free);
    values
        .iter()
        .enumerate()
        .map(|(at, value)| {
            let g = gradients.row(at).transpose();
            let indifferent = undetermined.iter().all(|&i| g[i].abs() < INDIFFERENT);
            let ci = covariance.as_ref().filter(|_| indifferent).and_then(|c| {
                let var = (g.transpose() * c * &g)[(0, 0)];
                (var.is_finite() && var >= 0.0).then(|| {
                    let half = 1.96 * var.sqrt();
                    [value - half, value + half]
                })
            });
            (*value, ci)
        })
        .collect()
}

/// A value's gradient in an undetermined log parameter below this (m per
/// unit of ln θ) is no dependence: the exact derivative of a quantity
/// that does not move with the parameter is 0 or round-off.
pub const INDIFFERENT: f64 = 1e-7;

/// The covariance of the free log parameters from `u`'s standard errors
/// and correlations, a parameter at a bound held there (no variance, as
/// the engine's intervals hold it), and the free parameters (their
/// positions in `free`) the data do not determine (no standard error:
/// rows and columns of zeros here); None when a correlation between
/// determined ones is missing.
fn log_covariance(
    u: &Uncertainty,
    theta: &[f64],
    free: &[usize],
) -> (Option<DMatrix<f64>>, Vec<usize>) {
    let mut undetermined = vec![];
    let se: Vec<Option<f64>> = free
        .iter()
        .enumerate()
        .map(|(a, &i)| match (u.at_bound[i], u.standard_errors[i]) {
            (true, _) => None,
            (false, Some(s)) => Some(s / theta[i]),
            (false, None) => {
                undetermined.push(a);
                None
            }
        })
        .collect();
    let q = free.len();
    let mut c = DMatrix::zeros(q, q);
    for a in 0..q {
        for b in 0..q {
            if let (Some(sa), Some(sb)) = (se[a], se[b]) {
                let Some(r) = u.correlation[free[a]][free[b]] else {
                    return (None, undetermined);
                };
                c[(a, b)] = r * sa * sb;
            }
        }
    }
    (Some(c), undetermined)
}

/// `scales`, or 1 for every channel when empty.
fn scales_or_unit(scales: &[[f64; 2]], cases: usize) -> Vec<[f64; 2]> {
    match scales.is_empty() {
        true => vec![[1.0, 1.0]; cases],
        false => scales.to_vec(),
    }
}

/// The front's knots (and the second path's) spread again up to 1.02
/// times the largest crush the car `theta` reaches in any case (a knot past
/// it is never loaded, so undetermined), their forces read off its curve:
/// the layout and the free log parameters.
fn reknotted(
    layout: &BarrierLayout,
    cases: &[LoadCase],
    theta: &[f64],
    free: &[usize],
    lower: &[f64],
    upper: &[f64],
) -> Result<(BarrierLayout, Vec<f64>), LinkIdentError> {
    let car = layout.car(theta)?;
    let last = layout.chain.dof - 1;
    let (mut reach, mut body) = (0.0_f64, 0.0_f64);
    for case in cases {
        let response = run(case, &car)?;
        let most = |x: &[f64], from: f64| x.iter().fold(from, |m, v| m.max(*v));
        reach = most(&response.displacement[0], reach);
        body = most(&response.displacement[last], body);
    }
    let mut theta = theta.to_vec();
    let mut out = layout.clone();
    let c = layout.chain.count();
    let k = c + layout.knots.len() + 1;
    if let Some(front) = car.front().filter(|_| reach > 0.0) {
        out.knots = spread(front.curve(), reach, &mut theta[c..k]);
    }
    if let Some(path) = car.path().filter(|_| body > 0.0) {
        let end = k + layout.path_knots.len() + 1;
        out.path_knots = spread(path.link.curve(), body, &mut theta[k..end]);
    }
    let p = free
        .iter()
        .zip(lower.iter().zip(upper))
        .map(|(&i, (l, h))| theta[i].ln().clamp(*l, *h))
        .collect();
    Ok((out, p))
}

/// A table's knots spread up to 1.02 `reach`, as many as `values` holds
/// forces before its unloading slope, the forces read off `curve` into
/// `values`.
fn spread(curve: &bumpsim_core::link::Curve, reach: f64, values: &mut [f64]) -> Vec<f64> {
    let count = values.len().saturating_sub(1);
    let knots: Vec<f64> = (1..=count)
        .map(|i| 1.02 * reach * i as f64 / count as f64)
        .collect();
    for (value, d) in values.iter_mut().zip(&knots) {
        *value = curve.force(*d).max(1e-3 * curve.force(reach));
    }
    knots
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_estimate::uncertainty::{Parameter, Series};

    /// Two log parameters, the second without any effect on the residuals
    /// (undetermined): a value of the first alone keeps its interval
    /// (`1.96 σ_p0` for `p0` itself), one that moves with the second has
    /// none.
    #[test]
    fn an_undetermined_parameter_leaves_only_the_values_that_depend_on_it_without_interval() {
        let parameters = [
            Parameter::with_symbol("a", "-"),
            Parameter::with_symbol("b", "-"),
        ];
        let p = [0.0, 0.0];
        let theta = [1.0, 1.0];
        let rows = 40;
        let jacobian = DMatrix::from_fn(rows, 2, |r, c| match c {
            0 => 1.0 + 0.01 * r as f64,
            _ => 0.0,
        });
        let residuals: Vec<f64> = (0..rows)
            .map(|r| if r % 2 == 0 { 0.1 } else { -0.1 })
            .collect();
        let series = Series::contiguous(std::iter::once(rows));
        let (lower, upper) = ([-5.0, -5.0], [5.0, 5.0]);
        let u = uncertainty(&Estimated {
            parameters: &parameters,
            theta: &theta,
            free: &[0, 1],
            p: &p,
            bounds: (&lower, &upper),
            residuals: &residuals,
            jacobian: &jacobian,
            series: &series,
            correlation: Correlation::Independent,
        });
        assert!(u.standard_errors[0].is_some() && u.standard_errors[1].is_none());
        // the values p0 and p0 + p1 and their gradients
        let gradients = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 1.0, 1.0]);
        let out = intervals(&[p[0], p[0] + p[1]], &gradients, &u, &theta, &[0, 1]);
        let [lo, hi] = out[0].1.expect("the first value does not depend on b");
        let half = 1.96 * u.standard_errors[0].unwrap();
        assert!(
            (hi - lo - 2.0 * half).abs() < 1e-6 * half,
            "{lo} {hi} {half}"
        );
        assert!(out[1].1.is_none(), "{:?}", out[1]);
    }
}
