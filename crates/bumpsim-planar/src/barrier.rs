//! The RCAR bumper barrier (RCAR *Dimensions and specifications of the
//! RCAR bumper barrier system*, Issue 1, September 2007, appendix 1 of the
//! RCAR Bumper Test, Issue 2.0, 2010): a rigid steel beam whose 100 mm tall
//! face is curved in plan with a radius of 3400 mm ± 25 mm across its
//! 1500 mm ± 25 mm width, carrying a 50 mm deep energy absorber (aluminium
//! honeycomb, egg-crate or thermoplastic: the protocol found the results
//! largely independent of the material) under a plastic cover. The barrier is
//! mounted with its face's lower edge 405 mm or 455 mm above the ground.
//!
//! **Face.** An arc of the circle of radius `R` about `C`, convex towards the
//! car, spanning the half-angle `asin(W / 2R)` either side of its apex
//! direction. A point `p` of the bumper line is inside by `R − |p − C|` and
//! is pushed along `(p − C)/|p − C|`: the penetration's gradient, so the
//! contact stays conservative like the plane's. A point whose direction from
//! `C` lies outside the arc is beside the barrier (no contact).
//!
//! **Absorber.** In series with each bumper segment it covers: a strip of
//! the segment's width whose force per metre of width rises with `stiffness`
//! to its crush `plateau`, stays there until the absorber is crushed solid at
//! `solid × depth`, then rises `SOLID_STIFFENING` times as steeply; it
//! unloads elastically like the bumper (spec §5). The common force `F` of a
//! segment at total penetration `d` splits it into the absorber's crush `a`
//! and the bumper's `d − a` with `F_absorber(a) = F_bumper(d − a)` (both
//! characteristics are non-decreasing, so the split is found by bracketing).
//! The crush force figures are **not** from the specification (its corridor
//! was not available here): a 0.35 MPa crush strength over the 100 mm face
//! height, stated as uncertain by the presets that use it.

use crate::car::{PlanarCar, PlanarError, require};
use bumpsim_impact::bumper::{Bumper, BumperState};
use serde::Serialize;

/// How much steeper the absorber gets once crushed solid.
pub const SOLID_STIFFENING: f64 = 20.0;

/// The crushable energy absorber on a barrier's face (per metre of face width).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Absorber {
    /// Depth of the absorber, m.
    pub depth: f64,
    /// Crush force per metre of contact width on its plateau, N/m.
    pub plateau: f64,
    /// Elastic stiffness per metre of width (loading ramp and unloading), N/m².
    pub stiffness: f64,
    /// Fraction of the depth crushed when it becomes solid, (0, 1].
    pub solid: f64,
}

impl Absorber {
    /// The RCAR bumper barrier's absorber: 50 mm deep (specification §3);
    /// 0.35 MPa over the 100 mm face (35 kN per metre of width), elastic up
    /// to it over 2 mm, solid at 80 % of its depth (assumed: the
    /// specification's crush corridor was not available here).
    pub const RCAR: Absorber = Absorber {
        depth: 0.05,
        plateau: 35e3,
        stiffness: 35e3 / 0.002,
        solid: 0.8,
    };

    /// Checks the figures; errors name the parameter.
    pub fn check(&self) -> Result<(), PlanarError> {
        for (name, value, unit) in [
            ("absorber depth", self.depth, "m"),
            ("absorber plateau", self.plateau, "N/m"),
            ("absorber stiffness", self.stiffness, "N/m²"),
        ] {
            require(name, value, unit, "must be positive", value > 0.0)?;
        }
        require(
            "absorber solid fraction",
            self.solid,
            "1",
            "must lie in (0, 1] and leave the elastic ramp below it",
            self.solid > 0.0
                && self.solid <= 1.0
                && self.plateau / self.stiffness < self.solid * self.depth,
        )
    }

    /// The absorber strip in front of a segment `width` m wide, as a
    /// characteristic (force per segment).
    pub fn characteristic(&self, width: f64) -> Result<Bumper, PlanarError> {
        self.check()?;
        let (p, k) = (self.plateau * width, self.stiffness * width);
        let solid = self.solid * self.depth;
        let end = solid + self.depth;
        let top = p + SOLID_STIFFENING * k * self.depth;
        let compression = vec![0.0, p / k, solid, end];
        let force = vec![0.0, p, p, top];
        let unloading = k.max(top / end);
        Bumper::table(compression, force, unloading).map_err(|source| PlanarError::Bumper {
            name: "barrier absorber".into(),
            source,
        })
    }
}

/// A circular face placed against a car (world frame at travel 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Arc {
    /// Centre of the face's circle, m.
    pub centre: [f64; 2],
    /// Radius, m.
    pub radius: f64,
    /// Unit direction from the centre to the apex (towards the car).
    pub direction: [f64; 2],
    /// Cosine of the half-angle the face spans either side of the apex.
    pub cos_half: f64,
}

/// The barrier's geometry in a protocol's terms (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Shape {
    pub angle: f64,
    pub overlap: f64,
    /// +1: overlap measured from the left, −1: from the right.
    pub side: f64,
    pub radius: f64,
    pub width: f64,
}

impl Arc {
    /// Penetration (m), whether `p` faces the arc, and the push direction
    /// (world) of a point `p` (world).
    pub fn depth(&self, p: [f64; 2]) -> (f64, bool, [f64; 2]) {
        let r = [p[0] - self.centre[0], p[1] - self.centre[1]];
        // √(x² + y²), not hypot: no overflow at these lengths, and this
        // runs for every segment at every step
        let length = (r[0] * r[0] + r[1] * r[1]).sqrt();
        if length == 0.0 {
            return (-1.0, false, [-1.0, 0.0]);
        }
        let u = [r[0] / length, r[1] / length];
        let covered = u[0] * self.direction[0] + u[1] * self.direction[1] >= self.cos_half;
        (self.radius - length, covered, u)
    }

    /// The apex, world, m.
    pub fn apex(&self) -> [f64; 2] {
        [
            self.centre[0] + self.radius * self.direction[0],
            self.centre[1] + self.radius * self.direction[1],
        ]
    }

    /// The arc's two ends, world, m.
    pub fn ends(&self) -> [[f64; 2]; 2] {
        let sin_half = (1.0 - self.cos_half * self.cos_half).sqrt();
        let [dx, dy] = self.direction;
        [1.0, -1.0].map(|s| {
            let (cx, cy) = (
                dx * self.cos_half - s * dy * sin_half,
                s * dx * sin_half + dy * self.cos_half,
            );
            [
                self.centre[0] + self.radius * cx,
                self.centre[1] + self.radius * cy,
            ]
        })
    }
}

fn check_shape(shape: &Shape) -> Result<(), PlanarError> {
    require(
        "barrier radius",
        shape.radius,
        "m",
        "must be positive",
        shape.radius > 0.0,
    )?;
    require(
        "barrier width",
        shape.width,
        "m",
        &format!(
            "must be positive and below the face's diameter, {} m",
            2.0 * shape.radius
        ),
        shape.width > 0.0 && shape.width < 2.0 * shape.radius,
    )?;
    require(
        "barrier angle",
        shape.angle,
        "rad",
        "must lie within ±80° (±1.396 rad)",
        shape.angle.abs() <= 80f64.to_radians(),
    )?;
    require(
        "overlap",
        shape.overlap,
        "fraction of the bumper width",
        "must lie in 0 < overlap ≤ 1 (0.15 is 15 %; 1: the barrier centred on the car)",
        shape.overlap > 0.0 && shape.overlap <= 1.0,
    )
}

/// Places the arc so that it just touches the bumper line at `x_f`: full
/// overlap centres its apex on the car; a partial overlap puts its inboard
/// end `overlap` of the bumper width in from the `side`.
pub(crate) fn place(car: &PlanarCar, shape: &Shape, x_f: f64) -> Result<Arc, PlanarError> {
    check_shape(shape)?;
    let (r, w) = (shape.radius, car.beam().width);
    let direction = [-shape.angle.cos(), -shape.angle.sin()];
    let cos_half = (1.0 - (0.5 * shape.width / r).powi(2)).sqrt();
    let mut arc = Arc {
        centre: [0.0, 0.0],
        radius: r,
        direction,
        cos_half,
    };
    let ends = arc.ends().map(|p| p[1]);
    let (low, high) = (ends[0].min(ends[1]), ends[0].max(ends[1]));
    arc.centre[1] = match (shape.overlap >= 1.0, shape.side > 0.0) {
        (true, _) => -r * direction[1],
        (false, true) => 0.5 * w - shape.overlap * w - low,
        (false, false) => -0.5 * w + shape.overlap * w - high,
    };
    let reach = (0..car.beam().segments.len())
        .map(|j| car.segment_centre(j) - arc.centre[1])
        .filter(|dy| (low..=high).contains(dy))
        .map(|dy| (r * r - dy * dy).sqrt())
        .fold(f64::NEG_INFINITY, f64::max);
    if !reach.is_finite() {
        return Err(PlanarError::NoContact {
            reason: format!(
                "a {} m wide barrier at {:.1} % overlap covers no segment centre of the {w} m bumper; raise the overlap or the number of segments",
                shape.width,
                shape.overlap * 100.0
            ),
        });
    }
    arc.centre[0] = x_f + reach;
    Ok(arc)
}

/// The common force (N) of a bumper segment in series with an absorber
/// strip at total penetration `d` (m), and the absorber's crush (m); the
/// states are updated. Regula falsi (Illinois) on `F_a(a) − F_b(d − a)`,
/// bracketed by `a = 0` and `a = d`, first tried at `guess` (the last
/// step's split: within one linear piece the next secant is the root).
/// `bumper` is the segment's force at its own crush (its characteristic and
/// its block, `car::Block`).
pub(crate) fn series(
    d: f64,
    guess: f64,
    absorber: &Bumper,
    absorbed: &mut BumperState,
    bumper: &dyn Fn(f64, &mut BumperState) -> f64,
    state: &mut BumperState,
) -> (f64, f64) {
    let gap = |a: f64| {
        let (mut sa, mut sb) = (*absorbed, *state);
        absorber.force(a, &mut sa) - bumper(d - a, &mut sb)
    };
    let (mut lo, mut hi) = (0.0, d);
    let (mut g_lo, mut g_hi) = (gap(lo), gap(hi));
    let mut a = if g_lo >= 0.0 {
        lo
    } else if g_hi <= 0.0 {
        hi
    } else {
        f64::NAN
    };
    let mut side = 0i8;
    let scale = 1e-12 * (g_hi - g_lo);
    for iteration in 0..100 {
        if !a.is_nan() {
            break;
        }
        let mid = match iteration {
            0 => guess,
            _ => (lo * g_hi - hi * g_lo) / (g_hi - g_lo),
        };
        let mid = if mid > lo && mid < hi {
            mid
        } else {
            0.5 * (lo + hi)
        };
        let g = gap(mid);
        if g.abs() <= scale || hi - lo <= 1e-13 * d.max(1e-9) {
            a = mid;
        } else if g < 0.0 {
            (lo, g_lo) = (mid, g);
            g_hi *= if side == -1 { 0.5 } else { 1.0 };
            side = -1;
        } else {
            (hi, g_hi) = (mid, g);
            g_lo *= if side == 1 { 0.5 } else { 1.0 };
            side = 1;
        }
    }
    let a = if a.is_nan() { 0.5 * (lo + hi) } else { a };
    let f_absorber = absorber.force(a, absorbed);
    let f_bumper = bumper(d - a, state);
    (0.5 * (f_absorber + f_bumper), a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_series_split_carries_one_force_and_adds_the_compliances() {
        let absorber = Absorber::RCAR.characteristic(0.15).unwrap();
        let bumper = Bumper::three_part(3e5, 2e4, 2e6).unwrap();
        let (mut sa, mut sb) = (BumperState::default(), BumperState::default());
        // elastic both: F = d / (1/k_a + 1/k_b)
        let k_a = Absorber::RCAR.stiffness * 0.15;
        let d = 0.004;
        let (f, a) = series(
            d,
            0.0,
            &absorber,
            &mut sa,
            &|d, s| bumper.force(d, s),
            &mut sb,
        );
        let expected = d / (1.0 / k_a + 1.0 / 3e5);
        assert!(
            (f - expected).abs() < 1e-9 * expected,
            "{f} against {expected}"
        );
        assert!((a - f / k_a).abs() < 1e-12, "{a}");
        // the absorber's plateau (5.25 kN) is below the bumper's: it crushes, the bumper holds
        let (f, a) = series(
            0.03,
            0.0,
            &absorber,
            &mut sa,
            &|d, s| bumper.force(d, s),
            &mut sb,
        );
        assert!((f - 35e3 * 0.15).abs() < 1e-6, "{f}");
        assert!((0.03 - a - f / 3e5).abs() < 1e-12, "{a}");
    }

    #[test]
    fn a_curved_face_pushes_along_its_radius() {
        let arc = Arc {
            centre: [5.4, 0.0],
            radius: 3.4,
            direction: [-1.0, 0.0],
            cos_half: 0.97,
        };
        let (depth, covered, u) = arc.depth([2.01, 0.0]);
        assert!((depth - 0.01).abs() < 1e-12 && covered && u == [-1.0, 0.0]);
        let (_, covered, _) = arc.depth([2.0, 1.0]);
        assert!(!covered, "beside the 1.5 m barrier");
        let ends = arc.ends();
        assert!((ends[0][1] + ends[1][1]).abs() < 1e-12);
    }
}
