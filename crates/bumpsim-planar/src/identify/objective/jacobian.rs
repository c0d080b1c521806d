//! The exact Jacobian of the planar objective: each case replayed on dual
//! numbers ([`crate::sensitivity`]), [`WIDTH`] parameters at a time, so a
//! column is `w_s ∂y_s(t_k)/∂p_j` of the discrete replay itself (no
//! difference step, no cancellation). A car parameter is searched as
//! `p = ln θ`, so its direction is seeded with `∂θ/∂p = θ`; a line of
//! action is searched as it is (seed 1). A side member's nonlinear link
//! ([`super::super::links`]) is replayed with its law's parameters on dual
//! numbers ([`bumpsim_core::link::Link::with_parameters`]): its initial
//! slope `springs[i]` seeds every parameter that scales with it (the
//! stiffness, an unloading slope, a table's forces), its `cubic`,
//! `yield_force` or `hardening` the law's own. The parameters are recognised by
//! their names ([`Unknowns::names`]); a problem with any other unknown
//! keeps the forward differences.

use super::super::{PlanarCase, Unknowns};
use crate::car::PlanarCar;
use crate::sensitivity::{Parameters, sensor_readings};
use bumpsim_core::dual::{Dual, Real};
use bumpsim_core::link::Link;
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
    /// Parameter `index` (in [`bumpsim_core::link::Link::parameters`]'s
    /// order) of chain link `link`'s nonlinear law.
    Law {
        link: usize,
        index: usize,
    },
    Grip,
    Cornering,
    Relaxation,
    /// The bumper's effective width.
    Width,
    /// Case `case`'s wall cells' arm.
    Arm {
        case: usize,
    },
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
            "tyres.relaxation_length" => Some(Slot::Relaxation),
            super::super::EFFECTIVE_WIDTH => Some(Slot::Width),
            arm if arm.starts_with("case '") && arm.ends_with(super::super::unknowns::ARM) => {
                let case = cases.iter().position(|c| {
                    arm == format!("case '{}'{}", c.name, super::super::unknowns::ARM)
                })?;
                Some(Slot::Arm { case })
            }
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
                    "cubic" | "yield_force" => Some(Slot::Law { link: i, index: 1 }),
                    "hardening" => Some(Slot::Law { link: i, index: 2 }),
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
    let laws: Vec<Option<&Link>> = [car.left(), car.right()]
        .iter()
        .flat_map(|c| (0..c.masses.len()).map(move |i| c.links.get(i)))
        .collect();
    let mut values: Vec<Option<Vec<Tangent>>> = laws
        .iter()
        .map(|l| l.map(|l| l.parameters().into_iter().map(Tangent::constant).collect()))
        .collect();
    let tyres = template.tyres();
    let follows = [
        tyres.front.mu_longitudinal == tyres.front.mu_lateral,
        tyres.rear.mu_longitudinal == tyres.rear.mu_lateral,
    ];
    for (j, (&slot, &value)) in slots.iter().zip(theta).enumerate() {
        let mine = j / WIDTH == chunk;
        let x = match mine {
            true => {
                let rate = match slot {
                    Slot::Line { .. } => 1.0,
                    _ => value,
                };
                Tangent::seeded(value, j % WIDTH, rate)
            }
            false => Tangent::constant(value),
        };
        // a log parameter's proportional component v of a law: ∂v/∂p = v
        let scaled = |v: f64| match mine {
            true => Tangent::seeded(v, j % WIDTH, v),
            false => Tangent::constant(v),
        };
        match slot {
            Slot::Spring(i) if laws[i].is_some() => {
                let (law, seeded) = (laws[i].expect("a law"), values[i].as_mut().expect("a law"));
                for (k, name) in law.parameter_names().iter().enumerate() {
                    if name == "stiffness" || name == "unloading" || name.starts_with("force[") {
                        seeded[k] = scaled(seeded[k].value());
                    }
                }
            }
            Slot::Law { link, index } => {
                if let Some(seeded) = values[link].as_mut() {
                    seeded[index] = x;
                }
            }
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
            Slot::Relaxation => p.relaxation = [x, x],
            Slot::Width => p.width = x,
            Slot::Line { case: c, load } if c == case.0 => p.lateral[load] = x,
            Slot::Line { .. } => {}
            Slot::Arm { case: c } if c == case.0 => p.arm = x,
            Slot::Arm { .. } => {}
        }
    }
    for (i, law) in laws.iter().enumerate() {
        if let (Some(law), Some(v)) = (law, &values[i]) {
            p.links[i] = Some(law.with_parameters(v));
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
            let window = &reading[case.window.0..=case.window.1];
            for (k, value) in window.iter().enumerate() {
                let row = starts[c] + k * sensors + s;
                for t in 0..columns {
                    jac[(row, chunk * WIDTH + t)] = weight * value.tangent[t];
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
    use crate::car::{Layout, SideChain};
    use crate::drive::{Drive, Load, Sensor, drive, segment_loads};
    use crate::simulate::{Settings, simulate};
    use crate::striker::{Face, Placed, Side, Striker, place};
    use bumpsim_core::model::MsdModel;
    use bumpsim_estimate::domain::Domain;
    use bumpsim_estimate::lm::LeastSquares;
    use bumpsim_impact::bumper::Bumper;

    fn car(mass: f64, spring: f64) -> PlanarCar {
        let chain = MsdModel::new(vec![12.0, mass], vec![3e3], vec![spring]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let c = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let mut tyres = *c.tyres();
        tyres.front = crate::car::Axle::rolling(0.015, 0.8);
        tyres.rear = tyres.front;
        let (left, right) = (c.left().clone(), c.right().clone());
        PlanarCar::new(*c.body(), left, right, c.beam().clone(), tyres).unwrap()
    }

    /// Three cases measured on a car 8 % heavier and 20 % stiffer than the
    /// start: a 10° wall and a 40 % offset wall replayed from their segment
    /// forces, the 10° wall's as two load cells (their arm estimated), and
    /// the offset's total force as one load whose line of action is
    /// estimated; two sill accelerometers and a yaw-rate sensor.
    fn cases(start: &PlanarCar) -> Vec<PlanarCase> {
        let truth = car(1350.0, 3e6);
        let faces = [
            Face::plane_in_degrees(10.0, 100.0, Side::Left),
            Face::plane_in_degrees(0.0, 40.0, Side::Right),
        ];
        let settings = Settings {
            output_step: 2e-4,
            ..Settings::default()
        };
        let mut out = Vec::new();
        for (i, face) in faces.into_iter().enumerate() {
            let striker = Striker::barrier(face, 15.0 / 3.6);
            let r = simulate(start, &striker, &settings).unwrap();
            let Placed::Plane { normal, offset, .. } = place(start, &striker).unwrap() else {
                unreachable!("a plane face")
            };
            let loads = segment_loads(&r, normal);
            // the wall's two halves as load cells on its face (centred on
            // the bumper's halves), their lines of action the segments'
            let tangent = [-normal[1], normal[0]];
            let half = |side: f64| {
                let centre = tangent[0] * start.body().cg_behind_bumper + tangent[1] * 0.4 * side;
                Load {
                    lateral: 0.0,
                    anchor: Some([
                        offset * normal[0] + centre * tangent[0],
                        offset * normal[1] + centre * tangent[1],
                    ]),
                    cell: Some(0.8),
                    direction: normal,
                    force: (0..loads[0].force.len())
                        .map(|k| {
                            (loads.iter())
                                .filter(|l| l.lateral * side > 0.0)
                                .map(|l| l.force[k])
                                .sum()
                        })
                        .collect(),
                }
            };
            let cells = vec![half(1.0), half(-1.0)];
            let total: Vec<f64> = (0..loads[0].force.len())
                .map(|k| loads.iter().map(|l| l.force[k]).sum())
                .collect();
            let single = Load {
                lateral: -0.2,
                anchor: None,
                cell: None,
                direction: normal,
                force: total,
            };
            let variants = match i {
                0 => vec![(loads, vec![]), (cells, vec![])],
                _ => vec![(loads, vec![]), (vec![single], vec![0])],
            };
            for (loads, estimated) in variants {
                let drive_input = Drive {
                    step: 2e-4,
                    loads,
                    speed: 15.0 / 3.6,
                    arm: 1.0,
                    sensors: vec![
                        Sensor::Body([0.6, 0.7]),
                        Sensor::Body([0.6, -0.7]),
                        Sensor::YawRate,
                    ],
                };
                let measured = drive(&truth, &drive_input, 0.25).unwrap().sensor_reading;
                let n = measured[0].len();
                let name = format!("case {}", out.len());
                out.push(PlanarCase {
                    window: (5, n - 1),
                    estimated,
                    weights: vec![1.0, 1.0, 0.05],
                    ..PlanarCase::replayed(&name, drive_input, measured)
                });
            }
        }
        out
    }

    /// The dual-number Jacobian against central differences of the
    /// residuals (step 1e-5 in `p`, 1e-6 for a column that misses there:
    /// truncation ~1e-10 of a column, rounding ~1e-11 of the residuals over
    /// the step) at a point off the start, with
    /// grip, cornering stiffness and a line of action and a wall's cells' arm
    /// estimated (13 unknowns: two passes of eight; then the bumper's
    /// effective width too, 14: its column's gap 1.0e-10 of 3.3e-2), rolling tyres with relaxation (grip
    /// 0.8): every column within 1e-4 of its largest entry (1.0e-5 seen at
    /// most, the body mass's column, whose differences cross the tyres'
    /// saturation kinks; μ's column crosses one at 1e-5, 1.4e-4, and
    /// matches at 1e-6, 9e-9).
    #[test]
    fn the_exact_jacobian_matches_central_differences() {
        let start = car(1250.0, 2.5e6);
        let cases = cases(&start);
        matches_central_differences(&start, &cases, 1e-4, Domain::Displacement);
        let unknowns = Unknowns::new(&start, true, true, &cases)
            .with_relaxation(true)
            .with_width(true);
        columns_match(&unknowns, &cases, 1e-4, Domain::Displacement);
    }

    /// The same in the velocity domain (the objective's differences of the
    /// columns, `super::compared`): a linear map, so the exact columns
    /// still match (2.2e-5 of the column seen at most, the body mass's,
    /// whose differences cross the tyres' saturation kinks; the others
    /// 9e-6 and below, the dampers' small columns). In acceleration the
    /// central differences' own rounding over h² (2e-4 absolute) is the
    /// gap, so it is not compared.
    #[test]
    fn the_exact_jacobian_matches_central_differences_in_velocity() {
        let start = car(1250.0, 2.5e6);
        let cases = cases(&start);
        matches_central_differences(&start, &cases, 1e-4, Domain::Velocity);
    }

    /// The same with nonlinear side members (issue 46): the left link
    /// progressive (its cubic term), the right one yielding (its yield
    /// force and hardening), each link's initial slope seeding its
    /// stiffness and unloading slope; the right link yields within the
    /// cases' crush. Every column within 1e-4 of its largest entry (8e-6
    /// seen at most, a damper; the history's kink is crossed at the same step).
    #[test]
    fn the_exact_jacobian_covers_nonlinear_links() {
        use super::super::super::{LinkLaw, LinkLaws};
        let linear = car(1250.0, 2.5e6);
        let cases = cases(&linear);
        let laws = LinkLaws {
            left: vec![LinkLaw::Progressive],
            right: vec![LinkLaw::Yielding],
        };
        let applied = laws.apply(&linear).unwrap();
        // the right link yields within the cases' crush (5 mm), unloading at 2k
        use bumpsim_core::link::{Curve, Link as Law, Unloading};
        let right = applied.right();
        let k = right.springs[0];
        let law = Law::new(
            Curve::bilinear(k, 5e-3 * k, 0.2).unwrap(),
            Unloading::Slope(2.0 * k),
        );
        let right = SideChain::linked(
            right.masses.clone(),
            right.dampers.clone(),
            vec![law.unwrap()],
        );
        let start =
            super::super::super::links::rebuilt(&applied, applied.left().clone(), right).unwrap();
        matches_central_differences(&start, &cases, 1e-4, Domain::Displacement);
    }

    /// The same with Magic-Formula tyres (shape factor 1.3: no clamp on
    /// the patch, the force rounded at its peak): every column within 1e-4
    /// of its largest entry.
    #[test]
    fn the_exact_jacobian_covers_the_magic_formula() {
        let linear = car(1250.0, 2.5e6);
        let mut tyres = *linear.tyres();
        tyres.front.shape = Some(1.3);
        tyres.rear.shape = Some(1.3);
        let (left, right) = (linear.left().clone(), linear.right().clone());
        let start =
            PlanarCar::new(*linear.body(), left, right, linear.beam().clone(), tyres).unwrap();
        let cases = cases(&start);
        matches_central_differences(&start, &cases, 1e-4, Domain::Displacement);
    }

    fn matches_central_differences(
        start: &PlanarCar,
        cases: &[PlanarCase],
        tolerance: f64,
        domain: Domain,
    ) {
        let unknowns = Unknowns::new(start, true, true, cases).with_relaxation(true);
        columns_match(&unknowns, cases, tolerance, domain);
    }

    fn columns_match(unknowns: &Unknowns, cases: &[PlanarCase], tolerance: f64, domain: Domain) {
        let objective =
            Objective::new(cases, unknowns, (domain, super::super::Bias::Pretrigger)).unwrap();
        assert!(objective.slots.is_some(), "every unknown has a slot");
        let names = unknowns.names();
        assert!(
            names.iter().any(|(n, _)| n == "tyres.relaxation_length"),
            "the rolling tyres' relaxation length is differentiated too: {names:?}"
        );
        let mut p = unknowns.search(&unknowns.start());
        p.iter_mut()
            .enumerate()
            .for_each(|(j, x)| *x += 0.2 * (j as f64).sin());
        let (m, n) = (objective.residual_count(), objective.parameter_count());
        assert!(n > WIDTH, "more unknowns than one pass");
        let (mut r, mut jac) = (vec![0.0; m], DMatrix::zeros(m, n));
        assert!(objective.evaluate(&p, &mut r, Some(&mut jac)));
        // each column against central differences at 1e-5, which rounds
        // least, and where that misses at 1e-6, ten times less likely to
        // straddle one of the tyres' saturation kinks (μ's column at 1e-5:
        // 1.4e-4 with the exact relaxation update; 4e-7 at 1e-6)
        let column = |j: usize, h: f64| {
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
            (gap, scale)
        };
        for j in 0..n {
            let (gap, scale) = match column(j, 1e-5) {
                (gap, scale) if gap <= tolerance * scale => (gap, scale),
                _ => column(j, 1e-6),
            };
            let name = &unknowns.names()[j].0;
            eprintln!("column {j} ({name}): gap {gap:.1e} of {scale:.1e}");
            assert!(scale > 0.0, "column {j} ({name}) moves the residuals");
            assert!(
                gap <= tolerance * scale,
                "column {j} ({name}): gap {gap:e} of {scale:e}"
            );
        }
    }
}
