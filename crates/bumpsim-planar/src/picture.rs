//! The top view of an impact at one instant (spec §9 outputs): the car's
//! outline, wheels, side members and crushed bumper line, and the striker's
//! face, in the world frame (x forward, y left, m), for the report's picture
//! at peak force.
//!
//! The body is drawn as a rectangle as wide as the bumper, from just behind
//! the bumper line to 0.8 m behind the rear axle (the model has no body
//! length: the outline is for orientation only). The bumper line at
//! segment j sits at `ξ = x_f + u(η_j) − d_j` (the beam line carried by
//! the front chain masses, minus the segment's crush); the side members'
//! tips, on the front chain masses, are drawn behind the bumper system
//! (as deep as the run's largest crush plus 50 mm: the model has no depth
//! for it); every body point moves with the CG displacement and yaw of
//! that sample.

use crate::car::{PlanarCar, PlanarError};
use crate::result::PlanarResult;
use crate::striker::{Placed, Striker, place};
use serde::Serialize;

/// The striker's face in a top view.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum FaceShape {
    /// The covered part of a plane, from one end to the other, m.
    Segment([f64; 2], [f64; 2]),
    /// A pole: centre and radius, m.
    Circle {
        /// Axis, m.
        centre: [f64; 2],
        /// Radius, m.
        radius: f64,
    },
}

/// A top view at one sample, world frame, m.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TopView {
    /// Time of the sample, s.
    pub time: f64,
    /// Body outline (closed polygon).
    pub body: Vec<[f64; 2]>,
    /// The four wheels (closed polygons).
    pub wheels: Vec<Vec<[f64; 2]>>,
    /// The side members: 0.6 m, their tips behind the bumper system.
    pub side_members: Vec<[[f64; 2]; 2]>,
    /// The crushed bumper line, right to left.
    pub bumper: Vec<[f64; 2]>,
    /// The face.
    pub face: FaceShape,
}

/// The sample of the largest striker force.
pub fn peak_sample(result: &PlanarResult) -> usize {
    (0..result.force.len())
        .max_by(|&a, &b| result.force[a].total_cmp(&result.force[b]))
        .unwrap_or(0)
}

/// The top view of `result` (of `car` hit by `striker`) at sample `k`.
pub fn top_view(
    car: &PlanarCar,
    striker: &Striker,
    result: &PlanarResult,
    k: usize,
) -> Result<TopView, PlanarError> {
    let sample = |h: &[f64]| h.get(k).copied().unwrap_or(0.0);
    let (x, y, yaw) = (sample(&result.x), sample(&result.y), sample(&result.yaw));
    let (sn, cs) = yaw.sin_cos();
    let world = |p: [f64; 2]| [x + p[0] * cs - p[1] * sn, y + p[0] * sn + p[1] * cs];
    let body = car.body();
    let (x_f, half) = (body.cg_behind_bumper, 0.5 * car.beam().width);
    let rear = body.cg_behind_front_axle - body.wheelbase - 0.8;
    let rectangle = |x0: f64, x1: f64, y0: f64, y1: f64| {
        [[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]
            .map(world)
            .to_vec()
    };
    let front = x_f - 0.15;
    let wheels = [
        body.cg_behind_front_axle,
        body.cg_behind_front_axle - body.wheelbase,
    ]
    .iter()
    .flat_map(|&xi| [1.0, -1.0].map(|side| (xi, side * 0.5 * body.track)))
    .map(|(xi, eta)| rectangle(xi - 0.32, xi + 0.32, eta - 0.1, eta + 0.1))
    .collect();
    let b = 0.5 * car.beam().side_member_spacing;
    let tips = fronts(car, result, k);
    // the bumper system lies ahead of the side members: drawn as deep as
    // the run's largest crush plus 50 mm (the model has no depth for it)
    let depth = result.max_compression + 0.05;
    let side_members = [(b, tips.0), (-b, tips.1)]
        .map(|(eta, u)| {
            [
                world([x_f + u - depth, eta]),
                world([x_f + u - depth - 0.6, eta]),
            ]
        })
        .to_vec();
    let bumper = bumper_line(car, result, k).into_iter().map(world).collect();
    let face = face(car, striker, sample(&result.pendulum_travel))?;
    Ok(TopView {
        time: sample(&result.time),
        body: rectangle(rear, front, -half, half),
        wheels,
        side_members,
        bumper,
        face,
    })
}

/// Displacements of the left and right front chain masses at sample `k`
/// (0 for a side without a chain), m.
fn fronts(car: &PlanarCar, result: &PlanarResult, k: usize) -> (f64, f64) {
    let left = car.left().masses.len();
    let front = |i: usize| {
        result
            .chain_displacement
            .get(i)
            .and_then(|h| h.get(k))
            .copied()
            .unwrap_or(0.0)
    };
    let right = match car.right().masses.is_empty() {
        true => 0.0,
        false => front(left),
    };
    (if left == 0 { 0.0 } else { front(0) }, right)
}

/// The crushed bumper line at sample `k`, body frame.
fn bumper_line(car: &PlanarCar, result: &PlanarResult, k: usize) -> Vec<[f64; 2]> {
    let x_f = car.body().cg_behind_bumper;
    let b = 0.5 * car.beam().side_member_spacing;
    let (u_left, u_right) = fronts(car, result, k);
    result
        .segment_centres
        .iter()
        .zip(&result.crush)
        .map(|(&eta, crush)| {
            let alpha = (eta + b) / (2.0 * b);
            let u = alpha * u_left + (1.0 - alpha) * u_right;
            [x_f + u - crush.get(k).copied().unwrap_or(0.0), eta]
        })
        .collect()
}

/// The face after the pendulum's `travel`, over the car's width plus 0.4 m.
fn face(car: &PlanarCar, striker: &Striker, travel: f64) -> Result<FaceShape, PlanarError> {
    let reach = 0.5 * car.beam().width + 0.4;
    Ok(match place(car, striker)?.moved(travel) {
        Placed::Pole { centre, radius } => FaceShape::Circle { centre, radius },
        // the curved barrier drawn as its chord (84 mm short of the RCAR apex)
        Placed::Barrier { arc, .. } => {
            let [a, b] = arc.ends();
            FaceShape::Segment(a, b)
        }
        Placed::Plane {
            normal,
            offset,
            edge,
            sign,
        } => {
            // the line n·p = offset, as x(y); |θ| ≤ 80° keeps n_x away from 0
            let at = |y: f64| [(offset - normal[1] * y) / normal[0], y];
            let (low, high) = match sign {
                s if s > 0.0 => (edge, edge.max(reach)),
                s if s < 0.0 => (edge.min(-reach), edge),
                _ => (-reach, reach),
            };
            FaceShape::Segment(at(low), at(high))
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Layout;
    use crate::simulate::{Settings, simulate};
    use crate::striker::{Face, Side};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn car() -> PlanarCar {
        let chain = MsdModel::new(vec![10.0, 1200.0], vec![2e3], vec![2e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap()
    }

    #[test]
    fn at_first_contact_the_face_touches_the_uncrushed_bumper_line() {
        let car = car();
        let striker = Striker::barrier(Face::flat(), 2.0);
        let r = simulate(&car, &striker, &Settings::default()).unwrap();
        let view = top_view(&car, &striker, &r, 0).unwrap();
        let x_f = car.body().cg_behind_bumper;
        assert!(view.bumper.iter().all(|p| (p[0] - x_f).abs() < 1e-12));
        let FaceShape::Segment(a, b) = view.face else {
            panic!("a plane is a segment")
        };
        assert!(
            (a[0] - x_f).abs() < 1e-12 && (b[0] - x_f).abs() < 1e-12,
            "{a:?} {b:?}"
        );
        assert!(
            a[1] < -0.8 && b[1] > 0.8,
            "across the whole bumper: {a:?} {b:?}"
        );
    }

    #[test]
    fn at_peak_force_an_offset_hit_is_crushed_on_its_side_and_the_car_turned() {
        let car = car();
        let face = Face::plane_in_degrees(10.0, 40.0, Side::Left);
        let striker = Striker::barrier(face, 15.0 / 3.6);
        let r = simulate(&car, &striker, &Settings::default()).unwrap();
        let k = peak_sample(&r);
        let view = top_view(&car, &striker, &r, k).unwrap();
        assert!((view.time - r.time[k]).abs() < 1e-12 && r.force[k] == r.peak_force);
        let (right, left) = (view.bumper[0], view.bumper[view.bumper.len() - 1]);
        assert!(
            left[0] < right[0] - 0.05,
            "the left end is pushed back: {left:?} {right:?}"
        );
        // the body turned by the yaw of that sample: its rear edge is not square to x
        let rear = (view.body[0], view.body[3]);
        let turned = (rear.1[0] - rear.0[0]).atan2(rear.1[1] - rear.0[1]);
        assert!((turned + r.yaw[k]).abs() < 1e-9, "{turned} vs {}", r.yaw[k]);
    }
}
