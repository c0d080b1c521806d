//! The planar car driven by given forces (spec §9): the model that planar
//! identification fits, and the reference for the exported FE decks.
//!
//! The equations of motion are those of [`crate::simulate`](mod@crate::simulate) (same
//! generalised coordinates, same Newton–Euler solve, same leapfrog), with
//! the striker's contact replaced by given loads: load k acts on the bumper
//! line at the lateral position η_k (body frame, left positive) with a fixed
//! direction `d_k` in the world frame and magnitude `F_k(t)`, linearly
//! interpolated between its samples. Its part along the body axis is shared
//! onto the two front chain masses by the lever rule (left share
//! `α = (η_k + b)/(2b)`); its lateral part and its moment about the CG act on
//! the body — exactly how a segment's contact force acts in an impact. This
//! is how a test is replayed: the barrier's load cells give the forces and
//! their lateral positions, the car's accelerometers the motion.
//!
//! Outputs, at the input's samples: the CG displacement (x, y) in the world,
//! the yaw ψ (counter-clockwise seen from above), the world-x displacement
//! of each sensor point `X + ξ cos ψ − η sin ψ − ξ`, the side-member tip
//! forces and the chain masses' displacements u_i.
//!
//! Integration: the one integrator of [`bumpsim_core::leapfrog`], with the
//! sensors' readings integrated alongside. Step: its one rule,
//! `T = safety · min(2/ω, 2/ω_c)` from the chain and tyre bounds of
//! [`crate::simulate`](mod@crate::simulate) (no segments), rounded down to divide the sample
//! interval.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_impact::bumper::Bumper;
//! use bumpsim_planar::car::{Layout, PlanarCar};
//! use bumpsim_planar::drive::{Drive, Load, drive};
//! // a rigid 1000-kg car (no chain), pushed at its axis by 1 kN for 0.1 s
//! let chain = MsdModel::new(vec![1000.0], vec![], vec![]).unwrap();
//! let bumper = Bumper::three_part(1e6, 1e5, 1e7).unwrap();
//! let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
//! let load = Load { lateral: 0.0, anchor: None, cell: None, direction: [-1.0, 0.0], force: vec![1e3; 1001] };
//! let input = Drive { step: 1e-4, loads: vec![load], speed: 0.0, arm: 1.0, sensors: vec![] };
//! let r = drive(&car, &input, 0.05).unwrap();
//! let expected = -0.5 * 1.0 * 0.1f64.powi(2);              // x = ½ (F/M) t²
//! assert!((r.x.last().unwrap() - expected).abs() < 1e-9);
//! assert!(r.yaw.iter().all(|y| y.abs() < 1e-15));         // on the axis: no turn
//! ```

use crate::car::{PlanarCar, PlanarError, parameter, require};
use crate::dynamics::{Contact, Model};
use crate::striker::Placed;
use bumpsim_core::leapfrog::{
    Control, Leapfrog, Mechanism, Stepped, critical_step, substeps as substeps_of,
};

/// The widest wall cell, m: wider than any barrier's load-cell wall.
pub const MAX_CELL: f64 = 10.0;

/// The farthest a body sensor may sit from the CG along either body axis,
/// m: beyond any car (a sill at ξ = 1e300 m left no start that could be
/// evaluated, "check the forces and the template").
pub const MAX_SENSOR_PLACE: f64 = 10.0;

/// A given force on the bumper line.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    /// Lateral position on the bumper line, body frame, m (left positive).
    pub lateral: f64,
    /// A point fixed in the world that the line of action passes through
    /// (a pole's axis), given in the body frame at t = 0 (ξ ahead of the
    /// CG, η left), m; `None`: the load moves with the bumper line at `lateral`.
    pub anchor: Option<[f64; 2]>,
    /// A load cell of a wall: the cell's width along the wall face, m; its
    /// `anchor` is the cell's centre on the face and its `direction` the
    /// wall's normal. Its line of action is found per step where the car's
    /// bumper crushes into the cell (each segment's loading force at its
    /// penetration), not fixed at the cell's centre.
    pub cell: Option<f64>,
    /// Direction of the force on the car, world frame (normalised on use).
    pub direction: [f64; 2],
    /// Magnitudes, N, at `k · step` (k = 0, 1, …).
    pub force: Vec<f64>,
}

/// The loads, the start and the sensors of one replay.
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    /// Sample interval of the forces and of the outputs, s.
    pub step: f64,
    /// The loads (all of the same length).
    pub loads: Vec<Load>,
    /// Initial forward speed of the whole car, m/s (x, towards the bumper).
    pub speed: f64,
    /// The wall cells' arm (1: the segments' rule; [`crate::car::ARM_RANGE`]).
    pub arm: f64,
    /// The accelerometers.
    pub sensors: Vec<Sensor>,
}

/// A sensor: what it measures and where it sits. Each is compared in the
/// domain its reading ([`Driven::sensor_reading`]) gives.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub enum Sensor {
    /// An accelerometer along the body x axis at a body point (a sill, the
    /// B-pillar): ξ ahead of the CG and η left, m (ISO `AC` `X`).
    Body([f64; 2]),
    /// An accelerometer along the body x axis on chain mass `i` (left chain
    /// first, each from the front; a side member's front end, a crash box).
    Chain(usize),
    /// An accelerometer along the body y axis at a body point (ISO `AC` `Y`):
    /// reads `A_y − ψ̇² η + ψ̈ ξ`.
    Lateral([f64; 2]),
    /// A yaw-rate sensor (ISO `AV` `Z`): the body's angular velocity ψ̇,
    /// the same at every point of the rigid body.
    YawRate,
    /// A displacement along world x of a body point (film, ISO `DS` `X`):
    /// `X + ξ cos ψ − η sin ψ − ξ`.
    Film([f64; 2]),
    /// A displacement of chain mass `i` along the body axis relative to the
    /// body (a string pot across the crush zone, ISO `DS` `X`): u_i.
    Crush(usize),
}

impl Sensor {
    /// How many times its measurement is integrated into the compared
    /// reading: 2 for accelerometers (to displacement, as the thesis
    /// does), 0 for the yaw rate (compared as measured: its noise is white
    /// there) and for displacements.
    pub fn integrations(&self) -> usize {
        match self {
            Sensor::Body(_) | Sensor::Chain(_) | Sensor::Lateral(_) => 2,
            Sensor::YawRate | Sensor::Film(_) | Sensor::Crush(_) => 0,
        }
    }

    /// Whether it measures a displacement (film, string pot): compared
    /// less its value at time zero, and its pre-trigger is not a bias.
    pub fn displacement(&self) -> bool {
        matches!(self, Sensor::Film(_) | Sensor::Crush(_))
    }

    /// Whether it is an accelerometer along the body x axis (the kind
    /// every study had; their residuals keep weight 1, m).
    pub fn along_x(&self) -> bool {
        matches!(self, Sensor::Body(_) | Sensor::Chain(_))
    }

    /// Its chain mass, if it sits on one.
    fn chain(&self) -> Option<usize> {
        match *self {
            Sensor::Chain(i) | Sensor::Crush(i) => Some(i),
            _ => None,
        }
    }

    /// Its body point, if it sits on one.
    fn body(&self) -> Option<[f64; 2]> {
        match *self {
            Sensor::Body(p) | Sensor::Lateral(p) | Sensor::Film(p) => Some(p),
            _ => None,
        }
    }
}

/// Histories of a replay, at the input's samples.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Driven {
    /// Time from the first sample, s.
    pub time: Vec<f64>,
    /// CG displacement along world x, m.
    pub x: Vec<f64>,
    /// CG displacement along world y, m.
    pub y: Vec<f64>,
    /// Yaw, rad (counter-clockwise seen from above).
    pub yaw: Vec<f64>,
    /// World-x displacement of each sensor's point, m (outer: sensors; the
    /// CG's for a yaw-rate sensor).
    pub sensor_x: Vec<Vec<f64>>,
    /// What each sensor reads in its compared domain
    /// ([`Sensor::integrations`]): an x accelerometer's body-x acceleration
    /// `A_x − ψ̈ η − ψ̇² ξ` integrated twice from the start speed, m (equal
    /// to `sensor_x` while the yaw stays small); a lateral one's
    /// `A_y + ψ̈ ξ − ψ̇² η` twice from rest, m; the yaw rate ψ̇, rad/s; a
    /// displacement as it is, m.
    pub sensor_reading: Vec<Vec<f64>>,
    /// Compressive force at the left side-member tip, N.
    pub side_force_left: Vec<f64>,
    /// Compressive force at the right side-member tip, N.
    pub side_force_right: Vec<f64>,
    /// Displacement u_i of each chain mass along the body axis, m (left chain first).
    pub chains: Vec<Vec<f64>>,
}

/// The largest speed of a replay's car at time zero, m/s, either sign
/// (a speed of 1e300 left "no start could be evaluated"; docs/limits.md).
pub const MAX_SPEED: f64 = 1000.0;

/// Most samples of one replay (as a simulation's output, docs/limits.md).
pub const MAX_SAMPLES: usize = 10_000_000;

fn check(input: &Drive, masses: usize) -> Result<usize, PlanarError> {
    require(
        "step",
        input.step,
        "s",
        "must be positive",
        input.step > 0.0,
    )?;
    require(
        "speed",
        input.speed,
        "m/s",
        &format!("finite, at most {MAX_SPEED} m/s in size (a crash test's is a few m/s)"),
        input.speed.abs() <= MAX_SPEED,
    )?;
    crate::car::check_arm(input.arm)?;
    let samples = input.loads.first().map_or(0, |l| l.force.len());
    require(
        "samples",
        samples as f64,
        "1",
        &format!("between 2 and {MAX_SAMPLES} samples per load"),
        (2..=MAX_SAMPLES).contains(&samples),
    )?;
    for (k, load) in input.loads.iter().enumerate() {
        let name = |what: &str| format!("load[{k}].{what}");
        require(&name("lateral"), load.lateral, "m", "must be finite", true)?;
        if let Some(p) = load.anchor {
            // (1e300 m left "no start could be evaluated"; NaN: not finite)
            let far = p[0].abs().max(p[1].abs()) + 0.0 * (p[0] + p[1]);
            let near = format!("finite, ξ and η within {MAX_SENSOR_PLACE} m of the CG");
            require(&name("anchor"), far, "m", &near, far <= MAX_SENSOR_PLACE)?;
        }
        if let Some(width) = load.cell {
            require(
                &name("cell"),
                width,
                "m",
                "a wall cell's width must be positive and at most 10 m, with its centre on the face as the anchor",
                width > 0.0 && width <= MAX_CELL && load.anchor.is_some(),
            )?;
        }
        let norm = load.direction[0].hypot(load.direction[1]);
        require(
            &name("direction"),
            norm,
            "1",
            "must be a finite, non-zero vector",
            norm > 0.0,
        )?;
        if load.force.len() != samples {
            return Err(parameter(
                &name("force"),
                load.force.len() as f64,
                "samples",
                &format!("all loads need the same {samples} samples"),
            ));
        }
        if let Some(i) = load.force.iter().position(|f| !f.is_finite()) {
            return Err(parameter(
                &format!("load[{k}].force[{i}]"),
                load.force[i],
                "N",
                "must be finite",
            ));
        }
    }
    for (k, s) in input.sensors.iter().enumerate() {
        if let Some(p) = s.body() {
            let far = match p.iter().all(|v| v.is_finite()) {
                true => p[0].abs().max(p[1].abs()),
                false => f64::NAN, // (f64::max passes over a NaN)
            };
            let expected = format!("finite, ξ and η within {MAX_SENSOR_PLACE} m of the CG");
            let place = format!("sensor[{k}] body");
            require(&place, far, "m", &expected, far <= MAX_SENSOR_PLACE)?;
        }
        if let Some(i) = s.chain() {
            require(
                &format!("sensor[{k}] chain mass"),
                i as f64,
                "1",
                &format!("the car has {masses} chain masses (index from 0, left chain first)"),
                i < masses,
            )?;
        }
    }
    Ok(samples)
}

/// The segment forces of an impact as loads at the segment centres, all
/// along `direction` (world; a plane face's normal): an impact's replay.
pub fn segment_loads(result: &crate::PlanarResult, direction: [f64; 2]) -> Vec<Load> {
    result
        .segment_force
        .iter()
        .zip(&result.segment_centres)
        .map(|(force, &lateral)| Load {
            lateral,
            anchor: None,
            cell: None,
            direction,
            force: force.clone(),
        })
        .collect()
}

/// Checks `input` for `car` (finite forces of one length, non-zero
/// directions, sensors on the car); returns the sample count.
pub fn validate(car: &PlanarCar, input: &Drive) -> Result<usize, PlanarError> {
    check(input, car.left().masses.len() + car.right().masses.len())
}

/// Replays given forces on `car`, starting at `input.speed` with everything
/// at rest relative to the body; `safety` is the fraction of the critical step.
pub fn drive(car: &PlanarCar, input: &Drive, safety: f64) -> Result<Driven, PlanarError> {
    drive_substeps(car, input, substeps(car, input.step, safety)?)
}

/// Integration steps per sample interval `step` for `car` at `safety`
/// (the fraction of its critical step), at least 1.
pub fn substeps(car: &PlanarCar, step: f64, safety: f64) -> Result<usize, PlanarError> {
    require("step", step, "s", "must be positive", step > 0.0)?;
    require(
        "safety",
        safety,
        "1",
        "must lie in (0, 1]",
        safety > 0.0 && safety <= 1.0,
    )?;
    let (omega2, omega_c) = model(car).chain_rates(car);
    let substeps = substeps_of(safety * critical_step(omega2, omega_c), step);
    let limit = crate::simulate::MAX_STEPS;
    require(
        "integration steps per sample",
        substeps,
        "1",
        &format!("at most {limit:e}: check the car for an implausibly stiff or light element"),
        substeps <= limit,
    )?;
    Ok(substeps as usize)
}

/// [`drive`] with a given number of integration steps per sample (the
/// replay of an identification keeps one step for every trial car, so the
/// objective does not jump where the step would change; a trial car too
/// stiff for it diverges and is refused).
pub fn drive_substeps(
    car: &PlanarCar,
    input: &Drive,
    substeps: usize,
) -> Result<Driven, PlanarError> {
    let samples = validate(car, input)?;
    let limit = crate::simulate::MAX_STEPS;
    require(
        "integration steps",
        (substeps * samples) as f64,
        "1",
        &format!("at most {limit:e} in all"),
        substeps >= 1 && (substeps * samples) as f64 <= limit,
    )?;
    let mut model = model(car);
    model.half_step = 0.5 * input.step / substeps as f64;
    Replay::new(model, input, &car.beam().segments, substeps).run()
}

/// The sensors' readings of a replay of the first `samples` samples only
/// (the identification's objective: the cases were validated once with
/// [`validate`], every trial car replays them with `substeps` steps a
/// sample, and nothing else is recorded).
pub(crate) fn sensor_readings(
    car: &PlanarCar,
    input: &Drive,
    substeps: usize,
    samples: usize,
) -> Result<Vec<Vec<f64>>, PlanarError> {
    let mut model = model(car);
    model.half_step = 0.5 * input.step / substeps as f64;
    let mut replay = Replay::new(model, input, &car.beam().segments, substeps);
    replay.samples = samples.clamp(2, replay.samples);
    replay.lean = true;
    Ok(replay.run()?.sensor_reading)
}

/// The car's model with no striker face.
fn model(car: &PlanarCar) -> Model {
    let nowhere = Placed::Plane {
        normal: [-1.0, 0.0],
        offset: f64::MAX,
        edge: 0.0,
        sign: 0.0,
    };
    Model::new(car, nowhere, None)
}

/// One replay as a [`Mechanism`] of the one integrator: the given loads
/// placed after each move, the sensors' readings integrated alongside
/// (their own leapfrog: displacement, half-step velocity, acceleration);
/// every buffer is allocated once.
struct Replay<'a> {
    model: Model,
    input: &'a Drive,
    /// The bumper's segments (their loading curves weigh a wall cell's contact).
    segments: &'a [bumpsim_impact::bumper::Bumper],
    directions: Vec<[f64; 2]>,
    substeps: usize,
    samples: usize,
    contact: Contact,
    chain: Vec<f64>,
    /// Side-member tip forces of the last accelerations, N.
    side: [f64; 2],
    /// Per sensor: integrated displacement, velocity (half steps), acceleration.
    readings: Vec<[f64; 3]>,
    /// Record only the sensors' readings (the identification's objective).
    lean: bool,
    /// The yaw's sine and cosine at the current positions.
    axes: (f64, f64),
    out: Driven,
}

impl Mechanism for Replay<'_> {
    type Error = PlanarError;

    fn accelerations(&mut self, q: &[f64], v: &[f64], a: &mut [f64]) {
        let loads = self
            .model
            .accelerations_at(q, v, &self.contact, &mut self.chain, a, self.axes);
        self.side = loads.side;
    }

    fn moved(&mut self, q: &[f64], v: &[f64], k: usize) {
        let t_step = 2.0 * self.model.half_step;
        self.axes = q[2].sin_cos();
        self.model.relax_at(self.axes, v, &mut self.contact, t_step);
        self.readings.iter_mut().for_each(|r| r[0] += t_step * r[1]);
        let (i, within) = (k / self.substeps, k % self.substeps + 1);
        self.place(q, i, within as f64 / self.substeps as f64);
    }

    fn stepped(&mut self, s: &Stepped<'_>) {
        self.sense(s.q, s.before, s.a);
        self.readings
            .iter_mut()
            .for_each(|r| r[1] += s.length * r[2]);
    }

    fn record(&mut self, k: usize, state: &Leapfrog) -> Result<Control, PlanarError> {
        let i = k / self.substeps;
        self.record_sample(i, state.q())?;
        Ok(match i + 1 >= self.samples {
            true => Control::Stop,
            false => Control::Continue,
        })
    }
}

impl<'a> Replay<'a> {
    fn new(
        model: Model,
        input: &'a Drive,
        segments: &'a [bumpsim_impact::bumper::Bumper],
        substeps: usize,
    ) -> Replay<'a> {
        let directions = input
            .loads
            .iter()
            .map(|l| {
                let norm = l.direction[0].hypot(l.direction[1]);
                [l.direction[0] / norm, l.direction[1] / norm]
            })
            .collect();
        let samples = input.loads[0].force.len();
        let chains = model.masses.len();
        let out = Driven {
            sensor_x: vec![Vec::with_capacity(samples); input.sensors.len()],
            sensor_reading: vec![Vec::with_capacity(samples); input.sensors.len()],
            chains: vec![Vec::with_capacity(samples); chains],
            ..Driven::default()
        };
        Replay {
            contact: Contact::new(input.loads.len()),
            chain: vec![0.0; chains],
            side: [0.0; 2],
            readings: input
                .sensors
                .iter()
                .map(|s| [0.0, if s.along_x() { input.speed } else { 0.0 }, 0.0])
                .collect(),
            lean: false,
            axes: (0.0, 1.0),
            model,
            input,
            segments,
            directions,
            substeps,
            samples,
            out,
        }
    }

    /// Fills the loads at sample `i` plus fraction `f` into the contact
    /// (and the nonlinear links' forces at `q`).
    fn place(&mut self, q: &[f64], i: usize, f: f64) {
        self.model.hold(q, &mut self.contact);
        let (sn, cs) = self.axes;
        for (k, load) in self.input.loads.iter().enumerate() {
            let next = load.force.get(i + 1).copied().unwrap_or(load.force[i]);
            self.contact.total[k] = load.force[i] + f * (next - load.force[i]);
            let d = self.directions[k];
            self.contact.direction[k] = [d[0] * cs + d[1] * sn, -d[0] * sn + d[1] * cs];
            let cell = load.cell.and_then(|w| self.cell_contact(q, k, w, (sn, cs)));
            self.contact.point[k] = match (cell, load.anchor) {
                (Some(eta), _) => self.model.bumper_point(q, eta),
                (None, None) => self.model.bumper_point(q, load.lateral),
                (None, Some(p)) => {
                    let r = [p[0] - q[0], p[1] - q[1]];
                    [r[0] * cs + r[1] * sn, -r[0] * sn + r[1] * cs]
                }
            };
        }
    }

    /// Where load `k`, a wall cell `width` wide, meets the bumper at `q`
    /// (yaw's sine and cosine `axes`): the lateral position (body frame, m)
    /// of the segments crushed into the cell's band, weighted by their
    /// loading force at their penetration; the band's segment nearest the
    /// face when none is crushed (times [`Drive::arm`]); `None` without one.
    fn cell_contact(&self, q: &[f64], k: usize, width: f64, (sn, cs): (f64, f64)) -> Option<f64> {
        let load = &self.input.loads[k];
        let anchor = load.anchor?;
        let normal = self.directions[k];
        let tangent = [-normal[1], normal[0]];
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        let (face, centre) = (dot(normal, anchor), dot(tangent, anchor));
        let (e, n) = ([cs, sn], [-sn, cs]);
        let (mut sum, mut weighted, mut nearest) = (0.0, 0.0, None::<(f64, f64)>);
        for (segment, &eta) in self.segments.iter().zip(&self.model.segment_y) {
            let b = self.model.bumper_point(q, eta);
            let p = [
                q[0] + b[0] * e[0] + b[1] * n[0],
                q[1] + b[0] * e[1] + b[1] * n[1],
            ];
            if (dot(tangent, p) - centre).abs() > 0.5 * width {
                continue;
            }
            let depth = face - dot(normal, p);
            if nearest.is_none_or(|(d, _)| depth > d) {
                nearest = Some((depth, eta));
            }
            if depth > 0.0 {
                let w = segment.loading_force(depth);
                sum += w;
                weighted += w * eta;
            }
        }
        match sum > 0.0 {
            true => Some(self.input.arm * weighted / sum),
            false => nearest.map(|(_, eta)| self.input.arm * eta),
        }
    }

    /// A sensor's body-frame point (ξ, η) at `q`, m, and its acceleration
    /// along the body axis relative to the body (from the accelerations `a`), m/s².
    fn point(&self, sensor: Sensor, q: &[f64], a: &[f64]) -> ([f64; 2], f64) {
        match (sensor.body(), sensor.chain()) {
            (Some(p), _) => (p, 0.0),
            (None, Some(i)) => ([self.model.x_f + q[3 + i], self.model.eta[i]], a[3 + i]),
            (None, None) => ([0.0; 2], 0.0),
        }
    }

    /// Sensor `k`'s reading at `q` ([`Driven::sensor_reading`]).
    fn reading(&self, k: usize, q: &[f64]) -> f64 {
        let (sn, cs) = self.axes;
        match self.input.sensors[k] {
            Sensor::YawRate => self.readings[k][0],
            Sensor::Film([xi, eta]) => q[0] + xi * cs - eta * sn - xi,
            Sensor::Crush(i) => q[3 + i],
            _ => self.readings[k][0],
        }
    }

    /// Body-x acceleration of each x accelerometer `A_x − ψ̈ η − ψ̇² ξ (+ ü_i)`
    /// (a lateral one's `A_y + ψ̈ ξ − ψ̇² η`) into its reading, with ψ̇ at
    /// the full step estimated as in the solve from the half-step
    /// velocities `v` and the accelerations `a`.
    fn sense(&mut self, q: &[f64], v: &[f64], a: &[f64]) {
        let (sn, cs) = self.axes;
        let along = a[0] * cs + a[1] * sn;
        let across = -a[0] * sn + a[1] * cs;
        let rate = v[2] + self.model.half_step * a[2];
        for k in 0..self.input.sensors.len() {
            let sensor = self.input.sensors[k];
            let ([xi, eta], relative) = self.point(sensor, q, a);
            self.readings[k][2] = match sensor {
                Sensor::Lateral(_) => across + a[2] * xi - rate * rate * eta,
                // the rate itself, not integrated: no velocity moves it on
                Sensor::YawRate => {
                    self.readings[k][0] = rate;
                    0.0
                }
                _ => along - a[2] * eta - rate * rate * xi + relative,
            };
        }
    }

    fn run(mut self) -> Result<Driven, PlanarError> {
        let t_step = 2.0 * self.model.half_step;
        let q = vec![0.0; self.model.dof()];
        let mut v = vec![0.0; self.model.dof()];
        v[0] = self.input.speed;
        self.place(&q, 0, 0.0);
        let mut state = Leapfrog::start(&mut self, q, v, t_step);
        let (every, last) = (self.substeps, (self.samples - 1) * self.substeps);
        state.run(&mut self, every, last)?;
        Ok(self.out)
    }

    fn record_sample(&mut self, i: usize, q: &[f64]) -> Result<(), PlanarError> {
        let time = i as f64 * self.input.step;
        // a step too large grows without bound: past 1e3 m (or rad), diverged
        if !q.iter().all(|x| x.abs() < 1e3) {
            let step = self.input.step / self.substeps as f64;
            return Err(PlanarError::Diverged { time, step });
        }
        for k in 0..self.input.sensors.len() {
            let reading = self.reading(k, q);
            self.out.sensor_reading[k].push(reading);
        }
        if self.lean {
            return Ok(());
        }
        let out = &mut self.out;
        out.time.push(time);
        out.x.push(q[0]);
        out.y.push(q[1]);
        out.yaw.push(q[2]);
        let (sn, cs) = self.axes;
        for (k, s) in self.input.sensors.iter().enumerate() {
            let ([xi, eta], _) = self.point(*s, q, q);
            let rest = match s.chain() {
                Some(_) => self.model.x_f,
                None => xi,
            };
            self.out.sensor_x[k].push(q[0] + xi * cs - eta * sn - rest);
        }
        let out = &mut self.out;
        out.side_force_left.push(self.side[0]);
        out.side_force_right.push(self.side[1]);
        for (history, u) in out.chains.iter_mut().zip(&q[3..]) {
            history.push(*u);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Layout;
    use crate::simulate::{Settings, simulate};
    use crate::striker::{Face, Side, Striker, place};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn car(chain: &MsdModel) -> PlanarCar {
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        PlanarCar::symmetric(chain, &bumper, &Layout::default()).unwrap()
    }

    /// A rigid body pushed along world −x at a lateral offset η by a
    /// constant force: ẍ = −F/M, and as the body turns the force's arm
    /// grows by x_f sin ψ (x_f: bumper ahead of the CG), so
    /// `I_z ψ̈ = F (η cos ψ + x_f sin ψ) ≈ F η + F x_f ψ`, solved by
    /// `ψ = (η/x_f)(cosh(√c t) − 1)` with `c = F x_f / I_z` (the linearisation
    /// errs by O(ψ²) ≈ 1e-7 relative here).
    #[test]
    fn an_offset_push_turns_a_rigid_car_as_newton_euler_says() {
        let rigid = car(&MsdModel::new(vec![1200.0], vec![], vec![]).unwrap());
        let (force, eta, samples) = (1e3, 0.5, 501);
        let load = Load {
            lateral: eta,
            anchor: None,
            cell: None,
            direction: [-1.0, 0.0],
            force: vec![force; samples],
        };
        let input = Drive {
            step: 1e-4,
            loads: vec![load],
            speed: 2.0,
            arm: 1.0,
            sensors: vec![Sensor::Body([1.0, 0.7]), Sensor::Body([1.0, -0.7])],
        };
        let r = drive(&rigid, &input, 0.05).unwrap();
        let t: f64 = 0.05;
        let x = 2.0 * t - 0.5 * force / 1200.0 * t * t;
        let c: f64 = force * 2.0 / 2000.0;
        let yaw = eta / 2.0 * ((c.sqrt() * t).cosh() - 1.0);
        assert!(
            (r.x[samples - 1] - x).abs() < 1e-9 * x,
            "{} {x}",
            r.x[samples - 1]
        );
        assert!(
            (r.yaw[samples - 1] - yaw).abs() < 1e-6 * yaw,
            "{} {yaw}",
            r.yaw[samples - 1]
        );
        // the sensors see x ∓ η ψ: their difference is the yaw
        let (left, right) = (&r.sensor_x[0], &r.sensor_x[1]);
        let seen = (right[samples - 1] - left[samples - 1]) / 1.4;
        assert!((seen - yaw).abs() < 1e-6 * yaw, "{seen} {yaw}");
    }

    /// An RCAR impact replayed: the segment forces of `simulate`, given as
    /// loads at the segment centres along the face normal, move the car as
    /// the impact did: 5e-7 of peak with the forces linearly interpolated
    /// between 0.1-ms samples (exact on the impact's own step).
    #[test]
    fn replaying_an_impact_s_segment_forces_reproduces_its_motion() {
        let chain = MsdModel::new(vec![12.0, 1250.0], vec![3e3], vec![2.5e6]).unwrap();
        let car = car(&chain);
        let striker = Striker::barrier(Face::plane_in_degrees(10.0, 40.0, Side::Left), 15.0 / 3.6);
        let settings = Settings {
            output_step: 1e-4,
            ..Settings::default()
        };
        let r = simulate(&car, &striker, &settings).unwrap();
        let Placed::Plane { normal, .. } = place(&car, &striker).unwrap() else {
            unreachable!("a plane face")
        };
        let loads = segment_loads(&r, normal);
        let input = Drive {
            step: 1e-4,
            loads,
            speed: 15.0 / 3.6,
            arm: 1.0,
            sensors: vec![],
        };
        let d = drive(&car, &input, 0.05).unwrap();
        let gap = |a: &[f64], b: &[f64]| {
            let peak = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            a.iter()
                .zip(b)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
                / peak
        };
        let (dx, dyaw) = (gap(&r.x, &d.x), gap(&r.yaw, &d.yaw));
        eprintln!("replay: x {dx:.1e}, yaw {dyaw:.1e} of peak");
        assert!(dx < 1e-5 && dyaw < 1e-5, "x {dx:e}, yaw {dyaw:e}");
        assert!(
            r.yaw.iter().fold(0.0f64, |m, v| m.max(v.abs())) > 1e-3,
            "it turns"
        );
    }

    #[test]
    fn bad_input_is_refused_by_name() {
        let rigid = car(&MsdModel::new(vec![1200.0], vec![], vec![]).unwrap());
        let load = |force: Vec<f64>, direction| Load {
            lateral: 0.0,
            anchor: None,
            cell: None,
            direction,
            force,
        };
        let input = |loads| Drive {
            step: 1e-4,
            loads,
            speed: 0.0,
            arm: 1.0,
            sensors: vec![],
        };
        let cases = [
            (
                input(vec![load(vec![1.0, f64::NAN], [-1.0, 0.0])]),
                "load[0].force[1]",
            ),
            (
                input(vec![load(vec![1.0; 3], [0.0, 0.0])]),
                "load[0].direction",
            ),
            (
                input(vec![
                    load(vec![1.0; 3], [-1.0, 0.0]),
                    load(vec![1.0; 4], [-1.0, 0.0]),
                ]),
                "load[1].force",
            ),
            (input(vec![load(vec![1.0], [-1.0, 0.0])]), "samples"),
            (
                Drive {
                    step: f64::NAN,
                    ..input(vec![load(vec![1.0; 3], [-1.0, 0.0])])
                },
                "step",
            ),
        ];
        for (bad, name) in cases {
            let err = drive(&rigid, &bad, 0.05).unwrap_err().to_string();
            assert!(err.starts_with(name), "{err}");
        }
    }
}
