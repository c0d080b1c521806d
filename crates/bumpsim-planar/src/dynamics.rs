//! Equations of motion of the planar car (see the `simulate` module for the
//! derivation). Generalised coordinates `q = [X, Y, ψ, u_1..u_N, s]`: the
//! body's CG in the world, its yaw, the chain masses' displacements along the
//! body x axis relative to their rest position on the bumper line (left chain
//! first), and the pendulum's travel along −x (unused for a fixed striker).
//! Everything here works on preallocated buffers: nothing allocates per step,
//! and the yaw's sine and cosine are computed once per position (a step's
//! contact, tyre relaxation, accelerations and record share them).

use crate::car::{Block, GRAVITY, PlanarCar};
use crate::result::{BoxBottomed, BoxSide};
use crate::striker::{Placed, pole_contact_span, pole_profile};
use crate::tyre::Wheel;
use bumpsim_impact::bumper::{Bumper, BumperState};
use std::cell::Cell;

/// A chain link: `front` mass, `back` mass or the body, spring N/m (or a
/// nonlinear `law`, `crate::car::SideChain::links`), damper N·s/m, and for
/// a side's first link (its crash box) the block at the end of its stroke.
struct Link {
    front: usize,
    back: Option<usize>,
    spring: f64,
    law: Option<bumpsim_core::link::Link>,
    damper: f64,
    block: Option<Block>,
}

impl Link {
    /// The link's elongation `u_front − u_back`, m (negative: compressed).
    fn stretch(&self, q: &[f64]) -> f64 {
        q[3 + self.front] - self.back.map_or(0.0, |i| q[3 + i])
    }

    /// The block's force at elongation `x`, N (≥ 0, pushing the masses apart).
    fn blocking(&self, x: f64) -> f64 {
        self.block.map_or(0.0, |b| b.force(-x))
    }

    /// The block's elastic energy at elongation `x`, J.
    fn block_energy(&self, x: f64) -> f64 {
        self.block
            .map_or(0.0, |b| 0.5 * b.stiffness * (-x - b.depth).max(0.0).powi(2))
    }
}

/// The prepared model.
pub(crate) struct Model {
    pub body_mass: f64,
    pub yaw_inertia: f64,
    /// Chain masses, kg, and their lateral positions ±b, m.
    pub masses: Vec<f64>,
    pub eta: Vec<f64>,
    links: Vec<Link>,
    /// Index of the left and right front (bumper-carrying) chain masses.
    fronts: [Option<usize>; 2],
    pub b: f64,
    pub x_f: f64,
    pub segment_y: Vec<f64>,
    half_width: f64,
    pub bending: f64,
    wheels: Vec<Wheel>,
    slip: f64,
    pub face: Placed,
    pub pendulum: Option<f64>,
    /// The barrier's absorber strip in front of each segment, in series
    /// with it (empty: the face has none; `crate::barrier`).
    absorbers: Vec<Bumper>,
    /// Half the integration step, s (for the full-step velocity estimate).
    pub half_step: f64,
    /// The last yaw's bits, its sine and cosine ([`Model::trig`]).
    trig: Cell<(u64, f64, f64)>,
}

/// The contact state of the bumper segments.
pub(crate) struct Contact {
    pub states: Vec<BumperState>,
    /// Penetration along the push direction, m (negative: no contact).
    pub penetration: Vec<f64>,
    /// Crush `d = max(penetration, 0)`, m.
    pub crush: Vec<f64>,
    /// Crush force from the characteristic, N.
    pub force: Vec<f64>,
    /// Crush force plus bending share, N.
    pub total: Vec<f64>,
    /// Push direction on the car, body frame (its x part is −1 for a pole).
    pub direction: Vec<[f64; 2]>,
    /// Application point, body frame, m.
    pub point: Vec<[f64; 2]>,
    /// Under the face (within the overlap) at the last evaluation.
    covered: Vec<bool>,
    /// Whether the coverage changed at the last evaluation.
    pub switched: Vec<bool>,
    /// Came under the face already inside it: no load until it is out.
    blocked: Vec<bool>,
    /// Beam deflection for the bending energy, m (see `Model::deflect`).
    deflection: Vec<f64>,
    /// Deflection kept after a loaded segment left the face, m.
    rest: Vec<f64>,
    /// Pushed by the striker beyond its rest deflection.
    engaged: Vec<bool>,
    /// Lateral deflection of each wheel's contact patch (rolling tyres
    /// with relaxation), m: front left, front right, rear left, rear right.
    pub patches: [f64; 4],
    /// Crush of the barrier's absorber in front of each segment, m (0
    /// without one): the segment's own crush is `crush − absorber`.
    pub absorber: Vec<f64>,
    /// The absorbers' histories.
    absorbed: Vec<BumperState>,
    /// Per chain link: a nonlinear link's history and its force, N
    /// (compression positive; `Model::hold`).
    links: Vec<bumpsim_core::link::LinkState>,
    link_force: Vec<f64>,
    /// Per chain link: its largest compression so far, m.
    link_most: Vec<f64>,
}

/// Loads of one evaluation (world frame unless said otherwise).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Loads {
    /// Resultant striker force on the car, N.
    pub contact: [f64; 2],
    /// Its moment about the body's CG, N·m.
    pub contact_moment: f64,
    /// Compressive force at the left and right side-member tips, N.
    pub side: [f64; 2],
    /// Resultant tyre force, N, and its moment about the CG, N·m.
    pub tyre: [f64; 2],
    pub tyre_moment: f64,
}

/// The body axes e (x) and n (y) in the world.
#[derive(Clone, Copy)]
struct Axes {
    e: [f64; 2],
    n: [f64; 2],
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

impl Model {
    pub fn new(car: &PlanarCar, face: Placed, pendulum: Option<f64>) -> Model {
        let (mut masses, mut eta, mut links) = (vec![], vec![], vec![]);
        let b = 0.5 * car.beam().side_member_spacing;
        let mut fronts = [None, None];
        for (side, (chain, y)) in [(car.left(), b), (car.right(), -b)].into_iter().enumerate() {
            let first = masses.len();
            let n = chain.masses.len();
            fronts[side] = (n > 0).then_some(first);
            for i in 0..n {
                masses.push(chain.masses[i]);
                eta.push(y);
                let back = (i + 1 < n).then_some(first + i + 1);
                links.push(Link {
                    front: first + i,
                    back,
                    spring: chain.springs[i],
                    law: chain.links.get(i).cloned(),
                    damper: chain.dampers[i],
                    block: car.crash_boxes().filter(|_| i == 0),
                });
            }
        }
        let body = car.body();
        let (a, l) = (body.cg_behind_front_axle, body.wheelbase);
        let weight = car.total_mass() * GRAVITY;
        let tyres = car.tyres();
        let mut wheels = vec![];
        for (xi, load, axle) in [
            (a, weight * (l - a) / l, tyres.front),
            (a - l, weight * a / l, tyres.rear),
        ] {
            for eta in [0.5 * body.track, -0.5 * body.track] {
                wheels.push(Wheel {
                    xi,
                    eta,
                    load: 0.5 * load,
                    axle,
                });
            }
        }
        Model {
            body_mass: body.mass,
            yaw_inertia: body.yaw_inertia,
            masses,
            eta,
            links,
            fronts,
            b,
            x_f: body.cg_behind_bumper,
            segment_y: (0..car.beam().segments.len())
                .map(|j| car.segment_centre(j))
                .collect(),
            half_width: 0.5 * car.segment_width(),
            bending: car.beam().bending,
            wheels,
            slip: tyres.slip_speed,
            absorbers: state::absorbers(car, &face),
            face,
            pendulum,
            half_step: 0.0,
            trig: Cell::new((0f64.to_bits(), 0.0, 1.0)),
        }
    }

    /// The sine and cosine of the yaw ψ (rad), computed once per value: a
    /// step evaluates them at the same position three to six times.
    pub fn trig(&self, yaw: f64) -> (f64, f64) {
        let (bits, sn, cs) = self.trig.get();
        if bits == yaw.to_bits() {
            return (sn, cs);
        }
        let (sn, cs) = yaw.sin_cos();
        self.trig.set((yaw.to_bits(), sn, cs));
        (sn, cs)
    }

    /// The body axes at the yaw ψ (rad).
    fn axes(&self, yaw: f64) -> Axes {
        let (sn, cs) = self.trig(yaw);
        Axes {
            e: [cs, sn],
            n: [-sn, cs],
        }
    }

    /// Number of generalised coordinates.
    pub fn dof(&self) -> usize {
        4 + self.masses.len()
    }

    /// Index of the pendulum travel.
    pub fn travel(&self) -> usize {
        3 + self.masses.len()
    }

    /// Left share α of a force at lateral position η on the beam lever.
    fn share(&self, eta: f64) -> f64 {
        (eta + self.b) / (2.0 * self.b)
    }

    /// Slope of the beam line `du/dη` from the side-member tips' displacements.
    fn tilt(&self, q: &[f64]) -> f64 {
        let tip = |side: usize| self.fronts[side].map_or(0.0, |i| q[3 + i]);
        (tip(0) - tip(1)) / (2.0 * self.b)
    }

    /// The beam line's displacement along body x at η, m.
    fn beam(&self, q: &[f64], eta: f64) -> f64 {
        let tip = |side: usize| self.fronts[side].map_or(0.0, |i| q[3 + i]);
        let alpha = self.share(eta);
        alpha * tip(0) + (1.0 - alpha) * tip(1)
    }

    /// The point of the bumper line at lateral position η, body frame, m.
    pub fn bumper_point(&self, q: &[f64], eta: f64) -> [f64; 2] {
        [self.x_f + self.beam(q, eta), eta]
    }

    /// Penetration, push direction and point of segment `j`, body frame.
    fn segment(
        &self,
        q: &[f64],
        axes: Axes,
        face: &Placed,
        j: usize,
    ) -> (f64, bool, [f64; 2], [f64; 2]) {
        let Axes { e, n } = axes;
        let y = self.segment_y[j];
        match *face {
            Placed::Plane {
                normal,
                offset,
                edge,
                sign,
            } => {
                let xi = self.x_f + self.beam(q, y);
                let p = [q[0] + xi * e[0] + y * n[0], q[1] + xi * e[1] + y * n[1]];
                let direction = [
                    normal[0] * e[0] + normal[1] * e[1],
                    normal[0] * n[0] + normal[1] * n[1],
                ];
                let covered = sign * (p[1] - edge) >= 0.0;
                let depth = offset - (normal[0] * p[0] + normal[1] * p[1]);
                (depth, covered, direction, [xi, y])
            }
            Placed::Barrier { arc, .. } => {
                let xi = self.x_f + self.beam(q, y);
                let p = [q[0] + xi * e[0] + y * n[0], q[1] + xi * e[1] + y * n[1]];
                let (depth, covered, u) = arc.depth(p);
                let direction = [u[0] * e[0] + u[1] * e[1], u[0] * n[0] + u[1] * n[1]];
                (depth, covered, direction, [xi, y])
            }
            Placed::Pole { centre, radius } => {
                let r = [centre[0] - q[0], centre[1] - q[1]];
                let (xc, yc) = (r[0] * e[0] + r[1] * e[1], r[0] * n[0] + r[1] * n[1]);
                let span = pole_contact_span(radius, self.half_width);
                let eta = yc.clamp(y - span, y + span);
                let (reach, mut lateral) = pole_profile(radius, eta - yc);
                if span > 0.0 && eta == yc {
                    // the contact follows the axis along the tilted beam line
                    lateral += self.tilt(q);
                }
                if reach <= 0.0 {
                    return (-1.0, false, [-1.0, 0.0], [self.x_f, y]);
                }
                let depth = self.x_f + self.beam(q, eta) - (xc - reach);
                // on the line of action through the axis, at the strip's lateral position
                let along = match lateral == 0.0 {
                    true => reach,
                    false => (eta - yc) / lateral,
                };
                (depth, true, [-1.0, lateral], [xc - along, eta])
            }
        }
    }

    /// Updates the segments' penetration, crush and forces for positions `q`.
    pub fn contact(&self, q: &[f64], car: &PlanarCar, c: &mut Contact) {
        let face = match self.pendulum {
            Some(_) => self.face.moved(q[self.travel()]),
            None => self.face,
        };
        let axes = self.axes(q[2]);
        let block = car.beam().block;
        for (j, segment) in car.beam().segments.iter().enumerate() {
            let (depth, covered, direction, point) = self.segment(q, axes, &face, j);
            let depth = self.admit(c, j, depth, covered);
            c.penetration[j] = depth;
            c.crush[j] = depth.max(0.0);
            c.direction[j] = direction;
            c.point[j] = point;
            // the characteristic, and beyond the depth the block (elastic)
            let own = |d: f64, state: &mut BumperState| {
                segment.force(d, state) + block.map_or(0.0, |b| b.force(d))
            };
            (c.force[j], c.absorber[j]) = match (depth > 0.0, self.absorbers.get(j)) {
                (true, None) => (own(depth, &mut c.states[j]), 0.0),
                (true, Some(strip)) => crate::barrier::series(
                    depth,
                    c.absorber[j],
                    strip,
                    &mut c.absorbed[j],
                    &own,
                    &mut c.states[j],
                ),
                (false, _) => (0.0, 0.0),
            };
            self.deflect(c, j, depth, covered);
        }
        self.bend(c);
        self.hold(q, c);
    }

    /// The beam's deflection at segment `j` for the bending energy: the crush
    /// while the striker pushes it; when a loaded segment leaves the face (an
    /// overlap edge, a pole's side) the beam keeps that deflection (`rest`)
    /// until the striker pushes it further again. So the deflection, and the
    /// bending energy, never jump: the coupling stays conservative.
    fn deflect(&self, c: &mut Contact, j: usize, depth: f64, covered: bool) {
        if c.switched[j] && !covered {
            c.rest[j] = c.deflection[j];
        }
        let engaged = depth > 0.0 && depth >= c.rest[j];
        if engaged {
            c.rest[j] = 0.0;
        }
        c.engaged[j] = engaged;
        c.deflection[j] = if engaged { depth } else { c.rest[j] };
    }

    /// Adds the bending share `∂V_b/∂d_j` to the segments in contact.
    fn bend(&self, c: &mut Contact) {
        let last = c.crush.len() - 1;
        let d = &c.deflection;
        let curvature = |i: usize| d[i - 1] - 2.0 * d[i] + d[i + 1];
        for j in 0..=last {
            let mut bend = 0.0;
            if c.engaged[j] && self.bending > 0.0 {
                // d_j enters the curvatures at j − 1 (×1), j (×−2) and j + 1 (×1)
                for (i, weight) in [(j.wrapping_sub(1), 1.0), (j, -2.0), (j + 1, 1.0)] {
                    if i >= 1 && i < last {
                        bend += weight * curvature(i);
                    }
                }
            }
            c.total[j] = c.force[j] + self.bending * bend;
        }
    }

    /// A segment that comes under the face's edge already inside the face has
    /// met the striker's side, not its face: it takes no load until it is out
    /// again. Returns the penetration to use (−1: no contact).
    fn admit(&self, c: &mut Contact, j: usize, depth: f64, covered: bool) -> f64 {
        let was = c.covered[j];
        c.covered[j] = covered;
        c.switched[j] = was != covered;
        if !covered || depth <= 0.0 {
            c.blocked[j] = false;
        } else if !was {
            c.blocked[j] = true;
        }
        if covered && !c.blocked[j] {
            depth
        } else {
            -1.0
        }
    }

    /// Bending energy ½ k_b Σ (d_{j−1} − 2 d_j + d_{j+1})² of the deflections, J.
    pub fn bending_energy(&self, c: &Contact) -> f64 {
        let sum: f64 = c
            .deflection
            .windows(3)
            .map(|w| (w[0] - 2.0 * w[1] + w[2]).powi(2))
            .sum();
        0.5 * self.bending * sum
    }

    /// Energy in the chain springs (a nonlinear link's elastic part), J.
    pub fn spring_energy(&self, q: &[f64], c: &Contact) -> f64 {
        let stored = |(k, l): (usize, &Link)| {
            let x = l.stretch(q);
            match &l.law {
                None => 0.5 * l.spring * x * x + l.block_energy(x),
                Some(law) => law.stored(-x, &c.links[k]) + l.block_energy(x),
            }
        };
        self.links.iter().enumerate().map(stored).sum()
    }

    /// The first crash box (a side's first link) compressed past its
    /// block's depth at positions `q`, as bottomed at `time` (s).
    pub fn box_bottomed(&self, q: &[f64], time: f64) -> Option<BoxBottomed> {
        let first = self.fronts.iter().enumerate().filter_map(|(side, f)| {
            let l = self.links.iter().find(|l| Some(l.front) == *f)?;
            let depth = l.block?.depth;
            (-l.stretch(q) > depth).then(|| BoxBottomed {
                time,
                side: [BoxSide::Left, BoxSide::Right][side],
                y: self.eta[l.front],
            })
        });
        first.into_iter().next()
    }

    /// Power of the chain dampers' forces at velocities `v` on the motion at
    /// velocities `w`, W (dissipated when positive).
    pub fn damper_power(&self, v: &[f64], w: &[f64]) -> f64 {
        let relative = |x: &[f64], l: &Link| x[3 + l.front] - l.back.map_or(0.0, |i| x[3 + i]);
        self.links
            .iter()
            .map(|l| l.damper * relative(v, l) * relative(w, l))
            .sum()
    }

    /// World velocity of chain mass `i`.
    fn mass_velocity(&self, q: &[f64], v: &[f64], axes: Axes, i: usize) -> ([f64; 2], [f64; 2]) {
        let Axes { e, n } = axes;
        let (xi, eta) = (self.x_f + q[3 + i], self.eta[i]);
        let p = [q[0] + xi * e[0] + eta * n[0], q[1] + xi * e[1] + eta * n[1]];
        let w = v[2];
        let u = v[3 + i];
        let pv = [
            v[0] + w * (xi * n[0] - eta * e[0]) + u * e[0],
            v[1] + w * (xi * n[1] - eta * e[1]) + u * e[1],
        ];
        (p, pv)
    }

    /// Kinetic energy of car and pendulum, J.
    pub fn kinetic(&self, q: &[f64], v: &[f64]) -> f64 {
        let axes = self.axes(q[2]);
        let mut t = 0.5 * self.body_mass * (v[0] * v[0] + v[1] * v[1]);
        t += 0.5 * self.yaw_inertia * v[2] * v[2];
        for (i, m) in self.masses.iter().enumerate() {
            let (_, pv) = self.mass_velocity(q, v, axes, i);
            t += 0.5 * m * (pv[0] * pv[0] + pv[1] * pv[1]);
        }
        let s = v[self.travel()];
        t + 0.5 * self.pendulum.unwrap_or(0.0) * s * s
    }

    /// Linear momentum (N·s) and angular momentum about the world origin
    /// (N·m·s) of car and pendulum.
    pub fn momentum(&self, q: &[f64], v: &[f64]) -> ([f64; 2], f64) {
        let (m, axes) = (self.body_mass, self.axes(q[2]));
        let mut p = [m * v[0], m * v[1]];
        let mut l = m * cross([q[0], q[1]], [v[0], v[1]]) + self.yaw_inertia * v[2];
        for (i, mi) in self.masses.iter().enumerate() {
            let (r, pv) = self.mass_velocity(q, v, axes, i);
            p[0] += mi * pv[0];
            p[1] += mi * pv[1];
            l += mi * cross(r, pv);
        }
        if let Some(mp) = self.pendulum {
            let s = q[self.travel()];
            let vp = [-mp * v[self.travel()], 0.0];
            p[0] += vp[0];
            l += cross(self.face.moved(s).reference(), vp);
        }
        (p, l)
    }

    /// Generalised accelerations `a` from positions `q`, half-step velocities
    /// `v` and the segment forces; `chain` is scratch of the chain's length.
    pub fn accelerations(
        &self,
        q: &[f64],
        v: &[f64],
        c: &Contact,
        chain: &mut [f64],
        a: &mut [f64],
    ) -> Loads {
        self.accelerations_at(q, v, c, chain, a, self.trig(q[2]))
    }

    /// [`Model::accelerations`] with the yaw's sine and cosine given.
    pub fn accelerations_at(
        &self,
        q: &[f64],
        v: &[f64],
        c: &Contact,
        chain: &mut [f64],
        a: &mut [f64],
        (sn, cs): (f64, f64),
    ) -> Loads {
        let (e, n) = ([cs, sn], [-sn, cs]);
        let mut loads = Loads::default();
        // external forces in the body frame: e, n and moment about the CG
        let (mut fe, mut fn_, mut mz) = (0.0, 0.0, 0.0);
        chain.iter_mut().for_each(|f| *f = 0.0);
        for (k, l) in self.links.iter().enumerate() {
            let (bx, bv) = l.back.map_or((0.0, 0.0), |i| (q[3 + i], v[3 + i]));
            let x = q[3 + l.front] - bx;
            let spring = match l.law {
                None => l.spring * x,
                Some(_) => -c.link_force[k],
            };
            let f = spring - l.blocking(x) + l.damper * (v[3 + l.front] - bv);
            chain[l.front] -= f;
            if let Some(i) = l.back {
                chain[i] += f;
            }
        }
        let (mut ce, mut cn) = (0.0, 0.0);
        for j in 0..c.total.len() {
            let (f, d, p) = (c.total[j], c.direction[j], c.point[j]);
            if f == 0.0 {
                continue;
            }
            let (pe, pn) = (f * d[0], f * d[1]);
            ce += pe;
            cn += pn;
            mz += p[0] * pn - p[1] * pe;
            let alpha = self.share(p[1]);
            loads.side[0] -= alpha * pe;
            loads.side[1] -= (1.0 - alpha) * pe;
            for (side, part) in [(0, alpha), (1, 1.0 - alpha)] {
                if let Some(i) = self.fronts[side] {
                    chain[i] += part * pe;
                }
            }
        }
        loads.contact = [ce * e[0] + cn * n[0], ce * e[1] + cn * n[1]];
        loads.contact_moment = mz;
        fe += ce;
        fn_ += cn;
        let tyre = self.tyres(v, (e, n), &c.patches, &mut loads);
        fe += tyre[0];
        fn_ += tyre[1];
        mz += loads.tyre_moment;
        self.solve(q, v, [fe, fn_, mz], chain, a, (sn, cs));
        if let Some(mp) = self.pendulum {
            a[self.travel()] = loads.contact[0] / mp;
        } else {
            a[self.travel()] = 0.0;
        }
        loads
    }

    /// Tyre forces (body frame e, n) at the patch deflections `patches`,
    /// filling their world resultant and moment.
    fn tyres(
        &self,
        v: &[f64],
        axes: ([f64; 2], [f64; 2]),
        patches: &[f64; 4],
        loads: &mut Loads,
    ) -> [f64; 2] {
        let (e, n) = axes;
        let (ve, vn, w) = (v[0] * e[0] + v[1] * e[1], v[0] * n[0] + v[1] * n[1], v[2]);
        let (mut fe, mut fn_) = (0.0, 0.0);
        for (wheel, &y) in self.wheels.iter().zip(patches) {
            let (we, wn) = (ve - w * wheel.eta, vn + w * wheel.xi);
            let (pe, pn) = wheel.force(we, wn, y, self.slip);
            fe += pe;
            fn_ += pn;
            loads.tyre_moment += wheel.xi * pn - wheel.eta * pe;
        }
        loads.tyre = [fe * e[0] + fn_ * n[0], fe * e[1] + fn_ * n[1]];
        [fe, fn_]
    }

    /// Advances the rolling tyres' patch deflections over `step` (s) at
    /// positions `q` and the velocities `v` of the step ([`Wheel::relax`]).
    pub fn relax(&self, q: &[f64], v: &[f64], c: &mut Contact, step: f64) {
        self.relax_at(self.trig(q[2]), v, c, step)
    }

    /// [`Model::relax`] with the yaw's sine and cosine given.
    pub fn relax_at(&self, (sn, cs): (f64, f64), v: &[f64], c: &mut Contact, step: f64) {
        let (e, n) = ([cs, sn], [-sn, cs]);
        let (ve, vn, w) = (v[0] * e[0] + v[1] * e[1], v[0] * n[0] + v[1] * n[1], v[2]);
        for (wheel, y) in self.wheels.iter().zip(&mut c.patches) {
            wheel.relax(ve - w * wheel.eta, vn + w * wheel.xi, y, step);
        }
    }

    /// Solves the Newton–Euler equations for the body and chain accelerations.
    fn solve(
        &self,
        q: &[f64],
        v: &[f64],
        external: [f64; 3],
        chain: &[f64],
        a: &mut [f64],
        (sn, cs): (f64, f64),
    ) {
        // the inertial (Coriolis, centrifugal) terms take the velocities at
        // the full step, extrapolated from v_{n−½} with the last accelerations
        // still in `a`: second order, so momentum stays balanced when spinning
        let h = self.half_step;
        let w = v[2] + h * a[2];
        let (mut sum_m, mut sum_mx, mut sum_mxx) = (0.0, 0.0, 0.0);
        let (mut sum_q, mut sum_eta_q, mut cor_n, mut cor_m) = (0.0, 0.0, 0.0, 0.0);
        for (i, &m) in self.masses.iter().enumerate() {
            let (xi, eta) = (self.x_f + q[3 + i], self.eta[i]);
            let coriolis = m * (2.0 * w * (v[3 + i] + h * a[3 + i]) - w * w * eta);
            sum_m += m;
            sum_mx += m * xi;
            sum_mxx += m * xi * xi;
            sum_q += chain[i];
            sum_eta_q += eta * chain[i];
            cor_n += coriolis;
            cor_m += xi * coriolis;
        }
        let [fe, fn_, mz] = external;
        let ax = (fe - sum_q) / self.body_mass;
        let (a11, a12, a22) = (self.body_mass + sum_m, sum_mx, self.yaw_inertia + sum_mxx);
        let (r1, r2) = (fn_ - cor_n, mz + sum_eta_q - cor_m);
        let det = a11 * a22 - a12 * a12;
        let ay = (r1 * a22 - a12 * r2) / det;
        let yaw = (a11 * r2 - a12 * r1) / det;
        a[0] = ax * cs - ay * sn;
        a[1] = ax * sn + ay * cs;
        a[2] = yaw;
        for (i, &m) in self.masses.iter().enumerate() {
            let xi = self.x_f + q[3 + i];
            a[3 + i] = chain[i] / m - ax + yaw * self.eta[i] + w * w * xi;
        }
    }

    /// Stiffness and damping bounds for the critical step: the largest
    /// Gershgorin row sums of M⁻¹K and M⁻¹C over the coordinates, 1/s² and 1/s.
    pub fn rates(&self, car: &PlanarCar) -> (f64, f64) {
        self.bounds(car, true)
    }

    /// [`Model::rates`] of the car alone, without the bumper segments (a
    /// force-driven car: the loads are given, not made by a contact).
    pub fn chain_rates(&self, car: &PlanarCar) -> (f64, f64) {
        self.bounds(car, false)
    }

    fn bounds(&self, car: &PlanarCar, contact: bool) -> (f64, f64) {
        let segments = &car.beam().segments;
        let block = car.beam().block.map_or(0.0, |b| b.stiffness);
        let seg = |j: usize| match contact {
            true => segments[j].stiffest() + block + 16.0 * self.bending,
            false => 0.0,
        };
        let total: f64 = (0..segments.len()).map(seg).sum();
        let mut stiff = vec![0.0; self.masses.len()];
        let mut damp = vec![0.0; self.masses.len()];
        let (mut body_k, mut body_c) = (0.0, 0.0);
        for l in &self.links {
            let slope = l.law.as_ref().map_or(l.spring, |law| law.steepest_slope());
            let spring = slope + l.block.map_or(0.0, |b| b.stiffness);
            stiff[l.front] += 2.0 * spring;
            damp[l.front] += 2.0 * l.damper;
            match l.back {
                Some(i) => {
                    stiff[i] += 2.0 * spring;
                    damp[i] += 2.0 * l.damper;
                }
                None => {
                    body_k += 2.0 * spring;
                    body_c += 2.0 * l.damper;
                }
            }
        }
        let mut rot_k = 0.0;
        for (j, &y) in self.segment_y.iter().enumerate() {
            let alpha = self.share(y);
            let lever = self.x_f * self.x_f + y * y;
            let spread = alpha.abs() + (1.0 - alpha).abs();
            rot_k += 2.0 * seg(j) * lever;
            for (side, part) in [(0, alpha), (1, 1.0 - alpha)] {
                match self.fronts[side] {
                    Some(i) => stiff[i] += 2.0 * seg(j) * part.abs() * spread,
                    None => body_k += 2.0 * seg(j) * part.abs(),
                }
            }
        }
        let rates: Vec<(f64, f64)> = self.wheels.iter().map(|w| w.rates(self.slip)).collect();
        let friction: f64 = rates.iter().map(|r| r.0).sum();
        let rot_c: f64 = self
            .wheels
            .iter()
            .zip(&rates)
            .map(|(w, r)| 2.0 * r.0 * (w.xi * w.xi + w.eta * w.eta))
            .sum();
        // the relaxed tyres' lateral springs to the ground
        for (w, r) in self.wheels.iter().zip(&rates) {
            body_k += 2.0 * r.1;
            rot_k += 2.0 * r.1 * (w.xi * w.xi + w.eta * w.eta);
        }
        let mut omega2 = (body_k / self.body_mass).max(rot_k / self.yaw_inertia);
        let mut omega_c =
            ((body_c + 2.0 * friction) / self.body_mass).max(rot_c / self.yaw_inertia);
        for (i, m) in self.masses.iter().enumerate() {
            omega2 = omega2.max(stiff[i] / m);
            omega_c = omega_c.max(damp[i] / m);
        }
        if let Some(mp) = self.pendulum {
            omega2 = omega2.max(2.0 * total / mp);
        }
        (omega2, omega_c)
    }
}

#[path = "dynamics_state.rs"]
mod state;
