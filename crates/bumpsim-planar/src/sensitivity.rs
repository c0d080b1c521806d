//! The replay of [`crate::drive`] written over any [`Real`]: on `f64` it
//! gives the sensors' readings, on [`bumpsim_core::dual::Dual`] their exact
//! derivatives with respect to the car's parameters (the forward
//! sensitivity equations of the leapfrog, carried by the dual numbers:
//! every operation of a step differentiated by the chain rule, so the
//! derivatives are those of the discrete replay itself, to rounding).
//!
//! The equations are [`crate::drive`]'s, term for term and in the same
//! order: the leapfrog of [`bumpsim_core::leapfrog`] (`a_0 = a(q_0, v_0)`,
//! `v_½ = v_0 + (T/2) a_0`; `q_{n+1} = q_n + T v_{n+½}`,
//! `v_{n+3/2} = v_{n+½} + T a_{n+1}`), the chain links
//! `f = k x − block(x) + c ẋ`, the lever rule onto the side-member tips,
//! the tyres of [`crate::tyre`] (rolling with relaxation and saturation, or
//! sliding), the Newton–Euler solve of the body and chain accelerations
//! with the full-step yaw rate extrapolated, and the sensors' readings
//! integrated alongside. What may vary ([`Parameters`]): the body's mass
//! and yaw inertia, every chain mass, damper and spring (or a side member's
//! nonlinear link, [`bumpsim_core::link`], whose one law runs here on the
//! same [`Real`] with its history carried through the steps, its
//! parameters in [`Parameters::links`]), the tyres' lateral
//! grip (with a sliding grip along the wheel that follows it) and cornering
//! stiffness, and each load's lateral position. The wheel loads follow the
//! total mass. A wall cell's line of action is the crushed segments'
//! loading-force-weighted position times the drive's arm (a parameter
//! too, [`Parameters::arm`]), the segments' positions spread over the
//! car's effective width ([`Parameters::width`]: `η_j = w_e r_j`, exact
//! in value to the car's [`PlanarCar::segment_centre`]); the weights' slopes in the crush are
//! taken by a central difference of the segment's loading curve (piecewise
//! linear: exact away from its knees).

use crate::car::{Block, GRAVITY, PlanarCar, PlanarError};
use crate::drive::{Drive, Sensor};
use crate::tyre::Grip;
use bumpsim_core::dual::Real;
use bumpsim_core::link::{Link as Law, LinkState};
use bumpsim_impact::bumper::Bumper;

/// The car's quantities a replay may be differentiated by, in the model's
/// order: chains' links left chain first, each from the front.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameters<T> {
    /// Body mass, kg.
    pub body_mass: T,
    /// Body yaw inertia, kg·m².
    pub yaw_inertia: T,
    /// Chain masses, kg.
    pub masses: Vec<T>,
    /// Chain dampers, N·s/m (link i behind mass i).
    pub dampers: Vec<T>,
    /// Chain springs, N/m (a link with a nonlinear law takes `links`).
    pub springs: Vec<T>,
    /// Each chain link's nonlinear law (left chain first; `None`: the
    /// linear spring). [`Parameters::of`] gives the car's links as
    /// constants; [`bumpsim_core::link::Link::with_parameters`] seeds them.
    pub links: Vec<Option<Law<T>>>,
    /// Lateral grip μ_y of both axles.
    pub mu_lateral: T,
    /// Sliding grip along the wheel μ_x of the front and rear axle.
    pub mu_longitudinal: [T; 2],
    /// Cornering stiffness of both axles, N/rad.
    pub cornering: [T; 2],
    /// Relaxation length of both axles' rolling tyres, m (0: the
    /// instantaneous slip-angle law).
    pub relaxation: [T; 2],
    /// Each load's lateral position on the bumper line, m.
    pub lateral: Vec<T>,
    /// The wall cells' arm ([`crate::drive::Drive::arm`]).
    pub arm: T,
    /// The bumper's effective width, m ([`PlanarCar::effective_width`]).
    pub width: T,
}

impl<T: Real> Parameters<T> {
    /// `car`'s values and `input`'s lateral positions, as constants.
    pub fn of(car: &PlanarCar, input: &Drive) -> Parameters<T> {
        let c = |v: &f64| T::constant(*v);
        let chains = [car.left(), car.right()];
        let all = |pick: fn(&crate::car::SideChain) -> &Vec<f64>| {
            chains.iter().flat_map(|s| pick(s).iter().map(c)).collect()
        };
        let tyres = car.tyres();
        Parameters {
            body_mass: c(&car.body().mass),
            yaw_inertia: c(&car.body().yaw_inertia),
            masses: all(|s| &s.masses),
            dampers: all(|s| &s.dampers),
            springs: all(|s| &s.springs),
            links: chains
                .iter()
                .flat_map(|s| (0..s.masses.len()).map(|i| s.links.get(i).map(Law::real)))
                .collect(),
            mu_lateral: c(&tyres.front.mu_lateral),
            mu_longitudinal: [
                c(&tyres.front.mu_longitudinal),
                c(&tyres.rear.mu_longitudinal),
            ],
            cornering: [
                c(&tyres.front.cornering_stiffness),
                c(&tyres.rear.cornering_stiffness),
            ],
            relaxation: [
                c(&tyres.front.relaxation_length),
                c(&tyres.rear.relaxation_length),
            ],
            lateral: input.loads.iter().map(|l| c(&l.lateral)).collect(),
            arm: c(&input.arm),
            width: c(&car.effective_width()),
        }
    }
}

/// A link of a chain.
struct Link<T> {
    front: usize,
    back: Option<usize>,
    spring: T,
    law: Option<Law<T>>,
    damper: T,
    block: Option<Block>,
}

/// A wheel where it is on the body (ξ ahead of and η left of the CG, m)
/// with its law on the replay's numbers.
struct Wheel<T> {
    xi: f64,
    eta: f64,
    grip: Grip<T>,
}

/// The segments' centres `η_j = w_e r_j` of `car` with its effective
/// width `width` (a parameter): `r_j = η_j / w_e` of the car's centres, the
/// value put back exactly on the car's (`a + (η_j − a)` is exact for the
/// nearby `a = w_e r_j`), so a replay on `f64` is the car's to the bit.
fn segment_y<T: Real>(car: &PlanarCar, width: T) -> Vec<T> {
    let w = car.effective_width();
    (0..car.beam().segments.len())
        .map(|j| {
            let centre = car.segment_centre(j);
            let near = width * (centre / w);
            near + T::constant(centre - near.value())
        })
        .collect()
}

/// The replay's state and the car's prepared model.
struct Replay<'a, T> {
    input: &'a Drive,
    segments: &'a [Bumper],
    body_mass: T,
    yaw_inertia: T,
    masses: Vec<T>,
    eta: Vec<f64>,
    links: Vec<Link<T>>,
    /// The nonlinear links' histories and forces (compression positive).
    states: Vec<LinkState<T>>,
    link_force: Vec<T>,
    fronts: [Option<usize>; 2],
    b: f64,
    x_f: f64,
    segment_y: Vec<T>,
    wheels: Vec<Wheel<T>>,
    slip: f64,
    half_step: f64,
    lateral: Vec<T>,
    /// The wall cells' arm.
    arm: T,
    directions: Vec<[f64; 2]>,
    /// Per load: magnitude, direction and point (body frame).
    total: Vec<f64>,
    direction: Vec<[T; 2]>,
    point: Vec<[T; 2]>,
    patches: [T; 4],
    chain: Vec<T>,
    readings: Vec<[T; 3]>,
    axes: (T, T),
}

/// The sensors' readings ([`crate::drive::Driven::sensor_reading`]) of the
/// first `samples` samples of `input` replayed on `car` with the values
/// `parameters` and `substeps` steps a sample: what
/// [`crate::drive::drive_substeps`] reads, on any [`Real`]. `input` must
/// have been validated for `car` ([`crate::drive::validate`]).
pub fn sensor_readings<T: Real>(
    car: &PlanarCar,
    parameters: &Parameters<T>,
    input: &Drive,
    substeps: usize,
    samples: usize,
) -> Result<Vec<Vec<T>>, PlanarError> {
    let mut replay = Replay::new(car, parameters, input, substeps);
    let available = input.loads.first().map_or(0, |l| l.force.len());
    replay.run(samples.clamp(2, available.max(2)), substeps)
}

impl<'a, T: Real> Replay<'a, T> {
    fn new(
        car: &'a PlanarCar,
        p: &Parameters<T>,
        input: &'a Drive,
        substeps: usize,
    ) -> Replay<'a, T> {
        let zero = T::constant(0.0);
        let b = 0.5 * car.beam().side_member_spacing;
        let (mut eta, mut links, mut fronts) = (vec![], vec![], [None, None]);
        let mut first = 0;
        for (side, (chain, y)) in [(car.left(), b), (car.right(), -b)].into_iter().enumerate() {
            let n = chain.masses.len();
            fronts[side] = (n > 0).then_some(first);
            for i in 0..n {
                eta.push(y);
                links.push(Link {
                    front: first + i,
                    back: (i + 1 < n).then_some(first + i + 1),
                    spring: p.springs[first + i],
                    law: p.links.get(first + i).cloned().flatten(),
                    damper: p.dampers[first + i],
                    block: car.crash_boxes().filter(|_| i == 0),
                });
            }
            first += n;
        }
        let body = car.body();
        let (a, l) = (body.cg_behind_front_axle, body.wheelbase);
        let total = p.masses.iter().fold(p.body_mass, |s, m| s + *m);
        let weight = total * GRAVITY;
        let tyres = car.tyres();
        let mut wheels = vec![];
        for (axle_index, (xi, load, axle)) in [
            (a, weight * ((l - a) / l), tyres.front),
            (a - l, weight * (a / l), tyres.rear),
        ]
        .into_iter()
        .enumerate()
        {
            for eta in [0.5 * body.track, -0.5 * body.track] {
                let grip = Grip {
                    axle,
                    load: load * 0.5,
                    mu_lateral: p.mu_lateral,
                    mu_longitudinal: p.mu_longitudinal[axle_index],
                    cornering: p.cornering[axle_index],
                    relaxation: p.relaxation[axle_index],
                };
                wheels.push(Wheel { xi, eta, grip });
            }
        }
        let loads = input.loads.len();
        Replay {
            input,
            segments: &car.beam().segments,
            body_mass: p.body_mass,
            yaw_inertia: p.yaw_inertia,
            masses: p.masses.clone(),
            eta,
            states: vec![LinkState::default(); links.len()],
            link_force: vec![zero; links.len()],
            links,
            fronts,
            b,
            x_f: body.cg_behind_bumper,
            segment_y: segment_y(car, p.width),
            wheels,
            slip: tyres.slip_speed,
            half_step: 0.5 * input.step / substeps as f64,
            lateral: p.lateral.clone(),
            arm: p.arm,
            directions: input
                .loads
                .iter()
                .map(|l| {
                    let norm = l.direction[0].hypot(l.direction[1]);
                    [l.direction[0] / norm, l.direction[1] / norm]
                })
                .collect(),
            total: vec![0.0; loads],
            direction: vec![[zero; 2]; loads],
            point: vec![[zero; 2]; loads],
            patches: [zero; 4],
            chain: vec![zero; p.masses.len()],
            readings: input
                .sensors
                .iter()
                .map(|s| {
                    let v = if s.along_x() { input.speed } else { 0.0 };
                    [zero, T::constant(v), zero]
                })
                .collect(),
            axes: (zero, T::constant(1.0)),
        }
    }

    fn dof(&self) -> usize {
        4 + self.masses.len()
    }

    /// The leapfrog of [`bumpsim_core::leapfrog::Leapfrog::run`], recording
    /// every `substeps` steps up to sample `samples − 1`.
    fn run(&mut self, samples: usize, substeps: usize) -> Result<Vec<Vec<T>>, PlanarError> {
        let zero = T::constant(0.0);
        let (n, t) = (self.dof(), 2.0 * self.half_step);
        let mut q = vec![zero; n];
        let mut v = vec![zero; n];
        v[0] = T::constant(self.input.speed);
        let mut a = vec![zero; n];
        self.place(&q, 0, 0.0);
        self.accelerations(&q, &v, &mut a);
        let mut half = v.clone();
        for (h, x) in half.iter_mut().zip(&a) {
            *h += *x * (0.5 * t);
        }
        self.sensed(&q, &v, &a, 0.5 * t);
        let mut out = vec![Vec::with_capacity(samples); self.input.sensors.len()];
        let mut previous = vec![zero; n];
        for k in 0..=(samples - 1) * substeps {
            if k % substeps == 0 {
                let i = k / substeps;
                if !q.iter().all(|x| x.value().abs() < 1e3) {
                    let time = i as f64 * self.input.step;
                    let step = self.input.step / substeps as f64;
                    return Err(PlanarError::Diverged { time, step });
                }
                for (s, history) in out.iter_mut().enumerate() {
                    history.push(self.reading(s, &q));
                }
                if i + 1 >= samples {
                    break;
                }
            }
            for (x, h) in q.iter_mut().zip(&half) {
                *x += *h * t;
            }
            self.axes = q[2].sin_cos();
            self.relax(&half, t);
            self.readings.iter_mut().for_each(|r| r[0] += r[1] * t);
            let (i, within) = (k / substeps, k % substeps + 1);
            self.place(&q, i, within as f64 / substeps as f64);
            previous.copy_from_slice(&half);
            self.accelerations(&q, &half, &mut a);
            for (h, x) in half.iter_mut().zip(&a) {
                *h += *x * t;
            }
            self.sensed(&q, &previous, &a, t);
        }
        Ok(out)
    }

    /// The sensors' accelerations at the end of a step of `length` (s), and
    /// their velocities advanced over it.
    fn sensed(&mut self, q: &[T], before: &[T], a: &[T], length: f64) {
        self.sense(q, before, a);
        self.readings.iter_mut().for_each(|r| r[1] += r[2] * length);
    }

    /// [`crate::drive`]'s `Replay::place` (and `Model::hold`).
    fn place(&mut self, q: &[T], i: usize, f: f64) {
        for (k, l) in self.links.iter().enumerate() {
            if let Some(law) = &l.law {
                let x = q[3 + l.front] - l.back.map_or(T::constant(0.0), |i| q[3 + i]);
                self.link_force[k] = law.force(-x, &mut self.states[k]);
            }
        }
        let (sn, cs) = self.axes;
        for k in 0..self.input.loads.len() {
            let load = &self.input.loads[k];
            let next = load.force.get(i + 1).copied().unwrap_or(load.force[i]);
            self.total[k] = load.force[i] + f * (next - load.force[i]);
            let d = self.directions[k];
            self.direction[k] = [cs * d[0] + sn * d[1], cs * d[1] - sn * d[0]];
            let cell = load.cell.and_then(|w| self.cell_contact(q, k, w));
            self.point[k] = match (cell, load.anchor) {
                (Some(eta), _) => self.bumper_point(q, eta),
                (None, None) => self.bumper_point(q, self.lateral[k]),
                (None, Some(p)) => {
                    let r = [-q[0] + p[0], -q[1] + p[1]];
                    [r[0] * cs + r[1] * sn, -(r[0] * sn) + r[1] * cs]
                }
            };
        }
    }

    /// [`crate::drive`]'s `Replay::cell_contact`.
    fn cell_contact(&self, q: &[T], k: usize, width: f64) -> Option<T> {
        let (sn, cs) = self.axes;
        let anchor = self.input.loads[k].anchor?;
        let normal = self.directions[k];
        let tangent = [-normal[1], normal[0]];
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        let along = |a: [f64; 2], p: [T; 2]| p[0] * a[0] + p[1] * a[1];
        let (face, centre) = (dot(normal, anchor), dot(tangent, anchor));
        let (mut sum, mut weighted) = (T::constant(0.0), T::constant(0.0));
        let mut nearest = None::<(f64, T)>;
        for (segment, &eta) in self.segments.iter().zip(&self.segment_y) {
            let b = self.bumper_point(q, eta);
            let p = [q[0] + b[0] * cs - b[1] * sn, q[1] + b[0] * sn + b[1] * cs];
            if (along(tangent, p).value() - centre).abs() > 0.5 * width {
                continue;
            }
            let depth = -along(normal, p) + face;
            if nearest.is_none_or(|(d, _)| depth.value() > d) {
                nearest = Some((depth.value(), eta));
            }
            if depth.value() > 0.0 {
                let w = loading(segment, depth);
                sum += w;
                weighted += w * eta;
            }
        }
        match sum.value() > 0.0 {
            true => Some(self.arm * weighted / sum),
            false => nearest.map(|(_, eta)| self.arm * eta),
        }
    }

    /// The bumper line's point at η, body frame.
    fn bumper_point(&self, q: &[T], eta: T) -> [T; 2] {
        let tip = |side: usize| self.fronts[side].map_or(T::constant(0.0), |i| q[3 + i]);
        let alpha = (eta + self.b) / (2.0 * self.b);
        let beam = alpha * tip(0) + (-alpha + 1.0) * tip(1);
        [beam + self.x_f, eta]
    }

    fn relax(&mut self, v: &[T], step: f64) {
        let (sn, cs) = self.axes;
        let (ve, vn, w) = (v[0] * cs + v[1] * sn, -(v[0] * sn) + v[1] * cs, v[2]);
        for (wheel, y) in self.wheels.iter().zip(&mut self.patches) {
            wheel
                .grip
                .relax(ve - w * wheel.eta, vn + w * wheel.xi, y, step);
        }
    }

    /// [`crate::dynamics`]'s `Model::accelerations_at` for given loads.
    fn accelerations(&mut self, q: &[T], v: &[T], a: &mut [T]) {
        let zero = T::constant(0.0);
        let (sn, cs) = self.axes;
        let chain = &mut self.chain;
        chain.iter_mut().for_each(|f| *f = zero);
        for (k, l) in self.links.iter().enumerate() {
            let (bx, bv) = l.back.map_or((zero, zero), |i| (q[3 + i], v[3 + i]));
            let x = q[3 + l.front] - bx;
            let block = l.block.map_or(zero, |b| {
                let over = -x - b.depth;
                match over.value() > 0.0 {
                    true => over * b.stiffness,
                    false => zero,
                }
            });
            let spring = match l.law {
                None => l.spring * x,
                Some(_) => -self.link_force[k],
            };
            let f = spring - block + l.damper * (v[3 + l.front] - bv);
            chain[l.front] -= f;
            if let Some(i) = l.back {
                chain[i] += f;
            }
        }
        let (mut ce, mut cn, mut mz) = (zero, zero, zero);
        for j in 0..self.total.len() {
            let (f, d, p) = (self.total[j], self.direction[j], self.point[j]);
            if f == 0.0 {
                continue;
            }
            let (pe, pn) = (d[0] * f, d[1] * f);
            ce += pe;
            cn += pn;
            mz += p[0] * pn - p[1] * pe;
            let alpha = (p[1] + self.b) / (2.0 * self.b);
            for (side, part) in [(0, alpha), (1, -alpha + 1.0)] {
                if let Some(i) = self.fronts[side] {
                    chain[i] += part * pe;
                }
            }
        }
        let (ve, vn, w) = (v[0] * cs + v[1] * sn, -(v[0] * sn) + v[1] * cs, v[2]);
        let (mut te, mut tn, mut tm) = (zero, zero, zero);
        for (wheel, &y) in self.wheels.iter().zip(&self.patches) {
            let (pe, pn) = wheel
                .grip
                .force(ve - w * wheel.eta, vn + w * wheel.xi, y, self.slip);
            te += pe;
            tn += pn;
            tm += pn * wheel.xi - pe * wheel.eta;
        }
        let external = [ce + te, cn + tn, mz + tm];
        self.solve(q, v, external, a);
        let travel = self.dof() - 1;
        a[travel] = zero;
    }

    /// [`crate::dynamics`]'s `Model::solve`.
    fn solve(&self, q: &[T], v: &[T], external: [T; 3], a: &mut [T]) {
        let zero = T::constant(0.0);
        let (sn, cs) = self.axes;
        let h = self.half_step;
        let w = v[2] + a[2] * h;
        let (mut sum_m, mut sum_mx, mut sum_mxx) = (zero, zero, zero);
        let (mut sum_q, mut sum_eta_q, mut cor_n, mut cor_m) = (zero, zero, zero, zero);
        for (i, &m) in self.masses.iter().enumerate() {
            let (xi, eta) = (q[3 + i] + self.x_f, self.eta[i]);
            let coriolis = m * (w * (v[3 + i] + a[3 + i] * h) * 2.0 - w * w * eta);
            sum_m += m;
            sum_mx += m * xi;
            sum_mxx += m * xi * xi;
            sum_q += self.chain[i];
            sum_eta_q += self.chain[i] * eta;
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
            let xi = q[3 + i] + self.x_f;
            a[3 + i] = self.chain[i] / m - ax + yaw * self.eta[i] + w * w * xi;
        }
    }

    /// A sensor's body point and its acceleration relative to the body.
    fn point(&self, sensor: Sensor, q: &[T], a: &[T]) -> ([T; 2], T) {
        let zero = T::constant(0.0);
        match sensor {
            Sensor::Body(p) | Sensor::Lateral(p) | Sensor::Film(p) => {
                ([T::constant(p[0]), T::constant(p[1])], zero)
            }
            Sensor::Chain(i) | Sensor::Crush(i) => {
                ([q[3 + i] + self.x_f, T::constant(self.eta[i])], a[3 + i])
            }
            Sensor::YawRate => ([zero; 2], zero),
        }
    }

    /// [`crate::drive`]'s `Replay::reading`.
    fn reading(&self, k: usize, q: &[T]) -> T {
        let (sn, cs) = self.axes;
        match self.input.sensors[k] {
            Sensor::Film([xi, eta]) => q[0] + cs * xi - sn * eta - xi,
            Sensor::Crush(i) => q[3 + i],
            _ => self.readings[k][0],
        }
    }

    /// [`crate::drive`]'s `Replay::sense`.
    fn sense(&mut self, q: &[T], v: &[T], a: &[T]) {
        let (sn, cs) = self.axes;
        let along = a[0] * cs + a[1] * sn;
        let across = -(a[0] * sn) + a[1] * cs;
        let rate = v[2] + a[2] * self.half_step;
        for k in 0..self.input.sensors.len() {
            let sensor = self.input.sensors[k];
            let ([xi, eta], relative) = self.point(sensor, q, a);
            self.readings[k][2] = match sensor {
                Sensor::Lateral(_) => across + a[2] * xi - rate * rate * eta,
                Sensor::YawRate => {
                    self.readings[k][0] = rate;
                    T::constant(0.0)
                }
                _ => along - a[2] * eta - rate * rate * xi + relative,
            };
        }
    }
}

/// A segment's loading force at the crush `depth`, with its slope by a
/// central difference of the loading curve.
fn loading<T: Real>(segment: &Bumper, depth: T) -> T {
    let d = depth.value();
    let h = 1e-9_f64.max(1e-7 * d.abs());
    let slope = (segment.loading_force(d + h) - segment.loading_force(d - h)) / (2.0 * h);
    (depth - d) * slope + segment.loading_force(d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Axle;
    use crate::car::Layout;
    use crate::drive::{drive_substeps, segment_loads, substeps};
    use crate::simulate::{Settings, simulate};
    use crate::striker::{Face, Placed, Side, Striker, place};
    use bumpsim_core::dual::Dual;
    use bumpsim_core::model::MsdModel;

    /// An RCAR 10° impact replayed from its segment forces with every kind
    /// of sensor: the readings on `f64` equal [`crate::drive`]'s to 1e-12
    /// of each history's peak (the same operations, some in another order),
    /// and so do the values on dual numbers (a quotient there is a product
    /// by the reciprocal).
    #[test]
    fn the_generic_replay_reads_what_drive_reads() {
        let chain = MsdModel::new(vec![12.0, 1250.0], vec![3e3], vec![2.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        replays_alike(&car);
        // rolling tyres with grip, relaxed in front and instantaneous at
        // the rear, each with a Magic-Formula shape
        let front = Axle {
            shape: Some(1.3),
            ..Axle::rolling(0.012, 0.8)
        };
        let rear = Axle {
            shape: Some(1.6),
            relaxation_length: 0.0,
            ..Axle::rolling(0.012, 0.8)
        };
        let tyres = crate::car::Tyres {
            front,
            rear,
            slip_speed: 0.05,
        };
        replays_alike(&car.with_tyres(tyres).unwrap());
    }

    /// The generic replay in f64 and in dual numbers reads what
    /// [`drive_substeps`] reads, for every sensor kind, on an angled wall.
    fn replays_alike(car: &PlanarCar) {
        let striker = Striker::barrier(Face::plane_in_degrees(10.0, 40.0, Side::Left), 15.0 / 3.6);
        let settings = Settings {
            output_step: 1e-4,
            ..Settings::default()
        };
        let r = simulate(car, &striker, &settings).unwrap();
        let Placed::Plane { normal, .. } = place(car, &striker).unwrap() else {
            unreachable!("a plane face")
        };
        let input = Drive {
            step: 1e-4,
            loads: segment_loads(&r, normal),
            speed: 15.0 / 3.6,
            arm: 1.0,
            sensors: vec![
                Sensor::Body([0.6, 0.7]),
                Sensor::Chain(0),
                Sensor::Lateral([0.6, -0.7]),
                Sensor::YawRate,
                Sensor::Film([0.6, 0.7]),
                Sensor::Crush(1),
            ],
        };
        let n = substeps(car, input.step, 0.25).unwrap();
        let expected = drive_substeps(car, &input, n).unwrap().sensor_reading;
        let samples = expected[0].len();
        let plain =
            sensor_readings::<f64>(car, &Parameters::of(car, &input), &input, n, samples).unwrap();
        let dual =
            sensor_readings::<Dual<2>>(car, &Parameters::of(car, &input), &input, n, samples)
                .unwrap();
        for (k, want) in expected.iter().enumerate() {
            let peak = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(peak > 0.0, "sensor {k} reads something");
            for (i, w) in want.iter().enumerate() {
                assert!(
                    (plain[k][i] - w).abs() <= 1e-12 * peak,
                    "sensor {k} sample {i}"
                );
                assert!(
                    (dual[k][i].real - w).abs() <= 1e-12 * peak,
                    "sensor {k} sample {i}"
                );
            }
        }
    }
}
