//! The joint final stage ([`crate::identify::Setup::joint`], with `bumper`):
//! the searched car and the bumper's law polished together on both things
//! the training tests measure, the sensors' replays and the forward runs'
//! force.
//!
//! The replays are driven by the measured forces and never see the bumper;
//! the bumper fit ([`crate::bumper_fit`]) holds the car. A car parameter
//! the replays hardly determine but a forward run does (a crash box's
//! elastic stiffness, in series with the bumper in every forward run) is
//! then left where the replays' noise put it, and the bumper is fitted
//! around it. Here the search variables are `(p, b)`: the identification's
//! `p` (ln θ and the lines of action, [`crate::identify::Unknowns`]) and the bumper
//! law's `b = [ln a, ln λ, ln u, c]` ([`crate::bumper_fit`]), and the
//! residuals are the identification's (data and stated priors,
//! [`bumpsim_estimate::prior::Priored`]) followed by the bumper fit's force
//! residuals `r_f(p, b)` of the training tests that carry a striker (a
//! wall's load cells one by one with `Setup::cells`), times
//! a weight `w`:
//!
//! `F_J(p, b) = F_P(p) + w² Σ r_f(p, b)²`, `w² = β F_P(p₀) / Σ r_f(p₀, b₀)²`,
//!
//! `p₀` the search's best, `b₀` the bumper fitted to its car: β
//! (`Setup::joint`, the study's `[model] joint`) is how much the forward runs
//! weigh against the replays at the stage's start. The bounded
//! Levenberg–Marquardt of [`bumpsim_estimate::lm`] minimises `F_J` from
//! `(p₀, b₀)` within the search's bounds and the bumper fit's, with the
//! replays' exact Jacobian (the objective's) and the forward runs' by
//! forward differences (step [`STEP`], backwards at an upper bound). The
//! polished `p` replaces the search's best when it lowers `F_J`; the
//! bumper is then fitted to the polished car as before
//! ([`crate::bumper_fit::identified`]). The replays keep the template's
//! bumper segments (which weigh a wall cell's line of action), as in the
//! search.

use super::{fit_bumper, force_residuals, law, law_bounds};
use crate::car::PlanarError;
use crate::identify::{PlanarCase, Unknowns};
use bumpsim_estimate::lm::{self, LeastSquares, minimise};
use bumpsim_estimate::multistart::Searched;
use nalgebra::DMatrix;
use rayon::prelude::*;

/// Step of the forward runs' forward differences (ln θ, m, bumper law).
pub const STEP: f64 = 1e-3;

/// The joint problem (see the module).
struct Joint<'a> {
    priored: &'a (dyn LeastSquares + Sync),
    unknowns: &'a Unknowns,
    strikers: Vec<&'a PlanarCase>,
    weight: f64,
    upper: Vec<f64>,
    forces: usize,
    /// A wall's load cells compared one by one ([`crate::identify::Setup::cells`]).
    cells: bool,
}

impl Joint<'_> {
    /// The car parameters' count (`p`'s length).
    fn cars(&self) -> usize {
        self.priored.parameter_count()
    }

    /// The weighted force residuals at `q = (p, b)`.
    fn forces_at(&self, q: &[f64]) -> Option<Vec<f64>> {
        let (p, b) = q.split_at(self.cars());
        let car = self.unknowns.car(&self.unknowns.theta(p)).ok()?;
        let r = force_residuals(&car, &self.strikers, b, self.cells)?;
        (r.len() == self.forces).then(|| r.iter().map(|v| self.weight * v).collect())
    }
}

impl LeastSquares for Joint<'_> {
    fn residual_count(&self) -> usize {
        self.priored.residual_count() + self.forces
    }

    fn parameter_count(&self) -> usize {
        self.cars() + 4
    }

    fn evaluate(&self, q: &[f64], r: &mut [f64], jacobian: Option<&mut DMatrix<f64>>) -> bool {
        let (n, m) = (self.cars(), self.priored.residual_count());
        let mut replays = jacobian.as_ref().map(|_| DMatrix::zeros(m, n));
        if !self
            .priored
            .evaluate(&q[..n], &mut r[..m], replays.as_mut())
        {
            return false;
        }
        let Some(f) = self.forces_at(q) else {
            return false;
        };
        r[m..].copy_from_slice(&f);
        let (Some(j), Some(replays)) = (jacobian, replays) else {
            return true;
        };
        j.fill(0.0);
        j.view_mut((0, 0), (m, n)).copy_from(&replays);
        let columns: Vec<Option<(f64, Vec<f64>)>> = (0..q.len())
            .into_par_iter()
            .map(|i| {
                let h = if q[i] + STEP > self.upper[i] {
                    -STEP
                } else {
                    STEP
                };
                let mut moved = q.to_vec();
                moved[i] += h;
                self.forces_at(&moved).map(|c| (h, c))
            })
            .collect();
        for (i, column) in columns.into_iter().enumerate() {
            let Some((h, c)) = column else {
                return false;
            };
            for (k, (moved, at)) in c.iter().zip(&f).enumerate() {
                j[(m + k, i)] = (moved - at) / h;
            }
        }
        true
    }
}

/// `searched` with its best run polished jointly with the bumper's law
/// (see the module), the forward runs weighing `balance` (β) against the
/// replays at the start, a wall's load cells compared one by one when
/// `cells`; unchanged when the polish does not lower `F_J`.
/// An error when no training case carries a striker or the start's
/// forward runs cannot be evaluated.
pub(crate) fn polished(
    (priored, unknowns): (&(dyn LeastSquares + Sync), &Unknowns),
    cases: &[PlanarCase],
    mut searched: Searched,
    bounds: (&[f64], &[f64]),
    (balance, cells): (f64, bool),
) -> Result<Searched, PlanarError> {
    let best = searched.starts.best;
    let p0 = searched.runs[best].outcome.parameters.clone();
    let car = unknowns.car(&unknowns.theta(&p0))?;
    let b0 = law(&fit_bumper(&car, cases, true, cells)?);
    let strikers: Vec<&PlanarCase> = cases.iter().filter(|c| c.striker.is_some()).collect();
    let unevaluated = || PlanarError::Case {
        case: "training".into(),
        message: "the joint stage cannot evaluate the searched car's forward runs".into(),
    };
    let f0 = force_residuals(&car, &strikers, &b0, cells).ok_or_else(unevaluated)?;
    let mut r = vec![0.0; priored.residual_count()];
    if !priored.evaluate(&p0, &mut r, None) {
        return Err(unevaluated());
    }
    let replays: f64 = r.iter().map(|v| v * v).sum();
    let forces: f64 = f0.iter().map(|v| v * v).sum();
    let (lower_b, upper_b) = law_bounds();
    let upper: Vec<f64> = bounds.1.iter().chain(&upper_b).copied().collect();
    let lower: Vec<f64> = bounds.0.iter().chain(&lower_b).copied().collect();
    let problem = Joint {
        priored,
        unknowns,
        strikers,
        weight: (balance * replays / forces.max(f64::MIN_POSITIVE)).sqrt(),
        upper: upper.clone(),
        forces: f0.len(),
        cells,
    };
    let start: Vec<f64> = p0.iter().chain(&b0).copied().collect();
    let settings = lm::Settings {
        max_iterations: 60,
        ftol: 1e-8,
        xtol: 1e-6,
        ..lm::Settings::default()
    };
    let at_start = replays + balance * replays;
    let outcome = minimise(&problem, &start, &lower, &upper, &settings);
    if outcome.objective.is_finite() && outcome.objective < at_start {
        let n = p0.len();
        let run = &mut searched.runs[best].outcome;
        let p = outcome.parameters[..n].to_vec();
        if priored.evaluate(&p, &mut r, None) {
            run.objective = r.iter().map(|v| v * v).sum();
            run.parameters = p;
            run.iterations += outcome.iterations;
        }
    }
    Ok(searched)
}
