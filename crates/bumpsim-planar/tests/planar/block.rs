//! Issue 45 item 1: a segment crushed to its depth blocks. One segment of
//! a rigid car into a flat wall against an independent scipy model of a
//! mass on a spring with a block (tests/peers/scipy_block.py).

use bumpsim_impact::bumper::Bumper;
use bumpsim_planar::car::{Beam, Block, Body, SideChain, Tyres};
use bumpsim_planar::{Face, PlanarCar, PlanarResult, Settings, Side, Striker, simulate};
use std::path::Path;

pub(crate) const MASS: f64 = 1200.0;
pub(crate) const SPRING: f64 = 4e5;
pub(crate) const DEPTH: f64 = 0.05;
pub(crate) const BLOCK: f64 = 2e7;
pub(crate) const SPEED: f64 = 2.0;

fn car(block: Option<Block>) -> PlanarCar {
    elastic_car(block, SideChain::default())
}

/// A rigid car of [`MASS`] behind one elastic segment of [`SPRING`] (the
/// same slope loading and unloading, no plateau in reach) with `block`, on
/// the side chains `side` (shared with the crash-box test).
pub(crate) fn elastic_car(block: Option<Block>, side: SideChain) -> PlanarCar {
    let body = Body {
        mass: MASS,
        yaw_inertia: 1500.0,
        cg_behind_bumper: 2.0,
        wheelbase: 2.5,
        cg_behind_front_axle: 1.2,
        track: 1.4,
    };
    let beam = Beam {
        width: 1.2,
        side_member_spacing: 0.9,
        segments: vec![Bumper::three_part(SPRING, 1e12, SPRING).unwrap()],
        bending: 0.0,
        block,
    };
    PlanarCar::new(body, side.clone(), side, beam, Tyres::default()).unwrap()
}

/// `car` into a flat wall at [`SPEED`] for `duration`, s, contact or not.
pub(crate) fn into_wall(car: &PlanarCar, duration: f64) -> PlanarResult {
    let face = Face::Plane {
        angle: 0.0,
        overlap: 1.0,
        side: Side::Left,
    };
    let settings = Settings {
        duration,
        output_step: 1e-3,
        stop_after_contact: false,
        ..Settings::default()
    };
    simulate(car, &Striker::barrier(face, SPEED), &settings).unwrap()
}

fn impact(block: Option<Block>) -> PlanarResult {
    into_wall(&car(block), 0.2)
}

#[test]
fn a_segment_past_its_depth_blocks_as_scipy_s_mass_on_a_spring_with_a_block() {
    if !bumpsim_peers::python_available("scipy") {
        return;
    }
    let block = Block {
        depth: DEPTH,
        stiffness: BLOCK,
    };
    let r = impact(Some(block));
    let free = impact(None);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("planar-block");
    std::fs::create_dir_all(&dir).unwrap();
    let params = dir.join("block.json");
    let json = format!(
        "{{\"mass\": {MASS}, \"stiffness\": {SPRING}, \"block\": {BLOCK}, \"depth\": {DEPTH}, \"speed\": {SPEED}, \"times\": {:?}}}",
        r.time.iter().map(|t| t - r.time[0]).collect::<Vec<_>>()
    );
    std::fs::write(&params, json).unwrap();
    let text = crate::scipy_peer("scipy_block.py", &params);
    let mut theirs = Vec::new();
    let mut bottomed = f64::NAN;
    for line in text.lines().skip(1) {
        let (a, b) = line.split_once(',').unwrap();
        match a {
            "bottomed" => bottomed = b.parse().unwrap(),
            _ => theirs.push(b.parse::<f64>().unwrap()),
        }
    }
    let ours = &r.crush[0];
    assert_eq!(ours.len(), theirs.len());
    let peak = theirs.iter().copied().fold(0.0, f64::max);
    let worst = ours
        .iter()
        .zip(&theirs)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(worst <= 2e-3 * peak, "crush off by {worst} m of {peak} m");
    // the block takes what the spring leaves at the depth: ½(k + k_b) e²
    // + k D e = ½ M V² − ½ k D² gives the crush past it, e = 12.7 mm;
    // without it the spring alone would take V √(M/k) = 109.5 mm
    let left = 0.5 * MASS * SPEED * SPEED - 0.5 * SPRING * DEPTH * DEPTH;
    let (a, b) = (0.5 * (SPRING + BLOCK), SPRING * DEPTH);
    let excess = (-b + (b * b + 4.0 * a * left).sqrt()) / (2.0 * a);
    assert!((r.max_compression - DEPTH - excess).abs() < 0.01 * excess);
    assert!((peak - DEPTH - excess).abs() < 0.01 * excess, "peak {peak}");
    assert!(free.max_compression > 0.1, "{}", free.max_compression);
    // the instant, from the first touch (the time origin), against scipy's event
    let b = r.bottomed.expect("the segment bottomed");
    assert_eq!(b.segment, 0);
    let at = b.time - r.contact_start.unwrap();
    assert!(
        (at - bottomed).abs() < 2.0 * r.step + 1e-5,
        "{at} against {bottomed}"
    );
    assert!(free.bottomed.is_none());
    // elastic: the energy balance closes and the car leaves at its speed
    assert!(r.energy.max_relative_error < 1e-3, "{:?}", r.energy);
    assert!((r.velocity_x.last().unwrap() + SPEED).abs() < 1e-3 * SPEED);
}
