//! Issue 44, item 4: one run started at the truth of the independent
//! series of tests/peers/planar_yaw_rate.py. The generator is another model
//! family (a rigid beam on elastic-plastic crash boxes), so "the truth" is
//! the equivalent bumpsim car: the generator's body mass, yaw inertia and
//! grip, each chain the half beam (4.5 kg) on its crash box's elastic
//! stiffness and damper; the geometry and the bumper the study's start car.
//! The search from it, with the stated priors, must not walk away to a
//! lower objective that predicts the held-out tests worse.

use bumpsim_planar::PlanarCar;
use bumpsim_planar::identify::{CaseFit, PlanarCase, Unknowns, identify, predict};
use bumpsim_planar::study::PlanarStudy;
use std::path::{Path, PathBuf};

fn series() -> Option<PathBuf> {
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
