//! The chain with nonlinear links ([`crate::link`]) and its time-stepper
//! (issue 46, item 2).
//!
//! Masses m1..mn in a line as in [`crate::model`]; between mass j and j+1 a
//! link with a loading curve and unloading rule, `s_j = L_j(x_j − x_(j+1))`,
//! and a viscous damper `d_j = c_j (v_j − v_(j+1))` in parallel (the rate
//! dependence). The force f(t) acts on m1:
//!
//! ```text
//! m_i x_i'' = f δ_i1 − s_i − d_i + s_(i−1) + d_(i−1)
//! ```
//!
//! The links remember their largest compression, so the linear chain's
//! exact exponential propagation does not apply: the chain is integrated by
//! the one explicit integrator [`crate::leapfrog`] (central differences),
//! at a step `safety · min(2/ω, 2/ω_c)` from Gershgorin bounds with the
//! links' steepest slopes, rounded to divide the force's sample interval;
//! the force is interpolated linearly between its samples (first-order
//! hold). Each link's history is updated once per step, after the
//! positions move ([`crate::leapfrog::Mechanism::moved`]).
//!
//! Energy balance (J), per sample: `E_kin + E_stored + W_viscous + W_plastic
//! − W_force = E_kin(t0)`, with `E_stored = Σ` the links' elastic energies
//! and `W_plastic` their plastic work (closed forms of [`crate::link`]),
//! `W_viscous = Σ T d_j (v̄_j − v̄_(j+1))` and `W_force = Σ T f v̄_1` on the
//! leapfrog's mean velocities. Its residual is O(T²), reported by
//! [`ChainResponse::energy_error`].
//!
//! A link's crush depends on which way x points ([`Frame`]): in the
//! pendulum's frame (x rearwards) link j is compressed by `x_j − x_(j+1)`,
//! in a moving car's (x forwards, m1 at the front, the barrier's force on
//! m1 negative) by `x_(j+1) − x_j`. A linear link gives the same motion in
//! both.
//!
//! Driven by [`Drive::Barrier`] the car runs into a rigid wall at x = 0 instead
//! (x positive into the wall; m1 starts at it). With a front link
//! ([`Chain::with_front`], Kamal's crush zone ahead of the engine) the
//! wall pushes m1 back by that link's force at the crush x1 (never
//! pulling); without one by a stiff penalty spring and a damper near
//! critical for m1. The recorded force is the wall's force on the car
//! (negative, as the load-cell barrier's is).
//!
//! Driven by [`Drive::Striker`] the wall is a free rigid mass M (a
//! pendulum or a moving barrier) at x_s, moving at −V onto the car at rest
//! (x as the barrier run's: the car is pushed towards −x): every wall link
//! is compressed by the travel relative to it, `x_i − x_s` (the front
//! link by `x_1 − x_s`, the penalty contact likewise with
//! `v_1 − v_s`), pushes only — the contact separates when it would pull
//! and a link's plastic set stays — and the striker takes the reaction,
//! `M x_s'' = F_wall` (the sum of the wall links' forces). Its kinetic
//! energy joins `E_kin`, and the penalty contact's work is taken on the
//! relative velocity, `W_force = Σ T f (v̄_1 − v̄_s)`, so the balance is
//! the barrier's with `W_contact = −W_force`; as M → ∞ it is the barrier
//! run seen from the wall. The striker's x and v are recorded
//! ([`ChainResponse::striker_velocity`]).
//!
//! A second load path ([`Chain::with_path`], Kamal 1970's parallel paths:
//! the body's rails beside the engine's, or the engine meeting the wall
//! after the radiator's gap) is a crush link between the wall and another
//! mass p, compressed by `x_p − g` (g ≥ 0 the gap), never pulling. The wall
//! force is then the sum of both links' forces; the path's energies join
//! the balance as the front link's do.
//!
//! **Exact sensitivities.** The mechanism is written once over
//! [`Real`] (`chain_mover.rs`): [`Chain::motion`] runs it on
//! [`crate::dual::Dual`] numbers seeded in [`ChainValues`], so the
//! displacements and the force on m1 carry their exact derivatives by
//! those values — the forward sensitivity equations of the leapfrog
//! (Griewank & Walther 2008, ch. 3), through the links' history: δ_max
//! carries its derivative, and at every step the branch taken (loading,
//! unloading, the wall in contact or not) is the one differentiated. The
//! integration step, a piecewise constant function of the steepest slopes,
//! is held at the chain's own.
//!
//! A rebound link ([`Chain::with_rebound`]) is one more such wall link in
//! parallel (on any mass, with its gap), acting and balancing as the
//! second path does: a crushed front's elastic springback over a longer
//! stroke than the crush zone's own unloading (a bilinear link with a
//! soft unloading slope adds a tail to the wall force while the car
//! rebounds).
//!
//! ```
//! use bumpsim_core::chain::{Chain, Drive};
//! use bumpsim_core::link::{Curve, Link, Unloading};
//! // one mass into a wall through an elastic-perfectly-plastic link: the
//! // crush is m V² / (2 F_y) + F_y / (2 k)
//! let link = Link::new(Curve::bilinear(1e7, 1e5, 0.0).unwrap(), Unloading::Slope(1e7)).unwrap();
//! let chain = Chain::new(vec![1.0, 1000.0], vec![0.0], vec![link]).unwrap();
//! let r = chain.run(&Drive::Barrier { speed: 10.0, step: 1e-4, samples: 2000 }).unwrap();
//! let crush = 1000.0 * 100.0 / 2e5 + 1e5 / 2e7;
//! assert!((r.max_deformation(0) - crush).abs() < 0.02 * crush);
//! ```

use crate::dual::Real;
use crate::leapfrog::{Leapfrog, critical_step, stable_step, substeps};
use crate::link::Link;
use crate::model::{MAX_DOF, ModelError};
pub use mover::{ChainValues, Motion};
use mover::{Driven, Mover, Out};

#[path = "chain_mover.rs"]
mod mover;

/// A validated chain of masses joined by nonlinear links and dampers.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    masses: Vec<f64>,
    dampers: Vec<f64>,
    links: Vec<Link>,
    front: Option<Link>,
    path: Option<WallPath>,
    rebound: Option<WallPath>,
}

/// A second load path into the wall ([`Chain::with_path`]).
#[derive(Debug, Clone, PartialEq)]
pub struct WallPath {
    /// The mass it pushes, 0-based.
    pub mass: usize,
    /// The gap before it touches, m (its crush is `x_mass − gap`).
    pub gap: f64,
    /// Its crush link.
    pub link: Link,
}

/// Why a chain cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ChainError {
    /// The masses, dampers or links are not a valid chain.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A drive value is out of range.
    #[error("{name} = {value}: {expected}")]
    Drive {
        /// The value's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What is expected.
        expected: &'static str,
    },
    /// The run would need more than [`MAX_STEPS`] steps.
    #[error(
        "{steps:.3e} integration steps needed (the links' steepest slope against the lightest mass): at most {MAX_STEPS}"
    )]
    TooManySteps {
        /// Steps needed.
        steps: f64,
    },
    /// The states left the finite range.
    #[error("the simulation diverged at sample {sample}")]
    Diverged {
        /// First sample with a non-finite state.
        sample: usize,
    },
}

/// Most integration steps of one run.
pub const MAX_STEPS: f64 = 5e7;

/// Safety factor on the critical step.
pub const SAFETY: f64 = 0.2;

/// What drives the chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Drive<'a> {
    /// A sampled force on m1 (N, interval `step` s), every mass moving at
    /// `initial_velocity` m/s at the first sample.
    Force {
        /// The force samples, N.
        force: &'a [f64],
        /// Their interval, s.
        step: f64,
        /// m/s.
        initial_velocity: f64,
        /// Which way x points.
        frame: Frame,
    },
    /// Into a rigid wall at `speed` m/s, recorded every `step` s for
    /// `samples` samples.
    Barrier {
        /// m/s.
        speed: f64,
        /// s.
        step: f64,
        /// Number of samples.
        samples: usize,
    },
    /// A rigid striker (a pendulum or a moving barrier) of `mass` kg at
    /// `speed` m/s hits m1 of the car at rest, recorded every `step` s for
    /// `samples` samples: the wall of [`Drive::Barrier`] made a free mass.
    Striker {
        /// kg.
        mass: f64,
        /// m/s.
        speed: f64,
        /// s.
        step: f64,
        /// Number of samples.
        samples: usize,
    },
}

/// Which way x points, and so which relative motion crushes a link.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Frame {
    /// x points rearwards into the car, m2 behind m1 at larger x (the
    /// pendulum's frame of [`crate::model`]): link j is compressed by
    /// `x_j − x_(j+1)`.
    #[default]
    Rearward,
    /// x points the way the car travels, m1 at its front (a moving car
    /// into a barrier, the force on m1 negative): link j is compressed by
    /// `x_(j+1) − x_j`.
    Forward,
}

impl Frame {
    /// +1 (rearward) or −1 (forward).
    pub fn sign(self) -> f64 {
        match self {
            Frame::Rearward => 1.0,
            Frame::Forward => -1.0,
        }
    }
}

/// Histories at the samples; outer index = mass or link.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainResponse {
    /// Sample interval, s.
    pub step: f64,
    /// The force on m1 (given, or the wall's), N.
    pub force: Vec<f64>,
    /// Displacements, m.
    pub displacement: Vec<Vec<f64>>,
    /// Velocities, m/s.
    pub velocity: Vec<Vec<f64>>,
    /// Link (spring) forces, N, compression positive.
    pub link_force: Vec<Vec<f64>>,
    /// Kinetic energy, J.
    pub kinetic: Vec<f64>,
    /// Elastic energy stored in the links, J.
    pub stored: Vec<f64>,
    /// Viscous work of the dampers since t0, J.
    pub viscous: Vec<f64>,
    /// Plastic work of the links since t0, J.
    pub plastic: Vec<f64>,
    /// Work of the force on m1 since t0, J.
    pub work: Vec<f64>,
    /// Each link's plastic set at the end, m.
    pub plastic_set: Vec<f64>,
    /// Each link's largest compression, m.
    pub reached: Vec<f64>,
    /// The striker's displacement, m (empty unless driven by
    /// [`Drive::Striker`]; x as the car's, so negative while it pushes).
    pub striker_displacement: Vec<f64>,
    /// The striker's velocity, m/s (empty unless driven by
    /// [`Drive::Striker`]; its impact speed is `−speed`).
    pub striker_velocity: Vec<f64>,
}

impl ChainResponse {
    /// The largest compression of link `j` (0-based), m.
    pub fn max_deformation(&self, j: usize) -> f64 {
        self.reached[j]
    }

    /// Largest |energy residual| relative to the largest energy term.
    pub fn energy_error(&self) -> f64 {
        let e0 = self.kinetic[0] + self.stored[0];
        let terms = [
            &self.kinetic,
            &self.stored,
            &self.viscous,
            &self.plastic,
            &self.work,
        ];
        let scale = terms
            .iter()
            .flat_map(|v| v.iter())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let worst = (0..self.kinetic.len())
            .map(|k| {
                self.kinetic[k] + self.stored[k] + self.viscous[k] + self.plastic[k]
                    - self.work[k]
                    - e0
            })
            .fold(0.0_f64, |m, r| m.max(r.abs()));
        if scale > 0.0 { worst / scale } else { 0.0 }
    }
}

impl Chain {
    /// A chain from masses (kg), dampers (N·s/m) and links.
    pub fn new(masses: Vec<f64>, dampers: Vec<f64>, links: Vec<Link>) -> Result<Chain, ModelError> {
        let dof = masses.len();
        if dof == 0 {
            return Err(ModelError::NoMass);
        }
        if dof > MAX_DOF {
            return Err(ModelError::TooManyMasses { dof });
        }
        for (kind, count) in [("dampers", dampers.len()), ("links", links.len())] {
            if count != dof - 1 {
                return Err(ModelError::Count {
                    kind,
                    dof,
                    expected: dof - 1,
                    count,
                });
            }
        }
        let bad = |parameter: String, value: f64, unit, requirement| ModelError::Value {
            parameter,
            value,
            unit,
            requirement,
        };
        if let Some(i) = masses.iter().position(|m| !(m.is_finite() && *m > 0.0)) {
            let r = "a mass must be positive and finite";
            return Err(bad(format!("m{}", i + 1), masses[i], "kg", r));
        }
        if let Some(j) = dampers.iter().position(|c| !(c.is_finite() && *c >= 0.0)) {
            let r = "a damper must be finite and non-negative (0 = no damper)";
            return Err(bad(format!("c{}", j + 1), dampers[j], "Ns/m", r));
        }
        Ok(Chain {
            masses,
            dampers,
            links,
            front: None,
            path: None,
            rebound: None,
        })
    }

    /// Number of masses.
    pub fn dof(&self) -> usize {
        self.masses.len()
    }

    /// Masses, kg.
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }

    /// Dampers, N·s/m.
    pub fn dampers(&self) -> &[f64] {
        &self.dampers
    }

    /// Links.
    pub fn links(&self) -> &[Link] {
        &self.links
    }

    /// The same chain with a front link: the crush zone between a rigid
    /// wall and m1, compressed by m1's travel into the wall.
    pub fn with_front(self, front: Link) -> Chain {
        Chain {
            front: Some(front),
            ..self
        }
    }

    /// The front link, if any.
    pub fn front(&self) -> Option<&Link> {
        self.front.as_ref()
    }

    /// The same chain with a second load path into the wall (it acts only
    /// when driven by [`Drive::Barrier`]): `link` between the wall and
    /// mass `mass` (0-based), compressed by that mass's travel past `gap`
    /// (m, ≥ 0), never pulling.
    pub fn with_path(self, mass: usize, gap: f64, link: Link) -> Result<Chain, ModelError> {
        Ok(Chain {
            path: Some(self.wall_link("second load path", mass, gap, link)?),
            ..self
        })
    }

    /// The second load path, if any.
    pub fn path(&self) -> Option<&WallPath> {
        self.path.as_ref()
    }

    /// The same chain with a rebound link into the wall, in parallel with
    /// the front link and the second path (it acts only when driven by
    /// [`Drive::Barrier`]): `link` between the wall and mass `mass`
    /// (0-based), compressed by its travel past `gap` (m, ≥ 0), never
    /// pulling.
    pub fn with_rebound(self, mass: usize, gap: f64, link: Link) -> Result<Chain, ModelError> {
        Ok(Chain {
            rebound: Some(self.wall_link("rebound link", mass, gap, link)?),
            ..self
        })
    }

    /// A wall link on mass `mass` (0-based) after `gap` (m), checked:
    /// `what` names it in the error.
    fn wall_link(
        &self,
        what: &str,
        mass: usize,
        gap: f64,
        link: Link,
    ) -> Result<WallPath, ModelError> {
        if mass >= self.dof() || !(gap.is_finite() && gap >= 0.0) {
            return Err(ModelError::Value {
                parameter: format!("{what} on mass {} with gap", mass + 1),
                value: gap,
                unit: "m",
                requirement: "a mass of the chain and a finite, non-negative gap",
            });
        }
        Ok(WallPath { mass, gap, link })
    }

    /// The rebound link, if any.
    pub fn rebound(&self) -> Option<&WallPath> {
        self.rebound.as_ref()
    }

    /// The wall's penalty stiffness (N/m) and damper (N·s/m): 100 times
    /// the steepest link slope, at least 1e9 N/m; the damper at 0.7 of
    /// critical for m1.
    pub fn wall(&self) -> (f64, f64) {
        let steepest = self
            .links
            .iter()
            .map(Link::steepest_slope)
            .fold(0.0, f64::max);
        if let Some(front) = &self.front {
            return (front.steepest_slope(), 0.0);
        }
        let k = (100.0 * steepest).max(1e9);
        (k, 1.4 * (k * self.masses[0]).sqrt())
    }

    /// The integration step for a sample interval `interval` (s), with
    /// a striker of mass `striker` kg when there is one.
    fn integration_step(
        &self,
        interval: f64,
        wall: Option<(f64, f64)>,
        striker: Option<f64>,
    ) -> Result<f64, ChainError> {
        let n = self.dof();
        let (mut omega2, mut omega_c) = (0.0_f64, 0.0_f64);
        for i in 0..n {
            let (mut k, mut c) = (0.0, 0.0);
            for j in [i.wrapping_sub(1), i] {
                if j < n - 1 {
                    k += 2.0 * self.links[j].steepest_slope();
                    c += 2.0 * self.dampers[j];
                }
            }
            if let (0, Some((kw, cw))) = (i, wall) {
                k += kw;
                c += cw;
            }
            if let (Some(path), Some(_)) = (&self.path, wall)
                && path.mass == i
            {
                k += path.link.steepest_slope();
            }
            if let (Some(rebound), Some(_)) = (&self.rebound, wall)
                && rebound.mass == i
            {
                k += rebound.link.steepest_slope();
            }
            omega2 = omega2.max(k / self.masses[i]);
            omega_c = omega_c.max(c / self.masses[i]);
        }
        if let (Some(mass), Some((kw, cw))) = (striker, wall) {
            // the striker carries every wall link's reaction
            let paths = [&self.path, &self.rebound];
            let k = kw
                + paths
                    .iter()
                    .flat_map(|p| p.iter())
                    .map(|p| p.link.steepest_slope())
                    .sum::<f64>();
            omega2 = omega2.max(k / mass);
            omega_c = omega_c.max(cw / mass);
        }
        let raw = SAFETY * critical_step(omega2, omega_c);
        let count = substeps(raw, interval);
        if count > MAX_STEPS {
            return Err(ChainError::TooManySteps { steps: count });
        }
        Ok(stable_step(raw.min(interval), interval))
    }

    /// Runs the chain under `drive`.
    pub fn run(&self, drive: &Drive<'_>) -> Result<ChainResponse, ChainError> {
        let values = self.values::<f64>();
        match self.integrate(drive, &values, true)? {
            Out::Full(response) => Ok(*response),
            Out::Motion(_) => unreachable!("a full run records in full"),
        }
    }

    /// The chain's values on any [`Real`], every one a constant: seed the
    /// ones [`Chain::motion`] should differentiate by.
    pub fn values<T: Real>(&self) -> ChainValues<T> {
        let c = |v: &f64| T::constant(*v);
        ChainValues {
            masses: self.masses.iter().map(c).collect(),
            dampers: self.dampers.iter().map(c).collect(),
            links: self.links.iter().map(Link::real).collect(),
            front: self.front.as_ref().map(Link::real),
            path: self.path.as_ref().map(|p| p.link.real()),
            rebound: self.rebound.as_ref().map(|p| p.link.real()),
            path_gap: self.path.as_ref().map(|p| T::constant(p.gap)),
            rebound_gap: self.rebound.as_ref().map(|p| T::constant(p.gap)),
        }
    }

    /// The motion under `drive` with the chain's values replaced by
    /// `values` (of the chain's shape, [`Chain::values`]), on any
    /// [`Real`]: on dual numbers, the exact derivatives of the discrete
    /// motion (displacements and the force on m1) by the seeded values,
    /// through the links' history. The step is
    /// the chain's own ([`Chain::run`]'s), so on `f64` with
    /// [`Chain::values`] it gives [`Chain::run`]'s displacements and force.
    pub fn motion<T: Real>(
        &self,
        drive: &Drive<'_>,
        values: &ChainValues<T>,
    ) -> Result<Motion<T>, ChainError> {
        let shape = |kind: &'static str, expected: usize, count: usize| match expected == count {
            true => Ok(()),
            false => Err(ModelError::Count {
                kind,
                dof: self.dof(),
                expected,
                count,
            }),
        };
        shape("masses", self.dof(), values.masses.len())?;
        shape("dampers", self.dof() - 1, values.dampers.len())?;
        shape("links", self.dof() - 1, values.links.len())?;
        shape(
            "front links",
            self.front.iter().count(),
            values.front.iter().count(),
        )?;
        shape(
            "path links",
            self.path.iter().count(),
            values.path.iter().count(),
        )?;
        shape(
            "rebound links",
            self.rebound.iter().count(),
            values.rebound.iter().count(),
        )?;
        match self.integrate(drive, values, false)? {
            Out::Motion(motion) => Ok(motion),
            Out::Full(_) => unreachable!("a motion run records the motion"),
        }
    }

    /// The one integration of [`Chain::run`] and [`Chain::motion`].
    fn integrate<T: Real>(
        &self,
        drive: &Drive<'_>,
        values: &ChainValues<T>,
        full: bool,
    ) -> Result<Out<T>, ChainError> {
        let (interval, samples, speed, wall, frame) = match *drive {
            Drive::Force {
                force,
                step,
                initial_velocity,
                frame,
            } => (step, force.len(), initial_velocity, None, frame),
            Drive::Barrier {
                speed,
                step,
                samples,
            }
            | Drive::Striker {
                speed,
                step,
                samples,
                ..
            } => (step, samples, speed, Some(self.wall()), Frame::Forward),
        };
        let striker = match *drive {
            Drive::Striker { mass, .. } => {
                let expected = "a positive, finite striker mass, kg";
                check("mass", mass, mass > 0.0, expected)?;
                Some(mass)
            }
            _ => None,
        };
        check(
            "step",
            interval,
            interval > 0.0,
            "a positive sample interval, s",
        )?;
        check(
            "speed",
            speed,
            speed.abs() <= 1e3,
            "a finite speed of at most 1000 m/s",
        )?;
        if samples < 2 {
            return Err(ChainError::Drive {
                name: "samples",
                value: samples as f64,
                expected: "at least 2",
            });
        }
        let h = self.integration_step(interval, wall, striker)?;
        let every = (interval / h).round() as usize;
        if samples as f64 * every as f64 > MAX_STEPS {
            return Err(ChainError::TooManySteps {
                steps: samples as f64 * every as f64,
            });
        }
        let n = self.dof();
        let force = match drive {
            Drive::Force { force, .. } => force,
            Drive::Barrier { .. } | Drive::Striker { .. } => &[][..],
        };
        let driven = Driven {
            force,
            every,
            wall,
            sign: frame.sign(),
            striker,
        };
        let out = Out::new(full, n, samples, striker.is_some());
        let mut m = Mover::new(self, values, driven, out);
        let zero = T::constant(0.0);
        let (q, v) = match striker {
            // the striker (last) moves at −speed onto m1 at rest, x as the
            // barrier run's: its force on m1 is negative
            Some(_) => {
                let mut v = vec![zero; n + 1];
                v[n] = T::constant(-speed);
                (vec![zero; n + 1], v)
            }
            None => (vec![zero; n], vec![T::constant(speed); n]),
        };
        let mut state = Leapfrog::start(&mut m, q, v, h);
        let last = (samples - 1) * every;
        state
            .run(&mut m, every, last)
            .map_err(|sample| ChainError::Diverged { sample })?;
        Ok(m.finish(interval))
    }
}

fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), ChainError> {
    if ok && value.is_finite() {
        return Ok(());
    }
    Err(ChainError::Drive {
        name,
        value,
        expected,
    })
}

#[cfg(test)]
#[path = "chain_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "chain_striker_tests.rs"]
mod striker_tests;
