//! The tyre forces of the planar car: each wheel's law ([`Axle`]: rolling
//! with its cornering stiffness, relaxation and saturation, or sliding),
//! the patch deflection of a rolling tyre advanced over a step, and the
//! linearised rates the critical step needs.
//!
//! Velocities are the wheel centre's in the body frame: `v_e` along the
//! car, `v_n` across it (left positive). Forces are the ground's on the
//! car, body frame. Equations and sources: [`Axle`].
//!
//! ```
//! use bumpsim_planar::car::Axle;
//! use bumpsim_planar::tyre::Wheel;
//! // a rolling tyre at 4 m/s with 2 cm/s of side slip, no relaxation:
//! // F_y ≈ −C_α α while far from saturation
//! let axle = Axle { relaxation_length: 0.0, ..Axle::rolling(0.0, 0.9) };
//! let wheel = Wheel { xi: 1.0, eta: 0.75, load: 3000.0, axle };
//! let (_, across) = wheel.force(4.0, 0.02, 0.0, 0.05);
//! let alpha = (0.02f64).atan2((16.0f64 + 0.0025).sqrt());
//! assert!((across + 60e3 * alpha).abs() < 0.02 * 60e3 * alpha);
//! ```

use crate::car::{Axle, TyreLaw};
use bumpsim_core::dual::Real;

/// A wheel: where it is on the body, what it carries, its axle's tyres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wheel {
    /// Ahead of the CG, m.
    pub xi: f64,
    /// Left of the CG, m.
    pub eta: f64,
    /// Normal load, N.
    pub load: f64,
    /// Its axle's law and coefficients.
    pub axle: Axle,
}

impl Wheel {
    /// The ground's force on the car at this wheel (along, across; body
    /// frame, N) from the wheel centre's velocity `(v_e, v_n)` (m/s), the
    /// patch deflection `y` (m, rolling with relaxation) and the slip
    /// speed `slip` (m/s) that regularises the laws at standstill.
    pub fn force(&self, v_e: f64, v_n: f64, y: f64, slip: f64) -> (f64, f64) {
        self.grip().force(v_e, v_n, y, slip)
    }

    /// Advances the patch deflection `y` of a rolling tyre with relaxation
    /// over `step` (s) at the wheel centre's velocity `(v_e, v_n)`:
    /// `ẏ = v_n − λ y`, `λ = |v_e|/σ`, solved exactly for the velocities
    /// held over the step (`y += (v_n − λ y) T (1 − e^{−λT})/(λT)`), then,
    /// with the clamped linear law, clamped where the patch slides (`|C_α y / σ| ≤ μ_y N`; a Magic
    /// Formula saturates in its force instead). Any other tyre has no
    /// deflection.
    pub fn relax(&self, v_e: f64, v_n: f64, y: &mut f64, step: f64) {
        self.grip().relax(v_e, v_n, y, step)
    }

    /// This wheel's law on `f64`.
    fn grip(&self) -> Grip<f64> {
        let a = &self.axle;
        Grip {
            axle: *a,
            load: self.load,
            mu_lateral: a.mu_lateral,
            mu_longitudinal: a.mu_longitudinal,
            cornering: a.cornering_stiffness,
            relaxation: a.relaxation_length,
        }
    }

    /// The linearised damping (N·s/m) and stiffness (N/m) of this tyre
    /// against the car's motion, largest over its directions, for the
    /// critical step: Coulomb laws `μN/v_s`, the instantaneous slip-angle
    /// law `C_α/v_s`, the relaxed tyre's lateral spring `C_α/σ`.
    pub fn rates(&self, slip: f64) -> (f64, f64) {
        let a = &self.axle;
        if a.law == TyreLaw::Sliding {
            return (self.load * a.mu_longitudinal.max(a.mu_lateral) / slip, 0.0);
        }
        let along = self.load * a.rolling_resistance / slip;
        match (a.mu_lateral * self.load > 0.0, a.relaxation_length > 0.0) {
            (false, _) => (along, 0.0),
            (true, true) => (along, a.cornering_stiffness / a.relaxation_length),
            (true, false) => (along.max(a.cornering_stiffness / slip), 0.0),
        }
    }
}

/// The one tyre law on any [`Real`]: `f64` in a run ([`Wheel`]), dual
/// numbers in the identification's exact derivatives
/// ([`crate::sensitivity`]), where the load and the coefficients are
/// parameters. The axle gives the law, its shape and whether the tyre
/// relaxes; the coefficients here override its values.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Grip<T> {
    /// The law, shape and relaxation switch.
    pub axle: Axle,
    /// Normal load, N.
    pub load: T,
    /// Lateral grip μ_y.
    pub mu_lateral: T,
    /// Sliding grip along the wheel μ_x.
    pub mu_longitudinal: T,
    /// Cornering stiffness C_α, N/rad.
    pub cornering: T,
    /// Relaxation length σ, m.
    pub relaxation: T,
}

impl<T: Real> Grip<T> {
    /// [`Wheel::force`].
    pub fn force(&self, v_e: T, v_n: T, y: T, slip: f64) -> (T, T) {
        match self.axle.law {
            TyreLaw::Sliding => {
                let scale = self.load / (v_e * v_e + v_n * v_n + slip * slip).sqrt();
                (
                    -(self.mu_longitudinal * scale * v_e),
                    -(self.mu_lateral * scale * v_n),
                )
            }
            TyreLaw::Rolling => {
                let rolling = (v_e * v_e + slip * slip).sqrt();
                let along = -(self.load * self.axle.rolling_resistance) * v_e / rolling;
                (along, self.lateral(v_n, y, rolling))
            }
        }
    }

    /// A rolling tyre's side force from its slip (relaxed: `y/σ`; else the
    /// slip angle), saturated at `μ_y N` by the axle's law.
    fn lateral(&self, v_n: T, y: T, rolling: T) -> T {
        let grip = self.mu_lateral * self.load;
        let relaxed = self.axle.relaxation_length > 0.0;
        let alpha = match relaxed {
            true => y / self.relaxation,
            false => v_n.atan2(rolling),
        };
        match (grip.value() <= 0.0, self.axle.shape) {
            (true, _) => T::constant(0.0),
            (false, Some(c)) => {
                let b = (self.cornering * alpha / (grip * c)).atan2(T::constant(1.0));
                -(grip * (b * c).sin_cos().0)
            }
            (false, None) if relaxed => {
                (-(self.cornering / self.relaxation) * y).clamp(-grip, grip)
            }
            (false, None) => -(grip * (self.cornering * alpha / grip).tanh()),
        }
    }

    /// [`Wheel::relax`].
    pub fn relax(&self, v_e: T, v_n: T, y: &mut T, step: f64) {
        let a = &self.axle;
        let grip = self.mu_lateral * self.load;
        if a.law != TyreLaw::Rolling || a.relaxation_length <= 0.0 || grip.value() <= 0.0 {
            *y = T::constant(0.0);
            return;
        }
        // exact for the velocities held over the step: y relaxes towards
        // v_n/λ at the rate λ = |v_e|/σ, `y ← y + (v_n − λ y) T φ(λT)`,
        // `φ(z) = (1 − e^{−z})/z`; stable for any σ and step (an Euler
        // step, φ = 1, overshoots once λT > 1: at a 1 mm σ and 15 km/h
        // from a 0.24 ms step)
        let rate = v_e.abs() / self.relaxation;
        let z = rate * step;
        let phi = match z.value() < 1e-2 {
            // its series to z³ (off by z⁴/120 < 1e-9 of φ): a tyre rolling
            // at σ ≈ 0.4 m has z ≈ 1e-4, and the exponential slowed the
            // angled bench by 12 %
            true => ((-(z / 24.0) + 1.0 / 6.0) * z - 0.5) * z + 1.0,
            false => -((-z).exp() - 1.0) / z,
        };
        *y += (v_n - rate * *y) * phi * step;
        if a.shape.is_none() {
            let limit = grip * self.relaxation / self.cornering;
            *y = y.clamp(-limit, limit);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wheel(axle: Axle) -> Wheel {
        Wheel {
            xi: 1.1,
            eta: 0.75,
            load: 3500.0,
            axle,
        }
    }

    /// A relaxed tyre rolling steadily at a constant slip settles at the
    /// slip-angle law's force, `−C_α v_n/|v_e|`, and saturates at μN.
    #[test]
    fn a_relaxed_tyre_settles_at_the_slip_angle_law() {
        let w = wheel(Axle::rolling(0.0, 0.9));
        let (v_e, v_n, mut y) = (4.0, 0.05, 0.0);
        for _ in 0..20_000 {
            w.relax(v_e, v_n, &mut y, 1e-4);
        }
        let (_, across) = w.force(v_e, v_n, y, 0.05);
        let law = -60e3 * v_n / v_e;
        assert!((across - law).abs() < 1e-3 * law.abs(), "{across} {law}");
        // ten times the slip: saturated at μ_y N
        let mut y = 0.0;
        for _ in 0..20_000 {
            w.relax(v_e, 0.5, &mut y, 1e-4);
        }
        let (_, across) = w.force(v_e, 0.5, y, 0.05);
        assert!((across + 0.9 * 3500.0).abs() < 1e-9, "{across}");
    }

    /// The Magic Formula (shape 1.3, Pacejka 2012 ch. 4.3.2) has the
    /// cornering stiffness at small slip, its peak μN at
    /// `B α' = tan(π/(2C))` and falls to `μN sin(Cπ/2)` at large slip; its
    /// patch is not clamped, and without a shape the law is the clamped
    /// linear one.
    #[test]
    fn the_magic_formula_rounds_the_peak_and_falls_past_it() {
        let shaped = wheel(Axle {
            shape: Some(1.3),
            ..Axle::rolling(0.0, 0.9)
        });
        let (grip, sigma, c) = (0.9 * 3500.0, 0.4, 60e3);
        let at = |slip: f64| shaped.force(4.0, 0.0, slip * sigma, 0.05).1;
        let small = at(1e-5);
        assert!((small + c * 1e-5).abs() < 1e-6 * c * 1e-5, "{small}");
        let b = c / (1.3 * grip);
        let peak = at((std::f64::consts::PI / 2.6).tan() / b);
        assert!((peak + grip).abs() < 1e-9 * grip, "{peak}");
        let far = at(1e3);
        let fall = grip * (1.3 * std::f64::consts::FRAC_PI_2).sin();
        assert!((far + fall).abs() < 1e-3 * grip, "{far} {fall}");
        let mut y = 0.0;
        for _ in 0..20_000 {
            shaped.relax(4.0, 0.5, &mut y, 1e-4);
        }
        assert!(y > 1.01 * grip * sigma / c, "not clamped: {y}");
        let plain = wheel(Axle::rolling(0.0, 0.9)).force(4.0, 0.1, 2e-3, 0.05).1;
        assert!(
            (plain + (c / sigma) * 2e-3).abs() <= 1e-15 * plain.abs(),
            "{plain}"
        );
    }

    /// At standstill the relaxed tyre is a spring C_α/σ, not a damper:
    /// pushed sideways by 1 mm it pulls back with C_α/σ × 1 mm.
    #[test]
    fn at_standstill_the_relaxed_tyre_is_a_lateral_spring() {
        let w = wheel(Axle::rolling(0.0, 0.9));
        let mut y = 0.0;
        for _ in 0..1000 {
            w.relax(0.0, 1e-3 / 0.1, &mut y, 1e-4); // 1 mm in 0.1 s
        }
        let (_, across) = w.force(0.0, 0.0, y, 0.05);
        assert!((y - 1e-3).abs() < 1e-12, "{y}");
        assert!((across + 60e3 / 0.4 * 1e-3).abs() < 1e-6, "{across}");
    }

    /// A 1 mm relaxation length at 15 km/h relaxes in 0.24 ms: an Euler
    /// step of 1 ms would overshoot fourfold and grow (1 − λT = −3.2).
    /// The update is the closed form `y(t) = (v_n/λ)(1 − e^{−λt})` after
    /// every step, whatever the step.
    #[test]
    fn a_short_relaxation_length_relaxes_exactly_at_any_step() {
        let w = wheel(Axle {
            relaxation_length: 1e-3,
            ..Axle::rolling(0.0, 0.9)
        });
        let (v_e, v_n, rate) = (4.1667, 2e-3, 4.1667 / 1e-3);
        for step in [1e-6, 1e-4, 1e-3] {
            let mut y = 0.0;
            for k in 1..=40 {
                w.relax(v_e, v_n, &mut y, step);
                let exact = v_n / rate * (1.0 - (-rate * step * k as f64).exp());
                assert!(
                    (y - exact).abs() <= 1e-12 * v_n / rate,
                    "{step} {k}: {y} {exact}"
                );
            }
        }
    }

    /// The sliding law is the Coulomb law of a locked wheel: at 4 m/s with
    /// 5 cm/s of side slip it yields about 1 % of μN sideways, where a
    /// rolling tyre yields about half (the issue's figures).
    #[test]
    fn a_locked_wheel_gives_little_side_force_where_a_rolling_one_gives_much() {
        let locked = wheel(Axle::sliding(0.9, 0.9)).force(4.0, 0.05, 0.0, 0.05);
        let grip = 0.9 * 3500.0;
        assert!(locked.1.abs() < 0.02 * grip, "{locked:?}");
        let rolling = wheel(Axle {
            relaxation_length: 0.0,
            ..Axle::rolling(0.015, 0.9)
        })
        .force(4.0, 0.05, 0.0, 0.05);
        assert!(rolling.1.abs() > 0.2 * grip, "{rolling:?}");
    }
}
