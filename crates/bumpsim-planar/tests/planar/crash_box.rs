//! Issue 45 item 1: a crash box compressed to its depth blocks, and the
//! force goes on into the rail. One elastic segment on two tips, each
//! joined to the body by its crash box, into a flat wall, against an
//! independent scipy model of the same two masses with both blocks
//! (tests/peers/scipy_block.py, its "box" case).

use super::block::{BLOCK, DEPTH, MASS, SPEED, SPRING, elastic_car, into_wall};
use bumpsim_planar::car::{Block, SideChain};
use bumpsim_planar::{PlanarCar, PlanarResult};
use std::path::Path;

const TIP: f64 = 8.0;
const BOX: f64 = 1.5e6;
const BOX_DEPTH: f64 = 0.02;
const BOX_BLOCK: f64 = 2e7;

fn car(boxes: Option<Block>) -> PlanarCar {
    let block = Block {
        depth: DEPTH,
        stiffness: BLOCK,
    };
    let side = SideChain {
        masses: vec![TIP],
        dampers: vec![0.0],
        springs: vec![BOX],
        links: Vec::new(),
    };
    elastic_car(Some(block), side)
        .with_crash_boxes(boxes)
        .unwrap()
}

fn impact(boxes: Option<Block>) -> PlanarResult {
    into_wall(&car(boxes), 0.15)
}

/// The boxes' compression history, m (both sides alike).
fn compression(r: &PlanarResult) -> Vec<f64> {
    r.chain_displacement[0].iter().map(|u| -u).collect()
}

#[test]
fn a_crash_box_past_its_depth_blocks_as_scipy_s_two_masses_with_blocks() {
    if !bumpsim_peers::python_available("scipy") {
        return;
    }
    let block = Block {
        depth: BOX_DEPTH,
        stiffness: BOX_BLOCK,
    };
    let r = impact(Some(block));
    let free = impact(None);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("planar-crash-box");
    std::fs::create_dir_all(&dir).unwrap();
    let params = dir.join("box.json");
    // both tips and both boxes together: the segment's force splits in half
    let json = format!(
        "{{\"mass\": {MASS}, \"stiffness\": {SPRING}, \"block\": {BLOCK}, \"depth\": {DEPTH}, \"speed\": {SPEED}, \"box\": {{\"tip_mass\": {}, \"stiffness\": {}, \"block\": {}, \"depth\": {BOX_DEPTH}}}, \"times\": {:?}}}",
        2.0 * TIP,
        2.0 * BOX,
        2.0 * BOX_BLOCK,
        r.time.iter().map(|t| t - r.time[0]).collect::<Vec<_>>()
    );
    std::fs::write(&params, json).unwrap();
    let text = crate::scipy_peer("scipy_block.py", &params);
    let (mut crush, mut boxes) = (vec![], vec![]);
    let (mut bottomed, mut box_bottomed) = (f64::NAN, f64::NAN);
    for line in text.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        match fields[0] {
            "bottomed" => bottomed = fields[1].parse().unwrap(),
            "box_bottomed" => box_bottomed = fields[1].parse().unwrap(),
            _ => {
                crush.push(fields[1].parse::<f64>().unwrap());
                boxes.push(fields[2].parse::<f64>().unwrap());
            }
        }
    }
    let ours = compression(&r);
    assert_eq!(ours.len(), boxes.len());
    for (mine, theirs, what) in [(&r.crush[0], &crush, "crush"), (&ours, &boxes, "box")] {
        let peak = theirs.iter().copied().fold(0.0, f64::max);
        let worst = mine
            .iter()
            .zip(theirs)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(worst <= 5e-3 * peak, "{what} off by {worst} m of {peak} m");
    }
    // the box passed its depth, by no more than its block's compliance
    // at the largest force it passed on
    let most = ours.iter().copied().fold(0.0, f64::max);
    let force = BOX * most + BOX_BLOCK * (most - BOX_DEPTH);
    assert!(most > BOX_DEPTH, "{most}");
    assert!(most <= BOX_DEPTH + force / BOX_BLOCK, "{most}");
    // the rail takes more than the box alone could pass at its depth
    let rail = r.side_force_left.iter().copied().fold(0.0, f64::max);
    assert!(rail > BOX * BOX_DEPTH, "{rail}");
    // without the block the box runs far past its depth
    let unblocked = compression(&free).into_iter().fold(0.0, f64::max);
    assert!(unblocked > most + 0.005, "{unblocked} against {most}");
    assert!(free.box_bottomed.is_none());
    // the instants, from the first touch, against scipy's events
    let start = r.contact_start.unwrap();
    let b = r.box_bottomed.expect("a crash box bottomed");
    let tolerance = 2.0 * r.step + 1e-5;
    assert!(
        (b.time - start - box_bottomed).abs() < tolerance,
        "{b:?} against {box_bottomed}"
    );
    let s = r.bottomed.expect("the segment bottomed");
    assert!(
        (s.time - start - bottomed).abs() < tolerance,
        "{s:?} against {bottomed}"
    );
    // elastic: the energy balance closes with the blocks' energy
    assert!(r.energy.max_relative_error < 1e-3, "{:?}", r.energy);
}

#[test]
fn a_car_file_s_crash_boxes_block_and_read_back() {
    let text = std::fs::read_to_string("../../examples/verdict/car.toml").unwrap();
    let with = format!("{text}\n[crash_boxes]\ndepth = 40.0\n");
    let car = PlanarCar::parse(&with, "car.toml".as_ref()).unwrap();
    let block = car.crash_boxes().unwrap();
    assert_eq!(block.depth, 0.04);
    assert_eq!(
        block.stiffness,
        bumpsim_planar::car::DEFAULT_CRASH_BOX_BLOCK_STIFFNESS
    );
    let again = PlanarCar::parse(&car.to_toml(), "car.toml".as_ref()).unwrap();
    assert_eq!(again, car);
    let bad = format!("{text}\n[crash_boxes]\nblock_stiffness = 1e8\n");
    let err = PlanarCar::parse(&bad, "car.toml".as_ref()).unwrap_err();
    assert!(err.to_string().contains("crash_boxes.depth"), "{err}");
    let bad = format!("{text}\n[crash_boxes]\ndepth = -4.0\n");
    let err = PlanarCar::parse(&bad, "car.toml".as_ref()).unwrap_err();
    assert!(
        err.to_string().contains("crash_boxes.depth = -0.004"),
        "{err}"
    );
}
