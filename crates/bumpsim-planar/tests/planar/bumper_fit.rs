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
use bumpsim_planar::bumper_fit::fit_bumper;
use bumpsim_planar::forward::forward;
use bumpsim_planar::identify::{LinkLaw, LinkLaws, PlanarIdentification};
use bumpsim_planar::study::PlanarStudy;

/// The study identified with every side-member link of `law` and its
/// bumper fitted (`bumper_fit::identified`, the study's `setup.bumper`).
fn identified(study: &PlanarStudy, law: LinkLaw) -> PlanarIdentification {
    let template = &study.setup.template;
    let laws = LinkLaws {
        left: vec![law; template.left().masses.len()],
        right: vec![law; template.right().masses.len()],
    };
    let mut setup = study.setup.clone();
    setup.template = laws.apply(template).unwrap();
    let result = bumpsim_planar::bumper_fit::identified(&study.cases, &setup, &|| {}).unwrap();
    for f in &result.fits {
        eprintln!(
            "{}: training {} x {:.2} %, yaw {:.2} %",
            law.word(),
            f.name,
            f.fit_x,
            f.fit_yaw
        );
    }
    result
}

/// `car` with the study's start bumper and no rate term.
fn start_bumper(car: &PlanarCar, study: &PlanarStudy) -> PlanarCar {
    let segments = study.setup.template.beam().segments.clone();
    let car = car.clone().with_segments(segments).unwrap();
    car.with_contact_rate(0.0).unwrap()
}

/// The forward OFFSET40 force, x-acceleration and yaw rate fit %.
fn ahead(car: &PlanarCar, study: &PlanarStudy) -> [f64; 3] {
    let case = study
        .validation
        .iter()
        .find(|c| c.name == "OFFSET40")
        .unwrap();
    let run = forward(car, case).unwrap();
    ["force", "x-acceleration", "yaw rate"].map(|name| run.fit_of(name).unwrap())
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
        let fit = fit_bumper(&truth, &study.cases, rate, study.setup.cells).unwrap();
        let after = ahead(&fit.car, &study);
        eprintln!(
            "rate {rate}: a {:.4}, λ {:.4}, u {:.3}, c {:.4} s/m; objective {:.4e} → {:.4e} in {} iterations; training force {:.2?}",
            fit.scale,
            fit.stretch,
            fit.unloading_ratio,
            fit.rate,
            fit.objective.0,
            fit.objective.1,
            fit.iterations,
            fit.tests
        );
        eprintln!("rate {rate}: forward OFFSET40 force, x-acceleration, yaw rate {after:.2?} %");
        assert!(fit.objective.1 < fit.objective.0);
        // measured (see docs/planar.md): no rate term 84.8, 84.8 %; with it
        // c = 0.359 s/m against the generator's 1.5 α = 0.375, and 94.2,
        // 94.1 % (the yaw rate falls from 84.7 to 77.3 %)
        match rate {
            false => assert!(after[0] < 90.0, "{after:?}"),
            true => {
                let truth = 1.5 * sheet["car"]["beam"]["hc_damping"].as_f64().unwrap();
                assert!(
                    (fit.rate / truth - 1.0).abs() < 0.1,
                    "c {} against {truth}",
                    fit.rate
                );
                assert!(after[0] >= 90.0 && after[1] >= 90.0, "{after:?}");
            }
        }
    }
}

/// Issue 44's forward offset thresholds on this series with the identified
/// car (yielding side members, C_α and the relaxation length estimated, 16
/// starts, the stated priors and the staged search, as `yaw_rate.rs`'s
/// issue-44 test) and the study's `bumper = "fit"`: force and
/// x-acceleration ≥ 90 %.
///
/// Measured (release, 22 s): the start bumper 80.79, 80.35 % (yaw rate
/// 91.19 %); fitted (c = 0.325 s/m) 92.02, 91.96 % (yaw rate 85.31 %) ✓.
/// With the side-member values the training leaves open (the left crash
/// box's hardening, the right box's stiffness and yield) set to the
/// generator's and the bumper fitted again: 91.04, 91.35 % (c = 0.320 s/m;
/// yaw rate 75.32 %): they no longer decide the forward force. (Before the
/// generator's crash-box couple was fixed and with the start's relaxed
/// tyres: 83.94 % fitted, 95.84 % with those values.) Ignored: the same
/// identification runs in `yaw_rate.rs`'s acceptance.
#[test]
#[ignore = "issue 44's forward offset force with the fitted bumper: measured 92.02 % (80.79 % with the start bumper); the same identification as yaw_rate.rs's acceptance, which runs; run with --ignored"]
fn the_identified_car_with_the_fitted_bumper_predicts_the_offset_force() {
    let Some(dir) = series() else { return };
    let mut study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    study.setup.cornering = true;
    study.setup.relaxation = true;
    study.setup.bumper = true;
    let result = identified(&study, LinkLaw::Yielding);
    let fit = result.bumper.as_ref().expect("the fitted bumper");
    let before = ahead(&start_bumper(&result.car, &study), &study);
    eprintln!("identified: start bumper forward OFFSET40 {before:.2?} %");
    let after = ahead(&result.car, &study);
    eprintln!(
        "identified: a {:.4}, λ {:.4}, u {:.3}, c {:.4} s/m; training force {:.2?}",
        fit.scale, fit.stretch, fit.unloading_ratio, fit.rate, fit.tests
    );
    eprintln!("identified: forward OFFSET40 force, x-acceleration, yaw rate {after:.2?} %");
    // diagnosis: the side members the training does not determine (the
    // left hardening, the right box's stiffness and yield) set to the
    // generator's, the bumper fitted again
    let sheet: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("series.json")).unwrap()).unwrap();
    let boxes = &sheet["car"]["crash_boxes"];
    let number = |v: &serde_json::Value| v.as_f64().unwrap();
    let (k, h) = (number(&boxes["elastic"][0]), number(&boxes["hardening"][0]));
    let laws = LinkLaws {
        left: vec![LinkLaw::Yielding],
        right: vec![LinkLaw::Yielding],
    };
    let template = laws.apply(&study.setup.template).unwrap();
    let unknowns = bumpsim_planar::identify::Unknowns::new(
        &template,
        study.setup.friction,
        true,
        &study.cases,
    )
    .with_relaxation(true);
    let theta: Vec<f64> = result
        .parameters
        .iter()
        .map(|p| match p.name.as_str() {
            "left.hardening[0]" => h / (k + h),
            "right.springs[0]" => number(&boxes["elastic"][1]),
            "right.yield_force[0]" => number(&boxes["yield"][1]),
            _ => p.value,
        })
        .collect();
    let mended = unknowns.car(&theta).unwrap();
    let refit = fit_bumper(&mended, &study.cases, true, study.setup.cells).unwrap();
    eprintln!(
        "identified, side members the training leaves open set to the generator's: c {:.4} s/m, forward OFFSET40 {:.2?} %",
        refit.rate,
        ahead(&refit.car, &study)
    );
    assert!(after[0] >= before[0] + 5.0, "{after:?} against {before:?}");
    let mended = ahead(&refit.car, &study);
    assert!(mended[0] >= 90.0 && mended[1] >= 90.0, "{mended:?}");
    assert!(after[0] >= 90.0 && after[1] >= 90.0, "{after:?}");
}

/// Issue 46's forward offset force (≥ 80 %) on the progressive series of
/// tests/peers/planar_progressive.py (the same Hunt–Crossley contact),
/// identified with progressive side members and `bumper = "fit"`.
///
/// Measured first (release, 16 starts, about 150 s under load): the start
/// bumper 60.72 % (x-acceleration 60.28 %, yaw rate 81.14 %); fitted (c =
/// 0.223 s/m against the generator's 0.375; training force 77.2 → 85.4 %
/// and 84.6 → 88.2 %) 70.75 % (71.37 %, yaw rate 70.90 %) ✗. Measured
/// again on 2026-11-30 (b5e17fa, release, 6 s): the identified car
/// with its start bumper 80.54 % (80.83 %, yaw rate 77.07 %), fitted
/// (a 0.662, λ 0.820, u 1.012, c 0 s/m: the rate term at its bound;
/// training force PENDULUM 72.82 → 85.04 %, WALL10 89.87 → 86.88 %)
/// 66.40 % (66.51 %, 72.38 %) ✗: the fit buys the pendulum's force with
/// the wall's, and the 15 km/h wall pays. With the wall's cells compared
/// one by one (w17-h1, the default): 70.12 % (70.32 %, 70.25 %) ✗.
#[test]
#[ignore = "issue 46's forward offset force with the fitted bumper: measured 70.12 % (80.54 % with the start bumper, 2026-11-30); a release identification of 16 starts; run with --ignored"]
fn the_progressive_series_with_the_fitted_bumper_predicts_the_offset_force() {
    if !bumpsim_peers::python_available("numpy") {
        return;
    }
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("planar-progressive");
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/peers/planar_progressive.py");
    bumpsim_peers::generated(&script, &dir, &[], "study.toml");
    let mut study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    study.setup.bumper = true;
    // the wall's cells compared one by one, as the study with `bumper =
    // "fit"` has it by default since w17-h1 (its training wall has cells,
    // so it estimates the width too); `BUMPSIM_CELLS=0`: by the total force
    study.setup.cells = std::env::var("BUMPSIM_CELLS").map_or(study.setup.width, |c| c != "0");
    // `BUMPSIM_NO_WIDTH=1`: the drawn width. The study's default estimates
    // the effective width from its wall cells (w16-h1, release): forward
    // force / x-acc / yaw rate with the fitted bumper 66.40 / 66.51 /
    // 72.38 %, with the drawn width 65.51 / 65.64 / 73.34 %;
    // the assertion fails either way. With the
    // wall's cells compared one by one (w17-h1) 70.12 / 70.32 / 70.25 %
    // (w_e 1.5805 m; with the width's prior at 0.05, 69.95 / 70.13 /
    // 38.58 %, w_e 1.4889 m: hence that prior only with the joint stage)
    study.setup.width &= std::env::var("BUMPSIM_NO_WIDTH").is_err();
    // `BUMPSIM_WIDTH_SPREAD=0.02`: the width's prior spread (`[priors]`)
    if let Ok(spread) = std::env::var("BUMPSIM_WIDTH_SPREAD") {
        let setting = bumpsim_planar::identify::PriorSetting {
            name: bumpsim_planar::identify::EFFECTIVE_WIDTH.into(),
            removed: false,
            value: None,
            spread: Some(spread.parse().unwrap()),
        };
        study.setup.priors.push(setting);
    }
    let result = identified(&study, LinkLaw::Progressive);
    let width = |m: &&bumpsim_estimate::prior::Moved| {
        m.name == bumpsim_planar::identify::EFFECTIVE_WIDTH || m.name == "body.yaw_inertia"
    };
    for m in result.priors.iter().filter(width) {
        eprintln!("progressive: {} {:.4} ({:+.2} sd)", m.name, m.estimate, m.z);
    }
    let fit = result.bumper.as_ref().expect("the fitted bumper");
    let before = ahead(&start_bumper(&result.car, &study), &study);
    let after = ahead(&result.car, &study);
    eprintln!(
        "progressive: a {:.4}, λ {:.4}, u {:.3}, c {:.4} s/m; training force {:.2?}",
        fit.scale, fit.stretch, fit.unloading_ratio, fit.rate, fit.tests
    );
    eprintln!(
        "progressive: forward OFFSET40 force, x-acceleration, yaw rate: start bumper {before:.2?} %, fitted {after:.2?} %"
    );
    assert!(after[0] >= 80.0, "{after:?}");
}

/// `[model] bumper = "fit"` asks for the fit; "start" (or nothing) keeps
/// the start car's bumper; anything else is refused by name.
#[test]
fn the_study_asks_for_the_fit_by_name() {
    let Some(dir) = series() else { return };
    let text = std::fs::read_to_string(dir.join("study.toml")).unwrap();
    let with = |value: &str| {
        let path = dir.join(format!("study-bumper-{value}.toml"));
        let body = text.replacen("[model]", &format!("[model]\nbumper = \"{value}\""), 1);
        std::fs::write(&path, body).unwrap();
        PlanarStudy::read(&path)
    };
    assert!(with("fit").unwrap().setup.bumper);
    assert!(!with("start").unwrap().setup.bumper);
    assert!(
        !PlanarStudy::read(&dir.join("study.toml"))
            .unwrap()
            .setup
            .bumper
    );
    let err = with("foam").unwrap_err().to_string();
    assert!(err.contains("[model] bumper = \"foam\""), "{err}");
    // the bumper's effective width: estimated by default on a study with
    // wall cells, `effective_width = false` keeps the start car's
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    assert!(study.setup.width, "wall cells: the width estimated");
    let path = dir.join("study-width-false.toml");
    let body = text.replacen("[model]", "[model]\neffective_width = false", 1);
    std::fs::write(&path, body).unwrap();
    assert!(!PlanarStudy::read(&path).unwrap().setup.width);
    // the forward runs compared cell by cell: by default with the bumper
    // fitted to a study with wall cells, never without the fit
    assert!(with("fit").unwrap().setup.cells, "wall cells and the fit");
    assert!(!study.setup.cells, "no fit: no forward runs to compare");
    let cells = |model: &str| {
        let path = dir.join("study-cells.toml");
        std::fs::write(&path, text.replacen("[model]", model, 1)).unwrap();
        PlanarStudy::read(&path)
    };
    let kept = cells("[model]\nbumper = \"fit\"\ncells = false").unwrap();
    assert!(kept.setup.bumper && !kept.setup.cells);
    let err = cells("[model]\ncells = true").unwrap_err().to_string();
    assert!(
        err.contains("[model] cells") && err.contains("bumper = \"fit\""),
        "{err}"
    );
    let err = cells("[model]\ncells = \"yes\"").unwrap_err().to_string();
    assert!(err.contains("cells"), "{err}");
    // the search confirmed at the final noise only when asked
    assert!(!study.setup.confirm);
    assert!(cells("[model]\nconfirm = true").unwrap().setup.confirm);
    let err = cells("[model]\nconfirm = \"yes\"").unwrap_err().to_string();
    assert!(err.contains("confirm"), "{err}");
}
