//! Bounded Levenberg–Marquardt for small nonlinear least-squares problems.
//!
//! Minimises `F(p) = Σ r_i(p)²` subject to `lower ≤ p ≤ upper`. Each
//! iteration solves `(JᵀJ + λ D) δ = −Jᵀr` on the free parameters, with
//! Marquardt's scaling `D = diag(JᵀJ)`; parameters at a bound whose
//! gradient points outwards are held (active set), and the trial point is
//! projected onto the box. λ follows Nielsen's update (gain ratio ρ), or
//! ([`Damping::TrustRegion`], an option: not yet the default anywhere) is the one
//! that keeps the scaled step within a trust radius Δ, which the gain ratio
//! sets as scipy's `least_squares` does except that a refused trial halves
//! it ([`crate::trust`]; Moré 1978): the Gauss–Newton step whenever it fits.
//! With [`Settings::acceleration`] (Nielsen's damping only; not the
//! default of [`Settings`], but of a search's lone start,
//! [`crate::multistart::alone`]) each trial is the geodesic step `v + a/2` (Transtrum &
//! Sethna 2012, GSL's `lmaccel`): v the damped step, and a the solution of
//! the same damped system for `Jᵀ r''`, where the residuals' second
//! directional derivative along v comes from one residual evaluation,
//! `r'' ≈ (2/h)((r(p + h v) − r(p))/h − J v)`, h = 0.1. As `JᵀJ v` and
//! `Jᵀr` are known, only `Jᵀ r(p + h v)` is asked of the problem
//! ([`LeastSquares::transposed`], at the point of the last normal
//! equations). A trial with `2‖a‖/‖v‖` (column-scaled) above the limit is
//! refused as a failed step; the gain ratio compares the actual decrease
//! with the model's along v.
//! Stopping rules, any of:
//! - the thesis's directional derivative `|∇F · δ|` (fmincon's) below
//!   `directional · F`, relative (see [`Settings::directional`]);
//! - a relative decrease of F below `ftol` after an accepted step;
//! - a step below `xtol` (parameters are logarithmic: a relative change);
//! - a projected gradient below `gtol · (1 + F)`;
//! - the iteration limit (reported as not converged).
//!
//! The rules but the gradient's need only the accepted step, the two
//! objectives and the gradient where the step began, so they are tested
//! before the normal equations at the new point are formed: a run that
//! stops by them forms none at its last point, where nothing would use
//! them (a polish forms its own at its start): one Jacobian fewer per
//! converged run, the same path and result.
//!
//! Why by hand: no long-proven bounded least-squares crate exists for Rust
//! (`levenberg-marquardt` has no bounds and pins an older nalgebra; `basin`
//! is young). The problems here have at most a few dozen parameters, so a
//! dense LM on nalgebra's Cholesky is small, fast and testable; the method
//! is the textbook one (Madsen, Nielsen & Tingleff 2004, ch. 3.2).

use crate::trust::Subproblem;
use nalgebra::{DMatrix, DVector};

/// A least-squares problem: residuals and their Jacobian at a point.
pub trait LeastSquares {
    /// Number of residuals m.
    fn residual_count(&self) -> usize;
    /// Number of parameters n.
    fn parameter_count(&self) -> usize;
    /// Writes the residuals (length m) and, when asked, the m × n Jacobian.
    /// Returns false when the model cannot be evaluated (non-finite output).
    fn evaluate(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        jacobian: Option<&mut DMatrix<f64>>,
    ) -> bool;

    /// Writes the residuals and the normal equations of a Gauss–Newton
    /// step: `JᵀJ` (n × n) and `Jᵀr` (n), all LM needs of the Jacobian.
    /// The default forms them from [`LeastSquares::evaluate`]'s Jacobian;
    /// a problem with many residuals can accumulate them without storing J.
    fn normal(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        jtj: &mut DMatrix<f64>,
        gradient: &mut DVector<f64>,
    ) -> bool {
        let mut jacobian = DMatrix::zeros(self.residual_count(), self.parameter_count());
        if !self.evaluate(p, residuals, Some(&mut jacobian)) {
            return false;
        }
        *jtj = jacobian.transpose() * &jacobian;
        *gradient = jacobian.transpose() * DVector::from_column_slice(residuals);
        true
    }

    /// Writes `Jᵀv` at `p` into `product` (n), for a vector `v` (m) other
    /// than the residuals: the geodesic acceleration's second derivative
    /// projected ([`Settings::acceleration`]). LM asks for it only at the
    /// point of its last [`LeastSquares::normal`], so a problem may keep J
    /// from there; the default forms J by [`LeastSquares::evaluate`] (a
    /// Jacobian's cost). False when it cannot be formed.
    fn transposed(&self, p: &[f64], v: &[f64], product: &mut DVector<f64>) -> bool {
        let (m, n) = (self.residual_count(), self.parameter_count());
        let (mut jacobian, mut residuals) = (DMatrix::zeros(m, n), vec![0.0; m]);
        if !self.evaluate(p, &mut residuals, Some(&mut jacobian)) {
            return false;
        }
        *product = jacobian.transpose() * DVector::from_column_slice(v);
        true
    }
}

/// A shared problem is a problem (the multi-start builds one per run).
impl<T: LeastSquares + ?Sized> LeastSquares for &T {
    fn residual_count(&self) -> usize {
        (**self).residual_count()
    }
    fn parameter_count(&self) -> usize {
        (**self).parameter_count()
    }
    fn evaluate(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        jacobian: Option<&mut DMatrix<f64>>,
    ) -> bool {
        (**self).evaluate(p, residuals, jacobian)
    }
    fn normal(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        jtj: &mut DMatrix<f64>,
        gradient: &mut DVector<f64>,
    ) -> bool {
        (**self).normal(p, residuals, jtj, gradient)
    }
    fn transposed(&self, p: &[f64], v: &[f64], product: &mut DVector<f64>) -> bool {
        (**self).transposed(p, v, product)
    }
}

/// Tolerances and limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Iteration limit.
    pub max_iterations: usize,
    /// Relative decrease of F that ends the run.
    pub ftol: f64,
    /// Largest parameter change that ends the run.
    pub xtol: f64,
    /// Projected gradient that ends the run, relative to 1 + F.
    pub gtol: f64,
    /// The thesis's directional-derivative test, relative to the objective:
    /// stop when `|∇F · δ| < directional · F`. The thesis's 1e-12 was an
    /// absolute number on its objectives of 0.3–1.3 mm² (paper B, table 1);
    /// as an absolute number in SI (m²) it stopped runs whose objective was
    /// still falling a part in 1e5 per step when F ≈ 1e-7 m², and would be
    /// unreachable at F ≈ 1 m². Relative, it means the same on any scale.
    pub directional: f64,
    /// How each step's damping is chosen.
    pub damping: Damping,
    /// Geodesic acceleration (Transtrum & Sethna 2012) with Nielsen's
    /// damping: `None` for none, else the largest `2‖a‖/‖v‖` accepted.
    pub acceleration: Option<f64>,
}

/// How LM damps its steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Damping {
    /// `(JᵀJ + λ diag(JᵀJ)) δ = −Jᵀr` with λ by Nielsen's update (Madsen,
    /// Nielsen & Tingleff 2004, eq. 3.16), starting at 1e-3 of the largest
    /// diagonal element.
    #[default]
    Nielsen,
    /// Nielsen's update of a dimensionless λ, starting at 1e-3: with
    /// Marquardt's scaling `D = diag(JᵀJ)` the damped system
    /// `(JᵀJ + λ D) δ = −Jᵀr` is invariant under a scaling of the residuals
    /// only if λ carries no unit. [`Damping::Nielsen`]'s start, 1e-3 of the
    /// largest diagonal element (Madsen, Nielsen & Tingleff's τ for
    /// `D = I`), carries the residuals' unit squared: residuals divided by
    /// a noise of 1e-8 m/s made it 1e14 and the first steps 1e-15 long, and
    /// the search stopped at its start (issue 44). The steps of this one
    /// do not depend on the residuals' scale.
    Scaled,
    /// A trust region on the step scaled by the column norms of J (Moré
    /// 1978; [`crate::trust`]): the Gauss–Newton step whenever it fits, the
    /// radius from the gain ratio as scipy's `least_squares` sets it (but
    /// halved, not quartered, after a refused trial), and starting at 100
    /// times the scaled length of the start (MINPACK's).
    TrustRegion,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            max_iterations: 1000,
            ftol: 1e-12,
            xtol: 1e-10,
            gtol: 1e-12,
            directional: 1e-9,
            damping: Damping::Nielsen,
            acceleration: None,
        }
    }
}

/// Why the solver stopped; serialised as the variant's name (`"Objective"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Stop {
    /// `|∇F · δ|` below the thesis tolerance.
    Directional,
    /// Relative decrease of F below `ftol`.
    Objective,
    /// Step below `xtol`.
    Step,
    /// Projected gradient below `gtol`.
    Gradient,
    /// No step decreased F (λ grew without bound).
    NoProgress,
    /// The iteration limit.
    Iterations,
    /// The start could not be evaluated.
    BadStart,
}

impl Stop {
    /// Whether the run converged (a local minimum to the tolerances).
    pub fn converged(self) -> bool {
        matches!(
            self,
            Stop::Directional | Stop::Objective | Stop::Step | Stop::Gradient | Stop::NoProgress
        )
    }
}

/// The result of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Final parameters.
    pub parameters: Vec<f64>,
    /// Final objective `F = Σ r²`.
    pub objective: f64,
    /// Iterations taken.
    pub iterations: usize,
    /// Residual evaluations.
    pub evaluations: usize,
    /// Why it stopped.
    pub stop: Stop,
}

struct State {
    p: Vec<f64>,
    r: Vec<f64>,
    jtj: DMatrix<f64>,
    g: DVector<f64>,
    cost: f64,
}

/// Runs bounded LM from `start` (clamped into the box).
pub fn minimise(
    problem: &dyn LeastSquares,
    start: &[f64],
    lower: &[f64],
    upper: &[f64],
    settings: &Settings,
) -> Outcome {
    let (m, n) = (problem.residual_count(), problem.parameter_count());
    let clamp =
        |p: &[f64]| -> Vec<f64> { (0..n).map(|i| p[i].clamp(lower[i], upper[i])).collect() };
    let mut s = State {
        p: clamp(start),
        r: vec![0.0; m],
        jtj: DMatrix::zeros(n, n),
        g: DVector::zeros(n),
        cost: f64::INFINITY,
    };
    let mut evaluations = 1;
    let ok = problem.normal(&s.p, &mut s.r, &mut s.jtj, &mut s.g);
    s.cost = s.r.iter().map(|v| v * v).sum();
    if !ok || !s.cost.is_finite() {
        return Outcome {
            parameters: s.p,
            objective: f64::INFINITY,
            iterations: 0,
            evaluations,
            stop: Stop::BadStart,
        };
    }
    let mut control = Control::new(settings.damping);
    let mut trial_r = vec![0.0; m];
    for iteration in 0..settings.max_iterations {
        let free: Vec<usize> = (0..n)
            .filter(|&i| !held(i, &s.p, s.g[i], lower, upper))
            .collect();
        let projected = free.iter().map(|&i| s.g[i].abs()).fold(0.0, f64::max);
        if projected <= settings.gtol * (1.0 + s.cost) {
            return finish(s, iteration, evaluations, Stop::Gradient);
        }
        control.prepare(&s, &free);
        let mut accepted = None;
        for _ in 0..60 {
            let Some(velocity) = control.propose(&s, &free) else {
                control.reject(0.0);
                continue;
            };
            // with acceleration, `along` keeps the velocity the model's
            // decrease is measured along
            let (delta, along) = match (settings.acceleration, &control) {
                (Some(limit), Control::Nielsen { lambda, .. }) => {
                    evaluations += 1;
                    let lambda = *lambda;
                    match accelerated(problem, &s, &free, &velocity, lambda, limit, &mut trial_r) {
                        Some(delta) => (delta, Some(velocity)),
                        None => {
                            control.reject(0.0);
                            continue;
                        }
                    }
                }
                _ => (velocity, None),
            };
            let trial = clamp(&(0..n).map(|i| s.p[i] + delta[i]).collect::<Vec<_>>());
            let step: DVector<f64> = DVector::from_iterator(n, (0..n).map(|i| trial[i] - s.p[i]));
            evaluations += 1;
            let ok = problem.evaluate(&trial, &mut trial_r, None);
            let cost: f64 = trial_r.iter().map(|v| v * v).sum();
            // with acceleration, the gain ratio against the model's decrease
            // along the velocity (against the whole step's it took 32 and 107
            // Jacobians on tests/iterations.rs's series instead of 22 and 42)
            let decrease = |d: &DVector<f64>| -(2.0 * s.g.dot(d) + d.dot(&(&s.jtj * d)));
            let predicted = match &along {
                Some(velocity) => {
                    let moved = clamp(&(0..n).map(|i| s.p[i] + velocity[i]).collect::<Vec<_>>());
                    decrease(&DVector::from_iterator(
                        n,
                        (0..n).map(|i| moved[i] - s.p[i]),
                    ))
                }
                None => decrease(&step),
            };
            let rho = (s.cost - cost) / predicted;
            if ok && cost.is_finite() && cost < s.cost && rho > 0.0 {
                control.accept(rho, step.as_slice());
                accepted = Some((trial, cost, step));
                break;
            }
            control.reject(control.length(step.as_slice()));
        }
        let Some((trial, cost, step)) = accepted else {
            return finish(s, iteration, evaluations, Stop::NoProgress);
        };
        let decrease = (s.cost - cost) / s.cost.max(f64::MIN_POSITIVE);
        let directional = (2.0 * s.g.dot(&step)).abs();
        s.p = trial;
        s.cost = cost;
        // the stopping rules need only the step, the two objectives and the
        // gradient where the step began: a run that stops by them forms no
        // normal equations at its last point, which nothing would use (a
        // polish forms its own at its start; issue 44 item 6). At the
        // iteration limit they are formed, as before: a point where they
        // cannot be formed ends the run (no progress) instead of being
        // handed on to a next stage that could not start from it.
        let stop = if directional < settings.directional * s.cost {
            Some(Stop::Directional)
        } else if decrease < settings.ftol {
            Some(Stop::Objective)
        } else if step.amax() < settings.xtol {
            Some(Stop::Step)
        } else {
            None
        };
        if let Some(stop) = stop {
            return finish(s, iteration + 1, evaluations, stop);
        }
        evaluations += 1;
        if !problem.normal(&s.p, &mut s.r, &mut s.jtj, &mut s.g) {
            return finish(s, iteration + 1, evaluations, Stop::NoProgress);
        }
    }
    finish(s, settings.max_iterations, evaluations, Stop::Iterations)
}

/// The damping's state between iterations ([`Damping`]).
enum Control {
    /// Nielsen's λ (negative: not yet set), its growth factor ν, and
    /// whether λ starts dimensionless ([`Damping::Scaled`]).
    Nielsen { lambda: f64, nu: f64, scaled: bool },
    /// The trust radius (negative: not yet set) and this iteration's
    /// decomposed subproblem.
    Trust {
        radius: f64,
        subproblem: Option<Subproblem>,
    },
}

impl Control {
    fn new(damping: Damping) -> Control {
        match damping {
            Damping::Nielsen | Damping::Scaled => Control::Nielsen {
                lambda: -1.0,
                nu: 2.0,
                scaled: damping == Damping::Scaled,
            },
            Damping::TrustRegion => Control::Trust {
                radius: -1.0,
                subproblem: None,
            },
        }
    }

    /// Sets up an iteration at the state `s` with the `free` parameters.
    fn prepare(&mut self, s: &State, free: &[usize]) {
        match self {
            Control::Nielsen { lambda, scaled, .. } if *lambda < 0.0 && *scaled => *lambda = 1e-3,
            Control::Nielsen { lambda, .. } if *lambda < 0.0 => {
                let n = s.g.len();
                *lambda = 1e-3 * (0..n).map(|i| s.jtj[(i, i)]).fold(0.0, f64::max);
            }
            Control::Nielsen { .. } => {}
            Control::Trust { radius, subproblem } => {
                let problem = Subproblem::new(&s.jtj, &s.g, free);
                if *radius < 0.0 {
                    let length = problem.scaled_norm(&s.p);
                    *radius = if length > 0.0 { 100.0 * length } else { 100.0 };
                }
                *subproblem = Some(problem);
            }
        }
    }

    /// The next trial step, `None` when it cannot be formed.
    fn propose(&self, s: &State, free: &[usize]) -> Option<Vec<f64>> {
        match self {
            Control::Nielsen { lambda, .. } => solve(&s.jtj, &s.g, free, *lambda),
            Control::Trust { radius, subproblem } => subproblem.as_ref()?.step(*radius),
        }
    }

    /// The step's scaled length (the trust region's measure; 0 for Nielsen).
    fn length(&self, step: &[f64]) -> f64 {
        match self {
            Control::Trust {
                subproblem: Some(problem),
                ..
            } => problem.scaled_norm(step),
            _ => 0.0,
        }
    }

    /// A step with gain ratio `rho` was taken.
    fn accept(&mut self, rho: f64, step: &[f64]) {
        let length = self.length(step);
        match self {
            Control::Nielsen { lambda, nu, .. } => {
                *lambda *= (1.0_f64 / 3.0).max(1.0 - (2.0 * rho - 1.0).powi(3));
                *nu = 2.0;
            }
            Control::Trust { radius, .. } if rho < 0.25 => *radius = 0.25 * length,
            Control::Trust { radius, .. } if rho > 0.75 && length > 0.95 * *radius => {
                *radius *= 2.0
            }
            Control::Trust { .. } => {}
        }
    }

    /// A trial of scaled `length` was refused (or could not be formed: 0):
    /// the trust region halves (Madsen, Nielsen & Tingleff 2004, eq. 2.19),
    /// where scipy's TRF quarters it. On a curved valley a quarter makes
    /// the radius cycle (refused at 2Δ, accepted at ½Δ, then Δ), two short
    /// Jacobians per cycle; half of it is accepted at Δ (issue 44 item 6,
    /// `bumpsim-ident/tests/iterations.rs`).
    fn reject(&mut self, length: f64) {
        match self {
            Control::Nielsen { lambda, nu, .. } => (*lambda, *nu) = (*lambda * *nu, *nu * 2.0),
            Control::Trust { radius, .. } if length > 0.0 => *radius = 0.5 * length.min(*radius),
            Control::Trust { radius, .. } => *radius *= 0.5,
        }
    }
}

/// The largest `2‖a‖/‖v‖` of an accelerated step to accept ([`Settings::acceleration`]). Transtrum & Sethna suggest 0.75;
/// on the peer series of `bumpsim-ident/tests/iterations.rs` 0.75 took 22
/// Jacobians on the velocity objective (scipy TRF 18), 1.0 took 18 (42
/// against 60 on the displacement one).
pub const ACCELERATION_LIMIT: f64 = 1.0;

/// The step h of the finite difference along the velocity that gives the
/// residuals' second directional derivative (Transtrum & Sethna 2012
/// use 0.1; GSL's `h_fvv` is 0.02).
const ACCELERATION_STEP: f64 = 0.1;

/// The geodesic acceleration's step `v + a/2` (Transtrum & Sethna 2012):
/// `a` solves the damped system for `Jᵀ r''`, the residuals' second
/// directional derivative along `v` by one residual evaluation,
/// `r'' ≈ (2/h) ((r(p + h v) − r(p))/h − J v)`; `Jᵀ J v` is known, so only
/// `Jᵀ r(p + h v)` is asked of the problem. None when `2‖a‖/‖v‖` (scaled)
/// exceeds `limit`: the step is refused.
fn accelerated(
    problem: &dyn LeastSquares,
    s: &State,
    free: &[usize],
    velocity: &[f64],
    lambda: f64,
    limit: f64,
    shifted: &mut [f64],
) -> Option<Vec<f64>> {
    let n = velocity.len();
    let h = ACCELERATION_STEP;
    let point: Vec<f64> = (0..n).map(|i| s.p[i] + h * velocity[i]).collect();
    let v = DVector::from_column_slice(velocity);
    let mut product = DVector::zeros(n);
    if !problem.evaluate(&point, shifted, None) || !problem.transposed(&s.p, shifted, &mut product)
    {
        return Some(velocity.to_vec());
    }
    let curvature = ((product - &s.g) / h - &s.jtj * &v) * (2.0 / h);
    let a = solve(&s.jtj, &curvature, free, lambda)?;
    let scaled = |x: &[f64]| -> f64 {
        free.iter()
            .map(|&i| s.jtj[(i, i)] * x[i] * x[i])
            .sum::<f64>()
            .sqrt()
    };
    let ratio = 2.0 * scaled(&a) / scaled(velocity);
    (ratio <= limit).then(|| (0..n).map(|i| velocity[i] + 0.5 * a[i]).collect())
}

fn finish(s: State, iterations: usize, evaluations: usize, stop: Stop) -> Outcome {
    Outcome {
        parameters: s.p,
        objective: s.cost,
        iterations,
        evaluations,
        stop,
    }
}

/// Whether parameter `i` sits on a bound with the gradient pushing it out.
fn held(i: usize, p: &[f64], gradient: f64, lower: &[f64], upper: &[f64]) -> bool {
    let tolerance = 1e-12 * (1.0 + p[i].abs());
    (p[i] <= lower[i] + tolerance && gradient > 0.0)
        || (p[i] >= upper[i] - tolerance && gradient < 0.0)
}

/// Solves the damped normal equations on the free parameters; zero elsewhere.
fn solve(jtj: &DMatrix<f64>, g: &DVector<f64>, free: &[usize], lambda: f64) -> Option<Vec<f64>> {
    let k = free.len();
    let scale_floor = 1e-12
        * free
            .iter()
            .map(|&i| jtj[(i, i)])
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
    let a = DMatrix::from_fn(k, k, |r, c| {
        let v = jtj[(free[r], free[c])];
        if r == c {
            v + lambda * v.max(scale_floor)
        } else {
            v
        }
    });
    let b = DVector::from_iterator(k, free.iter().map(|&i| -g[i]));
    let x = a.cholesky()?.solve(&b);
    let mut delta = vec![0.0; g.len()];
    for (j, &i) in free.iter().enumerate() {
        delta[i] = x[j];
    }
    delta.iter().all(|d| d.is_finite()).then_some(delta)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Rosenbrock as residuals: r = [10 (p1 − p0²), 1 − p0].
    struct Rosenbrock;

    impl LeastSquares for Rosenbrock {
        fn residual_count(&self) -> usize {
            2
        }
        fn parameter_count(&self) -> usize {
            2
        }
        fn evaluate(&self, p: &[f64], r: &mut [f64], jac: Option<&mut DMatrix<f64>>) -> bool {
            r[0] = 10.0 * (p[1] - p[0] * p[0]);
            r[1] = 1.0 - p[0];
            if let Some(j) = jac {
                j[(0, 0)] = -20.0 * p[0];
                j[(0, 1)] = 10.0;
                j[(1, 0)] = -1.0;
                j[(1, 1)] = 0.0;
            }
            true
        }
    }

    #[test]
    fn finds_the_rosenbrock_minimum() {
        let out = minimise(
            &Rosenbrock,
            &[-1.2, 1.0],
            &[-5.0; 2],
            &[5.0; 2],
            &Settings::default(),
        );
        assert!(out.stop.converged(), "{:?}", out.stop);
        assert_relative_eq!(out.parameters[0], 1.0, epsilon = 1e-6);
        assert_relative_eq!(out.parameters[1], 1.0, epsilon = 1e-6);
    }

    /// Rosenbrock with its residuals multiplied by `scale`.
    struct Scaled(f64);

    impl LeastSquares for Scaled {
        fn residual_count(&self) -> usize {
            2
        }
        fn parameter_count(&self) -> usize {
            2
        }
        fn evaluate(&self, p: &[f64], r: &mut [f64], mut jac: Option<&mut DMatrix<f64>>) -> bool {
            let ok = Rosenbrock.evaluate(p, r, jac.as_deref_mut());
            if let Some(j) = jac {
                *j *= self.0;
            }
            r.iter_mut().for_each(|v| *v *= self.0);
            ok
        }
        fn normal(
            &self,
            p: &[f64],
            r: &mut [f64],
            jtj: &mut DMatrix<f64>,
            g: &mut DVector<f64>,
        ) -> bool {
            let ok = Rosenbrock.normal(p, r, jtj, g);
            r.iter_mut().for_each(|v| *v *= self.0);
            *jtj *= self.0 * self.0;
            *g *= self.0 * self.0;
            ok
        }
    }

    /// A scaling of the residuals (a noise of 1e-8 against 1e-3) leaves
    /// the scaled damping's path alone: the same iterations, the same point.
    #[test]
    fn the_scaled_damping_does_not_depend_on_the_residuals_scale() {
        let settings = Settings {
            damping: Damping::Scaled,
            ..Settings::default()
        };
        let run = |scale| {
            minimise(
                &Scaled(scale),
                &[-1.2, 1.0],
                &[-5.0; 2],
                &[5.0; 2],
                &settings,
            )
        };
        let (coarse, fine) = (run(1e3), run(1e8));
        assert!(coarse.stop.converged() && fine.stop.converged());
        assert_eq!(coarse.iterations, fine.iterations);
        for (a, b) in coarse.parameters.iter().zip(&fine.parameters) {
            assert_relative_eq!(*a, *b, max_relative = 1e-9);
            assert_relative_eq!(*a, 1.0, epsilon = 1e-6);
        }
    }

    /// Rosenbrock's curved valley is the geodesic acceleration's case: the
    /// same minimum in fewer iterations than the plain steps take.
    #[test]
    fn the_geodesic_acceleration_follows_the_rosenbrock_valley() {
        let run = |acceleration| {
            let settings = Settings {
                acceleration,
                ..Settings::default()
            };
            minimise(&Rosenbrock, &[-1.2, 1.0], &[-5.0; 2], &[5.0; 2], &settings)
        };
        let (plain, accelerated) = (run(None), run(Some(ACCELERATION_LIMIT)));
        assert!(accelerated.stop.converged(), "{:?}", accelerated.stop);
        assert_relative_eq!(accelerated.parameters[0], 1.0, epsilon = 1e-6);
        assert_relative_eq!(accelerated.parameters[1], 1.0, epsilon = 1e-6);
        assert!(
            accelerated.iterations < plain.iterations,
            "{} against {}",
            accelerated.iterations,
            plain.iterations
        );
    }

    /// Rosenbrock counting the normal equations LM forms.
    struct Counted(std::cell::Cell<usize>);

    impl LeastSquares for Counted {
        fn residual_count(&self) -> usize {
            2
        }
        fn parameter_count(&self) -> usize {
            2
        }
        fn evaluate(&self, p: &[f64], r: &mut [f64], jac: Option<&mut DMatrix<f64>>) -> bool {
            Rosenbrock.evaluate(p, r, jac)
        }
        fn normal(
            &self,
            p: &[f64],
            r: &mut [f64],
            jtj: &mut DMatrix<f64>,
            g: &mut DVector<f64>,
        ) -> bool {
            self.0.set(self.0.get() + 1);
            Rosenbrock.normal(p, r, jtj, g)
        }
    }

    /// The start's normal equations and one set per accepted step but the
    /// last: a run that a stopping rule ends (here on the bound p0 ≤ 0.5,
    /// where the residuals do not vanish) forms none at its last point
    /// (nothing would use them); at the iteration limit it does.
    #[test]
    fn no_normal_equations_are_formed_at_the_last_point() {
        for (limit, upper) in [(5, 5.0), (1000, 0.5)] {
            let problem = Counted(std::cell::Cell::new(0));
            let settings = Settings {
                max_iterations: limit,
                ..Settings::default()
            };
            let out = minimise(&problem, &[-1.2, 1.0], &[-5.0; 2], &[upper, 5.0], &settings);
            let by_rule = matches!(out.stop, Stop::Directional | Stop::Objective | Stop::Step);
            assert_eq!(by_rule, limit == 1000, "{:?}", out.stop);
            assert!(out.iterations > 1);
            let last = usize::from(!by_rule);
            assert_eq!(problem.0.get(), out.iterations + last, "{:?}", out.stop);
        }
    }

    #[test]
    fn respects_bounds_and_stops_on_the_active_bound() {
        // minimum at (1, 1) is outside p0 <= 0.5: the constrained optimum is on p0 = 0.5
        let out = minimise(
            &Rosenbrock,
            &[-1.2, 1.0],
            &[-5.0, -5.0],
            &[0.5, 5.0],
            &Settings::default(),
        );
        assert!(out.stop.converged(), "{:?}", out.stop);
        assert_relative_eq!(out.parameters[0], 0.5, epsilon = 1e-9);
        assert_relative_eq!(out.parameters[1], 0.25, epsilon = 1e-6);
    }
}
