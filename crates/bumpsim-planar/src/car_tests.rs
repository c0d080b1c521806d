//! Tests of the planar car's construction (car.rs).

use super::*;

fn chain() -> MsdModel {
    MsdModel::new(vec![10.0, 20.0, 1000.0], vec![1e3, 2e3], vec![1e6, 2e6]).unwrap()
}

#[test]
fn symmetric_car_halves_the_chain_and_splits_the_bumper() {
    let bumper = Bumper::three_part(1e6, 5e4, 4e6).unwrap();
    let car = PlanarCar::symmetric(&chain(), &bumper, &Layout::default()).unwrap();
    assert_eq!(car.left().masses, vec![5.0, 10.0]);
    assert_eq!(car.right().springs, vec![5e5, 1e6]);
    assert_eq!(car.body().mass, 1000.0);
    assert_eq!(car.beam().segments.len(), 10);
    assert!((car.beam().segments[0].loading_force(1.0) - 5e3).abs() < 1e-9);
    assert!((car.total_mass() - 1030.0).abs() < 1e-12);
    assert!((car.segment_centre(0) + 0.72).abs() < 1e-12);
}

#[test]
fn bad_parameters_name_themselves() {
    let bumper = Bumper::three_part(1e6, 5e4, 4e6).unwrap();
    let mut layout = Layout {
        yaw_inertia: -5.0,
        ..Layout::default()
    };
    let err = PlanarCar::symmetric(&chain(), &bumper, &layout).unwrap_err();
    assert!(err.to_string().contains("body.yaw_inertia = -5"), "{err}");
    layout.yaw_inertia = 2000.0;
    layout.cg_behind_front_axle = 3.0;
    let err = PlanarCar::symmetric(&chain(), &bumper, &layout).unwrap_err();
    assert!(err.to_string().contains("between the axles"), "{err}");
    layout.cg_behind_front_axle = 1.0;
    let long = SideChain {
        masses: vec![1.0; 1001],
        dampers: vec![0.0; 1001],
        springs: vec![1e6; 1001],
        links: Vec::new(),
    };
    let car = PlanarCar::symmetric(&chain(), &bumper, &layout).unwrap();
    let err = PlanarCar::new(
        *car.body(),
        long,
        car.right().clone(),
        car.beam().clone(),
        *car.tyres(),
    )
    .unwrap_err();
    assert!(err.to_string().contains("left.masses = 1001"), "{err}");
    layout.tyres.front.mu_lateral = f64::NAN;
    let err = PlanarCar::symmetric(&chain(), &bumper, &layout).unwrap_err();
    assert!(err.to_string().contains("tyres.front.mu_lateral"), "{err}");
    // a relaxation length so short that |v|/σ overflows to NaN in a run
    layout.tyres.front.mu_lateral = 0.8;
    layout.tyres.rear.relaxation_length = 1e-320;
    let err = PlanarCar::symmetric(&chain(), &bumper, &layout).unwrap_err();
    assert!(
        err.to_string().contains("tyres.rear.relaxation_length")
            && err.to_string().contains("from 1e-6 m to 10 m"),
        "{err}"
    );
    layout.tyres.rear.relaxation_length = 0.0;
    assert!(PlanarCar::symmetric(&chain(), &bumper, &layout).is_ok());
}

#[test]
fn an_echoed_value_carries_no_unit_conversion_noise() {
    let echo = |v: f64| parameter("x", v, "m", "ok").to_string();
    assert_eq!(echo(3300.0 * 0.001), "x = 3.3 m: ok");
    assert_eq!(echo(-5.0), "x = -5.0 m: ok");
    assert_eq!(echo(1e-300), "x = 1e-300 m: ok");
    assert_eq!(echo(f64::NAN), "x = NaN m: ok");
    assert_eq!(echo(f64::INFINITY), "x = inf m: ok");
    assert_eq!(echo(0.1 + 0.2), "x = 0.3 m: ok");
}
