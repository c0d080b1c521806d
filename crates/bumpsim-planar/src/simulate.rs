//! Planar impact simulation by explicit central differences (spec §9).
//!
//! **Equations.** Generalised coordinates: the body's CG `R = (X, Y)`, yaw ψ,
//! the chain masses' displacements `u_i` along the body axis `e = (cos ψ, sin ψ)`
//! (`n = (−sin ψ, cos ψ)`), and the pendulum travel `s`. Chain mass i sits at
//! body coordinates `(ξ_i, η_i) = (x_f + u_i, ±b)`, so its acceleration is
//! `p̈_i = R̈ + ψ̈(ξ_i n − η_i e) − ψ̇²(ξ_i e + η_i n) + ü_i e + 2ψ̇ u̇_i n`.
//! With `Q_i` the force along `e` on mass i (chain links and its lever share
//! of the bumper forces), `F_e`, `F_n` the external forces (striker, tyres) in
//! body axes and `M_z` their moment about the CG, Newton's law for each chain
//! mass along `e`, and the linear and angular momentum of the whole car give,
//! with `A = (A_x, A_y)` = R̈ in body axes and the guide forces eliminated:
//!
//! - `M A_x = F_e − Σ Q_i`
//! - `(M + Σm_i) A_y + (Σ m_i ξ_i) ψ̈ = F_n − Σ m_i (2ψ̇u̇_i − ψ̇² η_i)`
//! - `(Σ m_i ξ_i) A_y + (I_z + Σ m_i ξ_i²) ψ̈ = M_z + Σ η_i Q_i − Σ m_i ξ_i (2ψ̇u̇_i − ψ̇² η_i)`
//! - `ü_i = Q_i / m_i − A_x + ψ̈ η_i + ψ̇² ξ_i`
//!
//! a 2 × 2 solve per step (the chain block of the mass matrix is diagonal, so
//! its Schur complement is explicit). The pendulum: `m_p s̈ = F_x` (the x
//! part of the striker force on the car; its guide carries the rest).
//!
//! **Integrator.** The one integrator of every impact,
//! [`bumpsim_core::leapfrog`] (the 1-D impact and the replay of
//! [`crate::drive`] run it too), central differences in leapfrog form: `v_{n+½} = v_{n−½} + T a_n`,
//! `q_{n+1} = q_n + T v_{n+½}`, with the dissipative forces (dampers, tyre
//! friction) from `v_{n−½}` as in the 1-D scheme, and the inertial Coriolis
//! and centrifugal terms from the full-step estimate `v_{n−½} + (T/2) a_{n−1}`
//! (second order: a freely spinning car with vibrating chains keeps its
//! momentum to ~1e-8; with `v_{n−½}` alone the drift was ~1e-6). Why this rather than an
//! adaptive implicit ODE solver: the bumper characteristics are history
//! dependent (loading and elastic unloading, §5), and an explicit scheme
//! evaluates each once per step in its natural order, with no rejected steps
//! that would have to roll the crush history back; the contact and stick–slip
//! non-linearities are non-smooth, which costs implicit solvers many Newton
//! failures; the system is small, so a step from the stiffest element is
//! cheap (a 10-segment 8 km/h impact takes about a millisecond); and with the
//! same step and arithmetic a symmetric planar car reproduces the 1-D result
//! to rounding. Step: the one rule of [`bumpsim_core::leapfrog`],
//! `T = safety · min(2/ω, 2/ω_c)`, with ω² and ω_c the Gershgorin bounds of
//! M⁻¹K and M⁻¹C over the coordinates (steepest segment slope plus 4 k_b,
//! chain links, tyre friction linearised as `μN/v_s`), rounded down to divide
//! the output interval. Default safety 0.05 as in the
//! 1-D integrator. The hot loop allocates nothing (histories are reserved).
//!
//! **Balances.** Energy: `E0 = T + springs + bending + dampers + crush + friction`,
//! crush work `∫ R dd` by the trapezoidal rule per segment (a loaded segment
//! that slides off the face's edge keeps its crush work: its stored elastic
//! energy is lost with it, not returned), damper and friction dissipation as
//! the work of each step's force on the step's mean velocity
//! `(v_{n−½} + v_{n+½})/2` (the leapfrog's own kinetic-energy identity). Momentum: the change of linear and angular
//! momentum (about the world origin) of car and pendulum against the
//! trapezoidal impulse of the external forces (fixed striker, tyres, guide).
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_impact::bumper::Bumper;
//! use bumpsim_planar::{PlanarCar, Striker, Face, Settings, simulate};
//! use bumpsim_planar::car::Layout;
//! let chain = MsdModel::new(vec![1000.0], vec![], vec![]).unwrap();
//! let bumper = Bumper::three_part(1e6, 1e9, 1e6).unwrap(); // linear, elastic
//! let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
//! let r = simulate(&car, &Striker::barrier(Face::flat(), 2.0), &Settings::default()).unwrap();
//! let expected = 2.0 * (1000.0f64 / 1e6).sqrt();              // V0 sqrt(m/s)
//! assert!((r.max_compression - expected).abs() < 1e-3 * expected);
//! assert!(r.yaw.iter().all(|y| y.abs() < 1e-12));             // a symmetric hit does not turn
//! ```

use crate::car::{PlanarCar, PlanarError, require};
use crate::dynamics::{Contact, Loads, Model};
use crate::result::{EnergyBalance, MomentumBalance, PlanarResult};
use crate::striker::{Motion, Striker, place};
use bumpsim_core::leapfrog::{Control, Leapfrog, Mechanism, Stepped, critical_step, stable_step};
use refine::{better, open};

mod refine;

/// Integration settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Fraction of the critical step, (0, 1].
    pub safety: f64,
    /// Interval of the recorded histories, s.
    pub output_step: f64,
    /// Longest simulated time, s.
    pub duration: f64,
    /// A given integration step, s, instead of the one from `safety`.
    pub step: Option<f64>,
    /// Stop a tenth of the contact time after the contact ends, once car
    /// and striker no longer close along x (a beam that chatters off the
    /// face and back has not ended its impact).
    pub stop_after_contact: bool,
    /// Initial gap, m (≥ 0): the striker starts this far ahead of its first
    /// touch along x, as a lab sets a car or pendulum up before the impact.
    /// The recorded times count from the nominal first touch (time zero of
    /// ISO 6487 and SAE J211: first contact), so the record starts at
    /// `−gap / speed`; `duration` counts from the start.
    pub gap: f64,
    /// How many times a run whose energy balance misses
    /// [`ENERGY_TOLERANCE`] is repeated at half the safety factor (0: never;
    /// a given `step` is never refined). The result is the run that closes,
    /// else the one that closes best; its `step` says which ran. Off by
    /// default, so a search's objective keeps one step; the engine's
    /// `impact` refines three times (a pendulum of a few kg rattling against
    /// a 4 kg tip left up to 0.33 % open at safety 0.05, and closed within
    /// three halvings: docs/planar.md).
    pub refine: u32,
}

/// The energy balance's largest relative error that passes without a
/// warning (and without a refinement, [`Settings::refine`]).
pub const ENERGY_TOLERANCE: f64 = 1e-3;

impl Default for Settings {
    fn default() -> Self {
        Settings {
            safety: 0.05,
            output_step: 1e-4,
            duration: 1.0,
            step: None,
            stop_after_contact: true,
            gap: 0.0,
            refine: 0,
        }
    }
}

fn check(settings: &Settings) -> Result<(), PlanarError> {
    let s = settings;
    require(
        "safety",
        s.safety,
        "1",
        "must lie in (0, 1]",
        s.safety > 0.0 && s.safety <= 1.0,
    )?;
    require(
        "output step",
        s.output_step,
        "s",
        "must be positive",
        s.output_step > 0.0,
    )?;
    // below one output step (1e-308 s) it ran one sample, with a warning
    require(
        "duration",
        s.duration,
        "s",
        "must be at least the output step",
        s.duration >= s.output_step,
    )?;
    if let Some(step) = s.step {
        require(
            "step",
            step,
            "s",
            "must be positive and at most the output step",
            step > 0.0 && step <= s.output_step,
        )?;
    }
    require(
        "gap",
        s.gap,
        "m",
        "must be zero or positive and at most 10 m (the striker's start ahead of its first touch)",
        (0.0..=MAX_GAP).contains(&s.gap),
    )?;
    let samples = s.duration / s.output_step;
    require(
        "duration / output step",
        samples,
        "samples",
        "at most 10 million samples",
        samples <= 1e7,
    )
}

/// The largest initial gap, m: ten metres of free travel before a
/// low-speed impact is a set-up error, not a test.
pub const MAX_GAP: f64 = 10.0;

/// Most integration steps one simulation may take (docs/limits.md): about
/// ten seconds of work; an ordinary car needs 10⁴–10⁶.
pub const MAX_STEPS: f64 = 5e7;

/// Refuses a step that would need more than [`MAX_STEPS`] steps for the
/// duration (an implausibly stiff or light element), instead of running for hours.
fn check_steps(step: f64, settings: &Settings) -> Result<(), PlanarError> {
    let steps = settings.duration / step;
    require(
        "integration step",
        step,
        "s",
        &format!(
            "needs {steps:.3e} steps for the {} s duration, above the limit of {MAX_STEPS:e}: check the car for an implausibly stiff or light element, or shorten the duration",
            settings.duration
        ),
        step > 0.0 && steps <= MAX_STEPS,
    )
}

/// Simulates a striker hitting a planar car; a run whose energy balance
/// misses [`ENERGY_TOLERANCE`], or that diverges, is repeated at half the
/// safety factor up to [`Settings::refine`] times (never with a given
/// `step`). A finer run replaces a diverged one whatever it gives, and a
/// finished one only when its balance closes better; else the refining
/// stops.
pub fn simulate(
    car: &PlanarCar,
    striker: &Striker,
    settings: &Settings,
) -> Result<PlanarResult, PlanarError> {
    let mut best = simulate_once(car, striker, settings);
    let mut finer = *settings;
    for _ in 0..settings.refine {
        if settings.step.is_some() || !open(&best) {
            break;
        }
        finer.safety /= 2.0;
        let run = simulate_once(car, striker, &finer);
        if !better(&run, &best) {
            break;
        }
        best = run;
    }
    best
}

/// One run at the settings' step.
fn simulate_once(
    car: &PlanarCar,
    striker: &Striker,
    settings: &Settings,
) -> Result<PlanarResult, PlanarError> {
    check(settings)?;
    let placed = place(car, striker)?;
    let (pendulum, speed) = match striker.motion {
        Motion::Fixed { speed } => (None, speed),
        Motion::Pendulum { mass, speed } => (Some(mass), speed),
    };
    let origin = -settings.gap / speed;
    require(
        "gap",
        settings.gap,
        "m",
        &format!(
            "leaves the striker {} s of free travel at {speed} m/s, not within the {} s duration",
            -origin, settings.duration
        ),
        -origin < settings.duration,
    )?;
    let model = Model::new(car, placed.moved(-settings.gap), pendulum);
    let step = match settings.step {
        Some(step) => step,
        None => {
            let (omega2, omega_c) = model.rates(car);
            stable_step(
                settings.safety * critical_step(omega2, omega_c),
                settings.output_step,
            )
        }
    };
    check_steps(step, settings)?;
    let mut v = vec![0.0; model.dof()];
    match pendulum {
        None => v[0] = speed,
        Some(_) => v[model.travel()] = speed,
    }
    // the balances are relative to the initial kinetic energy: a speed or a
    // pendulum mass that makes it 0 (underflow) or infinite (overflow) gave
    // "energy balance error NaN" with exit 0
    let initial = model.kinetic(&vec![0.0; model.dof()], &v);
    let figure = |x: f64| match x != 0.0 && !(1e-5..1e12).contains(&x.abs()) {
        true => format!("{x:e}"),
        false => format!("{x}"),
    };
    require(
        "striker kinetic energy",
        initial,
        "J",
        &format!(
            "must be positive and finite: the speed {} m/s{} gives no usable closing energy",
            figure(speed),
            pendulum.map_or(String::new(), |m| format!(
                " and the pendulum mass {} kg",
                figure(m)
            ))
        ),
        initial > 0.0,
    )?;
    Run::new(car, model, (step, origin), settings).integrate(v)
}

/// The planar impact as a [`Mechanism`] of the one integrator: the
/// segments' contact after each move, the balances' running sums after each
/// step; the histories are reserved once.
struct Run<'a> {
    car: &'a PlanarCar,
    model: Model,
    step: f64,
    /// The time of the first sample, s (−gap/speed: time zero is the first touch).
    origin: f64,
    settings: &'a Settings,
    contact: Contact,
    previous_crush: Vec<f64>,
    previous_force: Vec<f64>,
    /// Each segment's largest own crush in this run, m (a damaged car's
    /// histories remember earlier runs' too).
    reached: Vec<f64>,
    chain: Vec<f64>,
    /// The loads of the last accelerations and their external resultant
    /// (world force, moment about the origin).
    loads: Loads,
    external: ([f64; 2], f64),
    sums: Sums,
    out: PlanarResult,
}

/// Running sums of the balances.
#[derive(Default)]
struct Sums {
    crush: f64,
    dampers: f64,
    friction: f64,
    impulse: [f64; 2],
    angular_impulse: f64,
    initial: f64,
    p0: [f64; 2],
    /// |p0|, N·s.
    p0_norm: f64,
    l0: f64,
    peak_force: f64,
    /// The part of the last step's damper and friction work after its sample time, J.
    pending: (f64, f64),
}

impl Mechanism for Run<'_> {
    type Error = PlanarError;

    fn accelerations(&mut self, q: &[f64], v: &[f64], a: &mut [f64]) {
        self.loads = self
            .model
            .accelerations(q, v, &self.contact, &mut self.chain, a);
    }

    fn moved(&mut self, q: &[f64], v: &[f64], k: usize) {
        let t = self.time(k);
        self.previous_crush.copy_from_slice(&self.contact.crush);
        self.previous_force.copy_from_slice(&self.contact.force);
        self.model.contact(q, self.car, &mut self.contact);
        let rate = self.car.contact_rate();
        if rate > 0.0 {
            crate::car::rated(&mut self.contact, &self.previous_crush, rate, self.step);
        }
        let c = &self.contact;
        for (j, most) in self.reached.iter_mut().enumerate() {
            *most = most.max(c.crush[j] - c.absorber[j]);
        }
        self.model.relax(q, v, &mut self.contact, self.step);
        self.sums.crush += self.crush_work();
        self.track_contact(t + self.step);
        let bottomed = self.out.bottomed;
        self.out.bottomed = bottomed.or_else(|| self.contact.bottomed(self.car, t + self.step));
        let boxed = self.out.box_bottomed;
        self.out.box_bottomed = boxed.or_else(|| self.model.box_bottomed(q, t + self.step));
    }

    /// The work of forces from `v_{n−½}` over a step is `T F·(v_{n−½} +
    /// v_{n+½})/2`, the leapfrog's own kinetic-energy identity; half of it
    /// belongs after the sample time t_n (`pending`).
    fn stepped(&mut self, s: &Stepped<'_>) {
        let t_step = self.step;
        let (d, f) = self.dissipation(&self.loads, s.before, s.mean);
        let next = self.external(s.q, &self.loads);
        let sums = &mut self.sums;
        if s.half {
            (sums.dampers, sums.friction) = (0.5 * t_step * d, 0.5 * t_step * f);
            sums.pending = (sums.dampers, sums.friction);
            self.external = next;
            return;
        }
        sums.dampers += t_step * d;
        sums.friction += t_step * f;
        sums.pending = (0.5 * t_step * d, 0.5 * t_step * f);
        let [fx, fy] = self.loads.contact;
        // |F| ≤ |F_x| + |F_y|: the magnitude only when it may be a new peak
        if fx.abs() + fy.abs() > sums.peak_force {
            sums.peak_force = sums.peak_force.max(fx.hypot(fy));
        }
        let ext = self.external;
        sums.impulse[0] += 0.5 * t_step * (ext.0[0] + next.0[0]);
        sums.impulse[1] += 0.5 * t_step * (ext.0[1] + next.0[1]);
        sums.angular_impulse += 0.5 * t_step * (ext.1 + next.1);
        self.external = next;
    }

    fn record(&mut self, k: usize, state: &Leapfrog) -> Result<Control, PlanarError> {
        let t = self.time(k);
        let (q, v) = (state.q(), state.velocities());
        if !q.iter().chain(v).all(|x| x.is_finite()) {
            return Err(PlanarError::Diverged {
                time: t,
                step: self.step,
            });
        }
        self.record_sample(t, q, v);
        // a passive car cannot end with more than twice the energy it
        // started with: an error beyond 100 % is an unstable integration,
        // not a result (side members 1000 m apart gave 1.8e10 with exit 0
        // and a warning)
        if self.out.energy.relative_error > 1.0 {
            return Err(PlanarError::Diverged {
                time: t,
                step: self.step,
            });
        }
        Ok(Control::Continue)
    }

    fn finished(&self, k: usize, state: &Leapfrog) -> bool {
        let t = self.time(k);
        self.out.contact_end.is_some_and(|end| {
            self.settings.stop_after_contact
                && t > end + 0.1 * (end - self.out.contact_start.unwrap_or(0.0))
                && self.closing(state.velocities()) <= 0.0
        })
    }
}

impl<'a> Run<'a> {
    /// `clock`: the integration step and the time of the first sample, s.
    fn new(
        car: &'a PlanarCar,
        mut model: Model,
        clock: (f64, f64),
        settings: &'a Settings,
    ) -> Run<'a> {
        let (step, origin) = clock;
        model.half_step = 0.5 * step;
        let segments = car.beam().segments.len();
        let masses = model.masses.len();
        let samples = ((settings.duration / settings.output_step).ceil() as usize + 2).min(200_000);
        let chain = vec![0.0; model.masses.len()];
        Run {
            car,
            model,
            step,
            origin,
            settings,
            contact: Contact::damaged(segments, car.damage()),
            previous_crush: vec![0.0; segments],
            previous_force: vec![0.0; segments],
            reached: vec![0.0; segments],
            chain,
            loads: Loads::default(),
            external: ([0.0; 2], 0.0),
            sums: Sums::default(),
            out: PlanarResult::with_capacity(segments, masses, samples),
        }
    }

    /// The time of step `k`, s.
    fn time(&self, k: usize) -> f64 {
        self.origin + k as f64 * self.step
    }

    /// External force (world, N) and moment about the origin (N·m) on car and pendulum.
    fn external(&self, q: &[f64], loads: &Loads) -> ([f64; 2], f64) {
        let r = [q[0], q[1]];
        let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
        let mut force = loads.tyre;
        let mut moment = loads.tyre_moment + cross(r, loads.tyre);
        let contact_moment = loads.contact_moment + cross(r, loads.contact);
        match self.model.pendulum {
            None => {
                force[0] += loads.contact[0];
                force[1] += loads.contact[1];
                moment += contact_moment;
            }
            Some(_) => {
                // the guide keeps the pendulum from moving sideways and turning
                force[1] += loads.contact[1];
                let reference = self.model.face.moved(q[self.model.travel()]).reference();
                moment += cross(reference, [-loads.contact[0], 0.0]) + contact_moment;
            }
        }
        (force, moment)
    }

    /// Integrates from rest positions with initial velocities `v0`.
    fn integrate(mut self, v0: Vec<f64>) -> Result<PlanarResult, PlanarError> {
        let q = vec![0.0; self.model.dof()];
        self.sums.initial = self.model.kinetic(&q, &v0);
        (self.sums.p0, self.sums.l0) = self.model.momentum(&q, &v0);
        self.sums.p0_norm = self.sums.p0[0].hypot(self.sums.p0[1]);
        self.model.contact(&q, self.car, &mut self.contact);
        let step = self.step;
        let mut state = Leapfrog::start(&mut self, q, v0, step);
        let every = (self.settings.output_step / self.step).round().max(1.0) as usize;
        let limit = (self.settings.duration / self.step).ceil() as usize;
        state.run(&mut self, every, limit)?;
        Ok(self.finish(state.q(), state.velocities()))
    }

    /// Powers dissipated by the dampers (forces from `v`) and the tyres
    /// (`loads`) on the motion at velocities `mean`, W.
    fn dissipation(&self, loads: &Loads, v: &[f64], mean: &[f64]) -> (f64, f64) {
        let tyre = loads.tyre[0] * mean[0] + loads.tyre[1] * mean[1] + loads.tyre_moment * mean[2];
        (self.model.damper_power(v, mean), -tyre)
    }

    fn crush_work(&self) -> f64 {
        let c = &self.contact;
        (0..c.crush.len())
            .filter(|&j| !c.switched[j])
            .map(|j| {
                0.5 * (self.previous_force[j] + c.force[j]) * (c.crush[j] - self.previous_crush[j])
            })
            .sum()
    }

    /// The speed at which car and striker still close along x, m/s (car CG
    /// forwards plus pendulum travel): a contact that ended while they
    /// close is a bounce of the beam, not the end of the impact.
    fn closing(&self, v: &[f64]) -> f64 {
        let travel = match self.model.pendulum {
            Some(_) => v[self.model.travel()],
            None => 0.0,
        };
        v[0] + travel
    }

    fn track_contact(&mut self, t: f64) {
        let touching = self.contact.total.iter().any(|&f| f != 0.0);
        match (self.out.contact_start, self.out.contact_end, touching) {
            (None, _, true) => self.out.contact_start = Some(t),
            (Some(_), None, false) => self.out.contact_end = Some(t),
            // a stiff beam can chatter off the face and back: the contact
            // ends at its last separation, not its first
            (Some(_), Some(_), true) => self.out.contact_end = None,
            _ => {}
        }
    }

    fn energy(&self, q: &[f64], v: &[f64], sums: &Sums) -> EnergyBalance {
        let mut e = EnergyBalance {
            initial: sums.initial,
            kinetic: self.model.kinetic(q, v),
            springs: self.model.spring_energy(q, &self.contact),
            bending: self.model.bending_energy(&self.contact),
            dampers: sums.dampers - sums.pending.0,
            crush: sums.crush,
            friction: sums.friction - sums.pending.1,
            plastic: self.model.plastic_work(&self.contact),
            ..EnergyBalance::default()
        };
        let total = e.kinetic + e.springs + e.bending + e.dampers + e.crush + e.friction;
        let total = total + e.plastic;
        e.relative_error = (total - e.initial).abs() / e.initial;
        e.max_relative_error = self.out.energy.max_relative_error.max(e.relative_error);
        e
    }

    fn momentum(&self, q: &[f64], v: &[f64], sums: &Sums) -> MomentumBalance {
        let (p, l) = self.model.momentum(q, v);
        let p0 = sums.p0;
        let scale = sums.p0_norm;
        let length = self.model.x_f + 0.5 * self.car.beam().width;
        let linear = (p[0] - p0[0] - sums.impulse[0]).hypot(p[1] - p0[1] - sums.impulse[1]) / scale;
        let angular = (l - sums.l0 - sums.angular_impulse).abs() / (scale * length);
        let before = &self.out.momentum;
        MomentumBalance {
            initial_linear: p0,
            final_linear: p,
            external_impulse: sums.impulse,
            linear_residual: before.linear_residual.max(linear),
            initial_angular: sums.l0,
            final_angular: l,
            external_angular_impulse: sums.angular_impulse,
            angular_residual: before.angular_residual.max(angular),
            reference_length: length,
        }
    }

    fn record_sample(&mut self, t: f64, q: &[f64], v: &[f64]) {
        let (loads, sums) = (&self.loads, &self.sums);
        let energy = self.energy(q, v, sums);
        let momentum = self.momentum(q, v, sums);
        let model = &self.model;
        let out = &mut self.out;
        out.energy = energy;
        out.momentum = momentum;
        out.time.push(t);
        let [fx, fy] = loads.contact;
        out.force_x.push(fx);
        out.force_y.push(fy);
        out.force.push(fx.hypot(fy));
        let (sn, cs) = model.trig(q[2]);
        let (fe, fn_) = (fx * cs + fy * sn, -fx * sn + fy * cs);
        out.line_of_action.push(
            (fe.abs() > 1e-9 * fn_.abs().max(1.0))
                .then(|| (model.x_f * fn_ - loads.contact_moment) / fe),
        );
        out.side_force_left.push(loads.side[0]);
        out.side_force_right.push(loads.side[1]);
        for (j, (crush, force)) in out.crush.iter_mut().zip(&mut out.segment_force).enumerate() {
            // the segment's own crush: a barrier's absorber takes the rest
            crush.push(self.contact.crush[j] - self.contact.absorber[j]);
            force.push(self.contact.total[j]);
        }
        out.x.push(q[0]);
        out.y.push(q[1]);
        out.yaw.push(q[2]);
        out.yaw_rate.push(v[2]);
        out.velocity_x.push(v[0]);
        out.velocity_y.push(v[1]);
        out.pendulum_travel.push(q[model.travel()]);
        for (history, u) in out.chain_displacement.iter_mut().zip(&q[3..]) {
            history.push(*u);
        }
    }

    fn finish(mut self, q: &[f64], v: &[f64]) -> PlanarResult {
        let sums = &self.sums;
        let segments = &self.car.beam().segments;
        let states = &self.contact.states;
        let energy = self.energy(q, v, sums);
        let mut out = std::mem::take(&mut self.out);
        out.energy = energy;
        out.segment_centres = self.model.segment_y.clone();
        // a damaged car's histories hold the earlier runs' largest crush
        out.max_crush = match self.car.damage().is_empty() {
            true => states.iter().map(|s| s.max_compression).collect(),
            false => self.reached.clone(),
        };
        out.remaining_crush = segments
            .iter()
            .zip(states)
            .map(|(b, s)| b.remaining(s))
            .collect();
        out.damage = states.clone();
        (out.link_set, out.link_reached) = self.model.link_sets(&self.contact);
        out.max_compression = out.max_crush.iter().copied().fold(0.0, f64::max);
        out.peak_force = sums.peak_force;
        out.peak_yaw_rate = out
            .yaw_rate
            .iter()
            .copied()
            .fold(0.0, |a, b| if b.abs() > a.abs() { b } else { a });
        out.step = self.step;
        if out.energy.max_relative_error > ENERGY_TOLERANCE {
            let at = match self.settings.step {
                Some(_) => "the given step".to_string(),
                None => format!("safety {}", self.settings.safety),
            };
            out.warnings.push(format!(
                "the energy balance is off by up to {:.2} % of the initial kinetic energy at a step of {:e} s ({at}): check that the crush stays within the striker's reach, or run at a finer step",
                out.energy.max_relative_error * 100.0,
                self.step
            ));
        }
        if out.contact_start.is_none() {
            out.warnings.push(format!(
                "the striker did not touch the car within {} s",
                self.settings.duration
            ));
        } else if out.contact_end.is_none() {
            out.warnings.push(format!(
                "the contact had not ended at {}: raise the duration",
                bumpsim_core::units::format_quantity(
                    out.time.last().copied().unwrap_or(0.0),
                    bumpsim_core::units::Dimension::Time
                )
            ));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::{Axle, Beam, Body, SideChain, Tyres};
    use crate::striker::Placed;
    use bumpsim_impact::bumper::Bumper;

    fn car(mu: f64) -> PlanarCar {
        let body = Body {
            mass: 900.0,
            yaw_inertia: 1200.0,
            cg_behind_bumper: 1.8,
            wheelbase: 2.4,
            cg_behind_front_axle: 1.0,
            track: 1.4,
        };
        let left = SideChain {
            masses: vec![6.0, 30.0],
            dampers: vec![0.0, 50.0],
            springs: vec![8e5, 2e6],
            links: Vec::new(),
        };
        let right = SideChain {
            masses: vec![9.0],
            dampers: vec![20.0],
            springs: vec![1.2e6],
            links: Vec::new(),
        };
        let beam = Beam {
            width: 1.5,
            side_member_spacing: 1.0,
            segments: vec![Bumper::three_part(1e5, 5e3, 4e5).unwrap(); 4],
            bending: 0.0,
            block: None,
        };
        let axle = Axle::sliding(mu, mu);
        let tyres = Tyres {
            front: axle,
            rear: axle,
            slip_speed: 0.05,
        };
        PlanarCar::new(body, left, right, beam, tyres).unwrap()
    }

    /// The car spins and translates freely while its chains vibrate, far from
    /// any face: the Coriolis and centrifugal coupling of chains and body.
    fn free_flight(mu: f64) -> PlanarResult {
        let car = car(mu);
        let far = Placed::Plane {
            normal: [-1.0, 0.0],
            offset: -1e3,
            edge: 0.0,
            sign: 0.0,
        };
        let model = Model::new(&car, far, None);
        let settings = Settings {
            duration: 0.5,
            ..Settings::default()
        };
        let (omega2, omega_c) = model.rates(&car);
        let step = stable_step(0.05 * critical_step(omega2, omega_c), 1e-4);
        let v = vec![1.5, -0.4, 2.5, 0.3, -0.2, 0.4, 0.0];
        Run::new(&car, model, (step, 0.0), &settings)
            .integrate(v)
            .unwrap()
    }

    #[test]
    fn a_free_spinning_car_keeps_its_momentum_and_energy() {
        let r = free_flight(0.0);
        assert!(r.yaw.last().unwrap().abs() > 1.0, "it really spins");
        let m = r.momentum;
        let scale = m.initial_linear[0].hypot(m.initial_linear[1]);
        let dp = (m.final_linear[0] - m.initial_linear[0])
            .hypot(m.final_linear[1] - m.initial_linear[1]);
        eprintln!(
            "free flight: dP/P {:.1e}, dL/L {:.1e}",
            dp / scale,
            (m.final_angular - m.initial_angular).abs() / m.initial_angular.abs()
        );
        assert!(dp <= 1e-6 * scale, "{m:?}");
        assert!(m.external_impulse == [0.0, 0.0] && m.external_angular_impulse == 0.0);
        let dl = (m.final_angular - m.initial_angular).abs();
        assert!(dl <= 1e-6 * m.initial_angular.abs(), "{m:?}");
        assert!(
            m.linear_residual <= 1e-6 && m.angular_residual <= 1e-6,
            "{m:?}"
        );
        assert!(r.energy.max_relative_error <= 1e-3, "{:?}", r.energy);
        assert!(r.warnings.iter().any(|w| w.contains("did not touch")));
    }

    #[test]
    fn tyre_friction_stops_a_sliding_car_and_dissipates_its_energy() {
        let r = free_flight(0.9);
        let e = r.energy;
        assert!(e.kinetic < 1e-3 * e.initial, "{e:?}");
        assert!(
            e.friction > 0.9 * e.initial && e.max_relative_error <= 1e-3,
            "{e:?}"
        );
        assert!(r.momentum.linear_residual <= 1e-6, "{:?}", r.momentum);
    }
}

#[cfg(test)]
mod hostile;
