//! Issue 45 item 4: the pulse metrics at a defined contact end. The
//! simulation's contact end is the first sample with no force at all, so a
//! 1e-16 relative change of the pendulum speed (1.1176 against
//! 1.1176000000000001 m/s) moved it from 54.0 to 46.9 ms and the velocity
//! change to the record's end from 0.9009 to 0.8986 m/s. Ended where the
//! force stays below 1 % of its peak for 2 ms, ΔV, OLC and ASI move by
//! less than 1e-6 relative.

use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::test;
use bumpsim_verdict::pulse::{AsiMethod, Pulse};
use std::path::Path;

/// The 49 CFR 581 front pendulum test of the worked example's car at
/// `speed` m/s: the simulation's own contact end (s) and the pulse.
fn pendulum(speed: f64) -> (Option<f64>, Pulse) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml");
    let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
    let end = CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap();
    let t = test("part581-pendulum-front").unwrap();
    let car = end.car.clone().with_tyre_law(t.tyres);
    let nominal = t.striker(car.total_mass()).unwrap();
    let striker = nominal.with_speed(speed);
    let settings = bumpsim_planar::Settings::default();
    let r = bumpsim_planar::simulate(&car, &striker, &settings).unwrap();
    (r.contact_end, Pulse::of(&r))
}

#[test]
fn a_rounding_of_the_speed_moves_no_pulse_metric() {
    let (low, high) = (pendulum(1.1176), pendulum(1.1176000000000001));
    eprintln!(
        "simulation's contact end {:?} against {:?} s",
        low.0, high.0
    );
    for method in [AsiMethod::En2010, AsiMethod::En1998] {
        let (a, notes_a) = low.1.metrics(true, method);
        let (b, notes_b) = high.1.metrics(true, method);
        assert!(
            notes_a.is_empty() && notes_b.is_empty(),
            "{notes_a:?} {notes_b:?}"
        );
        let pairs = [
            ("delta-V", a.delta_v, b.delta_v),
            ("contact end", a.contact_end, b.contact_end),
            ("OLC", a.olc.unwrap(), b.olc.unwrap()),
            ("ASI", a.asi.unwrap(), b.asi.unwrap()),
            ("peak", a.peak, b.peak),
        ];
        for (name, x, y) in pairs {
            eprintln!("{method:?} {name}: {x} against {y}");
            assert!(
                (x / y - 1.0).abs() < 1e-6,
                "{method:?} {name}: {x} against {y}"
            );
        }
    }
}

/// EN 1317-1:1998's windows start at first contact (t = 0): 12 g before
/// it (a pre-trigger record) counts for nothing, 12 g after it for 1.
#[test]
fn the_1998_windows_start_at_first_contact() {
    let time: Vec<f64> = (0..=1500).map(|k| -0.05 + k as f64 * 1e-4).collect();
    let zeros = vec![0.0; time.len()];
    let before: Vec<f64> = time
        .iter()
        .map(|&t| if t < 0.0 { 12.0 * 9.81 } else { 0.0 })
        .collect();
    let after: Vec<f64> = time
        .iter()
        .map(|&t| {
            if (0.0..0.05).contains(&t) {
                12.0 * 9.81
            } else {
                0.0
            }
        })
        .collect();
    let asi = |a: &[f64]| {
        bumpsim_verdict::pulse::asi(&time, [a, &zeros, &zeros], AsiMethod::En1998).unwrap()
    };
    assert!(asi(&before) < 1e-3, "{}", asi(&before));
    assert!((asi(&after) - 1.0).abs() < 1e-3, "{}", asi(&after));
}
