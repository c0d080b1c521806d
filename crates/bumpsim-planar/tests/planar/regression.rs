//! The planar impact and the planar replay against their recorded outputs
//! (issue 31): moving both onto the one integrator must leave every history
//! within 1e-9 of its peak (`bumpsim_peers::recorded`;
//! `tests/data/planar-regression.txt` was written by the commit before the
//! one-engine refactoring).

use super::asymmetric_car;
use bumpsim_core::model::MsdModel;
use bumpsim_impact::bumper::Bumper;
use bumpsim_peers::recorded::Recording;
use bumpsim_planar::car::Layout;
use bumpsim_planar::drive::{Drive, Driven, Load, Sensor, drive, segment_loads};
use bumpsim_planar::{Face, PlanarCar, PlanarResult, Settings, Side, Striker, simulate};
use std::path::Path;

/// The six strikers the recording was made with (the planar presets of
/// that time, by their names of then; the flat 4.8 km/h corner faces are
/// no longer a table test: the IIHS corner tests run into the RCAR barrier).
fn recorded_strikers() -> [(&'static str, Striker); 6] {
    let kmh = 1.0 / 3.6;
    // the angle in radians as the presets wrote it, to the last bit
    let plane = |degrees: f64, percent: f64, side| Face::Plane {
        angle: degrees * std::f64::consts::PI / 180.0,
        overlap: percent / 100.0,
        side,
    };
    [
        (
            "rcar-structural-front",
            Striker::barrier(plane(10.0, 40.0, Side::Left), 15.0 * kmh),
        ),
        (
            "rcar-structural-rear",
            Striker::pendulum(plane(10.0, 40.0, Side::Left), 1400.0, 15.0 * kmh),
        ),
        (
            "iihs-angle-front",
            Striker::barrier(plane(30.0, 100.0, Side::Left), 8.0 * kmh),
        ),
        (
            "iihs-pole-rear",
            Striker::barrier(Face::pole_of_diameter(0.1778, 0.0), 8.0 * kmh),
        ),
        (
            "iihs-corner-front",
            Striker::barrier(plane(10.0, 15.0, Side::Left), 4.8 * kmh),
        ),
        (
            "iihs-corner-rear",
            Striker::barrier(plane(-10.0, 15.0, Side::Right), 4.8 * kmh),
        ),
    ]
}

fn impact(out: &mut Recording, name: &str, r: &PlanarResult) {
    let mut history = |what: &str, values: &[f64]| out.history(&format!("{name}.{what}"), values);
    let histories: [(&str, &[f64]); 12] = [
        ("time", &r.time),
        ("force_x", &r.force_x),
        ("force_y", &r.force_y),
        ("force", &r.force),
        ("side_force_left", &r.side_force_left),
        ("side_force_right", &r.side_force_right),
        ("x", &r.x),
        ("y", &r.y),
        ("yaw", &r.yaw),
        ("yaw_rate", &r.yaw_rate),
        ("velocity_x", &r.velocity_x),
        ("pendulum_travel", &r.pendulum_travel),
    ];
    for (what, values) in histories {
        history(what, values);
    }
    for (j, (crush, force)) in r.crush.iter().zip(&r.segment_force).enumerate() {
        history(&format!("crush[{j}]"), crush);
        history(&format!("segment_force[{j}]"), force);
    }
    for (i, u) in r.chain_displacement.iter().enumerate() {
        history(&format!("chain[{i}]"), u);
    }
    let line: Vec<f64> = r.line_of_action.iter().map(|l| l.unwrap_or(0.0)).collect();
    history("line_of_action", &line);
    let (e, m) = (&r.energy, &r.momentum);
    let scalars = [
        ("peak_force", r.peak_force),
        ("peak_yaw_rate", r.peak_yaw_rate),
        ("max_compression", r.max_compression),
        ("step", r.step),
        ("contact_start", r.contact_start.unwrap_or(-1.0)),
        ("contact_end", r.contact_end.unwrap_or(-1.0)),
        ("energy.kinetic", e.kinetic),
        ("energy.crush", e.crush),
        ("energy.dampers", e.dampers),
        ("energy.friction", e.friction),
        ("energy.bending", e.bending),
        ("energy.max_relative_error", e.max_relative_error),
        ("momentum.final_angular", m.final_angular),
        (
            "momentum.external_angular_impulse",
            m.external_angular_impulse,
        ),
        ("momentum.linear_residual", m.linear_residual),
    ];
    for (what, value) in scalars {
        out.scalar(&format!("{name}.{what}"), value);
    }
    for (j, crush) in r.max_crush.iter().chain(&r.remaining_crush).enumerate() {
        out.scalar(&format!("{name}.crush_result[{j}]"), *crush);
    }
}

fn replay(out: &mut Recording, name: &str, r: &Driven) {
    let mut history = |what: &str, values: &[f64]| out.history(&format!("{name}.{what}"), values);
    for (what, values) in [("time", &r.time), ("x", &r.x), ("y", &r.y), ("yaw", &r.yaw)] {
        history(what, values);
    }
    for (what, values) in [
        ("side_force_left", &r.side_force_left),
        ("side_force_right", &r.side_force_right),
    ] {
        history(what, values);
    }
    for (k, (x, reading)) in r.sensor_x.iter().zip(&r.sensor_reading).enumerate() {
        history(&format!("sensor_x[{k}]"), x);
        history(&format!("sensor_reading[{k}]"), reading);
    }
    for (i, u) in r.chains.iter().enumerate() {
        history(&format!("chain[{i}]"), u);
    }
}

fn symmetric() -> PlanarCar {
    let chain = MsdModel::new(vec![8.0, 40.0, 1250.0], vec![3e3, 8e3], vec![1.2e6, 3e6]).unwrap();
    let bumper = Bumper::three_part(1.5e6, 45e3, 6e6).unwrap();
    let layout = Layout {
        bending: 5e4,
        ..Layout::default()
    };
    PlanarCar::symmetric(&chain, &bumper, &layout).unwrap()
}

#[test]
fn planar_impacts_and_replays_are_as_recorded() {
    let mut out = Recording::every(100);
    let short = Settings {
        duration: 0.25,
        ..Settings::default()
    };
    let cars = [
        ("asymmetric", asymmetric_car(0.8)),
        ("symmetric", symmetric()),
    ];
    for (car_name, car) in &cars {
        for (name, striker) in recorded_strikers() {
            let r = simulate(car, &striker, &short).unwrap();
            impact(&mut out, &format!("{car_name}.{name}"), &r);
        }
    }
    let car = &cars[0].1;
    let fine = Settings {
        safety: 0.1,
        output_step: 5e-5,
        ..Settings::default()
    };
    let strikers = [
        (
            "pendulum-pole",
            Striker::pendulum(Face::pole_of_diameter(0.254, 0.3), 1100.0, 2.2),
            Settings::default(),
        ),
        (
            "offset-right-fine",
            Striker::barrier(Face::plane_in_degrees(-5.0, 40.0, Side::Right), 3.5),
            fine,
        ),
    ];
    for (name, striker, settings) in strikers {
        let r = simulate(car, &striker, &settings).unwrap();
        impact(&mut out, name, &r);
    }
    // an RCAR impact's segment forces replayed, with body and chain sensors
    let rcar = Striker::barrier(Face::plane_in_degrees(10.0, 40.0, Side::Left), 15.0 / 3.6);
    let r = simulate(car, &rcar, &Settings::default()).unwrap();
    let normal = [-(10f64.to_radians().cos()), 10f64.to_radians().sin()];
    let sensors = vec![
        Sensor::Body([0.6, 0.7]),
        Sensor::Body([0.6, -0.7]),
        Sensor::Chain(0),
        Sensor::Chain(2),
    ];
    let input = Drive {
        step: 1e-4,
        loads: segment_loads(&r, normal),
        speed: 15.0 / 3.6,
        arm: 1.0,
        sensors: sensors.clone(),
    };
    replay(&mut out, "replay-rcar", &drive(car, &input, 0.05).unwrap());
    // a pole load through a fixed axis, coarser safety
    let force: Vec<f64> = (0..600)
        .map(|k| 3e4 * (std::f64::consts::PI * (k as f64 / 450.0).min(1.0)).sin())
        .collect();
    let pole = Load {
        lateral: 0.2,
        anchor: Some([2.1, 0.2]),
        cell: None,
        direction: [-1.0, 0.05],
        force,
    };
    let input = Drive {
        step: 1e-4,
        loads: vec![pole],
        speed: 2.0,
        arm: 1.0,
        sensors,
    };
    replay(&mut out, "replay-pole", &drive(car, &input, 0.3).unwrap());
    out.check(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/planar-regression.txt"));
}
