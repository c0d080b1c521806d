//! The links chain's impact against closed forms: a heavy mass behind a
//! light one on an elastic-perfectly-plastic crush zone into a rigid wall.

use super::*;
use approx::assert_relative_eq;
use bumpsim_core::link::{Curve, Link, Unloading};

const M: f64 = 1000.0;
const V: f64 = 10.0;
const FY: f64 = 1e5;
const K: f64 = 1e7;
const KU: f64 = 2e7;

/// m1 = 1 kg on the crush zone, M behind it through a stiff elastic link.
fn car() -> Chain {
    let front = Link::new(Curve::bilinear(K, FY, 0.0).unwrap(), Unloading::Slope(KU)).unwrap();
    let stiff = Link::linear(1e9).unwrap();
    Chain::new(vec![1.0, M], vec![0.0], vec![stiff])
        .unwrap()
        .with_front(front)
}

#[test]
fn the_crush_plastic_set_and_peak_force_follow_the_energy_of_the_plateau() {
    let crush = Crush::run(&car(), V, "car.toml".as_ref()).unwrap();
    // the whole kinetic energy goes into the plateau F_y (plus the elastic
    // ramp): δ_max = (M+m1) V² / (2 F_y) + F_y / (2 k); the unloading slope
    // gives back F_y / k_u
    let total = M + 1.0;
    let reached = total * V * V / (2.0 * FY) + FY / (2.0 * K);
    let (front_max, set) = crush.front.unwrap();
    // 1 %: the stiff inner link's vibration and the sampled maximum
    assert_relative_eq!(front_max, reached, max_relative = 0.01);
    assert_relative_eq!(set, front_max - FY / KU, max_relative = 1e-9);
    assert_relative_eq!(crush.peak.0, FY, max_relative = 0.01);
    assert!(crush.ended, "the contact ends within the run");
    // the elastic energy F_y²/(2 k_u) comes back as the rebound
    let rebound = (FY * FY / (2.0 * KU) * 2.0 / total).sqrt();
    assert_relative_eq!(-crush.final_speed, rebound, max_relative = 0.05);
    let e = crush.energy();
    assert_relative_eq!(e.initial, 0.5 * total * V * V, max_relative = 1e-12);
    let closed = e.kinetic + e.stored + e.viscous + e.plastic + e.wall;
    assert_relative_eq!(closed, e.initial, max_relative = 0.01);
    assert!(crush.warnings().is_empty(), "{:?}", crush.warnings());
}

/// A pendulum through the same crush zone: with M = the car's mass the
/// plateau takes the relative kinetic energy ½ μ V² (μ = M(M+m1)/(2M+m1)),
/// the car and the striker leave their common speed apart by what the
/// unloading gives back, and the momentum M V is the car's and the
/// striker's at the end.
#[test]
fn a_pendulum_crushes_the_zone_by_the_relative_energy_and_keeps_the_momentum() {
    let striker = M + 1.0;
    let crush = Crush::struck(&car(), striker, V, "car.toml".as_ref()).unwrap();
    let total = M + 1.0;
    let mu = striker * total / (striker + total);
    let reached = mu * V * V / (2.0 * FY) + FY / (2.0 * K);
    let (front_max, set) = crush.front.unwrap();
    assert_relative_eq!(front_max, reached, max_relative = 0.01);
    assert_relative_eq!(set, front_max - FY / KU, max_relative = 1e-9);
    assert_relative_eq!(crush.peak.0, FY, max_relative = 0.01);
    let figures = crush.striker_figures().unwrap();
    let momentum = striker * figures.final_speed + total * figures.car_final_speed;
    assert_relative_eq!(momentum, striker * V, max_relative = 1e-9);
    // they leave the common speed apart at √(2 E_r/μ): the unloading
    // slope gives back E_r = F_y²/(2 k_u)
    let common = striker * V / (striker + total);
    let apart = (FY * FY / KU / mu).sqrt();
    let car = common + striker / (striker + total) * apart;
    assert_relative_eq!(figures.car_final_speed, car, max_relative = 0.01);
    let back = common - total / (striker + total) * apart;
    assert_relative_eq!(figures.final_speed, back, max_relative = 0.01);
    let e = crush.energy();
    assert_relative_eq!(e.initial, 0.5 * striker * V * V, max_relative = 1e-12);
    assert!(e.relative_error < 1e-3, "{}", e.relative_error);
    assert!(
        crush.ended && crush.warnings().is_empty(),
        "{:?}",
        crush.warnings()
    );
}

#[test]
fn a_pendulum_into_a_links_car_runs_and_a_moving_barrier_case_too() {
    let dir = std::env::temp_dir().join(format!("bumpsim-engine-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("car.toml");
    let text = "kind = \"links\"\nmasses = [2.0, 900.0]\ndampers = [0.0]\n[[links]]\ncurve = \"linear\"\nstiffness = \"1000 N/mm\"\n";
    std::fs::write(&path, text).unwrap();
    let request = ImpactRequest {
        car: Some(&path),
        pendulum: Some(1500.0),
        speed: Some("2 m/s"),
        ..ImpactRequest::default()
    };
    let outcome = Links.impact(&request).unwrap();
    assert!(
        outcome
            .text
            .contains("pendulum of 1500 kg into the car at rest at 7.200 km/h")
            && outcome.text.contains("peak contact force")
            && outcome.text.contains("striker "),
        "{}",
        outcome.text
    );
    assert!(outcome.json.contains("\"striker\": {"), "{}", outcome.json);
    let barrier = ImpactRequest {
        pendulum: None,
        barrier: true,
        ..request
    };
    let outcome = Links.impact(&barrier).unwrap();
    assert!(
        outcome.text.contains("peak barrier force"),
        "{}",
        outcome.text
    );
    assert!(!outcome.json.contains("\"striker\""), "{}", outcome.json);
    let case = ImpactRequest {
        case: Some("rcar-structural-rear"),
        speed: None,
        barrier: false,
        ..barrier
    };
    let outcome = Links.impact(&case).unwrap();
    assert!(
        outcome.text.contains("rcar-structural-rear"),
        "{}",
        outcome.text
    );
    assert!(
        outcome.json.contains("\"mass\": 1400.0"),
        "{}",
        outcome.json
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
