//! Issue 44, item 4: one run started at the truth of the independent
//! series of tests/peers/planar_yaw_rate.py. The generator is another model
//! family (a rigid beam on elastic-plastic crash boxes), so "the truth" is
//! the equivalent bumpsim car: the generator's body mass, yaw inertia and
//! grip, each chain the half beam (4.5 kg) on its crash box's elastic
//! stiffness and damper; the geometry and the bumper the study's start car.
//! The search from it, with the stated priors, must not walk away to a
//! lower objective that predicts the held-out tests worse.
//!
//! With yielding side members (issue 46) the truth-equivalent car has each
//! crash box's yield force and hardening too; the tests below diagnose what
//! issue 44's thresholds on this series are a matter of (the side members,
//! the tyres or the bumper) and what a run started there does.

use bumpsim_planar::PlanarCar;
use bumpsim_planar::forward::forward;
use bumpsim_planar::identify::{
    CaseFit, LinkLaw, LinkLaws, PlanarCase, Unknowns, identify, predict,
};
use bumpsim_planar::study::PlanarStudy;
use std::path::{Path, PathBuf};

pub(super) fn series() -> Option<PathBuf> {
    if !bumpsim_peers::python_available("numpy") {
        return None;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("planar-yaw-rate");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/planar_yaw_rate.py");
    bumpsim_peers::generated(&script, &out, &[], "study.toml");
    Some(out)
}

/// The bumpsim car equivalent to the generator's truth (see the module).
fn truth(study: &PlanarStudy, sheet: &serde_json::Value) -> PlanarCar {
    let car = &sheet["car"];
    let boxes = &car["crash_boxes"];
    let number = |v: &serde_json::Value| v.as_f64().unwrap();
    let half_beam = 0.5 * number(&car["beam"]["mass"]);
    let unknowns = Unknowns::new(&study.setup.template, true, false, &[]);
    let theta = [
        number(&car["body_mass"]),
        number(&car["yaw_inertia"]),
        half_beam,
        number(&boxes["damping"][0]),
        number(&boxes["elastic"][0]),
        half_beam,
        number(&boxes["damping"][1]),
        number(&boxes["elastic"][1]),
        number(&car["tyres"]["mu"]),
    ];
    unknowns.car(&theta).unwrap()
}

/// The truth-equivalent car with yielding side members: the linear
/// truth's masses, dampers and elastic stiffnesses, each crash box's yield
/// force and its hardening as the bilinear law's ratio: the generator's
/// isotropic hardening `h` after yield makes the force grow at
/// `k h/(k + h)`, so `r = h/(k + h)`.
pub(super) fn truth_yielding(study: &PlanarStudy, sheet: &serde_json::Value) -> PlanarCar {
    let car = &sheet["car"];
    let boxes = &car["crash_boxes"];
    let number = |v: &serde_json::Value| v.as_f64().unwrap();
    let half_beam = 0.5 * number(&car["beam"]["mass"]);
    let laws = LinkLaws {
        left: vec![LinkLaw::Yielding],
        right: vec![LinkLaw::Yielding],
    };
    let template = laws.apply(&study.setup.template).unwrap();
    let unknowns = Unknowns::new(&template, true, false, &[]);
    let side = |i: usize| {
        let (k, h) = (number(&boxes["elastic"][i]), number(&boxes["hardening"][i]));
        [
            half_beam,
            number(&boxes["damping"][i]),
            k,
            number(&boxes["yield"][i]),
            h / (k + h),
        ]
    };
    let mut theta = vec![number(&car["body_mass"]), number(&car["yaw_inertia"])];
    theta.extend(side(0));
    theta.extend(side(1));
    theta.push(number(&car["tyres"]["mu"]));
    unknowns.car(&theta).unwrap()
}

fn held(car: &PlanarCar, cases: &[PlanarCase]) -> Vec<CaseFit> {
    cases.iter().map(|c| predict(car, c).unwrap().fit).collect()
}

#[test]
fn a_run_started_at_the_truth_does_not_leave_it_for_a_worse_predicting_car() {
    let Some(dir) = series() else { return };
    let sheet: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("series.json")).unwrap()).unwrap();
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let truth = truth(&study, &sheet);
    let truth_fits = held(&truth, &study.validation);
    let mut setup = study.setup.clone();
    setup.template = truth.clone();
    setup.starts = 1;
    setup.staged = false;
    let from_truth = identify(&study.cases, &setup, &|| {}).unwrap();
    let fits = held(&from_truth.car, &study.validation);
    for (t, f) in truth_fits.iter().zip(&fits) {
        eprintln!(
            "{}: truth x {:.2} % yaw {:.2} %; from the truth x {:.2} % yaw {:.2} %",
            t.name, t.fit_x, t.fit_yaw, f.fit_x, f.fit_yaw
        );
    }
    for p in &from_truth.parameters {
        eprintln!(
            "from the truth: {:<28} {:>12.5e} {}",
            p.name, p.value, p.unit
        );
    }
    for m in &from_truth.priors {
        eprintln!(
            "prior {}: {:.4e} -> {:.4e} ({:+.2} sd)",
            m.name, m.centre, m.estimate, m.z
        );
    }
    eprintln!("objective from the truth {:.4e} m²", from_truth.objective);
    // the run from the truth may improve the fit of the training tests (the
    // linear chain follows elastic-plastic boxes only on average), but must
    // not trade the held-out yaw for it. Measured: the truth's offset yaw
    // 95.5 %, the run's 90.2 % (I_z 2300 -> 2369 kg·m², the training 10°
    // wall's yaw asks for more, the prior holds it); without the chain's
    // priors it walked to a damper 50 times the truth's and 85 %
    for (t, f) in truth_fits.iter().zip(&fits) {
        assert!(
            f.fit_yaw >= t.fit_yaw - 10.0 && f.fit_x >= t.fit_x - 1.0,
            "{}: the run from the truth left it for a car that predicts worse: yaw {:.2} % against {:.2} %, x {:.2} % against {:.2} %",
            t.name,
            f.fit_yaw,
            t.fit_yaw,
            f.fit_x,
            t.fit_x
        );
    }
}

/// `car` with both axles' tyres at relaxation length `sigma` (m) and
/// cornering stiffness `cornering` (N/rad).
fn with_tyres(car: &PlanarCar, sigma: f64, cornering: f64) -> PlanarCar {
    let mut tyres = *car.tyres();
    for axle in [&mut tyres.front, &mut tyres.rear] {
        axle.relaxation_length = sigma;
        axle.cornering_stiffness = cornering;
    }
    PlanarCar::new(
        *car.body(),
        car.left().clone(),
        car.right().clone(),
        car.beam().clone(),
        tyres,
    )
    .unwrap()
}

/// Issue 44's thresholds with yielding side members (issue 46), diagnosed
/// at the truth-equivalent car: what the off-centre narrow face's yaw and
/// the forward offset force are a matter of. Measured (release build,
/// figures printed):
///
/// - the off-centre face's yaw is the same with linear and with yielding
///   side members (−21.1 % both): its peak force, 59 kN at 0.4 m, loads the
///   left crash box with 0.9 × 59 = 53 kN by the lever rule, below its
///   75 kN yield, so no link yields in it;
/// - it is the tyres: with the generator's own law (no transient slip,
///   relaxation length 0, C_α 70 kN/rad) it is 98.5 %; the start car's
///   rolling tyres (relaxation 0.4 m) lag by σ/v ≈ 0.2 s at 8 km/h, longer
///   than the contact, and the car yaws twice the measured angle. But the
///   same instantaneous tyres replay the 10° walls worse (WALL10 86.6 →
///   74.0 %, OFFSET40 97.4 → 79.6 %): over σ 0–0.8 m and C_α 30–150 kN/rad
///   no pair holds WALL10 ≥ 90 %, OFFSET40 ≥ 93 % and the off-centre face
///   ≥ 80 % at once, so the relaxation length is not a missing unknown;
///   bumpsim's walls and the generator's disagree elsewhere (open);
/// - the forward offset force is 84.1 % at the yielding truth (x-acceleration
///   84.2 %, yaw rate 84.7 %): the simulated force rises later, stands
///   4–5 % higher on its plateau and falls to zero about 10 ms before the
///   measured one (the start car's bumper unloads along a slope 1.5 times
///   its tangent at 0.1 m, and a bumper's unloading slope must be at least
///   its curve's largest secant, where the generator's Hunt–Crossley
///   contact is elastic and rate-dependent) — the bumper, which no training
///   replay identifies (they are driven by the measured forces).
#[test]
fn the_off_centre_faces_yaw_is_the_tyres_not_the_side_members_yield() {
    let Some(dir) = series() else { return };
    let sheet: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("series.json")).unwrap()).unwrap();
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let yaw = |car: &PlanarCar, name: &str| {
        let case = study
            .validation
            .iter()
            .chain(&study.cases)
            .find(|c| c.name == name)
            .unwrap();
        predict(car, case).unwrap().fit.fit_yaw
    };
    let (linear, yielding) = (truth(&study, &sheet), truth_yielding(&study, &sheet));
    let instant = with_tyres(
        &yielding,
        0.0,
        sheet["car"]["tyres"]["cornering_stiffness"]
            .as_f64()
            .unwrap(),
    );
    let narrow = [&linear, &yielding, &instant].map(|c| yaw(c, "NARROW-OFFSET"));
    let walls = [&yielding, &instant].map(|c| [yaw(c, "WALL10"), yaw(c, "OFFSET40")]);
    eprintln!(
        "NARROW-OFFSET yaw: linear truth {:.2} %, yielding truth {:.2} %, with instantaneous tyres {:.2} %",
        narrow[0], narrow[1], narrow[2]
    );
    eprintln!(
        "WALL10, OFFSET40 yaw: yielding truth {:.2?} %, with instantaneous tyres {:.2?} %",
        walls[0], walls[1]
    );
    let offset = study
        .validation
        .iter()
        .find(|c| c.name == "OFFSET40")
        .unwrap();
    let ahead = forward(&yielding, offset).unwrap();
    for c in &ahead.channels {
        eprintln!(
            "yielding truth: forward OFFSET40 {}: {:.2} %",
            c.name, c.fit_percent
        );
    }
    // the side members' yield plays no part in the off-centre face's yaw
    assert!(
        (narrow[0] - narrow[1]).abs() < 2.0 && narrow[1] < 0.0,
        "{narrow:?}"
    );
    // the tyres' law does, and trades it against the walls' yaw
    assert!(narrow[2] >= 95.0, "{narrow:?}");
    assert!(
        walls[1][0] < 90.0 && walls[1][1] < 93.0 && walls[0][1] >= 93.0,
        "{walls:?}"
    );
    // no relaxation length and cornering stiffness hold the three at once
    for sigma in [0.0, 0.03, 0.1, 0.2, 0.4, 0.8] {
        for cornering in [30e3, 70e3, 150e3] {
            let car = with_tyres(&yielding, sigma, cornering);
            let fits = ["WALL10", "OFFSET40", "NARROW-OFFSET"].map(|n| yaw(&car, n));
            eprintln!(
                "tyres σ {sigma} m, C_α {cornering} N/rad: WALL10, OFFSET40, NARROW-OFFSET yaw {fits:.1?} %"
            );
            assert!(
                !(fits[0] >= 90.0 && fits[1] >= 93.0 && fits[2] >= 80.0),
                "σ {sigma}, C_α {cornering}: {fits:?}"
            );
        }
    }
    // the truth's forward force misses issue 44's 90 %: the bumper
    let force = ahead
        .channels
        .iter()
        .find(|c| c.name == "force")
        .unwrap()
        .fit_percent;
    assert!((80.0..90.0).contains(&force), "forward force {force:.2} %");
}

/// One run of the identification with yielding side members started at
/// the yielding truth (one start, the stated priors, no staging). Measured
/// (release): it leaves the truth for a lower objective that predicts
/// worse: I_z 2300 → 2371 kg·m² (the training 10° wall asks for it, its yaw
/// 86.6 → 93.0 %, the wall/tyre disagreement above) and the left crash box's
/// stiffness 2.6 → 3.9 MN/m (+0.36 prior sd: the force-driven replays hardly
/// see it); held-out offset yaw 97.4 → 92.5 %, off-centre face −21.1 →
/// −12.8 %, forward offset force 84.1 → 73.2 %, x-acceleration 84.2 →
/// 73.1 %, yaw rate 84.7 → 90.1 %.
#[test]
fn a_run_from_the_yielding_truth_leaves_it_for_a_worse_predicting_car() {
    let Some(dir) = series() else { return };
    let sheet: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("series.json")).unwrap()).unwrap();
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let truth = truth_yielding(&study, &sheet);
    let mut setup = study.setup.clone();
    setup.template = truth.clone();
    setup.starts = 1;
    setup.staged = false;
    let run = identify(&study.cases, &setup, &|| {}).unwrap();
    for m in &run.priors {
        eprintln!(
            "prior {}: {:.4e} -> {:.4e} ({:+.2} sd)",
            m.name, m.centre, m.estimate, m.z
        );
    }
    let offset = study
        .validation
        .iter()
        .find(|c| c.name == "OFFSET40")
        .unwrap();
    let scores = |car: &PlanarCar| {
        let held = predict(car, offset).unwrap().fit.fit_yaw;
        let ahead = forward(car, offset).unwrap();
        [held, ahead.channels[0].fit_percent]
    };
    let (at, from) = (scores(&truth), scores(&run.car));
    eprintln!(
        "OFFSET40 held-out yaw, forward force: truth {at:.2?} %, the run from it {from:.2?} %"
    );
    // the objective does not point at the truth (see the doc)
    assert!(from[0] < at[0] && from[1] < at[1], "{at:?} {from:?}");
}
