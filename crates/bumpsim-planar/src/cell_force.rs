//! A wall's load cells one by one in a forward run (issue 44, item 1:
//! every sensor a test carries): which cell carries how much of the
//! striker's force, and when, against what each cell measured.
//!
//! A load-cell wall measures its force per cell (`cell` with `anchor`,
//! [`crate::drive::Load::cell`]): cell k's centre `a_k` on the face (body
//! frame at the case's time zero), its width `w_k` along the face and the
//! face's normal `n` (the load's direction). The forward run
//! ([`crate::forward`]) simulates the striker against the car's segments;
//! cell k's simulated force at each of its samples is the sum of the
//! segments' forces ([`crate::PlanarResult::segment_force`], along the
//! face's normal) whose contact point lies in its band,
//!
//! `F_k(t) = Σ_{j : |t̂·p_j(t) − t̂·a_k| ≤ w_k/2} F_j(t)`, `t̂ = (−n_y, n_x)`,
//!
//! a segment outside every band counted in the nearest cell (the wall ends
//! where its cells do). **Assigned per sample**, not once at first touch:
//! the car's travel into a 10° wall moves a point along the face by
//! `sin 10° ≈ 0.17` of it (17 mm per 100 mm of crush), as much as the
//! difference between a beam acting 1.6 and 1.65 m wide, which the outer
//! cells are to show. `p_j(t)` is segment j's point on the bumper line in
//! the world, `X + ξ_j e + η_j n_b`, `ξ_j = x_f + α_j u_L + (1 − α_j) u_R`
//! (the beam's lever rule on the side members' tips, `α_j = (η_j + b)/2b`),
//! as the contact has it ([`crate::simulate()`]); the forward run starts at
//! first touch, the case's time zero lies `shift` before it
//! ([`crate::forward::Forward::shift`]), in which time the car travelled
//! `v₀ · shift` along x untouched, so `p_j` in the case's frame is the
//! run's plus `(v₀ · shift, 0)`. The simulated histories are then aligned
//! on the test's samples with the run's shift, as the total force is, and
//! filtered at the case's CFC as its channels were
//! ([`crate::forward`]'s conditioning).

use crate::PlanarResult;
use crate::car::{PlanarCar, PlanarError};
use crate::identify::PlanarCase;

/// One wall cell's force in a forward run, at the case's samples.
#[derive(Debug, Clone, PartialEq)]
pub struct CellForce {
    /// The cell's load (index into the case's `drive.loads`).
    pub load: usize,
    /// Simulated, aligned and filtered as the run's total force is, N.
    pub simulated: Vec<f64>,
    /// Measured (the cell's conditioned channel), N.
    pub measured: Vec<f64>,
    /// Fit % of the simulation against the measurement over the case's window.
    pub fit_percent: f64,
}

/// One cell's band on the face: its load, its centre and half-width along
/// the face, m (case frame).
struct Band {
    load: usize,
    centre: f64,
    half: f64,
}

/// The cells of `case`'s wall (loads with `cell` and `anchor`) and the
/// face's tangent; None when it has none.
fn bands(case: &PlanarCase) -> Option<(Vec<Band>, [f64; 2])> {
    let mut tangent = None;
    let bands: Vec<Band> = (case.drive.loads.iter().enumerate())
        .filter_map(|(k, load)| {
            let (width, anchor) = (load.cell?, load.anchor?);
            let d = load.direction;
            let norm = d[0].hypot(d[1]);
            let t = [-d[1] / norm, d[0] / norm];
            tangent.get_or_insert(t);
            Some(Band {
                load: k,
                centre: t[0] * anchor[0] + t[1] * anchor[1],
                half: 0.5 * width,
            })
        })
        .collect();
    Some((bands, tangent?))
}

/// The cell of `bands` holding face coordinate `s`, else the nearest.
fn holding(bands: &[Band], s: f64) -> usize {
    let outside = |b: &Band| ((s - b.centre).abs() - b.half).max(0.0);
    (0..bands.len())
        .min_by(|&i, &j| outside(&bands[i]).total_cmp(&outside(&bands[j])))
        .unwrap_or(0)
}

/// Each cell's simulated force at the run's samples (see the module).
fn simulated(
    car: &PlanarCar,
    run: &PlanarResult,
    (bands, t): (&[Band], [f64; 2]),
    travel: f64,
) -> Vec<Vec<f64>> {
    let x_f = car.body().cg_behind_bumper;
    let b = 0.5 * car.beam().side_member_spacing;
    let right = car.left().masses.len();
    let tip = |i: usize, k: usize| {
        run.chain_displacement
            .get(i)
            .and_then(|u| u.get(k))
            .copied()
            .unwrap_or(0.0)
    };
    let mut cells = vec![vec![0.0; run.time.len()]; bands.len()];
    for k in 0..run.time.len() {
        let (sn, cs) = run.yaw[k].sin_cos();
        let (left_tip, right_tip) = (tip(0, k), tip(right, k));
        for (force, &eta) in run.segment_force.iter().zip(&run.segment_centres) {
            if force[k] == 0.0 {
                continue;
            }
            let alpha = (eta + b) / (2.0 * b);
            let xi = x_f + alpha * left_tip + (1.0 - alpha) * right_tip;
            let p = [
                run.x[k] + travel + xi * cs - eta * sn,
                run.y[k] + xi * sn + eta * cs,
            ];
            cells[holding(bands, t[0] * p[0] + t[1] * p[1])][k] += force[k];
        }
    }
    cells
}

/// Each cell's load index and simulated force at the case's samples, in
/// `car`'s forward run `run`, whose time zero lies `shift` (s) after the
/// case's (see the module), filtered as the case's channels were; empty
/// when the case's wall has no cells, an error when its CFC cannot filter
/// at its sample interval. The residuals' path: nothing of the measurement
/// is copied.
pub(crate) fn simulated_cells(
    car: &PlanarCar,
    case: &PlanarCase,
    run: &PlanarResult,
    shift: f64,
) -> Result<Vec<(usize, Vec<f64>)>, PlanarError> {
    let Some((bands, tangent)) = bands(case) else {
        return Ok(Vec::new());
    };
    let step = case.drive.step;
    let lead = crate::forward::lead(step);
    let histories = simulated(car, run, (&bands, tangent), case.drive.speed * shift);
    let at = |load: usize, history: &[f64]| -> Result<Vec<f64>, PlanarError> {
        // as the forward run's channels: filtered as the cells' measurement was
        let conditioned = crate::forward::as_measured(case, history, step, lead)?;
        Ok((0..case.drive.loads[load].force.len())
            .map(|k| crate::forward::sample(&conditioned, k as f64 - shift / step + lead as f64))
            .collect())
    };
    (bands.iter().zip(histories))
        .map(|(band, history)| Ok((band.load, at(band.load, &history)?)))
        .collect()
}

/// [`simulated_cells`] with each cell's measurement and fit % over the
/// case's window.
fn of_run(
    car: &PlanarCar,
    case: &PlanarCase,
    run: &PlanarResult,
    shift: f64,
) -> Result<Vec<CellForce>, PlanarError> {
    let (a, b) = case.window;
    Ok(simulated_cells(car, case, run, shift)?
        .into_iter()
        .map(|(load, simulated)| {
            let measured = case.drive.loads[load].force.clone();
            CellForce {
                load,
                fit_percent: bumpsim_estimate::fit::percent(&simulated[a..=b], &measured[a..=b]),
                simulated,
                measured,
            }
        })
        .collect())
}

/// The forward run of `case` on `car` compared cell by cell (see the
/// module): one per wall cell, empty when the case has none; an error as
/// [`crate::forward::forward()`]'s.
pub fn cell_forces(car: &PlanarCar, case: &PlanarCase) -> Result<Vec<CellForce>, PlanarError> {
    let (ahead, run) = crate::forward::run(car, case)?;
    of_run(car, case, &run, ahead.shift)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Layout;
    use crate::drive::{Drive, Load, Sensor};
    use crate::striker::{Face, Side, Striker};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    /// A symmetric car (ten segments) driven at 4 m/s into a flat rigid
    /// wall whose two cells, `width` wide, are centred at `±centre`.
    fn flat_wall(centre: f64, width: f64) -> (PlanarCar, PlanarCase) {
        let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let flat = Face::Plane {
            angle: 0.0,
            overlap: 1.0,
            side: Side::Left,
        };
        let x_f = car.body().cg_behind_bumper;
        let n = 1200;
        let cell = |y: f64| Load {
            lateral: 0.0,
            anchor: Some([x_f, y]),
            cell: Some(width),
            direction: [-1.0, 0.0],
            force: vec![0.0; n],
        };
        let drive = Drive {
            step: 1e-4,
            loads: vec![cell(centre), cell(-centre)],
            speed: 4.0,
            arm: 1.0,
            sensors: vec![Sensor::Body([0.6, 0.7]), Sensor::Body([0.6, -0.7])],
        };
        let case = PlanarCase {
            striker: Some(Striker::barrier(flat, 4.0)),
            ..PlanarCase::replayed("flat", drive, vec![vec![0.0; n]; 2])
        };
        (car, case)
    }

    /// The cells' forces, the total force and its peak (N) of the forward
    /// run of `(car, case)`.
    fn struck((car, case): (PlanarCar, PlanarCase)) -> (Vec<CellForce>, Vec<f64>, f64) {
        let cells = cell_forces(&car, &case).unwrap();
        let ahead = crate::forward::forward(&car, &case).unwrap();
        let total = ahead.channels[0].simulated.clone();
        let peak = total.iter().fold(0.0f64, |m, v| m.max(*v));
        (cells, total, peak)
    }

    /// Mirror symmetry: a symmetric car square on a flat wall loads the
    /// left and right halves alike, and the two halves together carry the
    /// striker's whole force, sample by sample.
    #[test]
    fn a_flat_wall_splits_a_symmetric_car_s_force_in_halves() {
        let (cells, total, peak) = struck(flat_wall(0.5, 1.0));
        assert!(peak > 10e3, "the wall is struck: {peak} N");
        for (k, t) in total.iter().enumerate() {
            let (left, right) = (cells[0].simulated[k], cells[1].simulated[k]);
            assert!(
                (left - right).abs() <= 1e-9 * peak,
                "sample {k}: {left} against {right} N"
            );
            assert!((left + right - t).abs() <= 1e-9 * peak, "sample {k}");
        }
    }

    /// Cells narrower than the car: a segment beyond every band counts in
    /// the nearest cell, so the cells still carry the whole force.
    #[test]
    fn a_segment_beyond_every_band_counts_in_the_nearest_cell() {
        let (cells, total, peak) = struck(flat_wall(0.15, 0.3));
        for (k, t) in total.iter().enumerate() {
            let sum = cells[0].simulated[k] + cells[1].simulated[k];
            assert!(
                (sum - t).abs() <= 1e-9 * peak,
                "sample {k}: {sum} against {t} N"
            );
        }
        let bands = [
            Band {
                load: 0,
                centre: 0.15,
                half: 0.15,
            },
            Band {
                load: 1,
                centre: -0.15,
                half: 0.15,
            },
        ];
        assert_eq!(holding(&bands, 0.7), 0);
        assert_eq!(holding(&bands, -0.7), 1);
        assert_eq!(holding(&bands, -0.1), 1);
    }

    /// A case without wall cells has none to compare.
    #[test]
    fn a_case_without_cells_has_none() {
        let (car, mut case) = flat_wall(0.5, 1.0);
        for load in &mut case.drive.loads {
            load.cell = None;
        }
        assert!(cell_forces(&car, &case).unwrap().is_empty());
    }
}
