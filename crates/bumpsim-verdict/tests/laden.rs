//! Issue 45 item 2: UN R42's laden runs. The laden car carries its
//! passengers' mass (`bumpsim_io::protocols::PASSENGERS` of
//! `PASSENGER_MASS`) on its body, the impactor keeps the unladen mass, and
//! in `--sequence` the laden run on an end starts from the set the unladen
//! runs left.

use bumpsim_io::protocols::{PASSENGER_MASS, PASSENGERS};
use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::select;
use std::path::Path;

fn end() -> CarEnd {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml");
    let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
    CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap()
}

fn run(names: &[&str], sequence: bool) -> Verdict {
    let mut setup = Setup::new(vec![end()], select(names).unwrap(), 0.0).unwrap();
    setup.sequence = sequence;
    verdict(&setup).unwrap()
}

#[test]
fn the_laden_car_carries_the_passengers_and_the_impactor_the_unladen_mass() {
    let unladen = end().car.clone();
    let v = run(&["r42-laden-longitudinal-front"], false);
    let t = &v.tests[0];
    let (car, _) = t.run.as_ref().expect("assessed");
    let added = PASSENGERS * PASSENGER_MASS;
    assert_eq!(added, 375.0);
    assert!((car.total_mass() - unladen.total_mass() - added).abs() < 1e-9);
    let (m, i) = (unladen.body().mass, unladen.body().yaw_inertia);
    let ratio = car.body().yaw_inertia / i;
    assert!(unladen.clone().with_load(-1.0).is_err());
    assert!(unladen.clone().with_load(f64::NAN).is_err());
    assert!((ratio - (m + added) / m).abs() < 1e-12, "{ratio}");
    // the striker: the unladen mass at 4 km/h (annex 3 §2.3.3, §2.7.5)
    let r = t.result.as_ref().unwrap();
    let v0 = 4.0 / 3.6;
    let p0 = unladen.total_mass() * v0;
    let [px, py] = r.momentum.initial_linear;
    assert!((px.abs() - p0).abs() <= 1e-9 * p0 && py.abs() < 1e-9 * p0);
    let e0 = 0.5 * unladen.total_mass() * v0 * v0;
    assert!(
        (r.energy.initial - e0).abs() <= 1e-9 * e0,
        "{}",
        r.energy.initial
    );
}

#[test]
fn the_laden_run_balances_momentum_and_energy_and_loses_no_more_than_a_plastic_impact() {
    let v = run(&["r42-laden-longitudinal-front"], false);
    let r = v.tests[0].result.as_ref().unwrap();
    let p0 = r.momentum.initial_linear[0].hypot(r.momentum.initial_linear[1]);
    assert!(
        r.momentum.linear_residual <= 1e-6 * p0,
        "{}",
        r.momentum.linear_residual
    );
    assert!(
        r.energy.relative_error.abs() <= 1e-3,
        "{}",
        r.energy.relative_error
    );
    // a plastic central impact of M (striker) on M + m (car at rest) loses
    // ½ μ v², μ = M (M + m) / (2M + m): the most any impact can take from
    // the pair's motion; the laden run takes more than the unladen one
    let m = end().car.total_mass();
    let added = PASSENGERS * PASSENGER_MASS;
    let v0 = 4.0 / 3.6_f64;
    let bound = |load: f64| 0.5 * m * (m + load) / (2.0 * m + load) * v0 * v0;
    let lost = r.energy.initial - r.energy.kinetic;
    assert!(
        lost <= bound(added) * (1.0 + 1e-3),
        "{lost} J vs {} J",
        bound(added)
    );
    let u = run(&["r42-longitudinal-front"], false);
    let ru = u.tests[0].result.as_ref().unwrap();
    let lost_unladen = ru.energy.initial - ru.energy.kinetic;
    assert!(
        lost > lost_unladen,
        "{lost} J laden, {lost_unladen} J unladen"
    );
}

#[test]
fn r42_in_sequence_runs_the_laden_impact_on_the_set_the_unladen_one_left() {
    let v = run(
        &["r42-longitudinal-front", "r42-laden-longitudinal-front"],
        true,
    );
    assert_eq!(v.tests[0].test.name, "r42-longitudinal-front");
    assert!(v.tests[0].inherited.is_none());
    let laden = &v.tests[1];
    assert_eq!(laden.test.name, "r42-laden-longitudinal-front");
    let inherited = laden.inherited.as_ref().expect("the laden run inherits");
    assert_eq!(inherited.from, vec!["r42-longitudinal-front"]);
    assert!(inherited.set > 0.0, "the bundled bumper keeps a set");
    // the set left is the unladen run's damage: its largest remaining crush
    let first = v.tests[0].result.as_ref().unwrap();
    let car = &end().car;
    let most = car
        .beam()
        .segments
        .iter()
        .zip(&first.damage)
        .map(|(b, s)| b.remaining(s))
        .fold(0.0, f64::max);
    assert!(
        (inherited.set - most).abs() <= 1e-12,
        "{} vs {most}",
        inherited.set
    );
    assert!(
        laden.assumptions[0].contains("after r42-longitudinal-front"),
        "{:?}",
        laden.assumptions
    );
}
