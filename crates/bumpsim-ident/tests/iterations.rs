//! Issue 44 item 6: from its default (data-derived) start, one start,
//! bumpsim's LM with the trust region ([`Damping::TrustRegion`]; the 1-D
//! identification's default is still Nielsen's damping, see
//! docs/identify.md "Iterations") needs no more iterations than scipy's
//! `least_squares`
//! (trust-region-reflective, 2-point differences) needs Jacobian
//! evaluations from the same start, for the same optimum (objectives within
//! 1e-6, relative). The series is `bench/peers/scipy_identify.py`'s (three
//! synthetic pendulum cases, 500 samples each), written and fitted by
//! `tests/peers/scipy_trf_iterations.py`; skipped without scipy.

use bumpsim_estimate::lm::Damping;
use bumpsim_estimate::observer::Silent;
use bumpsim_ident::{Study, identify};
use std::path::{Path, PathBuf};
use std::process::Command;

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
    let mut settings = study.settings(3).unwrap();
    settings.solver.damping = Damping::TrustRegion;
    // scipy fits the data alone: no stated priors (the velocity objective's
    // defaults would polish towards the start's element priors)
    settings.default_priors = false;
    let result = identify(&cases, &settings, &Silent).unwrap();
    let (njev, value) = trf(&out, objective, &result.start);
    eprintln!(
        "{objective}: bumpsim {} iterations, objective {:e}; scipy TRF {njev} Jacobians, {value:e}",
        result.iterations, result.objective
    );
    assert!(
        (result.objective / value - 1.0).abs() < 1e-6,
        "{objective}: objective {:e} against scipy's {value:e}",
        result.objective
    );
    assert!(
        result.iterations <= njev,
        "{objective}: {} LM iterations against scipy's {njev} Jacobians",
        result.iterations
    );
}

/// Open (issue 44 item 6): the trust region takes 22 iterations here
/// against scipy's 18 (19 screening to `SCREEN_FTOL`, then 3 polishing
/// from a fresh radius; the earlier damping 31). Measured 2026-11-29 on the
/// data alone (before, this test left the velocity objective's default
/// element priors on: 36 iterations to an optimum 2e-4 above scipy's,
/// which fits no priors), with the variants of scipy's TRF tried in turn:
///
/// | step scaling, first radius | velocity | displacement |
/// |---|---|---|
/// | column norms of J, 100 × ‖D p‖ (MINPACK's; this one) | 22 | 38 |
/// | column norms of J, ‖D p‖ | 27 | 64 |
/// | none (scipy's `x_scale = 1` in log parameters), 100 × ‖p‖ | **17** | 106 |
/// | none, ‖p‖ | 29 | — |
/// | Coleman–Li `√(p − lower)` where the gradient points at the bound (scipy's TRF), 100 × | 17, optimum 7e-6 above scipy's | 44, 1.6 % above |
/// | column norms, MINPACK's radius update (`½ dirder/(dirder + ½ actred)` shrink, 2 ‖step‖ growth) | 27 | 60 |
///
/// No one rule meets both: without scaling the velocity objective holds
/// but the displacement one zigzags along its narrow valley (each trial
/// at a doubled radius refused, the next accepted at a quarter), and the
/// screening's restart is where the column scaling loses its iterations.
/// Run with `--ignored`.
#[test]
#[ignore = "open: 22 LM iterations against scipy's 18 Jacobians (issue 44 item 6; variants in the doc)"]
fn velocity_iterations_are_no_more_than_scipy_trf_jacobians() {
    compare("velocity");
}

#[test]
fn displacement_iterations_are_no_more_than_scipy_trf_jacobians() {
    compare("displacement");
}
