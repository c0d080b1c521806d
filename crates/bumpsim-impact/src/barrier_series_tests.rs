use super::*;
use bumpsim_core::link::{Curve, Link, Unloading};

/// A rigid 1000 kg car behind an elastic-perfectly-plastic crush zone
/// (k = 1e8 N/m, F_y = 100 kN, unloading at k): into the wall at 10 m/s it
/// is decelerated by F_y for t = m V / F_y = 0.1 s, then springs back at
/// `v = F_y / √(k m)`.
fn crushing_car() -> LinkChain {
    let front = Link::new(
        Curve::bilinear(1e8, 1e5, 0.0).unwrap(),
        Unloading::Slope(1e8),
    )
    .unwrap();
    LinkChain::new(vec![1000.0], vec![], vec![])
        .unwrap()
        .with_front(front)
}

/// The pendulum series' chain without noise or biases.
fn quiet() -> Chain {
    Chain {
        duration: 0.2,
        force_noise: 0.0,
        acceleration_noise: 0.0,
        biases: [0.0, 0.0],
        ..Chain::default()
    }
}

#[test]
fn a_crushing_rigid_car_records_its_yield_force_deceleration_and_momentum() {
    let chain = quiet();
    let sensors = accelerometers(None, 1).unwrap();
    assert_eq!(sensors[0].1[0].0, "10SIMELE0000ACXP");
    let channels = record(&crushing_car(), ("B10", 10.0), &sensors, &chain, 0).unwrap();
    assert_eq!(
        channels.iter().map(|c| c.code.as_str()).collect::<Vec<_>>(),
        ["B0LOMASU0000FOXP", "10SIMELE0000ACXP", "10SIMERI0000ACXP"]
    );
    let pre = (chain.pretrigger / chain.step).round() as usize;
    let force = channels[0].series.values();
    let accel = channels[1].series.values();
    assert!(
        force[..pre].iter().all(|f| *f == 0.0),
        "a quiet pre-trigger"
    );
    // mid-crush: the wall holds the car at −F_y, a = −F_y / m (0.1 %)
    let mid = pre + 500;
    assert!((force[mid] + 1e5).abs() < 1e2, "{}", force[mid]);
    assert!((accel[mid] + 100.0).abs() < 0.1, "{}", accel[mid]);
    // impulse = m (v_end − V), v_end the spring-back: 0.5 %
    let impulse: f64 = force.iter().sum::<f64>() * chain.step;
    let expected = 1000.0 * (-1e5 / (1e8_f64 * 1000.0).sqrt() - 10.0);
    assert!(
        (impulse - expected).abs() < 0.005 * expected.abs(),
        "{impulse} vs {expected}"
    );
    // the car's own ΔV from its accelerometer: the same
    let dv: f64 = accel.iter().sum::<f64>() * chain.step;
    assert!((1000.0 * dv - expected).abs() < 0.005 * expected.abs());
}

#[test]
fn the_same_seed_makes_the_same_noise_and_another_seed_other_noise() {
    let sensors = accelerometers(None, 1).unwrap();
    let car = crushing_car();
    let made = |seed: u64| {
        let chain = Chain {
            seed,
            ..Chain::default()
        };
        record(&car, ("B10", 10.0), &sensors, &chain, 0).unwrap()
    };
    let (a, b, c) = (made(1), made(1), made(2));
    assert_eq!(a, b);
    assert_ne!(a[0].series.values(), c[0].series.values());
}

#[test]
fn accelerometers_are_mass_numbers_of_the_car() {
    let codes = |given: &[i64]| {
        accelerometers(Some(given), 3)
            .unwrap()
            .iter()
            .map(|(j, c)| (*j, c[0].0))
            .collect::<Vec<_>>()
    };
    assert_eq!(
        codes(&[3, 1, 2]),
        [
            (2, "10SECMLE0000ACXP"),
            (0, "10SIMELE0000ACXP"),
            (1, "10ENGN000001ACXP")
        ]
    );
    assert_eq!(accelerometers(None, 3).unwrap()[0].0, 2);
    for (given, needle) in [
        (&[0][..], "mass 0: the car's masses are 1 to 3"),
        (&[4], "mass 4"),
        (&[2, 2], "given twice"),
        (&[], "an empty list"),
    ] {
        let e = accelerometers(Some(given), 3).unwrap_err().to_string();
        assert!(e.contains(needle), "{e}");
    }
    let e = accelerometers(Some(&[2, 3]), 4).unwrap_err().to_string();
    assert!(e.contains("only one mass between"), "{e}");
}

#[test]
fn derivative_is_exact_on_a_parabola_inside() {
    let step = 0.01;
    let v: Vec<f64> = (0..50).map(|k| (k as f64 * step).powi(2)).collect();
    let a = derivative(&v, step);
    for (k, ak) in a.iter().enumerate().take(49).skip(1) {
        assert!((ak - 2.0 * k as f64 * step).abs() < 1e-9);
    }
    assert_eq!(derivative(&[1.0], step), [0.0]);
}

#[test]
fn a_history_beyond_its_limit_is_refused_before_the_run() {
    let chain = Chain {
        duration: 100.0,
        ..Chain::default()
    };
    let e = check_history(&chain, 3).unwrap_err().to_string();
    assert!(e.contains("MAX_HISTORY_VALUES"), "{e}");
    assert!(check_history(&Chain::default(), 3).is_ok());
}
