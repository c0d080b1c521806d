//! Integration tests of impacts and the mass-reduction study against
//! analytic solutions and paper A's trends.

#[path = "impact/regression.rs"]
mod regression;

use approx::assert_relative_eq;
use bumpsim_core::model::MsdModel;
use bumpsim_impact::bumper::Bumper;
use bumpsim_impact::impact::{Options, Scenario, simulate};
use bumpsim_impact::reduction::{Criterion, TwoDof, equivalent_mass, linspace, sweep_bumper};
use std::f64::consts::PI;

fn rigid(mass: f64) -> MsdModel {
    MsdModel::new(vec![mass], vec![], vec![]).unwrap()
}

#[test]
fn single_mass_on_a_linear_bumper_matches_the_oscillator() {
    let (m, s, v0) = (900.0, 1.5e6, 8.0 / 3.6);
    let bumper = Bumper::three_part(s, 1e12, s).unwrap();
    let r = simulate(
        &rigid(m),
        &bumper,
        Scenario::Barrier { speed: v0 },
        &Options::default(),
    )
    .unwrap();
    assert_relative_eq!(r.contact_time, PI * (m / s).sqrt(), max_relative = 1e-3);
    assert_relative_eq!(r.max_compression, v0 * (m / s).sqrt(), max_relative = 1e-4);
    assert!(r.remaining_compression < 1e-9, "elastic: nothing remains");
    assert!(
        r.energy.relative_error < 1e-3,
        "energy balance {}",
        r.energy.relative_error
    );
    // elastic rebound: the mass leaves at the speed it came
    let last = *r.velocities[0].last().unwrap();
    assert_relative_eq!(last, -v0, max_relative = 1e-3);
}

#[test]
fn plateau_compression_follows_from_the_energy() {
    let (m, v0) = (1200.0, 8.0 / 3.6);
    let bumper = Bumper::three_part(3e6, 40e3, 9e6).unwrap();
    let r = simulate(
        &rigid(m),
        &bumper,
        Scenario::Barrier { speed: v0 },
        &Options::default(),
    )
    .unwrap();
    // ½ m V0² = ½ F_max d_knee + F_max (d − d_knee)
    let knee = 40e3 / 3e6;
    let expected = (0.5 * m * v0 * v0 - 0.5 * 40e3 * knee) / 40e3 + knee;
    assert_relative_eq!(r.max_compression, expected, max_relative = 1e-4);
    assert_relative_eq!(
        r.remaining_compression,
        expected - 40e3 / 9e6,
        max_relative = 1e-4
    );
    assert_relative_eq!(r.peak_force, 40e3, max_relative = 1e-9);
    assert!(
        r.energy.relative_error < 1e-3,
        "energy balance {}",
        r.energy.relative_error
    );
    assert!(r.absorbed_energy > 0.9 * 0.5 * m * v0 * v0);
}

#[test]
fn pendulum_into_a_damped_car_conserves_momentum_and_energy() {
    let car = MsdModel::new(vec![40.0, 300.0, 1100.0], vec![6e3, 2e4], vec![1.2e6, 5e5]).unwrap();
    let bumper = Bumper::three_part(1.2e6, 45e3, 4e6).unwrap();
    let (mp, v0) = (1450.0, 6.0 / 3.6);
    let r = simulate(
        &car,
        &bumper,
        Scenario::Impactor {
            mass: mp,
            speed: v0,
        },
        &Options::default(),
    )
    .unwrap();
    let masses = [mp, 40.0, 300.0, 1100.0];
    let last = r.time.len() - 1;
    let momentum: f64 = masses
        .iter()
        .zip(&r.velocities)
        .map(|(m, v)| m * v[last])
        .sum();
    assert_relative_eq!(momentum, mp * v0, max_relative = 1e-9);
    assert!(
        r.energy.relative_error < 1e-3,
        "energy balance {}",
        r.energy.relative_error
    );
    assert!(
        r.contact_time > 0.02 && r.contact_time < 0.3,
        "{}",
        r.contact_time
    );
    assert_eq!(r.bodies, ["impactor", "m1", "m2", "m3"]);
}

#[test]
fn scale_factor_follows_paper_a() {
    let v0 = 8.0 / 3.6;
    let bumper = Bumper::three_part(2e6, 80e3, 8e6).unwrap();
    let base = TwoDof {
        m1: 650.0,
        m2: 400.0,
        k: 4e6,
    };
    let f = equivalent_mass(&base, &bumper, v0, Criterion::Remaining)
        .unwrap()
        .scale_factor;
    assert!(
        f > 650.0 / 1050.0 && f < 1.0,
        "between M1/(M1+M2) and 1: {f}"
    );
    let stiff = TwoDof { k: 4e9, ..base };
    let g = equivalent_mass(&stiff, &bumper, v0, Criterion::Remaining)
        .unwrap()
        .scale_factor;
    assert!((g - 1.0).abs() < 0.01, "a stiff car is one rigid mass: {g}");
    // fig. 7: higher ramp slope and higher F_max give a lower factor (maximum criterion)
    let car = TwoDof {
        m1: 0.62 * 1050.0,
        m2: 0.38 * 1050.0,
        k: 4e6,
    };
    let grid = sweep_bumper(
        &car,
        linspace(1e6, 8e6, 4),
        linspace(40e3, 200e3, 4),
        8e6,
        v0,
        Criterion::Maximum,
        &|| {},
    );
    for i in 0..4 {
        for j in 0..4 {
            let here = grid.values[i][j].unwrap();
            assert!(here > 0.6 && here < 1.0, "{here}");
            if i + 1 < 4 {
                assert!(
                    grid.values[i + 1][j].unwrap() <= here + 1e-6,
                    "falls with the ramp slope"
                );
            }
            if j + 1 < 4 {
                assert!(
                    grid.values[i][j + 1].unwrap() <= here + 1e-6,
                    "falls with F_max"
                );
            }
        }
    }
}

#[test]
fn bad_input_is_refused() {
    assert!(Bumper::three_part(-2e6, 80e3, 8e6).is_err());
    assert!(Bumper::three_part(2e6, 0.0, 8e6).is_err());
    assert!(Bumper::three_part(2e6, 80e3, 1e6).is_err());
    let bumper = Bumper::three_part(2e6, 80e3, 8e6).unwrap();
    let err = simulate(
        &rigid(900.0),
        &bumper,
        Scenario::Barrier { speed: 0.0 },
        &Options::default(),
    )
    .unwrap_err();
    assert!(err.to_string().contains("speed"), "{err}");
    let elastic = Bumper::three_part(2e6, 1e9, 2e6).unwrap();
    let car = TwoDof {
        m1: 650.0,
        m2: 400.0,
        k: 4e6,
    };
    let err = equivalent_mass(&car, &elastic, 2.0, Criterion::Remaining)
        .unwrap_err()
        .to_string();
    assert!(err.contains("elastic"), "{err}");
}
