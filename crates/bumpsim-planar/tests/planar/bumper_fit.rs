//! The bumper's law fitted to the training tests' forward runs
//! (`bumpsim_planar::identify::fit_bumper`), on the independent yaw-rate
//! series of tests/peers/planar_yaw_rate.py, whose contact is Hunt–Crossley
//! (`F = k d^1.5 (1 + 1.5 α ḋ)`, elastic and rate-dependent) where
//! bumpsim's bumper is a rate-independent loading curve with an unloading
//! slope. Training tests with a striker: the flat pendulum (8 km/h) and the
//! 10° wall (10 km/h); held out and predicted forward: the 40 % offset 10°
//! wall at 15 km/h.

use super::truth_start::{series, truth_yielding};
use bumpsim_planar::PlanarCar;
use bumpsim_planar::forward::forward;
use bumpsim_planar::identify::fit_bumper;
use bumpsim_planar::study::PlanarStudy;

/// The forward OFFSET40 force, x-acceleration and yaw rate fit %.
fn ahead(car: &PlanarCar, study: &PlanarStudy) -> [f64; 3] {
    let case = study
        .validation
        .iter()
        .find(|c| c.name == "OFFSET40")
        .unwrap();
    let run = forward(car, case).unwrap();
    ["force", "x-acceleration", "yaw rate"].map(|name| {
        run.channels
            .iter()
            .find(|c| c.name == name)
            .unwrap()
            .fit_percent
    })
}

#[test]
fn the_bumper_fitted_at_the_yielding_truth_predicts_the_offset_force() {
    let Some(dir) = series() else { return };
    let sheet: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("series.json")).unwrap()).unwrap();
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let truth = truth_yielding(&study, &sheet);
    let before = ahead(&truth, &study);
    eprintln!("forward OFFSET40 force, x-acceleration, yaw rate: start bumper {before:.2?} %");
    for rate in [false, true] {
        let fit = fit_bumper(&truth, &study.cases, rate).unwrap();
        let after = ahead(&fit.car, &study);
        eprintln!(
            "rate {rate}: a {:.4}, λ {:.4}, u {:.3}, c {:.4} s/m; objective {:.4e} → {:.4e} in {} iterations; training force {:.2?}",
            fit.scale, fit.stretch, fit.unloading_ratio, fit.rate, fit.objective.0, fit.objective.1, fit.iterations, fit.tests
        );
        eprintln!("rate {rate}: forward OFFSET40 force, x-acceleration, yaw rate {after:.2?} %");
        assert!(fit.objective.1 < fit.objective.0);
    }
}
