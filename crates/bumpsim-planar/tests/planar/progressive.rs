//! Issue 46's planar acceptance: a series whose side members are
//! progressive springs on two masses each, written by
//! tests/peers/planar_progressive.py (another model family: a rigid beam
//! bolted to two point masses a side, free in the plane, joined by bars
//! whose compression carries `F = k d (1 + (d/d0)²)`; Hunt–Crossley contact,
//! tyres without transient slip, symplectic Euler). Sensors as a test has
//! them: two sill accelerometers, a yaw-rate sensor, the barrier's load
//! cells. Trained on a flat pendulum, a narrow centred face and a 10° wall;
//! held out a 40 % offset 10° wall at 15 km/h and the narrow face 0.4 m off
//! centre.

use bumpsim_planar::PlanarCar;
use bumpsim_planar::forward::forward;
use bumpsim_planar::identify::{
    LinkLaw, LinkLaws, PlanarIdentification, compare_links, identify, predict,
};
use bumpsim_planar::study::PlanarStudy;
use std::path::{Path, PathBuf};

fn series() -> Option<PathBuf> {
    if !bumpsim_peers::python_available("numpy") {
        return None;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("planar-progressive");
    let script =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/planar_progressive.py");
    bumpsim_peers::generated(&script, &out, &[], "study.toml");
    Some(out)
}

/// The held-out offset test's replayed yaw (%) and its forward force (%)
/// of `car`, printed with the rest of the forward channels.
fn offset_scores(study: &PlanarStudy, car: &PlanarCar, label: &str) -> (f64, f64) {
    let offset = study
        .validation
        .iter()
        .find(|c| c.name == "OFFSET40")
        .expect("the series holds OFFSET40");
    let held = predict(car, offset).unwrap().fit;
    let ahead = forward(car, offset).unwrap();
    for c in &ahead.channels {
        eprintln!(
            "{label}: forward OFFSET40 {}: {:.2} %",
            c.name, c.fit_percent
        );
    }
    eprintln!(
        "{label}: held-out OFFSET40 x {:.2} %, yaw {:.2} %",
        held.fit_x, held.fit_yaw
    );
    let force = ahead
        .channels
        .iter()
        .find(|c| c.unit == "N")
        .expect("a force channel")
        .fit_percent;
    (held.fit_yaw, force)
}

/// The premise, measured: bumpsim's car with linear links set to
/// the series' true masses, dampers and initial stiffnesses (the
/// generator's truth-linear.toml) cannot follow the stiffening side
/// members. The issue states 53 % offset yaw and 4 % forward force on its
/// own series of this kind. Measured on this one: the forward prediction
/// of the offset test (car, bumper and striker alone) scores force 4.45 %,
/// x-acceleration 4.07 %, yaw rate 39.3 % — the linear links at their
/// initial slopes crush far too softly; the replay driven by the measured
/// cell forces follows x at 98.6 % and the yaw at 95.3 % (the 53 %
/// is not reproduced here: the measured forces carry the yaw moment, the
/// chain's stiffness matters little to the replayed turning).
#[test]
fn linear_links_at_the_true_initial_stiffnesses_miss_the_offset_test() {
    let Some(dir) = series() else { return };
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let car = PlanarCar::read(&dir.join("truth-linear.toml")).unwrap();
    let (yaw, force) = offset_scores(&study, &car, "truth, linear links");
    assert!(
        force < 10.0,
        "the linear truth predicts the force at {force:.2} %"
    );
    assert!(yaw > 90.0, "the replay follows the yaw: {yaw:.2} %");
}

/// The study's cars identified with the side members of `law` (every link).
pub(super) fn identified(study: &PlanarStudy, law: LinkLaw) -> PlanarIdentification {
    let template = &study.setup.template;
    let laws = LinkLaws {
        left: vec![law; template.left().masses.len()],
        right: vec![law; template.right().masses.len()],
    };
    let mut setup = study.setup.clone();
    setup.template = laws.apply(template).unwrap();
    let result = identify(&study.cases, &setup, &|| {}).unwrap();
    for p in &result.parameters {
        eprintln!(
            "{}: {:<24} {:>12.5e} {:<6} {:?}",
            law.word(),
            p.name,
            p.value,
            p.unit,
            p.determined
        );
    }
    for f in &result.fits {
        eprintln!(
            "{}: training {} x {:.2} %, yaw {:.2} %",
            law.word(),
            f.name,
            f.fit_x,
            f.fit_yaw
        );
    }
    eprintln!("{}: starts {:?}", law.word(), result.starts);
    result
}

/// Issue 46's acceptance on this generator: identified with progressive
/// side members (16 starts, the stated priors, the staged search), the
/// held-out 40 % offset test's yaw ≥ 85 % and its forward force ≥ 80 %; and
/// the comparison with linear side members says the data want them.
///
/// Not yet measured: three 16-start identifications (linear and
/// progressive here) did not finish within the round's 45 minutes on the
/// shared machine (load 20 on 2 cores); run it with `--ignored`.
#[test]
#[ignore = "issue 46 acceptance, not yet measured: two 16-start planar identifications (slow); run with --ignored"]
fn progressive_side_members_predict_the_held_out_offset_test() {
    let Some(dir) = series() else { return };
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let linear = identified(&study, LinkLaw::Linear);
    let progressive = identified(&study, LinkLaw::Progressive);
    let (yaw_l, force_l) = offset_scores(&study, &linear.car, "identified, linear links");
    let (yaw, force) = offset_scores(&study, &progressive.car, "identified, progressive links");
    let verdict = compare_links(&linear, &progressive, &study.validation).unwrap();
    for reason in &verdict.reasons {
        eprintln!("links: {reason}");
    }
    eprintln!(
        "offset: linear yaw {yaw_l:.2} % force {force_l:.2} %; progressive yaw {yaw:.2} % force {force:.2} %"
    );
    assert!(yaw >= 85.0, "held-out offset yaw {yaw:.2} %");
    assert!(force >= 80.0, "forward offset force {force:.2} %");
    assert!(verdict.nonlinear, "{:?}", verdict.reasons);
}
