//! A wall's load cells one by one in the forward runs
//! (`bumpsim_planar::cell_force`, `[model] cells`): on issue 44's
//! independent yaw-rate series (tests/peers/planar_yaw_rate.py), what the
//! 10° wall's four cells say of the bumper's effective width that its total
//! force does not.

use bumpsim_planar::PlanarCar;
use bumpsim_planar::bumper_fit::fit_bumper;
use bumpsim_planar::cell_force::cell_forces;
use bumpsim_planar::forward::forward;
use bumpsim_planar::identify::PlanarCase;

/// The case named `name` of `cases`.
fn named<'a>(cases: &'a [PlanarCase], name: &str) -> &'a PlanarCase {
    cases.iter().find(|c| c.name == name).unwrap()
}

/// The fit % of each of `case`'s cells and of its total force in `car`'s
/// forward run.
fn cell_fits(car: &PlanarCar, case: &PlanarCase) -> (Vec<f64>, f64) {
    let cells = cell_forces(car, case).unwrap();
    let total = forward(car, case).unwrap().fit_of("force").unwrap();
    (cells.iter().map(|c| c.fit_percent).collect(), total)
}

/// In a forward run the cells' simulated forces are the segments' forces
/// split by where they touch the face: together they are the striker's
/// force (a plane pushes every segment along its normal), sample by sample
/// to rounding (both filtered at the case's CFC, the total as its
/// magnitude), and the struck corner's cell carries the first touch. On
/// the generator's truth the four cells fit their channels.
#[test]
fn the_cells_share_the_total_force_and_fit_at_the_truth() {
    let Some(dir) = super::defaults::series(0) else {
        return;
    };
    let (_, study, truth) = super::truth_start::yielding_truth_of(&dir, "study-doc.toml", 0.01);
    let wall = named(&study.cases, "WALL10");
    let cells = cell_forces(&truth, wall).unwrap();
    assert_eq!(cells.len(), 4);
    let ahead = forward(&truth, wall).unwrap();
    let total = &ahead.channels[0];
    assert_eq!(total.name, "force");
    let peak = total.simulated.iter().fold(0.0f64, |m, v| m.max(*v));
    for k in 0..total.simulated.len() {
        let sum: f64 = cells.iter().map(|c| c.simulated[k]).sum();
        assert!(
            (sum.abs() - total.simulated[k]).abs() <= 1e-9 * peak,
            "sample {k}: cells {sum} N against the total {} N",
            total.simulated[k]
        );
    }
    // the left corner strikes first: the cell whose centre lies furthest
    // left carries the first force, measured and simulated alike
    let first = |v: &[f64]| {
        v.iter()
            .position(|f| *f > 0.05 * peak)
            .unwrap_or(usize::MAX)
    };
    let leftmost = (0..4)
        .max_by(|&i, &j| {
            let y = |c: usize| wall.drive.loads[cells[c].load].anchor.unwrap()[1];
            y(i).total_cmp(&y(j))
        })
        .unwrap();
    for v in [
        |c: &bumpsim_planar::cell_force::CellForce| c.simulated.clone(),
        |c: &bumpsim_planar::cell_force::CellForce| c.measured.clone(),
    ] {
        let onsets: Vec<usize> = cells.iter().map(|c| first(&v(c))).collect();
        let earliest = (0..4).min_by_key(|&c| onsets[c]).unwrap();
        assert_eq!(earliest, leftmost, "onsets {onsets:?}");
    }
    // the truth-equivalent car (bumpsim's family: its bumper's law fitted)
    // fits the cells that carry the wall's force (measured, release: 94.3
    // and 81.5 % on the struck corner's two cells, which carry 49 and 24
    // kN; the other two carry 0.2 kN and nothing, noise); the second's gap
    // is the generator's beam acting 1.653 m wide (89.4 % with that width,
    // `at_the_truths`)
    let fitted = fit_bumper(&truth, &study.cases, true, true).unwrap().car;
    let (fits, force) = cell_fits(&fitted, wall);
    eprintln!("truth, bumper fitted to the cells: WALL10 cells {fits:.2?} %, total {force:.2} %");
    let measured_peak = |c: &bumpsim_planar::cell_force::CellForce| {
        c.measured.iter().fold(0.0f64, |m, v| m.max(*v))
    };
    let loaded: Vec<f64> = (cells.iter().zip(&fits))
        .filter(|(c, _)| measured_peak(c) > 0.1 * peak)
        .map(|(_, f)| *f)
        .collect();
    assert_eq!(loaded.len(), 2, "{fits:?}");
    assert!(
        loaded.iter().all(|f| *f > 75.0) && force > 90.0,
        "{fits:?} {force}"
    );
}

/// A measurement: at each car's truth (`BUMPSIM_SEEDS`, default `0,3`),
/// the 10° wall's cells and total force and the forward offset force / yaw
/// rate with the truth's bumper acting 1.6 m wide (drawn) and 1.653 m (the
/// generator's 31 points), fitted to the total force or to the cells.
/// `cargo test --release -p bumpsim-planar --test planar -- --ignored
/// cells::at_the_truths --nocapture`.
#[test]
#[ignore = "a measurement: four bumper fits per car, seconds each in release"]
fn at_the_truths() {
    let seeds = std::env::var("BUMPSIM_SEEDS").unwrap_or_else(|_| "0,3".into());
    for seed in seeds.split(',').map(|s| s.trim().parse::<u64>().unwrap()) {
        let Some(dir) = super::defaults::series(seed) else {
            return;
        };
        let (_, study, truth) = super::truth_start::yielding_truth_of(&dir, "study-doc.toml", 0.01);
        let wall = named(&study.cases, "WALL10");
        let offset = named(&study.validation, "OFFSET40");
        for width in [1.6, 1.6 * 31.0 / 30.0] {
            let car = truth.clone().with_effective_width(width).unwrap();
            for cells in [false, true] {
                let fitted = fit_bumper(&car, &study.cases, true, cells).unwrap().car;
                let (fits, force) = cell_fits(&fitted, wall);
                let peaks: Vec<String> = cell_forces(&fitted, wall)
                    .unwrap()
                    .iter()
                    .map(|c| {
                        let peak = |v: &[f64]| v.iter().fold(0.0f64, |m, f| m.max(*f)) / 1e3;
                        let y = wall.drive.loads[c.load].anchor.unwrap()[1];
                        format!(
                            "y {y:+.2} m {:.1}/{:.1} kN",
                            peak(&c.simulated),
                            peak(&c.measured)
                        )
                    })
                    .collect();
                eprintln!("  cells' peaks simulated/measured: {}", peaks.join(", "));
                let ahead = forward(&fitted, offset).unwrap();
                eprintln!(
                    "seed {seed}: w_e {width:.4} m, bumper fitted to the {}: WALL10 cells {fits:.2?} %, total {force:.2} %; forward OFFSET40 force {:.2} %, yaw rate {:.2} %",
                    if cells { "cells" } else { "total" },
                    ahead.fit_of("force").unwrap(),
                    ahead.fit_of("yaw rate").unwrap()
                );
            }
        }
    }
}
