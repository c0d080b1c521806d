//! Hostile inputs of a planar run: energies that underflow or overflow.

use super::*;
use crate::striker::{Face, Side};

/// A speed whose kinetic energy underflows to 0, or a pendulum mass whose
/// energy overflows, made the balances 0/0 = NaN with exit 0.
#[test]
fn an_unusable_closing_energy_is_refused_by_name() {
    let car = tests_car();
    for striker in [
        Striker::barrier(Face::flat(), 1e-300),
        Striker::pendulum(Face::flat(), 1e308, 2.0),
        Striker::barrier(Face::flat(), 1e200),
    ] {
        let err = simulate(&car, &striker, &Settings::default())
            .unwrap_err()
            .to_string();
        let named = ["striker kinetic energy", "speed = ", "striker mass = "]; // or the ranges
        assert!(named.iter().any(|n| err.contains(n)), "{err}");
    }
    // rails 1000 m apart: the balance error reached 1.8e10 before this
    // counted as a divergence
    let wide = wide_car(1e3);
    let rcar = Striker::barrier(Face::plane_in_degrees(10.0, 40.0, Side::Left), 15.0 / 3.6);
    let err = simulate(&wide, &rcar, &Settings::default());
    assert!(matches!(err, Err(PlanarError::Diverged { .. })), "{err:?}");
    let r = simulate(&wide_car(2.0), &rcar, &Settings::default()).unwrap();
    assert!(r.energy.max_relative_error < 1e-3, "{:?}", r.energy);
    let slow = Striker::barrier(Face::flat(), 1e-3);
    let r = simulate(&car, &slow, &Settings::default()).unwrap();
    assert!(r.energy.relative_error.is_finite());
}

/// A diverging run is repeated at half the safety factor as often as
/// `refine` allows, and refused with the smallest step it took, named in
/// the message with what to check.
#[test]
fn a_diverging_run_is_refined_and_refused_with_its_step() {
    let rcar = Striker::barrier(Face::plane_in_degrees(10.0, 40.0, Side::Left), 15.0 / 3.6);
    let step = |refine| match simulate(
        &wide_car(1e3),
        &rcar,
        &Settings {
            refine,
            ..Settings::default()
        },
    ) {
        Err(PlanarError::Diverged { step, .. }) => step,
        other => panic!("{other:?}"),
    };
    let (coarse, fine) = (step(0), step(2));
    // a quarter of the step, to the rounding of the step onto the output
    // interval (a whole number of steps per sample)
    assert!(
        fine <= 0.3 * coarse && fine >= 0.2 * coarse,
        "{coarse} {fine}"
    );
    let err = simulate(&wide_car(1e3), &rcar, &Settings::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains(" ms with a step of ") && err.contains("side members far apart"),
        "{err}"
    );
}

/// A gap is free travel before the same impact: the record starts at
/// −gap/v and the impact is the gap-less one to within its step.
#[test]
fn a_gap_delays_the_same_impact_and_bad_gaps_are_refused() {
    let car = tests_car();
    let rcar = Striker::barrier(Face::plane_in_degrees(10.0, 40.0, Side::Left), 10.0 / 3.6);
    let at = |gap| {
        simulate(
            &car,
            &rcar,
            &Settings {
                gap,
                ..Settings::default()
            },
        )
    };
    let (touching, apart) = (at(0.0).unwrap(), at(0.05).unwrap());
    assert!(
        (apart.time[0] + 0.05 / (10.0 / 3.6)).abs() < 1e-12,
        "{}",
        apart.time[0]
    );
    assert!(
        apart.contact_start.unwrap().abs() <= apart.step,
        "{:?}",
        apart.contact_start
    );
    for (a, b) in [
        (touching.peak_force, apart.peak_force),
        (touching.max_compression, apart.max_compression),
        (touching.peak_yaw_rate, apart.peak_yaw_rate),
    ] {
        assert!((a - b).abs() <= 1e-3 * a.abs(), "{a} against {b}");
    }
    for gap in [f64::NAN, -0.01, 11.0, f64::INFINITY, 2.9] {
        let err = at(gap).unwrap_err().to_string();
        assert!(err.contains("gap"), "{gap}: {err}");
    }
}

fn wide_car(spacing: f64) -> PlanarCar {
    use crate::car::Layout;
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;
    let chain = MsdModel::new(vec![16.0, 1300.0], vec![4e3], vec![6e6]).unwrap();
    let bumper = Bumper::three_part(3e6, 200e3, 2e7).unwrap();
    let layout = Layout {
        side_member_spacing: spacing,
        bumper_width: 1.5,
        bending: 2e4,
        ..Layout::default()
    };
    PlanarCar::symmetric(&chain, &bumper, &layout).unwrap()
}

fn tests_car() -> PlanarCar {
    use crate::car::Layout;
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;
    let chain = MsdModel::new(vec![10.0, 1200.0], vec![2e3], vec![2e6]).unwrap();
    let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
    PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap()
}
