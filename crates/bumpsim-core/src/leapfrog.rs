//! The one explicit integrator of every impact: central differences in
//! their leapfrog form (paper A; spec §5 and §9), for any [`Mechanism`].
//!
//! **Scheme.** With generalised coordinates `q`, the half-step velocities
//! `v_{n+½}` and the step `T`:
//!
//! - start: `a_0 = a(q_0, v_0)`, `v_½ = v_0 + (T/2) a_0`;
//! - step: `q_{n+1} = q_n + T v_{n+½}`, then `a_{n+1} = a(q_{n+1}, v_{n+½})`,
//!   `v_{n+3/2} = v_{n+½} + T a_{n+1}`;
//! - the full-step velocity `v_{n+1} = (v_{n+½} + v_{n+3/2}) / 2`.
//!
//! Dissipative forces (dampers, tyres) are taken from the half-step velocity
//! the mechanism is given, as in paper A's scheme; a mechanism whose inertial
//! terms need the full-step velocity may extrapolate it with the previous
//! accelerations, which it finds in `a` on entry (see
//! [`Mechanism::accelerations`]). Why explicit: the bumper characteristics
//! depend on their history (loading, elastic unloading), so each is evaluated
//! once per step in its natural order, with no rejected step that would have
//! to roll a crush history back; contacts and friction are non-smooth, which
//! costs implicit solvers Newton failures; the systems are small, so a step
//! from the stiffest element is cheap.
//!
//! **Stable step.** Central differences are stable for `T < 2/ω` with ω the
//! highest natural frequency, and damping adds `T < 2/ω_c` with ω_c the
//! largest rate of `M⁻¹C`. Both are bounded by Gershgorin row sums of
//! `M⁻¹K` and `M⁻¹C` (each mechanism sums its own rows); the one rule is
//! [`critical_step`] `= min(2/√(ω²), 2/ω_c)`, times a safety factor (0.05 by
//! default everywhere), then rounded down so that a recorded interval holds
//! a whole number of steps ([`stable_step`], [`substeps`]).
//!
//! A mechanism adds its physics through hooks: [`Mechanism::moved`] after
//! the positions advance (contacts, crush histories), [`Mechanism::stepped`]
//! after the velocities (work and impulse sums), [`Mechanism::record`] at
//! every recorded step, and [`Mechanism::finished`] to end early. Nothing
//! here allocates after [`Leapfrog::start`].
//!
//! The state is written over any [`Real`] (`f64` by default): on
//! [`crate::dual::Dual`] numbers the same steps carry the exact derivatives
//! of the discrete motion with respect to whatever the mechanism seeded
//! (the step `T` stays a plain number). Every product is written
//! `value · T`, the `f64` one's operands as before (a product commutes
//! bit for bit), so an `f64` run is what it was.
//!
//! ```
//! use bumpsim_core::leapfrog::{Control, Leapfrog, Mechanism, critical_step, stable_step};
//! /// An undamped oscillator m x'' = −k x.
//! struct Spring { omega2: f64, x: Vec<f64> }
//! impl Mechanism for Spring {
//!     type Error = ();
//!     fn accelerations(&mut self, q: &[f64], _v: &[f64], a: &mut [f64]) {
//!         a[0] = -self.omega2 * q[0];
//!     }
//!     fn record(&mut self, _k: usize, state: &Leapfrog) -> Result<Control, ()> {
//!         self.x.push(state.q()[0]);
//!         Ok(Control::Continue)
//!     }
//! }
//! let mut spring = Spring { omega2: 4.0, x: vec![] };
//! let step = stable_step(0.05 * critical_step(4.0, 0.0), 1e-2); // divides 10 ms
//! let mut state = Leapfrog::start(&mut spring, vec![0.0], vec![1.0], step);
//! let every = (1e-2 / step).round() as usize;
//! state.run(&mut spring, every, (std::f64::consts::PI / step) as usize).unwrap();
//! // x = sin(2t)/2: half a period later it is back at 0
//! assert!(spring.x.iter().all(|x| x.abs() <= 0.5 * (1.0 + 1e-3)));
//! ```

use crate::dual::Real;

/// What a mechanism says at a recorded step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// Go on.
    Continue,
    /// Stop here (the last record).
    Stop,
}

/// One completed step (or the first half step) as the hooks see it.
#[derive(Debug, Clone, Copy)]
pub struct Stepped<'a, T = f64> {
    /// Index of the step just completed: it moved from `k` to `k + 1`
    /// (0 for the first half step).
    pub k: usize,
    /// Its length, s (`T`, or `T/2` for the first half step).
    pub length: f64,
    /// Whether it is the first half step.
    pub half: bool,
    /// Positions at its end.
    pub q: &'a [T],
    /// Velocities the forces were taken from (`v_{n−½}`; `v_0` for the half step).
    pub before: &'a [T],
    /// Velocities after it (`v_{n+½}`).
    pub after: &'a [T],
    /// Their mean, the full-step velocity of the leapfrog's kinetic-energy
    /// identity: a force from `before` does the work `T F · mean`.
    pub mean: &'a [T],
    /// The accelerations used.
    pub a: &'a [T],
}

/// The physics of a system integrated by [`Leapfrog`], on the numbers `T`.
pub trait Mechanism<T: Real = f64> {
    /// The error a record may end the integration with.
    type Error;

    /// Writes the generalised accelerations at positions `q` and the
    /// half-step velocities `v` (dissipative forces from `v`) into `a`,
    /// which holds the previous accelerations on entry (zeros at the start).
    fn accelerations(&mut self, q: &[T], v: &[T], a: &mut [T]);

    /// The positions moved to `q` in step `k` (from `k` to `k + 1`) at the
    /// half-step velocities `v` (`v_{k+½}`), before the accelerations there:
    /// contacts, history-dependent forces and any state that follows the
    /// motion (a tyre's patch).
    fn moved(&mut self, _q: &[T], _v: &[T], _k: usize) {}

    /// A step (or the first half step) is complete: running sums of work
    /// and impulse.
    fn stepped(&mut self, _step: &Stepped<'_, T>) {}

    /// Step `k` is recorded (every `every` steps of [`Leapfrog::run`]).
    fn record(&mut self, _k: usize, _state: &Leapfrog<T>) -> Result<Control, Self::Error> {
        Ok(Control::Continue)
    }

    /// Whether the integration ends at step `k` (checked every step, after
    /// any record).
    fn finished(&self, _k: usize, _state: &Leapfrog<T>) -> bool {
        false
    }
}

/// The integration state: positions, half-step, full-step and previous
/// half-step velocities, accelerations; every buffer allocated once.
#[derive(Debug, Clone, PartialEq)]
pub struct Leapfrog<T = f64> {
    q: Vec<T>,
    v_half: Vec<T>,
    v_now: Vec<T>,
    previous: Vec<T>,
    a: Vec<T>,
    step: f64,
}

impl<T: Real> Leapfrog<T> {
    /// The state after the first half step from positions `q` and
    /// velocities `v` (of the same length) with step `step`, s. The
    /// mechanism is already prepared at `q` (its contacts evaluated there):
    /// [`Mechanism::moved`] is called from the first step on.
    pub fn start<M: Mechanism<T> + ?Sized>(
        mechanism: &mut M,
        q: Vec<T>,
        v: Vec<T>,
        step: f64,
    ) -> Leapfrog<T> {
        let n = q.len();
        let zero = T::constant(0.0);
        let mut state = Leapfrog {
            v_now: v.clone(),
            previous: vec![zero; n],
            a: vec![zero; n],
            v_half: v,
            q,
            step,
        };
        mechanism.accelerations(&state.q, &state.v_now, &mut state.a);
        let half = 0.5 * step;
        for ((h, p), a) in state
            .v_half
            .iter_mut()
            .zip(&mut state.previous)
            .zip(&state.a)
        {
            let before = *h;
            *h += *a * half;
            *p = (before + *h) * 0.5;
        }
        mechanism.stepped(&Stepped {
            k: 0,
            length: half,
            half: true,
            q: &state.q,
            before: &state.v_now,
            after: &state.v_half,
            mean: &state.previous,
            a: &state.a,
        });
        state
    }

    /// One step from step `k` to `k + 1`.
    pub fn advance<M: Mechanism<T> + ?Sized>(&mut self, mechanism: &mut M, k: usize) {
        let t = self.step;
        self.q
            .iter_mut()
            .zip(&self.v_half)
            .for_each(|(x, v)| *x += *v * t);
        mechanism.moved(&self.q, &self.v_half, k);
        self.previous.copy_from_slice(&self.v_half);
        mechanism.accelerations(&self.q, &self.v_half, &mut self.a);
        self.v_half
            .iter_mut()
            .zip(&self.a)
            .for_each(|(v, a)| *v += *a * t);
        self.v_now
            .iter_mut()
            .zip(self.previous.iter().zip(&self.v_half))
            .for_each(|(w, (p, h))| *w = (*p + *h) * 0.5);
        mechanism.stepped(&Stepped {
            k,
            length: t,
            half: false,
            q: &self.q,
            before: &self.previous,
            after: &self.v_half,
            mean: &self.v_now,
            a: &self.a,
        });
    }

    /// Steps `k = 0 ..= last`: records every `every` steps (from step 0),
    /// ends when a record says [`Control::Stop`] or the mechanism is
    /// [`Mechanism::finished`], and otherwise advances (also after the last).
    pub fn run<M: Mechanism<T> + ?Sized>(
        &mut self,
        mechanism: &mut M,
        every: usize,
        last: usize,
    ) -> Result<(), M::Error> {
        let every = every.max(1);
        for k in 0..=last {
            if k % every == 0 && mechanism.record(k, self)? == Control::Stop {
                break;
            }
            if mechanism.finished(k, self) {
                break;
            }
            self.advance(mechanism, k);
        }
        Ok(())
    }

    /// Positions.
    pub fn q(&self) -> &[T] {
        &self.q
    }

    /// Full-step velocities `v_n` (the start velocities before the first step).
    pub fn velocities(&self) -> &[T] {
        &self.v_now
    }

    /// Half-step velocities `v_{n+½}`.
    pub fn half_step_velocities(&self) -> &[T] {
        &self.v_half
    }

    /// The last accelerations.
    pub fn accelerations(&self) -> &[T] {
        &self.a
    }

    /// The step, s.
    pub fn step(&self) -> f64 {
        self.step
    }
}

/// The critical step of central differences, s: `min(2/√(ω²), 2/ω_c)` for
/// Gershgorin bounds `omega2` (1/s²) of `M⁻¹K` and `omega_c` (1/s) of
/// `M⁻¹C`; infinite when both are 0.
///
/// ```
/// use bumpsim_core::leapfrog::critical_step;
/// assert_eq!(critical_step(4.0, 0.0), 1.0);   // 2/ω, ω = 2 rad/s
/// assert_eq!(critical_step(4.0, 10.0), 0.2);  // damping limits it
/// ```
pub fn critical_step(omega2: f64, omega_c: f64) -> f64 {
    (2.0 / omega2.sqrt()).min(2.0 / omega_c)
}

/// The largest step not above `raw` (s) that divides `interval` (s) into
/// whole steps.
///
/// ```
/// use bumpsim_core::leapfrog::stable_step;
/// assert_eq!(stable_step(3e-5, 1e-4), 1e-4 / 4.0);
/// ```
pub fn stable_step(raw: f64, interval: f64) -> f64 {
    interval / (interval / raw).ceil()
}

/// Steps per `interval` (s) with steps not above `raw` (s), as a float (at
/// least 1; the caller checks it against its limit before converting).
///
/// ```
/// use bumpsim_core::leapfrog::substeps;
/// assert_eq!(substeps(3e-5, 1e-4), 4.0);
/// assert_eq!(substeps(1.0, 1e-4), 1.0);
/// ```
pub fn substeps(raw: f64, interval: f64) -> f64 {
    (interval / raw).ceil().max(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A free mass under a constant force F: x = v0 t + F t²/(2m), exact
    /// for the leapfrog (a quadratic).
    struct Pushed {
        force: f64,
        mass: f64,
        work: f64,
    }

    impl Mechanism for Pushed {
        type Error = ();
        fn accelerations(&mut self, _q: &[f64], _v: &[f64], a: &mut [f64]) {
            a[0] = self.force / self.mass;
        }
        fn stepped(&mut self, s: &Stepped<'_>) {
            self.work += s.length * self.force * s.mean[0];
        }
    }

    #[test]
    fn a_free_mass_under_a_constant_force_moves_exactly() {
        let (force, mass, v0, step) = (3.0, 2.0, 0.5, 1e-3);
        let mut m = Pushed {
            force,
            mass,
            work: 0.0,
        };
        let mut s = Leapfrog::start(&mut m, vec![0.0], vec![v0], step);
        for k in 0..1000 {
            s.advance(&mut m, k);
        }
        let t = 1000.0 * step;
        let x = v0 * t + force / (2.0 * mass) * t * t;
        assert!((s.q()[0] - x).abs() < 1e-12, "{} {x}", s.q()[0]);
        let v = v0 + force / mass * t;
        assert!((s.velocities()[0] - v).abs() < 1e-12);
        // the work on the mean velocities is the kinetic energy gained (to
        // the half step past t)
        let half = v + 0.5 * step * force / mass;
        let gained = 0.5 * mass * (half * half - v0 * v0);
        assert!(
            (m.work - gained).abs() < 1e-12 * gained,
            "{} {gained}",
            m.work
        );
    }

    /// The undamped oscillator keeps its amplitude and period to O(T²).
    struct Oscillator {
        omega2: f64,
        x: Vec<f64>,
    }

    impl Mechanism for Oscillator {
        type Error = ();
        fn accelerations(&mut self, q: &[f64], _v: &[f64], a: &mut [f64]) {
            a[0] = -self.omega2 * q[0];
        }
        fn record(&mut self, _k: usize, state: &Leapfrog) -> Result<Control, ()> {
            self.x.push(state.q()[0]);
            Ok(Control::Continue)
        }
        fn finished(&self, _k: usize, _state: &Leapfrog) -> bool {
            self.x.len() > 1000
        }
    }

    #[test]
    fn an_undamped_oscillator_keeps_its_amplitude_and_phase() {
        let omega: f64 = 30.0;
        let interval = 1e-3;
        let step = stable_step(0.05 * critical_step(omega * omega, 0.0), interval);
        assert!(step <= 0.05 * 2.0 / omega && (interval / step).fract() == 0.0);
        let mut m = Oscillator {
            omega2: omega * omega,
            x: vec![],
        };
        let mut s = Leapfrog::start(&mut m, vec![0.0], vec![omega], step);
        let every = (interval / step).round() as usize;
        s.run(&mut m, every, usize::MAX - 1).unwrap();
        assert_eq!(m.x.len(), 1001, "ended by `finished`");
        for (k, x) in m.x.iter().enumerate() {
            let t = k as f64 * interval;
            assert!((x - (omega * t).sin()).abs() < 2e-3, "{k}: {x}");
        }
    }

    #[test]
    fn the_step_rule_takes_the_tighter_bound_and_divides_the_interval() {
        assert_eq!(critical_step(0.0, 0.0), f64::INFINITY);
        assert_eq!(critical_step(1e6, 0.0), 2e-3);
        assert_eq!(critical_step(1e6, 1e4), 2e-4);
        assert_eq!(stable_step(2e-4, 1e-4), 1e-4);
        assert_eq!(substeps(2e-4, 1e-4), 1.0);
        assert_eq!(substeps(0.3e-4, 1e-4), 4.0);
    }
}
