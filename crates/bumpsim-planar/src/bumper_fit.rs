//! The bumper identified from the training tests' own forward runs.
//! [`identified`] runs the identification ([`crate::identify::identify()`])
//! and, when the study asks (`[model] bumper = "fit"`, `Setup::bumper`),
//! this fit; its result's car then carries the fitted bumper.
//!
//! Every training replay is driven by the measured load-cell forces, so it
//! never sees the bumper's law: the car's segments keep the study's start
//! characteristic, and a forward prediction ([`crate::forward::forward()`]), where the
//! striker's contact with the bumper makes the force, rests on it. Here,
//! after the car is identified, each training test that carries its
//! striker is run forward and the segments' characteristic is fitted to the
//! measured force, with the body and the side members held.
//!
//! Three parameters act on every segment alike, each on a log scale: a
//! force scale `a`, a compression stretch `λ` and the unloading ratio `u`;
//! a fourth, when asked, is the contact's rate coefficient `c` (s/m, from 0
//! to 3; [`crate::car`]'s rate term `F(d) · max(0, 1 + c ḋ)`, the
//! Hunt–Crossley form):
//!
//! - loading `F(d) = a F₀(d/λ)` (a three-part curve: ramp `a s/λ`, plateau
//!   `a F_max`; a table: points `(λ dᵢ, a Fᵢ)`);
//! - unloading slope `s_u = u · max_i(Fᵢ/dᵢ)` with `u ≥ 1`: the line must not
//!   run below the loading curve ([`bumpsim_impact::bumper::Bumper::table`]'s condition).
//!
//! Residuals, per forward-run test `c` over its window: `(F_sim − F_meas) /
//! (max|F_meas| √n_c)`, the simulated and measured force magnitudes
//! aligned at their onsets as [`crate::forward::forward()`] aligns them, so each test
//! weighs alike whatever its force. With [`crate::identify::Setup::cells`]
//! a test whose wall has load cells is compared cell by cell instead
//! ([`crate::cell_force`]): `(F_k,sim − F_k,meas) / (max|F_meas| √n_c)` for
//! each cell k, the same peak total force and window.
//!
//! The bounded Levenberg–Marquardt of [`bumpsim_estimate::lm`] minimises them with the forward-difference
//! Jacobian of [`bumpsim_estimate::difference`] (step 1e-3 in the log
//! parameters and in `c`). Bounds: `a` and `λ` within 1/3 to 3 of the
//! start, `u` from 1 to 20.
//!
//! Without the rate term the bumper is rate-independent (paper A's
//! characteristic, [`bumpsim_impact::bumper`]): a contact whose force grows
//! with the closing speed (Hunt–Crossley, `F = k dⁿ (1 + 1.5 α ḋ)`) is then
//! represented at the training tests' speeds only.
//!
//! With `Setup::joint` the car and the bumper's law are first polished
//! together on the replays and the forward runs (submodule `joint`,
//! src/joint_fit.rs), then the bumper is fitted to the polished car.

use crate::car::{PlanarCar, PlanarError};
use crate::forward::{self, forward};
use crate::identify::{
    BumperFit, PlanarCase, PlanarIdentification, Setup, Unknowns, identify_polished, transformed,
    unloading_ratio,
};
use bumpsim_estimate::difference::forward_jacobian;
use bumpsim_estimate::lm::{LeastSquares, Settings, minimise};
use bumpsim_estimate::multistart::Searched;
use bumpsim_estimate::observer::Observer;
use nalgebra::DMatrix;

#[path = "joint_fit.rs"]
mod joint;

impl crate::study::PlanarStudy {
    /// The study's planar identification, its bumper fitted when it asks
    /// ([`identified`]).
    pub fn identified(&self, observer: &dyn Observer) -> Result<PlanarIdentification, PlanarError> {
        identified(&self.cases, &self.setup, observer)
    }
}

/// Step of the forward differences in the log parameters.
const STEP: f64 = 1e-3;

/// The planar identification of `cases` ([`crate::identify::identify()`]), then, when
/// `setup.bumper`, the bumper fitted to the training tests' forward runs:
/// the result's car carries it and `result.bumper` records it.
pub fn identified(
    cases: &[PlanarCase],
    setup: &Setup,
    observer: &dyn Observer,
) -> Result<PlanarIdentification, PlanarError> {
    let polish = |problem: (&(dyn LeastSquares + Sync), &Unknowns),
                  searched: Searched,
                  bounds: (&[f64], &[f64])| {
        let balance = setup.joint.unwrap_or(1.0);
        joint::polished(problem, cases, searched, bounds, (balance, setup.cells))
    };
    let joint = setup.bumper && setup.joint.is_some();
    let mut result = identify_polished(cases, setup, observer, joint.then_some(&polish as _))?;
    if setup.bumper {
        let fit = fit_bumper(&result.car, cases, true, setup.cells)?;
        result.car = fit.car.clone();
        result.bumper = Some(fit);
    }
    Ok(result)
}

/// `car` with every segment transformed by `p = [ln a, ln λ, ln u]` and,
/// when `p` has a fourth, the rate coefficient `c = p[3]`.
fn with_law(car: &PlanarCar, p: &[f64]) -> Result<PlanarCar, PlanarError> {
    let segments = car
        .beam()
        .segments
        .iter()
        .enumerate()
        .map(|(j, b)| {
            transformed(b, p[0].exp(), p[1].exp(), p[2].exp()).map_err(|source| {
                PlanarError::Bumper {
                    name: format!("bumper.segment[{j}]"),
                    source,
                }
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let car = car.clone().with_segments(segments)?;
    match p.get(3) {
        Some(&rate) => car.with_contact_rate(rate),
        None => Ok(car),
    }
}

struct Problem<'a> {
    car: &'a PlanarCar,
    cases: Vec<&'a PlanarCase>,
    count: usize,
    parameters: usize,
    cells: bool,
}

impl Problem<'_> {
    /// The residuals at `p` (None: a law that cannot be built or run).
    fn residuals(&self, p: &[f64]) -> Option<Vec<f64>> {
        force_residuals(self.car, &self.cases, p, self.cells)
    }
}

/// The force residuals (see the module) of `car` with the bumper law `p`
/// (`[ln a, ln λ, ln u]`, and `c` when it has four) over the forward runs of
/// `cases` (each with its striker); with `cells`, a case whose wall has
/// load cells compared cell by cell ([`crate::cell_force`]: each cell's
/// residuals over the window, normalised by the case's peak total force
/// and window as the total's are); None: a law that cannot be built or run.
pub(crate) fn force_residuals(
    car: &PlanarCar,
    cases: &[&PlanarCase],
    p: &[f64],
    cells: bool,
) -> Option<Vec<f64>> {
    let car = with_law(car, p).ok()?;
    let mut r = Vec::new();
    for case in cases {
        let (ahead, run) = forward::run(&car, case).ok()?;
        let force = ahead.channels.iter().find(|c| c.name == "force")?;
        let (a, b) = ahead.window;
        let peak = force.measured[a..=b]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let norm = peak.max(f64::MIN_POSITIVE) * ((b - a + 1) as f64).sqrt();
        let split = match cells {
            true => crate::cell_force::simulated_cells(&car, case, &run, ahead.shift).ok()?,
            false => Vec::new(),
        };
        if split.is_empty() {
            r.extend((a..=b).map(|k| (force.simulated[k] - force.measured[k]) / norm));
        }
        for (load, simulated) in &split {
            let measured = &case.drive.loads[*load].force;
            r.extend((a..=b).map(|k| (simulated[k] - measured[k]) / norm));
        }
    }
    r.iter().all(|v| v.is_finite()).then_some(r)
}

/// The bumper law's search variables of `fit`, `[ln a, ln λ, ln u, c]`.
pub(crate) fn law(fit: &BumperFit) -> [f64; 4] {
    [
        fit.scale.ln(),
        fit.stretch.ln(),
        fit.unloading_ratio.ln(),
        fit.rate,
    ]
}

/// The bumper law's bounds, lower and upper: `a` and `λ` within 1/3 to 3,
/// `u` from 1 to 20, `c` from 0 to 3 s/m (see the module).
pub(crate) fn law_bounds() -> ([f64; 4], [f64; 4]) {
    let third = 3f64.ln();
    ([-third, -third, 0.0, 0.0], [third, third, 20f64.ln(), 3.0])
}

impl LeastSquares for Problem<'_> {
    fn residual_count(&self) -> usize {
        self.count
    }

    fn parameter_count(&self) -> usize {
        self.parameters
    }

    fn evaluate(
        &self,
        p: &[f64],
        residuals: &mut [f64],
        jacobian: Option<&mut DMatrix<f64>>,
    ) -> bool {
        let Some(r) = self.residuals(p) else {
            return false;
        };
        residuals.copy_from_slice(&r);
        let Some(j) = jacobian else {
            return true;
        };
        let shifted = |q: &[f64], out: &mut [f64]| match self.residuals(q) {
            Some(moved) => {
                out.copy_from_slice(&moved);
                true
            }
            None => false,
        };
        forward_jacobian(p, &r, STEP, &shifted, j)
    }
}

/// The force fit % of `car`'s forward run of `case`.
fn force_fit(car: &PlanarCar, case: &PlanarCase) -> Result<f64, PlanarError> {
    let run = forward(car, case)?;
    Ok(run
        .channels
        .iter()
        .find(|c| c.name == "force")
        .map_or(f64::NAN, |c| c.fit_percent))
}

/// Fits `car`'s bumper law (with the contact's rate coefficient when
/// `rate`) to the measured forces of the `cases` that carry a striker (see
/// the module), a wall's load cells one by one when `cells`
/// ([`crate::identify::Setup::cells`]); an error when none carries a striker.
pub fn fit_bumper(
    car: &PlanarCar,
    cases: &[PlanarCase],
    rate: bool,
    cells: bool,
) -> Result<BumperFit, PlanarError> {
    let cases: Vec<&PlanarCase> = cases.iter().filter(|c| c.striker.is_some()).collect();
    let Some(first) = cases.first() else {
        return Err(PlanarError::Case {
            case: "training".into(),
            message: "fitting the bumper needs training tests with their `striker = { ... }`"
                .into(),
        });
    };
    let parameters = if rate { 4 } else { 3 };
    let ratio = car
        .beam()
        .segments
        .first()
        .map_or(1.0, unloading_ratio)
        .max(1.0);
    // u replaces the segments' own ratio: the start keeps the first one's
    let n = parameters;
    let start = [0.0, 0.0, ratio.ln(), car.contact_rate()][..n].to_vec();
    let (lower, upper) = law_bounds();
    let (lower, upper) = (lower[..n].to_vec(), upper[..n].to_vec());
    let r0 = force_residuals(car, &cases, &start, cells).ok_or_else(|| PlanarError::Case {
        case: first.name.clone(),
        message: "the start car's forward run cannot be evaluated".into(),
    })?;
    let problem = Problem {
        car,
        cases: cases.clone(),
        count: r0.len(),
        parameters,
        cells,
    };
    let settings = Settings {
        max_iterations: 40,
        ftol: 1e-8,
        xtol: 1e-6,
        ..Settings::default()
    };
    let outcome = minimise(&problem, &start, &lower, &upper, &settings);
    let p = &outcome.parameters;
    let fitted = with_law(car, p)?;
    let tests = cases
        .iter()
        .map(|c| Ok((c.name.clone(), force_fit(car, c)?, force_fit(&fitted, c)?)))
        .collect::<Result<Vec<_>, PlanarError>>()?;
    Ok(BumperFit {
        scale: p[0].exp(),
        stretch: p[1].exp(),
        unloading_ratio: p[2].exp(),
        rate: p.get(3).copied().unwrap_or(0.0),
        tests,
        objective: (r0.iter().map(|v| v * v).sum(), outcome.objective),
        iterations: outcome.iterations,
        car: fitted,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Layout;
    use crate::simulate::{Settings as Run, simulate};
    use crate::striker::{Face, Striker};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn car(bumper: &Bumper) -> PlanarCar {
        let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
        PlanarCar::symmetric(&chain, bumper, &Layout::default()).unwrap()
    }

    /// A pendulum test of `truth` at `speed`: its simulated force as the
    /// one load cell, the striker known.
    fn test(truth: &PlanarCar, speed: f64) -> PlanarCase {
        let striker = Striker::pendulum(Face::flat(), 1000.0, speed);
        let step = 1e-4;
        let settings = Run {
            output_step: step,
            duration: 0.12,
            stop_after_contact: false,
            ..Run::default()
        };
        let r = simulate(truth, &striker, &settings).unwrap();
        let name = format!("{speed} m/s");
        crate::forward::tests::pendulum_case(&name, striker, r.force, step, None)
    }

    #[test]
    fn the_fit_recovers_the_bumper_a_car_was_simulated_with() {
        let truth_bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let truth = car(&truth_bumper);
        let cases = [test(&truth, 2.0), test(&truth, 5.0)];
        let peak = cases[1].drive.loads[0]
            .force
            .iter()
            .fold(0.0f64, |m, f| m.max(*f));
        assert!(
            peak > 60e3 * 0.999,
            "the fast test reaches the plateau: {peak} N"
        );
        // the start: 25 % stronger, 20 % shorter, unloading at 1.5 the ramp
        let start = car(&transformed(&truth_bumper, 1.25, 0.8, 1.5).unwrap());
        let fit = fit_bumper(&start, &cases, false, false).unwrap();
        eprintln!("{fit:?}");
        assert!((fit.scale / 0.8 - 1.0).abs() < 0.02, "a {}", fit.scale);
        assert!((fit.stretch / 1.25 - 1.0).abs() < 0.02, "λ {}", fit.stretch);
        assert!(
            (fit.unloading_ratio / 4.0 - 1.0).abs() < 0.05,
            "u {}",
            fit.unloading_ratio
        );
        assert!(
            fit.tests
                .iter()
                .all(|(_, before, after)| after > before && *after > 99.0)
        );
        assert!(fit.objective.1 < 1e-3 * fit.objective.0);
    }

    #[test]
    fn the_fit_recovers_a_rate_dependent_contact() {
        let truth_bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let truth = car(&truth_bumper).with_contact_rate(0.4).unwrap();
        let cases = [test(&truth, 2.0), test(&truth, 5.0)];
        let start = car(&transformed(&truth_bumper, 1.25, 0.8, 1.5).unwrap());
        let fit = fit_bumper(&start, &cases, true, false).unwrap();
        eprintln!(
            "{:?}",
            (fit.scale, fit.stretch, fit.unloading_ratio, fit.rate)
        );
        assert!((fit.rate / 0.4 - 1.0).abs() < 0.05, "c {}", fit.rate);
        assert!((fit.scale / 0.8 - 1.0).abs() < 0.05, "a {}", fit.scale);
        assert!(fit.objective.1 < 1e-3 * fit.objective.0);
        // without the rate term the same tests are not fitted as well
        let static_fit = fit_bumper(&start, &cases, false, false).unwrap();
        assert!(static_fit.objective.1 > 10.0 * fit.objective.1);
    }

    #[test]
    fn a_study_without_strikers_is_refused() {
        let truth = car(&Bumper::three_part(1.5e6, 60e3, 6e6).unwrap());
        let mut case = test(&truth, 2.0);
        case.striker = None;
        let err = fit_bumper(&truth, &[case], false, false)
            .unwrap_err()
            .to_string();
        assert!(err.contains("striker"), "{err}");
    }
}
