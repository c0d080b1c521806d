//! Issue 46's planar acceptance: a series whose side members are
//! progressive springs on two masses each, written by
//! tests/peers/planar_progressive.py (another model family: a rigid beam
//! bolted to two point masses a side, free in the plane, joined by bars
//! whose compression carries `F = k d (1 + (d/d0)²)` and whose shear a
//! lateral spring; Hunt–Crossley contact with a small rate term, tyres
//! without transient slip, symplectic Euler). Sensors as a test has
//! them: two sill accelerometers, a yaw-rate sensor, the barrier's load
//! cells. Trained on a flat pendulum, a narrow centred face and a 10° wall;
//! held out a 40 % offset 10° wall at 15 km/h and the narrow face 0.4 m off
//! centre. The link verdict's known answers (item 3) are checked on small
//! series of bumpsim's own family (a linear and a strongly progressive car).

use bumpsim_core::chain::Chain;
use bumpsim_core::link::{Curve, Link, Unloading};
use bumpsim_impact::bumper::Bumper;
use bumpsim_planar::PlanarCar;
use bumpsim_planar::car::Layout;
use bumpsim_planar::cases::TestChannels;
use bumpsim_planar::forward::forward;
use bumpsim_planar::identify::{
    LinkLaw, LinkLaws, PlanarCase, PlanarIdentification, Setup, identify, predict,
};
use bumpsim_planar::link_verdict::{Criterion, LinkVerdict, compare_links};
use bumpsim_planar::study::PlanarStudy;
use bumpsim_planar::synth::{self, record};
use bumpsim_planar::{Face, Side, Striker};
use std::path::{Path, PathBuf};

fn series() -> Option<PathBuf> {
    series_of("planar-progressive", &[])
}

/// The generator's series in `name` (under the target's temporary folder),
/// written with the generator's `args`; `None` without numpy.
fn series_of(name: &str, args: &[&str]) -> Option<PathBuf> {
    if !bumpsim_peers::python_available("numpy") {
        return None;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let script =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/planar_progressive.py");
    bumpsim_peers::generated(&script, &out, args, "study.toml");
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
/// of the offset test (car, bumper and striker alone) scores force 14.89 %,
/// x-acceleration 14.78 %, yaw rate 37.06 % (4.45 % force on the
/// generator's first version, whose contact's rate term stiffened the
/// front) — the linear links at their initial slopes crush far too
/// softly; the replay driven by the measured cell forces follows x at
/// 98.64 % and the yaw at 93.99 % (the 53 %
/// is not reproduced here: the measured forces carry the yaw moment, the
/// chain's stiffness matters little to the replayed turning).
#[test]
fn linear_links_at_the_true_initial_stiffnesses_miss_the_offset_test() {
    let Some(dir) = series() else { return };
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let car = PlanarCar::read(&dir.join("truth-linear.toml")).unwrap();
    let (yaw, force) = offset_scores(&study, &car, "truth, linear links");
    assert!(
        force < 25.0,
        "the linear truth predicts the force at {force:.2} %"
    );
    assert!(yaw > 90.0, "the replay follows the yaw: {yaw:.2} %");
}

/// Every test's forward force (%) of the series in `dir` run by the
/// generator's truth in bumpsim's form (truth-progressive.toml: the true
/// masses, dampers and progressive links, the contact's static curve as
/// the bumper), printed; and the offset test's (yaw, force).
fn truth_scores(dir: &Path, label: &str) -> (f64, f64) {
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let car = PlanarCar::read(&dir.join("truth-progressive.toml")).unwrap();
    for case in study.cases.iter().chain(&study.validation) {
        if let Ok(ahead) = forward(&car, case) {
            eprintln!(
                "{label}: forward {} force {:.2} %",
                case.name, ahead.channels[0].fit_percent
            );
        }
    }
    offset_scores(&study, &car, label)
}

/// The model-family question, asked before any identification: bumpsim's
/// car set to the series' truth (the progressive links with the true k, k3
/// = k/d0², masses and dampers) run forward into the offset test's wall.
/// Measured: force 88.55 %, x-acceleration 88.16 %, yaw rate 92.50 %;
/// held-out replayed yaw 90.45 %. (The pendulum's force: 76.40 %: it loads
/// as measured to 0.5 % and unloads faster, the bumper's linear unloading
/// slope against the contact's nearly elastic return.) An identification
/// cannot be asked to predict much better than this.
#[test]
fn the_truth_with_progressive_links_predicts_the_offset_test() {
    let Some(dir) = series() else { return };
    let (yaw, force) = truth_scores(&dir, "truth, progressive links");
    assert!(
        force >= 85.0,
        "the true car predicts the force at {force:.2} %"
    );
    assert!(yaw >= 85.0, "the replay follows the yaw: {yaw:.2} %");
}

/// Why the generator's first version could not pass: its contact's
/// Hunt–Crossley rate term (a = 0.25 s/m: 2.6 times the static force at
/// first touch at 15 km/h, restitution about 0) and side members as soft
/// across (1.5e6 N/m) as along. bumpsim's bumper has no rate term, so its
/// car set to that series' truth predicts the offset force at 64.94 %
/// (64.23 % with the first version's seven-knot bumper curve; the
/// identified progressive car: 60.72 %); measured on that truth with a = 0:
/// 78.2 %; with a = 0 and stiff side members: 91.1 %. Kept as the evidence
/// that a rate-dependent bumper is beyond bumpsim's bumper law.
#[test]
fn a_rate_dependent_contact_is_beyond_the_bumper_law() {
    let args = ["--contact-damping", "0.25", "--shear", "1.5e6"];
    let Some(dir) = series_of("planar-progressive-rate", &args) else {
        return;
    };
    let (_, force) = truth_scores(&dir, "truth, rate-dependent contact");
    assert!(
        force < 70.0,
        "the true car with a static bumper predicts the force at {force:.2} %"
    );
}

/// The study's cars identified with the side members of `law` (every link).
pub(super) fn identified(study: &PlanarStudy, law: LinkLaw) -> PlanarIdentification {
    identified_from(&study.cases, &study.setup, law)
}

/// `cases` identified under `setup` with the side members of `law` (every
/// link), the parameters and fits printed.
fn identified_from(cases: &[PlanarCase], setup: &Setup, law: LinkLaw) -> PlanarIdentification {
    let template = &setup.template;
    let laws = LinkLaws {
        left: vec![law; template.left().masses.len()],
        right: vec![law; template.right().masses.len()],
    };
    let mut setup = setup.clone();
    setup.template = laws.apply(template).unwrap();
    let result = identify(cases, &setup, &|| {}).unwrap();
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
    // the priors' weight against the data: σ² Σ z² against F
    let z2: f64 = result.priors.iter().map(|m| m.z * m.z).sum();
    for m in &result.priors {
        eprintln!("{}: prior {:<24} z {:+.2}", law.word(), m.name, m.z);
    }
    eprintln!(
        "{}: objective {:.4e} m², priors {:.4e} m² (noise {:.3e} m, inflation {:.1}, τ {:.1})",
        law.word(),
        result.objective,
        result.prior_noise.powi(2) * z2,
        result.prior_noise,
        result.inflation,
        result.effective.time
    );
    result
}

/// Issue 46's acceptance on the series in `dir`: identified with
/// progressive side members (16 starts, the stated priors, the staged
/// search), the held-out 40 % offset test's yaw ≥ 85 % and its forward
/// force ≥ 80 %; and the comparison with linear side members says the data
/// want them.
fn acceptance(dir: &Path) {
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

/// Issue 46's acceptance on this generator's series (see [`acceptance`]).
///
/// Measured: held-out offset yaw 95.94 % (✓), forward offset force 81.93 %
/// (✓; linear links 72.18 %; the generator's first version, whose contact
/// no bumpsim bumper represents: 96.74 % / 60.72 %). The verdict says
/// "nonlinear", decided by the held-out tests: OFFSET40 run forward from
/// its striker scores 81.20 % (mean of force, x-acceleration, yaw rate)
/// against the linear car's 73.45 %; NARROW-OFFSET, which has no striker,
/// is replayed (52.74 % against 52.70 %: the measured forces drive it);
/// the means 66.97 % against 63.08 %. The training BIC alone would say
/// "linear" (−162.0 against −173.2 on 14.4 effective of 3795 residuals,
/// τ = 264 samples): the nonlinear car's training objective is 3.9 %
/// *higher* than the linear one's, though it holds it — its priors weigh
/// more than its data (1.68e-3 against 1.18e-3 m²), see
/// [`without_their_priors_the_cubic_terms_leave_their_start`].
///
/// Run by the suite: both acceptances together took 99 s wall (30 s of CPU)
/// in the test build under load 18, the series already written (its
/// generator: about 14 s of CPU each). They took 191 s and 125 s in a
/// release build and 53 and 41 min in the test build before the replay's
/// step followed the loads' reach ([`bumpsim_planar::PlanarCar::within_force`]:
/// five integration steps per sample became one or two) and the test
/// build optimised `bumpsim-planar` (the workspace's Cargo.toml).
#[test]
fn progressive_side_members_predict_the_held_out_offset_test() {
    let Some(dir) = series() else { return };
    acceptance(&dir);
}

/// The same acceptance on a varied series: another noise seed and the
/// right side members 30 % stiffer (a stronger left/right asymmetry), so
/// that nothing passes by being tuned to one draw of the generator.
///
/// Measured: held-out offset yaw 95.78 % (✓), forward offset force 82.27 %
/// (✓; linear links 72.62 %); the verdict "nonlinear", decided by the
/// held-out tests (OFFSET40 forward 81.27 % against 73.62 %, NARROW-OFFSET
/// replayed 53.03 % against 52.93 %; means 67.15 % against 63.27 %; the
/// BIC alone: −174.3 against −185.6, linear, on 15.0 effective residuals).
/// The cubic terms stay near their start (6.0e8–6.4e8 N/m³ against the
/// truth's 2.6e9–3.8e9), the initial slopes rise to make up (3.0e6
/// against 1.1e6 N/m).
#[test]
fn progressive_side_members_predict_a_varied_series() {
    let args = ["--seed", "7", "--right-stiffness", "1.3"];
    let Some(dir) = series_of("planar-progressive-varied", &args) else {
        return;
    };
    acceptance(&dir);
}

/// A car of one link a side (the link's forces halved onto each side, a
/// 1200 kg body on the default layout, frictionless tyres) behind an
/// elastic bumper of 3e6 N/m.
fn one_link_car(link: Link, mass: f64, damper: f64) -> PlanarCar {
    let chain = Chain::new(vec![mass, 1200.0], vec![damper], vec![link]).unwrap();
    let bumper = Bumper::three_part(3e6, 1e12, 3e6).unwrap();
    PlanarCar::symmetric_links(&chain, &bumper, &Layout::default()).unwrap()
}

/// `truth`'s synthetic series (synth's measurement chain with a yaw-rate
/// sensor): trained on a flat wall and a 10° wall at 8 km/h, held out a
/// 40 % offset 10° wall at 15 km/h with its striker (a forward run).
fn synthetic_series(truth: &PlanarCar) -> (Vec<PlanarCase>, Vec<PlanarCase>) {
    let chain = synth::Chain {
        yaw_rate: Some(0.1f64.to_radians()),
        ..synth::Chain::default()
    };
    let (slow, fast) = (8.0 / 3.6, 15.0 / 3.6);
    let tests = [
        ("flat", Striker::barrier(Face::flat(), slow)),
        (
            "angled",
            Striker::barrier(Face::plane_in_degrees(10.0, 100.0, Side::Left), slow),
        ),
        (
            "offset",
            Striker::barrier(Face::plane_in_degrees(10.0, 40.0, Side::Left), fast),
        ),
    ];
    let mut cases: Vec<PlanarCase> = tests
        .iter()
        .enumerate()
        .map(|(k, (name, striker))| {
            let recorded = record(truth, name, striker, &chain, k as u64).unwrap();
            let mut case = TestChannels::of(&recorded).case().unwrap().0;
            case.striker = Some(*striker);
            case
        })
        .collect();
    let held = cases.split_off(2);
    (cases, held)
}

/// The link verdict on `truth`'s synthetic series, identified from a
/// linear start 15–40 % off (3 starts).
fn synthetic_verdict(truth: &PlanarCar) -> LinkVerdict {
    let (training, held) = synthetic_series(truth);
    let start = one_link_car(Link::linear(1.5e6).unwrap(), 10.0, 2e3);
    let setup = Setup {
        starts: 3,
        ..Setup::new(start)
    };
    let linear = identified_from(&training, &setup, LinkLaw::Linear);
    let progressive = identified_from(&training, &setup, LinkLaw::Progressive);
    let verdict = compare_links(&linear, &progressive, &held).unwrap();
    for reason in &verdict.reasons {
        eprintln!("links: {reason}");
    }
    verdict
}

/// The verdict's known answers (issue 46 item 3), on the data of a car of
/// bumpsim's own family: a car with linear side members (1.2e6 N/m) gets
/// linear links — the nonlinear car predicts its held-out test no better
/// and its BIC pays for the cubic terms.
#[test]
fn a_linear_car_s_data_want_linear_links() {
    let truth = one_link_car(Link::linear(1.2e6).unwrap(), 8.0, 1.5e3);
    let verdict = synthetic_verdict(&truth);
    assert!(!verdict.nonlinear, "{:?}", verdict.reasons);
    assert!(verdict.effective.effective > 2.0, "{:?}", verdict.effective);
}

/// ... and a strongly progressive car (`F = k δ (1 + (δ/0.03 m)²)`, the
/// cubic three times the linear force at the training tests' 5 cm crush)
/// gets progressive links, decided by the held-out test's forward run.
#[test]
fn a_strongly_progressive_car_s_data_want_progressive_links() {
    let k = 1.0e6;
    let curve = Curve::progressive(k, k / (0.03 * 0.03), 0.3).unwrap();
    let truth = one_link_car(Link::new(curve, Unloading::Elastic).unwrap(), 8.0, 1.5e3);
    let verdict = synthetic_verdict(&truth);
    assert!(verdict.nonlinear, "{:?}", verdict.reasons);
    assert_eq!(
        verdict.criterion,
        Criterion::HeldOut,
        "{:?}",
        verdict.reasons
    );
}

/// The series' progressive identification under `setup` (the study's
/// cases) and the offset test's (yaw, force), printed with `label`.
fn offset_of(study: &PlanarStudy, setup: &Setup, label: &str) -> (PlanarIdentification, f64, f64) {
    let result = identified_from(&study.cases, setup, LinkLaw::Progressive);
    let (yaw, force) = offset_scores(study, &result.car, label);
    (result, yaw, force)
}

/// Item 3's check at the truth: the study's search started at the series'
/// truth in bumpsim's form (truth-progressive.toml: the true masses,
/// dampers and progressive links; its priors centred there) must not walk
/// away to a car that predicts the held-out offset test worse than the
/// acceptance's thresholds.
///
/// Measured (202 s in release under load 15): it stays near the truth (the
/// cubic terms within 0.17 prior sd of it, 2.5e9–4.1e9 N/m³), held-out
/// offset yaw 95.18 %, forward force 85.71 % (the truth itself: 88.55 %;
/// from the lab's start: 81.93 %). Its data objective, 1.23e-3 m², is
/// *higher* than the lab start's optimum (1.18e-3): the training tests do
/// not prefer the true cubic terms, see the next test.
#[test]
#[ignore = "issue 46 item 3, a check at the truth: yaw 95.18 %, force 85.71 %; 202 s in release; run with --ignored"]
fn started_at_the_truth_the_progressive_fit_predicts_the_offset_test() {
    let Some(dir) = series() else { return };
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let setup = Setup {
        template: PlanarCar::read(&dir.join("truth-progressive.toml")).unwrap(),
        ..study.setup.clone()
    };
    let (_, yaw, force) = offset_of(&study, &setup, "identified from the truth");
    assert!(yaw >= 85.0, "held-out offset yaw {yaw:.2} %");
    assert!(force >= 80.0, "forward offset force {force:.2} %");
}

/// Item 3, why the cubic terms stay near their start (6.0e8–6.4e8 N/m³
/// against the truth's 2.6e9–3.8e9): the training tests (8–10 km/h) do not
/// determine them, their priors (the start within a factor 10 at 2 sd)
/// hold them. It is not the parameter's scaling (searched in ln k3 like
/// every other). Measured without the cubic terms' priors (602 s in
/// release under load 15): the left ones run to their upper bound (6e11,
/// 1000 times the start), the right ones to their lower (6e5), none
/// determined; the held-out offset yaw stays 94.38 % (the replay), the
/// forward force falls to 13.98 % (81.93 % with the priors). The data
/// objective is 1.28e-3 m² (1.18e-3 with them): no better a fit.
#[test]
#[ignore = "issue 46 item 3, the cubic terms without their priors run to their bounds: 602 s in release; run with --ignored"]
fn without_their_priors_the_cubic_terms_are_not_determined() {
    let Some(dir) = series() else { return };
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let mut setup = study.setup.clone();
    setup.priors.extend(
        ["left", "right"]
            .iter()
            .flat_map(|side| (0..2).map(move |j| format!("{side}.cubic[{j}]")))
            .map(|name| bumpsim_estimate::stated::PriorSetting {
                name,
                removed: true,
                ..Default::default()
            }),
    );
    let (result, _, force) = offset_of(&study, &setup, "identified without cubic priors");
    let cubic: Vec<_> = result
        .parameters
        .iter()
        .filter(|p| p.name.contains(".cubic["))
        .collect();
    assert_eq!(cubic.len(), 4);
    assert!(
        cubic.iter().all(|p| p.determined != Some(true)),
        "{cubic:?}"
    );
    assert!(force < 80.0, "forward offset force {force:.2} %");
}
