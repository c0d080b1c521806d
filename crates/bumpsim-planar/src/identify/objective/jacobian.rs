//! The exact Jacobian of the planar objective: each case replayed on dual
//! numbers ([`crate::sensitivity`]), [`WIDTH`] parameters at a time, so a
//! column is `w_s ∂y_s(t_k)/∂p_j` of the discrete replay itself (no
//! difference step, no cancellation). A car parameter is searched as
//! `p = ln θ`, so its direction is seeded with `∂θ/∂p = θ`; a line of
//! action is searched as it is (seed 1). The parameters are recognised by
//! their names ([`Unknowns::names`]); a problem with any other unknown
//! keeps the forward differences.

use super::super::{PlanarCase, Unknowns};
use crate::car::PlanarCar;
use crate::sensitivity::{Parameters, sensor_readings};
use bumpsim_core::dual::{Dual, Real};
use nalgebra::DMatrix;
use rayon::prelude::*;

/// Parameters differentiated in one replay.
pub(crate) const WIDTH: usize = 8;

type Tangent = Dual<WIDTH>;

/// What a search variable is in the replay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Slot {
    BodyMass,
    YawInertia,
    /// Chain mass, damper or spring of link `i` (left chain first).
    Mass(usize),
    Damper(usize),
    Spring(usize),
    Grip,
    Cornering,
    /// Load `load` of case `case`'s lateral position.
    Line {
        case: usize,
        load: usize,
    },
}

/// Each search variable's slot, or `None` when one is not a replay
/// quantity this module knows.
pub(crate) fn slots(unknowns: &Unknowns, cases: &[PlanarCase]) -> Option<Vec<Slot>> {
    let t = unknowns.template();
    let (left, right) = (t.left().masses.len(), t.right().masses.len());
    let mut lines = cases
        .iter()
        .enumerate()
        .flat_map(|(c, case)| case.estimated.iter().map(move |&k| (c, k)));
    let link = |side: &str, index: &str| -> Option<usize> {
        let i: usize = index.strip_suffix(']')?.parse().ok()?;
        match side {
            "left" => (i < left).then_some(i),
            "right" => (i < right).then_some(left + i),
            _ => None,
        }
    };
    let out = unknowns
        .names()
        .iter()
        .map(|(name, _)| match name.as_str() {
            "body.mass" => Some(Slot::BodyMass),
            "body.yaw_inertia" => Some(Slot::YawInertia),
            "tyres.mu_lateral" => Some(Slot::Grip),
            "tyres.cornering_stiffness" => Some(Slot::Cornering),
            line if line.starts_with("case '") && line.ends_with("].lateral") => {
                lines.next().map(|(case, load)| Slot::Line { case, load })
            }
            other => {
                let (side, rest) = other.split_once('.')?;
                let (what, index) = rest.split_once('[')?;
                let i = link(side, index)?;
                match what {
                    "masses" => Some(Slot::Mass(i)),
                    "dampers" => Some(Slot::Damper(i)),
                    "springs" => Some(Slot::Spring(i)),
                    _ => None,
                }
            }
        })
        .collect::<Option<Vec<Slot>>>()?;
    lines.next().is_none().then_some(out)
}

/// The replay's quantities of `car` and case `index`, with the slots of
/// chunk `chunk` seeded at `theta`.
fn seeded(
    car: &PlanarCar,
    template: &PlanarCar,
    case: (usize, &PlanarCase),
    slots: &[Slot],
    theta: &[f64],
    chunk: usize,
) -> Parameters<Tangent> {
    let mut p = Parameters::<Tangent>::of(car, &case.1.drive);
    let tyres = template.tyres();
    let follows = [
        tyres.front.mu_longitudinal == tyres.front.mu_lateral,
        tyres.rear.mu_longitudinal == tyres.rear.mu_lateral,
    ];
    for (j, (&slot, &value)) in slots.iter().zip(theta).enumerate() {
        let x = match j / WIDTH == chunk {
            true => {
                let rate = match slot {
                    Slot::Line { .. } => 1.0,
                    _ => value,
                };
                Tangent::seeded(value, j % WIDTH, rate)
            }
            false => Tangent::constant(value),
        };
        match slot {
            Slot::BodyMass => p.body_mass = x,
            Slot::YawInertia => p.yaw_inertia = x,
            Slot::Mass(i) => p.masses[i] = x,
            Slot::Damper(i) => p.dampers[i] = x,
            Slot::Spring(i) => p.springs[i] = x,
            Slot::Grip => {
                p.mu_lateral = x;
                for (mu, follow) in p.mu_longitudinal.iter_mut().zip(follows) {
                    if follow {
                        *mu = x;
                    }
                }
            }
            Slot::Cornering => p.cornering = [x, x],
            Slot::Line { case: c, load } if c == case.0 => p.lateral[load] = x,
            Slot::Line { .. } => {}
        }
    }
    p
}

/// Writes the weighted residuals' Jacobian at `theta` into `jac` (rows as
/// the objective's residuals: per case, per sample of its window, per
/// sensor). False when a replay fails.
pub(crate) fn jacobian(
    unknowns: &Unknowns,
    cases: &[PlanarCase],
    substeps: &[usize],
    slots: &[Slot],
    theta: &[f64],
    jac: &mut DMatrix<f64>,
) -> bool {
    let Ok(car) = unknowns.car(theta) else {
        return false;
    };
    let template = unknowns.template();
    let chunks = slots.len().div_ceil(WIDTH);
    let jobs: Vec<(usize, usize)> = (0..chunks)
        .flat_map(|chunk| (0..cases.len()).map(move |c| (chunk, c)))
        .collect();
    let replays: Vec<Option<Vec<Vec<Tangent>>>> = jobs
        .par_iter()
        .map(|&(chunk, c)| {
            let case = &cases[c];
            let p = seeded(&car, template, (c, case), slots, theta, chunk);
            sensor_readings(&car, &p, &case.drive, substeps[c], case.window.1 + 1).ok()
        })
        .collect();
    let mut starts = Vec::with_capacity(cases.len());
    let mut at = 0;
    for case in cases {
        starts.push(at);
        at += case.measured.len() * (case.window.1 - case.window.0 + 1);
    }
    for (&(chunk, c), replay) in jobs.iter().zip(replays) {
        let Some(replay) = replay else {
            return false;
        };
        let case = &cases[c];
        let sensors = case.measured.len();
        let columns = (slots.len() - chunk * WIDTH).min(WIDTH);
        for (s, reading) in replay.iter().enumerate().take(sensors) {
            let weight = case.weight(s);
            for k in case.window.0..=case.window.1 {
                let row = starts[c] + (k - case.window.0) * sensors + s;
                for t in 0..columns {
                    jac[(row, chunk * WIDTH + t)] = weight * reading[k].tangent[t];
                }
            }
        }
    }
    jac.iter().all(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::super::Objective;
    use super::*;
    use crate::cases::TestChannels;
    use crate::series::make_series;
    use bumpsim_estimate::lm::LeastSquares;
    use std::path::Path;

    /// The bundled series' training cases and its start car.
    fn bundled() -> (Vec<PlanarCase>, PlanarCar) {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/planar/identify");
        let series = make_series(&root.join("series.toml")).unwrap();
        let cases = series
            .tests
            .iter()
            .filter(|t| t.name != "OFFSET-RIGHT")
            .map(|t| TestChannels::of(t).case().unwrap().0)
            .collect();
        let start = PlanarCar::parse(&series.start, Path::new("start.toml")).unwrap();
        (cases, start)
    }

    /// The dual-number Jacobian against central differences of the
    /// residuals (step 1e-5 in `p`: truncation ~1e-10 of a column, rounding
    /// ~1e-11 of the residuals over the step) at a point off the start, with
    /// grip and cornering stiffness estimated: every column within 1e-5 of
    /// its largest entry (the replay's clamps and tyre kinks, crossed by a
    /// difference but not by the derivative, are the gap).
    #[test]
    fn the_exact_jacobian_matches_central_differences() {
        let (cases, start) = bundled();
        let unknowns = Unknowns::new(&start, true, true, &cases);
        let objective = Objective::new(&cases, &unknowns).unwrap();
        assert!(objective.slots.is_some(), "every unknown has a slot");
        let mut p = unknowns.search(&unknowns.start());
        p.iter_mut()
            .enumerate()
            .for_each(|(j, x)| *x += 0.2 * (j as f64).sin());
        let (m, n) = (objective.residual_count(), objective.parameter_count());
        let (mut r, mut jac) = (vec![0.0; m], DMatrix::zeros(m, n));
        assert!(objective.evaluate(&p, &mut r, Some(&mut jac)));
        let h = 1e-5;
        for j in 0..n {
            let (mut up, mut down) = (p.clone(), p.clone());
            up[j] += h;
            down[j] -= h;
            let (mut ru, mut rd) = (vec![0.0; m], vec![0.0; m]);
            assert!(objective.residuals(&up, &mut ru) && objective.residuals(&down, &mut rd));
            let difference: Vec<f64> = ru
                .iter()
                .zip(&rd)
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect();
            let scale = difference.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            let gap = (0..m).fold(0.0f64, |s, i| s.max((jac[(i, j)] - difference[i]).abs()));
            assert!(scale > 0.0, "column {j} is not zero");
            assert!(
                gap <= 1e-5 * scale,
                "column {j} ({:?}): gap {gap:e} of {scale:e}",
                unknowns.names()[j].0
            );
        }
    }
}
