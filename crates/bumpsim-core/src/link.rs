//! Nonlinear links: a spring given by a loading curve and an unloading
//! rule, with the history it carries (issue 46, item 2).
//!
//! Lumped crash models since Kamal (1970, "Analysis and simulation of
//! vehicle to barrier impact", SAE 700414) join the masses of a car by
//! springs that crush: the force follows a **loading curve** `F_L(δ)` while
//! the deformation δ (m, positive in compression) grows past its largest
//! value so far, and an **unloading rule** when it recedes.
//!
//! Loading curves ([`Curve`]), for δ ≥ 0:
//!
//! - linear: `F_L = k δ`;
//! - progressive (stiffening) up to a limit deformation `δ_lim`, the tangent
//!   there beyond: `F_L = k δ + k3 δ³` (δ ≤ δ_lim);
//! - yielding with hardening (bilinear elasto-plastic): `F_L = k δ` up to
//!   the yield force `F_y` (δ_y = F_y / k), then `F_L = F_y + r k (δ − δ_y)`
//!   with the hardening ratio `0 ≤ r ≤ 1` (r = 0: perfectly plastic);
//! - tabulated: piecewise linear through points `(δ_i, F_i)` from (0, 0),
//!   δ increasing, F ≥ 0 (a crush force may fall after a fold buckles),
//!   the last slope beyond the last point (held at its force when falling).
//!
//! Unloading rules ([`Unloading`]):
//!
//! - **elastic** along the same curve (`F = F_L(δ)`, odd in δ: tension
//!   mirrors compression); nothing is dissipated;
//! - **elastic slope** `k_u` from the reached deformation δ_max (the
//!   elasto-plastic spring): `F = F_max − k_e (δ_max − δ)` below δ_max,
//!   linear into tension, with the plastic set `δ_p = δ_max − F_max / k_e`.
//!   Past the curve's elastic limit δ_e the slope used is
//!   `k_e = max(k_u, F_max/δ_max, F_max²/(2 E_L))`, `E_L = ∫₀^δmax F_L dδ`:
//!   the secant keeps the set non-negative and the last term keeps the
//!   dissipated work non-negative on a stiffening curve. Up to δ_e
//!   (`δ_max ≤ δ_e`) the link is elastic whatever k_u: it unloads along its
//!   initial slope k, with no set and nothing dissipated.
//!   The elastic limit ([`Curve::elastic_limit`]): a linear curve's is
//!   infinite (it never takes a set), a bilinear one's is its yield
//!   deformation `δ_y = F_y / k`; progressive and tabulated curves have
//!   none (δ_e = 0: a crush curve's unloading rule holds from the first
//!   compression). A bilinear link with `k_u > k` therefore takes its set
//!   at yield: it jumps from 0 to `δ_y (1 − k/k_u)` as δ_max passes δ_y
//!   (as LS-DYNA's general nonlinear spring does past its initial yield
//!   force); with `k_u ≤ k` the set grows from 0 continuously.
//!
//! Energy: the elastic energy stored is `F² / (2 k_e)` (elastic rule:
//! `∫₀^|δ| F_L`), and the plastic work dissipated so far is
//! `W_p = E_L(δ_max) − F_max² / (2 k_e)`, exact for every curve (closed
//! form; trapezoids are exact on a table). A chain's energy balance then
//! closes with it (see [`crate::chain`]).
//!
//! Rate dependence is a viscous damper in parallel (the chain's `c_j`).
//!
//! ```
//! use bumpsim_core::link::{Curve, Link, LinkState, Unloading};
//! let link = Link::new(Curve::bilinear(1e6, 5e4, 0.1).unwrap(), Unloading::Slope(2e6)).unwrap();
//! let mut state = LinkState::default();
//! assert_eq!(link.force(0.01, &mut state), 1e4);            // elastic
//! let top = link.force(0.2, &mut state);                     // yielded, hardening
//! assert!((top - (5e4 + 0.1 * 1e6 * 0.15)).abs() < 1e-6);
//! let back = link.force(0.19, &mut state);                   // unloads at 2e6 N/m
//! assert!((back - (top - 2e6 * 0.01)).abs() < 1e-6);
//! assert!((state.plastic_set(&link) - (0.2 - top / 2e6)).abs() < 1e-12);
//! ```

use crate::dual::Real;

/// Why a link cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LinkError {
    /// A parameter is out of its range.
    #[error("{parameter} = {} {unit}: {requirement}", crate::units::short(*value))]
    Value {
        /// The parameter (`stiffness`, `yield_force`, ...).
        parameter: &'static str,
        /// The value given, SI.
        value: f64,
        /// Its SI unit.
        unit: &'static str,
        /// What is expected.
        requirement: &'static str,
    },
    /// A table of the loading curve is not usable.
    #[error("loading table point {index}: {reason}")]
    Table {
        /// 0-based point.
        index: usize,
        /// What is wrong.
        reason: String,
    },
}

/// Most points of a tabulated curve.
pub const MAX_TABLE_POINTS: usize = 10_000;

/// A loading curve `F_L(δ)`, δ ≥ 0 in compression (m → N).
#[derive(Debug, Clone, PartialEq)]
pub enum Curve<T = f64> {
    /// `F = k δ`.
    Linear {
        /// k, N/m.
        stiffness: T,
    },
    /// `F = k δ + k3 δ³` up to `limit`, the tangent beyond.
    Progressive {
        /// k, N/m.
        stiffness: T,
        /// k3, N/m³.
        cubic: T,
        /// δ_lim, m.
        limit: T,
    },
    /// Elastic `k δ` up to `F_y`, then `F_y + r k (δ − δ_y)`.
    Bilinear {
        /// k, N/m.
        stiffness: T,
        /// F_y, N.
        yield_force: T,
        /// r, 0..=1.
        hardening: T,
    },
    /// Piecewise linear through `(δ_i, F_i)`, starting at (0, 0) (added
    /// when absent); `[deformation m, force N]` pairs.
    Table {
        /// The points, the first (0, 0).
        points: Vec<[T; 2]>,
    },
}

fn value(
    parameter: &'static str,
    value: f64,
    unit: &'static str,
    ok: bool,
    requirement: &'static str,
) -> Result<(), LinkError> {
    if ok && value.is_finite() {
        return Ok(());
    }
    Err(LinkError::Value {
        parameter,
        value,
        unit,
        requirement,
    })
}

fn positive(parameter: &'static str, x: f64, unit: &'static str) -> Result<(), LinkError> {
    value(parameter, x, unit, x > 0.0, "must be positive and finite")
}

/// The smaller of two values (by value; `f64::min` on non-NaN values).
fn smaller<T: Real>(a: T, b: T) -> T {
    match a.value() < b.value() {
        true => a,
        false => b,
    }
}

/// The larger of two values (by value; `f64::max` on non-NaN values).
fn larger<T: Real>(a: T, b: T) -> T {
    match a.value() < b.value() {
        true => b,
        false => a,
    }
}

impl<T: Real> Curve<T> {
    /// `F_L(δ)` for δ ≥ 0, N.
    pub fn force(&self, d: T) -> T {
        match self {
            Curve::Linear { stiffness } => *stiffness * d,
            Curve::Progressive {
                stiffness,
                cubic,
                limit,
            } => {
                let e = smaller(d, *limit);
                let base = *stiffness * e + *cubic * e * e * e;
                base + (*stiffness + *cubic * 3.0 * e * e) * (d - e)
            }
            Curve::Bilinear {
                stiffness,
                yield_force,
                hardening,
            } => {
                let elastic = *stiffness * d;
                if elastic.value() <= yield_force.value() {
                    elastic
                } else {
                    *yield_force + *hardening * (elastic - *yield_force)
                }
            }
            Curve::Table { points } => {
                let i = segment(points, d.value());
                let ([d0, f0], [d1, f1]) = (points[i], points[i + 1]);
                let slope = (f1 - f0) / (d1 - d0);
                if d.value() > d1.value() && slope.value() < 0.0 {
                    return f1;
                }
                f0 + slope * (d - d0)
            }
        }
    }

    /// `E_L(δ) = ∫₀^δ F_L`, J, δ ≥ 0.
    pub fn energy(&self, d: T) -> T {
        match self {
            Curve::Linear { stiffness } => *stiffness * 0.5 * d * d,
            Curve::Progressive {
                stiffness,
                cubic,
                limit,
            } => {
                let e = smaller(d, *limit);
                let e2 = e * e;
                let within = *stiffness * 0.5 * e * e + *cubic * 0.25 * (e2 * e2);
                within + (self.force(e) + self.force(d)) * 0.5 * (d - e)
            }
            Curve::Bilinear {
                stiffness,
                yield_force,
                ..
            } => {
                let dy = *yield_force / *stiffness;
                if d.value() <= dy.value() {
                    *stiffness * 0.5 * d * d
                } else {
                    *yield_force * 0.5 * dy + (*yield_force + self.force(d)) * 0.5 * (d - dy)
                }
            }
            Curve::Table { points } => {
                let i = segment(points, d.value());
                let trapezoid = |a: [T; 2], b: [T; 2]| (a[1] + b[1]) * 0.5 * (b[0] - a[0]);
                let whole = points[..=i]
                    .windows(2)
                    .fold(T::constant(0.0), |sum, w| sum + trapezoid(w[0], w[1]));
                let ([d0, f0], [end, f1]) = (points[i], points[i + 1]);
                let falling = f1.value() < f0.value();
                if d.value() > end.value() && self.force(d).value() == f1.value() && falling {
                    return whole + trapezoid(points[i], points[i + 1]) + f1 * (d - end);
                }
                whole + (f0 + self.force(d)) * 0.5 * (d - d0)
            }
        }
    }

    /// The elastic limit δ_e, m: up to it the link unloads along its
    /// initial slope whatever its unloading rule (see the module). A
    /// linear curve's is infinite, a bilinear one's `F_y / k`; progressive
    /// and tabulated curves have none (0).
    pub fn elastic_limit(&self) -> T {
        match self {
            Curve::Linear { .. } => T::constant(f64::INFINITY),
            Curve::Bilinear {
                stiffness,
                yield_force,
                ..
            } => *yield_force / *stiffness,
            Curve::Progressive { .. } | Curve::Table { .. } => T::constant(0.0),
        }
    }

    /// The initial slope, N/m.
    pub fn initial_slope(&self) -> T {
        match self {
            Curve::Linear { stiffness }
            | Curve::Progressive { stiffness, .. }
            | Curve::Bilinear { stiffness, .. } => *stiffness,
            Curve::Table { points } => points[1][1] / points[1][0],
        }
    }
}

impl Curve<f64> {
    /// A linear curve.
    pub fn linear(stiffness: f64) -> Result<Curve, LinkError> {
        positive("stiffness", stiffness, "N/m")?;
        Ok(Curve::Linear { stiffness })
    }

    /// A progressive curve `k δ + k3 δ³` up to `limit` (m).
    pub fn progressive(stiffness: f64, cubic: f64, limit: f64) -> Result<Curve, LinkError> {
        positive("stiffness", stiffness, "N/m")?;
        value(
            "cubic",
            cubic,
            "N/m^3",
            cubic >= 0.0,
            "must be finite and non-negative (0 = linear)",
        )?;
        positive("limit", limit, "m")?;
        let slope = stiffness + 3.0 * cubic * limit * limit;
        value(
            "limit",
            limit,
            "m",
            slope.is_finite(),
            "gives an infinite slope with this cubic term",
        )?;
        Ok(Curve::Progressive {
            stiffness,
            cubic,
            limit,
        })
    }

    /// A yielding curve with hardening ratio `hardening` (0..=1).
    pub fn bilinear(stiffness: f64, yield_force: f64, hardening: f64) -> Result<Curve, LinkError> {
        positive("stiffness", stiffness, "N/m")?;
        positive("yield_force", yield_force, "N")?;
        value(
            "hardening",
            hardening,
            "",
            (0.0..=1.0).contains(&hardening),
            "the hardening ratio must lie in 0..=1 (0 = perfectly plastic)",
        )?;
        Ok(Curve::Bilinear {
            stiffness,
            yield_force,
            hardening,
        })
    }

    /// A tabulated curve through `points` (`[δ m, F N]`).
    pub fn table(points: Vec<[f64; 2]>) -> Result<Curve, LinkError> {
        let mut points = points;
        if points.first().is_none_or(|p| p[0] != 0.0) {
            points.insert(0, [0.0, 0.0]);
        }
        let fail = |index: usize, reason: String| Err(LinkError::Table { index, reason });
        if points.len() < 2 {
            return fail(0, "a table needs a point past (0, 0)".into());
        }
        if points.len() > MAX_TABLE_POINTS {
            return fail(
                MAX_TABLE_POINTS,
                format!("at most {MAX_TABLE_POINTS} points"),
            );
        }
        if points[0][1] != 0.0 {
            return fail(
                0,
                format!("the force at δ = 0 is {} N, expected 0", points[0][1]),
            );
        }
        for (i, w) in points.windows(2).enumerate() {
            let [[d0, _], [d1, f1]] = [w[0], w[1]];
            if !(d1.is_finite() && f1.is_finite()) {
                return fail(i + 1, format!("({d1} m, {f1} N) is not finite"));
            }
            if d1 <= d0 {
                return fail(
                    i + 1,
                    format!("deformation {d1} m after {d0} m: expected increasing"),
                );
            }
            if f1 < 0.0 {
                return fail(
                    i + 1,
                    format!("force {f1} N: a crush force is not negative"),
                );
            }
        }
        let [d, f] = points[1];
        if f / d <= 0.0 {
            return fail(1, "the first segment must have a positive slope".into());
        }
        Ok(Curve::Table { points })
    }

    /// The steepest slope anywhere on the curve, N/m (bounds the stable step).
    pub fn steepest_slope(&self) -> f64 {
        match self {
            Curve::Progressive {
                stiffness,
                cubic,
                limit,
            } => stiffness + 3.0 * cubic * limit * limit,
            Curve::Table { points } => points
                .windows(2)
                .map(|w| ((w[1][1] - w[0][1]) / (w[1][0] - w[0][0])).abs())
                .fold(0.0, f64::max),
            _ => self.initial_slope(),
        }
    }

    /// The steepest rising slope of the curve, N/m: what an unloading
    /// slope must reach for a solver's plasticity to follow the curve
    /// (a falling, softening segment needs none; LS-DYNA's
    /// `*MAT_SPRING_INELASTIC` unloads at the larger of its `KU` and this).
    pub fn steepest_rise(&self) -> f64 {
        match self {
            Curve::Table { points } => points
                .windows(2)
                .map(|w| (w[1][1] - w[0][1]) / (w[1][0] - w[0][0]))
                .fold(0.0, f64::max),
            _ => self.steepest_slope(),
        }
    }
}

/// Index of the table segment holding δ (the last beyond the last point).
fn segment<T: Real>(points: &[[T; 2]], d: f64) -> usize {
    let last = points.len() - 2;
    points[1..=last]
        .partition_point(|p| p[0].value() <= d)
        .min(last)
}

/// What a link does when its deformation recedes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Unloading<T = f64> {
    /// Back along the loading curve: nonlinear elastic.
    Elastic,
    /// Along this slope (N/m) from the reached deformation (see the module
    /// for the slope actually used): hysteresis and a plastic set.
    Slope(T),
}

/// A validated nonlinear link: loading curve and unloading rule. On a
/// [`Real`] other than `f64` (a [`crate::dual::Dual`]) it is the same law
/// with parameters that carry derivatives ([`Link::with_parameters`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Link<T = f64> {
    curve: Curve<T>,
    unloading: Unloading<T>,
}

/// What a link remembers: the largest compression reached, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkState<T = f64> {
    /// δ_max, m (0 before any compression).
    pub reached: T,
}

impl<T: Real> Default for LinkState<T> {
    fn default() -> Self {
        LinkState {
            reached: T::constant(0.0),
        }
    }
}

/// A link's history in a run with its unloading line kept: the line
/// `(F_max, k_e)` from δ_max ([`Link::force`]'s) depends on δ_max alone,
/// so it is computed once per reached compression instead of at every
/// unloading step (for a table, `E_L(δ_max)` sums every segment below
/// it); [`Link::remembered_force`] gives [`Link::force`]'s value bit for
/// bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Remembered<T = f64> {
    /// The history.
    pub state: LinkState<T>,
    /// The unloading line from `state.reached`, once computed.
    line: Option<(T, T)>,
}

impl<T: Real> Default for Remembered<T> {
    fn default() -> Self {
        Remembered {
            state: LinkState::default(),
            line: None,
        }
    }
}

impl<T: Real> LinkState<T> {
    /// The plastic set `δ_p = δ_max − F_max / k_e`, m (0 for an elastic link).
    pub fn plastic_set(&self, link: &Link<T>) -> T {
        match link.unloading {
            Unloading::Elastic => T::constant(0.0),
            Unloading::Slope(_) => {
                let (top, slope) = link.unloading_line(self.reached);
                self.reached - top / slope
            }
        }
    }

    /// The plastic work dissipated so far, J (0 for an elastic link).
    pub fn dissipated(&self, link: &Link<T>) -> T {
        match link.unloading {
            Unloading::Elastic => T::constant(0.0),
            Unloading::Slope(_) => {
                let (top, slope) = link.unloading_line(self.reached);
                (link.curve.energy(self.reached) - top * 0.5 * top / slope).max_constant(0.0)
            }
        }
    }
}

impl Link<f64> {
    /// A link from its curve and unloading rule; an unloading slope must
    /// be positive and finite.
    pub fn new(curve: Curve, unloading: Unloading) -> Result<Link, LinkError> {
        if let Unloading::Slope(k) = unloading {
            positive("unloading", k, "N/m")?;
        }
        Ok(Link { curve, unloading })
    }

    /// A linear elastic link of stiffness k (N/m).
    pub fn linear(stiffness: f64) -> Result<Link, LinkError> {
        Link::new(Curve::linear(stiffness)?, Unloading::Elastic)
    }

    /// The steepest slope the link can show, N/m (loading or unloading).
    pub fn steepest_slope(&self) -> f64 {
        let unloading = match self.unloading {
            Unloading::Slope(k) => k,
            Unloading::Elastic => 0.0,
        };
        self.curve.steepest_slope().max(unloading)
    }

    /// When the unloading rule replaced the given slope: from a reached
    /// compression `reached` (m) past the elastic limit, a link with an
    /// unloading slope k_u unloads at `k_e = max(k_u, F_max/δ_max,
    /// F_max²/(2 E_L))`; `Some((k_u, k_e))` when that is steeper than k_u,
    /// N/m, else `None` (an elastic link, or one that has not yielded).
    pub fn replaced_unloading(&self, reached: f64) -> Option<(f64, f64)> {
        match self.unloading {
            Unloading::Slope(given) if reached > self.curve.elastic_limit() => {
                let (_, used) = self.unloading_line(reached);
                (used > given).then_some((given, used))
            }
            _ => None,
        }
    }
}

impl<T: Real> Link<T> {
    /// The loading curve.
    pub fn curve(&self) -> &Curve<T> {
        &self.curve
    }

    /// The unloading rule.
    pub fn unloading(&self) -> Unloading<T> {
        self.unloading
    }

    /// `(F_max, k_e)`: the top of the unloading line from δ_max and its slope.
    fn unloading_line(&self, reached: T) -> (T, T) {
        let top = self.curve.force(reached);
        let k0 = self.curve.initial_slope();
        let given = match self.unloading {
            Unloading::Slope(k) => k,
            Unloading::Elastic => k0,
        };
        if reached.value() <= 0.0 {
            return (T::constant(0.0), larger(given, k0));
        }
        if reached.value() <= self.curve.elastic_limit().value() {
            return (top, k0);
        }
        let secant = top / reached;
        let energy = self.curve.energy(reached);
        let balance = match energy.value() > 0.0 {
            true => top * 0.5 * top / energy,
            false => k0,
        };
        (top, larger(larger(given, secant), balance))
    }

    /// The spring force at deformation `d` (m, compression positive), N,
    /// updating the history `state`.
    pub fn force(&self, d: T, state: &mut LinkState<T>) -> T {
        self.force_along(d, state, &mut None)
    }

    /// [`Link::force`] with the history `memory`, its unloading line kept
    /// while δ_max stays ([`Remembered`]): the same value.
    pub fn remembered_force(&self, d: T, memory: &mut Remembered<T>) -> T {
        self.force_along(d, &mut memory.state, &mut memory.line)
    }

    /// The force of both: `line` the unloading line from `state.reached`
    /// if known (made when needed, dropped when δ_max grows).
    fn force_along(&self, d: T, state: &mut LinkState<T>, line: &mut Option<(T, T)>) -> T {
        match self.unloading {
            // odd in δ (`signum(δ) F_L(|δ|)`, a negative zero included)
            Unloading::Elastic => match d.value().is_sign_negative() {
                true => -self.curve.force(-d),
                false => self.curve.force(d),
            },
            Unloading::Slope(_) => {
                if d.value() >= state.reached.value() {
                    state.reached = d;
                    *line = None;
                    return self.curve.force(d);
                }
                let (top, slope) = *line.get_or_insert_with(|| self.unloading_line(state.reached));
                top - slope * (state.reached - d)
            }
        }
    }

    /// The elastic energy stored at deformation `d` with history `state`, J.
    pub fn stored(&self, d: T, state: &LinkState<T>) -> T {
        match self.unloading {
            Unloading::Elastic => self.curve.energy(d.abs()),
            Unloading::Slope(_) => {
                let (top, slope) = self.unloading_line(state.reached);
                let f = match d.value() >= state.reached.value() {
                    true => self.curve.force(d),
                    false => top - slope * (state.reached - d),
                };
                f * 0.5 * f / slope
            }
        }
    }
}

#[path = "link_parameters.rs"]
mod parameters;

#[cfg(test)]
#[path = "link_tests.rs"]
mod tests;
