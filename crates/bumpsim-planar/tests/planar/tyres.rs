//! Issue 45: locked wheels slide with the tyre's sliding grip, not its
//! rolling resistance. The car file carries both (`rolling_resistance`,
//! `mu_longitudinal`, the latter defaulting to `mu_lateral`), a file of
//! the old form (`mu_longitudinal` as the rolling resistance) is refused
//! naming the fix, and the energy split of a locked car follows.

use bumpsim_planar::car::{GRAVITY, TyreLaw};
use bumpsim_planar::{Face, PlanarCar, Settings, Side, Striker, simulate};
use std::path::{Path, PathBuf};

fn saloon() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/planar/saloon.toml")
}

/// The bundled car's tyres: rolling resistance 0.02, grip 0.8 across and,
/// by default, 0.8 along a locked wheel.
#[test]
fn the_car_file_separates_rolling_resistance_from_sliding_grip() {
    let car = PlanarCar::read(&saloon()).unwrap();
    let front = car.tyres().front;
    assert_eq!(
        (
            front.rolling_resistance,
            front.mu_longitudinal,
            front.mu_lateral
        ),
        (0.02, 0.8, 0.8)
    );
    let text = std::fs::read_to_string(saloon()).unwrap();
    let given = text.replace(
        "front = { rolling_resistance = 0.02,",
        "front = { rolling_resistance = 0.02, mu_longitudinal = 0.7,",
    );
    let car = PlanarCar::parse(&given, "c.toml".as_ref()).unwrap();
    assert_eq!(car.tyres().front.mu_longitudinal, 0.7);
    // the old form: mu_longitudinal was the rolling resistance
    let old = text.replace("rolling_resistance", "mu_longitudinal");
    let e = PlanarCar::parse(&old, "old.toml".as_ref())
        .unwrap_err()
        .to_string();
    for needle in [
        "old.toml",
        "tyres.front.mu_longitudinal = 0.02",
        "write rolling_resistance = 0.02",
    ] {
        assert!(e.contains(needle), "{needle}: {e}");
    }
    // a sliding axle's mu_longitudinal kept its meaning
    let sliding = text.replace(
        "front = { rolling_resistance = 0.02,",
        "front = { law = \"sliding\", mu_longitudinal = 0.75,",
    );
    let car = PlanarCar::parse(&sliding, "s.toml".as_ref()).unwrap();
    assert_eq!(car.tyres().front.mu_longitudinal, 0.75);
    // the written car reads back with both coefficients
    let again = PlanarCar::parse(&car.to_toml(), "w.toml".as_ref()).unwrap();
    assert_eq!(again.tyres(), car.tyres());
}

/// The deceleration of the car before its first touch (a 1 m gap), m/s²,
/// from the CG velocity history.
fn free_deceleration(law: TyreLaw) -> f64 {
    let car = PlanarCar::read(&saloon()).unwrap().with_tyre_law(law);
    let settings = Settings {
        gap: 1.0,
        output_step: 1e-3,
        duration: 0.3,
        ..Settings::default()
    };
    let r = simulate(&car, &Striker::barrier(Face::flat(), 4.0), &settings).unwrap();
    let before: Vec<usize> = (0..r.time.len()).filter(|&k| r.time[k] < -0.01).collect();
    let (a, b) = (before[10], *before.last().unwrap());
    -(r.velocity_x[b] - r.velocity_x[a]) / (r.time[b] - r.time[a])
}

/// A car sliding straight on locked wheels decelerates at μ_x g (Coulomb;
/// the slip-speed regularisation changes it by (v_s/v)²/2 < 1e-4 at
/// 4 m/s); rolling, at the rolling resistance times g.
#[test]
fn locked_wheels_decelerate_at_the_sliding_grip_rolling_ones_at_the_rolling_resistance() {
    let locked = free_deceleration(TyreLaw::Sliding);
    assert!(
        (locked / (0.8 * GRAVITY) - 1.0).abs() < 1e-3,
        "{locked} m/s² against 0.8 g"
    );
    let rolling = free_deceleration(TyreLaw::Rolling);
    assert!(
        (rolling / (0.02 * GRAVITY) - 1.0).abs() < 1e-3,
        "{rolling} m/s² against 0.02 g"
    );
}

/// The RCAR structural set-up (15 km/h, 10°, 40 % from the left, 50 mm
/// gap, 0.4 s) on locked wheels: the tyres take 4292 J of the 11424 J and
/// the bumper 7057 J (issue 45's figures with μ_x 0.8), where the rolling
/// resistance taken as the sliding grip left the tyres 663 J and the
/// bumper 9260 J.
#[test]
fn locked_wheels_take_their_share_of_the_energy() {
    let car = PlanarCar::read(&saloon())
        .unwrap()
        .with_tyre_law(TyreLaw::Sliding);
    let face = Face::Plane {
        angle: 10f64.to_radians(),
        overlap: 0.4,
        side: Side::Left,
    };
    let settings = Settings {
        gap: 0.05,
        duration: 0.4,
        ..Settings::default()
    };
    let r = simulate(&car, &Striker::barrier(face, 15.0 / 3.6), &settings).unwrap();
    let e = r.energy;
    assert!((e.initial / 11424.0 - 1.0).abs() < 1e-3, "{e:?}");
    assert!((e.friction / 4292.0 - 1.0).abs() < 0.01, "{e:?}");
    assert!((e.crush / 7057.0 - 1.0).abs() < 0.01, "{e:?}");
    assert!(e.relative_error.abs() < 1e-3, "{e:?}");
}
