//! The identification's unit tests on cases the model makes itself.

use super::*;
use crate::car::Layout;
use crate::drive::Load;
use bumpsim_core::model::MsdModel;
use bumpsim_impact::bumper::Bumper;

fn car() -> PlanarCar {
    let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
    let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
    PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap()
}

/// A case made by the model itself: a half-sine push at `lateral`,
/// sills and both side members measured.
fn case(truth: &PlanarCar, lateral: f64) -> PlanarCase {
    pushed(truth, "offset", lateral, Sensor::Chain(1))
}

/// A case made by `truth` itself: a 40 kN half-sine push of 30 ms at
/// `lateral` from 2 m/s, the sills, the left front chain mass and
/// `right` measured (the identification's and the reduction's tests).
pub(super) fn pushed(truth: &PlanarCar, name: &str, lateral: f64, right: Sensor) -> PlanarCase {
    let force: Vec<f64> = (0..400)
        .map(|k| 4e4 * (std::f64::consts::PI * (k as f64 / 300.0).min(1.0)).sin())
        .collect();
    let load = Load {
        lateral,
        anchor: None,
        cell: None,
        direction: [-1.0, 0.0],
        force,
    };
    let sensors = vec![
        Sensor::Body([0.6, 0.7]),
        Sensor::Body([0.6, -0.7]),
        Sensor::Chain(0),
        right,
    ];
    let drive = Drive {
        step: 1e-4,
        loads: vec![load],
        speed: 2.0,
        arm: 1.0,
        sensors,
    };
    let replay = crate::drive::drive(truth, &drive, 0.05).unwrap();
    PlanarCase::replayed(name, drive, replay.sensor_reading)
}

#[test]
fn noise_free_data_of_the_model_are_fitted_exactly_and_the_truth_found() {
    let truth = car();
    let cases = [case(&truth, 0.4), case(&truth, -0.2)];
    let unknowns = Unknowns::new(&truth, false, false, &cases);
    let guess = [1000.0, 2500.0, 6.0, 1500.0, 1.2e6, 6.0, 1500.0, 1.2e6];
    let mut start = Setup::new(unknowns.car(&guess).unwrap());
    start.starts = 2;
    start.priors = removing_all(&unknowns);
    let r = identify(&cases, &start, &|| {}).unwrap();
    let truth_values = unknowns.start();
    for (p, t) in r.parameters.iter().zip(&truth_values) {
        assert!(
            (p.value - t).abs() < 1e-3 * t,
            "{} {} vs {t}",
            p.name,
            p.value
        );
    }
    assert!(
        r.fits[0].fit_x > 99.99 && r.fits[0].fit_yaw > 99.9,
        "{:?}",
        r.fits
    );
}

#[test]
fn bad_settings_and_cases_are_refused_by_name() {
    let truth = car();
    let good = case(&truth, 0.4);
    let setup = Setup::new(truth.clone());
    let err = |cases: &[PlanarCase], setup: &Setup| {
        identify(cases, setup, &|| {}).unwrap_err().to_string()
    };
    assert!(err(&[], &setup).starts_with("cases"));
    assert!(
        err(
            std::slice::from_ref(&good),
            &Setup {
                starts: 0,
                ..setup.clone()
            }
        )
        .starts_with("starts")
    );
    assert!(
        err(
            std::slice::from_ref(&good),
            &Setup {
                spread: f64::NAN,
                ..setup.clone()
            }
        )
        .starts_with("spread")
    );
    let mut short = good.clone();
    short.window = (10, 4000);
    assert!(err(&[short], &setup).contains("window"));
    let mut swapped = good.clone();
    swapped.drive.sensors.swap(0, 1);
    assert!(err(&[swapped], &setup).contains("sensors"));
    let mut nan = good.clone();
    nan.measured[1][7] = f64::NAN;
    assert!(err(&[nan], &setup).contains("sensor[1] displacement[7]"));
    // a relaxation length to estimate needs tyres that have one
    let mut tyres = *truth.tyres();
    tyres.front.relaxation_length = 0.0;
    tyres.rear = tyres.front;
    let (l, r) = (truth.left().clone(), truth.right().clone());
    let instant = PlanarCar::new(*truth.body(), l, r, truth.beam().clone(), tyres).unwrap();
    let relaxing = Setup {
        relaxation: true,
        ..Setup::new(instant)
    };
    assert!(err(std::slice::from_ref(&good), &relaxing).starts_with("relaxation"));
    let frictionless = Setup {
        friction: true,
        ..setup
    };
    assert!(
        err(&[good], &frictionless).contains("tyres.mu_lateral"),
        "a zero start cannot be estimated on a log scale"
    );
}
