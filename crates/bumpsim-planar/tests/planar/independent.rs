//! Issue 32's acceptance: the planar car identified from an independent
//! asymmetric series predicts the tests it has not seen.
//!
//! The series is written by tests/peers/planar_independent.py, a model of
//! another family (progressive side-member springs on guides whose
//! reactions are solved for, a rigid beam on 40 foam strips with
//! bottoming, Magic-Formula tyres with transient slip, RK4): a flat
//! pendulum, a centred pole and a 10° wall with four load cells to train
//! on; a 40 % offset at 15 km/h and an offset pole held out. With
//! `--yaw-rate` the same family in issue 44's layout (the sills and a
//! yaw-rate sensor, the held-out offset a 10° wall): the documented study's
//! measurement at the end.

use bumpsim_planar::forward::forward;
use bumpsim_planar::identify::{CaseFit, identify, predict};
use bumpsim_planar::study::PlanarStudy;
use std::path::{Path, PathBuf};

fn series() -> Option<PathBuf> {
    generated("planar-independent", &[], "study.toml")
}

/// The generator run with `args` into the test target's folder `name`,
/// once (None without numpy).
fn generated(name: &str, args: &[&str], marker: &str) -> Option<PathBuf> {
    if !bumpsim_peers::python_available("numpy") {
        return None;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let script =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/planar_independent.py");
    bumpsim_peers::generated(&script, &out, args, marker);
    Some(out)
}

#[test]
fn an_independent_asymmetric_series_predicts_its_held_out_tests() {
    let Some(dir) = series() else { return };
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let sheet: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("series.json")).unwrap()).unwrap();
    let result = identify(&study.cases, &study.setup, &|| {}).unwrap();
    for p in &result.parameters {
        eprintln!(
            "{:<40} {:>12.5e} {:<6} {:?} {:?}",
            p.name, p.value, p.unit, p.ci95, p.determined
        );
    }
    eprintln!("starts {:?}", result.starts);
    for w in &result.warnings {
        eprintln!("warning: {w}");
    }
    for f in &result.fits {
        eprintln!(
            "fitted {}: x {:.2} %, yaw {:.2} %",
            f.name, f.fit_x, f.fit_yaw
        );
    }
    let held = held_out(&study, &result.car);
    let offset = study
        .validation
        .iter()
        .find(|c| c.name == "OFFSET40")
        .unwrap();
    let ahead = forward(&result.car, offset).unwrap();
    for c in &ahead.channels {
        eprintln!("forward {}: {:.2} %", c.name, c.fit_percent);
    }
    let mass = result.car.total_mass();
    let sheet_mass = sheet["total_mass"].as_f64().unwrap();
    let inertia = result
        .parameters
        .iter()
        .find(|p| p.name == "body.yaw_inertia")
        .unwrap();
    let truth_inertia = sheet["yaw_inertia"].as_f64().unwrap();
    eprintln!(
        "mass {mass:.1} kg (sheet {sheet_mass}), I_z {:.0} (truth {truth_inertia})",
        inertia.value
    );
    let fit = |name: &str| held.iter().find(|f| f.name == name).unwrap();
    assert!(
        fit("OFFSET40").fit_x >= 99.5 && fit("OFFSET40").fit_yaw >= 95.0,
        "{held:?}"
    );
    assert!(
        fit("POLE-OFFSET").fit_x >= 99.3 && fit("POLE-OFFSET").fit_yaw > 0.0,
        "{held:?}"
    );
    let channel = |name: &str| ahead.fit_of(name).unwrap();
    assert!(
        channel("force") >= 85.0 && channel("x-acceleration") >= 85.0,
        "{ahead:?}"
    );
    assert!(channel("yaw rate") >= 70.0, "{ahead:?}");
    assert!(
        (mass - sheet_mass).abs() <= 0.01 * sheet_mass,
        "mass {mass} kg"
    );
    let close = (inertia.value - truth_inertia).abs() <= 0.25 * truth_inertia;
    assert!(close || inertia.determined == Some(false), "{inertia:?}");
}

/// Issue 44's search criterion on this series: ≥ 4 of 16 starts reach a
/// fit the data cannot tell from the best of the final objective. The
/// default search's starts weigh the priors at 10.2× the final noise
/// (`bumpsim identify` on the series' `study.toml` prints so), and each is
/// then carried along the best's continuation to the final objective,
/// where the tally counts them; with `confirm` the search runs again at
/// the final noise. Measured (release, 3 s a search): 16 of 16 both ways (counts
/// printed), within κ = 34.2 and 34.3 noise variances; the confirmed car's held-out
/// OFFSET40 x 99.85 %, yaw 96.07 %, POLE-OFFSET x 99.31 %, yaw 97.68 %.
#[test]
fn both_searches_find_their_best_from_most_starts() {
    use bumpsim_planar::identify::CONFIRMED;
    let Some(dir) = series() else { return };
    let mut study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let first = identify(&study.cases, &study.setup, &|| {}).unwrap();
    eprintln!("default search: starts {:?}", first.starts);
    assert!(
        first.search_noise > CONFIRMED * first.prior_noise,
        "{first:?}"
    );
    assert!(first.starts.reached_correlated >= 4, "{:?}", first.starts);
    study.setup.confirm = true;
    let result = identify(&study.cases, &study.setup, &|| {}).unwrap();
    eprintln!("confirmed search: starts {:?}", result.starts);
    assert!(result.search_noise <= CONFIRMED * result.prior_noise);
    assert!(result.starts.reached_correlated >= 4, "{:?}", result.starts);
    assert!(result.starts.inflation > 1.0, "{:?}", result.starts);
    let held = held_out(&study, &result.car);
    assert!(held[0].fit_x >= 99.5 && held[0].fit_yaw >= 95.0, "{held:?}");
}

/// The held-out cases of `study` replayed by `car`, each printed.
fn held_out(study: &PlanarStudy, car: &bumpsim_planar::PlanarCar) -> Vec<CaseFit> {
    let held: Vec<_> = study
        .validation
        .iter()
        .map(|c| predict(car, c).unwrap().fit)
        .collect();
    for f in &held {
        eprintln!(
            "held out {}: x {:.2} %, yaw {:.2} % (peak yaw {:.3}°)",
            f.name,
            f.fit_x,
            f.fit_yaw,
            f.peak_yaw.to_degrees()
        );
    }
    held
}

/// Issue 32: results stable to input rounding. A direction written with
/// other digits (a 1e-7 turn of the 10° wall's normal, as 16 digits against
/// 6) moves no parameter beyond its 95 % interval; before the staged search
/// such an edit flipped the result.
#[test]
fn a_direction_rounded_otherwise_moves_no_parameter_beyond_its_interval() {
    let Some(dir) = series() else { return };
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let base = identify(&study.cases, &study.setup, &|| {}).unwrap();
    let mut turned = study.cases.clone();
    let wall = turned.iter_mut().find(|c| c.name == "WALL10").unwrap();
    for load in &mut wall.drive.loads {
        let [x, y] = load.direction;
        let (s, c) = 1e-7f64.sin_cos();
        load.direction = [c * x - s * y, s * x + c * y];
    }
    let moved = identify(&turned, &study.setup, &|| {}).unwrap();
    for (a, b) in base.parameters.iter().zip(&moved.parameters) {
        let Some([low, high]) = a.ci95 else { continue };
        eprintln!("{}: {} -> {} ({low} .. {high})", a.name, a.value, b.value);
        assert!(
            (low..=high).contains(&b.value),
            "{}: {} moved to {} outside {low} .. {high}",
            a.name,
            a.value,
            b.value
        );
    }
}

/// The series of this family in issue 44's low-information layout
/// (`--yaw-rate`: the sills and a yaw-rate sensor only, the held-out
/// offset a 10° wall), of the base car (seed 0) or seeded car `seed`.
fn yaw_rate_series(seed: u64) -> Option<PathBuf> {
    if seed == 0 {
        return generated(
            "planar-independent-yaw-rate",
            &["--yaw-rate"],
            "study-doc.toml",
        );
    }
    let name = format!("planar-independent-yaw-rate-seed-{seed}");
    let (seeds, marker) = (format!("{seed}:1"), format!("seeds-{seed}-1.txt"));
    let out = generated(&name, &["--seeds", &seeds, "--yaw-rate"], &marker)?;
    Some(out.join(format!("seed-{seed}")))
}

/// Issue 44's thresholds on a third model family: this generator's cars
/// (progressive side members on guides, foam strips, Magic-Formula tyres
/// with transient slip, RK4), recorded as the series was (two
/// sills and a yaw-rate sensor; a flat pendulum, a centred pole and a 10°
/// wall to train on; a 40 % offset 10° wall at 15 km/h and the pole 0.35 m
/// off centre held out), identified with the study as docs/planar.md has a
/// lab write it (`study-doc.toml`). A measurement over `BUMPSIM_SEEDS`
/// (default `0`: the base car; k: the k-th seeded car of the coverage
/// test), one table row per car (docs/planar.md, "Issue 44's thresholds on
/// a third family (w20)": every threshold held on 6 of cars 0–19); it
/// asserts, after every car has run, the floors that held on every car
/// measured, and the base car's every threshold without a switch.
/// `BUMPSIM_INERTIA_SPREAD=s|none` widens or removes the yaw inertia's
/// prior, `BUMPSIM_WIDTH_FIXED=1` keeps the drawn width,
/// `BUMPSIM_START_BUMPER=1` keeps the start car's bumper,
/// `BUMPSIM_TYRE_SHAPE=C` gives the start car's tyres the Magic Formula
/// with shape factor C (this generator's law, `C = 1.3`).
#[test]
#[ignore = "a measurement: 16 starts on each car, release build"]
fn the_documented_study_on_a_third_family_with_a_yaw_rate_sensor() {
    let switched = [
        "BUMPSIM_INERTIA_SPREAD",
        "BUMPSIM_WIDTH_FIXED",
        "BUMPSIM_START_BUMPER",
        "BUMPSIM_TYRE_SHAPE",
    ]
    .iter()
    .any(|v| std::env::var(v).is_ok());
    let mut failed = Vec::new();
    for seed in super::yaw_rate::seeds("0") {
        let Some(dir) = yaw_rate_series(seed) else {
            return;
        };
        let mut study = PlanarStudy::read(&dir.join("study-doc.toml")).unwrap();
        super::defaults::inertia_prior_from_env(&mut study);
        // `BUMPSIM_START_BUMPER=1`: the start car's bumper, not fitted
        // (`[model] bumper` and `joint` left out)
        if std::env::var("BUMPSIM_START_BUMPER").is_ok() {
            study.setup.bumper = false;
            study.setup.joint = None;
        }
        shape_from_env(&mut study);
        let (result, scores) = super::defaults::identified_and_scored(&dir, &study);
        eprintln!("{}", scores.row(&format!("seed {seed}")));
        let misses = scores.misses();
        eprintln!("seed {seed}: misses {misses:?}");
        let width = result
            .parameters
            .iter()
            .find(|p| p.name == "bumper.effective_width")
            .map(|p| p.value);
        eprintln!(
            "seed {seed}: objective {:.4e}, effective width {width:?}",
            result.objective
        );
        // the floors that held on cars 0–19 (docs/planar.md, "Issue 44's
        // thresholds on a third family"); the base car holds every
        // threshold with the study as written
        let floors = scores.inertia.abs() <= 0.2
            && scores.grip.abs() <= 0.3
            && scores.offset[0] >= 99.3
            && scores.narrow[0] >= 99.0;
        let base = seed != 0 || switched || misses.is_empty();
        if !(floors && base) {
            failed.push(format!("seed {seed}: {misses:?} {scores:?}"));
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}

/// Issue 44's every threshold on one car of the third family, in the
/// suite: car 2 (`--seeds 2:1 --yaw-rate`), whose search with the width
/// held near the drawn width ended at 4.54e-3 (m/s)² under the priors and
/// predicted the held-out offset yaw at 85.35 %; the second search, with
/// the width pinned, ends at 3.38e-3 and 99.44 % (docs/planar.md, "The
/// width pinned in a second search (w25)"). Asserted: every threshold
/// (held-out x and yaw, the forward offset prediction, the starts at the
/// best, I_z within 20 % and μ within 30 % of the truth, the held-out
/// yaw inside its band).
#[test]
fn the_third_familys_car_2_holds_every_threshold() {
    let Some(dir) = yaw_rate_series(2) else {
        return;
    };
    let study = PlanarStudy::read(&dir.join("study-doc.toml")).unwrap();
    let (_, scores) = super::defaults::identified_and_scored(&dir, &study);
    eprintln!("{}", scores.row("seed 2"));
    assert!(
        scores.misses().is_empty(),
        "{:?} {scores:?}",
        scores.misses()
    );
}

/// `BUMPSIM_TYRE_SHAPE=C`: the study's start car with Magic-Formula tyres
/// of shape factor C on both axles.
fn shape_from_env(study: &mut PlanarStudy) {
    let Ok(shape) = std::env::var("BUMPSIM_TYRE_SHAPE") else {
        return;
    };
    let shape: f64 = shape.parse().expect("BUMPSIM_TYRE_SHAPE: a number");
    let mut tyres = *study.setup.template.tyres();
    tyres.front.shape = Some(shape);
    tyres.rear.shape = Some(shape);
    study.setup.template = study.setup.template.clone().with_tyres(tyres).unwrap();
}
