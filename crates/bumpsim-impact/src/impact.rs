//! Impact simulation: a bumper characteristic between an impactor and an MSD
//! car, or between a moving car and a rigid barrier (papers A, B; spec §5).
//!
//! Bodies move along x. With an impactor (pendulum) of mass `m_p` at speed
//! `V0` hitting the car at rest, the bumper compression is `d = x_p − x_1`;
//! with the car at `V0` hitting a rigid barrier, `d = x_1`. The bumper force
//! `R(d)` (see [`bumper`](crate::bumper)) pushes the sides apart; springs and
//! dampers join consecutive car masses:
//!
//! `m_i x_i'' = Σ links − R` (barrier, on m1), `m_p x_p'' = −R`, `m_1 x_1'' = … + R` (impactor).
//!
//! Integration: the one integrator of every impact,
//! [`bumpsim_core::leapfrog`] (the explicit central-difference scheme of
//! paper A in its leapfrog form), `v_{n+½} = v_{n−½} + T a_n`, `x_{n+1} = x_n + T v_{n+½}`, with
//! damper forces from `v_{n−½}`. The step is its one rule, `T = safety · min(2/ω, 2/ω_c)`
//! where ω² bounds the eigenvalues of `M⁻¹K` (Gershgorin, with the steepest
//! bumper slope) and `ω_c` does the same for `M⁻¹C`; default safety 0.05,
//! rounded down so that an output interval holds a whole number of steps.
//! Contact end — the force returns to zero while the sides separate — is
//! located within a step by linear interpolation of the compression.
//!
//! Energy balance: `E0 = KE + E_springs + W_dampers + W_bumper`, with the
//! bumper work `∫ R dd` (trapezoidal in d) and the damper dissipation summed
//! per step; its relative error is reported.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_impact::bumper::Bumper;
//! use bumpsim_impact::impact::{Scenario, simulate, Options};
//! let car = MsdModel::new(vec![1000.0], vec![], vec![]).unwrap();
//! let bumper = Bumper::three_part(1e6, 1e9, 1e6).unwrap();  // linear, elastic
//! let r = simulate(&car, &bumper, Scenario::Barrier { speed: 2.0 }, &Options::default()).unwrap();
//! let expected = 2.0 * (1000.0f64 / 1e6).sqrt();           // V0 sqrt(m/s)
//! assert!((r.max_compression - expected).abs() < 1e-3 * expected);
//! ```

use crate::bumper::{Bumper, BumperState};
use bumpsim_core::leapfrog::{Control, Leapfrog, Mechanism, Stepped, critical_step, stable_step};
use bumpsim_core::model::MsdModel;
use serde::Serialize;

/// Why an impact cannot be simulated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ImpactError {
    /// A scenario or option value is out of range.
    #[error("impact {name} = {value:?}: {expected}")]
    Parameter {
        /// The parameter.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What is allowed.
        expected: &'static str,
    },
    /// The load case is not said, or names no preset.
    #[error("{0}")]
    LoadCase(String),
    /// The run would need more than [`MAX_STEPS`] integration steps.
    #[error(
        "the car and bumper need a stable step of {} for the {} run: {steps:.3e} steps, at most 5e7 (limit MAX_STEPS); its lightest mass on its stiffest spring, damper or bumper slope governs",
        bumpsim_core::units::format_quantity(*step, bumpsim_core::units::Dimension::Time),
        bumpsim_core::units::format_quantity(*duration, bumpsim_core::units::Dimension::Time)
    )]
    TooManySteps {
        /// The stable step, s.
        step: f64,
        /// The simulated duration, s.
        duration: f64,
        /// Steps the run would take.
        steps: f64,
    },
    /// The bodies never touched or never separated within the duration.
    #[error(
        "no contact ended within {duration} s (the simulated duration): the impact does not separate; check the bumper's unloading curve and the speed"
    )]
    NoSeparation {
        /// The simulated duration, s.
        duration: f64,
    },
}

/// What hits what.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Scenario {
    /// An impactor (pendulum) of `mass` kg at `speed` m/s hits the car at rest.
    Impactor {
        /// Impactor mass, kg.
        mass: f64,
        /// Impact speed, m/s.
        speed: f64,
    },
    /// The car at `speed` m/s hits a rigid barrier.
    Barrier {
        /// Impact speed, m/s.
        speed: f64,
    },
}

/// Impact speeds a scenario may have, m/s (1 mm/s to 3600 km/h): a slower
/// impact's energy and compression fall below what the integration resolves
/// (1e-300 m/s gave a NaN energy balance), a faster one is no bumper impact.
pub const SPEED_RANGE: std::ops::RangeInclusive<f64> = 1e-3..=1e3;

/// Impactor masses a scenario may have, kg (1 g to 10 000 t): beyond them the
/// kinetic energy overflows (1e308 kg gave an infinite initial energy) or
/// underflows, and no test rig swings such a pendulum.
pub const MASS_RANGE: std::ops::RangeInclusive<f64> = 1e-3..=1e7;

impl Scenario {
    /// Refuses a speed outside [`SPEED_RANGE`] or an impactor mass outside
    /// [`MASS_RANGE`], naming the parameter and the range.
    ///
    /// ```
    /// use bumpsim_impact::impact::Scenario;
    /// assert!(Scenario::Impactor { mass: 1450.0, speed: 1.67 }.check().is_ok());
    /// let slow = Scenario::Barrier { speed: 1e-300 }.check().unwrap_err();
    /// assert!(slow.to_string().contains("speed (m/s) = 1e-300"), "{slow}");
    /// assert!(Scenario::Impactor { mass: 1e308, speed: 2.0 }.check().is_err());
    /// ```
    pub fn check(&self) -> Result<(), ImpactError> {
        let speed = match *self {
            Scenario::Impactor { mass, speed } => {
                let expected = "from 0.001 to 1e7 kg (limit MASS_RANGE: 1 g to 10 000 t)";
                check(
                    "impactor mass (kg)",
                    mass,
                    expected,
                    MASS_RANGE.contains(&mass),
                )?;
                speed
            }
            Scenario::Barrier { speed } => speed,
        };
        check(
            "speed (m/s)",
            speed,
            "from 0.001 to 1000 m/s (limit SPEED_RANGE: 1 mm/s to 3600 km/h; an impact needs a closing speed)",
            SPEED_RANGE.contains(&speed),
        )
    }
}

/// Integration options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Fraction of the critical step.
    pub safety: f64,
    /// Interval of the recorded histories, s.
    pub output_step: f64,
    /// Longest simulated time, s.
    pub duration: f64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            safety: 0.05,
            output_step: 1e-4,
            duration: 1.0,
        }
    }
}

/// Energies at the end, J.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyBalance {
    /// Initial kinetic energy.
    pub initial: f64,
    /// Kinetic energy at the end.
    pub kinetic: f64,
    /// Energy in the car's springs at the end.
    pub springs: f64,
    /// Dissipated by the car's dampers.
    pub dampers: f64,
    /// Work done on the bumper (absorbed plus stored elastically).
    pub bumper: f64,
    /// `|E0 − (KE + E_springs + W_dampers + W_bumper)| / E0`.
    pub relative_error: f64,
}

/// Time histories and results of an impact.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ImpactResult {
    /// Body names: `impactor` (if any), then `m1`..`mn`.
    pub bodies: Vec<String>,
    /// Sample times, s.
    pub time: Vec<f64>,
    /// Bumper force, N.
    pub force: Vec<f64>,
    /// Bumper compression, m.
    pub compression: Vec<f64>,
    /// Displacement of each body, m.
    pub displacements: Vec<Vec<f64>>,
    /// Velocity of each body, m/s.
    pub velocities: Vec<Vec<f64>>,
    /// Contact start, s (0: the bodies touch at t = 0).
    pub contact_start: f64,
    /// Contact end, s.
    pub contact_time: f64,
    /// Largest compression, m.
    pub max_compression: f64,
    /// Permanent compression after unloading, m.
    pub remaining_compression: f64,
    /// Largest bumper force, N.
    pub peak_force: f64,
    /// Energy the bumper absorbed (hysteresis), J.
    pub absorbed_energy: f64,
    /// Energy balance.
    pub energy: EnergyBalance,
    /// Integration step, s.
    pub step: f64,
}

struct Chain<'a> {
    car: &'a MsdModel,
    masses: Vec<f64>,
    impactor: bool,
}

impl Chain<'_> {
    /// The car's links: (left body, right body, spring N/m, damper N·s/m).
    fn links(&self) -> impl Iterator<Item = (usize, usize, f64, f64)> + '_ {
        let o = usize::from(self.impactor);
        let pairs = self.car.springs().iter().zip(self.car.dampers());
        pairs
            .enumerate()
            .map(move |(j, (&k, &c))| (o + j, o + j + 1, k, c))
    }

    /// Accelerations of all bodies from positions, half-step velocities and the bumper force.
    fn accelerations(&self, x: &[f64], v: &[f64], force: f64, a: &mut [f64]) {
        a.iter_mut().for_each(|v| *v = 0.0);
        for (i, l, k, c) in self.links() {
            let link = k * (x[i] - x[l]) + c * (v[i] - v[l]);
            a[i] -= link;
            a[l] += link;
        }
        a[0] -= force;
        if self.impactor {
            a[1] += force;
        }
        a.iter_mut().zip(&self.masses).for_each(|(a, m)| *a /= m);
    }

    fn compression(&self, x: &[f64]) -> f64 {
        if self.impactor { x[0] - x[1] } else { x[0] }
    }

    fn spring_energy(&self, x: &[f64]) -> f64 {
        self.links()
            .map(|(i, l, k, _)| 0.5 * k * (x[i] - x[l]).powi(2))
            .sum()
    }

    fn damper_power(&self, v: &[f64]) -> f64 {
        self.links()
            .map(|(i, l, _, c)| c * (v[i] - v[l]).powi(2))
            .sum()
    }

    /// The critical-step bound: Gershgorin on M⁻¹K (with the bumper) and M⁻¹C.
    fn step(&self, bumper: &Bumper, options: &Options) -> f64 {
        let n = self.masses.len();
        let (mut stiff, mut damp) = (vec![0.0; n], vec![0.0; n]);
        for (i, l, k, c) in self.links() {
            for body in [i, l] {
                stiff[body] += 2.0 * k;
                damp[body] += 2.0 * c;
            }
        }
        let s = bumper.stiffest();
        stiff[0] += 2.0 * s;
        if self.impactor {
            stiff[1] += 2.0 * s;
        }
        let omega2 = (0..n)
            .map(|i| stiff[i] / self.masses[i])
            .fold(0.0, f64::max);
        let omega_c = (0..n).map(|i| damp[i] / self.masses[i]).fold(0.0, f64::max);
        stable_step(
            options.safety * critical_step(omega2, omega_c),
            options.output_step,
        )
    }
}

fn check(
    name: &'static str,
    value: f64,
    expected: &'static str,
    ok: bool,
) -> Result<(), ImpactError> {
    match ok && value.is_finite() {
        true => Ok(()),
        false => Err(ImpactError::Parameter {
            name,
            value,
            expected,
        }),
    }
}

/// Simulates an impact until the contact has ended (and a tenth of the
/// contact time after it, to show separation).
pub fn simulate(
    car: &MsdModel,
    bumper: &Bumper,
    scenario: Scenario,
    options: &Options,
) -> Result<ImpactResult, ImpactError> {
    check(
        "safety",
        options.safety,
        "in (0, 1]",
        options.safety > 0.0 && options.safety <= 1.0,
    )?;
    check(
        "output step (s)",
        options.output_step,
        "positive",
        options.output_step > 0.0,
    )?;
    check(
        "duration (s)",
        options.duration,
        "positive",
        options.duration > 0.0,
    )?;
    scenario.check()?;
    let (impactor, speed) = match scenario {
        Scenario::Impactor { mass, speed } => (Some(mass), speed),
        Scenario::Barrier { speed } => (None, speed),
    };
    let masses: Vec<f64> = impactor
        .into_iter()
        .chain(car.masses().iter().copied())
        .collect();
    let chain = Chain {
        car,
        masses,
        impactor: impactor.is_some(),
    };
    let step = chain.step(bumper, options);
    let steps = options.duration / step;
    if !(steps.is_finite() && steps <= MAX_STEPS as f64) {
        let duration = options.duration;
        return Err(ImpactError::TooManySteps {
            step,
            duration,
            steps,
        });
    }
    integrate(&chain, bumper, speed, step, options)
}

/// Most integration steps of one impact (a guard against runs that would
/// not end: a 1e-9 kg mass on a stiff spring needs ~1e9 steps per second).
pub const MAX_STEPS: usize = 50_000_000;

/// Tolerance of the energy balance check of [`ImpactResult::warnings`].
pub const ENERGY_TOLERANCE: f64 = 0.01;

impl ImpactResult {
    /// The result's own checks: every figure finite, the energy balance
    /// within [`ENERGY_TOLERANCE`] of the initial energy, and the bumper's
    /// absorbed energy not negative. Empty when the result can be trusted.
    pub fn warnings(&self) -> Vec<String> {
        let e = &self.energy;
        let figures = [
            ("peak force", self.peak_force),
            ("largest compression", self.max_compression),
            ("absorbed energy", self.absorbed_energy),
            ("contact time", self.contact_time),
            ("initial energy", e.initial),
            ("final kinetic energy", e.kinetic),
            ("energy balance error", e.relative_error),
        ];
        let mut out: Vec<String> = figures
            .iter()
            .filter(|(_, v)| !v.is_finite())
            .map(|(name, v)| format!("{name} is {v}: the result is not usable"))
            .collect();
        if e.relative_error > ENERGY_TOLERANCE {
            out.push(format!(
                "energy balance error {:.3} of the initial energy exceeds the tolerance {ENERGY_TOLERANCE}",
                e.relative_error
            ));
        }
        if self.absorbed_energy < -ENERGY_TOLERANCE * e.initial.abs() {
            out.push(format!(
                "the bumper absorbed a negative energy ({:.4e} J): the integration did not resolve the bumper",
                self.absorbed_energy
            ));
        }
        out
    }
}

struct Histories {
    time: Vec<f64>,
    force: Vec<f64>,
    compression: Vec<f64>,
    x: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
}

impl Histories {
    fn record(&mut self, t: f64, force: f64, d: f64, x: &[f64], v: &[f64]) {
        self.time.push(t);
        self.force.push(force);
        self.compression.push(d);
        for (h, &value) in self.x.iter_mut().zip(x) {
            h.push(value);
        }
        for (h, &value) in self.v.iter_mut().zip(v) {
            h.push(value);
        }
    }
}

/// The chain, bumper and impactor as a [`Mechanism`] of the one integrator:
/// the bumper force at the new positions, its work by the trapezoidal rule
/// in the compression, the dampers' work on the half-step velocities.
struct Impact<'a> {
    chain: &'a Chain<'a>,
    bumper: &'a Bumper,
    step: f64,
    state: BumperState,
    force: f64,
    d: f64,
    bumper_work: f64,
    damper_work: f64,
    peak_force: f64,
    contact_end: Option<f64>,
    histories: Histories,
}

impl Mechanism for Impact<'_> {
    type Error = std::convert::Infallible;

    fn accelerations(&mut self, q: &[f64], v: &[f64], a: &mut [f64]) {
        self.chain.accelerations(q, v, self.force, a);
    }

    fn moved(&mut self, q: &[f64], _v: &[f64], k: usize) {
        let t = k as f64 * self.step;
        let (force, d) = (self.force, self.d);
        let d_next = self.chain.compression(q);
        let force_next = if d_next > 0.0 {
            self.bumper.force(d_next, &mut self.state)
        } else {
            0.0
        };
        self.bumper_work += 0.5 * (force + force_next) * (d_next - d);
        if self.contact_end.is_none() && force > 0.0 && force_next == 0.0 && d_next < d {
            let zero_at = self.bumper.remaining(&self.state).max(0.0);
            let fraction = ((d - zero_at) / (d - d_next)).clamp(0.0, 1.0);
            self.contact_end = Some(t + fraction * self.step);
        }
        (self.force, self.d) = (force_next, d_next);
        self.peak_force = self.peak_force.max(force_next);
    }

    fn stepped(&mut self, s: &Stepped<'_>) {
        if !s.half {
            self.damper_work += self.step * self.chain.damper_power(s.before);
        }
    }

    fn record(&mut self, k: usize, state: &Leapfrog) -> Result<Control, Self::Error> {
        let t = k as f64 * self.step;
        let (force, d) = (self.force, self.d);
        self.histories
            .record(t, force, d, state.q(), state.velocities());
        Ok(Control::Continue)
    }

    fn finished(&self, k: usize, _state: &Leapfrog) -> bool {
        let t = k as f64 * self.step;
        self.contact_end.is_some_and(|end| t > end * 1.1)
    }
}

fn integrate(
    chain: &Chain,
    bumper: &Bumper,
    speed: f64,
    step: f64,
    options: &Options,
) -> Result<ImpactResult, ImpactError> {
    let n = chain.masses.len();
    let v0 = if chain.impactor {
        (0..n)
            .map(|i| if i == 0 { speed } else { 0.0 })
            .collect::<Vec<_>>()
    } else {
        vec![speed; n]
    };
    let initial: f64 = chain
        .masses
        .iter()
        .zip(&v0)
        .map(|(m, v)| 0.5 * m * v * v)
        .sum();
    check(
        "initial kinetic energy (J)",
        initial,
        "finite and positive: the car's masses at this speed carry more energy than a number holds",
        initial > 0.0,
    )?;
    let mut impact = Impact {
        chain,
        bumper,
        step,
        state: BumperState::default(),
        force: 0.0,
        d: 0.0,
        bumper_work: 0.0,
        damper_work: 0.0,
        peak_force: 0.0,
        contact_end: None,
        histories: Histories {
            time: vec![],
            force: vec![],
            compression: vec![],
            x: vec![vec![]; n],
            v: vec![vec![]; n],
        },
    };
    let every = (options.output_step / step).round().max(1.0) as usize;
    let limit = (options.duration / step).ceil() as usize;
    let mut leapfrog = Leapfrog::start(&mut impact, vec![0.0; n], v0, step);
    let Ok(()) = leapfrog.run(&mut impact, every, limit);
    let Impact {
        state,
        force,
        bumper_work,
        damper_work,
        peak_force,
        contact_end,
        histories: h,
        ..
    } = impact;
    let (x, v_now) = (leapfrog.q(), leapfrog.velocities());
    let contact_end = contact_end.ok_or(ImpactError::NoSeparation {
        duration: options.duration,
    })?;
    let kinetic: f64 = chain
        .masses
        .iter()
        .zip(v_now)
        .map(|(m, v)| 0.5 * m * v * v)
        .sum();
    let springs = chain.spring_energy(x);
    let total = kinetic + springs + damper_work + bumper_work;
    let energy = EnergyBalance {
        initial,
        kinetic,
        springs,
        dampers: damper_work,
        bumper: bumper_work,
        relative_error: (total - initial).abs() / initial,
    };
    let stored = if force > 0.0 {
        0.5 * force * force / bumper.unloading_slope()
    } else {
        0.0
    };
    let mut bodies: Vec<String> = (1..=chain.car.dof()).map(|i| format!("m{i}")).collect();
    if chain.impactor {
        bodies.insert(0, "impactor".into());
    }
    Ok(ImpactResult {
        bodies,
        time: h.time,
        force: h.force,
        compression: h.compression,
        displacements: h.x,
        velocities: h.v,
        contact_start: 0.0,
        contact_time: contact_end,
        max_compression: state.max_compression,
        remaining_compression: bumper.remaining(&state),
        peak_force,
        absorbed_energy: bumper_work - stored,
        energy,
        step,
    })
}
