//! Issue 44: the objective's domain on an independent pendulum series of a
//! 3-mass car (tests/peers/pendulum_independent.py: a swinging pendulum,
//! Hunt–Crossley contact, rolling resistance, DOP853, anti-alias filter,
//! load-cell and accelerometer noise, accelerometer biases; written without
//! bumpsim). Each noise draw is identified as docs/identify.md's study does
//! (CFC 180, bias from the pre-trigger, the contact window, 3 masses).
//!
//! - **Coverage**: in the velocity domain (the default), weighted by each case's
//!   pre-trigger noise, with the intervals widened by the residuals'
//!   integrated autocorrelation time, the 95 % intervals of the seven
//!   parameters contain the truth in 85–99 % of 50 draws × 7 parameters.
//! - **The default's evidence** (docs/identify.md prints this table): on
//!   10 draws, the three domains' parameter errors against the truth, their
//!   coverage, and the held-out fit (each test predicted by the model
//!   refitted to the other two, [`cross_validate`]), the domains compared
//!   without the stated priors (with them, the element priors centred on
//!   the data-derived start pull the weakly determined m2: the velocity
//!   row's median worst error was 8.5 % against 7.2 %).

use bumpsim_estimate::observer::Silent;
use bumpsim_ident::crossval::cross_validate;
use bumpsim_ident::study::DofSpec;
use bumpsim_ident::{Identification, Study, identify};
use std::path::{Path, PathBuf};

/// Noise draws of the coverage test.
const DRAWS: usize = 50;
/// Draws of the domains' comparison.
const COMPARED: usize = 10;

/// The independent series (`DRAWS` noise draws), written once per target dir.
fn series() -> Option<PathBuf> {
    if !bumpsim_peers::present(
        bumpsim_peers::python_available("scipy"),
        "python3 with scipy",
    ) {
        return None;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("pendulum-coverage");
    let script =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/pendulum_independent.py");
    bumpsim_peers::generated(&script, &out, &[&DRAWS.to_string()], "truth.json");
    Some(out)
}

/// The truth's seven parameters, thesis order, SI.
fn truth(dir: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(dir.join("truth.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let car = &json["car"];
    ["masses", "dampers", "springs"]
        .iter()
        .flat_map(|kind| car[kind].as_array().unwrap().clone())
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// Draw `k` identified with 3 masses in `objective`, 8 starts, with the
/// study's default priors when `priors` (the draws' studies state no sheet
/// mass: each element within a factor 10 of the start).
fn identified(dir: &Path, k: usize, objective: &str, priors: bool) -> (Identification, f64) {
    let mut study = Study::read(&dir.join(format!("draw-{k}/study.toml"))).unwrap();
    study.identification.objective = Some(objective.into());
    study.model.dof = DofSpec::One(3);
    let cases = study.cases(3).unwrap();
    let mut settings = study.settings(3).unwrap();
    settings.default_priors &= priors;
    let result = identify(&cases, &settings, &Silent).unwrap();
    let held_out = cross_validate(&cases, &settings, &result)
        .map(|cv| {
            cv.folds
                .iter()
                .map(|f| f.fit_percent)
                .fold(f64::INFINITY, f64::min)
        })
        .unwrap_or(f64::NAN);
    (result, held_out)
}

/// How many of the parameters' 95 % intervals contain `truth`.
fn covered(result: &Identification, truth: &[f64]) -> usize {
    result
        .uncertainty
        .ci95
        .iter()
        .zip(truth)
        .filter(|(ci, t)| ci.is_some_and(|[lo, hi]| lo <= **t && **t <= hi))
        .count()
}

/// The largest relative error of the parameters against `truth`.
fn worst_error(result: &Identification, truth: &[f64]) -> f64 {
    let theta = result.model.parameters();
    theta
        .iter()
        .zip(truth)
        .map(|(v, t)| (v / t - 1.0).abs())
        .fold(0.0, f64::max)
}

#[test]
fn velocity_intervals_cover_an_independent_generators_truth() {
    let Some(dir) = series() else { return };
    let truth = truth(&dir);
    let (mut inside, mut total) = (0, 0);
    for k in 0..DRAWS {
        let (result, _) = identified(&dir, k, "velocity", true);
        inside += covered(&result, &truth);
        total += truth.len();
    }
    let share = inside as f64 / total as f64;
    println!(
        "coverage of the 95 % intervals: {inside} of {total} ({:.1} %)",
        100.0 * share
    );
    assert!(
        (0.85..=0.99).contains(&share),
        "coverage {share}: {inside} of {total}"
    );
}

#[test]
fn the_domains_compared_on_an_independent_series() {
    let Some(dir) = series() else { return };
    let truth = truth(&dir);
    println!("objective      median worst error  coverage  worst held-out fit");
    let mut medians = Vec::new();
    for objective in ["displacement", "velocity", "acceleration"] {
        let (mut errors, mut inside, mut held) = (Vec::new(), 0, f64::INFINITY);
        for k in 0..COMPARED {
            let (result, held_out) = identified(&dir, k, objective, false);
            errors.push(worst_error(&result, &truth));
            inside += covered(&result, &truth);
            held = held.min(held_out);
        }
        errors.sort_by(f64::total_cmp);
        let median = errors[COMPARED / 2];
        println!(
            "{objective:<14} {:>17.1} %  {:>3} of {}  {held:>17.2} %",
            100.0 * median,
            inside,
            COMPARED * truth.len()
        );
        medians.push(median);
    }
    // the velocity domain's estimates are the closest to the truth
    assert!(
        medians[1] < medians[0] && medians[1] < medians[2],
        "{medians:?}"
    );
}
