//! Issue 44 item 6: from its default (data-derived) start, one start,
//! bumpsim's LM with the trust region ([`Damping::TrustRegion`]; the 1-D
//! identification's default is still Nielsen's damping, see
//! docs/identify.md "Iterations") needs no more Jacobians than scipy's
//! `least_squares` (trust-region-reflective, 2-point differences) evaluates
//! from the same start, for the same optimum (objectives within 1e-9,
//! relative: both stop at the same precision, so neither count is bought
//! with a looser tolerance). Like for like: scipy's `njev` counts the
//! start's Jacobian and one per accepted step; bumpsim's count is the
//! normal equations LM forms (`LeastSquares::normal`: the start's and one
//! per accepted step, its iterations + 1), counted on the problem itself.
//! The series is `bench/peers/scipy_identify.py`'s (three synthetic
//! pendulum cases, 500 samples each), written and fitted by
//! `tests/peers/scipy_trf_iterations.py`; skipped without scipy.

use bumpsim_estimate::lm::{self, Damping, LeastSquares};
use bumpsim_ident::Study;
use bumpsim_ident::case::Objective;
use bumpsim_ident::estimate::data_start;
use nalgebra::{DMatrix, DVector};
use std::cell::Cell;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A problem that counts the Jacobians (normal equations) LM asks for.
struct Counted<'a> {
    objective: Objective<'a>,
    jacobians: Cell<usize>,
}

impl LeastSquares for Counted<'_> {
    fn residual_count(&self) -> usize {
        self.objective.residual_count()
    }
    fn parameter_count(&self) -> usize {
        self.objective.parameter_count()
    }
    fn evaluate(&self, p: &[f64], r: &mut [f64], jacobian: Option<&mut DMatrix<f64>>) -> bool {
        self.jacobians
            .set(self.jacobians.get() + usize::from(jacobian.is_some()));
        self.objective.evaluate(p, r, jacobian)
    }
    fn normal(
        &self,
        p: &[f64],
        r: &mut [f64],
        jtj: &mut DMatrix<f64>,
        g: &mut DVector<f64>,
    ) -> bool {
        self.jacobians.set(self.jacobians.get() + 1);
        self.objective.normal(p, r, jtj, g)
    }
}

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/scipy_trf_iterations.py")
}

/// The series and its study, written once per target folder.
fn series() -> Option<PathBuf> {
    if !bumpsim_peers::python_available("scipy") {
        return None;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("scipy-trf-iterations");
    bumpsim_peers::generated(&script(), &out, &[], "study.toml");
    Some(out)
}

/// scipy's Jacobian evaluations and objective from `start` (SI).
fn trf(out: &Path, objective: &str, start: &[f64]) -> (usize, f64) {
    let run = Command::new("python3")
        .arg(script())
        .arg(out)
        .arg(objective)
        .args(start.iter().map(|v| format!("{v:e}")))
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = String::from_utf8(run.stdout).unwrap();
    let mut words = text.split_whitespace();
    let njev = words.next().unwrap().parse().unwrap();
    (njev, words.next().unwrap().parse().unwrap())
}

fn compare(objective: &str) {
    let Some(out) = series() else { return };
    let mut study = Study::read(&out.join("study.toml")).unwrap();
    study.identification.objective = Some(objective.into());
    let cases = study.cases(3).unwrap();
    let settings = study.settings(3).unwrap();
    // the identification's own solver and bounds, the trust region, the data
    // alone (scipy fits no priors), one start: the data-derived one
    let solver = lm::Settings {
        damping: Damping::TrustRegion,
        ..settings.solver
    };
    let start = data_start(&cases, 3);
    let log = |v: &[f64]| -> Vec<f64> { v.iter().map(|x| x.ln()).collect() };
    let problem = Counted {
        objective: Objective::new(&cases, 3, &settings.bounds.fixed),
        jacobians: Cell::new(0),
    };
    let outcome = lm::minimise(
        &problem,
        &log(&start),
        &log(&settings.bounds.lower),
        &log(&settings.bounds.upper),
        &solver,
    );
    assert!(outcome.stop.converged(), "{:?}", outcome.stop);
    let jacobians = problem.jacobians.get();
    assert_eq!(jacobians, outcome.iterations + 1, "one per accepted step");
    let (njev, value) = trf(&out, objective, &start);
    eprintln!(
        "{objective}: bumpsim {jacobians} Jacobians ({} iterations), objective {:e}; scipy TRF {njev} Jacobians, {value:e}",
        outcome.iterations, outcome.objective
    );
    assert!(
        (outcome.objective / value - 1.0).abs() < 1e-9,
        "{objective}: objective {:e} against scipy's {value:e}",
        outcome.objective
    );
    assert!(
        jacobians <= njev,
        "{objective}: {jacobians} Jacobians against scipy's {njev}"
    );
}

/// Open (issue 44 item 6): the trust region forms 23 Jacobians here (22
/// accepted steps) against scipy's 18, to the same optimum (scipy's ends
/// 1.2e-12 above bumpsim's, scipy stopped by its `ftol`, bumpsim by its
/// directional rule; displacement: 39 against 60, objectives equal to
/// 1e-13). Both reach 3e-5 above the optimum at their 11th Jacobian;
/// bumpsim then creeps along a curved valley (steps at the radius, 0.35
/// and 0.7 scaled, the doubled radius refused each time), where scipy's
/// unscaled steps reach the optimum in 7 more. Measured 2026-11-29 on the
/// data alone, iterations (Jacobians less one) of the variants of scipy's
/// TRF tried in turn:
///
/// | step scaling, first radius | velocity | displacement |
/// |---|---|---|
/// | column norms of J, 100 × ‖D p‖ (MINPACK's; this one) | 22 | 38 |
/// | column norms of J, ‖D p‖ | 27 | 64 |
/// | MINPACK's non-decreasing column norms (`D_k = max(D_k−1, ‖J_i‖)`), 100 × | 21 | 49 |
/// | none (scipy's `x_scale = 1` in log parameters), 100 × ‖p‖ | **17** | 106 |
/// | none, ‖p‖ | 29, stops 4e-6 above | 104, 2.6 % above |
/// | Coleman–Li `√(p − lower)` where the gradient points at the bound (scipy's TRF), 100 × | 17, optimum 7e-6 above scipy's | 44, 1.6 % above |
/// | column norms, MINPACK's radius update (`½ dirder/(dirder + ½ actred)` shrink, 2 ‖step‖ growth) | 27 | 60 |
/// | column norms, the directional stop only after a Gauss–Newton (interior) step | 22 | 38 |
///
/// No one rule meets both: without scaling the velocity objective holds
/// but the displacement one zigzags along its narrow valley (each trial
/// at a doubled radius refused, the next accepted at a quarter). Not
/// tried: geodesic acceleration (Transtrum & Sethna 2012) and Broyden's
/// rank-1 updates of J between evaluations both need J or `Jᵀv` for a new
/// vector, and LM's problems hand it only `JᵀJ` and `Jᵀr`
/// (`LeastSquares::normal`, the modal form never stores J).
/// Run with `--ignored`.
#[test]
#[ignore = "open: 23 Jacobians against scipy's 18 (issue 44 item 6; variants in the doc)"]
fn velocity_iterations_are_no_more_than_scipy_trf_jacobians() {
    compare("velocity");
}

#[test]
fn displacement_iterations_are_no_more_than_scipy_trf_jacobians() {
    compare("displacement");
}
