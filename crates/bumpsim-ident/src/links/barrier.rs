//! The car with yielding links identified as it ran into the barrier
//! (issue 46's acceptance): the model the forward run uses is the model
//! fitted, and both the barrier's load cells and the vehicle's
//! accelerometers enter the likelihood.
//!
//! Why not the force-driven chain ([`super::identify`]): applying the
//! measured barrier force to m1 lets m1 and the first link do anything
//! that moves the output mass right. On NHTSA 10146 its best fit puts m1
//! at its lower bound and throws it about a metre through its link (m1
//! bounces off the load while the prescribed force keeps pushing), so a
//! front crush zone read off m1's travel ([`super::front`]) rebuilds a
//! barrier force that fits 1.4 % and a crossmember ΔV 20 % off.
//!
//! Here the car is the chain of [`super::Layout`] behind a front crush
//! zone (Kamal 1970) between the wall and m1: a tabulated loading curve
//! `F_f(δ)` through K knots at fixed crush `δ_i = i D / K` (D: the crush
//! of the rigid car, `max_t [V t + ∫∫ F/M]`, times [`REACH`]) with
//! forces `Ff1..FfK` and an unloading slope `kf` (N/m). Driven by the
//! wall ([`bumpsim_core::chain::Drive::Barrier`]) at the case's speed,
//! it gives the wall force and the output mass's motion, and the
//! residuals of case l are
//!
//! ```text
//! r = [ (F_sim − F_meas)_k / s_F,l ;  (y_sim − y_meas)_k / s_y,l ]
//! ```
//!
//! over its window (y in the case's domain).
//!
//! A second load path ([`BarrierLayout::path_knots`], Kamal's parallel
//! paths; [`bumpsim_core::chain::Chain::with_path`]) adds a tabulated
//! crush link from the last mass (the body) into the wall, J knots of the
//! body's crush with forces `Fp1..FpJ` and an unloading slope `kp`; the
//! front zone on m1 then plays the engine's path (its table may stay low
//! over a gap), and the wall force is the sum of both. `s_F` and `s_y` are each
//! channel's error scale ([`super::weighting`]): by default its noise and
//! a stated model-error floor (10 % of the measured wall force's spread,
//! 1 % of the output's: [`super::weighting::FLOOR`]), held fixed, so that
//! each channel's misfit counts against the error stated for it. The model
//! error, not the sensor's pre-trigger noise, dominates both channels:
//! weighting by pre-trigger noise alone would let the quieter channel
//! (the doubly integrated crossmember) drown the load cells, and each
//! channel's own residual (maximum likelihood, Bard 1974 §4-13,
//! [`super::weighting::Weighting::Likelihood`], estimated at the start
//! and again before each polishing run) lets the channel the model
//! follows best outweigh the other.
//!
//! A rebound link ([`BarrierLayout::rebound`],
//! [`bumpsim_core::chain::Chain::with_rebound`]) adds in parallel an
//! elastic–perfectly-plastic link from a chosen mass into the wall after
//! a gap `gt` (m), its plateau `Ft` (N) and its loading and unloading
//! slope `kt` (N/m): while the car rebounds it gives back `Ft` over a
//! stroke `Ft / kt`, the
//! crushed front's springback that outlasts the crush zone's steep
//! unloading (on NHTSA 10146 the wall force falls 450 → 100 kN over 25
//! mm, then 100 → 0 kN over the last 70 mm: one unloading slope per link
//! follows one of the two).
//!
//! With the test sheet's mass M the Gaussian prior `ln Σ m_i ~ N(ln M,
//! s²)` ([`bumpsim_estimate::prior`]) joins them. The Jacobian is exact:
//! the car runs into the wall once per block of 8 log parameters on dual
//! numbers ([`BarrierLayout::values`], [`super::objective::jacobian`]),
//! through the links' history, the front and path tables and the rebound
//! link's gap. The uncertainty is the
//! shared engine's over the extended residuals (spectral inflation per
//! channel), the plastic sets' (front zone and links) by the delta method
//! on that covariance.

use super::objective::LogParameters;
use super::objective::jacobian::{Tangent, fill, in_domain};
use super::weighting::Weighting;
use super::{Layout, LinkIdentError, LinkSettings};
use crate::case::LoadCase;
use bumpsim_core::chain::{Chain, ChainResponse, ChainValues, Drive, Motion};
use bumpsim_core::dual::Real;
use bumpsim_core::link::{Curve, Link, LinkState, Unloading};
use bumpsim_core::units::Dimension;
use bumpsim_estimate::lm::LeastSquares;
use bumpsim_estimate::uncertainty::Parameter;
use nalgebra::DMatrix;

/// The knots reach this multiple of the rigid car's crush.
pub const REACH: f64 = 1.3;

/// Bounds of a knot force (N) and of the front unloading slope (N/m).
const FRONT_BOUNDS: [(f64, f64); 2] = [(1e2, 1e7), (1e4, 1e10)];

/// Bounds of the rebound link's gap, m.
const GAP_BOUNDS: (f64, f64) = (1e-3, 2.0);

/// The chain behind a tabulated front crush zone, with an optional second
/// load path from the last mass (the body) into the wall.
#[derive(Debug, Clone, PartialEq)]
pub struct BarrierLayout {
    /// The chain.
    pub chain: Layout,
    /// The front curve's knots, crush m (increasing, positive).
    pub knots: Vec<f64>,
    /// The second path's knots, crush of the last mass m (increasing,
    /// positive); empty: no second path.
    pub path_knots: Vec<f64>,
    /// The mass (0-based) a rebound link pushes from the wall; None: no
    /// rebound link.
    pub rebound: Option<usize>,
}

impl BarrierLayout {
    /// Number of parameters: the chain's, K knot forces, the unloading
    /// slope, the second path's J knot forces and unloading slope, and
    /// the rebound link's plateau and slope.
    pub fn count(&self) -> usize {
        let path = match self.path_knots.is_empty() {
            true => 0,
            false => self.path_knots.len() + 1,
        };
        let rebound = 3 * usize::from(self.rebound.is_some());
        self.chain.count() + self.knots.len() + 1 + path + rebound
    }

    /// Names and units: the chain's, `Ff1..FfK`, `kf`, then `Fp1..FpJ`,
    /// `kp` with a second path, `Ft`, `kt`, `gt` with a rebound link.
    pub fn parameters(&self) -> Vec<Parameter> {
        let mut out = self.chain.parameters();
        let table = |letter: &str, knots: &[f64], out: &mut Vec<Parameter>| {
            out.extend(
                (1..=knots.len())
                    .map(|i| Parameter::new(format!("F{letter}{i}"), Dimension::Force)),
            );
            out.push(Parameter::new(format!("k{letter}"), Dimension::Stiffness));
        };
        table("f", &self.knots, &mut out);
        if !self.path_knots.is_empty() {
            table("p", &self.path_knots, &mut out);
        }
        if self.rebound.is_some() {
            out.push(Parameter::new("Ft", Dimension::Force));
            out.push(Parameter::new("kt", Dimension::Stiffness));
            out.push(Parameter::new("gt", Dimension::Length));
        }
        out
    }

    /// Default bounds (SI).
    pub fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut lower, mut upper) = self.chain.bounds();
        let tables = match self.path_knots.is_empty() {
            true => vec![self.knots.len()],
            false => vec![self.knots.len(), self.path_knots.len()],
        };
        for count in tables {
            for _ in 0..count {
                lower.push(FRONT_BOUNDS[0].0);
                upper.push(FRONT_BOUNDS[0].1);
            }
            lower.push(FRONT_BOUNDS[1].0);
            upper.push(FRONT_BOUNDS[1].1);
        }
        if self.rebound.is_some() {
            lower.extend([FRONT_BOUNDS[0].0, FRONT_BOUNDS[1].0, GAP_BOUNDS.0]);
            upper.extend([FRONT_BOUNDS[0].1, FRONT_BOUNDS[1].1, GAP_BOUNDS.1]);
        }
        (lower, upper)
    }

    /// The car (chain with its front link) of the SI parameters `theta`.
    pub fn car(&self, theta: &[f64]) -> Result<Chain, LinkIdentError> {
        let c = self.chain.count();
        if theta.len() != self.count() {
            return Err(LinkIdentError::Settings(format!(
                "{} parameters for a chain behind a {}-knot front: expected {}",
                theta.len(),
                self.knots.len(),
                self.count()
            )));
        }
        let chain = self.chain.chain(&theta[..c])?;
        let k = c + self.knots.len() + 1;
        let mut car = chain.with_front(table_link(&self.knots, &theta[c..k], 0)?);
        let end = match self.path_knots.is_empty() {
            true => k,
            false => k + self.path_knots.len() + 1,
        };
        if end > k {
            let path = table_link(&self.path_knots, &theta[k..end], self.chain.dof)?;
            car = car.with_path(self.chain.dof - 1, 0.0, path)?;
        }
        if let Some(mass) = self.rebound {
            let link = rebound_link(theta[end], theta[end + 1], self.chain.dof + 1)?;
            car = car.with_rebound(mass, theta[end + 2], link)?;
        }
        Ok(car)
    }
}

impl BarrierLayout {
    /// The car's values on any [`Real`] from the SI parameters `theta` in
    /// the layout's order (`car` = [`BarrierLayout::car`] of θ, for its
    /// shape): the chain's ([`super::objective::jacobian::values`]), the
    /// front table's forces and unloading slope, the second path's, and
    /// the rebound link's `[Ft, kt, gt]` as the bilinear link `(kt, Ft, 0)`
    /// unloading at `kt` after the gap `gt`.
    pub fn values<T: Real>(&self, car: &Chain, theta: &[T]) -> ChainValues<T> {
        let c = self.chain.count();
        let k = c + self.knots.len() + 1;
        let end = match self.path_knots.is_empty() {
            true => k,
            false => k + self.path_knots.len() + 1,
        };
        let mut values = super::objective::jacobian::values(self.chain, car, &theta[..c]);
        values.front = car.front().map(|front| front.with_parameters(&theta[c..k]));
        values.path = car
            .path()
            .map(|path| path.link.with_parameters(&theta[k..end]));
        values.path_gap = car.path().map(|path| T::constant(path.gap));
        if let Some(rebound) = car.rebound() {
            let (plateau, slope) = (theta[end], theta[end + 1]);
            let law = [slope, plateau, T::constant(0.0), slope];
            values.rebound = Some(rebound.link.with_parameters(&law));
            values.rebound_gap = Some(theta[end + 2]);
        }
        values
    }
}

/// A tabulated crush link of its parameters `[F1..FK, k_u]` at `knots`
/// (`link`: its number in errors, 0 the front zone).
fn table_link(knots: &[f64], values: &[f64], link: usize) -> Result<Link, LinkIdentError> {
    let k = knots.len();
    let points = knots
        .iter()
        .zip(&values[..k])
        .map(|(d, f)| [*d, *f])
        .collect();
    Curve::table(points)
        .and_then(|curve| Link::new(curve, Unloading::Slope(values[k])))
        .map_err(|source| LinkIdentError::Link { link, source })
}

/// The rebound link of plateau `plateau` (N) and slope `slope` (N/m):
/// elastic–perfectly-plastic, unloading along its loading slope (`link`:
/// its number in errors).
fn rebound_link(plateau: f64, slope: f64, link: usize) -> Result<Link, LinkIdentError> {
    Curve::bilinear(slope, plateau, 0.0)
        .and_then(|curve| Link::new(curve, Unloading::Slope(slope)))
        .map_err(|source| LinkIdentError::Link { link, source })
}

/// The rigid car's crush `V t + ∫∫ F/M` (m) at every sample of `case`.
pub fn rigid_crush(case: &LoadCase, mass: f64) -> Vec<f64> {
    let (mut v, mut x) = (case.initial_velocity, 0.0);
    let mut out = Vec::with_capacity(case.force.len());
    for f in &case.force {
        out.push(x);
        v += f / mass * case.step;
        x += v * case.step;
    }
    out
}

/// A start for the front: `knots` knots up to [`REACH`] times the rigid
/// car's largest crush, each at the mean measured force while the rigid
/// crush passes it, and an unloading slope 20 times the mean secant.
pub fn front_start(
    case: &LoadCase,
    mass: f64,
    knots: usize,
) -> Result<(Vec<f64>, Vec<f64>), LinkIdentError> {
    let crush = rigid_crush(case, mass);
    let (a, b) = case.window;
    let reach = crush[a..=b].iter().fold(0.0_f64, |m, x| m.max(*x));
    if reach.is_nan() || reach <= 0.0 || knots < 2 {
        return Err(LinkIdentError::Settings(format!(
            "load case '{}': a front zone needs a car moving into the barrier and 2 knots or more (the rigid car crushes {reach} m, {knots} knots)",
            case.name
        )));
    }
    let spacing = REACH * reach / knots as f64;
    let at: Vec<f64> = (1..=knots).map(|i| i as f64 * spacing).collect();
    let mut sums = vec![(0.0, 0usize); knots];
    for (x, f) in crush[a..=b].iter().zip(&case.force[a..=b]) {
        let i = ((x / spacing).round() as usize).clamp(1, knots) - 1;
        sums[i].0 += (-f).max(0.0);
        sums[i].1 += 1;
    }
    let peak = case.force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    let mut forces: Vec<f64> = sums
        .iter()
        .map(|(s, n)| if *n > 0 { s / *n as f64 } else { 0.0 })
        .collect();
    for i in 0..knots {
        if forces[i] < 0.05 * peak {
            forces[i] = if i > 0 { forces[i - 1] } else { 0.5 * peak };
        }
    }
    let mean = forces.iter().sum::<f64>() / knots as f64;
    let mut values = forces;
    values.push(20.0 * mean / reach);
    Ok((at, values))
}

/// The run of the car `car` into the wall over `case`'s samples.
pub fn run(case: &LoadCase, car: &Chain) -> Result<ChainResponse, LinkIdentError> {
    let drive = Drive::Barrier {
        speed: case.initial_velocity,
        step: case.step,
        samples: case.window.1 + 1,
    };
    car.run(&drive).map_err(|source| LinkIdentError::Chain {
        case: case.name.clone(),
        source,
    })
}

/// The largest of 0 and the values of `x`, by value.
fn most<T: Real>(x: impl Iterator<Item = T>) -> T {
    x.fold(T::constant(0.0), |m, v| match v.value() > m.value() {
        true => v,
        false => m,
    })
}

/// The plastic sets (m) of a run of the car `car` with `values` into the
/// wall: the front zone's (its largest crush m1's largest travel, the
/// wall at x = 0; 0 without one), each link's, the second path's and the
/// rebound link's when the car has them (their mass's largest travel past
/// the gap), on any [`Real`].
pub fn plastic_sets<T: Real>(car: &Chain, values: &ChainValues<T>, motion: &Motion<T>) -> Vec<T> {
    let set = |link: &Link<T>, reached: T| LinkState { reached }.plastic_set(link);
    let front = values.front.as_ref().map_or(T::constant(0.0), |front| {
        set(front, most(motion.displacement[0].iter().copied()))
    });
    let mut out = vec![front];
    out.extend(motion.plastic_set.iter().copied());
    let walls = [
        (car.path(), &values.path, values.path_gap),
        (car.rebound(), &values.rebound, values.rebound_gap),
    ];
    for (wall, link, gap) in walls {
        if let (Some(wall), Some(link)) = (wall, link) {
            let gap = gap.unwrap_or(T::constant(wall.gap));
            let crush = motion.displacement[wall.mass].iter().map(|x| *x - gap);
            out.push(set(link, most(crush)));
        }
    }
    out
}

/// The motion of the car `car` with `values` into the wall over `case`'s
/// samples, on any [`Real`].
pub fn motion<T: Real>(
    case: &LoadCase,
    car: &Chain,
    values: &ChainValues<T>,
) -> Result<Motion<T>, LinkIdentError> {
    let drive = Drive::Barrier {
        speed: case.initial_velocity,
        step: case.step,
        samples: case.window.1 + 1,
    };
    car.motion(&drive, values)
        .map_err(|source| LinkIdentError::Chain {
            case: case.name.clone(),
            source,
        })
}

/// Each case's residuals (force rows, then output rows, each channel
/// divided by its scale) of the car `car` with `values`, on any
/// [`Real`]; None when it cannot run.
fn rows<T: Real>(
    cases: &[LoadCase],
    car: &Chain,
    values: &ChainValues<T>,
    scales: &[[f64; 2]],
) -> Option<Vec<T>> {
    let count = cases.iter().map(|c| c.window_len() + c.residual_len());
    let mut r = Vec::with_capacity(count.sum());
    for (case, [sf, sy]) in cases.iter().zip(scales) {
        let run = motion(case, car, values).ok()?;
        let y = run.displacement.get(case.output_dof.wrapping_sub(1))?;
        for k in case.window.0..=case.window.1 {
            r.push((run.force[k] - case.force[k]) / *sf);
        }
        let domain = case.compare.domain;
        for k in case.first_compared()..=case.window.1 {
            let measured = domain.at(&case.measured, k, case.step);
            r.push((in_domain(domain, y, k, case.step) - measured) / *sy);
        }
    }
    Some(r)
}

/// Each case's residuals at the SI parameters `theta` into `r`; false
/// when the car cannot run or a residual is not finite.
fn raw(
    cases: &[LoadCase],
    layout: &BarrierLayout,
    theta: &[f64],
    scales: &[[f64; 2]],
    r: &mut [f64],
) -> bool {
    let Ok(car) = layout.car(theta) else {
        return false;
    };
    match rows(cases, &car, &car.values::<f64>(), scales) {
        Some(rows) if rows.len() == r.len() => r.copy_from_slice(&rows),
        _ => return false,
    }
    r.iter().all(|v| v.is_finite())
}

/// The barrier objective over the free log parameters.
#[derive(Clone)]
pub struct BarrierObjective<'a> {
    cases: &'a [LoadCase],
    layout: BarrierLayout,
    parameters: LogParameters,
    scales: Vec<[f64; 2]>,
    count: usize,
}

impl<'a> BarrierObjective<'a> {
    /// The objective of `cases`, each channel divided by its scale
    /// `scales[l] = [s_F N, s_y]`; `fixed[i]` holds a fixed SI value.
    pub fn new(
        cases: &'a [LoadCase],
        layout: BarrierLayout,
        fixed: &[Option<f64>],
        scales: Vec<[f64; 2]>,
    ) -> BarrierObjective<'a> {
        let count = cases
            .iter()
            .map(|c| c.window_len() + c.residual_len())
            .sum();
        BarrierObjective {
            cases,
            parameters: LogParameters::new(layout.count(), fixed, count),
            layout,
            scales,
            count,
        }
    }

    /// The SI parameters of the free log parameters `p`.
    pub fn theta(&self, p: &[f64]) -> Vec<f64> {
        self.parameters.theta(p)
    }

    /// Indices of the free parameters.
    pub fn free(&self) -> &[usize] {
        self.parameters.free()
    }

    /// The residual series: per case its force rows, then its output rows.
    pub fn series(&self) -> Vec<bumpsim_estimate::uncertainty::Series> {
        let lengths = self
            .cases
            .iter()
            .flat_map(|c| [c.window_len(), c.residual_len()]);
        bumpsim_estimate::uncertainty::Series::contiguous(lengths)
    }

    /// Each channel's root mean square residual at `p`, in the units of
    /// the current scales times those scales: the new scales.
    pub fn channel_scales(&self, p: &[f64]) -> Option<Vec<[f64; 2]>> {
        let mut r = vec![0.0; self.count];
        if !self.evaluate(p, &mut r, None) {
            return None;
        }
        let mut at = 0;
        let mut out = Vec::new();
        for (case, s) in self.cases.iter().zip(&self.scales) {
            let mut pair = [0.0; 2];
            for (c, n) in [case.window_len(), case.residual_len()]
                .into_iter()
                .enumerate()
            {
                let ms = r[at..at + n].iter().map(|v| v * v).sum::<f64>() / n as f64;
                pair[c] = s[c] * ms.sqrt().max(1e-12);
                at += n;
            }
            out.push(pair);
        }
        Some(out)
    }
}

impl LeastSquares for BarrierObjective<'_> {
    fn residual_count(&self) -> usize {
        self.count
    }

    fn parameter_count(&self) -> usize {
        self.parameters.free().len()
    }

    fn evaluate(&self, p: &[f64], r: &mut [f64], jacobian: Option<&mut DMatrix<f64>>) -> bool {
        let residuals =
            |theta: &[f64], r: &mut [f64]| raw(self.cases, &self.layout, theta, &self.scales, r);
        if !self.parameters.residuals(p, r, &residuals) {
            return false;
        }
        let Some(j) = jacobian else {
            return true;
        };
        let theta = self.theta(p);
        let Ok(car) = self.layout.car(&theta) else {
            return false;
        };
        let rows = |theta: &[Tangent]| {
            let values = self.layout.values(&car, theta);
            rows(self.cases, &car, &values, &self.scales)
        };
        fill(&theta, self.free(), &rows, j)
    }
}

/// How to identify a car into the barrier: the chain's settings, the
/// front's knots and the test sheet's mass.
#[derive(Debug, Clone, PartialEq)]
pub struct BarrierSettings {
    /// The chain's (its start, bounds and fixed values in its layout).
    pub links: LinkSettings,
    /// Knots of the front curve.
    pub knots: usize,
    /// The front's start: its knots (m) and values `[F1..FK N, kf N/m]`;
    /// None: [`front_start`] from the first case (`knots` knots).
    pub front_start: Option<(Vec<f64>, Vec<f64>)>,
    /// Knots of a second load path from the last mass into the wall (0:
    /// none).
    pub path_knots: usize,
    /// The mass (0-based) of a rebound link into the wall
    /// ([`BarrierLayout::rebound`]); None: none (the default before it).
    pub rebound: Option<usize>,
    /// The test sheet's mass, kg, and the spread of its prior (standard
    /// deviation of ln M); None: no prior.
    pub sheet_mass: Option<(f64, f64)>,
    /// The second path's start: its knots (m) and values `[F1..FJ N, kp
    /// N/m]`; None: [`front_start`] with `path_knots` knots, the front's
    /// and its forces halved (the two paths share the rigid car's force).
    pub path_start: Option<(Vec<f64>, Vec<f64>)>,
    /// The rebound link's start `[Ft N, kt N/m, gt m]`; None: a plateau
    /// of 0.15 times the largest force, the front's start lowered by it.
    pub rebound_start: Option<[f64; 3]>,
    /// How each channel's residuals are scaled ([`super::weighting`]):
    /// by default its noise and a model-error floor of 10 % of the wall
    /// force's spread and 1 % of the output's; [`Weighting::Likelihood`] re-estimates each
    /// channel's scale from its residuals, [`Weighting::Given`] holds
    /// given scales `[s_F N, s_y]` per case.
    pub weighting: Weighting,
}

#[cfg(test)]
mod tests {
    use super::super::objective::jacobian::tests::worst_column;
    use super::*;

    fn case(force: f64, samples: usize) -> LoadCase {
        LoadCase {
            name: "wall".into(),
            start: 0.0,
            step: 1e-3,
            force: vec![-force; samples],
            measured: (0..samples).map(|k| k as f64).collect(),
            output_dof: 2,
            initial_velocity: 10.0,
            window: (0, samples - 1),
            compare: Default::default(),
        }
    }

    /// A constant force F on a rigid car M from V: x = V t − F t² / (2 M)
    /// (the semi-implicit sum lags by a t h / 2); the knots reach REACH
    /// times its largest crush V² M / (2 F), each knot's force is F.
    #[test]
    fn a_constant_force_crushes_the_rigid_car_by_its_kinetic_energy() {
        let (f, m) = (1e5, 1000.0);
        let c = case(f, 200);
        let x = rigid_crush(&c, m);
        let t = 0.05;
        let exact = 10.0 * t - f * t * t / (2.0 * m);
        // the semi-implicit sum lags by a t h / 2 (velocity first)
        let lag = f / m * t * 1e-3 / 2.0;
        assert!((x[50] + lag - exact).abs() < 1e-9, "{} vs {exact}", x[50]);
        let (knots, values) = front_start(&c, m, 5).unwrap();
        let reach = 100.0 * m / (2.0 * f);
        assert!((knots[4] / (REACH * reach) - 1.0).abs() < 0.01, "{knots:?}");
        assert!(
            values[..5].iter().all(|v| (v - f).abs() < 1e-6 * f),
            "{values:?}"
        );
    }

    #[test]
    fn the_layout_names_the_front_and_refuses_a_wrong_vector() {
        let layout = BarrierLayout {
            chain: Layout { dof: 2 },
            knots: vec![0.1, 0.2],
            path_knots: vec![],
            rebound: None,
        };
        let names: Vec<String> = layout.parameters().into_iter().map(|p| p.name).collect();
        assert_eq!(names.join(" "), "m1 m2 c1 k1 Fy1 r1 u1 Ff1 Ff2 kf");
        let good = [300.0, 900.0, 100.0, 1e6, 5e4, 0.2, 3.0, 5e4, 6e4, 1e7];
        let car = layout.car(&good).unwrap();
        assert!(car.front().is_some());
        assert!(layout.car(&good[..9]).is_err());
        let mut bad = good;
        bad[9] = -1.0;
        assert!(
            layout
                .car(&bad)
                .unwrap_err()
                .to_string()
                .starts_with("link 0")
        );
        // a car that does not move into the barrier is refused by name
        let still = LoadCase {
            initial_velocity: -10.0,
            ..case(0.0, 10)
        };
        let e = front_start(&still, 1000.0, 4).unwrap_err().to_string();
        assert!(e.contains("'wall'"), "{e}");
    }

    /// A 2-mass car behind a 3-knot front, with a 2-knot second path from
    /// m2 and a rebound link on m2 after a gap, m2 held: the truth's wall
    /// force and m2's displacement are the case, evaluated away from the
    /// truth.
    fn wall_case() -> (LoadCase, BarrierLayout, Vec<f64>, Vec<Option<f64>>) {
        let layout = BarrierLayout {
            chain: Layout { dof: 2 },
            knots: vec![0.1, 0.3, 0.6],
            path_knots: vec![0.1, 0.4],
            rebound: Some(1),
        };
        // m1 m2 c1 k1 Fy1 r1 u1 | Ff1..3 kf | Fp1 Fp2 kp | Ft kt gt
        let truth = [
            250.0, 1250.0, 4e3, 1.5e6, 6e4, 0.1, 4.0, 8e4, 1.2e5, 1.5e5, 5e6, 5e4, 8e4, 4e6, 3e4,
            2e6, 0.2,
        ];
        let car = layout.car(&truth).unwrap();
        let samples = 1200;
        let drive = Drive::Barrier {
            speed: 12.0,
            step: 1e-4,
            samples,
        };
        let run = car.run(&drive).unwrap();
        let case = LoadCase {
            name: "wall".into(),
            start: 0.0,
            step: 1e-4,
            force: run.force.clone(),
            measured: run.displacement[1].clone(),
            output_dof: 2,
            initial_velocity: 12.0,
            window: (0, samples - 1),
            compare: Default::default(),
        };
        let away = [
            1.1, 1.0, 0.8, 1.2, 0.9, 1.3, 0.9, 1.1, 0.95, 1.05, 0.8, 1.1, 0.9, 1.2, 1.2, 0.9, 1.1,
        ];
        let theta = truth.iter().zip(away).map(|(t, a)| t * a).collect();
        let mut fixed = vec![None; truth.len()];
        fixed[1] = Some(1250.0);
        (case, layout, theta, fixed)
    }

    /// The barrier objective's exact Jacobian (dual numbers through the car
    /// run into the wall: chain, front table, second path, rebound link
    /// and its gap) and the plastic sets' gradients against central
    /// differences (step 1e-5 in each free log parameter, the chain's
    /// integration step held): within 1e-6 of each column's largest
    /// entry (measured: 2.0e-8 for the residuals, 3.8e-9 for the sets; the
    /// forward differences they replace were off by up to 1.7e-5 on the
    /// links objective).
    #[test]
    fn the_barrier_jacobian_and_the_sets_gradients_match_central_differences() {
        let (case, layout, theta, fixed) = wall_case();
        let cases = [case];
        let objective = BarrierObjective::new(&cases, layout.clone(), &fixed, vec![[1e4, 1e-3]]);
        let free = objective.free().to_vec();
        let p: Vec<f64> = free.iter().map(|&i| theta[i].ln()).collect();
        let rows = objective.residual_count();
        let (mut r, mut j) = (vec![0.0; rows], DMatrix::zeros(rows, p.len()));
        assert!(objective.evaluate(&p, &mut r, Some(&mut j)));
        let residuals = |q: &[f64]| {
            let mut r = vec![0.0; rows];
            assert!(objective.evaluate(q, &mut r, None));
            r
        };
        let worst = worst_column(&j, &p, 1e-5, &residuals);
        eprintln!("residuals: worst {worst:.3e} of a column");
        assert!(worst <= 1e-6, "residuals: worst {worst:.3e} of a column");
        let theta = objective.theta(&p);
        let car = layout.car(&theta).unwrap();
        let sets = |theta: &[Tangent]| {
            let values = layout.values(&car, theta);
            let run = motion(&cases[0], &car, &values).ok()?;
            Some(plastic_sets(&car, &values, &run))
        };
        let (values, gradients) =
            super::super::objective::jacobian::tangents(&theta, &free, &sets).unwrap();
        // front zone, link 1, second path, rebound link: every one set
        assert_eq!(values.len(), 4);
        assert!(values.iter().all(|v| *v > 0.0), "{values:?}");
        let of = |q: &[f64]| {
            let theta = objective.theta(q);
            let car = layout.car(&theta).unwrap();
            let values = car.values::<f64>();
            plastic_sets(&car, &values, &motion(&cases[0], &car, &values).unwrap())
        };
        assert_eq!(of(&p), values);
        let worst = worst_column(&gradients, &p, 1e-5, &of);
        eprintln!("plastic sets: worst {worst:.3e} of a column");
        assert!(worst <= 1e-6, "plastic sets: worst {worst:.3e} of a column");
    }
}
